//! Figures of the thermodynamic state (physics.md §5–§8, §15): the speed
//! histogram with the Maxwell–Boltzmann pdf (`speed_species{k}`), v_x and v_y
//! histograms with the Gaussian (`components_species{k}`), kT against time — for
//! a cooling run on log–log axes against the time since the first record, with
//! Haff's law kT0/(1 + t/t0)² (`temperature`) — Z = βPA/N against time with the
//! mean ± one standard error and the halves' means when it drifts (`pressure`),
//! and n(y) per species on a log axis with the fitted barometric law
//! n(a) e^{−β(y − a)} (`density_profile`). Axes are in the run's units.

use carom_analysis::Report;
use carom_analysis::{GravityReport, HaffReport, HistogramReport, PressureReport, SpeciesMb};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{
    axes, band, chart, dash_key, dot_key, fill_key, legend, lin, line_key, log_axes, log_range,
};
use super::{range, top, DrawResult};

fn histogram_series<DB: DrawingBackend>(
    chart: &mut super::axes::Chart<'_, DB>,
    h: &HistogramReport,
    colour: RGBColor,
    label: &str,
) -> DrawResult<DB> {
    let fill = colour.mix(0.35);
    let bars = h
        .edges
        .windows(2)
        .zip(&h.density)
        .map(move |(e, &d)| Rectangle::new([(e[0], 0.0), (e[1], d)], fill.filled()));
    chart.draw_series(bars)?.label(label).legend(fill_key(fill));
    Ok(())
}

fn theory_line<DB: DrawingBackend>(
    chart: &mut super::axes::Chart<'_, DB>,
    h: &HistogramReport,
    label: &str,
) -> DrawResult<DB> {
    let centres = h.edges.windows(2).map(|e| 0.5 * (e[0] + e[1]));
    chart
        .draw_series(LineSeries::new(
            centres.zip(h.theory.iter().copied()),
            BLACK.stroke_width(2),
        ))?
        .label(label)
        .legend(line_key(BLACK.stroke_width(2)));
    Ok(())
}

/// The (x, y) of a histogram's bar tops, for placing the legend.
fn tops(h: &HistogramReport) -> impl Iterator<Item = (f64, f64)> + '_ {
    h.edges
        .windows(2)
        .zip(h.density.iter().zip(&h.theory))
        .flat_map(|(e, (&d, &t))| {
            let c = 0.5 * (e[0] + e[1]);
            (0..=4).map(move |k| (c, d.max(t) * k as f64 / 4.0))
        })
}

pub(super) fn draw_speed<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    m: &SpeciesMb,
) -> DrawResult<DB> {
    let h = &m.speed_histogram;
    let x_max = *h.edges.last().unwrap_or(&1.0);
    let y_max = top(h.density.iter().chain(&h.theory).copied());
    let caption = format!(
        "species {} (m = {}): speeds, χ² p = {:.3}, KS p = {:.3}",
        m.species, m.mass, m.chi_square.p_value, m.ks.p_value
    );
    let axis = ("speed v (length/time)", "probability density (time/length)");
    let mut chart = axes(root, &caption, axis, 0.0..x_max, 0.0..y_max)?;
    histogram_series(&mut chart, h, BLUE, &format!("{} speeds", m.samples))?;
    theory_line(
        &mut chart,
        h,
        &format!("Maxwell–Boltzmann, kT = {:.4}", m.kt),
    )?;
    legend(&mut chart, &tops(h).collect::<Vec<_>>())
}

pub(super) fn draw_components<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    m: &SpeciesMb,
) -> DrawResult<DB> {
    let (hx, hy) = (&m.vx_histogram, &m.vy_histogram);
    let x_lo = *hx.edges.first().unwrap_or(&-1.0);
    let x_hi = *hx.edges.last().unwrap_or(&1.0);
    let y_max = top(hx
        .density
        .iter()
        .chain(&hy.density)
        .chain(&hx.theory)
        .copied());
    let caption = format!(
        "species {}: velocity components, KS p(vx) = {:.3}, p(vy) = {:.3}",
        m.species, m.ks_vx.p_value, m.ks_vy.p_value
    );
    let axis = (
        "velocity component vx, vy (length/time)",
        "probability density (time/length)",
    );
    let mut chart = axes(root, &caption, axis, x_lo..x_hi, 0.0..y_max)?;
    histogram_series(&mut chart, hx, BLUE, "vx")?;
    histogram_series(&mut chart, hy, RED, "vy")?;
    theory_line(
        &mut chart,
        hx,
        &format!("Gaussian, variance kT/m = {:.4}", m.kt / m.mass),
    )?;
    let data: Vec<(f64, f64)> = tops(hx).chain(tops(hy)).collect();
    legend(&mut chart, &data)
}

