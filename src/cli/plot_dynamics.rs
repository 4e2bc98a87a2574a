//! Figures of the single-disc dynamics (physics.md §13), lags in τ₀ when kT is
//! constant ([`Units`]), one standard error as a band on every curve: the MSD
//! per species on log–log axes with a slope-1 (diffusive) guide, the fit
//! 4Dτ + c and its window marked (`msd`); |C(τ)|/C(0) of the snapshot VACF on
//! log–log axes with a τ⁻¹ guide (the 2D long-time tail; `vacf`); and
//! F_s(k*, τ) against log τ with 1/e and τ_α marked (`self_scattering`).

use carom_analysis::DynamicsReport;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{band, chart, dash_key, legend, lin, line_key, log_axes, log_range};
use super::{DrawResult, Units};

/// (τ, y, SE) of every point with τ > 0 and y > 0 finite, τ scaled by `ts`.
fn positive(lag: &[f64], y: &[f64], e: &[f64], ts: f64) -> Vec<(f64, f64, f64)> {
    lag.iter()
        .zip(y.iter().zip(e.iter().chain(std::iter::repeat(&f64::NAN))))
        .filter(|(t, (v, _))| **t > 0.0 && v.is_finite() && **v > 0.0)
        .map(|(&t, (&v, &e))| (t * ts, v, e))
        .collect()
}

/// The extent of `pts` (x and y), widened when a range is empty.
fn extent(pts: &[(f64, f64, f64)]) -> Option<((f64, f64), (f64, f64))> {
    let fold = |f: &dyn Fn(&(f64, f64, f64)) -> f64| {
        pts.iter()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            })
    };
    let ((x0, x1), (y0, y1)) = (fold(&|p| p.0), fold(&|p| p.1));
    (x0.is_finite() && y0.is_finite()).then(|| ((x0, x1.max(x0 * 1.01)), (y0, y1.max(y0 * 1.01))))
}

/// (x, y) of points with errors, for placing the legend.
fn xy(pts: &[(f64, f64, f64)]) -> impl Iterator<Item = (f64, f64)> + '_ {
    pts.iter().map(|p| (p.0, p.1))
}

/// MSD(τ) per species with its band, 4Dτ + c over the fit window, τ through
/// the first point with slope 1, and the window's ends.
/// `exact`: the report has the exact replay's D, the headline one.
pub(super) fn draw_msd<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    d: &DynamicsReport,
    u: &Units,
    exact: bool,
) -> DrawResult<DB> {
    let (ts, lag_desc) = u.lag();
    let curves: Vec<Vec<(f64, f64, f64)>> = d
        .species
        .iter()
        .map(|s| positive(&s.lag, &s.msd, &s.msd_std_error, ts))
        .collect();
    let all: Vec<(f64, f64, f64)> = curves.iter().flatten().copied().collect();
    let Some(((x0, x1), (y0, y1))) = extent(&all) else {
        return Ok(());
    };
    let caption = match d.species.first().and_then(|s| s.diffusion.as_ref()) {
        Some(f) => format!(
            "snapshot MSD: D = {:.4} ± {:.4} over τ ∈ [{:.3}, {:.3}]{}",
            f.d,
            f.std_error,
            f.t_a,
            f.t_b,
            if exact {
                " (a check: D from msd_exact)"
            } else {
                ""
            }
        ),
        None => "mean-square displacement".to_owned(),
    };
    let axis = (lag_desc.as_str(), "MSD (length²)");
    let mut chart = log_axes(root, &caption, axis, (x0, x1), (y0, y1))?;
    let first = all[0];
    chart
        .draw_series(DashedLineSeries::new(
            [(x0, first.1 * x0 / first.0), (x1, first.1 * x1 / first.0)],
            8,
            5,
            BLACK.stroke_width(1),
        ))?
        .label("slope 1 (diffusion)")
        .legend(dash_key(BLACK.stroke_width(1)));
    for (k, (s, pts)) in d.species.iter().zip(&curves).enumerate() {
        let c = Palette99::pick(s.species).to_rgba();
        let label = (k == 0).then_some("± one standard error");
        band(&mut chart, pts.iter().copied(), c, label)?;
        chart
            .draw_series(LineSeries::new(xy(pts), c.stroke_width(2)))?
            .label(format!("species {} ({} discs)", s.species, s.count))
            .legend(line_key(c.stroke_width(2)));
        if let Some(f) = &s.diffusion {
            let line: Vec<(f64, f64)> = (0..=20)
                .map(|k| f.t_a * (f.t_b / f.t_a).powf(k as f64 / 20.0))
                .map(|t| (t * ts, 4.0 * f.d * t + f.intercept))
                .filter(|p| p.1 > 0.0)
                .collect();
            chart
                .draw_series(LineSeries::new(line, BLACK.stroke_width(2)))?
                .label(format!("fit 4Dτ + c, D = {:.4}", f.d))
                .legend(line_key(BLACK.stroke_width(2)));
            let grey = c.mix(0.6).stroke_width(1);
            let mut drawn = None;
            for t in [f.t_a, f.t_b] {
                drawn = Some(chart.draw_series(DashedLineSeries::new(
                    [(t * ts, 0.8 * y0), (t * ts, 1.25 * y1)],
                    3,
                    4,
                    grey,
                ))?);
            }
            if let Some(w) = drawn {
                w.label(format!("fit window [{:.3}, {:.3}]", f.t_a * ts, f.t_b * ts))
                    .legend(dash_key(grey));
            }
        }
    }
    let data: Vec<(f64, f64)> = xy(&all).collect();
    legend(&mut chart, &data)
}

