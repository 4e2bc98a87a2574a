//! Mixture profiling driver:
//! `cargo run --release -p carom-engine --example mixture -- N_SMALL N_LARGE RATIO ETA COLLISIONS`.
//! N_SMALL discs of diameter 1 and N_LARGE of diameter RATIO (masses as areas) at
//! packing fraction ETA in a square periodic box (relaxed placement), equilibrated
//! for 5 collisions per disc; prints collisions per second of CPU time over
//! COLLISIONS more, and a hash of the final state.
use carom_core::{Boundary, Species};
use carom_engine::{Engine, EngineParams, Placement, SystemSpec};

mod common;
use common::{arg, cpu_seconds};

fn main() {
    let small = arg(1, 20_000.0) as usize;
    let large = arg(2, 200.0) as usize;
    let ratio = arg(3, 5.0);
    let eta = arg(4, 0.4);
    let count = arg(5, 1e6) as u64;
    let species = vec![Species::reference(small), Species::scaled(large, ratio)];
    let mut spec = SystemSpec::square_box(species, eta, [Boundary::Periodic; 2], 42);
    spec.placement = Placement::Relaxed;
    let mut e = Engine::new(spec.build().unwrap(), EngineParams::default()).unwrap();
    let n = small + large;
    e.run_collisions(5 * n as u64).unwrap();
    let s0 = *e.stats();
    let cpu = cpu_seconds();
    e.run_collisions(count).unwrap();
    let dcpu = cpu_seconds() - cpu;
    let s = e.stats();
    let c = (s.pair_collisions - s0.pair_collisions) as f64;
    let state = e.state();
    let h = common::state_hash(&state);
    println!(
        "{small} + {large} ratio {ratio} eta {eta}: {} grid(s), {:.3e} coll/s of CPU time; crossings/collision {:.3}; heap bytes/disc {:.1}; hash {h:016x}",
        e.grid_count(),
        c / dcpu,
        (s.cell_crossings - s0.cell_crossings) as f64 / c,
        e.heap_bytes() as f64 / n as f64,
    );
}
