// A Foxglove WebSocket client (Foxglove's own @foxglove/ws-protocol over `ws`)
// watching a running `carom run --live` (tests/integration/live.rs).
//
//   node live.mjs URL watch N  subscribe to every channel, decode /scene
//                              (foxglove.SceneUpdate, protobuf from the advertised
//                              FileDescriptorSet), /thermo and /progress (JSON,
//                              each property checked against its JSON Schema's
//                              type) until N frames; disconnect; reconnect, take
//                              frames until the server closes the connection at
//                              the end of the run. Prints JSON: the frames (exact
//                              time from the metadata `time`, positions), the
//                              records, what the reconnected client got.
//   node live.mjs URL stall    subscribe to every channel and never read again
//                              (the socket is paused), until the server closes it.
import wsProtocol from "@foxglove/ws-protocol";
import WebSocket from "ws";
import protobuf from "protobufjs";
import descriptor from "protobufjs/ext/descriptor/index.js";

const { FoxgloveClient } = wsProtocol;
const SUBPROTOCOL = "foxglove.sdk.v1";
const [url, mode, wanted] = process.argv.slice(2);
const fail = (msg) => {
  process.stderr.write(`live.mjs: ${msg}\n`);
  process.exit(1);
};
const TYPES = { number: "number", integer: "number", string: "string", boolean: "boolean" };

// Check a JSON record against the rules Foxglove's JSON Schema reader follows:
// every property of the schema typed, every property of the record in it.
function checkJson(topic, schema, record) {
  for (const [k, v] of Object.entries(record)) {
    const p = schema.properties[k];
    if (!p || !p.type) fail(`${topic}: property ${k} has no type in the schema`);
    const finite = typeof v === "number" || ["NaN", "Infinity", "-Infinity"].includes(v);
    const ok = p.type === "number" ? finite : typeof v === TYPES[p.type];
    if (!ok || (p.type === "integer" && !Number.isInteger(v))) {
      fail(`${topic}: ${k} = ${JSON.stringify(v)} is not of type ${p.type}`);
    }
  }
  for (const k of schema.required ?? []) {
    if (!(k in record)) fail(`${topic}: required ${k} missing`);
  }
}

// A decoder per advertised channel.
function decoderOf(channel) {
  if (channel.encoding === "json") {
    const schema = JSON.parse(channel.schema);
    for (const [k, p] of Object.entries(schema.properties)) {
      if (!p.type) fail(`${channel.topic}: property ${k} has no type`);
    }
    return (view) => {
      const record = JSON.parse(new TextDecoder().decode(view));
      checkJson(channel.topic, schema, record);
      return record;
    };
  }
  if (channel.encoding === "protobuf") {
    const set = descriptor.FileDescriptorSet.decode(Buffer.from(channel.schema, "base64"));
    const type = protobuf.Root.fromDescriptor(set).lookupType(channel.schemaName);
    return (view) =>
      type.toObject(type.decode(new Uint8Array(view.buffer, view.byteOffset, view.byteLength)), {
        longs: Number,
        defaults: true,
      });
  }
  fail(`${channel.topic}: unknown encoding ${channel.encoding}`);
}

// What a decoded SceneUpdate says: the exact time and the discs.
function frameOf(update) {
  if (update.entities.length !== 1) fail(`a frame with ${update.entities.length} entities`);
  const e = update.entities[0];
  if (e.frameId !== "box" || e.id !== "discs") fail(`entity ${e.frameId}/${e.id}`);
  const time = e.metadata.find((kv) => kv.key === "time");
  if (!time) fail("a frame without its time");
  return {
    time: Number(time.value),
    stamp: [e.timestamp.sec, e.timestamp.nsec],
    x: e.cylinders.map((c) => c.pose.position.x),
    y: e.cylinders.map((c) => c.pose.position.y),
    d: e.cylinders.map((c) => c.size.x),
    outline: e.lines[0].points.map((p) => [p.x, p.y]),
  };
}

// What the server advertised: topic → encoding and schema name.
const advertised = {};

// Connect, subscribe to every channel; `onMessage(topic, value)` for each message.
function connect(onMessage, onClose) {
  // Foxglove's SDK (0.30) serves the protocol of this client under its new name
  // `foxglove.sdk.v1` (inline schemas, the messages of `foxglove.websocket.v1`).
  const ws = new WebSocket(url, [SUBPROTOCOL]);
  const client = new FoxgloveClient({ ws });
  const subs = new Map();
  client.on("error", (e) => fail(`client error: ${e}`));
  client.on("advertise", (channels) => {
    for (const ch of channels) {
      advertised[ch.topic] = { encoding: ch.encoding, schemaName: ch.schemaName };
      const id = client.subscribe(ch.id);
      subs.set(id, { topic: ch.topic, decode: mode === "stall" ? null : decoderOf(ch) });
    }
    if (mode === "stall") {
      // Never read again: the server's queue for this client fills.
      ws._socket.pause();
      process.stderr.write("live.mjs: subscribed, not reading\n");
    }
  });
  client.on("message", ({ subscriptionId, timestamp, data }) => {
    const s = subs.get(subscriptionId);
    if (s) onMessage(s.topic, s.decode(data), timestamp);
  });
  client.on("close", () => onClose());
  return client;
}

if (mode === "stall") {
  connect(() => {}, () => process.exit(0));
} else {
  const want = Number(wanted);
  const out = { frames: [], thermo: [], progress: [], again: { frames: [], thermo: 0 } };
  let stampsOk = true;
  const first = connect(
    (topic, v, timestamp) => {
      if (topic === "/scene") {
        const f = frameOf(v);
        // The message's log time is the simulated time in ns, as in the log.
        stampsOk &&= Number(timestamp) === Math.round(f.time * 1e9) || f.time * 1e9 > 2 ** 53;
        out.frames.push(f);
        if (out.frames.length === want) {
          first.close();
          again();
        }
      } else if (topic === "/thermo") {
        if (out.frames.length < want) out.thermo.push(v);
      } else if (topic === "/progress") {
        out.progress.push(v);
      }
    },
    () => {},
  );
  function again() {
    connect(
      (topic, v) => {
        if (topic === "/scene") out.again.frames.push(frameOf(v));
        if (topic === "/thermo") out.again.thermo += 1;
      },
      () => {
        out.stamps_ok = stampsOk;
        out.channels = advertised;
        process.stdout.write(JSON.stringify(out), () => process.exit(0));
      },
    );
  }
}