/// |C(τ)|/C(0) per species with its band (three decades at most) and τ⁻¹
/// through the first lag.
pub(super) fn draw_vacf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    d: &DynamicsReport,
    u: &Units,
) -> DrawResult<DB> {
    let (ts, lag_desc) = u.lag();
    let curves: Vec<Vec<(f64, f64, f64)>> = d
        .species
        .iter()
        .map(|s| {
            let c0 = s.vacf.first().copied().unwrap_or(f64::NAN);
            let abs: Vec<f64> = s.vacf_normalised.iter().map(|c| c.abs()).collect();
            let e: Vec<f64> = s.vacf_std_error.iter().map(|e| e / c0.abs()).collect();
            positive(&s.lag, &abs, &e, ts)
        })
        .collect();
    let all: Vec<(f64, f64, f64)> = curves.iter().flatten().copied().collect();
    let Some(((x0, x1), (y0, y1))) = extent(&all) else {
        return Ok(());
    };
    // Noise crossing zero would stretch the axis over decades: three at most.
    let y0 = y0.max(1e-3 * y1);
    let axis = (lag_desc.as_str(), "|C(τ)|/C(0) (dimensionless)");
    let caption = "velocity autocorrelation at the snapshots";
    let mut chart = log_axes(root, caption, axis, (x0, x1), (y0, y1))?;
    let mut data = Vec::new();
    for (k, (s, pts)) in d.species.iter().zip(&curves).enumerate() {
        let c = Palette99::pick(s.species).to_rgba();
        let pts: Vec<(f64, f64, f64)> = pts.iter().filter(|p| p.1 >= y0).copied().collect();
        let label = (k == 0).then_some("± one standard error");
        band(&mut chart, pts.iter().copied(), c, label)?;
        chart
            .draw_series(LineSeries::new(xy(&pts), c.stroke_width(2)))?
            .label(format!("species {}", s.species))
            .legend(line_key(c.stroke_width(2)));
        data.extend(xy(&pts));
        if let Some(&(tl, cl, _)) = pts.first().filter(|_| k == 0) {
            let guide: Vec<(f64, f64)> = (0..=20)
                .map(|k| x0 * (x1 / x0).powf(k as f64 / 20.0))
                .map(|t| (t, cl * tl / t))
                .filter(|p| p.1 > 0.8 * y0 && p.1 < 1.25 * y1)
                .collect();
            chart
                .draw_series(DashedLineSeries::new(guide, 8, 5, BLACK.stroke_width(1)))?
                .label("τ⁻¹ (the 2D long-time tail)")
                .legend(dash_key(BLACK.stroke_width(1)));
        }
    }
    legend(&mut chart, &data)
}

/// F_s(k*, τ) per species against log τ with its band, the level 1/e and τ_α.
pub(super) fn draw_fs<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    d: &DynamicsReport,
    u: &Units,
) -> DrawResult<DB> {
    let (ts, lag_desc) = u.lag();
    let curves: Vec<Vec<(f64, f64, f64)>> = d
        .species
        .iter()
        .map(|s| {
            s.lag
                .iter()
                .zip(s.fs.iter().zip(&s.fs_std_error))
                .filter(|(t, (f, _))| **t > 0.0 && f.is_finite())
                .map(|(&t, (&f, &e))| (t * ts, f, e))
                .collect()
        })
        .collect();
    let all: Vec<(f64, f64, f64)> = curves.iter().flatten().copied().collect();
    let Some(((x0, x1), _)) = extent(&all) else {
        return Ok(());
    };
    let lo = all.iter().map(|p| p.1).fold(0.0, f64::min) - 0.05;
    let caption = format!(
        "self intermediate scattering at k* = {:.4} (1/length)",
        d.k_star.unwrap_or(f64::NAN)
    );
    let axis = (lag_desc.as_str(), "F_s(k*, τ) (dimensionless)");
    let mut chart = chart(root, &caption, axis, log_range(x0, x1), lin(lo..1.05))?;
    let e = (-1.0f64).exp();
    chart
        .draw_series(DashedLineSeries::new(
            [(x0, e), (x1, e)],
            8,
            5,
            BLACK.stroke_width(1),
        ))?
        .label("1/e")
        .legend(dash_key(BLACK.stroke_width(1)));
    for (k, (s, pts)) in d.species.iter().zip(&curves).enumerate() {
        let c = Palette99::pick(s.species).to_rgba();
        let label = (k == 0).then_some("± one standard error");
        band(&mut chart, pts.iter().copied(), c, label)?;
        let label = match s.tau_alpha {
            Some(t) => format!("species {}: τ_α = {t:.4} (time)", s.species),
            None => format!("species {}: no τ_α", s.species),
        };
        chart
            .draw_series(LineSeries::new(xy(pts), c.stroke_width(2)))?
            .label(label)
            .legend(line_key(c.stroke_width(2)));
        if let Some(t) = s.tau_alpha {
            let style = c.mix(0.6).stroke_width(1);
            chart
                .draw_series(DashedLineSeries::new(
                    [(t * ts, lo), (t * ts, 1.05)],
                    3,
                    4,
                    style,
                ))?
                .label(format!("τ_α of species {}", s.species))
                .legend(dash_key(style));
        }
    }
    let data: Vec<(f64, f64)> = xy(&all).collect();
    legend(&mut chart, &data)
}
