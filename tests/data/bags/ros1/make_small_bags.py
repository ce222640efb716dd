# SPDX-License-Identifier: BSD-3-Clause
"""Writes the ROS 1 bag fixtures of tests/core/tst_rosbag1.cpp with Debian's own writer.

Run with Debian's python3 (python3-rosbag, python3-sensor-msgs, python3-nav-msgs, python3-roslz4):

    /usr/bin/python3 tests/data/bags/ros1/make_small_bags.py

Every bag holds the same 7 messages, written in time order (ROS 1 bag format 2.0, described at
http://wiki.ros.org/Bags/Format/2.0):

  /sonar  sensor_msgs/Range    4 messages at 1700000000.0, .1, .2, .3 s   (header.seq 0..3)
  /odom   nav_msgs/Odometry    3 messages at 1700000000.05, .15, .25 s    (header.seq 10..12)

small_none.bag, small_bz2.bag, small_lz4.bag   one chunk each, in that compression
small_chunks.bag                               lz4, chunk_threshold=1: a chunk per message
small_noindex.bag                              small_chunks.bag as a recording cut short leaves it
"""

import os
import struct

import rosbag
import rospy
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Range

HERE = os.path.dirname(os.path.abspath(__file__))
T0 = 1700000000


def messages():
    """(topic, message, time) in the order written."""
    out = []
    for i in range(4):
        r = Range()
        r.header.seq = i
        r.header.stamp = rospy.Time(T0, i * 100000000)
        r.header.frame_id = 'sonar0'
        r.radiation_type = Range.ULTRASOUND
        r.field_of_view = 0.5
        r.min_range = 0.1
        r.max_range = 5.0
        r.range = 1.0 + i
        out.append(('/sonar', r, r.header.stamp))
        if i < 3:
            o = Odometry()
            o.header.seq = 10 + i
            o.header.stamp = rospy.Time(T0, i * 100000000 + 50000000)
            o.header.frame_id = 'odom'
            o.child_frame_id = 'base_link'
            o.pose.pose.position.x = 0.5 * i
            o.pose.pose.orientation.w = 1.0
            o.twist.twist.linear.x = 0.2
            out.append(('/odom', o, o.header.stamp))
    return out


def write(name, compression, chunk_threshold=768 * 1024):
    path = os.path.join(HERE, name)
    with rosbag.Bag(path, 'w', compression=compression, chunk_threshold=chunk_threshold) as bag:
        for topic, msg, t in messages():
            bag.write(topic, msg, t)
    return path


def cut_before_index(src, dst):
    """A recording cut short: the chunks and their index data records are on disk, the index
    (connection and chunk info records at index_pos) is not, and the bag header still holds what
    the writer put there when it started (index_pos 0, conn_count 0, chunk_count 0)."""
    with open(src, 'rb') as f:
        data = bytearray(f.read())
    field = b'index_pos='
    at = data.index(field) + len(field)
    (index_pos,) = struct.unpack_from('<Q', data, at)
    del data[index_pos:]
    struct.pack_into('<Q', data, at, 0)
    for name in (b'conn_count=', b'chunk_count='):
        struct.pack_into('<I', data, data.index(name) + len(name), 0)
    with open(dst, 'wb') as f:
        f.write(data)


def main():
    write('small_none.bag', rosbag.Compression.NONE)
    write('small_bz2.bag', rosbag.Compression.BZ2)
    write('small_lz4.bag', rosbag.Compression.LZ4)
    # chunk_threshold=1: the writer closes the chunk after every message (its uncompressed size
    # is over 1 byte), so each of the 7 messages has a chunk of its own.
    chunks = write('small_chunks.bag', rosbag.Compression.LZ4, chunk_threshold=1)
    cut_before_index(chunks, os.path.join(HERE, 'small_noindex.bag'))


if __name__ == '__main__':
    main()
