//! # carom-core
//!
//! The pure physics of hard discs in two dimensions, with no allocation and no state:
//!
//! * [`kinematics`] — free flight and the exact contact time of two discs
//!   (physics.md §1–2, seed 000 Eq. 14–17);
//! * [`collision`] — elastic and inelastic resolution of a pair collision
//!   (physics.md §3–4, seed 000 Eq. 8–13 and 22–27, seed 004);
//! * [`gravity`] — free fall in a uniform field: heights, wall and cell-edge times
//!   (physics.md §15);
//! * [`growth`] — growing discs (compression): contact and wall times, the
//!   contact rule (physics.md §17);
//! * [`roots`] — the first descent through zero of a polynomial of degree ≤ 4,
//!   isolated to rounding (the contact of a resting and a falling disc, §15);
//! * [`boundary`] — rectangular boxes, periodic or walled per axis, and wall collisions;
//! * [`species`] — what a disc is made of (radius, mass);
//! * [`observables`] — degrees of freedom, kT, packing fraction, the area centres
//!   reach, and the pressure estimators (physics.md §5): their only definitions;
//! * [`rates`] — the collision rates expected from density and temperature (§7).
//!
//! Units are the caller's: lengths, times and masses in any consistent system. The
//! reference values in physics.md use disc diameter σ = 1, m = 1, kT = 1.
//! Every quantity is `f64`; vectors are [`glam::DVec2`].

#![deny(missing_docs)]

pub mod boundary;
pub mod collision;
pub mod gravity;
pub mod growth;
pub mod kinematics;
pub mod observables;
pub mod rates;
pub mod roots;
pub mod species;
pub mod vibrating_wall;

pub use boundary::{Axis, Boundary, SimBox, WallSide};
pub use collision::{Resolution, Restitution};
pub use glam::DVec2;
pub use species::{check_species, Species, SpeciesProblem};
