//! Shared statistics of the physics tests: a mean with its standard error from the
//! blocking analysis of the test's own time series, and the one pass rule
//! |value − reference| ≤ k √(SE² + err²) with k stated at each call (issue 39
//! item 3); plus the dilute-gas wall pressure the walled-box tests compare with.
#![allow(dead_code)]

use carom_analysis::stats::{block_average, blocking};

/// Mean and standard error from the blocking analysis; when the analysis does not
/// converge (the series is short for its correlation time) the error is the larger
/// of its coarsest level's and that of 8 equal blocks, and `converged` is false.
#[derive(Debug, Clone, Copy)]
pub struct Est {
    pub mean: f64,
    pub se: f64,
    pub converged: bool,
}

pub fn est(x: &[f64]) -> Est {
    let b = blocking(x).expect("blocking analysis (≥ 16 samples)");
    let se = if b.converged {
        b.std_error
    } else {
        let e8 = block_average(x, 8).expect("8 blocks").std_error;
        b.std_error.max(e8)
    };
    Est {
        mean: b.mean,
        se,
        converged: b.converged,
    }
}

/// (value − reference) / √(se² + err²); `None` when both errors are zero.
pub fn deviation(value: f64, se: f64, reference: f64, err: f64) -> Option<f64> {
    let s = se.hypot(err);
    (s > 0.0).then(|| (value - reference) / s)
}

/// Assert |value − reference| ≤ k √(se² + err²), naming `what` and the numbers.
#[track_caller]
pub fn assert_within(what: &str, value: f64, se: f64, reference: f64, err: f64, k: f64) {
    let d = deviation(value, se, reference, err).expect("a nonzero combined error");
    assert!(
        d.abs() <= k,
        "{what}: {value} ± {se} against {reference} ± {err}: {d:+.2} combined SE \
         (allowed {k})"
    );
}

/// Z = βP A_acc/N of a dilute gas of discs of diameter 1 in a box with walls on
/// both axes (A_acc the area the centres reach, P_acc its perimeter), to second
/// order in density: the bulk 1 + 2η + 4(4/3 − √3/π)η² (second and third virial
/// coefficients) with η = Nπ/(4A_acc), plus the first-order wall term
/// −(2/3)σ³ρ P_acc/A_acc: a disc within σ of a wall has part of its excluded disc
/// outside the reachable area, so the bulk density exceeds N/A_acc (derivation in
/// tests/integration/validation/mod.rs, case 6).
pub fn dilute_wall_z(n: usize, a_acc: f64, p_acc: f64) -> f64 {
    use std::f64::consts::PI;
    let rho = n as f64 / a_acc;
    let eta = rho * PI / 4.0;
    let wall_term = -(2.0 / 3.0) * rho * p_acc / a_acc;
    1.0 + 2.0 * eta + 4.0 * (4.0 / 3.0 - 3f64.sqrt() / PI) * eta * eta + wall_term
}
