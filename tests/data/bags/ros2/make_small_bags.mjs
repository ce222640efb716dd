// SPDX-License-Identifier: BSD-3-Clause
// Writes the small ROS 2 bags of tests/core/tst_rosbag2.cpp with real writers: MCAP files with
// @mcap/core's McapWriter, messages CDR-serialised by @foxglove/rosmsg2-serialization's
// MessageWriter, and rosbag2 SQLite storages (.db3) written by SQLite itself (better-sqlite3)
// with the tables rosbag2 creates. The exact package versions are in package.json here.
//
//   NPM_DIR=$(mktemp -d) && cp tests/data/bags/ros2/package.json "$NPM_DIR"/
//   npm install --prefix "$NPM_DIR"
//   node tests/data/bags/ros2/make_small_bags.mjs "$NPM_DIR"/node_modules
//
// The output is deterministic: running it again gives the same bytes. It prints each file's
// layout (chunks and the messages in them), which the tests' comments quote.

import fs from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const modules = path.resolve(process.argv[2] ?? path.join(here, "node_modules"));
const require = createRequire(path.join(modules, "noop.js"));
const { McapWriter } = require("@mcap/core");
const { MessageWriter } = require("@foxglove/rosmsg2-serialization");
const { parse } = require("@foxglove/rosmsg");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("lz4js");
const Database = require("better-sqlite3");

// ---- message definitions: the fields of the public ROS 2 .msg files (comments left out) ----

const SEP = "=".repeat(80);
const defs = {
  "builtin_interfaces/msg/Time": "int32 sec\nuint32 nanosec\n",
  "std_msgs/msg/Header": "builtin_interfaces/Time stamp\nstring frame_id\n",
  "sensor_msgs/msg/Range":
    "std_msgs/Header header\n" +
    "uint8 ULTRASOUND=0\nuint8 INFRARED=1\n" +
    "uint8 radiation_type\nfloat32 field_of_view\nfloat32 min_range\nfloat32 max_range\n" +
    "float32 range\n",
  "geometry_msgs/msg/Point": "float64 x\nfloat64 y\nfloat64 z\n",
  "geometry_msgs/msg/Quaternion": "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n",
  "geometry_msgs/msg/Pose": "Point position\nQuaternion orientation\n",
  "geometry_msgs/msg/PoseWithCovariance": "Pose pose\nfloat64[36] covariance\n",
  "geometry_msgs/msg/Vector3": "float64 x\nfloat64 y\nfloat64 z\n",
  "geometry_msgs/msg/Twist": "Vector3  linear\nVector3  angular\n",
  "geometry_msgs/msg/TwistWithCovariance": "Twist twist\nfloat64[36] covariance\n",
  "nav_msgs/msg/Odometry":
    "std_msgs/Header header\nstring child_frame_id\n" +
    "geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n",
};
// rosbag2's "ros2msg" complete definition (its docs/message_definition_encoding.md): the type's
// text, then each dependency after a line of 80 '=' and "MSG: pkg/Type", the name as the fields
// spell it (rosbag2's MCAP files read "MSG: std_msgs/Header").
const deps = {
  "sensor_msgs/msg/Range": ["std_msgs/msg/Header", "builtin_interfaces/msg/Time"],
  "nav_msgs/msg/Odometry": [
    "std_msgs/msg/Header",
    "builtin_interfaces/msg/Time",
    "geometry_msgs/msg/PoseWithCovariance",
    "geometry_msgs/msg/Pose",
    "geometry_msgs/msg/Point",
    "geometry_msgs/msg/Quaternion",
    "geometry_msgs/msg/TwistWithCovariance",
    "geometry_msgs/msg/Twist",
    "geometry_msgs/msg/Vector3",
  ],
};
function fullText(type) {
  const msgName = (d) => d.replace("/msg/", "/");
  return [defs[type], ...deps[type].map((d) => `${SEP}\nMSG: ${msgName(d)}\n${defs[d]}`)].join("");
}
const writers = {};
for (const type of Object.keys(deps)) {
  writers[type] = new MessageWriter(parse(fullText(type), { ros2: true }));
}

// ---- the messages: three sonars' ranges and odometry over 0.2 s ----

const T0 = 1700000000n; // seconds of the first stamp
const stamp = (ms) => ({ sec: Number(T0), nanosec: ms * 1000000 });
const ns = (ms) => T0 * 1000000000n + BigInt(ms) * 1000000n;
const range = (frame, ms, r) => ({
  header: { stamp: stamp(ms), frame_id: frame },
  radiation_type: 0,
  field_of_view: 0.4363,
  min_range: 0.1,
  max_range: 5.0,
  range: r,
});
const cov = (d) => Array.from({ length: 36 }, (_, i) => (i % 7 === 0 ? d : 0));
const odom = (ms, x, yaw) => ({
  header: { stamp: stamp(ms), frame_id: "odom" },
  child_frame_id: "base_link",
  pose: {
    pose: {
      position: { x, y: 0.5, z: 0 },
      orientation: { x: 0, y: 0, z: Math.sin(yaw / 2), w: Math.cos(yaw / 2) },
    },
    covariance: cov(0.01),
  },
  twist: { twist: { linear: { x: 0.25, y: 0, z: 0 }, angular: { x: 0, y: 0, z: 0.1 } }, covariance: cov(0.02) },
});

