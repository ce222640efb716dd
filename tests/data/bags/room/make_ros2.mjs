// SPDX-License-Identifier: BSD-3-Clause
// Writes datasets/room/room.sglog as ROS 2 bags with real writers: MCAP files with @mcap/core's
// McapWriter, messages CDR-serialised by @foxglove/rosmsg2-serialization's MessageWriter from
// ROS 2 .msg definitions parsed by @foxglove/rosmsg, and a rosbag2 SQLite storage written by
// SQLite itself (better-sqlite3) with the tables rosbag2 creates. Exact versions: package.json.
//
//   NPM_DIR=$(mktemp -d)
//   cp tests/data/bags/room/package.json tests/data/bags/room/package-lock.json "$NPM_DIR"/
//   npm ci --prefix "$NPM_DIR"
//   /usr/bin/python3 tests/data/bags/room/sglog_messages.py --json "$NPM_DIR/room.json"
//   node tests/data/bags/room/make_ros2.mjs "$NPM_DIR/node_modules" "$NPM_DIR/room.json"
//
// The messages are the records of sglog_messages.py (the JSON it dumps), in that order:
// /tf_static once, then per scan /odom, /ground_truth and one /sonar per reading, every log time
// equal to the message's header stamp. Output: room-zstd.mcap, room-lz4.mcap and
// room-sqlite/{room-sqlite_0.db3,metadata.yaml}. Running it again gives the same bytes.

import fs from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
if (process.argv.length !== 4) {
  console.error("usage: node make_ros2.mjs NODE_MODULES_DIR RECORDS_JSON");
  process.exit(2);
}
const require = createRequire(path.join(path.resolve(process.argv[2]), "noop.js"));
const { McapWriter } = require("@mcap/core");
const { MessageWriter } = require("@foxglove/rosmsg2-serialization");
const { parse } = require("@foxglove/rosmsg");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("lz4js");
const Database = require("better-sqlite3");
const modulesDir = path.resolve(process.argv[2]);
const versionOf = (name) =>
  JSON.parse(fs.readFileSync(path.join(modulesDir, name, "package.json"), "utf8")).version;

// ---- ROS 2 message definitions (Humble's .msg files, their fields without the comments) ----

const MSG = {
  "builtin_interfaces/msg/Time": "int32 sec\nuint32 nanosec\n",
  "std_msgs/msg/Header": "builtin_interfaces/Time stamp\nstring frame_id\n",
  "geometry_msgs/msg/Point": "float64 x\nfloat64 y\nfloat64 z\n",
  "geometry_msgs/msg/Quaternion": "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n",
  "geometry_msgs/msg/Vector3": "float64 x\nfloat64 y\nfloat64 z\n",
  "geometry_msgs/msg/Pose": "Point position\nQuaternion orientation\n",
  "geometry_msgs/msg/PoseStamped": "std_msgs/Header header\nPose pose\n",
  "geometry_msgs/msg/PoseWithCovariance": "Pose pose\nfloat64[36] covariance\n",
  "geometry_msgs/msg/Twist": "Vector3  linear\nVector3  angular\n",
  "geometry_msgs/msg/TwistWithCovariance": "Twist twist\nfloat64[36] covariance\n",
  "geometry_msgs/msg/Transform": "Vector3 translation\nQuaternion rotation\n",
  "geometry_msgs/msg/TransformStamped":
    "std_msgs/Header header\nstring child_frame_id\nTransform transform\n",
  "nav_msgs/msg/Odometry":
    "std_msgs/Header header\nstring child_frame_id\n" +
    "geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n",
  "sensor_msgs/msg/Range":
    "std_msgs/Header header\n" +
    "uint8 ULTRASOUND=0\nuint8 INFRARED=1\n" +
    "uint8 radiation_type\nfloat32 field_of_view\nfloat32 min_range\nfloat32 max_range\n" +
    "float32 range\n",
  "tf2_msgs/msg/TFMessage": "geometry_msgs/TransformStamped[] transforms\n",
};
const PRIMITIVES = new Set([
  "bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16",
  "int32", "uint32", "int64", "uint64", "string", "wstring",
]);

