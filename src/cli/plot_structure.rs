//! Figures of the structure (physics.md §11): |Ψ6| against time with its mean
//! (`bond_order`), g6(r) on log–log axes with both fitted decays and the hexatic
//! bound r^(−1/4) (`g6`), and S(k) with error bars (`structure_factor`).

use carom::analysis::{BondCorrelationReport, BondOrderReport, StructureFactorReport};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{axes, legend, log_axes, log_legend, range, top, DrawResult};

/// |Ψ6| of every snapshot against time, with the mean ± one standard error.
pub(super) fn draw_bond_order<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    b: &BondOrderReport,
) -> DrawResult<DB> {
    let (x0, x1) = range(b.series.iter().map(|p| p[0]));
    let y1 = top(b.series.iter().map(|p| p[1]).chain([b.global]));
    let caption = format!(
        "global bond order |Ψ6| = {:.4} ± {:.4}, χ6 = {:.4}",
        b.global, b.global_std_error, b.susceptibility
    );
    let axis = ("time t (time)", "|Ψ6| (dimensionless)");
    let mut chart = axes(root, &caption, axis, x0..x1, 0.0..y1)?;
    chart
        .draw_series(LineSeries::new(
            b.series.iter().map(|p| (p[0], p[1])),
            BLUE.stroke_width(2),
        ))?
        .label("|Ψ6| of each snapshot")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLUE.stroke_width(2)));
    for (v, style) in [
        (b.global, BLACK.stroke_width(2)),
        (
            b.global - b.global_std_error,
            BLACK.mix(0.4).stroke_width(1),
        ),
        (
            b.global + b.global_std_error,
            BLACK.mix(0.4).stroke_width(1),
        ),
    ] {
        chart.draw_series(LineSeries::new([(x0, v), (x1, v)], style))?;
    }
    legend(&mut chart)
}

/// g6(r) on log–log axes (positive values), the fitted power law and
/// exponential, and r^(−1/4) through the first point for the hexatic bound.
pub(super) fn draw_g6<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    g: &BondCorrelationReport,
) -> DrawResult<DB> {
    let pts: Vec<(f64, f64)> =
        g.r.iter()
            .zip(&g.g6)
            .filter(|(_, v)| v.is_finite() && **v > 0.0)
            .map(|(&r, &v)| (r, v))
            .collect();
    let (Some(&first), Some(&last)) = (pts.first(), pts.last()) else {
        return Ok(());
    };
    let (x0, x1) = (first.0, last.0.max(first.0 * 1.01));
    let y0 = pts
        .iter()
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min)
        .max(1e-4);
    let y1 = pts.iter().map(|p| p.1).fold(0.0, f64::max).max(y0 * 1.01);
    let caption = match (g.eta6, g.xi6) {
        (Some([eta, e]), Some([xi, f])) => format!(
            "g6(r): η6 = {eta:.3} ± {e:.3}, ξ6 = {xi:.3} ± {f:.3} ({} fits better)",
            g.decay.unwrap_or("neither")
        ),
        _ => format!("g6(r), {} snapshots (no decay fit)", g.snapshots),
    };
    let axis = ("distance r (length)", "g6(r) (dimensionless)");
    let mut chart = log_axes(root, &caption, axis, (x0, x1), (y0, y1))?;
    chart
        .draw_series(LineSeries::new(pts.iter().copied(), BLUE.stroke_width(2)))?
        .label("g6(r)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLUE.stroke_width(2)));
    let n = 100;
    let curve = |f: &dyn Fn(f64) -> f64| -> Vec<(f64, f64)> {
        (0..=n)
            .map(|k| x0 * (x1 / x0).powf(k as f64 / n as f64))
            .map(|r| (r, f(r)))
            .filter(|p| p.1 > 0.8 * y0 && p.1 < 1.25 * y1)
            .collect()
    };
    let bound = curve(&|r: f64| first.1 * (r / first.0).powf(-0.25));
    chart
        .draw_series(DashedLineSeries::new(bound, 8, 5, BLACK.stroke_width(2)))?
        .label("r^(−1/4): the slowest decay of the hexatic phase")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK.stroke_width(2)));
    if let (Some([eta, _]), Some([xi, _])) = (g.eta6, g.xi6) {
        let power = curve(&|r: f64| first.1 * (r / first.0).powf(-eta));
        chart
            .draw_series(LineSeries::new(power, RED.stroke_width(1)))?
            .label(format!("power law r^(−{eta:.3})"))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], RED));
        let expo = curve(&|r: f64| first.1 * (-(r - first.0) / xi).exp());
        chart
            .draw_series(LineSeries::new(expo, GREEN.stroke_width(1)))?
            .label(format!("exponential e^(−r/{xi:.3})"))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], GREEN));
    }
    log_legend(&mut chart)
}

/// S(k) with one-standard-error bars, and S = 1 (the ideal gas).
pub(super) fn draw_sk<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    f: &StructureFactorReport,
) -> DrawResult<DB> {
    let x1 = f.k.last().copied().unwrap_or(1.0);
    let y1 = top(f.s.iter().zip(&f.std_error).map(|(s, e)| s + e.max(0.0)));
    let peak = match (f.peak_s, f.peak_k) {
        (Some(s), Some(k)) => format!("first peak {s:.3} at k = {k:.3}"),
        _ => "no first peak in range".to_string(),
    };
    let caption = format!(
        "S(k): {peak}; ψ_T = {:.3} ± {:.3}",
        f.translational, f.translational_std_error
    );
    let axis = (
        "wave number k (1/length)",
        "structure factor S(k) (dimensionless)",
    );
    let mut chart = axes(root, &caption, axis, 0.0..x1, 0.0..y1)?;
    chart.draw_series(LineSeries::new([(0.0, 1.0), (x1, 1.0)], BLACK.mix(0.4)))?;
    chart
        .draw_series(LineSeries::new(
            f.k.iter().zip(&f.s).map(|(&k, &s)| (k, s)),
            BLUE.stroke_width(2),
        ))?
        .label(format!("S(k), {} snapshots", f.snapshots))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLUE.stroke_width(2)));
    chart.draw_series(
        f.k.iter()
            .zip(f.s.iter().zip(&f.std_error))
            .filter(|(_, (_, e))| e.is_finite())
            .map(|(&k, (&s, &e))| PathElement::new(vec![(k, s - e), (k, s + e)], BLUE.mix(0.5))),
    )?;
    legend(&mut chart)
}
