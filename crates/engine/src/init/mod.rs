//! Initial states: placement of the discs and their velocities, reproducible from a
//! seed (a `rand_pcg` generator).
//!
//! A [`SystemSpec`] names the species, the box, the temperature, the seed and how
//! to place the discs; [`SystemSpec::build`] validates it and returns a [`State`]
//! with no overlaps. Lattice placement (`lattice`) picks the arrangement whose
//! closest pair is farthest apart; random placement (`random`) inserts discs one by
//! one, largest first, for low densities; relaxed placement (`relaxed`, with the
//! minimizer in `relax`) removes the overlaps of random positions by minimizing a
//! soft overlap energy, up to just below jamming; compressed placement
//! (`compressed`) grows the discs of a dilute random start in the engine
//! (physics.md §17). Velocities (`velocities`) are
//! Maxwell–Boltzmann at kT or of one speed per species, shifted to zero momentum
//! and scaled so that 2K/f = kT exactly (physics.md §5–§6).
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
