//! # carom-engine
//!
//! The exact event-driven engine for hard discs: discs fly straight between events,
//! a calendar of predicted event times says what happens next, and each collision
//! is resolved in closed form (physics.md §1–§4).
//!
//! * [`SystemSpec`] builds an initial [`State`] from a seed ([`Placement`],
//!   [`Velocities`]);
//! * [`Engine`] runs it with [`EngineParams`], handing out [`Event`]s
//!   ([`PairCollision`], [`WallCollision`], scheduled observations) and keeping
//!   running [`Stats`];
//! * [`Checkpoint`] is the engine's complete state, for a bit-identical resume;
//! * [`InvariantChecker`] checks conservation and overlaps, for tests.
//!
//! Data flows one way: a [`State`] goes in, [`Event`]s come out; the engine knows
//! nothing about files.
//!
//! ```
//! use carom_engine::{Engine, EngineParams, Event, SystemSpec};
//!
//! // 100 discs of diameter 1 at packing fraction 0.3 in a periodic box.
//! let state = SystemSpec::periodic_fluid(100, 0.3, 7).build().unwrap();
//! let mut engine = Engine::new(state, EngineParams::default()).unwrap();
//! let energy = engine.kinetic_energy();
//! let collisions = engine.run_until(2.0).unwrap();
//! assert!(collisions > 0);
//! assert!((engine.kinetic_energy() - energy).abs() < 1e-9 * energy);
//! ```

#![deny(missing_docs)]

mod cells;
mod checkpoint;
mod classes;
mod engine;
mod error;
mod event;
mod init;
mod invariants;
mod memory;
mod queue;
mod state;
mod thermostat;

pub use checkpoint::Checkpoint;
pub use engine::{Engine, EngineParams, Growth, GrowthEnd, GrowthState, Stats};
pub use error::{EngineError, InitError};
pub use event::{Event, PairCollision, WallCollision};
pub use init::{
    box_size_for, largest_radius, Compressing, Placement, PlacementProgress, SystemSpec,
    Velocities, COMPRESSED_MAX_REDUCED_PRESSURE,
};
pub use invariants::{InvariantChecker, Violation};
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
