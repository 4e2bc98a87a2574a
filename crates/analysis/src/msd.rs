//! The self-diffusion coefficient from the mean-square displacement (physics.md
//! §13): in 2D MSD(τ) = ⟨|u_i(t₀ + τ) − u_i(t₀)|²⟩ → 4Dτ + c at long lags, so D is
//! a quarter of the slope of a straight line fitted to MSD against τ, weighted by
//! 1/SE², over a window [t_a, t_b]: by default from [`D_WINDOW_COLLISIONS`] mean
//! collision times per disc (a tenth of the longest lag when the rate is
//! unknown) to half the longest lag with data from ≥ 3 time segments. The lags
//! share origins, so the fit's own error is meaningless; the error of D is the
//! spread of the same fit done segment by segment, widened for the overlap of
//! displacements longer than a segment ([`overlap_factor`]); the choice of fit is
//! part of the error: the unweighted fit over the same window is done too, and
//! SE² = SE_segments² + (D_weighted − D_unweighted)². In 2D the velocity
//! correlation decays like 1/τ and D grows like ln τ: D is a function of the
//! window and of N, and the report states both.

use super::dynamics_report::DiffusionFit;
use super::pair_correlation::mean_se;

/// Start of the default D window in mean collision times per disc.
pub const D_WINDOW_COLLISIONS: f64 = 10.0;

/// The factor by which a standard error from the spread of S segments of width
/// `w` is widened at lag `tau`: √max(1, τ/w). Displacements over τ from origins k
/// segments apart share the fraction max(0, 1 − kw/τ) of their path (exactly so
/// for independent increments), so the segment values are correlated and
/// Var(mean) ≈ (s²/S)(1 + 2Σ_k ρ_k) ≈ (s²/S) τ/w once τ ≥ w.
pub fn overlap_factor(tau: f64, w: f64) -> f64 {
    (tau / w).max(1.0).sqrt()
}

/// Least-squares line y = a + b x with weights `w`: (b, a); `None` with fewer
/// than two distinct x.
pub fn weighted_line(x: &[f64], y: &[f64], w: &[f64]) -> Option<(f64, f64)> {
    let sw: f64 = w.iter().sum();
    let xm = x.iter().zip(w).map(|(x, w)| x * w).sum::<f64>() / sw;
    let ym = y.iter().zip(w).map(|(y, w)| y * w).sum::<f64>() / sw;
    let sxx: f64 = x.iter().zip(w).map(|(x, w)| w * (x - xm).powi(2)).sum();
    let sxy: f64 = x
        .iter()
        .zip(y.iter().zip(w))
        .map(|(x, (y, w))| w * (x - xm) * (y - ym))
        .sum();
    (x.len() >= 2 && sxx > 0.0 && sxx.is_finite()).then(|| (sxy / sxx, ym - sxy / sxx * xm))
}

