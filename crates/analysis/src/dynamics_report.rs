//! The report of the single-disc dynamics from a log's snapshots (physics.md
//! §13): per species the mean-square displacement with the non-Gaussian
//! parameter and the self-diffusion coefficient D, the velocity autocorrelation
//! sampled at the snapshots, and the self intermediate scattering function
//! F_s(k*, τ) at the first peak of S(k) with the α-relaxation time. Serialised
//! as `dynamics` in `carom analyze --json`; units are the run's. Every curve is
//! over the same lags τ (one per pairing key of [`super::origins`], sorted), each
//! with a standard error from the spread of the run's time segments (NaN, JSON
//! `null`, where fewer than two segments have data).

use serde::Serialize;

/// Diffusion, velocity correlation and self scattering of every species.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DynamicsReport {
    /// One entry per species with discs.
    pub species: Vec<SpeciesDynamics>,
    /// Time origins used (block-start snapshots after the equilibration time).
    pub origins: u64,
    /// Origins kept per level (p).
    pub origins_per_level: usize,
    /// Levels of origins (lags up to about 2^(levels−1) p blocks).
    pub levels: usize,
    /// Most origins held at once (memory: N × this × 32 bytes).
    pub max_stored: usize,
    /// Whether the memory cap lowered p or the levels (long lags then missing).
    pub origins_capped: bool,
    /// Time segments the errors come from.
    pub segments: usize,
    /// The mean collision time t_c = 1/ω (time) the D window is set from; `null`
    /// without a collision rate.
    pub collision_time: Option<f64>,
    /// k* (1/length), the first peak of S(k) of the first origin; `null` unless
    /// the box is periodic.
    pub k_star: Option<f64>,
    /// Snapshot gaps too long to unwrap with certainty (logs without images):
    /// displacements across them may be wrong by a box length.
    pub ambiguous_gaps: u64,
}

/// The dynamics of one species.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeciesDynamics {
    /// Species index.
    pub species: usize,
    /// Discs of the species.
    pub count: usize,
    /// Mean lag τ of each point (time), increasing; the first is 0.
    pub lag: Vec<f64>,
    /// Disc-origin pairs averaged at each lag.
    pub samples: Vec<u64>,
    /// MSD(τ) = ⟨|Δu|²⟩ (length²).
    pub msd: Vec<f64>,
    /// Its standard error.
    pub msd_std_error: Vec<f64>,
    /// Non-Gaussian parameter α₂(τ) = ⟨Δu⁴⟩/(2⟨Δu²⟩²) − 1 (NaN at τ = 0).
    pub alpha2: Vec<f64>,
    /// C(τ) = ⟨v(t₀)·v(t₀ + τ)⟩ at the snapshots (length²/time²).
    pub vacf: Vec<f64>,
    /// Its standard error.
    pub vacf_std_error: Vec<f64>,
    /// C(τ)/C(0).
    pub vacf_normalised: Vec<f64>,
    /// F_s(k*, τ) = ⟨J₀(k*|Δu|)⟩; empty without k*.
    pub fs: Vec<f64>,
    /// Its standard error; empty without k*.
    pub fs_std_error: Vec<f64>,
    /// τ_α: F_s(k*, τ_α) = 1/e, interpolated in ln τ; `null` if F_s stays above
    /// 1/e, or is below it already at the first positive lag.
    pub tau_alpha: Option<f64>,
    /// D from the slope of the MSD; `null` with too few lags in the window.
    pub diffusion: Option<DiffusionFit>,
}

/// The self-diffusion coefficient from MSD = 4Dτ + c over a window of lags. In
/// 2D D grows like ln τ (the long-time tail), so it depends on the window and N.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiffusionFit {
    /// D (length²/time).
    pub d: f64,
    /// Its standard error: the statistical one and the fit's spread in
    /// quadrature, √(statistical_std_error² + (d − d_unweighted)²) (physics.md §13).
    pub std_error: f64,
    /// The statistical part, from the same fit done per time segment.
    pub statistical_std_error: f64,
    /// D from the unweighted fit over the same window (a consistency check; its
    /// difference from `d` is part of `std_error`).
    pub d_unweighted: f64,
    /// Intercept c (length²).
    pub intercept: f64,
    /// Window start t_a (time).
    pub t_a: f64,
    /// Window end t_b (time).
    pub t_b: f64,
    /// Lags in the window.
    pub points: usize,
    /// Segments whose own fit gave the error.
    pub segments: usize,
}
