#!/usr/bin/python3
"""Writes imu_among_images.bag from session.csv with Debian's rosbag (not mpcal).

The IMU messages as make_ros1_bags.py writes them (the same stamps, receive
times and values), among camera images as a recorder interleaves them: a
sensor_msgs/Image on /camera/image_raw (256x64 mono8, 16 KiB of a fixed
gradient) before every twentieth row, received with it. Chunks are stored
(no compression) and closed past 32 KiB, so each holds about two images and
the forty IMU messages between them: the IMU's records are under half of a
chunk's bytes, as in a camera recording, where they are a few percent.

Also the fuzz seed tests/fuzz/ros1_bag/seed_imu_among_images.bag: the first
12 rows, a 64x48 image before every fourth, 4 KiB chunks (29 KB, so that
scripts/fuzz.sh gives the ros1_bag target inputs of up to 32 KiB).

  /usr/bin/python3 make_ros1_images.py   (Debian's python, where rosbag is)
"""
import csv
import os

import rosbag
import rospy
from sensor_msgs.msg import Image

from make_ros1_bags import imu_message, receive_ns, stamps_ns



def image(stamp_ns, seq, width, height):
    m = Image()
    m.header.seq = seq
    m.header.stamp = rospy.Time(nsecs=stamp_ns)
    m.header.frame_id = "camera"
    m.height, m.width = height, width
    m.encoding = "mono8"
    m.step = width
    m.data = bytes((x + y) % 256 for y in range(height) for x in range(width))
    return m


def write(path, rows, stamps, receive, every, width, height, chunk_bytes):
    with rosbag.Bag(path, "w", compression="none", chunk_threshold=chunk_bytes) as bag:
        for i, row in enumerate(rows):
            if i % every == 0:
                bag.write("/camera/image_raw", image(receive[i], i // every, width, height),
                          rospy.Time(nsecs=receive[i]))
            bag.write("/imu/data", imu_message(i, row, stamps[i]),
                      rospy.Time(nsecs=receive[i]))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "session.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    stamps, receive = stamps_ns(rows), receive_ns(rows)
    write(os.path.join(here, "imu_among_images.bag"), rows, stamps, receive,
          every=20, width=256, height=64, chunk_bytes=32768)
    seed = os.path.join(here, "..", "..", "fuzz", "ros1_bag", "seed_imu_among_images.bag")
    write(seed, rows[:12], stamps[:12], receive[:12],
          every=4, width=64, height=48, chunk_bytes=4096)


if __name__ == "__main__":
    main()
