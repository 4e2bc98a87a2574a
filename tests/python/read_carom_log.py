#!/usr/bin/env python3
"""Read a carom MCAP log with the independent Python readers (`mcap`,
`mcap-ros2-support`) and print what was decoded as one JSON object.

Usage: read_carom_log.py FILE.mcap [--streaming] [--fields]

Without --streaming the file is read with `mcap.reader.make_reader` (the
summary/index path for complete files); with it, with `NonSeekingReader`, which
also reads files cut short by a crash (then "error" says where it stopped).

Always printed: message counts per topic, each topic's schema (name, encoding,
message encoding), the number of collisions decoded, and for a complete file its
metadata records and the MCAP statistics. With --fields, also "messages": every
message in file order with its envelope (topic, sequence, log and publish time)
and EVERY field the schema defines (generic: the decoded object's fields, nested
messages as objects, so a field added to a schema shows up here unasked), and
"schemas": each topic's schema text. Floats are printed as the 16 hex digits of
their IEEE-754 bits (exact, and distinct from integers); uint8[] as integers.
"""

import json
import struct
import sys

from mcap.reader import NonSeekingReader, make_reader
from mcap_ros2.decoder import DecoderFactory


def f64_bits(values):
    """Hex bit patterns of a list of floats."""
    n = len(values)
    words = struct.unpack("<%dQ" % n, struct.pack("<%dd" % n, *values))
    return ["%016x" % w for w in words]


def plain(v):
    """A decoded value as JSON: floats as bit patterns, messages as objects."""
    if isinstance(v, bool) or isinstance(v, int) or isinstance(v, str):
        return v
    if isinstance(v, float):
        return f64_bits([v])[0]
    if isinstance(v, (bytes, bytearray)):
        return list(v)
    if isinstance(v, list):
        if v and all(type(x) is float for x in v):
            return f64_bits(v)
        return [plain(x) for x in v]
    if isinstance(v, dict):
        return {k: plain(x) for k, x in v.items()}
    if hasattr(v, "__slots__"):
        return {k: plain(getattr(v, k)) for k in v.__slots__}
    raise TypeError("cannot print a %s" % type(v).__name__)


def main():
    path = sys.argv[1]
    streaming = "--streaming" in sys.argv[2:]
    fields = "--fields" in sys.argv[2:]
    out = {
        "mode": "streaming" if streaming else "seeking",
        "error": None,
        "counts": {},
        "channels": {},
        "metadata": {},
        "collisions": 0,
    }
    if fields:
        out["messages"] = []
        out["schemas"] = {}
    ros2 = DecoderFactory()
    with open(path, "rb") as f:
        reader = (
            NonSeekingReader(f, validate_crcs=True)
            if streaming
            else make_reader(f, validate_crcs=True)
        )
        try:
            for schema, channel, message in reader.iter_messages(log_time_order=False):
                topic = channel.topic
                out["counts"][topic] = out["counts"].get(topic, 0) + 1
                out["channels"][topic] = [
                    schema.name if schema else None,
                    schema.encoding if schema else None,
                    channel.message_encoding,
                ]
                if channel.message_encoding == "json":
                    msg = json.loads(message.data)
                else:
                    msg = ros2.decoder_for(channel.message_encoding, schema)(message.data)
                if topic == "/collisions":
                    out["collisions"] += len(msg.time)
                if fields:
                    out["schemas"][topic] = schema.data.decode() if schema else None
                    out["messages"].append(
                        {
                            "topic": topic,
                            "sequence": message.sequence,
                            "log_time": message.log_time,
                            "publish_time": message.publish_time,
                            "fields": plain(msg),
                        }
                    )
        except Exception as e:  # a truncated file ends in an exception
            out["error"] = "%s: %s" % (type(e).__name__, e)
    if not streaming and out["error"] is None:
        with open(path, "rb") as f:
            reader = make_reader(f)
            for m in reader.iter_metadata():
                out["metadata"][m.name] = dict(m.metadata)
            summary = reader.get_summary()
            if summary is not None and summary.statistics is not None:
                stats = summary.statistics.channel_message_counts
                out["statistics"] = {
                    summary.channels[cid].topic: n for cid, n in stats.items()
                }
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
