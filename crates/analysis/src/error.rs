//! Why a log could not be analysed: it could not be read, a statistic could not
//! be computed, or it holds nothing to analyse (or an option does not fit it).

use carom_log::ReadError;
use thiserror::Error;

use super::stats::StatsError;

/// Why a log could not be analysed.
#[derive(Debug, Error)]
pub enum AnalysisError {
    /// The log could not be read.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// A statistic could not be computed.
    #[error("analysis: {0}")]
    Stats(#[from] StatsError),
    /// The log holds nothing to analyse, or an option does not fit it.
    #[error("{0}")]
    Unusable(String),
}
