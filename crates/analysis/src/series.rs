//! Time series as the report shows them: means of per-bin series with a blocked
//! standard error (the blocking analysis when it converges, else 16 blocks), and
//! series thinned or coarsened to a few thousand points for the JSON and figures.

use super::pair_correlation::mean_se;
use super::stats::{block_average, blocking, StatsError};
use super::thermo_report::DriftReport;

/// A blocked estimate: the automatic blocking analysis when it converges, else 16
/// equal blocks.
pub(super) struct Blocked {
    pub(super) mean: f64,
    pub(super) std_error: f64,
    pub(super) blocks: usize,
    pub(super) block_len: usize,
    pub(super) converged: bool,
}

pub(super) fn blocked(x: &[f64]) -> Result<Blocked, StatsError> {
    let b = blocking(x)?;
    if b.converged {
        let lv = b.levels[b.chosen];
        return Ok(Blocked {
            mean: b.mean,
            std_error: b.std_error,
            blocks: lv.blocks,
            block_len: lv.block_len,
            converged: true,
        });
    }
    let e = block_average(x, 16)?;
    Ok(Blocked {
        mean: b.mean,
        std_error: e.std_error,
        blocks: e.blocks,
        block_len: e.block_len,
        converged: false,
    })
}

/// Most points in a time series of the report.
pub(super) const MAX_SERIES: usize = 2000;

/// At most `max` points of `s`, evenly spaced in index, always keeping the last.
pub(super) fn subsample(s: &[(f64, f64)], max: usize) -> Vec<[f64; 2]> {
    let step = s.len().div_ceil(max).max(1);
    let mut out: Vec<[f64; 2]> = s.iter().step_by(step).map(|&(t, v)| [t, v]).collect();
    if let Some(&(t, v)) = s.last() {
        if out.last().is_some_and(|p| p[0] != t) {
            out.push([t, v]);
        }
    }
    out
}

/// Averages of `x` over `parts` consecutive groups, with their mid times.
pub(super) fn coarse_series(x: &[f64], t0: f64, dt: f64, parts: usize) -> Vec<[f64; 2]> {
    let len = (x.len() / parts).max(1);
    x.chunks(len)
        .enumerate()
        .map(|(k, c)| {
            let t = t0 + (k * len) as f64 * dt + 0.5 * c.len() as f64 * dt;
            [t, c.iter().sum::<f64>() / c.len() as f64]
        })
        .collect()
}

/// A series counts as drifting when the means of its two halves differ by more
/// than this many combined standard errors (physics.md §5, drift).
pub const DRIFT_STD_ERRORS: f64 = 3.0;