const topics = [
  { name: "/sonar/front", type: "sensor_msgs/msg/Range" },
  { name: "/odom", type: "nav_msgs/msg/Odometry" },
  { name: "/sonar/rear", type: "sensor_msgs/msg/Range" },
];
// [topic index, log time in ms after T0, message], in time order.
const messages = [
  [0, 0, range("sonar_front", 0, 1.25)],
  [1, 25, odom(25, 1.0, 0.0)],
  [2, 50, range("sonar_rear", 50, 2.5)],
  [0, 100, range("sonar_front", 100, 1.5)],
  [2, 150, range("sonar_rear", 150, 3.0)],
  [1, 175, odom(175, 1.05, 0.02)],
  [0, 200, range("sonar_front", 200, 0.75)],
].map(([t, ms, m]) => ({ topic: t, logTime: ns(ms), data: writers[topics[t].type].writeMessage(m) }));

// rosbag2's default offered QoS of a publisher (reliable, volatile, keep last), as it records it.
const qos =
  "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n  deadline:\n    sec: 9223372036\n" +
  "    nsec: 854775807\n  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n  liveliness: 1\n" +
  "  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n" +
  "  avoid_ros_namespace_conventions: false";

// ---- MCAP ----

class Sink {
  chunks = [];
  size = 0n;
  async write(buffer) {
    this.chunks.push(Buffer.from(buffer));
    this.size += BigInt(buffer.byteLength);
  }
  position() {
    return this.size;
  }
  bytes() {
    return Buffer.concat(this.chunks);
  }
}

async function writeMcap(file, options) {
  const sink = new Sink();
  const writer = new McapWriter({ writable: sink, ...options });
  await writer.start({ profile: "ros2", library: "SonarGrid make_small_bags.mjs (@mcap/core 2.2.2)" });
  const schemaIds = {};
  for (const type of Object.keys(deps)) {
    schemaIds[type] = await writer.registerSchema({
      name: type,
      encoding: "ros2msg",
      data: new TextEncoder().encode(fullText(type)),
    });
  }
  const channelIds = [];
  for (const t of topics) {
    channelIds.push(
      await writer.registerChannel({
        topic: t.name,
        schemaId: schemaIds[t.type],
        messageEncoding: "cdr",
        metadata: new Map([["offered_qos_profiles", qos]]),
      }),
    );
  }
  let sequence = 0;
  for (const m of messages) {
    await writer.addMessage({
      channelId: channelIds[m.topic],
      sequence: sequence++,
      logTime: m.logTime,
      publishTime: m.logTime,
      data: m.data,
    });
  }
  await writer.addMetadata({ name: "sonargrid", metadata: new Map([["purpose", "test fixture"]]) });
  await writer.end();
  const bytes = sink.bytes();
  fs.writeFileSync(path.join(here, file), bytes);
  console.log(`${file}: ${bytes.length} bytes`);
  printLayout(bytes);
}

// Prints the chunk and message records at the top level of an MCAP file (offsets in bytes).
function printLayout(b) {
  let p = 8;
  const names = { 1: "Header", 2: "Footer", 3: "Schema", 4: "Channel", 5: "Message", 6: "Chunk" };
  while (p + 9 <= b.length) {
    const op = b[p];
    const len = Number(b.readBigUInt64LE(p + 1));
    if (op === 6) {
      const compressionLen = b.readUInt32LE(p + 9 + 28);
      const compression = b.toString("latin1", p + 9 + 32, p + 9 + 32 + compressionLen);
      console.log(`  Chunk at ${p}: ${len + 9} bytes, compression '${compression}'`);
    } else if (op === 5) {
      console.log(`  Message at ${p}: channel ${b.readUInt16LE(p + 9)}, ${len - 22} data bytes`);
    } else if (op === 15 || op === 2) {
      break;
    }
    p += 9 + len;
  }
}

await zstd.isLoaded;
const zstdChunk = (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 19) });
const lz4Chunk = (data) => ({ compression: "lz4", compressedData: new Uint8Array(lz4.compress(data)) });
// chunkSize 0: every chunk ends after its first message (McapWriter closes a chunk once it is
// larger than chunkSize), so each message has a chunk of its own.
await writeMcap("small_zstd.mcap", { chunkSize: 0, compressChunk: zstdChunk });
await writeMcap("small_lz4.mcap", { compressChunk: lz4Chunk }); // one chunk
await writeMcap("small_none.mcap", { chunkSize: 0 });
// No summary section: no statistics, no index of any kind, schemas and channels only in the data
// section; McapWriter then writes summary_start 0 in the footer.
await writeMcap("small_nosummary.mcap", {
  chunkSize: 0,
  compressChunk: zstdChunk,
  useStatistics: false,
  useSummaryOffsets: false,
  repeatSchemas: false,
  repeatChannels: false,
  useAttachmentIndex: false,
  useMetadataIndex: false,
  useMessageIndex: false,
  useChunkIndex: false,
});
// Messages straight in the data section (no chunks), with a summary of schemas, channels and
// statistics.
await writeMcap("small_unchunked.mcap", { useChunks: false });

