//! What can go wrong with a sweep, each saying which file, point or field.

use std::path::PathBuf;

use thiserror::Error;

/// A sweep's error.
#[derive(Debug, Error)]
pub enum SweepError {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The operating-system error.
        #[source]
        source: std::io::Error,
    },
    /// The plan is malformed.
    #[error("{plan}: {field}: {problem} (allowed: {allowed})")]
    Plan {
        /// The plan file.
        plan: String,
        /// The field of the plan.
        field: String,
        /// What was wrong.
        problem: String,
        /// What is allowed.
        allowed: String,
    },
    /// A point's configuration is refused (the message is the configuration's).
    #[error("{plan}: point {point}: {problem}")]
    Point {
        /// The plan file.
        plan: String,
        /// The point's name.
        point: String,
        /// The configuration error.
        problem: String,
    },
    /// The output directory holds another sweep.
    #[error("{}: {problem}", dir.display())]
    Directory {
        /// The sweep's directory.
        dir: PathBuf,
        /// What was wrong.
        problem: String,
    },
    /// Slurm refused or failed (the message names the command).
    #[error("slurm: {0}")]
    Slurm(String),
}

/// `SweepError::Io` for `path`.
pub(crate) fn io(path: impl Into<PathBuf>) -> impl FnOnce(std::io::Error) -> SweepError {
    let path = path.into();
    move |source| SweepError::Io { path, source }
}
