"""Time `open_log(path).collisions()` on whole logs and on a window covering
them, best of 3 (docs/python.md, Speed). Make the logs with, e.g.,

    carom run --set stop.collisions=5000000 --set log.snapshot_interval=1 --out compact.mcap
    carom run --set stop.collisions=5000000 --set log.snapshot_interval=1 \\
              --set log.collision_detail=full --out full.mcap
    python crates/python/benches/collisions.py compact.mcap full.mcap
"""
import sys
import time

import carom

for path in sys.argv[1:]:
    for name, read in (("whole", lambda: carom.open_log(path).collisions()),
                       ("window", lambda: carom.open_log(path).collisions(0.0, 1e300))):
        best, n = float("inf"), 0
        for _ in range(3):
            t = time.perf_counter()
            n = len(read())
            best = min(best, time.perf_counter() - t)
        print(f"{path} {name}: {n} collisions in {best:.3f} s, {n / best / 1e6:.2f} M/s")