// The complete "ros2msg" definition as rosbag2 records it (its message_definition_encoding.md):
// the type's own text, then every type it uses, depth first, each type's dependencies in sorted
// order and each type once, preceded by "\n", a line of 80 '=' and "MSG: pkg/Type" (the name
// as the field spells it, a bare name taking the package of the type that uses it).
function dependencies(type) {
  const pkg = type.split("/")[0];
  const out = new Set();
  for (const line of MSG[type].split("\n")) {
    const m = /^\s*([A-Za-z0-9_/]+)(?:\[[^\]]*\])?\s+/.exec(line);
    if (!m || PRIMITIVES.has(m[1])) continue;
    out.add(m[1].includes("/") ? m[1] : `${pkg}/${m[1]}`);
  }
  return [...out].sort();
}
const full = (name) => name.replace(/^([^/]+)\/([^/]+)$/, "$1/msg/$2");
function fullText(root) {
  const seen = new Set();
  const append = (type) => {
    let text = MSG[type];
    for (const dep of dependencies(type)) {
      if (seen.has(dep)) continue;
      seen.add(dep);
      text += `\n${"=".repeat(80)}\nMSG: ${dep}\n` + append(full(dep));
    }
    return text;
  };
  return append(root);
}

// ---- the messages ----

const records = JSON.parse(fs.readFileSync(process.argv[3], "utf8"));
const ros2Type = (ros1) => ros1.replace("/", "/msg/");

// Turns a record's fields into the object MessageWriter takes: a header stamp [sec, nsec]
// becomes {sec, nanosec}, the string "inf" (no echo) becomes Infinity.
function ros2Fields(v) {
  if (Array.isArray(v)) return v.map(ros2Fields);
  if (v === "inf") return Infinity;
  if (v === null || typeof v !== "object") return v;
  const out = {};
  for (const [k, x] of Object.entries(v)) {
    out[k] = k === "stamp" ? { sec: x[0], nanosec: x[1] } : ros2Fields(x);
  }
  return out;
}

const topics = []; // {name, type}, in the order of their first message
const topicIndex = new Map();
const writers = {};
const messages = records.map((r) => {
  const type = ros2Type(r.type);
  if (!topicIndex.has(r.topic)) {
    topicIndex.set(r.topic, topics.length);
    topics.push({ name: r.topic, type });
  }
  writers[type] ??= new MessageWriter(parse(fullText(type), { ros2: true }));
  return {
    topic: topicIndex.get(r.topic),
    logTime: BigInt(r.sec) * 1000000000n + BigInt(r.nsec),
    data: writers[type].writeMessage(ros2Fields(r.fields)),
  };
});
for (let i = 1; i < messages.length; i++) {
  if (messages[i].logTime < messages[i - 1].logTime) throw new Error("records out of time order");
}

// The QoS rosbag2 records for a topic: its publisher's offered profile (reliable, keep last; the
// static transform broadcaster's is transient local). History 3 ("unknown") and depth 0 are what
// rosbag2 stores, as it cannot see them.
const qos = (durability) =>
  "- history: 3\n  depth: 0\n  reliability: 1\n" +
  `  durability: ${durability}\n` +
  "  deadline:\n    sec: 9223372036\n    nsec: 854775807\n" +
  "  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n  liveliness: 1\n" +
  "  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n" +
  "  avoid_ros_namespace_conventions: false";
const qosOf = (topic) => qos(topic === "/tf_static" ? 1 : 2);

// ---- MCAP ----

class Sink {
  parts = [];
  size = 0n;
  async write(buffer) {
    this.parts.push(Buffer.from(buffer));
    this.size += BigInt(buffer.byteLength);
  }
  position() {
    return this.size;
  }
  bytes() {
    return Buffer.concat(this.parts);
  }
}

async function writeMcap(file, compressChunk) {
  const sink = new Sink();
  // Default options: chunks of about 1 MiB, a summary with schemas, channels, statistics, chunk
  // and message indexes, and summary offsets.
  const writer = new McapWriter({ writable: sink, compressChunk });
  await writer.start({
    profile: "ros2",
    library: `SonarGrid make_ros2.mjs (@mcap/core ${versionOf("@mcap/core")})`,
  });
  const schemaIds = {};
  const channelIds = [];
  for (const t of topics) {
    schemaIds[t.type] ??= await writer.registerSchema({
      name: t.type,
      encoding: "ros2msg",
      data: new TextEncoder().encode(fullText(t.type)),
    });
    channelIds.push(
      await writer.registerChannel({
        topic: t.name,
        schemaId: schemaIds[t.type],
        messageEncoding: "cdr",
        metadata: new Map([["offered_qos_profiles", qosOf(t.name)]]),
      }),
    );
  }
  const sequence = topics.map(() => 0);
  for (const m of messages) {
    await writer.addMessage({
      channelId: channelIds[m.topic],
      sequence: sequence[m.topic]++,
      logTime: m.logTime,
      publishTime: m.logTime,
      data: m.data,
    });
  }
  await writer.end();
  const bytes = sink.bytes();
  fs.writeFileSync(path.join(here, file), bytes);
  let chunks = 0;
  for (let p = 8; p + 9 <= bytes.length; ) {
    const op = bytes[p];
    if (op === 6) chunks++;
    if (op === 15 || op === 2) break; // data end, footer
    p += 9 + Number(bytes.readBigUInt64LE(p + 1));
  }
  console.log(`${file}: ${bytes.length} bytes, ${chunks} chunks`);
}

