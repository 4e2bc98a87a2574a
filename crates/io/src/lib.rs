//! # carom-io
//!
//! Configuration, MCAP logging and reading, and analysis input for carom.
//! The io crate sees the engine only through plain data (states, events,
//! checkpoints); it knows nothing about queues or cells.

pub mod config;
pub mod options;

pub use options::{Compression, LogOptions, RunSpec, Stop};
