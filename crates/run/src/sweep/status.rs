//! A point's state, read from its files alone (no database, no scheduler query),
//! so that `carom sweep status` tells the same on a laptop and on a cluster:
//! a log being written is locked by its writer; a finished log's `carom.summary`
//! says why the run stopped; a log cut short (killed) has no index, and resumes
//! from its last checkpoint if it has one. A log counts for a point only if it is
//! that point's run: the configuration stored in its `carom.run` record must give
//! the run the point's configuration gives (the same [`RunSpec`]: discs, box,
//! dynamics, seed, stop, log options). A log copied from another point or left by
//! an unrelated run is a `mismatch`, one that cannot be read `unreadable`: neither
//! is collected, resumed or overwritten (the next sweep moves it aside first).

use std::fs::{File, TryLockError};
use std::path::Path;

use carom_config::Config;
use carom_log::{scan, scan_indexed, RunMetadata, RunSpec, StopReason};
use serde_json::Value;

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
    /// The log is another run's: its configuration is not the point's.
    Mismatch {
        /// What differs.
        detail: String,
    },
    /// The log cannot be read at all (not a carom log, or its start is damaged).
    Unreadable {
        /// The reader's error.
        detail: String,
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
            PointState::Mismatch { .. } => "mismatch",
            PointState::Unreadable { .. } => "unreadable",
        }
    }

    /// Whether the point's log is not the point's own readable run: it must be
    /// moved aside before the point runs, and is never collected.
    pub fn foreign(&self) -> bool {
        matches!(
            self,
            PointState::Mismatch { .. } | PointState::Unreadable { .. }
        )
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
    let state = log_state(&log, &sweep.plan.run_spec(i));
    match (state, failure) {
        (s @ PointState::Done { .. }, _) => s,
        (PointState::Interrupted { .. }, Some(error)) => PointState::Failed {
            error: error.trim().to_owned(),
        },
        (s, _) => s,
    }
}

/// The state `log` shows by itself, as the log of the run `expected`.
pub(super) fn log_state(log: &Path, expected: &RunSpec) -> PointState {
    let unreadable = |e: &dyn std::fmt::Display| PointState::Unreadable {
        detail: format!("unreadable ({e})"),
    };
    let info = match scan_indexed(log) {
        Ok(Some(info)) => info,
        // No index: a run cut short. Its last checkpoint needs a full scan.
        Ok(None) => match scan(log) {
            Ok(info) => {
                if let Some(detail) = mismatch(&info.run, expected) {
                    return PointState::Mismatch { detail };
                }
                return PointState::Interrupted {
                    resumable: info.last_checkpoint_time.is_some(),
                    detail: match info.last_checkpoint_time {
                        Some(t) => format!("cut short; last checkpoint at t = {t}"),
                        None => "cut short before its first checkpoint".into(),
                    },
                };
            }
            Err(e) => return unreadable(&e),
        },
        Err(e) => return unreadable(&e),
    };
    if let Some(detail) = mismatch(&info.run, expected) {
        return PointState::Mismatch { detail };
    }
    match info.summary {
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
    }
}

/// How the run logged in `run` differs from `expected`, if it does: the first
/// setting of the resolved configuration that differs, or why the log's
/// configuration cannot be read.
fn mismatch(run: &RunMetadata, expected: &RunSpec) -> Option<String> {
    let logged = match Config::from_json_str(&run.config).and_then(|c| c.to_run_spec()) {
        Ok(spec) => spec,
        Err(e) => return Some(format!("the configuration in the log cannot be read ({e})")),
    };
    if logged == *expected && run.seed == expected.system.seed {
        return None;
    }
    let parse = |s: &str| serde_json::from_str::<Value>(s).unwrap_or(Value::Null);
    let mut found = Vec::new();
    differences(
        &parse(&logged.config_json),
        &parse(&expected.config_json),
        "",
        &mut found,
    );
    let mut told: Vec<String> = found
        .iter()
        .take(3)
        .map(|(path, a, b)| format!("{path} is {} in it, {} here", short(a), short(b)))
        .collect();
    if found.len() > 3 {
        told.push(format!("and {} more", found.len() - 3));
    }
    Some(if told.is_empty() {
        "another run's log (its run differs from this point's)".into()
    } else {
        format!("another run's log: {}", told.join("; "))
    })
}

/// Every place (dotted path) where `a` and `b` differ, with both values, in
/// the order of the keys.
fn differences(a: &Value, b: &Value, at: &str, found: &mut Vec<(String, Value, Value)>) {
    let join = |k: &str| {
        if at.is_empty() {
            k.to_owned()
        } else {
            format!("{at}.{k}")
        }
    };
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let mut keys: Vec<&String> = x.keys().chain(y.keys()).collect();
            keys.sort_unstable();
            keys.dedup();
            for k in keys {
                let (u, v) = (
                    x.get(k).unwrap_or(&Value::Null),
                    y.get(k).unwrap_or(&Value::Null),
                );
                differences(u, v, &join(k), found);
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (k, (u, v)) in x.iter().zip(y).enumerate() {
                differences(u, v, &join(&k.to_string()), found);
            }
        }
        _ if a == b => {}
        _ => found.push((at.to_owned(), a.clone(), b.clone())),
    }
}

/// A value cut to about 40 characters for a message.
fn short(v: &Value) -> String {
    let s = v.to_string();
    if s.chars().count() <= 40 {
        s
    } else {
        s.chars().take(37).collect::<String>() + "…"
    }
}

/// Whether another process holds the writer's lock on `log` (see `run::lock`).
fn locked(log: &Path) -> bool {
    match File::open(log) {
        Ok(f) => matches!(f.try_lock_shared(), Err(TryLockError::WouldBlock)),
        Err(_) => false,
    }
}
