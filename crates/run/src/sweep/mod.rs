//! Sweeps: many runs from one plan (`carom sweep`, `carom collect`).
//!
//! A [`Plan`] (a base configuration, the dotted paths to vary, replicas by seed)
//! expands into points, each a directory `DIR/<point>/` with its `config.json` and
//! its log `run.mcap` ([`SweepDir`]). A point's state is read from its log alone
//! ([`PointState`]: no log, finished, cut short, failed, being written), so a sweep
//! re-run or resubmitted skips what is finished and resumes what was interrupted.
//! Points run as `carom run` / `carom resume` processes: locally in a pool of
//! [`run_pool`] (one per core), or as the tasks of a Slurm job array written by
//! [`slurm`]. [`collect()`] analyses every finished log and combines replicas.
//! Only one `carom sweep` works in a directory at a time ([`SweepLock`]).

mod collect;
mod error;
mod jobs;
mod layout;
mod lock;
mod names;
mod plan;
mod point;
mod pool;
pub mod slurm;
mod status;

pub use collect::{collect, CollectOptions, Collected, CollectedPoint, Combined, QUANTITIES};
pub use error::SweepError;
pub use jobs::{cores, jobs_at_once};
pub use layout::SweepDir;
pub use lock::SweepLock;
pub use names::MAX_NAME_BYTES;
pub use plan::{Axis, Plan, Point, MAX_POINTS};
pub use point::{point_command, run_point, PointOutcome};
pub use pool::{run_pool, PoolEvent, PoolReport};
pub use status::{point_state, PointState};
