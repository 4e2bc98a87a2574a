//! The report of `carom analyze`: plain serialisable data, one struct per
//! observable, serialised as the JSON object that `carom analyze --json` prints.
//! Every field says what it holds and in which units (the run's: length, time,
//! mass; energies as kT).

use serde::Serialize;

use super::atmosphere::GravityReport;
use super::bond_correlation::BondCorrelationReport;
use super::bond_order::BondOrderReport;
use super::contact::PairCorrelationReport;
use super::dynamics_report::DynamicsReport;
use super::stats::{Histogram, KsTest};
use super::structure_factor::StructureFactorReport;
use super::transport_report::TransportReport;
#[cfg(doc)]
use super::{
    DECORRELATION_COLLISIONS, ENSKOG_COOLING_TOLERANCE, MAX_SNAPSHOT_CORRELATION, MB_FAMILY_ALPHA,
};

/// Everything `carom analyze` reports. Serialised as one JSON object; units are
/// the run's (length, time, mass; energies as kT).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Number of discs N.
    pub n: usize,
    /// The species.
    pub species: Vec<SpeciesInfo>,
    /// Packing fraction η = Σ N_s π a_s² / (L_x L_y).
    pub packing_fraction: f64,
    /// Box edge lengths [L_x, L_y] (length).
    pub box_size: [f64; 2],
    /// Whether the x and y axes are periodic (else hard walls).
    pub periodic: [bool; 2],
    /// True when pair and wall collisions conserve energy.
    pub elastic: bool,
    /// Which part of the log was used.
    pub window: WindowReport,
    /// Temperature and its degrees-of-freedom convention.
    pub temperature: TemperatureReport,
    /// Velocity distribution against Maxwell–Boltzmann, one entry per species with
    /// enough samples for the tests (the others are in
    /// `maxwell_boltzmann_untested`).
    pub maxwell_boltzmann: Vec<SpeciesMb>,
    /// Species with speeds but too few for the Maxwell–Boltzmann tests.
    pub maxwell_boltzmann_untested: Vec<SpeciesUntested>,
    /// Pressure and compressibility factor; `null` when no temperature is known.
    pub pressure: Option<PressureReport>,
    /// Pair collisions per disc per unit time.
    pub collision_rate: CollisionRateReport,
    /// Enskog consistency check (periodic, monodisperse, elastic runs only).
    pub enskog: Option<EnskogReport>,
    /// Inelastic runs only: cooling and energy budget.
    pub inelastic: Option<InelasticReport>,
    /// Pair correlation g(r), contact values and the contact theorem
    /// (physics.md §10); `null` without snapshots after the equilibration time.
    pub pair_correlation: Option<PairCorrelationReport>,
    /// Bond-orientational order ψ6, |Ψ6| and χ6 (physics.md §11); `null` with
    /// fewer than two snapshots after the equilibration time.
    pub bond_order: Option<BondOrderReport>,
    /// g6(r) and its decay (physics.md §11); `null` without snapshots.
    pub orientational_correlation: Option<BondCorrelationReport>,
    /// S(k) and the translational order (physics.md §11); `null` unless the box
    /// is periodic and there are snapshots.
    pub structure_factor: Option<StructureFactorReport>,
    /// MSD and D per species, the VACF at the snapshots and F_s(k*, τ) with τ_α
    /// (physics.md §13); `null` without time origins after the equilibration time.
    pub dynamics: Option<DynamicsReport>,
    /// D, η and λ from the collision log, with the exact VACF (physics.md §14);
    /// `null` unless the run is elastic and periodic and logs every collision.
    pub transport: Option<TransportReport>,
    /// Potential energy, n(y) and the barometric fit (physics.md §15); `null`
    /// without a field or without snapshots after the equilibration time.
    pub gravity: Option<GravityReport>,
    /// The thermostat's target against the measured temperature (physics.md
    /// §16); `null` without a thermostat.
    pub thermostat: Option<super::thermostat::ThermostatReport>,
    /// How the discs grew: start and final η, how growth ended, the last Z and
    /// the rescales (physics.md §17); `null` unless the run compressed.
    pub compression: Option<super::compression::CompressionReport>,
    /// The vibrating floor and the mean powers it puts in and the collisions
    /// dissipate (physics.md §18); `null` without a floor.
    pub floor: Option<super::floor::FloorReport>,
    /// The quantities absent above that a reader would look for, each with the
    /// reason it could not be computed.
    pub not_computed: Vec<super::not_computed::NotComputed>,
}

/// One species of the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeciesInfo {
    /// Number of discs.
    pub count: usize,
    /// Radius (length).
    pub radius: f64,
    /// Mass (mass).
    pub mass: f64,
}

/// The part of the log analysed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WindowReport {
    /// First simulated time in the log (time).
    pub t_start: f64,
    /// Last simulated time in the log (time).
    pub t_end: f64,
    /// Data before this time are ignored (time).
    pub equilibrate: f64,
    /// Minimum spacing of the snapshots used for the velocity distribution (time);
    /// `null`: every snapshot.
    pub every: Option<f64>,
    /// Whether `every` is the default rather than asked for: [`DECORRELATION_COLLISIONS`]
    /// collision times from the log's collision rate, or more when that would keep
    /// more than `max_velocities` velocities.
    pub every_default: bool,
    /// The default spacing of an inelastic run, whose collision rate changes: the
    /// snapshots used are at least this many pair collisions per disc apart,
    /// counted between them (`every` then only applies the memory bound); `null`
    /// otherwise.
    pub every_collisions: Option<f64>,
    /// Whether the default `every` was widened to keep at most `max_velocities`
    /// velocities in memory.
    pub every_from_budget: bool,
    /// The most velocities (discs × snapshots) the default spacing keeps.
    pub max_velocities: usize,
    /// The smallest spacing of the snapshots used, in pair collisions per disc
    /// counted between them (2 ΔN_pair/N, from the `/thermo` running counts or
    /// the logged collisions); `null` with fewer than two. Below
    /// about 4, the velocities of consecutive snapshots are correlated and the
    /// Maxwell–Boltzmann tests reject too often.
    pub spacing_collisions: Option<f64>,
    /// Snapshots in the log.
    pub snapshots_seen: usize,
    /// Times of the snapshots used for the velocity distribution.
    pub snapshot_times: Vec<f64>,
}

