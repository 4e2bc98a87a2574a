//! Profiling driver: `cargo run --release -p carom-engine --example profile -- N ETA COLLISIONS`.
//! Equilibrates 5 collisions per disc, then runs COLLISIONS more and prints event
//! counts per collision (for use under `valgrind --tool=cachegrind` or `perf`).
//! An optional fourth argument `on` or `off` forces fetching ahead on or off
//! (default: the engine's own choice for N). The environment variable
//! `CAROM_NEIGHBOURS=cells|lists` forces the neighbour search (default: the
//! engine's choice, lists from η = 0.6). Built with `--features counters`, it
//! also prints the operations per pair collision (carom_engine::counters).
use carom_engine::{Engine, EngineParams, Neighbours, SystemSpec};

mod common;
use common::{arg, cpu_seconds};

fn main() {
    let n = arg(1, 10_000.0) as usize;
    let eta = arg(2, 0.5);
    let count = arg(3, 1e6) as u64;
    let spec = SystemSpec::periodic_fluid(n, eta, 42);
    let neighbours = std::env::var("CAROM_NEIGHBOURS")
        .ok()
        .map(|v| Neighbours::from_name(&v).expect("CAROM_NEIGHBOURS: auto, cells or lists"))
        .unwrap_or_default();
    let params = EngineParams {
        neighbours,
        ..EngineParams::default()
    };
    let mut e = Engine::new(spec.build().unwrap(), params).unwrap();
    match std::env::args().nth(4).as_deref() {
        Some("on") => e.set_look_ahead(true),
        Some("off") => e.set_look_ahead(false),
        _ => {}
    }
    e.run_collisions(5 * n as u64).unwrap();
    #[cfg(feature = "counters")]
    let k0 = carom_engine::counters::counts();
    let s0 = *e.stats();
    let (t, cpu) = (std::time::Instant::now(), cpu_seconds());
    e.run_collisions(count).unwrap();
    let (dt, dcpu) = (t.elapsed().as_secs_f64(), cpu_seconds() - cpu);
    let s = e.stats();
    let c = (s.pair_collisions - s0.pair_collisions) as f64;
    println!(
        "N={n} eta={eta} {:.3e} coll/s wall, {:.3e} coll/s of CPU time; per collision: crossings {:.3}, stale {:.3}",
        c / dt,
        c / dcpu,
        (s.cell_crossings - s0.cell_crossings) as f64 / c,
        (s.stale_events - s0.stale_events) as f64 / c
    );
    #[cfg(feature = "counters")]
    for (k, (_, name)) in carom_engine::counters::ALL.iter().enumerate() {
        let per = (carom_engine::counters::counts()[k] - k0[k]) as f64 / c;
        println!("per collision: {name:<30} {per:8.3}");
    }
    let state = e.state();
    let h = common::state_hash(&state);
    println!(
        "heap bytes per disc: {:.1}",
        e.heap_bytes() as f64 / n as f64
    );
    println!("final state hash {h:016x} at t = {}", state.time);
    let search = if e.neighbour_lists() {
        "neighbour lists"
    } else {
        "cells"
    };
    println!("neighbour search at the end: {search}");
}
