//! # carom
//!
//! Exact event-driven molecular dynamics of hard discs. This crate is the `carom`
//! command and re-exports the workspace's public API:
//!
//! * [`core`] (`carom-core`) — discs, boxes, exact kinematics and collision rules;
//! * [`engine`] (`carom-engine`) — the event queue, neighbour search and the event loop;
//! * [`log`] (`carom-log`) — the MCAP log: format, writer, reader;
//! * [`config`] (`carom-config`) — the configuration and its resolution into a run;
//!
//! Its own modules: `run` (runs and resumes), `analysis` (reports from logs),
//! `frames` (choosing snapshots), `render` (pictures), `export` (GSD, XYZ) and
//! `sweep` (many runs from one plan, locally or on Slurm).

pub mod export;
pub mod frames;
pub mod render;

pub use carom_analysis as analysis;
pub use carom_config as config;
pub use carom_core as core;
pub use carom_engine as engine;
pub use carom_log as log;
pub use carom_run as run;
pub use carom_run::sweep;
