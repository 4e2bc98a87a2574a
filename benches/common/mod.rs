//! What the engine benches share: the system they time.

use carom::events::{Engine, EngineParams, SystemSpec};

/// An equilibrated periodic fluid of `n` monodisperse discs (σ = 1, m = 1, kT = 1,
/// seed 42) at packing fraction `eta`: a lattice start with Maxwell–Boltzmann
/// velocities, run for 10 collisions per disc.
pub fn equilibrated_fluid(n: usize, eta: f64) -> Engine {
    let spec = SystemSpec::periodic_fluid(n, eta, 42);
    let mut e = Engine::new(spec.build().expect("valid system"), EngineParams::default())
        .expect("engine starts");
    e.run_collisions(10 * n as u64).expect("equilibration runs");
    e
}
