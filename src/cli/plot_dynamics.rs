//! Figures of the single-disc dynamics (physics.md §13): the MSD per species on
//! log–log axes with a slope-1 (diffusive) guide and the D fit window marked
//! (`msd`), |C(τ)|/C(0) of the snapshot VACF on log–log axes with a τ⁻¹ guide
//! (the 2D long-time tail; `vacf`), and F_s(k*, τ) against log τ with 1/e and
//! τ_α marked (`self_scattering`).

use carom::analysis::DynamicsReport;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{log_axes, log_legend, DrawResult};

/// (τ, y) of every point with τ > 0 and y > 0 finite.
fn positive(lag: &[f64], y: &[f64]) -> Vec<(f64, f64)> {
    lag.iter()
        .zip(y)
        .filter(|(t, v)| **t > 0.0 && v.is_finite() && **v > 0.0)
        .map(|(&t, &v)| (t, v))
        .collect()
}

/// The extent of `pts` (x and y), widened when a range is empty.
fn extent(pts: &[(f64, f64)]) -> Option<((f64, f64), (f64, f64))> {
    let fold = |f: &dyn Fn(&(f64, f64)) -> f64| {
        pts.iter()
            .map(f)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            })
    };
    let ((x0, x1), (y0, y1)) = (fold(&|p| p.0), fold(&|p| p.1));
    (x0.is_finite() && y0.is_finite()).then(|| ((x0, x1.max(x0 * 1.01)), (y0, y1.max(y0 * 1.01))))
}

/// MSD(τ) per species, 4Dτ + c over the fit window, τ through the first point
/// with slope 1, and the window's ends.
pub(super) fn draw_msd<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    d: &DynamicsReport,
) -> DrawResult<DB> {
    let all: Vec<(f64, f64)> = d
        .species
        .iter()
        .flat_map(|s| positive(&s.lag, &s.msd))
        .collect();
    let Some(((x0, x1), (y0, y1))) = extent(&all) else {
        return Ok(());
    };
    let caption = match d.species.first().and_then(|s| s.diffusion.as_ref()) {
        Some(f) => format!(
            "MSD: D = {:.4} ± {:.4} over [{:.3}, {:.3}]",
            f.d, f.std_error, f.t_a, f.t_b
        ),
        None => "mean-square displacement".to_owned(),
    };
    let axis = ("lag τ (time)", "MSD (length²)");
    let mut chart = log_axes(root, &caption, axis, (x0, x1), (y0, y1))?;
    let first = all[0];
    chart
        .draw_series(DashedLineSeries::new(
            [(x0, first.1 * x0 / first.0), (x1, first.1 * x1 / first.0)]
                .into_iter()
                .filter(|p| p.1 > 0.8 * y0 && p.1 < 1.25 * y1),
            8,
            5,
            BLACK.stroke_width(1),
        ))?
        .label("slope 1 (diffusion)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK));
    for s in &d.species {
        let c = Palette99::pick(s.species).to_rgba();
        chart
            .draw_series(LineSeries::new(positive(&s.lag, &s.msd), c.stroke_width(2)))?
            .label(format!("species {} ({} discs)", s.species, s.count))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], c.stroke_width(2)));
        if let Some(f) = &s.diffusion {
            let line: Vec<(f64, f64)> = (0..=20)
                .map(|k| f.t_a * (f.t_b / f.t_a).powf(k as f64 / 20.0))
                .map(|t| (t, 4.0 * f.d * t + f.intercept))
                .filter(|p| p.1 > 0.0)
                .collect();
            chart.draw_series(LineSeries::new(line, RED.stroke_width(1)))?;
            for t in [f.t_a, f.t_b] {
                chart.draw_series(LineSeries::new(
                    [(t, 0.8 * y0), (t, 1.25 * y1)],
                    c.mix(0.4).stroke_width(1),
                ))?;
            }
        }
    }
    log_legend(&mut chart)
}

/// |C(τ)|/C(0) per species (three decades at most) with τ⁻¹ through the
/// first lag.
pub(super) fn draw_vacf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    d: &DynamicsReport,
) -> DrawResult<DB> {
    let abs: Vec<Vec<f64>> = d
        .species
        .iter()
        .map(|s| s.vacf_normalised.iter().map(|c| c.abs()).collect())
        .collect();
    let all: Vec<(f64, f64)> = d
        .species
        .iter()
        .zip(&abs)
        .flat_map(|(s, a)| positive(&s.lag, a))
        .collect();
    let Some(((x0, x1), (y0, y1))) = extent(&all) else {
        return Ok(());
    };
    // Noise crossing zero would stretch the axis over decades: three at most.
    let y0 = y0.max(1e-3 * y1);
    let axis = ("lag τ (time)", "|C(τ)|/C(0) (dimensionless)");
    let caption = "velocity autocorrelation at the snapshots";
    let mut chart = log_axes(root, caption, axis, (x0, x1), (y0, y1))?;
    for (s, a) in d.species.iter().zip(&abs) {
        let c = Palette99::pick(s.species).to_rgba();
        let pts: Vec<(f64, f64)> = positive(&s.lag, a)
            .into_iter()
            .filter(|p| p.1 >= y0)
            .collect();
        chart
            .draw_series(LineSeries::new(pts.iter().copied(), c.stroke_width(2)))?
            .label(format!("species {}", s.species))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], c.stroke_width(2)));
        if let Some(&(tl, cl)) = pts.first() {
            let guide: Vec<(f64, f64)> = (0..=20)
                .map(|k| x0 * (x1 / x0).powf(k as f64 / 20.0))
                .map(|t| (t, cl * tl / t))
                .filter(|p| p.1 > 0.8 * y0 && p.1 < 1.25 * y1)
                .collect();
            chart
                .draw_series(DashedLineSeries::new(guide, 8, 5, BLACK.stroke_width(1)))?
                .label("τ⁻¹ (the 2D long-time tail)")
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK));
        }
    }
    log_legend(&mut chart)
}

