//! Figures of the transport report (physics.md §14): the exact VACF |C(τ)/C(0)|
//! on log–log axes per species, negative values hollow, with the mode-coupling
//! tail A_MC/τ, A_MC = 1/[8π n (D + ν)], from the window's start and a τ⁻¹ slope
//! guide (`vacf_exact`); η and λ against τ on a log τ axis by Einstein–Helfand,
//! Var[ΔG(τ)]/(2 V kT^a τ), and by Green–Kubo, the running integral of the flux
//! autocorrelation, with the window shaded and Enskog's value
//! (`helfand_viscosity`, `helfand_conductivity`); the MSD per species log–log with
//! the ballistic ⟨v²⟩τ², diffusive 4Dτ and Enskog 4D_Eτ guides (`msd_exact`).
//! Lags τ > 0 only (a log axis has no 0), in τ₀ when kT is constant; the window
//! [τ_a, τ_b] is marked on every figure, and on η and λ the value read over it
//! (± one standard error) with the report's verdict on it (physics.md §14.6): an
//! unreliable value is not titled as a result.

use carom_analysis::{HelfandReport, TransportReport};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{
    bars, chart, dash_key, dot_key, fill_key, legend, lin, line_key, log_axes, log_range, Axis, Fig,
};
use super::{range, DrawResult, Units};

/// Points of a guide y = f(τ) at 100 log-spaced τ in [x0, x1], kept inside the
/// log chart's y range (0.8 y0, 1.25 y1).
fn guide(f: &dyn Fn(f64) -> f64, (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> Vec<(f64, f64)> {
    let n = 100;
    (0..=n)
        .map(|k| x0 * (x1 / x0).powf(k as f64 / n as f64))
        .map(|t| (t, f(t)))
        .filter(|p| p.1 > 0.8 * y0 && p.1 < 1.25 * y1)
        .collect()
}

/// The window [τ_a, τ_b] (already in the figure's unit) as two dotted grey
/// verticals from y0 to y1.
fn mark_window<'a, DB: DrawingBackend + 'a, X: Axis, Y: Axis>(
    chart: &mut Fig<'a, DB, X, Y>,
    [a, b]: [f64; 2],
    (y0, y1): (f64, f64),
) -> DrawResult<DB> {
    let grey = BLACK.mix(0.5).stroke_width(1);
    let mut drawn = None;
    for t in [a, b] {
        drawn = Some(chart.draw_series(DashedLineSeries::new([(t, y0), (t, y1)], 3, 4, grey))?);
    }
    if let Some(d) = drawn {
        d.label(format!("window τ ∈ [{a:.4}, {b:.4}]"))
            .legend(dash_key(grey));
    }
    Ok(())
}

/// |C(τ)/C(0)| per species (filled where C > 0, hollow where C < 0) with one
/// standard error as a bar, the mode-coupling tail A_MC/τ over τ ≥ τ_a and a
/// τ⁻¹ guide through the first point at or after τ_a.
pub(super) fn draw_vacf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    t: &TransportReport,
    u: &Units,
) -> DrawResult<DB> {
    let (ts, lag_desc) = u.lag();
    let window = t.window.map(|w| w * ts);
    let pts = |k: usize| -> Vec<(f64, f64, f64)> {
        let s = &t.species[k];
        s.lags
            .iter()
            .zip(s.vacf.iter().zip(&s.vacf_std_error))
            .filter(|(&tau, (c, _))| tau > 0.0 && c.is_finite() && **c != 0.0)
            .map(|(&tau, (&c, &e))| (tau * ts, c, e))
            .collect()
    };
    let all: Vec<(f64, f64, f64)> = (0..t.species.len()).flat_map(pts).collect();
    if all.is_empty() {
        return Ok(());
    }
    let x0 = all.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
    let x1 = all.iter().map(|p| p.0).fold(0.0, f64::max).max(x0 * 1.01);
    let y1 = all.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let y0 = all
        .iter()
        .map(|p| p.1.abs())
        .fold(f64::INFINITY, f64::min)
        .max(1e-6 * y1);
    let caption = format!(
        "exact VACF |C(τ)/C(0)|, N = {}, t_c = {:.4} (time)",
        t.n, t.collision_time
    );
    let axis = (lag_desc.as_str(), "|C(τ)/C(0)| (dimensionless)");
    let mut chart = log_axes(root, &caption, axis, (x0, x1), (y0, y1))?;
    mark_window(&mut chart, window, (0.8 * y0, 1.25 * y1))?;
    let inside = |p: &&(f64, f64, f64)| p.1.abs() > 0.8 * y0;
    for (k, s) in t.species.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        let p = pts(k);
        let label = (k == 0).then_some("± one standard error");
        let abs = p.iter().filter(inside).map(|p| (p.0, p.1.abs(), p.2));
        bars(&mut chart, abs, colour.mix(0.6).stroke_width(1), label)?;
        chart
            .draw_series(
                p.iter()
                    .filter(|p| p.1 > 0.0)
                    .filter(inside)
                    .map(|&(x, y, _)| Circle::new((x, y), 3, colour.filled())),
            )?
            .label(format!("species {}: C > 0", s.species))
            .legend(dot_key(colour.filled(), 3));
        if p.iter().any(|p| p.1 < 0.0) {
            chart
                .draw_series(
                    p.iter()
                        .filter(|p| p.1 < 0.0)
                        .filter(inside)
                        .map(|&(x, y, _)| Circle::new((x, -y), 4, colour.stroke_width(1))),
                )?
                .label(format!("species {}: C < 0 (|C| shown)", s.species))
                .legend(dot_key(colour.stroke_width(1), 4));
        }
        if let Some(a) = s.tail_amplitude_theory.filter(|a| *a > 0.0) {
            // A_MC/τ in the run's time; τ here is τ_run · ts.
            let line = guide(&|tau| a * ts / tau, (window[0].max(x0), x1), (y0, y1));
            chart
                .draw_series(LineSeries::new(line, BLACK.stroke_width(2)))?
                .label(format!("mode coupling A_MC/τ, A_MC = {a:.4} (time)"))
                .legend(line_key(BLACK.stroke_width(2)));
        }
    }
    if let Some(&(ta, ca, _)) = pts(0).iter().find(|p| p.0 >= window[0] && p.1 > 0.0) {
        let line = guide(&|tau| ca * ta / tau, (x0, x1), (y0, y1));
        let style = BLACK.mix(0.5).stroke_width(1);
        chart
            .draw_series(DashedLineSeries::new(line, 8, 5, style))?
            .label("slope τ⁻¹")
            .legend(dash_key(style));
    }
    let data: Vec<(f64, f64)> = all.iter().map(|p| (p.0, p.1.abs())).collect();
    legend(&mut chart, &data)
}

