#!/usr/bin/env python3
"""Read a carom MCAP log with the independent Python readers (`mcap`,
`mcap-ros2-support`) and print what was decoded as one JSON object.

Usage: read_carom_log.py FILE.mcap [--streaming]

Without --streaming the file is read with `mcap.reader.make_reader` (the
summary/index path for complete files); with it, with `NonSeekingReader`, which
also reads files cut short by a crash (then "error" says where it stopped).

Exact comparison with the Rust side: for every decoded array field the output
holds a CRC-32 of the little-endian packed values, concatenated over all messages
of the topic in file order.
"""

import json
import struct
import sys
import zlib

from mcap.reader import NonSeekingReader, make_reader
from mcap_ros2.decoder import DecoderFactory

PACK = {
    "float64": "d",
    "uint64": "Q",
    "uint32": "I",
    "uint16": "H",
    "uint8": "B",
}

BATCH_FIELDS = [
    ("time", "d"), ("kind", "B"), ("i", "I"), ("j", "I"), ("nx", "d"), ("ny", "d"),
    ("vix_before", "d"), ("viy_before", "d"), ("vjx_before", "d"), ("vjy_before", "d"),
    ("vix_after", "d"), ("viy_after", "d"), ("vjx_after", "d"), ("vjy_after", "d"),
    ("energy_lost", "d"), ("virial", "d"),
]
# The compact record (log format 2; tests/python/replay_compact_log.py replays it).
COMPACT_FIELDS = [("time", "d"), ("i", "I"), ("j", "I"), ("dpx", "d"), ("dpy", "d")]
SNAPSHOT_FIELDS = [("species", "H"), ("x", "d"), ("y", "d"), ("vx", "d"), ("vy", "d")]


def packed(values, code):
    if isinstance(values, (bytes, bytearray)):
        return bytes(values)
    return struct.pack("<%d%s" % (len(values), code), *values)


class Crc:
    def __init__(self, fields):
        self.fields = fields
        self.crc = {name: 0 for name, _ in fields}

    def add(self, msg):
        for name, code in self.fields:
            self.crc[name] = zlib.crc32(packed(getattr(msg, name), code), self.crc[name])


def main():
    path = sys.argv[1]
    streaming = "--streaming" in sys.argv[2:]
    out = {
        "mode": "streaming" if streaming else "seeking",
        "error": None,
        "counts": {},
        "channels": {},
        "metadata": {},
        "batches": [],
        "snapshots": [],
        "thermo": [],
        "checkpoints": [],
    }
    ros2 = DecoderFactory()
    batch_crc = Crc(BATCH_FIELDS)
    compact_crc = Crc(COMPACT_FIELDS)
    snap_crc = Crc(SNAPSHOT_FIELDS)
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
                    rec = json.loads(message.data)
                    out["thermo"].append(rec)
                    continue
                decode = ros2.decoder_for(channel.message_encoding, schema)
                msg = decode(message.data)
                if topic == "/collisions":
                    n = len(msg.time)
                    compact = schema.name == "carom_msgs/msg/CompactCollisionBatch"
                    for name, _ in COMPACT_FIELDS if compact else BATCH_FIELDS:
                        assert len(getattr(msg, name)) == n, name
                    out["batches"].append(
                        {
                            "sequence": message.sequence,
                            "log_time": message.log_time,
                            "first_ordinal": msg.first_ordinal,
                            "stride": msg.stride,
                            "len": n,
                            "first_time": msg.time[0].hex() if n else None,
                        }
                    )
                    (compact_crc if compact else batch_crc).add(msg)
                elif topic == "/snapshot":
                    out["snapshots"].append(
                        {
                            "time": msg.time.hex(),
                            "n": len(msg.x),
                            "box": [msg.box_x.hex(), msg.box_y.hex()],
                            "species_mass": [m.hex() for m in msg.species_mass],
                        }
                    )
                    snap_crc.add(msg)
                elif topic == "/checkpoint":
                    out["checkpoints"].append(
                        {
                            "now": msg.now.hex(),
                            "pair_collisions": msg.pair_collisions,
                            "wall_collisions": msg.wall_collisions,
                            "logged_collisions": msg.logged_collisions,
                            "x_crc": zlib.crc32(packed(msg.x, "d")),
                            "n": len(msg.x),
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
    out["batch_crc"] = batch_crc.crc
    out["compact_crc"] = compact_crc.crc
    out["snapshot_crc"] = snap_crc.crc
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
