//! Figures of the transport report (physics.md §14): the exact VACF |C(τ)/C(0)|
//! on log–log axes per species, negative values hollow, with the mode-coupling
//! tail A_MC/τ, A_MC = 1/[8π n (D + ν)], from the window's start and a τ⁻¹ slope
//! guide (`vacf_exact`); η and λ against τ on a log τ axis by Einstein–Helfand,
//! Var[ΔG(τ)]/(2 V kT^a τ), and by Green–Kubo, the running integral of the flux
//! autocorrelation, with the window shaded and Enskog's value
//! (`helfand_viscosity`, `helfand_conductivity`); the MSD per species log–log with
//! the ballistic ⟨v²⟩τ² and diffusive 4Dτ guides (`msd_exact`). Lags τ > 0 only
//! (a log axis has no 0); the window [τ_a, τ_b] is marked on every figure.

use carom::analysis::{HelfandReport, TransportReport};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{log_axes, log_legend, range, DrawResult, LogChart};

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

/// The window [τ_a, τ_b] as two dotted grey verticals over a log–log chart.
fn mark_window<DB: DrawingBackend>(
    chart: &mut LogChart<'_, DB>,
    [a, b]: [f64; 2],
    (y0, y1): (f64, f64),
) -> DrawResult<DB> {
    let grey = BLACK.mix(0.4).stroke_width(1);
    let mut drawn = None;
    for t in [a, b] {
        drawn = Some(chart.draw_series(DashedLineSeries::new(
            [(t, 0.8 * y0), (t, 1.25 * y1)],
            3,
            4,
            grey,
        ))?);
    }
    if let Some(d) = drawn {
        d.label(format!("window τ ∈ [{a:.4}, {b:.4}]"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], grey));
    }
    Ok(())
}

/// |C(τ)/C(0)| per species (filled where C > 0, hollow where C < 0), the
/// mode-coupling tail A_MC/τ over τ ≥ τ_a and a τ⁻¹ guide through the first
/// point at or after τ_a.
pub(super) fn draw_vacf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    t: &TransportReport,
) -> DrawResult<DB> {
    let pts = |k: usize| -> Vec<(f64, f64)> {
        let s = &t.species[k];
        s.lags
            .iter()
            .zip(&s.vacf)
            .filter(|(&tau, c)| tau > 0.0 && c.is_finite() && **c != 0.0)
            .map(|(&tau, &c)| (tau, c))
            .collect()
    };
    let all: Vec<(f64, f64)> = (0..t.species.len()).flat_map(pts).collect();
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
        "exact VACF |C(τ)/C(0)|, N = {}, t_c = {:.4}",
        t.n, t.collision_time
    );
    let axis = ("lag τ (time)", "|C(τ)/C(0)| (dimensionless)");
    let mut chart = log_axes(root, &caption, axis, (x0, x1), (y0, y1))?;
    mark_window(&mut chart, t.window, (y0, y1))?;
    let inside = |p: &(f64, f64)| p.1.abs() > 0.8 * y0;
    for (k, s) in t.species.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        let p = pts(k);
        chart
            .draw_series(
                p.iter()
                    .filter(|p| p.1 > 0.0 && inside(p))
                    .map(|&(x, y)| Circle::new((x, y), 3, colour.filled())),
            )?
            .label(format!("species {}: C > 0", s.species))
            .legend(move |(x, y)| Circle::new((x + 7, y), 3, colour.filled()));
        if p.iter().any(|p| p.1 < 0.0) {
            chart
                .draw_series(
                    p.iter()
                        .filter(|p| p.1 < 0.0 && inside(p))
                        .map(|&(x, y)| Circle::new((x, -y), 4, colour.stroke_width(1))),
                )?
                .label(format!("species {}: C < 0 (|C| shown)", s.species))
                .legend(move |(x, y)| Circle::new((x + 7, y), 4, colour.stroke_width(1)));
        }
        if let Some(a) = s.tail_amplitude_theory.filter(|a| *a > 0.0) {
            let line = guide(&|tau| a / tau, (t.window[0].max(x0), x1), (y0, y1));
            chart
                .draw_series(LineSeries::new(line, BLACK.stroke_width(2)))?
                .label(format!("mode coupling A_MC/τ, A_MC = {a:.4}"))
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 15, y)], BLACK.stroke_width(2))
                });
        }
    }
    if let Some(&(ta, ca)) = pts(0).iter().find(|p| p.0 >= t.window[0] && p.1 > 0.0) {
        let line = guide(&|tau| ca * ta / tau, (x0, x1), (y0, y1));
        chart
            .draw_series(DashedLineSeries::new(
                line,
                8,
                5,
                BLACK.mix(0.5).stroke_width(1),
            ))?
            .label("slope τ⁻¹")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK.mix(0.5)));
    }
    log_legend(&mut chart)
}

