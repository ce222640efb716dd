# SPDX-License-Identifier: BSD-3-Clause
"""Writes the ROS 1 message fixtures (*.ros1.bin) of tst_ros_messages with the real ROS 1
serialiser: the genpy message classes of Debian's python3-sensor-msgs, python3-nav-msgs,
python3-geometry-msgs, python3-tf2-msgs and python3-std-msgs (`msg.serialize(buffer)`).

    apt-get install -y python3-sensor-msgs python3-nav-msgs python3-geometry-msgs \
        python3-tf2-msgs python3-std-msgs
    /usr/bin/python3 tests/data/bags/messages/make_ros1_messages.py

Run it with Debian's python3 (the packages live in its dist-packages). The values are those of
make_cdr_messages.mjs, so that the test compares every encoding with the same numbers; the
quaternions are written as literals (Python's repr of math.sin and math.cos of half the yaw) so
that every writer writes the same bits.
"""

import io
import math
import os
import struct

import genpy
from geometry_msgs.msg import (Point, Point32, Pose, PoseStamped, PoseWithCovariance,
                               Quaternion, Transform, TransformStamped, Twist,
                               TwistWithCovariance, Vector3)
from nav_msgs.msg import Odometry
from sensor_msgs.msg import ChannelFloat32, PointCloud, PointCloud2, PointField, Range
from std_msgs.msg import Header
from tf2_msgs.msg import TFMessage

HERE = os.path.dirname(os.path.abspath(__file__))

# Yaw 0.3 rad: z = sin(0.15), w = cos(0.15). Yaw -1.2: sin(-0.6), cos(-0.6). Yaw pi/2: sqrt(0.5).
YAW_03 = (0.0, 0.0, 0.14943813247359922, 0.9887710779360422)
YAW_M12 = (0.0, 0.0, -0.5646424733950354, 0.8253356149096783)
YAW_90 = (0.0, 0.0, 0.7071067811865476, 0.7071067811865476)


def header(seq, secs, nsecs, frame):
    return Header(seq=seq, stamp=genpy.Time(secs, nsecs), frame_id=frame)


def write(name, msg):
    buf = io.BytesIO()
    msg.serialize(buf)
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(buf.getvalue())
    print(name, len(buf.getvalue()), "bytes")


def quaternion(q):
    return Quaternion(x=q[0], y=q[1], z=q[2], w=q[3])


def range_msg():
    return Range(header=header(7, 12, 500000000, "sonar_3"), radiation_type=Range.INFRARED,
                 field_of_view=0.4363, min_range=0.1, max_range=5.0, range=2.873)


def odometry_msg():
    return Odometry(
        header=header(3, 1700000000, 123456789, "odom"),
        child_frame_id="base_link",
        pose=PoseWithCovariance(
            pose=Pose(position=Point(x=1.25, y=-3.5, z=0.0625), orientation=quaternion(YAW_03)),
            covariance=[0.01 * i for i in range(36)]),
        twist=TwistWithCovariance(
            twist=Twist(linear=Vector3(x=0.5, y=0.0, z=0.0), angular=Vector3(x=0.0, y=0.0, z=0.1)),
            covariance=[-0.5 * i for i in range(36)]))


def pose_stamped_msg():
    return PoseStamped(header=header(9, 42, 1, "map"),
                       pose=Pose(position=Point(x=10.5, y=20.25, z=-0.75),
                                 orientation=quaternion(YAW_M12)))


def tf_msg():
    return TFMessage(transforms=[
        TransformStamped(header=header(0, 100, 250000000, "odom"), child_frame_id="base_link",
                         transform=Transform(translation=Vector3(x=0.1, y=0.2, z=0.3),
                                             rotation=quaternion(YAW_03))),
        TransformStamped(header=header(1, 100, 250000001, "base_link"),
                         child_frame_id="sonar_3",
                         transform=Transform(translation=Vector3(x=0.115, y=-0.05, z=0.2),
                                             rotation=quaternion(YAW_90))),
    ])


def point_cloud_msg():
    return PointCloud(
        header=header(11, 12, 500000000, "sonar_ring"),
        points=[Point32(x=1.5, y=-0.25, z=0.125), Point32(x=2.75, y=0.5, z=0.0),
                Point32(x=-1.0, y=3.25, z=0.5)],
        channels=[ChannelFloat32(name="intensity", values=[0.5, 1.0, 0.25]),
                  ChannelFloat32(name="sonar", values=[0.0, 1.0, 2.0])])


def point_cloud2_msg():
    # FLOAT32 x, y, z and an intensity, 16 bytes a point, one row of four; the last point's x is
    # NaN (an invalid point, kept).
    points = [(1.5, -2.25, 0.125, 10.0), (3.0, 0.5, -0.75, 20.0), (0.0625, 100.5, 7.0, 30.0),
              (math.nan, 1.0, 2.0, 40.0)]
    data = b"".join(struct.pack("<4f", *p) for p in points)
    fields = [PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1)
              for i, n in enumerate(["x", "y", "z", "intensity"])]
    return PointCloud2(header=header(12, 12, 500000000, "sonar_ring"), height=1, width=4,
                       fields=fields, is_bigendian=False, point_step=16, row_step=64, data=data,
                       is_dense=False)


def main():
    write("range.ros1.bin", range_msg())
    write("odometry.ros1.bin", odometry_msg())
    write("posestamped.ros1.bin", pose_stamped_msg())
    write("tf.ros1.bin", tf_msg())
    write("pointcloud.ros1.bin", point_cloud_msg())
    write("pointcloud2.ros1.bin", point_cloud2_msg())


if __name__ == "__main__":
    main()
