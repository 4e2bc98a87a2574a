"""A hard-disc fluid from Python: run it, check its speeds against Maxwell–Boltzmann
and its g(r) against freud's.

    python examples/python/fluid.py                 # N = 4000, η = 0.6, a few seconds
    python examples/python/fluid.py --n 1000 --duration 10 --out /tmp/fluid

It runs a periodic fluid with `carom.Simulation` and logs it (`fluid.mcap`, the
log `carom run` writes), then reads the log back:

* speeds.png — the speeds of every snapshot after equilibration against the 2D
  Maxwell–Boltzmann density P(v) = (m v / kT) exp(−m v² / 2kT) (physics.md §7),
  kT from the same velocities; error bars are Poisson √count.
* gr.png — carom's g(r) with its block error (`carom.analyze`, physics.md §10)
  and freud's `freud.density.RDF` on the same snapshots and bins, with the
  difference in units of carom's error below.

Needs matplotlib and freud-analysis (`pip install matplotlib freud-analysis`).
"""

from __future__ import annotations

import argparse
import math
import pathlib

import freud
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import carom  # noqa: E402


def arguments() -> argparse.Namespace:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--n", type=int, default=4000, help="number of discs (4000)")
    p.add_argument("--eta", type=float, default=0.6, help="packing fraction (0.6)")
    p.add_argument("--duration", type=float, default=20.0,
                   help="simulated time, in units of σ√(m/kT) (20)")
    p.add_argument("--seed", type=int, default=1, help="random seed (1)")
    p.add_argument("--out", type=pathlib.Path, default=pathlib.Path("fluid-python"),
                   help="directory for the log and the figures (fluid-python)")
    return p.parse_args()


def run(a: argparse.Namespace) -> pathlib.Path:
    """Run the fluid with a log of a snapshot every half time unit."""
    a.out.mkdir(parents=True, exist_ok=True)
    log = a.out / "fluid.mcap"
    log.unlink(missing_ok=True)
    sim = carom.Simulation({
        "species": [{"count": a.n}],
        "box": {"packing_fraction": a.eta},
        "seed": a.seed,
        "stop": {"duration": a.duration},
        "log": {"snapshot_interval": 0.5},
    })
    sim.run(log=log)
    print(f"ran N = {len(sim)}, η = {a.eta}: {sim.collisions} collisions to t = {sim.time:g}")
    return log


def speeds(log: carom.Log, t_eq: float, path: pathlib.Path) -> None:
    """Histogram of the speeds after t_eq against the 2D Maxwell–Boltzmann density."""
    snaps = [s for s in log.snapshots(t_eq)]
    v = np.concatenate([np.hypot(s["vx"], s["vy"]) for s in snaps])
    m = snaps[0]["mass"][0]
    kt = m * np.mean(v**2) / 2  # equipartition in 2D: <m v²/2> = kT
    edges = np.linspace(0, 4.5 * math.sqrt(kt / m), 46)
    counts, _ = np.histogram(v, edges)
    width = np.diff(edges)
    centres = (edges[:-1] + edges[1:]) / 2
    density = counts / (len(v) * width)
    error = np.sqrt(counts) / (len(v) * width)
    vv = np.linspace(0, edges[-1], 400)
    mb = m * vv / kt * np.exp(-m * vv**2 / (2 * kt))
    expected = len(v) * width * (m * centres / kt) * np.exp(-m * centres**2 / (2 * kt))
    chi2 = float(np.sum((counts - expected) ** 2 / np.maximum(expected, 1e-300)))
    print(f"speeds: {len(v)} samples from {len(snaps)} snapshots, kT = {kt:.4f}, "
          f"χ² = {chi2:.1f} over {len(counts)} bins (a rough check; the report's "
          "tests account for correlated snapshots)")

    fig, ax = plt.subplots(figsize=(5, 3.6), layout="constrained")
    ax.errorbar(centres, density, yerr=error, fmt="o", ms=3, lw=1, label="carom")
    ax.plot(vv, mb, "k-", lw=1, label=r"$P(v) = \frac{mv}{kT}\,e^{-mv^2/2kT}$")
    ax.set_xlabel(r"speed $v$ [$\sqrt{kT/m}$]")
    ax.set_ylabel(r"$P(v)$")
    ax.set_title(f"speeds after t = {t_eq:g}: N = {len(snaps[0]['x'])}, "
                 f"{len(snaps)} snapshots", fontsize=10)
    ax.legend(frameon=False)
    fig.savefig(path, dpi=150)
    plt.close(fig)


