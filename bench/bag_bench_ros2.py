#!/usr/bin/env python3
"""Writes the bag benchmark's ROS 2 bag (SQLite) with Python's sqlite3 and the
CDR encoder of tests/data/bags/make_ros2_db3.py (not mpcal), in the tables
ros2/rosbag2's SQLite storage creates (that script cites them).

Each CSV row (t in s, ax ay az in m/s2, gx gy gz in rad/s) becomes one
sensor_msgs/msg/Imu on /imu/data, header stamp and timestamp 1700000000 s + t;
a sensor_msgs/msg/Image's bytes (640x480 mono8 of pseudo-random pixels and
its header's length, 307,264 bytes) on /camera/image_raw every 1/30 s among
them, in time order, as a recorder inserts two topics (none with
--no-camera).

  python3 bag_bench_ros2.py CSV OUT_DIR [--no-camera]
                                (writes OUT_DIR/metadata.yaml and
                                 OUT_DIR/<name>_0.db3)
"""
import csv
import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", "tests", "data", "bags"))
from make_ros2_db3 import imu, open_database, write_metadata  # noqa: E402

EPOCH_NS = 1700000000 * 10**9
CAMERA_HZ = 30


def main():
    csv_path, out = sys.argv[1], sys.argv[2]
    camera = "--no-camera" not in sys.argv[3:]
    os.makedirs(out)
    # Named for the directory it is moved to once whole (bag_bench.sh writes
    # NAME.tmp and renames it).
    name = os.path.basename(os.path.normpath(out)).removesuffix(".tmp")
    db = open_database(out, [("/camera/image_raw", "sensor_msgs/msg/Image"),
                             ("/imu/data", "sensor_msgs/msg/Imu")], name)
    rng = random.Random(7)
    frames = [rng.randbytes(640 * 480 + 64) for _ in range(8)]
    frame = 0
    with open(csv_path, newline="") as f:
        for row in csv.DictReader(f):
            t_ns = EPOCH_NS + int(round(float(row["t"]) * 1e9))
            while camera and EPOCH_NS + frame * 10**9 // CAMERA_HZ <= t_ns:
                db.execute("INSERT INTO messages(topic_id, timestamp, data) VALUES (1, ?, ?)",
                           (EPOCH_NS + frame * 10**9 // CAMERA_HZ, frames[frame % len(frames)]))
                frame += 1
            db.execute("INSERT INTO messages(topic_id, timestamp, data) VALUES (2, ?, ?)",
                       (t_ns, imu(row, t_ns)))
    db.commit()
    db.close()
    write_metadata(out, name)


if __name__ == "__main__":
    main()
