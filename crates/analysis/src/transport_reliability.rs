//! When a transport coefficient can be trusted (physics.md §14.6), and the
//! standard error of a mean over time segments. Two rules, each defined here once:
//!
//! - the window: τ_a ≥ 10 t_c and τ_b ≥ 100 t_c ([`TRANSPORT_WINDOW`]); a run too
//!   short for it gets [τ_b/10, τ_b] and the value is flagged;
//! - levelling off: the running coefficient X(τ) (D(τ), or the Green–Kubo running
//!   integral of η and λ) averaged over the window's two halves in ln τ, X₁ and
//!   X₂, gives the log-slope s = (X₂ − X₁)/(X̄ · ½ ln(τ_b/τ_a)); the value is
//!   flagged when |s| > [`LEVELLING_SLOPE`] and |X₂ − X₁| exceeds two standard
//!   errors of the difference. An integrand not yet decayed gives s ≈ 1; the 2D
//!   long-time tail alone gives s = (kT/m) A/D ≈ 0.16 at φ = 0.5, less when dilute.
//!
//! Errors of a mean over S segments are the segments' spread s/√S times Student's
//! t for S − 1 degrees of freedom at one standard deviation ([`student_t_1sigma`]).

use super::pair_correlation::mean_se;
use super::transport_report::{Estimate, Reliability};

/// The documented lag window, in collision times t_c.
pub const TRANSPORT_WINDOW: [f64; 2] = [10.0, 100.0];
/// Largest |d ln X / d ln τ| over the window for a levelled-off running coefficient.
pub const LEVELLING_SLOPE: f64 = 0.25;
/// A window edge on the lag grid may fall this far short of the documented one
/// (the grid has 10 points per decade, steps of 26 %).
const GRID_SLACK: f64 = 0.88;

/// Student's t quantile at the one-sigma level (two-sided 68.27 %) for `dof`
/// degrees of freedom, by its expansion in 1/ν about the normal quantile z = 1
/// (Abramowitz & Stegun 26.7.5): t ≈ 1 + 1/(2ν) + 1/(4ν²) + 1/(16ν³); within
/// 0.1 % for ν ≥ 2 (ν = 9: 1.0588, exact 1.0590), 1.4 % at ν = 1. NaN for ν = 0.
pub fn student_t_1sigma(dof: usize) -> f64 {
    if dof == 0 {
        return f64::NAN;
    }
    let nu = dof as f64;
    1.0 + 1.0 / (2.0 * nu) + 1.0 / (4.0 * nu * nu) + 1.0 / (16.0 * nu * nu * nu)
}

/// The standard error of the mean of `values` (the finite ones), Student-t
/// corrected: s/√n · t_{n−1}; NaN with fewer than two.
pub fn segment_std_error(values: &[f64]) -> f64 {
    let v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.len() < 2 {
        return f64::NAN;
    }
    mean_se(&v).1 * student_t_1sigma(v.len() - 1)
}

/// The running coefficient over the window's halves: X₁, X₂ (over the whole
/// run's data), the error of X₂ − X₁ (over segments) and the window mean X̄.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Halves {
    pub(super) first: f64,
    pub(super) second: f64,
    pub(super) difference_std_error: f64,
    pub(super) mean: f64,
}

/// The verdict on a value over the window [τ_a, τ_b] = `window_tc` (in t_c),
/// with the halves of its running coefficient when there is one.
pub(super) fn judge(window_tc: [f64; 2], halves: Option<Halves>) -> Reliability {
    let mut why = Vec::new();
    let [a, b] = window_tc;
    let [da, db] = TRANSPORT_WINDOW;
    if a < GRID_SLACK * da || b < GRID_SLACK * db {
        why.push(format!(
            "window [{a:.1}, {b:.1}] t_c is shorter than the documented [{da}, {db}] t_c"
        ));
    }
    if let Some(h) = halves {
        let slope = (h.second - h.first) / (h.mean * 0.5 * (b / a).ln());
        let significant = (h.second - h.first).abs() > 2.0 * h.difference_std_error;
        if slope.abs() > LEVELLING_SLOPE && significant {
            why.push(format!(
                "running value has not levelled off: d ln X/d ln τ = {slope:.2} over the window \
                 (limit {LEVELLING_SLOPE})"
            ));
        }
    }
    Reliability {
        reliable: why.is_empty(),
        why,
    }
}

/// `value` with the Student-t corrected error of its per-segment values.
pub(super) fn estimate(value: f64, per_segment: &[f64]) -> Estimate {
    Estimate {
        value,
        std_error: segment_std_error(per_segment),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tabulated t quantiles at 68.27 % (two-sided): ν = 2: 1.3213, 4: 1.1417,
    /// 9: 1.0590, 30: 1.0170; the expansion is within 0.1 % of them.
    #[test]
    fn student_t_against_the_table() {
        for (nu, t) in [(2, 1.3213), (4, 1.1417), (9, 1.0590), (30, 1.0170)] {
            assert!((student_t_1sigma(nu) / t - 1.0).abs() < 1e-3, "{nu}");
        }
        // Two values 1 and 3: s = √2, s/√2 = 1, times t₁.
        assert!((segment_std_error(&[1.0, 3.0]) - student_t_1sigma(1)).abs() < 1e-12);
        assert!(segment_std_error(&[1.0, f64::NAN]).is_nan());
    }

    /// A window of [10, 100] t_c with a flat running value is reliable; [1.6, 15.8]
    /// is not; a running value that doubles over the window (s ≈ 0.58 for a
    /// decade) is flagged when the rise is significant, not when it is noise.
    #[test]
    fn the_window_and_levelling_off_rules() {
        let flat = Halves {
            first: 1.0,
            second: 1.01,
            difference_std_error: 0.01,
            mean: 1.0,
        };
        assert!(judge([10.0, 100.0], Some(flat)).reliable);
        assert!(judge([9.5, 95.0], None).reliable);
        let short = judge([1.6, 15.8], Some(flat));
        assert!(!short.reliable && short.why.len() == 1);
        let rising = Halves {
            first: 0.8,
            second: 1.4,
            difference_std_error: 0.05,
            mean: 1.1,
        };
        let r = judge([10.0, 100.0], Some(rising));
        assert!(!r.reliable && r.why[0].contains("levelled"));
        let noisy = Halves {
            difference_std_error: 0.4,
            ..rising
        };
        assert!(judge([10.0, 100.0], Some(noisy)).reliable);
    }
}
