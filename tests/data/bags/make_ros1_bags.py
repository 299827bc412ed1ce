#!/usr/bin/python3
"""Writes the ROS 1 test bags from session.csv with Debian's rosbag (not mpcal).

Each CSV row (t in s, ax ay az in m/s2, gx gy gz in rad/s) becomes one
sensor_msgs/Imu on /imu/data: header.stamp = kEpoch + t, linear_acceleration
and angular_velocity the row's values as they are (doubles, written exactly),
received 2 ms after its stamp. Rows 100 and 101 have their header stamps
swapped (out of order), as a driver with a jittery clock may write them; the
receive times stay in order. A std_msgs/String on /chatter precedes every
tenth row, and 300 of them come first, so the first chunk holds no IMU
message. Chunks are kept small (8 KiB) so each bag has several.

  /usr/bin/python3 make_ros1_bags.py   (Debian's python, where rosbag is)

writes imu_none.bag, imu_bz2.bag and imu_lz4.bag, and empty.bag (closed with no
message).
"""
import csv
import os

import rosbag
import rospy
from sensor_msgs.msg import Imu
from std_msgs.msg import String

EPOCH_S = 1700000000
LATENCY_NS = 2_000_000
SWAPPED = (100, 101)


def stamps_ns(rows):
    stamps = [EPOCH_S * 10**9 + int(round(float(r["t"]) * 1e9)) for r in rows]
    a, b = SWAPPED
    stamps[a], stamps[b] = stamps[b], stamps[a]
    return stamps


def receive_ns(rows):
    return [EPOCH_S * 10**9 + int(round(float(r["t"]) * 1e9)) + LATENCY_NS for r in rows]


def imu_message(seq, row, stamp_ns):
    m = Imu()
    m.header.seq = seq
    m.header.stamp = rospy.Time(nsecs=stamp_ns)
    m.header.frame_id = "imu_link"
    m.orientation_covariance[0] = -1.0  # no orientation, as REP 145 says
    m.linear_acceleration.x = float(row["ax"])
    m.linear_acceleration.y = float(row["ay"])
    m.linear_acceleration.z = float(row["az"])
    m.angular_velocity.x = float(row["gx"])
    m.angular_velocity.y = float(row["gy"])
    m.angular_velocity.z = float(row["gz"])
    return m


def write(path, compression, rows):
    stamps, receive = stamps_ns(rows), receive_ns(rows)
    with rosbag.Bag(path, "w", compression=compression, chunk_threshold=8192) as bag:
        for k in range(300):
            bag.write("/chatter", String(data="warming up %d" % k),
                      rospy.Time(nsecs=receive[0] - 1_000_000 + k))
        for i, row in enumerate(rows):
            if i % 10 == 0:
                bag.write("/chatter", String(data="row %d" % i), rospy.Time(nsecs=receive[i]))
            bag.write("/imu/data", imu_message(i, row, stamps[i]), rospy.Time(nsecs=receive[i]))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "session.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    for compression in ("none", "bz2", "lz4"):
        write(os.path.join(here, "imu_%s.bag" % compression), compression, rows)
    rosbag.Bag(os.path.join(here, "empty.bag"), "w").close()


if __name__ == "__main__":
    main()
