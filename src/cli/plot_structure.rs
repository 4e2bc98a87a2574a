//! Figures of the structure (physics.md §10–§11), distances in σ ([`Units`]):
//! g_ab(r) per species pair with one standard error as a band, its contact
//! value g(σ⁺) ± SE and the ideal gas g = 1 (`pair_correlation`); |Ψ6| against
//! time with the mean ± one standard error (`bond_order`); g6(r) on log–log axes
//! with its band, both fitted decays and the hexatic bound r^(−1/4) (`g6`); and
//! S(k) against kσ with error bars and S = 1 (`structure_factor`).

use carom_analysis::{
    BondCorrelationReport, BondOrderReport, PairCorrelationReport, StructureFactorReport,
};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{axes, band, bars, dash_key, legend, line_key, log_axes};
use super::{range, top, DrawResult, Units};

/// The ideal gas's value (g = 1, S = 1) as a dashed grey line over [0, x1].
fn ideal_gas<'a, DB: DrawingBackend + 'a>(
    chart: &mut super::axes::Chart<'a, DB>,
    x1: f64,
    label: &str,
) -> DrawResult<DB> {
    let grey = BLACK.mix(0.6).stroke_width(1);
    chart
        .draw_series(DashedLineSeries::new([(0.0, 1.0), (x1, 1.0)], 6, 4, grey))?
        .label(label)
        .legend(dash_key(grey));
    Ok(())
}

/// g_ab(r) of every species pair against r/σ with one standard error as a
/// band, the contact value g(σ_ab⁺) ± SE as a dot with a bar at σ_ab.
pub(super) fn draw_g<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    pc: &PairCorrelationReport,
    u: &Units,
) -> DrawResult<DB> {
    let s = 1.0 / u.sigma;
    let x1 = pc.r_max * s;
    let y1 = top(pc
        .pairs
        .iter()
        .flat_map(|p| p.g.iter().zip(&p.std_error).map(|(g, e)| g + e.max(0.0))));
    let caption = match &pc.contact_theorem {
        Some(c) => format!(
            "g(r): contact theorem Z = {:.4} ± {:.4}, virial Z = {:.4} ± {:.4}",
            c.z_structure, c.z_structure_std_error, c.z_virial, c.z_virial_std_error
        ),
        None => format!("pair correlation g(r), {} snapshots", pc.snapshots),
    };
    let axis = (u.r_desc(), "pair correlation g(r) (dimensionless)");
    let mut chart = axes(root, &caption, (&axis.0, axis.1), 0.0..x1, 0.0..y1)?;
    ideal_gas(&mut chart, x1, "ideal gas g = 1")?;
    let mut data = Vec::new();
    for (k, p) in pc.pairs.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        let pts: Vec<(f64, f64, f64)> =
            pc.r.iter()
                .zip(p.g.iter().zip(&p.std_error))
                .filter(|(_, (g, _))| g.is_finite())
                .map(|(&r, (&g, &e))| (r * s, g, e))
                .collect();
        let label = (k == 0).then_some("± one standard error");
        band(&mut chart, pts.iter().copied(), colour, label)?;
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|p| (p.0, p.1)),
                colour.stroke_width(2),
            ))?
            .label(format!("species {}–{}", p.a, p.b))
            .legend(line_key(colour.stroke_width(2)));
        data.extend(pts.iter().map(|p| (p.0, p.1)));
        if let Some(c) = &p.contact {
            let at = (p.sigma * s, c.value);
            if let Some(se) = c.std_error {
                bars(
                    &mut chart,
                    std::iter::once((at.0, at.1, se)),
                    BLACK.stroke_width(2),
                    None,
                )?;
            }
            let value = match c.std_error {
                Some(se) => format!("{:.4} ± {se:.4}", c.value),
                None => format!("{:.4} (no error estimate)", c.value),
            };
            chart
                .draw_series(std::iter::once(Circle::new(at, 5, colour.filled())))?
                .label(format!("contact g(σ⁺) = {value} ({}–{})", p.a, p.b))
                .legend(super::axes::dot_key(colour.filled(), 5));
            data.push(at);
        }
    }
    legend(&mut chart, &data)
}

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
    let mean = [
        (x0, b.global, b.global_std_error),
        (x1, b.global, b.global_std_error),
    ];
    band(
        &mut chart,
        mean.into_iter(),
        BLACK.to_rgba(),
        Some("± one standard error of the mean"),
    )?;
    chart
        .draw_series(LineSeries::new(
            [(x0, b.global), (x1, b.global)],
            BLACK.stroke_width(2),
        ))?
        .label(format!("mean |Ψ6| = {:.4}", b.global))
        .legend(line_key(BLACK.stroke_width(2)));
    let pts: Vec<(f64, f64)> = b.series.iter().map(|p| (p[0], p[1])).collect();
    chart
        .draw_series(LineSeries::new(pts.iter().copied(), BLUE.stroke_width(2)))?
        .label("|Ψ6| of each snapshot")
        .legend(line_key(BLUE.stroke_width(2)));
    legend(&mut chart, &pts)
}

