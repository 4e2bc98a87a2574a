//! Analysis of carom runs: statistics checked independently of the engine
//! ([`stats`]: histograms, χ² and Kolmogorov–Smirnov tests, block averaging and the
//! 2D Maxwell–Boltzmann distribution, physics.md §5–§6) and what `carom analyze`
//! reports ([`report`]).

pub mod report;
pub mod stats;
