//! The transport part of `carom analyze`'s report (physics.md §14): the exact
//! VACF, D two ways, η and λ by Einstein–Helfand and Green–Kubo, Enskog's
//! values and the mode-coupling tail. Units are the run's; k_B = 1.

use serde::Serialize;

/// Transport coefficients from the collision log (elastic, fully periodic runs
/// that log every collision).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TransportReport {
    /// Number of discs N (the coefficients of 2D fluids depend on it).
    pub n: usize,
    /// Mean time between pair collisions of a disc, t_c = 1/ω (time), the unit
    /// of the lags below.
    pub collision_time: f64,
    /// kT in the centre-of-mass frame, K/(N − 1) (energy).
    pub kt: f64,
    /// The lag window [τ_a, τ_b] (time) over which D, η and λ are taken: they
    /// grow like ln τ in 2D, so each value belongs to its window.
    pub window: [f64; 2],
    /// The same window in collision times, [τ_a/t_c, τ_b/t_c].
    pub window_collision_times: [f64; 2],
    /// The documented window in collision times, [10, 100] (physics.md §14.6): a
    /// shorter window makes every value below unreliable.
    pub documented_window_collision_times: [f64; 2],
    /// Time segments the run was cut into for the standard errors (each error is
    /// the segments' spread over √segments times Student's t, physics.md §14.6).
    pub segments: usize,
    /// Snapshots whose velocities were compared with the replayed ones, and how
    /// many differed (a sign of missing collisions; then nothing here holds).
    pub snapshots_checked: u64,
    /// Of those, how many disagreed.
    pub snapshots_mismatched: u64,
    /// Exact VACF, MSD and D per species.
    pub species: Vec<SpeciesTransport>,
    /// Shear viscosity.
    pub viscosity: HelfandReport,
    /// Thermal conductivity (one-species runs only: with several species the heat
    /// flux mixes with interdiffusion).
    pub thermal_conductivity: Option<HelfandReport>,
    /// Enskog's values (one-species runs only).
    pub enskog: Option<EnskogTransport>,
}

/// One species' exact VACF, MSD and self-diffusion.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeciesTransport {
    /// Species index.
    pub species: usize,
    /// Time origins used.
    pub origins: u64,
    /// Lags τ (time): 0, then log-spaced.
    pub lags: Vec<f64>,
    /// C(τ)/C(0), C(τ) = ⟨v_i(t₀)·v_i(t₀+τ)⟩, exact at each lag.
    pub vacf: Vec<f64>,
    /// Standard error of C(τ)/C(0) over segments.
    pub vacf_std_error: Vec<f64>,
    /// C(0) = ⟨|v|²⟩ (length²/time²).
    pub vacf_zero: f64,
    /// MSD(τ) = ⟨|ΔX_i|²⟩ (length²), exact.
    pub msd: Vec<f64>,
    /// D(τ) = ½ ∫₀^τ C (length²/time), exact.
    pub running_diffusion: Vec<f64>,
    /// D from the MSD over the window, [MSD(τ_b) − MSD(τ_a)]/[4(τ_b − τ_a)].
    pub diffusion_msd: Estimate,
    /// D from the VACF integral, the mean of D(τ) over the window; equal to the
    /// above in expectation.
    pub diffusion_vacf: Estimate,
    /// D(MSD) − D(VACF), with the error of the difference per segment.
    pub difference: Estimate,
    /// Whether D (both routes) holds: the window and the levelling off of D(τ)
    /// (physics.md §14.6).
    pub diffusion_reliability: Reliability,
    /// The measured tail amplitude A, τ C(τ)/C(0) averaged over lags ≥ τ_a.
    pub tail_amplitude: Option<Estimate>,
    /// Whether A holds (lags ≥ τ_a: the window rule only).
    pub tail_amplitude_reliability: Reliability,
    /// The mode-coupling amplitude 1/[8π n (D + ν)] with D and ν = η/(n m)
    /// measured here (one-species runs).
    pub tail_amplitude_theory: Option<f64>,
    /// Its standard error, from those of D and η.
    pub tail_amplitude_theory_std_error: Option<f64>,
}

/// A value and its standard error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// One standard error: the spread of the time segments' values over
    /// √segments, times Student's t for segments − 1 degrees of freedom.
    pub std_error: f64,
}

/// A transport coefficient by Einstein–Helfand and Green–Kubo.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HelfandReport {
    /// What it is ("shear viscosity", "thermal conductivity").
    pub quantity: &'static str,
    /// Lags τ (time).
    pub lags: Vec<f64>,
    /// Var[ΔG(τ)] (the Helfand moments' mean-square growth, averaged over their
    /// components).
    pub helfand_moment: Vec<f64>,
    /// The coefficient from the moment, Var[ΔG(τ)]/(2 V kT^a τ) (a = 1 for η, 2
    /// for λ).
    pub helfand: Vec<f64>,
    /// The Green–Kubo running integral at τ, ∫₀^τ ⟨J(0) J(s)⟩ ds/(V kT^a).
    pub green_kubo: Vec<f64>,
    /// The coefficient by Einstein–Helfand over the window (secant of Var\[ΔG\]).
    pub value_helfand: Estimate,
    /// The coefficient by Green–Kubo over the window (mean running integral).
    pub value_green_kubo: Estimate,
    /// Helfand − Green–Kubo, with the error of the difference per segment.
    pub difference: Estimate,
    /// Whether the coefficient holds: the window and the levelling off of the
    /// Green–Kubo running integral (physics.md §14.6).
    pub reliability: Reliability,
}

/// Whether a value can be trusted, and if not why (physics.md §14.6).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reliability {
    /// `false` when the window is shorter than the documented one or the running
    /// coefficient has not levelled off.
    pub reliable: bool,
    /// The reasons, in words (empty when reliable).
    pub why: Vec<String>,
}

/// Enskog's values for this run, with the dilute gas's Sonine factors on their
/// kinetic parts (physics.md §14.4–14.5).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnskogTransport {
    /// The contact value χ used, from the measured Z = 1 + 2φχ.
    pub chi: f64,
    /// The dilute gas's Sonine factors f_D, f_η, f_λ applied (the exact
    /// Chapman–Enskog values over the first Sonine approximation).
    pub sonine_factors: [f64; 3],
    /// D_E (length²/time).
    pub diffusion: f64,
    /// η_E.
    pub viscosity: f64,
    /// λ_E.
    pub thermal_conductivity: f64,
}
