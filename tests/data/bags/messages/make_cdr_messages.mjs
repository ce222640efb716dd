// SPDX-License-Identifier: BSD-3-Clause
// Writes the ROS 2 CDR message fixtures of tst_ros_messages with real CDR writers:
// - *.cdr-le.bin: @foxglove/rosmsg2-serialization's MessageWriter (little-endian XCDR1, as
//   rosbag2 stores it), given the ROS 2 .msg definitions below as text, parsed by
//   @foxglove/rosmsg;
// - *.cdr-be.bin: @foxglove/cdr's CdrWriter with kind CDR_BE, written field by field in the
//   order of the same definitions (Range and Odometry).
//
//   NPM_DIR=$(mktemp -d)
//   cp tests/data/bags/messages/package.json "$NPM_DIR"/
//   npm install --prefix "$NPM_DIR"
//   node tests/data/bags/messages/make_cdr_messages.mjs "$NPM_DIR"
//
// The values are those of make_ros1_messages.py (ROS 2 headers have no seq).
import { createRequire } from "node:module";
import { writeFileSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

if (!process.argv[2]) {
  console.error("usage: node make_cdr_messages.mjs NPM_PREFIX (the folder npm installed into)");
  process.exit(2);
}
const prefix = resolve(process.argv[2]);
const require = createRequire(join(prefix, "node_modules", "package.json"));
const { parse } = require("@foxglove/rosmsg");
const { MessageWriter } = require("@foxglove/rosmsg2-serialization");
const { CdrWriter, EncapsulationKind } = require("@foxglove/cdr");

const here = dirname(fileURLToPath(import.meta.url));

// Yaw 0.3 rad: z = sin(0.15), w = cos(0.15). Yaw -1.2: sin(-0.6), cos(-0.6). Yaw pi/2: sqrt(0.5).
const YAW_03 = { x: 0, y: 0, z: 0.14943813247359922, w: 0.9887710779360422 };
const YAW_M12 = { x: 0, y: 0, z: -0.5646424733950354, w: 0.8253356149096783 };
const YAW_90 = { x: 0, y: 0, z: 0.7071067811865476, w: 0.7071067811865476 };

// The ROS 2 (Humble) .msg definitions, concatenated as rosbag2 and MCAP carry them.
const SEP = "\n================================================================================\n";
const HEADER = `MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id`;
const POINT = `MSG: geometry_msgs/Point
float64 x
float64 y
float64 z`;
const QUATERNION = `MSG: geometry_msgs/Quaternion
float64 x 0
float64 y 0
float64 z 0
float64 w 1`;
const VECTOR3 = `MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z`;
const POSE = `MSG: geometry_msgs/Pose
Point position
Quaternion orientation`;

const RANGE = `uint8 ULTRASOUND=0
uint8 INFRARED=1
std_msgs/Header header
uint8 radiation_type
float32 field_of_view
float32 min_range
float32 max_range
float32 range`;
// Newer ROS 2 releases add a variance at the end of sensor_msgs/Range.
const RANGE_VARIANCE = `${RANGE}
float32 variance`;
const ODOMETRY = [
  `std_msgs/Header header
string child_frame_id
geometry_msgs/PoseWithCovariance pose
geometry_msgs/TwistWithCovariance twist`,
  HEADER,
  `MSG: geometry_msgs/PoseWithCovariance
Pose pose
float64[36] covariance`,
  POSE,
  POINT,
  QUATERNION,
  `MSG: geometry_msgs/TwistWithCovariance
Twist twist
float64[36] covariance`,
  `MSG: geometry_msgs/Twist
Vector3 linear
Vector3 angular`,
  VECTOR3,
].join(SEP);
const POSE_STAMPED = [
  `std_msgs/Header header
geometry_msgs/Pose pose`,
  HEADER,
  POSE,
  POINT,
  QUATERNION,
].join(SEP);
const TF = [
  "geometry_msgs/TransformStamped[] transforms",
  `MSG: geometry_msgs/TransformStamped
std_msgs/Header header
string child_frame_id
Transform transform`,
  HEADER,
  `MSG: geometry_msgs/Transform
Vector3 translation
Quaternion rotation`,
  VECTOR3,
  QUATERNION,
].join(SEP);
const POINT_CLOUD = [
  `std_msgs/Header header
geometry_msgs/Point32[] points
ChannelFloat32[] channels`,
  HEADER,
  `MSG: geometry_msgs/Point32
float32 x
float32 y
float32 z`,
  `MSG: sensor_msgs/ChannelFloat32
string name
float32[] values`,
].join(SEP);
const POINT_CLOUD2 = [
  `std_msgs/Header header
uint32 height
uint32 width
PointField[] fields
bool is_bigendian
uint32 point_step
uint32 row_step
uint8[] data
bool is_dense`,
  HEADER,
  `MSG: sensor_msgs/PointField
uint8 INT8    = 1
uint8 UINT8   = 2
uint8 INT16   = 3
uint8 UINT16  = 4
uint8 INT32   = 5
uint8 UINT32  = 6
uint8 FLOAT32 = 7
uint8 FLOAT64 = 8
string name
uint32 offset
uint8 datatype
uint32 count`,
].join(SEP);

function write(name, bytes) {
  writeFileSync(join(here, name), bytes);
  console.log(name, bytes.length, "bytes");
}

function writeMessage(name, definition, message) {
  const writer = new MessageWriter(parse(definition, { ros2: true }));
  write(name, writer.writeMessage(message));
}

const header = (sec, nanosec, frame_id) => ({ stamp: { sec, nanosec }, frame_id });
const iota = (n, f) => Array.from({ length: n }, (_, i) => f(i));

const range = {
  header: header(12, 500000000, "sonar_3"),
  radiation_type: 1,
  field_of_view: 0.4363,
  min_range: 0.1,
  max_range: 5.0,
  range: 2.873,
};
const odometry = {
  header: header(1700000000, 123456789, "odom"),
  child_frame_id: "base_link",
  pose: {
    pose: { position: { x: 1.25, y: -3.5, z: 0.0625 }, orientation: YAW_03 },
    covariance: iota(36, (i) => 0.01 * i),
  },
  twist: {
    twist: { linear: { x: 0.5, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0.1 } },
    covariance: iota(36, (i) => -0.5 * i),
  },
};
const poseStamped = {
  header: header(42, 1, "map"),
  pose: { position: { x: 10.5, y: 20.25, z: -0.75 }, orientation: YAW_M12 },
};
const tf = {
  transforms: [
    {
      header: header(100, 250000000, "odom"),
      child_frame_id: "base_link",
      transform: { translation: { x: 0.1, y: 0.2, z: 0.3 }, rotation: YAW_03 },
    },
    {
      header: header(100, 250000001, "base_link"),
      child_frame_id: "sonar_3",
      transform: { translation: { x: 0.115, y: -0.05, z: 0.2 }, rotation: YAW_90 },
    },
  ],
};
const pointCloud = {
  header: header(12, 500000000, "sonar_ring"),
  points: [
    { x: 1.5, y: -0.25, z: 0.125 },
    { x: 2.75, y: 0.5, z: 0 },
    { x: -1, y: 3.25, z: 0.5 },
  ],
  channels: [
    { name: "intensity", values: [0.5, 1.0, 0.25] },
    { name: "sonar", values: [0, 1, 2] },
  ],
};

// PointCloud2 payloads: each point's fields written with a DataView at their offsets.
function cloudData(rows, cols, pointStep, rowStep, fields, values, littleEndian) {
  const data = new Uint8Array(rows * rowStep);
  const view = new DataView(data.buffer);
  const setters = {
    1: (o, v) => view.setInt8(o, v),
    2: (o, v) => view.setUint8(o, v),
    3: (o, v) => view.setInt16(o, v, littleEndian),
    4: (o, v) => view.setUint16(o, v, littleEndian),
    5: (o, v) => view.setInt32(o, v, littleEndian),
    6: (o, v) => view.setUint32(o, v, littleEndian),
    7: (o, v) => view.setFloat32(o, v, littleEndian),
    8: (o, v) => view.setFloat64(o, v, littleEndian),
  };
  for (let r = 0; r < rows; ++r) {
    for (let c = 0; c < cols; ++c) {
      const point = values[r * cols + c];
      fields.forEach((f, i) => setters[f.datatype](r * rowStep + c * pointStep + f.offset, point[i]));
    }
  }
  return data;
}

function pointCloud2(height, width, fields, pointStep, rowStep, values, isBigendian) {
  return {
    header: header(12, 500000000, "sonar_ring"),
    height,
    width,
    fields: fields.map((f) => ({ ...f, count: 1 })),
    is_bigendian: isBigendian,
    point_step: pointStep,
    row_step: rowStep,
    data: cloudData(height, width, pointStep, rowStep, fields, values, !isBigendian),
    is_dense: false,
  };
}

// FLOAT32 x, y, z and an intensity, one row of four; the last point's x is NaN.
const F32 = ["x", "y", "z", "intensity"].map((name, i) => ({ name, offset: 4 * i, datatype: 7 }));
const cloudF32 = pointCloud2(1, 4, F32, 16, 64, [
  [1.5, -2.25, 0.125, 10],
  [3.0, 0.5, -0.75, 20],
  [0.0625, 100.5, 7.0, 30],
  [NaN, 1.0, 2.0, 40],
], false);
// A FLOAT32 intensity first, then FLOAT64 x, y, z; two rows of two points, each row padded with 8
// bytes (row_step 72 = 2 * 32 + 8).
const F64 = [
  { name: "intensity", offset: 0, datatype: 7 },
  { name: "x", offset: 8, datatype: 8 },
  { name: "y", offset: 16, datatype: 8 },
  { name: "z", offset: 24, datatype: 8 },
];
const cloudF64 = pointCloud2(2, 2, F64, 32, 72, [
  [1, 1.1, 2.2, 3.3],
  [2, -4.4, 5.5, -6.6],
  [3, 7.7, -8.8, 9.9],
  [4, 0.001, 0.002, 0.003],
], false);
// Big-endian integer coordinates: INT16 x, UINT32 y (not aligned), INT8 z; 8 bytes a point.
const INTS = [
  { name: "x", offset: 0, datatype: 3 },
  { name: "y", offset: 2, datatype: 6 },
  { name: "z", offset: 6, datatype: 1 },
];
const cloudInt = pointCloud2(1, 2, INTS, 8, 16, [
  [-1234, 3000000000, -7],
  [32767, 1, 127],
], true);

writeMessage("range.cdr-le.bin", RANGE + SEP + HEADER, range);
writeMessage("range-variance.cdr-le.bin", RANGE_VARIANCE + SEP + HEADER, { ...range, variance: 0.0009 });
writeMessage("odometry.cdr-le.bin", ODOMETRY, odometry);
writeMessage("posestamped.cdr-le.bin", POSE_STAMPED, poseStamped);
writeMessage("tf.cdr-le.bin", TF, tf);
writeMessage("pointcloud.cdr-le.bin", POINT_CLOUD, pointCloud);
writeMessage("pointcloud2.cdr-le.bin", POINT_CLOUD2, cloudF32);
writeMessage("pointcloud2-f64.cdr-le.bin", POINT_CLOUD2, cloudF64);
writeMessage("pointcloud2-int-be.cdr-le.bin", POINT_CLOUD2, cloudInt);

// Big-endian CDR, field by field.
function writeHeader(w, h) {
  w.int32(h.stamp.sec).uint32(h.stamp.nanosec).string(h.frame_id);
}
{
  const w = new CdrWriter({ kind: EncapsulationKind.CDR_BE });
  writeHeader(w, range.header);
  w.uint8(range.radiation_type);
  w.float32(range.field_of_view).float32(range.min_range).float32(range.max_range);
  w.float32(range.range);
  write("range.cdr-be.bin", w.data);
}
{
  const w = new CdrWriter({ kind: EncapsulationKind.CDR_BE });
  const o = odometry;
  writeHeader(w, o.header);
  w.string(o.child_frame_id);
  const p = o.pose.pose;
  w.float64(p.position.x).float64(p.position.y).float64(p.position.z);
  w.float64(p.orientation.x).float64(p.orientation.y).float64(p.orientation.z);
  w.float64(p.orientation.w);
  w.float64Array(o.pose.covariance, false);
  const t = o.twist.twist;
  w.float64(t.linear.x).float64(t.linear.y).float64(t.linear.z);
  w.float64(t.angular.x).float64(t.angular.y).float64(t.angular.z);
  w.float64Array(o.twist.covariance, false);
  write("odometry.cdr-be.bin", w.data);
}
