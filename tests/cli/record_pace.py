#!/usr/bin/env python3
"""Feeds a session log at the pace of its time column, as a sensor would.

  record_pace.py LOG [--speed X] [--serve PORTFILE | --device PATH] [--boot]

The lines go to standard output, or to the one client that connects to a
TCP port on 127.0.0.1 (its number written to PORTFILE), or into a device
(a pseudo-terminal standing in for a serial port). --boot sends a line cut in half (the port opened
mid-line) and a sensor's boot text before the log. Stops quietly when the
reader goes away.
"""
import argparse
import os
import socket
import sys
import time


def lines_with_time(path):
    """(time_s or None, line) for every line of the log; the first column
    of a data line is its time."""
    out = []
    with open(path, "rb") as f:
        for raw in f:
            first = raw.split(b",", 1)[0].strip()
            try:
                out.append((float(first), raw))
            except ValueError:
                out.append((None, raw))
    return out


def feed(write, lines, speed, boot):
    if boot:
        data = [raw for t, raw in lines if t is not None]
        if data:
            write(data[0][len(data[0]) // 2:])  # the tail of a line cut in half
        write(b"ets Jun  8 2016 00:22:57\r\nrst:0x1 (POWERON_RESET),boot:0x13\r\n"
              b"IMU ready\r\n")
    start = time.monotonic()
    t0 = None
    batch = []
    for t, raw in lines:
        if boot and t is None:
            continue  # a sensor that was already running sends no header again
        if t is not None:
            if t0 is None:
                t0 = t
            due = start + (t - t0) / speed
            wait = due - time.monotonic()
            if wait > 0.005:
                if batch:
                    write(b"".join(batch))
                    batch = []
                time.sleep(wait)
        batch.append(raw)
    if batch:
        write(b"".join(batch))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("log")
    p.add_argument("--speed", type=float, default=1.0)
    p.add_argument("--serve")
    p.add_argument("--device")
    p.add_argument("--boot", action="store_true")
    a = p.parse_args()
    lines = lines_with_time(a.log)
    try:
        if a.serve:
            server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
            server.bind(("127.0.0.1", 0))
            server.listen(1)
            tmp = a.serve + ".tmp"
            with open(tmp, "w") as f:
                f.write(str(server.getsockname()[1]))
            os.replace(tmp, a.serve)
            server.settimeout(30)
            conn, _ = server.accept()
            feed(conn.sendall, lines, a.speed, a.boot)
            conn.shutdown(socket.SHUT_WR)
            conn.close()
        elif a.device:
            fd = os.open(a.device, os.O_WRONLY | os.O_NOCTTY)

            def write_all(b):
                while b:
                    b = b[os.write(fd, b):]

            feed(write_all, lines, a.speed, a.boot)
            os.close(fd)
        else:
            out = sys.stdout.buffer

            def write_flush(b):
                out.write(b)
                out.flush()

            feed(write_flush, lines, a.speed, a.boot)
    except (BrokenPipeError, ConnectionResetError, OSError):
        # The reader stopped (record ends by itself when the session is done).
        try:
            sys.stdout = None
        except Exception:
            pass
        os._exit(0)


if __name__ == "__main__":
    main()
