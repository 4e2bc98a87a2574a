//! Initial states: placement of the discs and their velocities, reproducible from a
//! seed (a `rand_pcg` generator).
//!
//! A [`SystemSpec`] names the species, the box, the temperature, the seed and the
//! placement; [`SystemSpec::build`] validates it and returns a [`State`] with no
//! overlaps. Placements: `lattice` (the arrangement whose closest pair is farthest
//! apart), `random` (one by one, largest first; low densities), `relaxed` (a soft
//! overlap energy minimized by `relax`, up to just below jamming), `compressed`
//! (growing the discs of a dilute start in the engine, physics.md §17). Velocities
//! (`velocities`): Maxwell–Boltzmann at kT or one speed per species, at zero
//! momentum, scaled so that 2K/f = kT exactly (§5–§6).
//!
//! [`State`]: crate::State

mod build;
mod compressed;
mod lattice;
mod random;
mod relax;
mod relaxed;
mod spec;
mod velocities;

pub use compressed::COMPRESSED_MAX_REDUCED_PRESSURE;
pub use spec::{
    box_size_for, largest_radius, Compressing, Placement, PlacementProgress, SystemSpec, Velocities,
};
