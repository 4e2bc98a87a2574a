// Reads an MCAP file with @mcap/core's McapStreamReader (the reader Foxglove
// uses), feeding it the file in pieces as a stream would, and prints one JSON
// object: messages per topic, `complete` (the footer and end magic were read).
// Exits 1 with the reader's error on stderr if it rejects the file. zstd and lz4
// chunks are decompressed with the pure-JS fzstd and lz4js packages.
// Usage: node tests/node/read.mjs FILE
import { streamReader } from "./stream_reader.mjs";
import { openSync, readSync, closeSync } from "node:fs";

const file = process.argv[2];
if (!file) {
  console.error("usage: node read.mjs FILE");
  process.exit(2);
}
const reader = streamReader();
const topics = new Map();
const counts = {};
let records = 0;
const take = () => {
  for (let r; (r = reader.nextRecord()); ) {
    records += 1;
    if (r.type === "Channel") topics.set(r.id, r.topic);
    if (r.type === "Message") {
      const t = topics.get(r.channelId) ?? `#${r.channelId}`;
      counts[t] = (counts[t] ?? 0) + 1;
    }
  }
};
try {
  const fd = openSync(file, "r");
  const buf = Buffer.alloc(1 << 16);
  for (let n; (n = readSync(fd, buf, 0, buf.length, null)) > 0; ) {
    reader.append(new Uint8Array(buf.subarray(0, n)));
    take();
  }
  closeSync(fd);
  const complete = reader.done();
  console.log(JSON.stringify({ messages: counts, records, complete }));
} catch (e) {
  console.error(`@mcap/core: ${e.message}`);
  process.exit(1);
}
