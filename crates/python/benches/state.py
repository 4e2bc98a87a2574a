"""Time `sim.state` of a fluid of N discs (default 10⁶, η = 0.5) after 2N
collisions: best and median of 20 (docs/python.md, Speed).

    python crates/python/benches/state.py [N]
"""
import sys
import time
import timeit

import carom

n = int(sys.argv[1]) if len(sys.argv) > 1 else 10**6
sim = carom.Simulation({"species": [{"count": n}], "box": {"packing_fraction": 0.5},
                        "seed": 1})
t = time.perf_counter()
sim.run(collisions=2 * n)
print(f"N = {n}: {sim.collisions} collisions in {time.perf_counter() - t:.1f} s")
times = sorted(timeit.repeat(lambda: sim.state, number=1, repeat=20))
print(f"sim.state: best {times[0] * 1e3:.1f} ms, median {times[10] * 1e3:.1f} ms")
