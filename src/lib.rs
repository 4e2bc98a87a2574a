//! carom: exact event-driven molecular dynamics of hard discs.
pub use carom_core as core;
