#!/usr/bin/python3
"""Checks a ROS 1 bag written by `mpcal apply` with Debian's rosbag (not mpcal).

  /usr/bin/python3 apply_bag_ros1.py INPUT.bag OUTPUT.bag CORRECTED.csv [TOPIC [NOISE.json]]

Opening OUTPUT.bag reads its bag header, connection and chunk info records;
reading its messages goes through the index data records to each message's
offset in its chunk, so a wrong index fails here. Then: the same topics,
types, md5sums, message counts and chunk compression as INPUT.bag; every
message of another topic byte for byte as it was, at the same record time;
every IMU message with its record time, header (seq, stamp, frame_id),
orientation and the three covariances as they were, and its linear
acceleration and angular velocity equal to the row of CORRECTED.csv (the same
rows corrected by `mpcal apply` as a CSV) to 1e-12 relative. With NOISE.json
(`apply --noise`), the linear acceleration and angular velocity covariances
are instead N**2 * f on the diagonal and 0 elsewhere, to 1e-12 relative: N the
file's white noise per axis, f = (n - 1) / (last - first record time) of the
topic's n messages, as rosbag reads them.
"""
import json
import csv
import sys

import rosbag


def fail(what):
    print("apply_bag_ros1.py: " + what)
    sys.exit(1)


def close(a, b):
    return abs(a - b) <= 1e-12 * max(1.0, abs(a), abs(b))


def topics_of(bag):
    info = bag.get_type_and_topic_info()
    return {name: (t.msg_type, t.message_count) for name, t in info.topics.items()}


def noise_covariances(noise, bag, topic):
    """The covariances `apply --noise` sets: {field: 9 values}."""
    times = [t.to_nsec() for _, _, t in bag.read_messages(topics=[topic])]
    rate = (len(times) - 1) / ((times[-1] - times[0]) * 1e-9)
    d = json.load(open(noise))
    out = {}
    for sensor, key, field in (
            ("accelerometer", "white_noise_mps2_per_rthz", "linear_acceleration_covariance"),
            ("gyroscope", "white_noise_radps_per_rthz", "angular_velocity_covariance")):
        n = [d[sensor]["axes"][a][key]["value"] for a in "xyz"]
        out[field] = [n[i] ** 2 * rate if i == j else 0.0 for i in range(3) for j in range(3)]
    return out


def main(src, out, corrected, topic="/imu/data", noise=None):
    rows = list(csv.DictReader(open(corrected, newline="")))
    with rosbag.Bag(src) as bin_, rosbag.Bag(out) as bout:
        expected_cov = noise_covariances(noise, bin_, topic) if noise else {}
        if topics_of(bin_) != topics_of(bout):
            fail("topics differ: %s vs %s" % (topics_of(bin_), topics_of(bout)))
        md5_in = {c.topic: c.md5sum for c in bin_._connections.values()}
        md5_out = {c.topic: c.md5sum for c in bout._connections.values()}
        if md5_in != md5_out:
            fail("connections differ: %s vs %s" % (md5_in, md5_out))
        if bin_.get_compression_info().compression != bout.get_compression_info().compression:
            fail("compression %s, not %s" % (bout.get_compression_info().compression,
                                             bin_.get_compression_info().compression))
        others = [t for t in topics_of(bin_) if t != topic]
        n_other = 0
        for a, b in zip(bin_.read_messages(topics=others, raw=True),
                        bout.read_messages(topics=others, raw=True)):
            if a.topic != b.topic or a.timestamp != b.timestamp or a.message[1] != b.message[1]:
                fail("message %d of the other topics differs" % n_other)
            n_other += 1
        n_imu = 0
        for a, b in zip(bin_.read_messages(topics=[topic]), bout.read_messages(topics=[topic])):
            m, c = a.message, b.message
            if a.timestamp != b.timestamp:
                fail("IMU message %d: record time changed" % n_imu)
            if (m.header.seq, m.header.stamp, m.header.frame_id) != (
                    c.header.seq, c.header.stamp, c.header.frame_id):
                fail("IMU message %d: header changed" % n_imu)
            for name in ("orientation_covariance", "angular_velocity_covariance",
                         "linear_acceleration_covariance"):
                if name in expected_cov:
                    if not all(close(g, w) for g, w in zip(getattr(c, name), expected_cov[name])):
                        fail("IMU message %d: %s %s, not %s" % (
                            n_imu, name, tuple(getattr(c, name)), expected_cov[name]))
                elif tuple(getattr(m, name)) != tuple(getattr(c, name)):
                    fail("IMU message %d: %s changed" % (n_imu, name))
            if (m.orientation.x, m.orientation.y, m.orientation.z, m.orientation.w) != (
                    c.orientation.x, c.orientation.y, c.orientation.z, c.orientation.w):
                fail("IMU message %d: orientation changed" % n_imu)
            row = rows[n_imu]
            got = [c.linear_acceleration.x, c.linear_acceleration.y, c.linear_acceleration.z,
                   c.angular_velocity.x, c.angular_velocity.y, c.angular_velocity.z]
            want = [float(row[k]) for k in ("ax", "ay", "az", "gx", "gy", "gz")]
            if not all(close(g, w) for g, w in zip(got, want)):
                fail("IMU message %d: %s, the CSV row says %s" % (n_imu, got, want))
            n_imu += 1
        if n_imu != len(rows) or n_imu != topics_of(bin_)[topic][1]:
            fail("%d IMU messages for %d rows" % (n_imu, len(rows)))
        if n_other != sum(topics_of(bin_)[t][1] for t in others):
            fail("%d messages of other topics" % n_other)
    print("%s: %d IMU messages as the CSV, %d others byte for byte" % (out, n_imu, n_other))


if __name__ == "__main__":
    main(*sys.argv[1:])
