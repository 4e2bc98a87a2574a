//! # carom-run
//!
//! The run driver: builds the engine, asks it for observations at exact times,
//! hands every event to the MCAP log writer and ends the log cleanly; and
//! [`sweep`], many runs from one plan (a local pool of processes, or Slurm).
//!
//! Two entry points, both blocking until the run ends: [`run`], a fresh run from a
//! [`RunSpec`](carom_log::RunSpec) into a new log file, and [`resume`], which
//! continues a log (complete, or cut short by a crash) from its last checkpoint.
//! The caller steers both through a [`Control`] (stop flag, progress, free disk;
//! an example is on [`run`]).

#![deny(missing_docs)]

mod bounds;
mod bytes;
mod control;
mod disk;
mod driver;
mod error;
mod lock;
mod memory;
mod observation;
mod repair;
mod replace;
mod resume;
mod start;
mod thermo;
mod watchdog;

pub mod sweep;

use std::path::PathBuf;

use carom_log::Stop;
use carom_log::StopReason;

pub use bytes::Bytes;
pub use control::{Control, Observer, Progress, ResumePass};
pub use disk::{disk_low, far_too_small, free_space_for, FreeSpace, FAR_BEYOND_FREE};
pub use error::RunError;
pub use lock::{lock_log, LogLock};
pub use memory::{check_memory, memory_available, memory_needed, IGNORE_MEMORY_CHECK};
pub use repair::{repair, Repaired};
pub use resume::{resume, same_file};
pub use start::run;
pub use thermo::thermo;
pub use watchdog::MEAN_FREE_TIMES;

/// What a finished run did.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// The log file.
    pub log: PathBuf,
    /// Why it ended.
    pub stop_reason: StopReason,
    /// Simulated time at the end (time).
    pub sim_time: f64,
    /// Pair collisions over the whole run.
    pub pair_collisions: u64,
    /// Wall collisions over the whole run.
    pub wall_collisions: u64,
    /// Collisions written to `/collisions` over the whole run.
    pub logged_collisions: u64,
    /// Collisions processed by this process (excludes the part before a resume).
    pub collisions_this_process: u64,
    /// Wall-clock seconds of this process's part.
    pub wall_seconds: f64,
    /// `collisions_this_process / wall_seconds`.
    pub collisions_per_second: f64,
    /// Kinetic energy at the end (energy).
    pub kinetic_energy: f64,
    /// Potential energy U = Σ m g y at the end (energy); `None` without a field.
    pub potential_energy: Option<f64>,
    /// Energy dissipated over the whole run (energy).
    pub energy_lost: f64,
    /// Size of the log file (bytes).
    pub file_bytes: u64,
    /// Why the run stopped early, in words, when the reason alone does not say it
    /// (`no_collision`: since when, and the bound).
    pub detail: Option<String>,
}

/// Options of [`resume`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ResumeOptions {
    /// A new stop criterion (e.g. to extend a finished run); `None` keeps the input's.
    pub stop: Option<Stop>,
}