def pair_correlation(log: carom.Log, report: dict, path: pathlib.Path) -> None:
    """carom's g(r) (the report's, with block errors) and freud's on the same frames."""
    pc = report["pair_correlation"]
    pair = pc["pairs"][0]
    r = np.array(pc["r"])
    g = np.array(pair["g"], dtype=float)
    err = np.array(pair["std_error"], dtype=float)
    width = pc["bin_width"] * pair["sigma"]
    r_max = r[-1] + width / 2
    t_eq, t_end = report["window"]["equilibrate"], report["window"]["t_end"]

    # finite_size: the (N − 1)/N of freud's exact mode undone, as carom normalises
    rdf = freud.density.RDF(bins=len(r), r_max=r_max, normalization_mode="finite_size")
    frames = 0
    for s in log.snapshots(t_eq, t_end):
        lx, ly = s["box"]
        box = freud.box.Box(Lx=lx, Ly=ly, is2D=True)
        # freud's box is centred on the origin; carom's runs from 0 to L.
        points = np.column_stack([s["x"] - lx / 2, s["y"] - ly / 2, np.zeros_like(s["x"])])
        rdf.compute((box, points), reset=False)
        frames += 1
    if frames != pc["snapshots"]:
        print(f"note: freud saw {frames} snapshots, carom's report {pc['snapshots']}")
    gf = rdf.rdf
    used = (err > 0) & (g > 0)
    z = (gf[used] - g[used]) / err[used]
    print(f"g(r): {frames} snapshots, contact value {pair['contact']['value']:.3f} "
          f"± {pair['contact']['std_error']:.3f}; freud − carom over {used.sum()} bins: "
          f"rms {np.sqrt(np.mean(z**2)):.2f} σ, max |Δ| {np.max(np.abs(z)):.2f} σ")

    fig, (ax, dx) = plt.subplots(2, 1, figsize=(5, 4.6), sharex=True, layout="constrained",
                                 gridspec_kw={"height_ratios": [3, 1]})
    ax.fill_between(r, g - err, g + err, color="C0", alpha=0.35, lw=0,
                    label="carom ± block error")
    ax.plot(r, g, color="C0", lw=1)
    ax.plot(rdf.bin_centers, gf, "k.", ms=2, label="freud RDF")
    ax.set_ylabel(r"$g(r)$")
    ax.set_xlim(0.8 * pair["sigma"], min(r_max, 5 * pair["sigma"]))
    ax.legend(frameon=False)
    ax.set_title(f"pair correlation of N = {report['n']} discs at η = "
                 f"{report['packing_fraction']:.3g}, t in [{t_eq:g}, {t_end:g}]", fontsize=10)
    dx.axhline(0, color="k", lw=0.5)
    dx.plot(r[used], z, "k.", ms=2)
    dx.set_ylabel(r"$(g_\mathrm{freud} - g)/\sigma_g$")
    dx.set_xlabel(r"$r$ [$\sigma$]")
    fig.savefig(path, dpi=150)
    plt.close(fig)


def main() -> None:
    a = arguments()
    path = run(a)
    log = carom.open_log(path)
    report = carom.analyze(path)
    t_eq = report["window"]["equilibrate"]
    speeds(log, t_eq, a.out / "speeds.png")
    pair_correlation(log, report, a.out / "gr.png")
    print(f"wrote {a.out / 'speeds.png'} and {a.out / 'gr.png'}")


if __name__ == "__main__":
    main()
