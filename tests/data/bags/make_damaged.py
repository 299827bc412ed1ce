#!/usr/bin/python3
"""Writes the damaged ROS 1 bags whose copy by `apply` would read otherwise
than it was written, byte by byte from the format's description
(wiki.ros.org/Bags/Format/2.0), not with mpcal's writer nor rosbag (which
cannot write them damaged):

- connection_after_message.bag: a closed bag, one uncompressed chunk in which
  the first /imu/data message comes before the /imu/data connection record,
  three after it. A reader that takes the connections from the index reads
  four IMU messages; one that walks the chunk reads three.
- connection_given_twice.bag: connection 0 is /chatter (std_msgs/String) in
  the first chunk, with one message, and /imu/data (sensor_msgs/Imu) in the
  second, with three. The index, as the last record of the id says.

Both are refused by `apply` in one line, before anything is written; the
fuzz target's corpus (tests/fuzz/ros1_bag/) holds them too.

  /usr/bin/python3 make_damaged.py [OUTDIR]   (default: this directory)
"""
import os
import struct
import sys

IMU_MD5 = "6a62c6daae103f4ff57a132d6f95cec2"
STRING_MD5 = "992ce8a1687cec8c8bd883ec73ca41d1"
EPOCH_S = 1700000000


def field(name, value):
    if isinstance(value, str):
        value = value.encode()
    body = name.encode() + b"=" + value
    return struct.pack("<I", len(body)) + body


def record(fields, data):
    header = b"".join(field(k, v) for k, v in fields)
    return struct.pack("<I", len(header)) + header + struct.pack("<I", len(data)) + data


def time_bytes(sec, nsec):
    return struct.pack("<II", sec, nsec)


def connection(conn, topic, type_, md5):
    data = b"".join(field(k, v) for k, v in
                    (("topic", topic), ("type", type_), ("md5sum", md5),
                     ("message_definition", "")))
    return record((("op", b"\x07"), ("conn", struct.pack("<I", conn)), ("topic", topic)), data)


def imu(seq, sec, nsec, accel, gyro):
    out = struct.pack("<III", seq, sec, nsec) + struct.pack("<I", 8) + b"imu_link"
    out += struct.pack("<4d", 0, 0, 0, 1) + struct.pack("<9d", -1, *([0] * 8))
    out += struct.pack("<3d", *gyro) + struct.pack("<9d", *([0] * 9))
    out += struct.pack("<3d", *accel) + struct.pack("<9d", *([0] * 9))
    return out


def string_msg(text):
    return struct.pack("<I", len(text)) + text.encode()


def message(conn, sec, nsec, data):
    return record((("op", b"\x02"), ("conn", struct.pack("<I", conn)),
                   ("time", time_bytes(sec, nsec))), data)


def chunk(records):
    body = b"".join(records)
    return record((("op", b"\x05"), ("compression", "none"),
                   ("size", struct.pack("<I", len(body)))), body)


def bag(chunks, connections):
    """`chunks`: lists of (record bytes, conn or None, time); the index
    after them: `connections`, then one chunk info per chunk."""
    # The magic, the bag header (4096 bytes of header and data, as rosbag
    # pads it), each chunk followed by its index data records, the index.
    body = b""
    chunk_infos = []
    magic = b"#ROSBAG V2.0\n"

    def bag_header(index_pos, conn_count, chunk_count):
        fields = (("op", b"\x03"), ("index_pos", struct.pack("<Q", index_pos)),
                  ("conn_count", struct.pack("<I", conn_count)),
                  ("chunk_count", struct.pack("<I", chunk_count)))
        header = b"".join(field(k, v) for k, v in fields)
        return record(fields, b" " * (4096 - len(header)))

    head_len = len(bag_header(0, 0, 0))
    for records in chunks:
        pos = len(magic) + head_len + len(body)
        body += chunk([r for r, _, _ in records])
        per_conn = {}
        offset = 0
        times = []
        for r, conn, t in records:
            if conn is not None:
                per_conn.setdefault(conn, []).append((t, offset))
                times.append(t)
            offset += len(r)
        for conn, entries in per_conn.items():
            data = b"".join(time_bytes(*t) + struct.pack("<I", o) for t, o in entries)
            body += record((("op", b"\x04"), ("ver", struct.pack("<I", 1)),
                            ("conn", struct.pack("<I", conn)),
                            ("count", struct.pack("<I", len(entries)))), data)
        chunk_infos.append((pos, min(times), max(times),
                            {c: len(e) for c, e in per_conn.items()}))
    index_pos = len(magic) + head_len + len(body)
    for c in connections:
        body += c
    for pos, start, end, counts in chunk_infos:
        data = b"".join(struct.pack("<II", c, n) for c, n in counts.items())
        body += record((("op", b"\x06"), ("ver", struct.pack("<I", 1)),
                        ("chunk_pos", struct.pack("<Q", pos)),
                        ("start_time", time_bytes(*start)), ("end_time", time_bytes(*end)),
                        ("count", struct.pack("<I", len(counts)))), data)
    return magic + bag_header(index_pos, len(connections), len(chunk_infos)) + body


def imu_records(conn, first, n):
    out = []
    for k in range(first, first + n):
        t = (EPOCH_S, 10_000_000 * k)
        data = imu(k, t[0], t[1], (0.1 * k, 0.2, 9.8), (0.01, 0.02 * k, 0.03))
        out.append((message(conn, t[0], t[1], data), conn, t))
    return out


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    imu_conn = connection(0, "/imu/data", "sensor_msgs/Imu", IMU_MD5)
    chatter_conn = connection(0, "/chatter", "std_msgs/String", STRING_MD5)

    # The first IMU message before its connection's record.
    records = imu_records(0, 0, 1) + [(imu_conn, None, None)] + imu_records(0, 1, 3)
    with open(os.path.join(out, "connection_after_message.bag"), "wb") as f:
        f.write(bag([records], [imu_conn]))

    # Connection 0 given twice, as /chatter and then as /imu/data.
    first = [(chatter_conn, None, None),
             (message(0, EPOCH_S, 0, string_msg("hello")), 0, (EPOCH_S, 0))]
    second = [(imu_conn, None, None)] + imu_records(0, 1, 3)
    with open(os.path.join(out, "connection_given_twice.bag"), "wb") as f:
        f.write(bag([first, second], [imu_conn]))


if __name__ == "__main__":
    main()
