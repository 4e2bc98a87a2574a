#!/usr/bin/env python3
"""Replay a carom log of compact collision records with nothing but the
independent readers (`mcap`, `mcap-ros2-support`): no carom code.

Usage: replay_compact_log.py FILE.mcap

From the first /snapshot on, every disc moves freely (r += v dt) and each
/collisions entry applies its impulse exactly as documented in the schema
(docs/log-format.md, "Compact collisions"): a pair (i, j) gets
v_i += dp / m_i and v_j -= dp / m_j, a wall on axis k gets v_i[k] += dp[k] / m_i,
each component one float64 division then one addition. Every later /snapshot
is compared with the replay: velocities must match bit for bit, positions to
within the printed error (periodic axes compared modulo the box length). The
replay is never re-synchronised from a later snapshot.

Prints one JSON object: collisions and snapshots replayed, velocity mismatches
(with the first one), the largest position error.
"""

import json
import struct
import sys

from mcap.reader import NonSeekingReader
from mcap_ros2.decoder import DecoderFactory

WALL_CODE_BASE = 4294967292  # j of a wall: base + 2 * axis + side


def bits(x):
    return struct.pack("<d", x)


def main(path):
    out = {
        "collisions": 0,
        "walls": 0,
        "snapshots_checked": 0,
        "velocity_mismatches": 0,
        "first_mismatch": None,
        "max_position_error": 0.0,
        "schema": None,
    }
    state = None
    factory = DecoderFactory()
    decoders = {}
    with open(path, "rb") as f:
        reader = NonSeekingReader(f)
        for schema, channel, message in reader.iter_messages():
            if channel.topic not in ("/collisions", "/snapshot"):
                continue
            key = channel.id
            if key not in decoders:
                decoders[key] = factory.decoder_for(channel.message_encoding, schema)
            msg = decoders[key](message.data)
            if channel.topic == "/snapshot":
                if state is None:
                    state = start(msg)
                else:
                    check(state, msg, out)
                continue
            out["schema"] = schema.name
            if schema.name != "carom_msgs/msg/CompactCollisionBatch":
                raise SystemExit(f"not a compact log: /collisions has {schema.name}")
            if state is None:
                raise SystemExit("a /collisions batch before the first /snapshot")
            apply_batch(state, msg, out)
    print(json.dumps(out))


def start(s):
    mass = list(s.species_mass)
    return {
        "box": (s.box_x, s.box_y),
        "periodic": (s.boundary_x == 0, s.boundary_y == 0),
        "m": [mass[k] for k in s.species],
        "t": [s.time] * len(s.x),  # time at which each disc is at (x, y)
        "x": list(s.x),
        "y": list(s.y),
        "vx": list(s.vx),
        "vy": list(s.vy),
    }


def move(st, d, t):
    """Free flight of disc d to time t."""
    dt = t - st["t"][d]
    st["x"][d] += st["vx"][d] * dt
    st["y"][d] += st["vy"][d] * dt
    st["t"][d] = t


def apply_batch(st, b, out):
    m, vx, vy = st["m"], st["vx"], st["vy"]
    for k in range(len(b.time)):
        t, i, j = b.time[k], b.i[k], b.j[k]
        dpx, dpy = b.dpx[k], b.dpy[k]
        move(st, i, t)
        if j >= WALL_CODE_BASE:
            axis = (j - WALL_CODE_BASE) // 2
            if axis == 0:
                vx[i] = vx[i] + dpx / m[i]
            else:
                vy[i] = vy[i] + dpy / m[i]
            out["walls"] += 1
        else:
            move(st, j, t)
            vx[i] = vx[i] + dpx / m[i]
            vy[i] = vy[i] + dpy / m[i]
            vx[j] = vx[j] - dpx / m[j]
            vy[j] = vy[j] - dpy / m[j]
        out["collisions"] += 1


def check(st, s, out):
    out["snapshots_checked"] += 1
    for d in range(len(s.x)):
        for name, got, want in (("vx", st["vx"][d], s.vx[d]), ("vy", st["vy"][d], s.vy[d])):
            if bits(got) != bits(want):
                out["velocity_mismatches"] += 1
                if out["first_mismatch"] is None:
                    out["first_mismatch"] = f"t = {s.time}: disc {d} {name} {got!r} vs {want!r}"
        dt = s.time - st["t"][d]
        for axis, (r, v, want) in enumerate(
            ((st["x"][d], st["vx"][d], s.x[d]), (st["y"][d], st["vy"][d], s.y[d]))
        ):
            diff = r + v * dt - want
            if st["periodic"][axis]:
                length = st["box"][axis]
                diff -= length * round(diff / length)
            out["max_position_error"] = max(out["max_position_error"], abs(diff))


if __name__ == "__main__":
    main(sys.argv[1])
