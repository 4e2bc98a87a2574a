//! The cost of a collision at N = 10⁶ relative to N = 10⁴ (issue 2's locality
//! target: at most 1.5×), measured in alternating pairs.
//!
//! `cargo bench --bench ratio` (both η), or `cargo bench --bench ratio -- 0.5` for
//! one packing fraction. Pin it to one core for steadier numbers:
//! `taskset -c 0 cargo bench --bench ratio`.
//!
//! Periodic monodisperse discs (σ = 1, m = 1, kT = 1) on a lattice start, each system
//! equilibrated for 10 collisions per disc as in `benches/engine.rs`. Then, for each
//! pair, [`SMALL_BATCH`] collisions at N = 10⁴ and [`LARGE_BATCH`] at N = 10⁶ are
//! timed one right after the other, and the pair's ratio is the CPU time per
//! collision at 10⁶ over that at 10⁴. The machine this runs on is shared: other
//! tenants take part of the last-level cache and of the memory bandwidth, and how
//! much drifts over minutes, which moves the large system's rate by ±20 %. Two
//! criterion cases measured minutes apart compare different machines; a pair
//! measured seconds apart sees nearly the same one, so the median over pairs is the
//! figure to quote (with the spread of the pairs beside it).
//!
//! Not a criterion bench for that reason: criterion measures its cases one after
//! the other. CPU time of this thread (Linux `/proc/thread-self/schedstat`) rather
//! than wall time, so that time spent descheduled is not counted; elsewhere it falls
//! back to wall time.

mod common;

use carom_engine::Engine;
use common::equilibrated_fluid as engine;
use std::time::Instant;

/// Discs of the small system (its state, 1.5 MB, runs from the caches).
const SMALL: usize = 10_000;
/// Discs of the large system (138 MB of state: every event a cold part of memory).
const LARGE: usize = 1_000_000;
/// Collisions timed at N = 10⁴ per pair (about 1.5 s).
const SMALL_BATCH: u64 = 3_000_000;
/// Collisions timed at N = 10⁶ per pair (about 2 s): two collisions per disc, so
/// that each batch visits the whole state.
const LARGE_BATCH: u64 = 2_000_000;
/// Alternating pairs per packing fraction.
const PAIRS: usize = 8;

/// CPU time of this thread so far (s), or wall time where that is not available.
fn cpu_seconds(start: Instant) -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or_else(|| start.elapsed().as_secs_f64(), |ns| ns * 1e-9)
}

/// Seconds per collision of `count` more collisions of `e`.
fn seconds_per_collision(e: &mut Engine, count: u64, clock: Instant) -> f64 {
    let before = e.stats().pair_collisions + e.stats().wall_collisions;
    let t = cpu_seconds(clock);
    e.run_collisions(count).expect("no runaway in elastic runs");
    let dt = cpu_seconds(clock) - t;
    dt / (e.stats().pair_collisions + e.stats().wall_collisions - before) as f64
}

/// The middle of `x` (mean of the middle two for an even count).
fn median(x: &[f64]) -> f64 {
    let mut s = x.to_vec();
    s.sort_by(f64::total_cmp);
    let m = s.len() / 2;
    if s.len().is_multiple_of(2) {
        0.5 * (s[m - 1] + s[m])
    } else {
        s[m]
    }
}

fn main() {
    // Cargo passes `--bench`; any other argument is a packing fraction to measure.
    let etas: Vec<f64> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .map(|a| {
            a.parse()
                .expect("arguments are packing fractions, e.g. 0.5")
        })
        .collect();
    let etas = if etas.is_empty() {
        vec![0.5, 0.7]
    } else {
        etas
    };
    let clock = Instant::now();
    for eta in etas {
        let mut small = engine(SMALL, eta);
        let mut large = engine(LARGE, eta);
        let mut ratios = Vec::with_capacity(PAIRS);
        let (mut rate_small, mut rate_large) = (Vec::new(), Vec::new());
        for pair in 0..PAIRS {
            let s = seconds_per_collision(&mut small, SMALL_BATCH, clock);
            let l = seconds_per_collision(&mut large, LARGE_BATCH, clock);
            ratios.push(l / s);
            rate_small.push(1e-6 / s);
            rate_large.push(1e-6 / l);
            println!(
                "eta={eta:.2} pair {pair}: N=10^4 {:.3} M/s, N=10^6 {:.3} M/s, ratio {:.3}",
                1e-6 / s,
                1e-6 / l,
                l / s
            );
        }
        let lo = ratios.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ratios.iter().copied().fold(0.0, f64::max);
        println!(
            "eta={eta:.2}: cost per collision at N=10^6 / at N=10^4: median {:.3} \
             (pairs {lo:.3}-{hi:.3}, {PAIRS} pairs); median rates {:.3} and {:.3} M collisions/s \
             of CPU time; heap bytes per disc at N=10^6: {:.1}",
            median(&ratios),
            median(&rate_small),
            median(&rate_large),
            large.heap_bytes() as f64 / LARGE as f64
        );
    }
}
