//! Statistics for checking a simulation against theory, independent of the engine:
//! histograms, χ² and Kolmogorov–Smirnov goodness-of-fit tests, block averaging
//! for correlated series, and the 2D Maxwell–Boltzmann distribution
//! (physics.md §5–§6).
//!
//! Special functions (regularised incomplete gamma for χ² p-values, erfc for the
//! Gaussian CDF, χ² quantiles) come from `statrs`; only the Kolmogorov series,
//! which `statrs` does not provide, is summed here.

use thiserror::Error;

/// Why a statistic could not be computed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum StatsError {
    /// Too few data for the requested statistic.
    #[error("not enough data: {0}")]
    NotEnoughData(String),
    /// An argument is outside its allowed range.
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
}

mod blocking;
mod chi_square;
mod histogram;
mod ks;
mod maxwell_boltzmann;

pub use blocking::{block_average, blocking, BlockEstimate, Blocking, BlockingLevel};
pub use chi_square::{chi_square_histogram, chi_square_test, ChiSquareTest, MIN_EXPECTED};
pub use histogram::Histogram;
pub use ks::{kolmogorov_p_value, kolmogorov_survival, ks_test, KsTest};
pub use maxwell_boltzmann::{mb_speed_test, MaxwellBoltzmann2d, MbTest};
