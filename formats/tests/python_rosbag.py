#!/usr/bin/python3
"""Writes a ROS 1 bag with Debian's python3-rosbag (another writer than ours) and what it holds.

usage: python_rosbag.py OUT.bag none|bz2|lz4 EXPECTED.txt

Two topics of std_msgs/String and one of std_msgs/UInt32, recorded out of time order across
topics and over several small chunks, so that a reader must merge the chunks' indexes to give
the messages in time order. EXPECTED.txt lists, in the order rosbag's own reader gives them
(time order), one line a message: topic, sec, nsec and the serialised bytes in hex.
"""
import io
import sys

import rosbag
import rospy
from std_msgs.msg import String, UInt32


def main():
    out, compression, expected = sys.argv[1:4]
    with rosbag.Bag(out, "w", compression=compression, chunk_threshold=2048) as bag:
        for i in range(60):
            # /chatter ticks every 0.1 s; /late is written 1.05 s behind it; /count every 0.25 s.
            bag.write("/chatter", String(data="hello %d " % i + "x" * (i * 7)),
                      rospy.Time(100, 0) + rospy.Duration(0.1 * i))
            if i >= 10:
                bag.write("/late", String(data="late %d" % i),
                          rospy.Time(100, 0) + rospy.Duration(0.1 * i - 1.05))
            if i % 5 == 0:
                bag.write("/count", UInt32(data=i), rospy.Time(100, 0) + rospy.Duration(0.05 * i))
    with rosbag.Bag(out) as bag, open(expected, "w") as listing:
        for topic, message, time in bag.read_messages():
            buffer = io.BytesIO()
            message.serialize(buffer)
            listing.write("%s %d %d %s\n" % (topic, time.secs, time.nsecs, buffer.getvalue().hex()))


if __name__ == "__main__":
    main()