/// The drift check of a per-bin series: the blocked means of its first and second
/// halves and their difference in combined standard errors
/// (m₂ − m₁)/√(s₁² + s₂²). A half too short to block (< 16 values, e.g. a few
/// snapshots) takes its values as independent, s = std/√n: snapshots are usually
/// further apart than the correlation time, and a series that rises across the
/// window must not go unchecked. `None` below 2 values per half.
pub(super) fn drift(x: &[f64]) -> Option<DriftReport> {
    let (a, b) = x.split_at(x.len() / 2);
    let half = |h: &[f64]| match blocked(h) {
        Ok(b) => Some((b.mean, b.std_error)),
        Err(_) => (h.len() >= 2).then(|| mean_se(h)),
    };
    let ((m1, s1), (m2, s2)) = (half(a)?, half(b)?);
    let se = s1.hypot(s2);
    let d = if se > 0.0 {
        (m2 - m1) / se
    } else if m2 == m1 {
        0.0
    } else {
        f64::INFINITY.copysign(m2 - m1)
    };
    Some(DriftReport {
        first_half: m1,
        first_half_std_error: s1,
        second_half: m2,
        second_half_std_error: s2,
        difference_std_errors: d,
        drifting: d.abs() > DRIFT_STD_ERRORS,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sixteen values about `mean` whose blocked standard error is exactly `se`
    /// (an integer). Pairs of deviations ±a·se with a = 6, 6, 4, 4, 2, 2, 2, 2,
    /// the sign of each pair flipped from the last: every pair averages to the
    /// mean, so the blocking analysis' coarser levels have no variance and its
    /// statistic is the first level's, n (γ/σ²)² with σ² = 2·120 se²/16 = 15 se²
    /// and 16 γ = (−120 + 96) se² (within pairs −Σa², between pairs
    /// +Σ a_i a_{i+1}): 16 · 0.1² = 0.16, far below the χ²(3) 99 % quantile
    /// 11.3. So the first level is taken, SE = √(σ²/(n − 1)) = √(15 se²/15) = se.
    fn half(mean: f64, se: f64) -> Vec<f64> {
        let mut x = Vec::new();
        for (k, a) in [6.0, 6.0, 4.0, 4.0, 2.0, 2.0, 2.0, 2.0]
            .into_iter()
            .enumerate()
        {
            let d = if k % 2 == 0 { a * se } else { -a * se };
            x.extend([mean + d, mean - d]);
        }
        x
    }

    #[test]
    fn the_constructed_half_has_the_standard_error_it_was_built_for() {
        let b = blocked(&half(100.0, 3.0)).unwrap();
        assert!(b.converged);
        assert_eq!(
            (b.mean, b.std_error, b.blocks, b.block_len),
            (100.0, 3.0, 16, 1)
        );
    }

    /// (5.13) with halves of means 100 and 115 and errors 3 and 4:
    /// d = 15/√(9 + 16) = 3 exactly, on the threshold, which is not drifting
    /// (|d| > 3 is); means 130 and 100 give d = ±6, drifting either way.
    #[test]
    fn drift_is_the_difference_of_the_halves_in_combined_standard_errors() {
        let series = |m1: f64, m2: f64| [half(m1, 3.0), half(m2, 4.0)].concat();
        let d = drift(&series(100.0, 115.0)).unwrap();
        assert_eq!(
            (
                d.first_half,
                d.first_half_std_error,
                d.second_half,
                d.second_half_std_error
            ),
            (100.0, 3.0, 115.0, 4.0)
        );
        assert_eq!(d.difference_std_errors, 3.0);
        assert!(!d.drifting);
        let d = drift(&series(100.0, 130.0)).unwrap();
        assert_eq!(d.difference_std_errors, 6.0);
        assert!(d.drifting);
        let d = drift(&series(130.0, 100.0)).unwrap();
        assert_eq!(d.difference_std_errors, -6.0);
        assert!(d.drifting);
        // One value per half is too few to check.
        assert_eq!(drift(&[1.0, 2.0]), None);
    }

    /// Halves too short to block (10 values each, as 20 snapshots give) use
    /// s/√n: 0, 1, …, 9 then 10, …, 19 have means 4.5 and 14.5, each with
    /// s² = 55/6 and SE √(55/60), so d = 10/√(2·55/60) = 7.385…, drifting; a
    /// flat pair of halves (alternating 0, 1) is not.
    #[test]
    fn short_halves_are_checked_with_independent_errors() {
        let ramp: Vec<f64> = (0..20).map(f64::from).collect();
        let d = drift(&ramp).unwrap();
        assert_eq!((d.first_half, d.second_half), (4.5, 14.5));
        let expect = 10.0 / (2.0 * 55.0 / 60.0f64).sqrt();
        assert!((d.difference_std_errors - expect).abs() < 1e-12, "{d:?}");
        assert!(d.drifting);
        let flat: Vec<f64> = (0..20).map(|k| f64::from(k % 2)).collect();
        assert!(!drift(&flat).unwrap().drifting);
    }

    /// Constant halves have no error: equal means are no drift (d = 0), unequal
    /// ones are infinitely many errors apart, with the sign of m₂ − m₁.
    #[test]
    fn constant_halves_drift_only_when_their_values_differ() {
        let steps = |m1: f64, m2: f64| [vec![m1; 16], vec![m2; 16]].concat();
        let d = drift(&steps(2.5, 2.5)).unwrap();
        assert_eq!((d.difference_std_errors, d.drifting), (0.0, false));
        let d = drift(&steps(5.0, 2.0)).unwrap();
        assert_eq!(
            (d.difference_std_errors, d.drifting),
            (f64::NEG_INFINITY, true)
        );
        let d = drift(&steps(2.0, 5.0)).unwrap();
        assert_eq!((d.difference_std_errors, d.drifting), (f64::INFINITY, true));
    }

    /// Five points at most two: every third (step ⌈5/2⌉ = 3), points 0 and 3, and
    /// the last, 4, added; five at most three: step 2, points 0, 2, 4, the last
    /// already there and not repeated.
    #[test]
    fn subsampling_keeps_evenly_spaced_points_and_the_last_once() {
        let s: Vec<(f64, f64)> = (0..5).map(|k| (k as f64 * 0.5, (k * k) as f64)).collect();
        assert_eq!(subsample(&s, 2), vec![[0.0, 0.0], [1.5, 9.0], [2.0, 16.0]]);
        assert_eq!(subsample(&s, 3), vec![[0.0, 0.0], [1.0, 4.0], [2.0, 16.0]]);
        assert_eq!(subsample(&s, 10).len(), 5);
        assert!(subsample(&[], 3).is_empty());
    }

    /// Seven values from t0 = 10 in steps dt = 0.5 in 3 parts: groups of
    /// ⌊7/3⌋ = 2 and the remainder alone, each at its mid time
    /// t0 + (first index + len/2)·dt: 10.5, 11.5, 12.5 and 10 + 6.5·0.5 = 13.25,
    /// with means (1+3)/2, (2+6)/2, (5+5)/2, 8.
    #[test]
    fn a_coarse_series_averages_groups_at_their_mid_times() {
        let x = [1.0, 3.0, 2.0, 6.0, 5.0, 5.0, 8.0];
        assert_eq!(
            coarse_series(&x, 10.0, 0.5, 3),
            vec![[10.5, 2.0], [11.5, 4.0], [12.5, 5.0], [13.25, 8.0]]
        );
        // More parts than values: one value per group.
        assert_eq!(
            coarse_series(&x[..2], 0.0, 2.0, 5),
            vec![[1.0, 1.0], [3.0, 3.0]]
        );
    }
}
