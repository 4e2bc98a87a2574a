//! The error of the log options' check: the setting, what was wrong and what is
//! allowed (shared by the options and the snapshot schedule).

use thiserror::Error;

/// A log option, or the stop, out of range (see [`crate::check_log_options`]).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("{field}: {problem} (allowed: {allowed})")]
pub struct OptionsError {
    /// The setting, as a dotted path (`log.snapshot_interval`, `stop.time`).
    pub field: &'static str,
    /// What was wrong.
    pub problem: String,
    /// What is allowed.
    pub allowed: String,
}

pub(crate) fn options_error(
    field: &'static str,
    problem: String,
    allowed: impl Into<String>,
) -> OptionsError {
    OptionsError {
        field,
        problem,
        allowed: allowed.into(),
    }
}
