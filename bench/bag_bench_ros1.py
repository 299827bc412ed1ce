#!/usr/bin/python3
"""Writes the bag benchmark's ROS 1 bags with Debian's rosbag (not mpcal).

Each CSV row (t in s, ax ay az in m/s2, gx gy gz in rad/s) becomes one
sensor_msgs/Imu on /imu/data, header stamp and receive time 1700000000 s + t.
With --camera, a sensor_msgs/Image on /camera/image_raw every 1/30 s
(640x480 mono8, 307,200 bytes of pseudo-random pixels: a camera's noise,
which lz4 does not shrink) is written among them in time order, as a
recorder writes two topics.

  /usr/bin/python3 bag_bench_ros1.py CSV OUT.bag --compression lz4 [--camera]
"""
import argparse
import bisect
import csv
import random

import rosbag
import rospy
from sensor_msgs.msg import Image, Imu

EPOCH_NS = 1700000000 * 10**9
CAMERA_HZ = 30
WIDTH, HEIGHT = 640, 480


class _InOrderBisect:
    """rosbag.bag's bisect, with insort_right appending an entry that sorts
    last (where insort_right puts it) without the binary search: the rows
    are in time order, and on a million messages the search over the bag's
    whole index, by rospy.Time comparisons in Python, is most of the
    writer's time. The file written is the same."""

    def __getattr__(self, name):
        return getattr(bisect, name)

    @staticmethod
    def insort_right(a, x):
        if not a or not x < a[-1]:
            a.append(x)
        else:
            bisect.insort_right(a, x)


rosbag.bag.bisect = _InOrderBisect()


def main():
    p = argparse.ArgumentParser()
    p.add_argument("csv")
    p.add_argument("out")
    p.add_argument("--compression", default="lz4", choices=("none", "bz2", "lz4"))
    p.add_argument("--camera", action="store_true")
    args = p.parse_args()
    rng = random.Random(7)
    # Eight frames, reused in turn: the pixels' content does not matter to
    # the reader, only their bytes.
    frames = [rng.randbytes(WIDTH * HEIGHT) for _ in range(8)]
    next_frame = 0
    with open(args.csv, newline="") as f, \
            rosbag.Bag(args.out, "w", compression=args.compression) as bag:
        for i, row in enumerate(csv.DictReader(f)):
            t_ns = EPOCH_NS + int(round(float(row["t"]) * 1e9))
            while args.camera and EPOCH_NS + next_frame * 10**9 // CAMERA_HZ <= t_ns:
                img = Image()
                img.header.seq = next_frame
                img.header.stamp = rospy.Time(nsecs=EPOCH_NS + next_frame * 10**9 // CAMERA_HZ)
                img.header.frame_id = "camera"
                img.height, img.width, img.encoding, img.step = HEIGHT, WIDTH, "mono8", WIDTH
                img.data = frames[next_frame % len(frames)]
                bag.write("/camera/image_raw", img, img.header.stamp)
                next_frame += 1
            m = Imu()
            m.header.seq = i
            m.header.stamp = rospy.Time(nsecs=t_ns)
            m.header.frame_id = "imu_link"
            m.orientation_covariance[0] = -1.0  # no orientation, as REP 145 says
            m.linear_acceleration.x = float(row["ax"])
            m.linear_acceleration.y = float(row["ay"])
            m.linear_acceleration.z = float(row["az"])
            m.angular_velocity.x = float(row["gx"])
            m.angular_velocity.y = float(row["gy"])
            m.angular_velocity.z = float(row["gz"])
            bag.write("/imu/data", m, m.header.stamp)


if __name__ == "__main__":
    main()
