# SPDX-License-Identifier: BSD-3-Clause
"""Writes a large ROS 1 bag for bench_bag with Debian's own writer (python3-rosbag): the room
log's messages (tests/data/bags/room/sglog_messages.py: /tf_static, /odom, /ground_truth, /sonar,
as in room-none.bag) and, at every scan, a camera frame on /camera/image_raw (sensor_msgs/Image,
mono8) large enough that the bag reaches SIZE_MB. The chunks are rosbag's default (768 KiB
threshold), so every chunk holds a frame beside the sonar: the reader cannot pass chunks over, only
records within them.

    /usr/bin/python3 tests/bench/make_big_bag.py OUT.bag [SIZE_MB=1024] [none|lz4|bz2]

Run with Debian's python3 (python3-rosbag, python3-genpy, python3-sensor-msgs and the message
packages make_ros1.py lists).
"""

import os
import sys

import genpy
import rosbag
from sensor_msgs.msg import Image

sys.dont_write_bytecode = True
ROOM = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'data', 'bags', 'room')
sys.path.insert(0, ROOM)
import make_ros1  # noqa: E402
import sglog_messages  # noqa: E402


def main():
    out = sys.argv[1]
    size_mb = float(sys.argv[2]) if len(sys.argv) > 2 else 1024.0
    compression = {'none': rosbag.Compression.NONE, 'lz4': rosbag.Compression.LZ4,
                   'bz2': rosbag.Compression.BZ2}[sys.argv[3] if len(sys.argv) > 3 else 'none']
    records = list(sglog_messages.records())
    scans = sum(1 for r in records if r['topic'] == '/odom')
    width = 1280
    height = max(1, int(size_mb * 1e6 / scans / width))
    # A frame that does not compress to nothing: a ramp that shifts every frame.
    row = bytes(range(256)) * (width // 256 + 1)
    seqs = {}
    frame = 0
    with rosbag.Bag(out, 'w', compression=compression) as bag:
        for r in records:
            cls = make_ros1.CLASSES[r['type']]
            seq = seqs.get(r['topic'], 0)
            seqs[r['topic']] = seq + 1
            msg = make_ros1.fill(cls(), r['fields'], seq)
            t = genpy.Time(r['sec'], r['nsec'])
            bag.write(r['topic'], msg, t)
            if r['topic'] == '/odom':
                image = Image()
                image.header.seq = frame
                image.header.stamp = t
                image.header.frame_id = 'camera'
                image.height = height
                image.width = width
                image.encoding = 'mono8'
                image.step = width
                image.data = b''.join(row[(frame + y) % 256:(frame + y) % 256 + width]
                                      for y in range(height))
                bag.write('/camera/image_raw', image, t)
                frame += 1
    print(f'{out}: {os.path.getsize(out)} bytes, {frame} frames of {width} x {height}')


if __name__ == '__main__':
    main()
