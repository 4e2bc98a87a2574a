//! The thermodynamic sections of the report (physics.md §5, §7): temperature,
//! pressure and Z, the collision rate and the Enskog check, and the drift check
//! their series share. Plain serialisable data in the run's units.

use serde::Serialize;

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
