"""Check what `carom export` wrote against the log's own snapshots, read with
the independent packages only: `mcap` + `mcap-ros2-support` for the log, `gsd`
for the GSD file, and a small extended-XYZ parser written here.

usage: check_export.py LOG.mcap OUT.gsd OUT.xyz EVERY

EVERY is the --every given to both exports (0: every snapshot). Prints one JSON
object: frames, discs and times found; exits non-zero with a message on any
mismatch.
"""

import json
import math
import shlex
import sys

import gsd.hoomd
import numpy
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory


def snapshots(path):
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        for _, _, _, m in reader.iter_decoded_messages(topics=["/snapshot"]):
            yield m


def kept(snaps, every):
    last = None
    for s in snaps:
        if every > 0 and last is not None and s.time - last < every * (1 - 1e-9):
            continue
        last = s.time
        yield s


def fail(why):
    print(why, file=sys.stderr)
    sys.exit(1)


def read_xyz(path):
    with open(path) as f:
        while True:
            line = f.readline()
            if not line:
                return
            n = int(line)
            info = {}
            for item in shlex.split(f.readline()):
                key, _, value = item.partition("=")
                info[key] = value
            rows = [f.readline().split() for _ in range(n)]
            yield info, rows


def main():
    log, gsd_path, xyz_path, every = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
    expected = list(kept(snapshots(log), every))
    if not expected:
        fail("the log has no snapshots")
    with gsd.hoomd.open(gsd_path, "r") as traj:
        if len(traj) != len(expected):
            fail(f"gsd: {len(traj)} frames, expected {len(expected)}")
        for k, (frame, s) in enumerate(zip(traj, expected)):
            n = len(s.x)
            lx, ly = s.box_x, s.box_y
            if frame.particles.N != n:
                fail(f"gsd frame {k}: N = {frame.particles.N}, expected {n}")
            box = [float(b) for b in frame.configuration.box]
            want = [numpy.float32(lx), numpy.float32(ly), 1, 0, 0, 0]
            if box != [float(w) for w in want] or frame.configuration.dimensions != 2:
                fail(f"gsd frame {k}: box {box}, dimensions {frame.configuration.dimensions}")
            if frame.log["carom/time"][0] != s.time:
                fail(f"gsd frame {k}: time {frame.log['carom/time']}, expected {s.time}")
            pos = frame.particles.position
            centred = numpy.stack([numpy.array(s.x) - lx / 2, numpy.array(s.y) - ly / 2], axis=1)
            # float32, and a coordinate at L/2 wraps to -L/2 on a periodic axis.
            d = numpy.abs(pos[:, :2] - centred)
            d = numpy.minimum(d, numpy.abs(d - numpy.array([lx, ly])))
            if d.max() > 4e-7 * max(lx, ly) or numpy.any(pos[:, 2] != 0):
                fail(f"gsd frame {k}: positions off by up to {d.max()}")
            if numpy.any(numpy.abs(pos[:, :2]) > numpy.array([lx, ly], dtype=numpy.float32) / 2):
                fail(f"gsd frame {k}: a position outside HOOMD's box")
            # Unwrapped positions (log format 2.1 on): HOOMD's position + image * L is
            # the log's x + image_x * L, shifted by L/2, to float32 rounding.
            if len(getattr(s, "image_x", [])) == n:
                lengths = numpy.array([lx, ly])
                images = frame.particles.image
                if numpy.any(images[:, 2] != 0):
                    fail(f"gsd frame {k}: a z image")
                got = pos[:, :2].astype(numpy.float64) + images[:, :2] * lengths
                want = centred + numpy.stack([s.image_x, s.image_y], axis=1) * lengths
                off = numpy.abs(got - want).max()
                if off > 4e-7 * max(lx, ly):
                    fail(f"gsd frame {k}: unwrapped positions off by up to {off}")
            v = frame.particles.velocity[:, :2]
            if not numpy.allclose(v, numpy.stack([s.vx, s.vy], axis=1), rtol=1e-6, atol=1e-6):
                fail(f"gsd frame {k}: velocities differ")
            types = list(frame.particles.types)
            if types != [chr(ord("A") + j) for j in range(len(s.species_radius))]:
                fail(f"gsd frame {k}: types {types}")
            if list(frame.particles.typeid) != list(s.species):
                fail(f"gsd frame {k}: typeid differs from the species")
            diam = numpy.array([2 * s.species_radius[j] for j in s.species], dtype=numpy.float32)
            if not numpy.array_equal(frame.particles.diameter, diam):
                fail(f"gsd frame {k}: diameters differ")
            mass = numpy.array([s.species_mass[j] for j in s.species], dtype=numpy.float32)
            if not numpy.array_equal(frame.particles.mass, mass):
                fail(f"gsd frame {k}: masses differ")
    xyz = list(read_xyz(xyz_path))
    if len(xyz) != len(expected):
        fail(f"xyz: {len(xyz)} frames, expected {len(expected)}")
    for k, ((info, rows), s) in enumerate(zip(xyz, expected)):
        lattice = [float(x) for x in info["Lattice"].split()]
        if lattice != [s.box_x, 0, 0, 0, s.box_y, 0, 0, 0, 1]:
            fail(f"xyz frame {k}: Lattice {lattice}")
        props = info["Properties"].split(":")
        names = props[0::3]
        if names[:5] != ["species", "pos", "velo", "radius", "mass"]:
            fail(f"xyz frame {k}: Properties {info['Properties']}")
        pbc = ["T" if b == 0 else "F" for b in (s.boundary_x, s.boundary_y)] + ["F"]
        if info["pbc"].split() != pbc or float(info["Time"]) != s.time:
            fail(f"xyz frame {k}: pbc {info['pbc']} Time {info['Time']}")
        if len(rows) != len(s.x):
            fail(f"xyz frame {k}: {len(rows)} rows")
        for i, r in enumerate(rows):
            got = [float(x) for x in r[1:]]
            want = [s.x[i], s.y[i], 0, s.vx[i], s.vy[i], 0,
                    s.species_radius[s.species[i]], s.species_mass[s.species[i]]]
            if r[0] != chr(ord("A") + s.species[i]) or got != want:
                fail(f"xyz frame {k} disc {i}: {r}, expected {want}")
    print(json.dumps({
        "frames": len(expected),
        "discs": len(expected[0].x),
        "times": [s.time for s in expected],
    }))


main()