pub(super) fn draw_temperature<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &Report,
) -> DrawResult<DB> {
    let s = &r.temperature.series;
    if let Some(h) = r.inelastic.as_ref().and_then(|i| i.haff.as_ref()) {
        return draw_cooling(root, s, h);
    }
    let (x0, x1) = range(s.iter().map(|p| p[0]));
    let (y0, y1) = range(s.iter().map(|p| p[1]).chain([0.0]));
    let caption = "temperature kT = 2K/f against time";
    let axis = ("time t (time)", "kT (energy)");
    let mut chart = axes(root, caption, axis, x0..x1, y0..y1)?;
    let pts: Vec<(f64, f64)> = s.iter().map(|p| (p[0], p[1])).collect();
    chart
        .draw_series(LineSeries::new(pts.iter().copied(), BLUE.stroke_width(2)))?
        .label("measured kT")
        .legend(line_key(BLUE.stroke_width(2)));
    legend(&mut chart, &pts)
}

/// A cooling run's kT against the time since its first record on log–log axes,
/// with Haff's law T0/(1 + t/t0)² (physics.md (8.2)): flat for t ≪ t0, t⁻² after.
fn draw_cooling<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    s: &[[f64; 2]],
    h: &HaffReport,
) -> DrawResult<DB> {
    let (t0, kt0) = (s[0][0], s[0][1]);
    let pts: Vec<(f64, f64)> = s
        .iter()
        .map(|p| (p[0] - t0, p[1]))
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .collect();
    let haff = |t: f64| kt0 / (1.0 + t / h.t0).powi(2);
    let (Some(first), Some(last)) = (pts.first(), pts.last()) else {
        return Ok(());
    };
    let (x0, x1) = (first.0, last.0.max(first.0 * 1.0001));
    let ys = pts.iter().map(|p| p.1).chain([haff(x0), haff(x1)]);
    let (y0, y1) = ys.fold((f64::INFINITY, 0.0f64), |(a, b), v| (a.min(v), b.max(v)));
    let mut chart = log_axes(
        root,
        &format!("cooling: kT against time, Haff's law t0 = {:.4}", h.t0),
        (
            "time since the first record t − t_start (time)",
            "kT (energy)",
        ),
        (x0, x1),
        (y0, y1),
    )?;
    chart
        .draw_series(LineSeries::new(pts.iter().copied(), BLUE.stroke_width(2)))?
        .label("measured kT")
        .legend(line_key(BLUE.stroke_width(2)));
    let n = 200;
    let curve: Vec<(f64, f64)> = (0..=n)
        .map(|k| {
            let t = x0 * (x1 / x0).powf(k as f64 / n as f64);
            (t, haff(t))
        })
        .collect();
    chart
        .draw_series(DashedLineSeries::new(
            curve.iter().copied(),
            8,
            5,
            BLACK.stroke_width(2),
        ))?
        .label(format!("Haff's law kT0/(1 + t/t0)², t0 = {:.4}", h.t0))
        .legend(dash_key(BLACK.stroke_width(2)));
    let data: Vec<(f64, f64)> = pts.into_iter().chain(curve).collect();
    legend(&mut chart, &data)
}

