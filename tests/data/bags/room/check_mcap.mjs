// SPDX-License-Identifier: BSD-3-Clause
// Helper of check_roundtrip.py: reads an MCAP file with @mcap/core's McapIndexedReader (chunk
// CRCs checked, zstd and LZ4-frame chunks decompressed) and prints one JSON line per schema,
// channel and message, the message data as base64 CDR bytes for check_roundtrip.py to decode
// on its own. The summary's statistics come last.
//
//   node tests/data/bags/room/check_mcap.mjs NODE_MODULES_DIR FILE.mcap

import fs from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";

const [modules, file] = process.argv.slice(2);
const require = createRequire(path.join(path.resolve(modules), "noop.js"));
const { McapIndexedReader } = require("@mcap/core");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("lz4js");

await zstd.isLoaded;
const bytes = fs.readFileSync(file);
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
};
const reader = await McapIndexedReader.Initialize({
  readable,
  decompressHandlers: {
    zstd: (data, size) => zstd.decompress(data, Number(size)),
    lz4: (data, size) => new Uint8Array(lz4.decompress(data, Number(size))),
  },
});
const out = [];
const text = (d) => Buffer.from(d).toString("utf8");
for (const s of reader.schemasById.values()) {
  out.push({ schema: s.id, name: s.name, encoding: s.encoding, data: text(s.data) });
}
for (const c of reader.channelsById.values()) {
  out.push({
    channel: c.id,
    topic: c.topic,
    schemaId: c.schemaId,
    messageEncoding: c.messageEncoding,
    metadata: Object.fromEntries(c.metadata),
  });
}
out.push({
  header: { profile: reader.header.profile, library: reader.header.library },
  chunks: reader.chunkIndexes.map((c) => c.compression),
});
for await (const m of reader.readMessages({ validateCrcs: true })) {
  out.push({
    channelId: m.channelId,
    sequence: m.sequence,
    logTime: String(m.logTime),
    publishTime: String(m.publishTime),
    data: Buffer.from(m.data).toString("base64"),
  });
}
const st = reader.statistics;
out.push({
  statistics: {
    messageCount: String(st.messageCount),
    channelMessageCounts: Object.fromEntries([...st.channelMessageCounts].map(([k, v]) => [k, String(v)])),
    messageStartTime: String(st.messageStartTime),
    messageEndTime: String(st.messageEndTime),
  },
});
process.stdout.write(out.map((o) => JSON.stringify(o)).join("\n") + "\n");
