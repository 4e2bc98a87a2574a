//! What the engine benches share: the system they time, how they time it, and
//! their `main`.

/// The bench binary's `main`, running `$bench` with criterion's plots off:
/// criterion draws them with plotters, whose PDF backend panics when the machine
/// has no fonts (the 2-core test machine has none), ending the run after the first
/// case. The numbers are printed either way.
#[allow(unused_macros)] // the ratio bench has its own main
macro_rules! bench_main {
    ($bench:ident) => {
        criterion::criterion_group! {
            name = benches;
            config = criterion::Criterion::default().without_plots();
            targets = $bench
        }
        criterion::criterion_main!(benches);
    };
}

use carom_engine::{Engine, EngineParams, SystemSpec};
use criterion::measurement::WallTime;
use criterion::BenchmarkGroup;
use std::time::Instant;

/// An equilibrated periodic fluid of `n` monodisperse discs (σ = 1, m = 1, kT = 1,
/// seed 42) at packing fraction `eta`: a lattice start with Maxwell–Boltzmann
/// velocities, run for 10 collisions per disc.
#[allow(dead_code)] // each bench binary uses only some of these systems
pub fn equilibrated_fluid(n: usize, eta: f64) -> Engine {
    let spec = SystemSpec::periodic_fluid(n, eta, 42);
    let mut e = Engine::new(spec.build().expect("valid system"), EngineParams::default())
        .expect("engine starts");
    e.run_collisions(10 * n as u64).expect("equilibration runs");
    e
}

/// An equilibrated periodic binary mixture (kT = 1, seed 42): `small` discs of
/// diameter 1 and mass 1 and `large` of diameter `ratio` and mass `ratio²`, at
/// packing fraction `eta`, placed by relaxed placement and run for 10 collisions
/// per disc.
#[allow(dead_code)] // each bench binary uses only some of these systems
pub fn equilibrated_mixture(small: usize, large: usize, ratio: f64, eta: f64) -> Engine {
    use carom_core::{Boundary, Species};
    use carom_engine::Placement;
    let species = vec![Species::reference(small), Species::scaled(large, ratio)];
    let mut spec = SystemSpec::square_box(species, eta, [Boundary::Periodic; 2], 42);
    spec.placement = Placement::Relaxed;
    let mut e = Engine::new(
        spec.build().expect("valid mixture"),
        EngineParams::default(),
    )
    .expect("engine starts");
    e.run_collisions(10 * (small + large) as u64)
        .expect("equilibration runs");
    e
}

/// Time criterion's `iters` batches of `batch` collisions of `e` (wall time), for
/// `Bencher::iter_custom`: the engine runs on from where the last batch left it.
#[allow(dead_code)] // the ratio bench times its own batches
fn time_batches(b: &mut criterion::Bencher, e: &mut Engine, batch: u64) {
    b.iter_custom(|iters| {
        let start = Instant::now();
        for _ in 0..iters {
            e.run_collisions(batch).expect("no runaway in elastic runs");
        }
        start.elapsed()
    });
}

/// Bench `name` in `group`: batches of `batch` collisions of the engine that
/// `build` makes on first use (criterion calls the closure several times, and only
/// for the cases the filter selects); `build` may print what it built.
#[allow(dead_code)] // the ratio bench times its own batches
pub fn bench_built_once(
    group: &mut BenchmarkGroup<'_, WallTime>,
    name: String,
    batch: u64,
    build: impl FnOnce() -> Engine,
) {
    let mut build = Some(build);
    let mut slot: Option<Engine> = None;
    group.bench_function(name, |b| {
        let e = slot.get_or_insert_with(|| build.take().expect("built once")());
        time_batches(b, e, batch);
    });
}
