#!/usr/bin/env python3
"""Copies a ROS 1 bag with the header stamps of one topic's messages moved
by a number of seconds, each message's receive time (the bag's own record
time) kept: a recording whose two clocks disagree, written with Debian's
python3-rosbag, apart from mpcal's reader.

  restamp_bag.py IN.bag OUT.bag TOPIC SECONDS
"""
import sys

import rosbag
import rospy


def main():
    src, dst, topic, seconds = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
    shift = rospy.Duration.from_sec(seconds)
    moved = 0
    with rosbag.Bag(src) as bag_in:
        # Topic by topic, each read in one pass over the file's chunks (read
        # all at once in time order, rosbag decompresses a chunk again for
        # each change of topic: minutes for this bag), then merged in time.
        messages = []
        for name in sorted(bag_in.get_type_and_topic_info().topics):
            for _, msg, received in bag_in.read_messages(topics=[name]):
                if name == topic:
                    msg.header.stamp = msg.header.stamp + shift
                    moved += 1
                messages.append((received.to_nsec(), len(messages), name, msg, received))
    if moved == 0:
        sys.exit(f"restamp_bag.py: no message on {topic} in {src}")
    messages.sort(key=lambda m: m[:2])
    with rosbag.Bag(dst, "w") as bag_out:
        for _, _, name, msg, received in messages:
            bag_out.write(name, msg, received)

if __name__ == "__main__":
    main()
