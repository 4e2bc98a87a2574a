//! Collisions per second of the bare engine (no logging), issue 2.
//!
//! Periodic monodisperse discs (σ = 1, m = 1, kT = 1) on a lattice start with
//! Maxwell–Boltzmann velocities, equilibrated for 10 collisions per disc before
//! measuring. Throughput is in collisions (pair + wall) per second.
//!
//! Run all: `cargo bench --bench engine`; one case:
//! `cargo bench --bench engine -- 'eta=0.50/N=10000$'`.
//! The setup also prints the engine's heap bytes per disc for each case.

#[macro_use]
mod common;

use common::{bench_built_once, equilibrated_fluid as engine};
use criterion::{Criterion, Throughput};
use std::time::Duration;

fn bench(c: &mut Criterion) {
    for eta in [0.5, 0.7] {
        let mut group = c.benchmark_group(format!("eta={eta:.2}"));
        for n in [1_000usize, 10_000, 100_000, 1_000_000] {
            let batch = 100_000u64;
            group.throughput(Throughput::Elements(batch));
            group.sample_size(if n >= 100_000 { 10 } else { 20 });
            group.measurement_time(Duration::from_secs(if n >= 100_000 { 20 } else { 8 }));
            bench_built_once(&mut group, format!("N={n}"), batch, || {
                let e = engine(n, eta);
                eprintln!(
                    "\n[eta={eta:.2} N={n}] cells {:?}, heap bytes per disc: {:.1}",
                    e.cells(),
                    e.heap_bytes() as f64 / n as f64
                );
                e
            });
        }
        group.finish();
    }
}

bench_main!(bench);
