//! Time series as the report shows them: means of per-bin series with a blocked
//! standard error (the blocking analysis when it converges, else 16 blocks), and
//! series thinned or coarsened to a few thousand points for the JSON and figures.

use super::report::DriftReport;
use super::stats::{block_average, blocking, StatsError};

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
/// (m₂ − m₁)/√(s₁² + s₂²); `None` when a half is too short to block.
pub(super) fn drift(x: &[f64]) -> Option<DriftReport> {
    let (a, b) = x.split_at(x.len() / 2);
    let (a, b) = (blocked(a).ok()?, blocked(b).ok()?);
    let se = a.std_error.hypot(b.std_error);
    let d = if se > 0.0 {
        (b.mean - a.mean) / se
    } else if b.mean == a.mean {
        0.0
    } else {
        f64::INFINITY.copysign(b.mean - a.mean)
    };
    Some(DriftReport {
        first_half: a.mean,
        first_half_std_error: a.std_error,
        second_half: b.mean,
        second_half_std_error: b.std_error,
        difference_std_errors: d,
        drifting: d.abs() > DRIFT_STD_ERRORS,
    })
}
