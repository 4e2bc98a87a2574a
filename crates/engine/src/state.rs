//! The plain state of a system of discs: what goes into the engine and what the
//! caller sees at observation times.

use carom_core::{observables, DVec2, SimBox, Species};

/// Positions, velocities and species of every disc at one time.
///
/// Discs are numbered 0..N; disc k belongs to species `species_of[k]`.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// The box and its boundaries.
    pub sim_box: SimBox,
    /// The species (count, radius, mass).
    pub species: Vec<Species>,
    /// Species index of each disc.
    pub species_of: Vec<u16>,
    /// Centre positions, inside the box (length).
    pub positions: Vec<DVec2>,
    /// Velocities (length/time).
    pub velocities: Vec<DVec2>,
    /// Periodic image of each disc: its unwrapped position, continuous in time, is
    /// `positions[i] + images[i] · box size` (the net number of periodic edges it
    /// crossed since the run began, per axis; 0 along walls). Empty in a state that
    /// does not track them, which counts as all 0.
    pub images: Vec<[i32; 2]>,
    /// The time of this state (time).
    pub time: f64,
}

impl State {
    /// Number of discs N.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// True when there are no discs.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Mass of disc `i` (mass).
    pub fn mass(&self, i: usize) -> f64 {
        self.species[self.species_of[i] as usize].mass
    }

    /// Radius of disc `i` (length).
    pub fn radius(&self, i: usize) -> f64 {
        self.species[self.species_of[i] as usize].radius
    }

    /// Total kinetic energy K = Σ m v²/2 (energy).
    pub fn kinetic_energy(&self) -> f64 {
        kinetic_energy(&self.species, &self.species_of, &self.velocities)
    }

    /// Total momentum Σ m v (mass·length/time).
    pub fn momentum(&self) -> DVec2 {
        self.velocities
            .iter()
            .zip(&self.species_of)
            .map(|(v, &s)| *v * self.species[s as usize].mass)
            .sum()
    }

    /// Degrees of freedom f = 2N − (conserved momentum components) (physics.md §5).
    pub fn degrees_of_freedom(&self) -> usize {
        observables::degrees_of_freedom(self.len(), &self.sim_box)
    }

    /// Kinetic temperature kT = 2K/f (energy), physics.md §5.
    pub fn temperature(&self) -> f64 {
        observables::temperature(self.kinetic_energy(), self.degrees_of_freedom())
    }

    /// Packing fraction η = Σ π a² / A.
    pub fn packing_fraction(&self) -> f64 {
        observables::packing_fraction(&self.species, &self.sim_box)
    }
}

/// K = Σ m v²/2 over discs with the given species (energy).
pub(crate) fn kinetic_energy(species: &[Species], species_of: &[u16], velocities: &[DVec2]) -> f64 {
    velocities
        .iter()
        .zip(species_of)
        .map(|(v, &s)| 0.5 * species[s as usize].mass * v.length_squared())
        .sum()
}
