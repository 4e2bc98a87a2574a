//! The velocity-distribution section of the report (physics.md §6): per species
//! the speed and component histograms against Maxwell–Boltzmann with the χ² and
//! Kolmogorov–Smirnov tests, and the species too sparse to test.

use serde::Serialize;

use super::stats::{Histogram, KsTest};
#[cfg(doc)]
use super::{MAX_SNAPSHOT_CORRELATION, MB_FAMILY_ALPHA};

/// A histogram with the theoretical density at the bin centres.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HistogramReport {
    /// Bin edges (bins + 1 values).
    pub edges: Vec<f64>,
    /// Counts per bin.
    pub counts: Vec<u64>,
    /// Values outside the edges (below, above).
    pub outside: [u64; 2],
    /// Estimated density per bin, count / (total × width).
    pub density: Vec<f64>,
    /// Maxwell–Boltzmann density at the bin centres.
    pub theory: Vec<f64>,
}

impl HistogramReport {
    pub(super) fn new(h: &Histogram, pdf: impl Fn(f64) -> f64) -> Self {
        HistogramReport {
            edges: h.edges(),
            counts: h.counts.clone(),
            outside: [h.underflow, h.overflow],
            density: h.density(),
            theory: h.centres().into_iter().map(pdf).collect(),
        }
    }
}

/// χ² test result (physics.md §6).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChiSquareReport {
    /// χ² statistic.
    pub statistic: f64,
    /// Degrees of freedom: merged bins − 1 − 1 (kT measured from the data).
    pub dof: usize,
    /// p-value.
    pub p_value: f64,
    /// Bins after merging to ≥ 5 expected counts.
    pub bins: usize,
}

/// Kolmogorov–Smirnov test result. The temperature is measured from the same
/// data, so the p-value is conservative (Lilliefors).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KsReport {
    /// D statistic.
    pub statistic: f64,
    /// Sample size.
    pub n: usize,
    /// p-value (asymptotic Kolmogorov with Stephens' correction).
    pub p_value: f64,
}

impl From<&KsTest> for KsReport {
    fn from(k: &KsTest) -> Self {
        KsReport {
            statistic: k.statistic,
            n: k.n,
            p_value: k.p_value,
        }
    }
}

/// A species whose velocities could not be tested against Maxwell–Boltzmann.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeciesUntested {
    /// Species index.
    pub species: usize,
    /// Speeds in the window (discs × snapshots).
    pub samples: usize,
    /// Why the tests could not be made.
    pub reason: String,
}

/// One species' velocities against the 2D Maxwell–Boltzmann distribution
/// (physics.md §6).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeciesMb {
    /// Species index.
    pub species: usize,
    /// Mass (mass).
    pub mass: f64,
    /// Radius (length).
    pub radius: f64,
    /// Speeds used (discs × snapshots).
    pub samples: usize,
    /// Snapshots used for this species.
    pub snapshots: usize,
    /// Correlation of this species' velocities between consecutive snapshots of
    /// the window (before thinning; `None` with fewer than two).
    pub snapshot_correlation: Option<f64>,
    /// Every how many of the window's snapshots this species was tested on: 1, or
    /// more when its velocities correlate more than [`MAX_SNAPSHOT_CORRELATION`]
    /// from one to the next (a heavy species).
    pub snapshot_step: usize,
    /// kT of the reference distribution (energy), measured from the same snapshots.
    pub kt: f64,
    /// Inelastic runs: each snapshot's velocities were scaled by √(kt/kT(t)) to
    /// the common `kt` before testing (the homogeneous cooling state).
    pub scaled_to_snapshot_temperature: bool,
    /// Speed histogram over [0, 4.5 √(kT/m)) with the MB speed pdf.
    pub speed_histogram: HistogramReport,
    /// v_x histogram over ±4.5 √(kT/m) with the Gaussian pdf.
    pub vx_histogram: HistogramReport,
    /// v_y histogram.
    pub vy_histogram: HistogramReport,
    /// χ² of the speed histogram.
    pub chi_square: ChiSquareReport,
    /// KS test of the speeds.
    pub ks: KsReport,
    /// KS test of v_x against the Gaussian.
    pub ks_vx: KsReport,
    /// KS test of v_y against the Gaussian.
    pub ks_vy: KsReport,
    /// The smallest p-value of this species' four tests (speed χ², speed KS, v_x
    /// KS, v_y KS).
    pub min_p_value: f64,
    /// Tests made over all species (4 per species tested): the m of the
    /// Bonferroni rule.
    pub tests: usize,
    /// α/m with α = [`MB_FAMILY_ALPHA`]: the p-value below which a test rejects.
    pub p_threshold: f64,
    /// `min_p_value ≥ p_threshold`: no test of this species rejects
    /// Maxwell–Boltzmann at family-wise level α (physics.md §6).
    pub passed: bool,
}
