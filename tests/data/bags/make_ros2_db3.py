#!/usr/bin/env python3
"""Writes the ROS 2 test bag imu_ros2/ (metadata.yaml + imu_ros2_0.db3) from
session.csv with Python's sqlite3 and a CDR encoder written here from the CDR
rules (not from mpcal's decoder): a 4-byte encapsulation header 00 01 00 00
(little endian), then each primitive aligned to its own size counted from the
end of that header; a string is a u32 length that counts its NUL, the bytes,
the NUL.

The tables are those ros2/rosbag2 creates (rosbag2_storage_sqlite3,
sqlite_storage.cpp at 25304dd, SqliteStorage::initialize, lines 434-480).
Each CSV row becomes a sensor_msgs/msg/Imu on /imu/data exactly as
make_ros1_bags.py writes it (header stamp kEpoch + t with rows 100 and 101
swapped, received 2 ms later, the row's doubles as they are); a
std_msgs/msg/String on /chatter precedes every tenth row.

  python3 make_ros2_db3.py      (in this directory; no ROS needed)

With --csv FILE --out DIR [--in-order] it writes DIR from another session
(the command-line tests make a bag of a whole calibration session this way;
--in-order leaves every stamp in order).
"""
import argparse
import csv
import os
import shutil
import sqlite3
import struct

EPOCH_NS = 1700000000 * 10**9
LATENCY_NS = 2_000_000
SWAPPED = (100, 101)


class Cdr:
    def __init__(self):
        self.body = bytearray()

    def align(self, n):
        while len(self.body) % n:
            self.body.append(0)

    def put(self, fmt, value):
        size = struct.calcsize("<" + fmt)
        self.align(size)
        self.body += struct.pack("<" + fmt, value)

    def string(self, text):
        raw = text.encode() + b"\0"
        self.put("I", len(raw))
        self.body += raw

    def bytes(self):
        return b"\x00\x01\x00\x00" + bytes(self.body)


def imu(row, stamp_ns):
    c = Cdr()
    c.put("i", stamp_ns // 10**9)
    c.put("I", stamp_ns % 10**9)
    c.string("imu_link")
    doubles = [0.0] * 37
    doubles[4] = -1.0  # orientation_covariance[0]: no orientation (REP 145)
    doubles[13:16] = [float(row["gx"]), float(row["gy"]), float(row["gz"])]
    doubles[25:28] = [float(row["ax"]), float(row["ay"]), float(row["az"])]
    for d in doubles:
        c.put("d", d)
    return c.bytes()


def text(s):
    c = Cdr()
    c.string(s)
    return c.bytes()


def open_database(bag, topics, name=None):
    """BAG/<name>_0.db3 (name: the directory's by default) with rosbag2's
    tables (SqliteStorage::initialize) and `topics`, (name, type) pairs, as
    topic ids 1, 2, ... in order."""
    name = name or os.path.basename(os.path.normpath(bag))
    db = sqlite3.connect(os.path.join(bag, name + "_0.db3"))
    db.executescript("""
      CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);
      CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL,
                            metadata TEXT NOT NULL);
      CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                          serialization_format TEXT NOT NULL,
                          offered_qos_profiles TEXT NOT NULL,
                          type_description_hash TEXT NOT NULL);
      CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,
                            timestamp INTEGER NOT NULL, data BLOB NOT NULL);
      CREATE INDEX timestamp_idx ON messages (timestamp ASC);
      INSERT INTO schema VALUES (4, 'jazzy');
    """)
    for topic_id, (topic, message_type) in enumerate(topics, start=1):
        db.execute("INSERT INTO topics VALUES (?, ?, ?, 'cdr', '', '')",
                   (topic_id, topic, message_type))
    return db


def write_metadata(bag, name=None):
    """BAG/metadata.yaml, naming its one database file, <name>_0.db3."""
    name = name or os.path.basename(os.path.normpath(bag))
    with open(os.path.join(bag, "metadata.yaml"), "w") as f:
        f.write("rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
                "  relative_file_paths:\n    - %s_0.db3\n" % name)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser()
    parser.add_argument("--csv", default=os.path.join(here, "session.csv"))
    parser.add_argument("--out", default=os.path.join(here, "imu_ros2"))
    parser.add_argument("--in-order", action="store_true")
    args = parser.parse_args()
    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    bag = args.out
    shutil.rmtree(bag, ignore_errors=True)
    os.makedirs(bag)
    db = open_database(bag, [("/chatter", "std_msgs/msg/String"),
                             ("/imu/data", "sensor_msgs/msg/Imu")])
    stamps = [EPOCH_NS + int(round(float(r["t"]) * 1e9)) for r in rows]
    if not args.in_order:
        a, b = SWAPPED
        stamps[a], stamps[b] = stamps[b], stamps[a]
    for i, row in enumerate(rows):
        receive = EPOCH_NS + int(round(float(row["t"]) * 1e9)) + LATENCY_NS
        if i % 10 == 0:
            db.execute("INSERT INTO messages(topic_id, timestamp, data) VALUES (1, ?, ?)",
                       (receive, text("row %d" % i)))
        db.execute("INSERT INTO messages(topic_id, timestamp, data) VALUES (2, ?, ?)",
                   (receive, imu(row, stamps[i])))
    db.commit()
    db.execute("VACUUM")
    db.close()
    write_metadata(bag)


if __name__ == "__main__":
    main()
