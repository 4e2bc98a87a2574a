//! Why a run or a resume failed: one error type, each variant saying what and where.
//!
//! A failure after the log exists still finishes the log where it can
//! ([`RunError::Engine`]); a failure to write it leaves a log readable up to its
//! last flush, which `carom resume` continues ([`RunError::LogCut`]).

use std::path::PathBuf;

use carom_engine::{EngineError, InitError};
use carom_log::WriteError;
use carom_log::{OptionsError, ReadError};
use thiserror::Error;

/// A run that could not be carried out. Each variant says what and where.
#[derive(Debug, Error)]
pub enum RunError {
    /// The initial state could not be built.
    #[error("initial state: {0}")]
    Init(#[from] InitError),
    /// An option is out of range.
    #[error("{field}: {problem} (allowed: {allowed})")]
    Invalid {
        /// The option, as a dotted path (e.g. `log.snapshot_interval`).
        field: &'static str,
        /// What is wrong.
        problem: String,
        /// What is allowed.
        allowed: String,
    },
    /// The engine failed mid-run; the log was finished (with `stop_reason = error`
    /// in its summary) and is readable up to the failure.
    #[error("engine failed at simulated time {time}: {source}; the log {log} is finished and readable up to there")]
    Engine {
        /// The engine's error.
        source: EngineError,
        /// Simulated time of the failure.
        time: f64,
        /// The log file.
        log: PathBuf,
    },
    /// The checkpoint to resume from was rejected by the engine.
    #[error("cannot resume from the last checkpoint of {file}: {source}")]
    BadCheckpoint {
        /// The input log.
        file: PathBuf,
        /// The engine's reason.
        source: EngineError,
    },
    /// Writing the log failed.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// Writing the log failed during the run (a full disk, a file system gone):
    /// the log is not finished, but readable up to its last flush, and `resume`
    /// continues it from its last complete checkpoint.
    #[error(
        "{source}\nthe run stopped at simulated time {}; {log} is readable up to its last \
         flush, and `carom resume {log}` continues it from its last complete checkpoint \
         once the cause is removed (a full disk: free space, or resume with --out on \
         another disk)",
        // Seven digits are plenty to say where; the log has the exact times.
        *.time as f32
    )]
    LogCut {
        /// The writer's error.
        source: WriteError,
        /// Simulated time when the run stopped (time).
        time: f64,
        /// The log file.
        log: PathBuf,
    },
    /// Writing the continuation of a resume in place failed (a full disk): the
    /// continuation is lost, and the log is as it was before the resume.
    #[error(
        "{source}\nthe resume stopped at simulated time {}; its continuation is lost, and \
         {log} is as it was before the resume; remove the cause (a full disk: free some \
         space) and run `carom resume {log}` again, or resume with --out on another disk",
        *.time as f32
    )]
    ResumeCut {
        /// The writer's error.
        source: WriteError,
        /// Simulated time when the resume stopped (time).
        time: f64,
        /// The log that was being resumed, unchanged.
        log: PathBuf,
    },
    /// Reading the log to resume failed.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// The stop flag was raised while the discs were being placed, before the log
    /// was created: nothing was written.
    #[error("interrupted while placing the discs (after {steps} minimization steps of relaxed placement, or rescale intervals of compressed placement); no log was written")]
    InterruptedPlacing {
        /// Minimization steps (relaxed) or rescale intervals (compressed) taken.
        steps: usize,
    },
    /// The disk that is to hold the resumed log has too little room for the copy
    /// of the input up to its last checkpoint and the reserve to finish the log
    /// (nothing was written).
    #[error(
        "cannot resume into {out}: its disk has {} free, and the copy of {input} up to its \
         last checkpoint with the room to finish the log after it needs about {}; free some \
         space, or resume with --out on another disk",
        crate::Bytes(*.free),
        crate::Bytes(*.need)
    )]
    NoRoom {
        /// The log being resumed.
        input: PathBuf,
        /// The file the resumed log was to be written to.
        out: PathBuf,
        /// Bytes the copy and the finish need (the input's size and the reserve).
        need: u64,
        /// Bytes free on the output's disk.
        free: u64,
    },
    /// Another process holds the lock on a log this run would write (or resume):
    /// nothing was written.
    #[error(
        "{file} is being written by {}; wait for it to end, or write to another file \
         with --out",
        super::lock::holder_text(.holder)
    )]
    Locked {
        /// The log.
        file: PathBuf,
        /// The process holding the lock ("process PID (COMMAND LINE)"), where it can
        /// be told (Linux).
        holder: Option<String>,
    },
    /// The log to lock could not be opened or locked.
    #[error("cannot open {file} to lock it: {source}")]
    Lock {
        /// The log.
        file: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The engine or the writer failed before the run's log started (before its
    /// first checkpoint): no log was written, and the older log it was to replace
    /// (`carom run --force`), if any, is as it was.
    #[error(
        "{reason}\nno log was written{}",
        .kept.as_ref().map_or(String::new(), |k| format!("; {} is as it was", k.display()))
    )]
    NotStarted {
        /// What failed.
        reason: String,
        /// The older log, left as it was.
        kept: Option<PathBuf>,
    },
    /// Renaming the finished resumed log over the input, or a new run's log over
    /// the older one, failed.
    #[error("cannot move the new log {from} over {to}: {source}")]
    Rename {
        /// The finished temporary file.
        from: PathBuf,
        /// The input log.
        to: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
}

impl From<OptionsError> for RunError {
    fn from(e: OptionsError) -> Self {
        RunError::Invalid {
            field: e.field,
            problem: e.problem,
            allowed: e.allowed,
        }
    }
}