// ---- rosbag2 SQLite storage ----

const startNs = messages[0].logTime;
const endNs = messages[messages.length - 1].logTime;
function metadataYaml(version, file, extraTopic, extraTop) {
  const lines = [
    "rosbag2_bagfile_information:",
    `  version: ${version}`,
    "  storage_identifier: sqlite3",
    "  duration:",
    `    nanoseconds: ${endNs - startNs}`,
    "  starting_time:",
    `    nanoseconds_since_epoch: ${startNs}`,
    `  message_count: ${messages.length}`,
    "  topics_with_message_count:",
  ];
  topics.forEach((t, i) => {
    lines.push(
      "    - topic_metadata:",
      `        name: ${t.name}`,
      `        type: ${t.type}`,
      "        serialization_format: cdr",
      `        offered_qos_profiles: ${JSON.stringify(qos)}`,
      ...extraTopic.map((l) => `        ${l}`),
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
    `        nanoseconds_since_epoch: ${startNs}`,
    "      duration:",
    `        nanoseconds: ${endNs - startNs}`,
    `      message_count: ${messages.length}`,
    ...extraTop,
  );
  return lines.join("\n") + "\n";
}

// `jazzy`: the tables of rosbag2 in ROS 2 Jazzy (schema version 4): schema, metadata,
// message_definitions, and topics with type_description_hash. Otherwise the two tables every
// rosbag2 release has, and a metadata.yaml of version 5 (Galactic, Humble). Pages of 512 bytes
// keep the files small.
function writeDb3(dir, jazzy) {
  const folder = path.join(here, dir);
  fs.mkdirSync(folder, { recursive: true });
  const file = `${dir}_0.db3`;
  const target = path.join(folder, file);
  fs.rmSync(target, { force: true });
  const db = new Database(target);
  db.pragma("page_size = 512");
  db.pragma("journal_mode = DELETE");
  const yaml = jazzy
    ? metadataYaml(9, file, ['type_description_hash: ""'], ["  custom_data: ~", "  ros_distro: jazzy"])
    : metadataYaml(5, file, [], []);
  if (jazzy) {
    db.exec("CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL);");
    db.exec(
      "CREATE TABLE metadata(id INTEGER PRIMARY KEY,metadata_version INTEGER NOT NULL," +
        "metadata TEXT NOT NULL);",
    );
    db.prepare("INSERT INTO schema VALUES (4, 'jazzy')").run();
    db.prepare("INSERT INTO metadata(metadata_version, metadata) VALUES (9, ?)").run(yaml);
  }
  db.exec(
    "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL," +
      "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL" +
      (jazzy ? ",type_description_hash TEXT NOT NULL" : "") +
      ");",
  );
  db.exec(
    "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL," +
      "timestamp INTEGER NOT NULL, data BLOB NOT NULL);",
  );
  db.exec("CREATE INDEX timestamp_idx ON messages (timestamp ASC);");
  if (jazzy) {
    db.exec(
      "CREATE TABLE message_definitions(id INTEGER PRIMARY KEY,topic_type TEXT NOT NULL," +
        "encoding TEXT NOT NULL,encoded_message_definition TEXT NOT NULL," +
        "type_description_hash TEXT NOT NULL);",
    );
    for (const type of Object.keys(deps)) {
      db.prepare(
        "INSERT INTO message_definitions(topic_type, encoding, encoded_message_definition, " +
          "type_description_hash) VALUES (?, 'ros2msg', ?, '')",
      ).run(type, fullText(type));
    }
  }
  // The hash is left empty: computing RIHS01 type hashes is beyond this script.
  const addTopic = db.prepare(
    "INSERT INTO topics(id, name, type, serialization_format, offered_qos_profiles" +
      (jazzy ? ", type_description_hash) VALUES (?, ?, ?, 'cdr', ?, '')" : ") VALUES (?, ?, ?, 'cdr', ?)"),
  );
  topics.forEach((t, i) => addTopic.run(i + 1, t.name, t.type, qos));
  const addMessage = db.prepare("INSERT INTO messages(topic_id, timestamp, data) VALUES (?, ?, ?)");
  for (const m of messages) addMessage.run(BigInt(m.topic + 1), m.logTime, Buffer.from(m.data));
  db.exec("VACUUM");
  db.close();
  fs.writeFileSync(path.join(folder, "metadata.yaml"), yaml);
  console.log(`${dir}/${file}: ${fs.statSync(target).size} bytes`);
}

writeDb3("small_sqlite", false);
writeDb3("small_jazzy", true);

for (const m of messages) {
  console.log(`message on ${topics[m.topic].name} at ${m.logTime}: ${m.data.length} bytes`);
}