/// D from the MSD over the lags `lag` (increasing) with standard errors `se`,
/// and `per_segment[s][i]` the MSD of segment s at lag i (NaN without data).
/// `t_a`: the window's start when known (10 collision times); `w`: the segments'
/// width (time). The error is the spread of the segments' D widened by
/// [`overlap_factor`] at t_b, with the difference from the unweighted fit added
/// in quadrature. `None` with fewer than two lags in the window or no line
/// through them.
pub fn fit_diffusion(
    lag: &[f64],
    msd: &[f64],
    se: &[f64],
    per_segment: &[Vec<f64>],
    t_a: Option<f64>,
    w: f64,
) -> Option<DiffusionFit> {
    let with_data = |i: usize| per_segment.iter().filter(|s| s[i].is_finite()).count();
    let longest = (0..lag.len())
        .filter(|&i| with_data(i) >= 3)
        .map(|i| lag[i])
        .fold(f64::NAN, f64::max);
    let t_b = 0.5 * longest;
    let t_a = t_a.unwrap_or(0.1 * longest);
    let window: Vec<usize> = (0..lag.len())
        .filter(|&i| lag[i] > 0.0 && lag[i] >= t_a && lag[i] <= t_b && msd[i].is_finite())
        .collect();
    if window.len() < 2 {
        return None;
    }
    let weighted = window.iter().all(|&i| se[i].is_finite() && se[i] > 0.0);
    let w_of = |i: usize| if weighted { se[i].powi(-2) } else { 1.0 };
    let fit = |pts: &[usize], y: &dyn Fn(usize) -> f64| {
        let x: Vec<f64> = pts.iter().map(|&i| lag[i]).collect();
        let yv: Vec<f64> = pts.iter().map(|&i| y(i)).collect();
        let w: Vec<f64> = pts.iter().map(|&i| w_of(i)).collect();
        weighted_line(&x, &yv, &w)
    };
    let (slope, intercept) = fit(&window, &|i| msd[i])?;
    let x: Vec<f64> = window.iter().map(|&i| lag[i]).collect();
    let y: Vec<f64> = window.iter().map(|&i| msd[i]).collect();
    let unweighted = weighted_line(&x, &y, &vec![1.0; x.len()]).map_or(f64::NAN, |l| l.0 / 4.0);
    let per: Vec<f64> = per_segment
        .iter()
        .filter_map(|s| {
            let pts: Vec<usize> = window
                .iter()
                .copied()
                .filter(|&i| s[i].is_finite())
                .collect();
            fit(&pts, &|i| s[i]).map(|(b, _)| b / 4.0)
        })
        .collect();
    let statistical = if per.len() >= 2 {
        mean_se(&per).1 * overlap_factor(t_b, w)
    } else {
        f64::NAN
    };
    let fit_spread = (slope / 4.0 - unweighted).abs();
    Some(DiffusionFit {
        d: slope / 4.0,
        std_error: statistical.hypot(fit_spread),
        statistical_std_error: statistical,
        d_unweighted: unweighted,
        intercept,
        t_a,
        t_b,
        points: window.len(),
        segments: per.len(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points on y = 3 + 2x are fitted exactly whatever the weights; (1, 0),
    /// (2, 1), (3, 1) unweighted: x̄ = 2, ȳ = 2/3, Sxx = 2, Sxy = (−1)(−2/3) +
    /// (1)(1/3) = 1, so b = 1/2 and a = 2/3 − 1 = −1/3.
    #[test]
    fn the_weighted_line_by_hand() {
        let (b, a) = weighted_line(&[1.0, 2.0, 4.0], &[5.0, 7.0, 11.0], &[1.0, 9.0, 0.5]).unwrap();
        assert!((b - 2.0).abs() < 1e-12 && (a - 3.0).abs() < 1e-12);
        let (b, a) = weighted_line(&[1.0, 2.0, 3.0], &[0.0, 1.0, 1.0], &[1.0; 3]).unwrap();
        assert!((b - 0.5).abs() < 1e-12 && (a + 1.0 / 3.0).abs() < 1e-12);
        assert_eq!(weighted_line(&[1.0, 1.0], &[0.0, 1.0], &[1.0; 2]), None);
    }

    /// MSD = 4·0.25·τ + 1 at τ = 0 … 10 exactly, segment s offset by s (slope
    /// the same): D = 0.25 with zero spread. Segments 0–2 have data to τ = 10, the
    /// rest to τ = 6: longest with ≥ 3 segments 10, window [1, 5] (a tenth and a
    /// half), 5 lags; with t_a = 2.5 the lags 3, 4, 5.
    #[test]
    fn the_window_and_d_of_a_straight_msd() {
        let lag: Vec<f64> = (0..=10).map(|i| i as f64).collect();
        let msd: Vec<f64> = lag.iter().map(|t| t + 1.0).collect();
        let per: Vec<Vec<f64>> = (0..10)
            .map(|s| {
                lag.iter()
                    .map(|&t| {
                        if s < 3 || t <= 6.0 {
                            t + s as f64
                        } else {
                            f64::NAN
                        }
                    })
                    .collect()
            })
            .collect();
        let se = vec![0.1; 11];
        let f = fit_diffusion(&lag, &msd, &se, &per, None, 1.0).unwrap();
        assert!((f.d - 0.25).abs() < 1e-12 && (f.intercept - 1.0).abs() < 1e-12);
        assert_eq!((f.t_a, f.t_b, f.points, f.segments), (1.0, 5.0, 5, 10));
        assert!(f.std_error.abs() < 1e-12);
        assert!((f.d_unweighted - 0.25).abs() < 1e-12);
        let f = fit_diffusion(&lag, &msd, &se, &per, Some(2.5), 1.0).unwrap();
        assert_eq!(f.points, 3);
        assert!(fit_diffusion(&lag, &msd, &se, &per, Some(4.5), 1.0).is_none());
    }
}