/// Temperature (physics.md §5).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TemperatureReport {
    /// kT = 2K/f averaged over the snapshots used (energy); if none, at the start of
    /// the window.
    pub kt: f64,
    /// kT at the first record of the log.
    pub kt_initial: Option<f64>,
    /// kT at the last record of the log.
    pub kt_final: Option<f64>,
    /// Degrees of freedom f.
    pub dof: usize,
    /// Momentum components conserved (periodic axes), subtracted from 2N.
    pub conserved_momentum_components: usize,
    /// The convention in words.
    pub convention: &'static str,
    /// [time, kT] from the thermo records and snapshots of the whole log (at most
    /// 2000 points, evenly subsampled).
    pub series: Vec<[f64; 2]>,
}

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

/// Pressure and compressibility factor with one standard error (physics.md §5).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PressureReport {
    /// How P was measured.
    pub estimator: &'static str,
    /// Z = βPA/N.
    pub z: f64,
    /// One standard error of Z (blocking analysis over time bins).
    pub z_std_error: f64,
    /// βP (1/length²).
    pub beta_p: f64,
    /// Standard error of βP.
    pub beta_p_std_error: f64,
    /// P = βP × kT (energy/length²), with kT averaged over the window.
    pub p: f64,
    /// Area A used (length²): the box, or the area reachable by centres with walls.
    pub area: f64,
    /// Independent blocks the error is estimated from.
    pub blocks: usize,
    /// Duration of one block (time).
    pub block_time: f64,
    /// False when the blocking analysis found no plateau (error from 16 blocks;
    /// the run may be too short for its correlation time).
    pub converged: bool,
    /// Z against time: [time, Z] averaged over ~64 consecutive intervals.
    pub series: Vec<[f64; 2]>,
    /// Drift check of Z over the window; `null` when too short.
    pub drift: Option<DriftReport>,
}

/// Drift check of a series reported as a mean with a blocked standard error: the
/// means of the window's two halves (physics.md §5, drift). A drifting series has
/// not reached its steady state: its mean and error mean little.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DriftReport {
    /// Mean over the first half of the window.
    pub first_half: f64,
    /// Its blocked standard error.
    pub first_half_std_error: f64,
    /// Mean over the second half of the window.
    pub second_half: f64,
    /// Its blocked standard error.
    pub second_half_std_error: f64,
    /// (second − first)/√(SE₁² + SE₂²).
    pub difference_std_errors: f64,
    /// |difference_std_errors| > 3.
    pub drifting: bool,
}

/// Pair collision rate (physics.md §7).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CollisionRateReport {
    /// ω = 2 N_pair / (N t): pair collisions per disc per unit time (1/time),
    /// the mean over the window (for a cooling gas, an average over a rate that
    /// falls as √T: see `start` and `end`).
    pub per_disc: f64,
    /// One standard error of ω.
    pub std_error: f64,
    /// Logged pair collisions in the whole log.
    pub logged_pair_collisions: u64,
    /// Logged wall collisions in the whole log.
    pub logged_wall_collisions: u64,
    /// Every k-th collision is logged; counts are scaled by it.
    pub collision_stride: u64,
    /// Where the pair collisions were counted: `"collisions"`, the logged
    /// collisions (the counts above); `"thermo"`, the running counts of the
    /// `/thermo` records (logs without every collision: the logged counts above
    /// are then not what ω is made of).
    pub counted_from: &'static str,
    /// [start, end] of the window the rate is measured over (time).
    pub window: [f64; 2],
    /// Drift check of ω over the window; `null` for inelastic runs (ω ∝ √T
    /// changes as they cool) or a window too short.
    pub drift: Option<DriftReport>,
    /// ω over the first sixteenth of the window (inelastic runs only).
    pub start: Option<RateAt>,
    /// ω over the last sixteenth of the window (inelastic runs only).
    pub end: Option<RateAt>,
}

/// The pair collision rate over part of the window.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RateAt {
    /// [start, end] of the part (time).
    pub window: [f64; 2],
    /// ω over it (1/time).
    pub per_disc: f64,
    /// One standard error (blocked over its time bins).
    pub std_error: f64,
    /// kT at its middle (energy).
    pub kt: f64,
}

/// Enskog consistency check Z − 1 = (√π/4) ω τ0 (physics.md §7).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnskogReport {
    /// Z − 1 from the pressure.
    pub z_minus_1: f64,
    /// (√π/4) ω τ0 from the collision rate.
    pub rate_term: f64,
    /// Its standard error.
    pub rate_term_std_error: f64,
    /// (Z − 1) − (√π/4) ω τ0, blocked per time bin (correlations included); 0
    /// within a few standard errors when pressure and rate agree.
    pub difference: f64,
    /// One standard error of the difference.
    pub difference_std_error: f64,
    /// The relation in words.
    pub relation: &'static str,
}

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
