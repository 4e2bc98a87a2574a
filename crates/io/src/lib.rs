//! # carom-io
//!
//! Configuration, MCAP logging and reading, and analysis input for carom.
//! The io crate sees the engine only through plain data (states, events,
//! checkpoints); it knows nothing about queues or cells.

pub mod cdr;
pub mod checkpoint_codec;
pub mod config;
pub mod log_reader;
pub mod log_writer;
pub mod options;
pub mod run_metadata;
pub mod schema;

pub use options::{Compression, LogOptions, RunSpec, Stop};

/// The `mcap` crate carom's logs are written with (for tools and tests that need
/// raw MCAP access).
pub use mcap;