pub(super) fn draw_pressure<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    p: &PressureReport,
) -> DrawResult<DB> {
    let s = &p.series;
    let (x0, x1) = range(s.iter().map(|q| q[0]));
    let (y0, y1) = range(s.iter().map(|q| q[1]));
    let drifting = p.drift.as_ref().filter(|d| d.drifting);
    let caption = match drifting {
        Some(d) => format!(
            "Z = βPA/N DRIFTING: halves {:.4} and {:.4} ({:.1} SE apart)",
            d.first_half, d.second_half, d.difference_std_errors
        ),
        None => format!("Z = βPA/N = {:.4} ± {:.4}", p.z, p.z_std_error),
    };
    let axis = ("time t (time)", "Z = βPA/N (dimensionless)");
    let mut chart = axes(root, &caption, axis, x0..x1, y0..y1)?;
    let mean = [(x0, p.z, p.z_std_error), (x1, p.z, p.z_std_error)];
    band(
        &mut chart,
        mean.into_iter(),
        GREEN.to_rgba(),
        Some("± one standard error of the mean"),
    )?;
    chart
        .draw_series(LineSeries::new(
            [(x0, p.z), (x1, p.z)],
            GREEN.stroke_width(2),
        ))?
        .label(format!("mean Z = {:.4}", p.z))
        .legend(line_key(GREEN.stroke_width(2)));
    if let Some(d) = drifting {
        let mid = 0.5 * (s[0][0] + s[s.len() - 1][0]);
        let halves = [
            vec![(x0, d.first_half), (mid, d.first_half)],
            vec![(mid, d.second_half), (x1, d.second_half)],
        ];
        let mut drawn = None;
        for h in halves {
            drawn = Some(chart.draw_series(LineSeries::new(h, RED.stroke_width(2)))?);
        }
        if let Some(d) = drawn {
            d.label("means of the two halves (drift)")
                .legend(line_key(RED.stroke_width(2)));
        }
    }
    let pts: Vec<(f64, f64)> = s.iter().map(|q| (q[0], q[1])).collect();
    chart.draw_series(LineSeries::new(pts.iter().copied(), BLUE.stroke_width(1)))?;
    chart
        .draw_series(pts.iter().map(|&q| Circle::new(q, 3, BLUE.filled())))?
        .label("Z per interval")
        .legend(dot_key(BLUE.filled(), 3));
    legend(&mut chart, &pts)
}

/// n(y) per species (bin centres, log scale) and each species' fitted barometric
/// law n(a) e^{−β (y − a)} (physics.md (15.6)), with the known m g/kT in the caption.
pub(super) fn draw_density_profile<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    g: &GravityReport,
) -> DrawResult<DB> {
    let half = 0.5 * g.bin_width;
    let points: Vec<Vec<(f64, f64)>> = g
        .density
        .iter()
        .map(|d| {
            g.heights
                .iter()
                .zip(d)
                .filter(|(_, &n)| n > 0.0)
                .map(|(&y, &n)| (y + half, n))
                .collect()
        })
        .collect();
    let all = || points.iter().flatten();
    let (y0, y1) = (0.0, g.heights.last().map_or(1.0, |h| h + g.bin_width));
    let lo = all().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let hi = all().map(|p| p.1).fold(0.0, f64::max);
    if !(lo.is_finite() && hi > 0.0) {
        return Ok(());
    }
    let caption = match g.barometric.first() {
        Some(b) => format!(
            "density profile; fitted m g/kT = {:.4}, known {:.4}",
            b.beta, b.beta_expected
        ),
        None => "density profile".to_owned(),
    };
    let axis = ("height y (length)", "n(y) (1/length²)");
    let mut chart = chart(
        root,
        &caption,
        axis,
        lin(y0..y1),
        log_range(0.8 * lo, 1.25 * hi),
    )?;
    for (s, pts) in points.iter().enumerate() {
        let color = Palette99::pick(s).to_rgba();
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))?
            .label(format!("species {s}"))
            .legend(dot_key(color.filled(), 3));
    }
    for b in &g.barometric {
        let color = Palette99::pick(b.species).to_rgba();
        let a = b.floor;
        let line: Vec<(f64, f64)> = (0..=100)
            .map(|k| y0 + (y1 - y0) * k as f64 / 100.0)
            .map(|y| (y, b.floor_density * (-b.beta * (y - a)).exp()))
            .filter(|p| p.1 >= 0.8 * lo)
            .collect();
        chart
            .draw_series(LineSeries::new(line, color.stroke_width(2)))?
            .label(format!("barometric fit, species {}", b.species))
            .legend(line_key(color.stroke_width(2)));
    }
    let data: Vec<(f64, f64)> = all().copied().collect();
    legend(&mut chart, &data)
}