/// MSD(τ) per species, with ⟨v²⟩τ² (ballistic, short dashes), 4Dτ (diffusive,
/// D from the MSD over the window, long dashes) and Enskog's 4D_Eτ (grey),
/// black for one species and in the species' colour for several.
pub(super) fn draw_msd<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    t: &TransportReport,
    u: &Units,
) -> DrawResult<DB> {
    let (ts, lag_desc) = u.lag();
    let pts = |k: usize| -> Vec<(f64, f64)> {
        let s = &t.species[k];
        s.lags
            .iter()
            .zip(&s.msd)
            .filter(|(&tau, m)| tau > 0.0 && m.is_finite() && **m > 0.0)
            .map(|(&tau, &m)| (tau * ts, m))
            .collect()
    };
    let all: Vec<(f64, f64)> = (0..t.species.len()).flat_map(pts).collect();
    if all.is_empty() {
        return Ok(());
    }
    let x0 = all.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
    let x1 = all.iter().map(|p| p.0).fold(0.0, f64::max).max(x0 * 1.01);
    let y0 = all.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let y1 = all.iter().map(|p| p.1).fold(0.0, f64::max).max(y0 * 1.01);
    let caption = format!("exact mean-square displacement, N = {}", t.n);
    let axis = (lag_desc.as_str(), "MSD(τ) = ⟨|ΔX|²⟩ (length²)");
    let mut chart = log_axes(root, &caption, axis, (x0, x1), (y0, y1))?;
    mark_window(&mut chart, t.window.map(|w| w * ts), (0.8 * y0, 1.25 * y1))?;
    for (k, s) in t.species.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(pts(k), colour.stroke_width(2)))?
            .label(format!("species {}", s.species))
            .legend(line_key(colour.stroke_width(2)));
        let colour = if t.species.len() == 1 {
            BLACK.to_rgba()
        } else {
            colour
        };
        // The guides in the figure's lag x = τ ts: τ = x / ts.
        let v2 = s.vacf_zero;
        let ballistic = guide(&|x| v2 * (x / ts).powi(2), (x0, x1), (y0, y1));
        let style = colour.stroke_width(1);
        chart
            .draw_series(DashedLineSeries::new(ballistic, 3, 3, style))?
            .label(format!("ballistic ⟨v²⟩τ², ⟨v²⟩ = {v2:.4}"))
            .legend(dash_key(style));
        let d = s.diffusion_msd.value;
        if d > 0.0 {
            let diffusive = guide(&|x| 4.0 * d * x / ts, (x0, x1), (y0, y1));
            let style = colour.stroke_width(2);
            chart
                .draw_series(DashedLineSeries::new(diffusive, 10, 5, style))?
                .label(format!(
                    "diffusive 4Dτ, D = {d:.4} ± {:.4}",
                    s.diffusion_msd.std_error
                ))
                .legend(dash_key(style));
        }
    }
    if let Some(e) = t.enskog.as_ref().filter(|_| t.species.len() == 1) {
        let d = e.diffusion;
        let line = guide(&|x| 4.0 * d * x / ts, (x0, x1), (y0, y1));
        let style = BLUE.mix(0.6).stroke_width(2);
        chart
            .draw_series(LineSeries::new(line, style))?
            .label(format!("Enskog 4D_Eτ, D_E = {d:.4}"))
            .legend(line_key(style));
    }
    legend(&mut chart, &all)
}

