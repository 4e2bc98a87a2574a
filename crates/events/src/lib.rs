//! # carom-events
//!
//! The exact event-driven engine: discs fly straight between events, a queue of
//! predicted event times says what happens next, and each collision is resolved in
//! closed form.
//!
//! * [`queue`] — one pending event per disc in an event calendar keyed by time;
//! * [`cells`] — the cell grid used for neighbour search (crossings are events);
//! * [`classes`] — a grid per size class in mixtures of very different sizes;
//! * [`engine`] — the event loop ([`Engine`]);
//! * [`init`] — initial states from a seed ([`SystemSpec`]);
//! * [`checkpoint`] — the engine's complete state, for bit-identical resume;
//! * [`invariants`] — the invariant checker used by the tests;
//! * [`state`], [`event`], [`error`] — the plain data going in and coming out.
//!
//! Data flows one way: a [`State`] goes in, [`Event`]s come out; the engine knows
//! nothing about files.

pub mod cells;
pub mod checkpoint;
pub mod classes;
pub mod engine;
pub mod error;
pub mod event;
pub mod init;
pub mod invariants;
pub mod lookahead;
mod memory;
pub mod queue;
pub mod relax;
pub mod state;

pub use checkpoint::Checkpoint;
pub use engine::{Engine, EngineParams, Stats};
pub use error::{EngineError, InitError};
pub use event::{Event, PairCollision, WallCollision};
pub use init::{
    box_size_for, largest_radius, Placement, PlacementProgress, SystemSpec, Velocities,
};
pub use invariants::{InvariantChecker, Violation};
pub use state::State;
