// Checks every JSON-Schema channel of an MCAP file the way Foxglove's (and
// Lichtblick's) JSON Schema reader accepts them, then decodes every message on
// those channels against its schema. Foxglove's reader turns a schema into
// message fields: the root and every nested object need "type": "object"; each
// property must have a "type" among boolean, string, number, integer, object or
// array (of those); a property without one (say a bare {"enum": [...]}) makes it
// throw "Unsupported object field type", and then the channel shows nothing.
// Prints one JSON object {schemas, messages, per_topic}; exits 1 naming the first
// schema or message that breaks a rule.
// Usage: node tests/node/jsonschema.mjs FILE
import { streamReader } from "./stream_reader.mjs";
import { readFileSync } from "node:fs";

const SCALARS = new Set(["boolean", "string", "number", "integer"]);

// The fields a schema object declares, or a thrown error naming the rule broken.
function fieldsOf(schema, path) {
  if (schema.type !== "object") {
    throw new Error(`${path}: expected "type": "object", got ${JSON.stringify(schema.type)}`);
  }
  const fields = {};
  for (const [name, field] of Object.entries(schema.properties ?? {})) {
    const where = `${path}.${name}`;
    if (SCALARS.has(field.type)) {
      if (field.type === "string" && field.contentEncoding !== undefined && field.contentEncoding !== "base64") {
        throw new Error(`${where}: unsupported contentEncoding ${field.contentEncoding}`);
      }
      if (field.enum !== undefined && !field.enum.every((v) => typeof v === jsType(field.type))) {
        throw new Error(`${where}: enum values are not all of type ${field.type}`);
      }
      fields[name] = field;
    } else if (field.type === "object") {
      fields[name] = { ...field, nested: fieldsOf(field, where) };
    } else if (field.type === "array") {
      const items = field.items ?? {};
      if (items.type === "object") fieldsOf(items, `${where}[]`);
      else if (!SCALARS.has(items.type)) {
        throw new Error(`${where}: unsupported array item type ${JSON.stringify(items.type)}`);
      }
      fields[name] = field;
    } else {
      throw new Error(`${where}: unsupported object field type ${JSON.stringify(field.type)}`);
    }
  }
  return fields;
}

function jsType(t) {
  return t === "integer" ? "number" : t;
}

// A decoded message against its fields: each value of the declared JSON type,
// integers whole, strings of an enum among its values, required fields present.
function checkValue(fields, required, value, path) {
  for (const name of required ?? []) {
    if (!(name in value)) throw new Error(`${path}: required field ${name} is missing`);
  }
  for (const [name, v] of Object.entries(value)) {
    const field = fields[name];
    const where = `${path}.${name}`;
    if (!field) throw new Error(`${where}: not in the schema`);
    if (field.type === "object") {
      checkValue(field.nested, field.required, v, where);
    } else if (field.type === "array") {
      if (!Array.isArray(v)) throw new Error(`${where}: not an array`);
    } else {
      if (typeof v !== jsType(field.type)) {
        throw new Error(`${where}: ${JSON.stringify(v)} is not of type ${field.type}`);
      }
      if (field.type === "integer" && !Number.isInteger(v)) throw new Error(`${where}: ${v} is not an integer`);
      if (field.type === "number" && !Number.isFinite(v)) throw new Error(`${where}: ${v} is not finite`);
      if (field.enum && !field.enum.includes(v)) throw new Error(`${where}: ${v} is not one of ${field.enum}`);
    }
  }
}

const file = process.argv[2];
if (!file) {
  console.error("usage: node jsonschema.mjs FILE");
  process.exit(2);
}
const reader = streamReader();
const schemas = new Map(); // schema id -> {fields, required, name}
const channels = new Map(); // channel id -> {topic, schema}
const perTopic = {};
let messages = 0;
try {
  reader.append(new Uint8Array(readFileSync(file)));
  const text = new TextDecoder();
  for (let r; (r = reader.nextRecord()); ) {
    if (r.type === "Schema" && r.encoding === "jsonschema") {
      const root = JSON.parse(text.decode(r.data));
      schemas.set(r.id, { fields: fieldsOf(root, r.name), required: root.required, name: r.name });
    } else if (r.type === "Channel") {
      channels.set(r.id, { topic: r.topic, schema: schemas.get(r.schemaId), encoding: r.messageEncoding });
    } else if (r.type === "Message") {
      const ch = channels.get(r.channelId);
      if (!ch?.schema) continue;
      if (ch.encoding !== "json") throw new Error(`${ch.topic}: a jsonschema channel encoded as ${ch.encoding}`);
      const value = JSON.parse(text.decode(r.data));
      checkValue(ch.schema.fields, ch.schema.required, value, `${ch.topic}#${perTopic[ch.topic] ?? 0}`);
      perTopic[ch.topic] = (perTopic[ch.topic] ?? 0) + 1;
      messages += 1;
    }
  }
  if (!reader.done()) throw new Error("the file ends before its footer");
  console.log(JSON.stringify({ schemas: schemas.size, messages, per_topic: perTopic }));
} catch (e) {
  console.error(`${file}: ${e.message}`);
  process.exit(1);
}
