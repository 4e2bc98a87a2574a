//! When a figure would show nothing, and why: each rule returns the one-line
//! reason [`super::write_all`] reports for the figure it does not draw.
//!
//! - A time series constant to [`FLAT`] relative (kT of an elastic run, which
//!   conserves the energy; |Ψ6| = 0 where no disc has six neighbours) is a flat
//!   line: its value is in the text report.
//! - Averages over discs (g(r), g6, S(k), Ψ6, the MSD, VACF and F_s) need at
//!   least [`MIN_DISCS`] discs: with fewer they are a handful of trajectories.
//! - F_s(k*, τ) that is below 1/e already at the first lag decayed between
//!   snapshots: τ_α is shorter than their spacing and the curve is flat at 0.

use carom_analysis::{BondOrderReport, DynamicsReport, Report};

/// The relative spread below which a series is flat.
pub(super) const FLAT: f64 = 1e-9;
/// The fewest discs an average over discs is drawn for.
pub(super) const MIN_DISCS: usize = 10;

/// Whether the values are all equal to [`FLAT`] relative (or all zero).
fn flat(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    (hi - lo <= FLAT * hi.abs().max(lo.abs())).then_some(hi)
}

/// kT against time when it is constant.
pub(super) fn temperature(r: &Report) -> Option<String> {
    let kt = flat(r.temperature.series.iter().map(|p| p[1]))?;
    let why = if r.elastic {
        "an elastic run conserves the energy"
    } else {
        "it does not change"
    };
    Some(format!(
        "kT = {kt:.6} at every record to {FLAT:e} relative ({why}): a flat line"
    ))
}

/// Averages over discs with fewer than [`MIN_DISCS`] discs.
pub(super) fn few_discs(r: &Report) -> Option<String> {
    (r.n < MIN_DISCS).then(|| {
        format!(
            "N = {} discs: fewer than {MIN_DISCS}, too few for an average over discs",
            r.n
        )
    })
}

/// |Ψ6| constant (zero when no disc has neighbours).
pub(super) fn psi6(b: &BondOrderReport) -> Option<String> {
    let v = flat(b.series.iter().map(|p| p[1]))?;
    Some(format!("|Ψ6| = {v:.4} in every snapshot: a flat line"))
}

/// F_s below 1/e at the first positive lag for every species.
pub(super) fn self_scattering(d: &DynamicsReport) -> Option<String> {
    let e = (-1.0f64).exp();
    let mut first = f64::NAN;
    for s in &d.species {
        let (lag, fs) = s
            .lag
            .iter()
            .zip(&s.fs)
            .find(|(t, f)| **t > 0.0 && f.is_finite())?;
        if *fs >= e {
            return None;
        }
        first = *lag;
    }
    Some(format!(
        "F_s(k*, τ) < 1/e already at the first lag τ = {first:.4}: τ_α is shorter \
         than the snapshot spacing and the curve is flat at 0"
    ))
}
