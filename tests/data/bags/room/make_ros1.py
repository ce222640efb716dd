# SPDX-License-Identifier: BSD-3-Clause
"""Writes datasets/room/room.sglog as ROS 1 bags with Debian's own writer (python3-rosbag).

Run with Debian's python3 (python3-rosbag, python3-roslz4, python3-genpy and the message packages
python3-sensor-msgs, python3-nav-msgs, python3-geometry-msgs, python3-tf2-msgs):

    /usr/bin/python3 tests/data/bags/room/make_ros1.py

room-none.bag, room-bz2.bag, room-lz4.bag   the sglog-equivalent messages of sglog_messages.py
                                            (/tf_static, /odom, /ground_truth, /sonar), in that
                                            chunk compression (default chunk threshold, 768 KiB)
rosaria-room.bag                            bz2: /RosAria/pose and /RosAria/sonar (PointCloud) per
                                            scan, as RosAria publishes them

The output is deterministic: running it again gives the same bytes.
"""

import os
import sys

import genpy
import rosbag
from geometry_msgs.msg import Point32, PoseStamped, TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import PointCloud, Range
from tf2_msgs.msg import TFMessage

sys.dont_write_bytecode = True  # no __pycache__ beside the fixtures
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sglog_messages  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
CLASSES = {
    'sensor_msgs/Range': Range,
    'nav_msgs/Odometry': Odometry,
    'geometry_msgs/PoseStamped': PoseStamped,
    'tf2_msgs/TFMessage': TFMessage,
    'sensor_msgs/PointCloud': PointCloud,
}
# The element types of the array fields the records fill.
ARRAY_ITEMS = {
    'transforms': TransformStamped,
    'points': Point32,
}
# The connection header a latched publisher (tf2_ros' static broadcaster) gives rosbag record.
LATCHED = {'/tf_static': '/sonar_static_tf'}


def fill(msg, fields, seq):
    """Sets MSG's fields from the record's nested dicts; a header gets header.seq = SEQ."""
    for name, value in fields.items():
        if name == 'header':
            msg.header.seq = seq
            msg.header.stamp = genpy.Time(*value['stamp'])
            msg.header.frame_id = value['frame_id']
        elif isinstance(value, dict):
            fill(getattr(msg, name), value, seq)
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            item_class = ARRAY_ITEMS[name]
            items = []
            for v in value:
                item = item_class()
                fill(item, v, 0)
                items.append(item)
            setattr(msg, name, items)
        else:
            setattr(msg, name, value)
    return msg


def write(name, records, compression):
    path = os.path.join(HERE, name)
    seqs = {}
    counts = {}
    with rosbag.Bag(path, 'w', compression=compression) as bag:
        for r in records:
            cls = CLASSES[r['type']]
            seq = seqs.get(r['topic'], 0)
            seqs[r['topic']] = seq + 1
            msg = fill(cls(), r['fields'], seq)
            header = None
            if r['topic'] in LATCHED:
                header = {
                    'callerid': LATCHED[r['topic']],
                    'latching': '1',
                    'md5sum': cls._md5sum,
                    'message_definition': cls._full_text,
                    'topic': r['topic'],
                    'type': cls._type,
                }
            bag.write(r['topic'], msg, genpy.Time(r['sec'], r['nsec']), connection_header=header)
            counts[r['topic']] = counts.get(r['topic'], 0) + 1
    summary = ', '.join(f'{n} {t}' for t, n in counts.items())
    print(f'{name}: {os.path.getsize(path)} bytes ({summary})')


def main():
    records = list(sglog_messages.records())
    write('room-none.bag', records, rosbag.Compression.NONE)
    write('room-bz2.bag', records, rosbag.Compression.BZ2)
    write('room-lz4.bag', records, rosbag.Compression.LZ4)
    write('rosaria-room.bag', list(sglog_messages.rosaria_records()), rosbag.Compression.BZ2)
    sglog_messages.report_angles(sys.stdout)
    if sglog_messages.UNMATCHED:
        print('WARNING: some yaws do not come back exactly from their quaternion (see above)')


if __name__ == '__main__':
    main()
