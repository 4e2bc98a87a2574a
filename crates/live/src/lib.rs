//! # carom-live
//!
//! A run watched while it runs: a Foxglove WebSocket server (Foxglove's own SDK,
//! the `foxglove` crate) that serves the channels a viewer made for MCAP logs
//! shows live, `/scene` (the discs, `foxglove.SceneUpdate`, drawn by the log's own
//! `/scene` rules and coloured by species or by speed), `/thermo` (the log's
//! records, the log's JSON Schema) and `/progress` (time, collisions, rate, ETA).
//!
//! [`Live`] is a [`carom_run::Observer`]: any front end (the command's `--live`,
//! Python) starts one and hands it to the run's `Control`. The run never waits for
//! a viewer: frames are taken at most [`LiveOptions::frame_rate`] times a second
//! of wall time, only while a client is subscribed, and handed through a single
//! slot to a sender thread; the server's queue per client is short and drops the
//! oldest message when a client falls behind.

#![deny(missing_docs)]

mod channels;
mod colour;
mod handoff;
mod progress;
mod scene;
mod server;

pub use colour::Colouring;
pub use server::{Live, LiveError, LiveOptions, DEFAULT_ADDR, DEFAULT_FRAME_RATE};