/// g6(r) against r/σ on log–log axes (positive values) with one standard
/// error as a band, the fitted power law and exponential, and r^(−1/4)
/// through the first point for the hexatic bound.
pub(super) fn draw_g6<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    g: &BondCorrelationReport,
    u: &Units,
) -> DrawResult<DB> {
    let s = 1.0 / u.sigma;
    let pts: Vec<(f64, f64, f64)> =
        g.r.iter()
            .zip(g.g6.iter().zip(&g.std_error))
            .filter(|(_, (v, _))| v.is_finite() && **v > 0.0)
            .map(|(&r, (&v, &e))| (r * s, v, e))
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
    let r_desc = u.r_desc();
    let axis = (r_desc.as_str(), "g6(r) (dimensionless)");
    let mut chart = log_axes(root, &caption, axis, (x0, x1), (y0, y1))?;
    band(
        &mut chart,
        pts.iter().copied(),
        BLUE.to_rgba(),
        Some("± one standard error"),
    )?;
    chart
        .draw_series(LineSeries::new(
            pts.iter().map(|p| (p.0, p.1)),
            BLUE.stroke_width(2),
        ))?
        .label("g6(r)")
        .legend(line_key(BLUE.stroke_width(2)));
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
        .legend(dash_key(BLACK.stroke_width(2)));
    if let (Some([eta, _]), Some([xi, _])) = (g.eta6, g.xi6) {
        let power = curve(&|r: f64| first.1 * (r / first.0).powf(-eta));
        chart
            .draw_series(LineSeries::new(power, RED.stroke_width(1)))?
            .label(format!("power law r^(−{eta:.3})"))
            .legend(line_key(RED.stroke_width(1)));
        // ξ6 is in length: in σ it is ξ6/σ.
        let expo = curve(&|r: f64| first.1 * (-(r - first.0) / (xi * s)).exp());
        chart
            .draw_series(LineSeries::new(expo, GREEN.stroke_width(1)))?
            .label(format!("exponential e^(−r/ξ6), ξ6 = {xi:.3}"))
            .legend(line_key(GREEN.stroke_width(1)));
    }
    let data: Vec<(f64, f64)> = pts.iter().map(|p| (p.0, p.1)).collect();
    legend(&mut chart, &data)
}

/// S(k) against kσ with one-standard-error bars, and S = 1 (the ideal gas).
pub(super) fn draw_sk<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    f: &StructureFactorReport,
    u: &Units,
) -> DrawResult<DB> {
    let s = u.sigma;
    let x1 = f.k.last().copied().unwrap_or(1.0) * s;
    let y1 = top(f.s.iter().zip(&f.std_error).map(|(s, e)| s + e.max(0.0)));
    let peak = match (f.peak_s, f.peak_k) {
        (Some(s), Some(k)) => format!("first peak {s:.3} at k = {k:.3}"),
        _ => "no first peak in range".to_string(),
    };
    let caption = format!(
        "S(k): {peak}; ψ_T = {:.3} ± {:.3}",
        f.translational, f.translational_std_error
    );
    let x_desc = if u.mixture {
        format!("wave number kσ (σ = {} the diameter of species 0)", u.sigma)
    } else {
        format!("wave number kσ (σ = {} the disc diameter)", u.sigma)
    };
    let axis = (x_desc.as_str(), "structure factor S(k) (dimensionless)");
    let mut chart = axes(root, &caption, axis, 0.0..x1, 0.0..y1)?;
    ideal_gas(&mut chart, x1, "ideal gas S = 1")?;
    let pts: Vec<(f64, f64, f64)> =
        f.k.iter()
            .zip(f.s.iter().zip(&f.std_error))
            .map(|(&k, (&v, &e))| (k * s, v, e))
            .collect();
    bars(
        &mut chart,
        pts.iter().copied(),
        BLUE.mix(0.5).stroke_width(1),
        Some("± one standard error"),
    )?;
    chart
        .draw_series(LineSeries::new(
            pts.iter().map(|p| (p.0, p.1)),
            BLUE.stroke_width(2),
        ))?
        .label(format!("S(k), {} snapshots", f.snapshots))
        .legend(line_key(BLUE.stroke_width(2)));
    let data: Vec<(f64, f64)> = pts.iter().map(|p| (p.0, p.1)).collect();
    legend(&mut chart, &data)
}
