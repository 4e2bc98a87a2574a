// Decodes a carom log's /scene frames as Foxglove does — @mcap/core reads the
// file, @foxglove/rosmsg parses the stored ros2msg schema, @foxglove/rosmsg2-
// serialization decodes the CDR — and checks them against /snapshot, decoded
// the same way: at every snapshot time a frame with one cylinder per disc at the
// disc's position (exactly), sized to its diameter, coloured by species, and the
// box outline. Prints one JSON object: frames, snapshots, frames checked against
// a snapshot, discs checked, the species colours seen. Exits 1 with the first
// mismatch on stderr.
// Usage: node tests/node/scene.mjs FILE
import { streamReader } from "./stream_reader.mjs";
import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";
import { readFileSync } from "node:fs";

const file = process.argv[2];
if (!file) {
  console.error("usage: node scene.mjs FILE");
  process.exit(2);
}
const fail = (why) => {
  console.error(`scene.mjs: ${why}`);
  process.exit(1);
};

const reader = streamReader();
reader.append(new Uint8Array(readFileSync(file)));

const schemas = new Map();
const decoders = new Map(); // channel id -> [topic, MessageReader]
const frames = new Map(); // log time (ns, string) -> decoded SceneUpdate
const snapshots = [];
let sceneSchema = null;
for (let r; (r = reader.nextRecord()); ) {
  if (r.type === "Schema") schemas.set(r.id, r);
  if (r.type === "Channel" && (r.topic === "/scene" || r.topic === "/snapshot")) {
    const s = schemas.get(r.schemaId);
    if (r.topic === "/scene") sceneSchema = [s.name, s.encoding, r.messageEncoding];
    const text = new TextDecoder().decode(s.data);
    decoders.set(r.id, [r.topic, new MessageReader(parse(text, { ros2: true }))]);
  }
  if (r.type === "Message" && decoders.has(r.channelId)) {
    const [topic, dec] = decoders.get(r.channelId);
    const m = dec.readMessage(r.data);
    if (topic === "/scene") frames.set(r.logTime.toString(), m);
    else snapshots.push([r.logTime.toString(), m]);
  }
}
if (!reader.done()) fail("the file does not end with the MCAP footer");
if (!sceneSchema) fail("no /scene channel");

const colours = {};
let checked = 0;
let discs = 0;
for (const [t, snap] of snapshots) {
  const f = frames.get(t);
  if (!f) continue;
  checked += 1;
  if (f.deletions.length !== 0 || f.entities.length !== 1) fail(`t=${t}: not one entity`);
  const e = f.entities[0];
  if (e.frame_id !== "box" || e.id !== "discs") fail(`t=${t}: frame ${e.frame_id}, id ${e.id}`);
  const ns = BigInt(e.timestamp.sec) * 1000000000n + BigInt(e.timestamp.nanosec);
  if (ns.toString() !== t) fail(`t=${t}: entity timestamp ${ns}`);
  const time = e.metadata.find((kv) => kv.key === "time");
  if (!time || Number(time.value) !== snap.time) {
    fail(`t=${t}: metadata time ${time?.value}, snapshot ${snap.time}`);
  }
  const n = snap.x.length;
  if (e.cylinders.length !== n) fail(`t=${t}: ${e.cylinders.length} cylinders, ${n} discs`);
  for (let i = 0; i < n; i++) {
    const c = e.cylinders[i];
    const s = snap.species[i];
    const d = 2 * snap.species_radius[s];
    const p = c.pose.position;
    const o = c.pose.orientation;
    if (p.x !== snap.x[i] || p.y !== snap.y[i] || p.z !== 0) {
      fail(`t=${t} disc ${i}: cylinder at (${p.x}, ${p.y}, ${p.z}), disc at (${snap.x[i]}, ${snap.y[i]})`);
    }
    if (o.x !== 0 || o.y !== 0 || o.z !== 0 || o.w !== 1) fail(`t=${t} disc ${i}: rotated`);
    if (c.size.x !== d || c.size.y !== d || !(c.size.z > 0 && c.size.z < d)) {
      fail(`t=${t} disc ${i}: size ${JSON.stringify(c.size)}, diameter ${d}`);
    }
    if (c.bottom_scale !== 1 || c.top_scale !== 1) fail(`t=${t} disc ${i}: not a cylinder`);
    const rgba = [c.color.r, c.color.g, c.color.b, c.color.a];
    const seen = colours[s];
    if (seen === undefined) colours[s] = rgba;
    else if (seen.join() !== rgba.join()) fail(`t=${t} disc ${i}: colour ${rgba}, species ${s} had ${seen}`);
    discs += 1;
  }
  if (e.lines.length !== 1) fail(`t=${t}: ${e.lines.length} line primitives`);
  const box = e.lines[0];
  const corners = box.points.map((q) => [q.x, q.y, q.z]);
  const want = [[0, 0, 0], [snap.box_x, 0, 0], [snap.box_x, snap.box_y, 0], [0, snap.box_y, 0]];
  if (box.type !== 1 || JSON.stringify(corners) !== JSON.stringify(want)) {
    fail(`t=${t}: box outline type ${box.type} through ${JSON.stringify(corners)}, box ${snap.box_x} x ${snap.box_y}`);
  }
  for (const k of ["arrows", "cubes", "spheres", "triangles", "texts", "models"]) {
    if (e[k].length !== 0) fail(`t=${t}: ${k} present`);
  }
}
console.log(
  JSON.stringify({
    schema: sceneSchema,
    frames: frames.size,
    snapshots: snapshots.length,
    checked,
    discs,
    colours,
  }),
);
