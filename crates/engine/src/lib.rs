//! # carom-engine
//!
//! The exact event-driven engine for hard discs: between events each disc follows a
//! closed-form path (straight, r(t) = r₀ + v t; falling; growing), a calendar of
//! predicted event times says what happens next, and each collision, at the root of
//! |Δr + Δv t| = σ, is resolved in closed form (physics.md §1–§4). [`SystemSpec`]
//! builds an initial [`State`] from a seed; [`Engine`] runs it with
//! [`EngineParams`], handing out [`Event`]s and keeping running [`Stats`] (an
//! example is on [`Engine`]); [`Checkpoint`] is its complete state, for a
//! bit-identical resume; [`InvariantChecker`] checks conservation and overlaps, for
//! tests. Data flows one way: a [`State`] goes in, [`Event`]s come out; the engine
//! knows nothing about files.

#![deny(missing_docs)]

/// Count one operation (or `$n`) of kind `$what` (`counters::Count`) with the
/// feature `counters`; nothing at all without it.
macro_rules! count {
    ($what:ident) => {
        count!($what, 1)
    };
    ($what:ident, $n:expr) => {{
        #[cfg(feature = "counters")]
        $crate::counters::add($crate::counters::Count::$what, ($n) as u64);
    }};
}

mod cells;
mod checkpoint;
mod classes;
#[cfg(feature = "counters")]
pub mod counters;
mod engine;
mod error;
mod event;
mod init;
mod invariants;
mod lists;
mod memory;
mod queue;
mod state;
mod thermostat;

pub use checkpoint::{Checkpoint, ListsCheckpoint};
pub use engine::{DiscNow, Engine, EngineParams, Growth, GrowthEnd, GrowthState, Stats};
pub use error::{EngineError, InitError};
pub use event::{Event, PairCollision, WallCollision};
pub use init::{
    box_size_for, largest_radius, Compressing, Placement, PlacementProgress, SystemSpec,
    Velocities, COMPRESSED_MAX_REDUCED_PRESSURE,
};
pub use invariants::{InvariantChecker, Violation};
pub use lists::{Neighbours, LISTS_FROM_PACKING};
pub use state::State;
pub use thermostat::{Thermostat, ThermostatState, ThermostatStats};

/// The most records of one kind (snapshots, thermo, checkpoints or scenes) a run
/// may ask for through its log interval, and the most events of one kind its
/// parameters schedule in advance (Andersen redraws, driving kicks, growth
/// rescales, floor periods): far more than any analysis reads (10⁹ thermo
/// records are about 100 GB) or any sensible run takes, so only a mistyped
/// interval, rate or stop time meets it.
pub const MAX_RECORDS: f64 = 1e9;

/// "No disc": the end of a cell's list, an empty place in the event calendar, a
/// disc without a pair candidate; in a [`Checkpoint`] too.
pub const NO_DISC: u32 = u32::MAX;
