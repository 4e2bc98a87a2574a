//! Collisions per second of the bare engine (no logging) for binary mixtures with a
//! few large discs: 20 000 discs of diameter 1 and 200 of diameter 1, 2, 5 and 10
//! (masses ∝ area) at η = 0.4 in a periodic square box, relaxed placement,
//! equilibrated for 10 collisions per disc. Shows what a grid per size class
//! (the engine's size classes) buys where it is chosen (ratios 5 and 10) and that the
//! other cases keep one grid.
//!
//! Run: `cargo bench --bench mixture`; one case:
//! `cargo bench --bench mixture -- 'ratio=5$'`. The setup prints how many grids
//! each case got.

#[macro_use]
mod common;

use common::{bench_built_once, equilibrated_mixture};
use criterion::{Criterion, Throughput};
use std::time::Duration;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("20000+200 eta=0.40");
    let batch = 100_000u64;
    group.throughput(Throughput::Elements(batch));
    group.sample_size(20);
    group.measurement_time(Duration::from_secs(8));
    for ratio in [1.0, 2.0, 5.0, 10.0] {
        bench_built_once(&mut group, format!("ratio={ratio}"), batch, || {
            let e = equilibrated_mixture(20_000, 200, ratio, 0.4);
            eprintln!("\n[ratio={ratio}] {} cell grid(s)", e.grid_count());
            e
        });
    }
    group.finish();
}

bench_main!(bench);