/// F_s(k*, τ) per species against log τ, the level 1/e and τ_α.
pub(super) fn draw_fs<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    d: &DynamicsReport,
) -> DrawResult<DB> {
    let all: Vec<(f64, f64)> = d
        .species
        .iter()
        .flat_map(|s| {
            s.lag
                .iter()
                .zip(&s.fs)
                .filter(|(t, f)| **t > 0.0 && f.is_finite())
                .map(|(&t, &f)| (t, f))
        })
        .collect();
    let Some(((x0, x1), _)) = extent(&all) else {
        return Ok(());
    };
    let lo = all.iter().map(|p| p.1).fold(0.0, f64::min) - 0.05;
    let caption = format!(
        "self intermediate scattering at k* = {:.4}",
        d.k_star.unwrap_or(f64::NAN)
    );
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), lo..1.05)?;
    chart
        .configure_mesh()
        .x_desc("lag τ (time)")
        .y_desc("F_s(k*, τ) (dimensionless)")
        .x_label_formatter(&|v| format!("{v:.3}"))
        .draw()?;
    let e = (-1.0f64).exp();
    chart
        .draw_series(DashedLineSeries::new(
            [(x0, e), (x1, e)],
            8,
            5,
            BLACK.stroke_width(1),
        ))?
        .label("1/e")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK));
    for s in &d.species {
        let c = Palette99::pick(s.species).to_rgba();
        let pts = s
            .lag
            .iter()
            .zip(&s.fs)
            .filter(|(t, f)| **t > 0.0 && f.is_finite())
            .map(|(&t, &f)| (t, f));
        let label = match s.tau_alpha {
            Some(t) => format!("species {}: τ_α = {t:.4}", s.species),
            None => format!("species {}: no τ_α", s.species),
        };
        chart
            .draw_series(LineSeries::new(pts, c.stroke_width(2)))?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], c.stroke_width(2)));
        if let Some(t) = s.tau_alpha {
            chart.draw_series(LineSeries::new(
                [(t, lo), (t, 1.05)],
                c.mix(0.5).stroke_width(1),
            ))?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
}

#[cfg(test)]
mod tests {
    use super::*;
    use carom::analysis::{DiffusionFit, SpeciesDynamics};

    /// Two species, one with a D fit and τ_α, one with neither and a VACF that
    /// crosses zero (NaN errors where one segment had data).
    fn report() -> DynamicsReport {
        let lag = vec![0.0, 1.0, 2.0, 4.0, 8.0];
        let sp = |species: usize, fit: bool| SpeciesDynamics {
            species,
            count: 10,
            lag: lag.clone(),
            samples: vec![10; 5],
            msd: vec![0.0, 1.0, 3.0, 7.0, 15.0],
            msd_std_error: vec![f64::NAN, 0.1, 0.2, 0.3, f64::NAN],
            alpha2: vec![f64::NAN, 0.1, 0.1, 0.05, 0.0],
            vacf: vec![2.0, 1.0, 0.1, -0.02, 0.01],
            vacf_std_error: vec![0.0; 5],
            vacf_normalised: vec![1.0, 0.5, 0.05, -0.01, 0.005],
            fs: vec![1.0, 0.8, 0.5, 0.2, 0.05],
            fs_std_error: vec![0.0; 5],
            tau_alpha: fit.then_some(2.9),
            diffusion: fit.then_some(DiffusionFit {
                d: 0.5,
                std_error: 0.01,
                intercept: -1.0,
                t_a: 2.0,
                t_b: 4.0,
                points: 2,
                segments: 10,
            }),
        };
        DynamicsReport {
            species: vec![sp(0, true), sp(1, false)],
            origins: 9,
            origins_per_level: 16,
            levels: 1,
            max_stored: 9,
            origins_capped: false,
            segments: 10,
            k_star: Some(6.0),
            ambiguous_gaps: 0,
        }
    }

    /// The SVG text of one figure drawn by `$draw`.
    macro_rules! svg {
        ($draw:expr, $d:expr) => {{
            let mut svg = String::new();
            {
                let root = SVGBackend::with_string(&mut svg, (900, 600)).into_drawing_area();
                $draw(&root, $d).unwrap();
                root.present().unwrap();
            }
            svg
        }};
    }

    /// Each figure draws with its guides and labels in its legend.
    #[test]
    fn the_dynamics_figures_carry_their_guides() {
        carom::render::register_font();
        let d = report();
        let figures = [
            (
                svg!(draw_msd, &d),
                &["slope 1", "D = 0.5000", "species 1"][..],
            ),
            (svg!(draw_vacf, &d), &["τ⁻¹", "species 0"][..]),
            (svg!(draw_fs, &d), &["1/e", "τ_α = 2.9000", "no τ_α"][..]),
        ];
        for (svg, labels) in figures {
            for l in labels {
                assert!(svg.contains(l), "{l} missing");
            }
        }
    }
}
