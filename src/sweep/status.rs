//! A point's state, read from its files alone (no database, no scheduler query),
//! so that `carom sweep status` tells the same on a laptop and on a cluster:
//! a log being written is locked by its writer; a finished log's `carom.summary`
//! says why the run stopped; a log cut short (killed) has no index, and resumes
//! from its last checkpoint if it has one.

use std::fs::{File, TryLockError};
use std::path::Path;

use carom_io::{scan, scan_indexed, StopReason};

use super::SweepDir;

/// Where a point stands.
#[derive(Debug, Clone, PartialEq)]
pub enum PointState {
    /// Not started (no log).
    Pending,
    /// Its log is being written (another process holds its lock).
    Running,
    /// Finished: the run reached its stop (or ended for a physical reason: no
    /// events left, or no collision for a long time).
    Done {
        /// Why it stopped.
        stop_reason: StopReason,
        /// Simulated time reached.
        sim_time: f64,
    },
    /// Stopped early (interrupted, killed, disk full): `carom resume` continues it
    /// if the log holds a checkpoint, otherwise it starts again.
    Interrupted {
        /// Whether the log holds a checkpoint to resume from.
        resumable: bool,
        /// What was found.
        detail: String,
    },
    /// The last attempt failed (the error as reported).
    Failed {
        /// The error.
        error: String,
    },
}

impl PointState {
    /// One word for tables: pending, running, done, interrupted, failed.
    pub fn word(&self) -> &'static str {
        match self {
            PointState::Pending => "pending",
            PointState::Running => "running",
            PointState::Done { .. } => "done",
            PointState::Interrupted { .. } => "interrupted",
            PointState::Failed { .. } => "failed",
        }
    }

    /// Whether the point still needs running.
    pub fn unfinished(&self) -> bool {
        !matches!(self, PointState::Done { .. } | PointState::Running)
    }
}

/// Point `i`'s state.
pub fn point_state(sweep: &SweepDir, i: usize) -> PointState {
    let log = sweep.log_path(i);
    let failure = std::fs::read_to_string(sweep.failure_path(i)).ok();
    if !log.exists() {
        return match failure {
            Some(error) => PointState::Failed {
                error: error.trim().to_owned(),
            },
            None => PointState::Pending,
        };
    }
    if locked(&log) {
        return PointState::Running;
    }
    let state = log_state(&log);
    match (state, failure) {
        (s @ PointState::Done { .. }, _) => s,
        (PointState::Interrupted { .. }, Some(error)) => PointState::Failed {
            error: error.trim().to_owned(),
        },
        (s, _) => s,
    }
}

/// The state a log shows by itself.
pub(super) fn log_state(log: &Path) -> PointState {
    match scan_indexed(log) {
        Ok(Some(info)) => match info.summary {
            Some(s) => match s.stop_reason {
                StopReason::Time
                | StopReason::Collisions
                | StopReason::Exhausted
                | StopReason::NoCollision => PointState::Done {
                    stop_reason: s.stop_reason,
                    sim_time: s.sim_time,
                },
                StopReason::Error => PointState::Failed {
                    error: s
                        .error
                        .unwrap_or_else(|| "the run stopped at an error".into()),
                },
                StopReason::Interrupted | StopReason::DiskFull => PointState::Interrupted {
                    resumable: info.last_checkpoint_time.is_some(),
                    detail: format!("stopped: {} at t = {}", s.stop_reason.as_str(), s.sim_time),
                },
            },
            None => PointState::Interrupted {
                resumable: info.last_checkpoint_time.is_some(),
                detail: "complete log without a summary".into(),
            },
        },
        // No index: a run cut short. Its last checkpoint needs a full scan.
        Ok(None) => match scan(log) {
            Ok(info) => PointState::Interrupted {
                resumable: info.last_checkpoint_time.is_some(),
                detail: match info.last_checkpoint_time {
                    Some(t) => format!("cut short; last checkpoint at t = {t}"),
                    None => "cut short before its first checkpoint".into(),
                },
            },
            Err(e) => PointState::Interrupted {
                resumable: false,
                detail: format!("unreadable ({e})"),
            },
        },
        Err(e) => PointState::Interrupted {
            resumable: false,
            detail: format!("unreadable ({e})"),
        },
    }
}

/// Whether another process holds the writer's lock on `log` (see `run::lock`).
fn locked(log: &Path) -> bool {
    match File::open(log) {
        Ok(f) => matches!(f.try_lock_shared(), Err(TryLockError::WouldBlock)),
        Err(_) => false,
    }
}
