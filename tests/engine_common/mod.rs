//! Shared helpers of the engine tests: systems built on a lattice in a given box.
#![allow(dead_code)]

use carom::core::{SimBox, Species};
use carom::events::{Placement, SystemSpec, Velocities};

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
    vec![Species {
        count: n,
        radius: 0.5,
        mass: 1.0,
    }]
}
