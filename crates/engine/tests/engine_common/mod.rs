//! Shared helpers of the engine tests: systems built on a lattice in a given box.
#![allow(dead_code)]

use carom_core::{SimBox, Species};
use carom_engine::{Placement, SystemSpec, Velocities};

/// `species` on a lattice in `sim_box`, Maxwell–Boltzmann velocities at T = 1.
pub fn lattice_spec(species: Vec<Species>, sim_box: SimBox, seed: u64) -> SystemSpec {
    SystemSpec {
        species,
        sim_box,
        temperature: 1.0,
        seed,
        placement: Placement::Lattice,
        velocities: Velocities::MaxwellBoltzmann,
    }
}

/// `n` discs of radius 0.5 and mass 1.
pub fn mono(n: usize) -> Vec<Species> {
    vec![Species::reference(n)]
}

/// Random dynamics, as the random-system tests draw them: the pair rule (elastic,
/// or either inelastic model with a coefficient in [0, 1), one in three each) and
/// the TC duration (0, or 10^x with x uniform in `tc_exponents`, one in two each).
pub fn draw_dynamics(
    g: &mut rand_pcg::Pcg64,
    tc_exponents: std::ops::Range<f64>,
) -> (carom_core::Restitution, f64) {
    use carom_core::Restitution;
    use rand::RngExt;
    let restitution = match g.random_range(0..3) {
        0 => Restitution::Elastic,
        1 => Restitution::CentreOfMass(g.random_range(0.0..1.0)),
        _ => Restitution::Normal(g.random_range(0.0..1.0)),
    };
    let tc = if g.random::<bool>() {
        0.0
    } else {
        10f64.powf(g.random_range(tc_exponents))
    };
    (restitution, tc)
}

pub mod oracle;

/// A binary mixture: `n_small` discs of radius 0.5 and mass 1 and `n_large` of
/// radius 0.7 and mass 2.5 (neither ratio a power of two).
pub fn mixture(n_small: usize, n_large: usize) -> Vec<Species> {
    vec![Species::reference(n_small), Species::new(n_large, 0.7, 2.5)]
}
