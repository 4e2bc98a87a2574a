//! The inelastic section of the report (physics.md §8): the energy budget,
//! Haff's law with its Enskog prediction, and the Sonine coefficient a2.

use serde::Serialize;

#[cfg(doc)]
use super::{TemperatureReport, ENSKOG_COOLING_TOLERANCE};

/// Inelastic runs: energy budget and Haff's law (physics.md §8); the temperature
/// against time is [`TemperatureReport::series`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InelasticReport {
    /// Energy at the first and last record against the energy dissipated between;
    /// `null` in a field (the budget counts K only; `/thermo` has U since log
    /// format 2.2, and `gravity` gives K + U from the snapshots).
    pub energy: Option<EnergyBudget>,
    /// Haff's law check (normal restitution only).
    pub haff: Option<HaffReport>,
    /// Sonine coefficient a2 of the velocities; `null` with fewer than two
    /// snapshots used (`not_computed` says why).
    pub sonine: Option<SonineReport>,
}

/// The Sonine coefficient a2 = ⟨c⁴⟩/⟨c⁴⟩_MB − 1 = ⟨(m v²)²⟩/(2⟨m v²⟩²) − 1 of a
/// cooling gas (physics.md (8.5)), per snapshot, averaged over the snapshots used.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SonineReport {
    /// Measured a2 (mean over the snapshots used).
    pub a2: f64,
    /// Its standard error.
    pub std_error: f64,
    /// Whether the error is blocked over the snapshots (≥ 16) or the plain error
    /// of the mean.
    pub std_error_blocked: bool,
    /// Snapshots averaged.
    pub snapshots: usize,
    /// van Noije & Ernst's a2 for the run's e (physics.md (8.4)): the first
    /// Sonine approximation, linear in a2 — an approximation, 10–20 % off for
    /// discs near e = 0.8–0.9; `null` unless normal restitution.
    pub theory: Option<f64>,
    /// a2 of the second Sonine approximation (a2 and a3, linear in both;
    /// physics.md §8), the reference a2 is judged against; `null` unless normal
    /// restitution below 1.
    pub theory_second_order: Option<f64>,
}

/// E(t_end) = E(t_start) − dissipated (physics.md §8).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnergyBudget {
    /// Kinetic energy at the first record (energy).
    pub initial: f64,
    /// Kinetic energy at the last record (energy).
    #[serde(rename = "final")]
    pub final_: f64,
    /// Energy dissipated in between (energy).
    pub dissipated: f64,
    /// Where `dissipated` comes from.
    pub dissipated_source: &'static str,
    /// initial − dissipated − final (energy); 0 up to rounding when exact.
    pub residual: f64,
    /// residual / initial.
    pub relative_residual: f64,
}

/// Haff's law T(t) = T0/(1 + t/t0)² with 1/t0 = (1 − e²)(1 + 3a2/16) ω(T0)/4
/// (physics.md §8), ω(T0) from the measured collision rate scaled as √T: a
/// self-consistency check (the measured rate already holds the distribution's
/// (1 − a2/16)); `enskog` is the prediction from first principles.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HaffReport {
    /// What the check is, in words.
    pub check: &'static str,
    /// a2 (van Noije & Ernst) for the run's e.
    pub a2: f64,
    /// ω(T0) (1/time).
    pub collision_frequency_initial: f64,
    /// t0 (time).
    pub t0: f64,
    /// Haff's kT at the last record.
    pub kt_final_predicted: f64,
    /// Measured kT at the last record.
    pub kt_final_measured: f64,
    /// measured / predicted (1 in homogeneous cooling; clustering makes it differ).
    pub ratio: f64,
    /// Haff's law from Enskog's collision frequency over the window; `null` for
    /// a mixture, walls, or without a measured a2.
    pub enskog: Option<HaffEnskog>,
}

/// The cooling rate from first principles (physics.md §8): Enskog's collision
/// frequency ω_E = 2σ n g(σ) √(π kT/m) with Henderson's g(σ) and the measured
/// a2, so d(kT^(−1/2))/dt = (1 − e²)(1 + 3a2/16) ω_E/(4√kT), a constant, against
/// the measured kT(t) over the window.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HaffEnskog {
    /// [start, end] of the window compared (time).
    pub window: [f64; 2],
    /// Henderson's g(σ) at the run's η.
    pub g_contact: f64,
    /// The measured a2 used.
    pub a2: f64,
    /// ω_E at the window's start (1/time).
    pub omega_start: f64,
    /// Predicted slope of 1/√kT against t (1/(time·√energy)).
    pub slope_predicted: f64,
    /// Least-squares slope of the measured 1/√kT against t over the window.
    pub slope_measured: f64,
    /// measured / predicted slope.
    pub ratio: f64,
    /// kT at the window's end from kT at its start and the predicted slope.
    pub kt_end_predicted: f64,
    /// Measured kT at the window's end.
    pub kt_end_measured: f64,
    /// |ratio − 1| within [`ENSKOG_COOLING_TOLERANCE`].
    pub agrees: bool,
}