/// How many standard errors a running coefficient may still change by over
/// the second half of the window and count as levelled off.
/// A coefficient against τ (log axis) by Einstein–Helfand and Green–Kubo, the
/// window shaded, the value read over it as a line across the window with a
/// one-standard-error bar (hollow where the curve has not levelled off),
/// Enskog's value (if any) as a dashed line; `unit` is the coefficient's unit.
pub(super) fn draw_helfand<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    h: &HelfandReport,
    ((symbol, unit), enskog): ((&str, &str), Option<f64>),
    window: [f64; 2],
    u: &Units,
) -> DrawResult<DB> {
    let (ts, lag_desc) = u.lag();
    let curve = |ys: &[f64]| -> Vec<(f64, f64)> {
        h.lags
            .iter()
            .zip(ys)
            .filter(|(&tau, y)| tau > 0.0 && y.is_finite())
            .map(|(&tau, &y)| (tau * ts, y))
            .collect()
    };
    let (helfand, gk) = (curve(&h.helfand), curve(&h.green_kubo));
    let xs = || helfand.iter().chain(&gk).map(|p| p.0);
    let x0 = xs().fold(f64::INFINITY, f64::min);
    if !x0.is_finite() {
        return Ok(());
    }
    let x1 = xs().fold(0.0, f64::max).max(x0 * 1.01);
    let (vh, vg) = (&h.value_helfand, &h.value_green_kubo);
    let (y0, y1) = range(
        helfand
            .iter()
            .chain(&gk)
            .map(|p| p.1)
            .chain(enskog)
            .chain([0.0])
            .chain([vh.value + vh.std_error, vg.value + vg.std_error]),
    );
    let methods = [
        ("Einstein–Helfand", vh, &h.helfand, BLUE.to_rgba()),
        ("Green–Kubo", vg, &h.green_kubo, RED.to_rgba()),
    ];
    // The report's verdict (physics.md §14.6, one rule for text, JSON and figure):
    // an unreliable value is not titled as a result.
    let r = &h.reliability;
    let caption = if r.reliable {
        format!(
            "{} {symbol}: Einstein–Helfand {:.4} ± {:.4}, Green–Kubo {:.4} ± {:.4}",
            h.quantity, vh.value, vh.std_error, vg.value, vg.std_error
        )
    } else {
        format!(
            "{} {symbol}: unreliable here ({})",
            h.quantity,
            if r.why.iter().any(|w| w.contains("levelled")) {
                "not levelled off"
            } else {
                "window shorter than documented"
            }
        )
    };
    let axis = (
        lag_desc.as_str(),
        format!("{} {symbol} ({unit})", h.quantity),
    );
    let mut chart = chart(
        root,
        &caption,
        (axis.0, &axis.1),
        log_range(x0, x1),
        lin(y0..y1),
    )?;
    let [a, b] = window.map(|w| w * ts);
    let shade = BLACK.mix(0.08);
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(a.max(x0), y0), (b.min(x1), y1)],
            shade.filled(),
        )))?
        .label(format!("window τ ∈ [{a:.4}, {b:.4}]"))
        .legend(fill_key(shade));
    let labels = [
        "Einstein–Helfand Var[ΔG]/(2V kT^a τ)",
        "Green–Kubo ∫₀^τ ⟨J(0)J(s)⟩ ds/(V kT^a)",
    ];
    let verdict = if r.reliable { "reliable" } else { "UNRELIABLE" };
    for (m, (pts, label)) in methods
        .iter()
        .zip([(&helfand, labels[0]), (&gk, labels[1])])
    {
        let (name, v, _, colour) = *m;
        chart
            .draw_series(LineSeries::new(pts.iter().copied(), colour.stroke_width(2)))?
            .label(label)
            .legend(line_key(colour.stroke_width(2)));
        // The value read: across the window, its error bar near the window's
        // middle (Green–Kubo's a little to the right, not to hide the other).
        let mid = (a * b).sqrt() * if name == "Green–Kubo" { 1.15 } else { 1.0 };
        let read = colour.mix(0.7).stroke_width(3);
        chart
            .draw_series(LineSeries::new([(a, v.value), (b, v.value)], read))?
            .label(format!(
                "{name} read: {:.4} ± {:.4} ({verdict})",
                v.value, v.std_error
            ))
            .legend(line_key(read));
        bars(
            &mut chart,
            std::iter::once((mid, v.value, v.std_error)),
            colour.stroke_width(2),
            None,
        )?;
    }
    if let Some(e) = enskog {
        let style = BLACK.stroke_width(2);
        chart
            .draw_series(DashedLineSeries::new([(x0, e), (x1, e)], 8, 5, style))?
            .label(format!("Enskog {symbol}_E = {e:.4}"))
            .legend(dash_key(style));
    }
    // Enskog's line is data too: the legend must not hide it.
    let line = (0..=20).filter_map(|k| enskog.map(|e| (x0 * (x1 / x0).powf(k as f64 / 20.0), e)));
    let data: Vec<(f64, f64)> = helfand.iter().chain(&gk).copied().chain(line).collect();
    legend(&mut chart, &data)
}