await zstd.isLoaded;
await writeMcap("room-zstd.mcap", (data) => ({
  compression: "zstd",
  compressedData: zstd.compress(data, 19),
}));
await writeMcap("room-lz4.mcap", (data) => ({
  compression: "lz4",
  compressedData: new Uint8Array(lz4.compress(data)),
}));

// ---- rosbag2 SQLite storage (sqlite3 plugin, metadata version 5 as in Humble) ----

function writeSqlite(dir) {
  const folder = path.join(here, dir);
  fs.mkdirSync(folder, { recursive: true });
  const file = `${dir}_0.db3`;
  const target = path.join(folder, file);
  fs.rmSync(target, { force: true });
  const db = new Database(target);
  db.pragma("journal_mode = MEMORY");
  db.pragma("synchronous = OFF");
  db.exec(
    "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL," +
      "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL);",
  );
  db.exec(
    "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL," +
      "timestamp INTEGER NOT NULL, data BLOB NOT NULL);",
  );
  db.exec("CREATE INDEX timestamp_idx ON messages (timestamp ASC);");
  const addTopic = db.prepare(
    "INSERT INTO topics (id, name, type, serialization_format, offered_qos_profiles) " +
      "VALUES (?, ?, ?, 'cdr', ?)",
  );
  const addMessage = db.prepare("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)");
  db.transaction(() => {
    topics.forEach((t, i) => addTopic.run(i + 1, t.name, t.type, qosOf(t.name)));
    for (const m of messages) addMessage.run(m.topic + 1, m.logTime, Buffer.from(m.data));
  })();
  db.close();

  const start = messages[0].logTime;
  const duration = messages[messages.length - 1].logTime - start;
  const lines = [
    "rosbag2_bagfile_information:",
    "  version: 5",
    "  storage_identifier: sqlite3",
    "  duration:",
    `    nanoseconds: ${duration}`,
    "  starting_time:",
    `    nanoseconds_since_epoch: ${start}`,
    `  message_count: ${messages.length}`,
    "  topics_with_message_count:",
  ];
  topics.forEach((t, i) => {
    lines.push(
      "    - topic_metadata:",
      `        name: ${t.name}`,
      `        type: ${t.type}`,
      "        serialization_format: cdr",
      `        offered_qos_profiles: ${JSON.stringify(qosOf(t.name))}`,
      `      message_count: ${messages.filter((m) => m.topic === i).length}`,
    );
  });
  lines.push(
    '  compression_format: ""',
    '  compression_mode: ""',
    "  relative_file_paths:",
    `    - ${file}`,
    "  files:",
    `    - path: ${file}`,
    "      starting_time:",
    `        nanoseconds_since_epoch: ${start}`,
    "      duration:",
    `        nanoseconds: ${duration}`,
    `      message_count: ${messages.length}`,
  );
  fs.writeFileSync(path.join(folder, "metadata.yaml"), lines.join("\n") + "\n");
  console.log(`${dir}/${file}: ${fs.statSync(target).size} bytes`);
}

writeSqlite("room-sqlite");

const counts = topics.map((t, i) => `${messages.filter((m) => m.topic === i).length} ${t.name}`);
console.log(`${messages.length} messages: ${counts.join(", ")}`);
console.log(
  `writers: @mcap/core ${versionOf("@mcap/core")}, ` +
    `@foxglove/rosmsg2-serialization ${versionOf("@foxglove/rosmsg2-serialization")}, ` +
    `@foxglove/rosmsg ${versionOf("@foxglove/rosmsg")}, ` +
    `@foxglove/wasm-zstd ${versionOf("@foxglove/wasm-zstd")}, lz4js ${versionOf("lz4js")}, ` +
    `better-sqlite3 ${versionOf("better-sqlite3")} (SQLite ` +
    `${new Database(":memory:").prepare("SELECT sqlite_version() AS v").get().v})`,
);
