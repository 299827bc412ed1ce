#!/usr/bin/python3
"""Writes a ROS 1 bag whose IMU messages are out of order and duplicated,
with Debian's rosbag (not mpcal), and prints what it did.

Each CSV row (t in s, ax ay az in m/s2, gx gy gz in rad/s) becomes one
sensor_msgs/Imu on /imu/data, header.stamp = 1700000000 s + t, the readings
the row's doubles as they are. The messages are written out of order:

- every 23rd row (from row 7) is written late, 1 to 40 messages after its
  place (a message held up in a queue);
- rows 50, 150, 250, ... are written twice, the copy (same stamp, same
  readings) 3 messages after the original (a message recorded twice);
- rows 75, 175, 275, ... get a second message right after theirs with the
  same stamp and other readings (ax + 0.3 m/s2): the first is the row.

Receive times are in write order, 1/rate apart. The positions come from a
seeded generator, so a file is the same on every run. The last line printed
counts what was done, by this script's own reckoning (a message is out of
order when its stamp is earlier than one written before it):

  out_of_order=N worst_back_ms=X duplicated=N same_time_other_readings=N

  /usr/bin/python3 make_ros1_shuffled.py [--csv session.csv] [--out imu_shuffled.bag]
"""
import argparse
import csv
import os
import random

import rosbag
import rospy

from make_ros1_bags import imu_message

EPOCH_S = 1700000000
SEED = 25


def message(stamp_ns, row, seq, ax_offset=0.0):
    m = imu_message(seq, row, stamp_ns)
    m.linear_acceleration.x = float(row["ax"]) + ax_offset
    return m


def plan(rows):
    """(write key, stamp ns, row index, ax offset, kind) for every message."""
    rng = random.Random(SEED)
    n = len(rows)
    out = []
    for i, row in enumerate(rows):
        stamp = EPOCH_S * 10**9 + int(round(float(row["t"]) * 1e9))
        key = float(i)
        if i >= 7 and (i - 7) % 23 == 0:
            key = i + rng.randint(1, 40) + 0.5
        out.append((key, stamp, i, 0.0, "row"))
        if i % 100 == 50 and i + 3 < n:
            out.append((i + 3 + 0.25, stamp, i, 0.0, "copy"))
        if i % 100 == 75:
            out.append((key + 0.125, stamp, i, 0.3, "other"))
    out.sort(key=lambda m: m[0])
    return out


def reckon(planned):
    latest = None
    out_of_order = 0
    worst_ns = 0
    for _, stamp, _, _, _ in planned:
        if latest is not None and stamp < latest:
            out_of_order += 1
            worst_ns = max(worst_ns, latest - stamp)
        else:
            latest = stamp
    duplicated = sum(1 for m in planned if m[4] == "copy")
    other = sum(1 for m in planned if m[4] == "other")
    return out_of_order, worst_ns / 1e6, duplicated, other


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser()
    parser.add_argument("--csv", default=os.path.join(here, "session.csv"))
    parser.add_argument("--out", default=os.path.join(here, "imu_shuffled.bag"))
    args = parser.parse_args()
    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    times = [float(r["t"]) for r in rows]
    period_ns = int(round((times[-1] - times[0]) / (len(rows) - 1) * 1e9))
    planned = plan(rows)
    with rosbag.Bag(args.out, "w", compression="lz4") as bag:
        for k, (_, stamp, i, offset, _) in enumerate(planned):
            receive = rospy.Time(nsecs=EPOCH_S * 10**9 + k * period_ns + 2_000_000)
            bag.write("/imu/data", message(stamp, rows[i], k, offset), receive)
    out_of_order, worst_ms, duplicated, other = reckon(planned)
    print("out_of_order=%d worst_back_ms=%.4g duplicated=%d same_time_other_readings=%d"
          % (out_of_order, worst_ms, duplicated, other))


if __name__ == "__main__":
    main()