/// MSD(τ) per species, with ⟨v²⟩τ² (ballistic, short dashes) and 4Dτ (diffusive,
/// D from the MSD over the window, long dashes), black for one species and in
/// the species' colour for several.
pub(super) fn draw_msd<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    t: &TransportReport,
) -> DrawResult<DB> {
    let pts = |k: usize| -> Vec<(f64, f64)> {
        let s = &t.species[k];
        s.lags
            .iter()
            .zip(&s.msd)
            .filter(|(&tau, m)| tau > 0.0 && m.is_finite() && **m > 0.0)
            .map(|(&tau, &m)| (tau, m))
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
    let axis = ("lag τ (time)", "MSD(τ) = ⟨|ΔX|²⟩ (length²)");
    let mut chart = log_axes(root, &caption, axis, (x0, x1), (y0, y1))?;
    mark_window(&mut chart, t.window, (y0, y1))?;
    for (k, s) in t.species.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(pts(k), colour.stroke_width(2)))?
            .label(format!("species {}", s.species))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 15, y)], colour.stroke_width(2))
            });
        let colour = if t.species.len() == 1 {
            BLACK.to_rgba()
        } else {
            colour
        };
        let v2 = s.vacf_zero;
        let ballistic = guide(&|tau| v2 * tau * tau, (x0, x1), (y0, y1));
        chart
            .draw_series(DashedLineSeries::new(
                ballistic,
                3,
                3,
                colour.stroke_width(1),
            ))?
            .label(format!("ballistic ⟨v²⟩τ², ⟨v²⟩ = {v2:.4}"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], colour));
        let d = s.diffusion_msd.value;
        if d > 0.0 {
            let diffusive = guide(&|tau| 4.0 * d * tau, (x0, x1), (y0, y1));
            chart
                .draw_series(DashedLineSeries::new(
                    diffusive,
                    10,
                    5,
                    colour.stroke_width(2),
                ))?
                .label(format!("diffusive 4Dτ, D = {d:.4}"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 15, y)], colour.stroke_width(2))
                });
        }
    }
    log_legend(&mut chart)
}

/// A coefficient against τ (log axis) by Einstein–Helfand and Green–Kubo, the
/// window shaded, Enskog's value (if any) as a horizontal line; `unit` is the
/// coefficient's unit for the axis.
pub(super) fn draw_helfand<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    h: &HelfandReport,
    (symbol, unit): (&str, &str),
    enskog: Option<f64>,
    window: [f64; 2],
) -> DrawResult<DB> {
    let curve = |ys: &[f64]| -> Vec<(f64, f64)> {
        h.lags
            .iter()
            .zip(ys)
            .filter(|(&tau, y)| tau > 0.0 && y.is_finite())
            .map(|(&tau, &y)| (tau, y))
            .collect()
    };
    let (helfand, gk) = (curve(&h.helfand), curve(&h.green_kubo));
    let xs = || helfand.iter().chain(&gk).map(|p| p.0);
    let x0 = xs().fold(f64::INFINITY, f64::min);
    if !x0.is_finite() {
        return Ok(());
    }
    let x1 = xs().fold(0.0, f64::max).max(x0 * 1.01);
    let (y0, y1) = range(
        helfand
            .iter()
            .chain(&gk)
            .map(|p| p.1)
            .chain(enskog)
            .chain([0.0]),
    );
    let (vh, vg) = (&h.value_helfand, &h.value_green_kubo);
    let caption = format!(
        "{} {symbol}: Einstein–Helfand {:.4} ± {:.4}, Green–Kubo {:.4} ± {:.4}",
        h.quantity, vh.value, vh.std_error, vg.value, vg.std_error
    );
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), y0..y1)?;
    chart
        .configure_mesh()
        .x_desc("lag τ (time)")
        .y_desc(format!("{} {symbol} ({unit})", h.quantity))
        .x_label_formatter(&|v| format!("{v:.3}"))
        .draw()?;
    let [a, b] = window;
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(a.max(x0), y0), (b.min(x1), y1)],
            BLACK.mix(0.08).filled(),
        )))?
        .label(format!("window τ ∈ [{a:.4}, {b:.4}]"))
        .legend(|(x, y)| Rectangle::new([(x, y - 5), (x + 15, y + 5)], BLACK.mix(0.08).filled()));
    chart
        .draw_series(LineSeries::new(helfand, BLUE.stroke_width(2)))?
        .label("Einstein–Helfand Var[ΔG]/(2V kT^a τ)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLUE.stroke_width(2)));
    chart
        .draw_series(LineSeries::new(gk, RED.stroke_width(2)))?
        .label("Green–Kubo ∫₀^τ ⟨J(0)J(s)⟩ ds/(V kT^a)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], RED.stroke_width(2)));
    if let Some(e) = enskog {
        chart
            .draw_series(DashedLineSeries::new(
                [(x0, e), (x1, e)],
                8,
                5,
                BLACK.stroke_width(2),
            ))?
            .label(format!("Enskog {symbol}_E = {e:.4}"))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
}
