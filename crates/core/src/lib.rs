//! # carom-core
//!
//! The pure physics of hard discs in two dimensions, with no allocation and no
//! state: free flight and exact contact times ([`kinematics`], physics.md §1–2), the
//! collision rules ([`collision`], §3–4), free fall ([`gravity`], §15), growing discs
//! ([`growth`], §17), the vibrating floor ([`vibrating_wall`], §18), the first root of
//! a quartic ([`roots`], §15), boxes and walls ([`boundary`]), species
//! ([`species`]), the observables' only definitions ([`observables`], §5) and the
//! expected collision rates ([`rates`], §7).
//!
//! Units are the caller's (physics.md's reference values use σ = 1, m = 1, kT = 1);
//! every quantity is `f64`, vectors are [`glam::DVec2`].

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
