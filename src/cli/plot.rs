//! `carom analyze --plot DIR`: figures of a [`Report`] as PNG and SVG (plotters;
//! text in DejaVu Sans, embedded, so no system fonts are needed).
//!
//! Files: `speed_species{k}` (speed histogram with the MB pdf),
//! `components_species{k}` (v_x and v_y histograms with the Gaussian),
//! `temperature` (kT against time; for a cooling run on log–log axes against the
//! time since the first record, with Haff's law), `pressure` (Z against time with
//! the mean and one standard error, and the halves' means when it drifts),
//! `pair_correlation` (g_ab(r) per species pair with its contact value),
//! `bond_order`, `g6` and `structure_factor` ([`structure`]), `msd`, `vacf` and
//! `self_scattering` ([`dynamics`]), `vacf_exact`, `msd_exact`,
//! `helfand_viscosity` and `helfand_conductivity` ([`transport`]),
//! `density_profile` (n(y) per species on a log axis with the fitted barometric
//! law, in a field). Axes are in the run's units.

use std::ops::Range;
use std::path::Path;

use carom::analysis::{GravityReport, HistogramReport, Report, SpeciesMb};
use plotters::coord::combinators::LogCoord;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::CliError;

#[path = "plot_structure.rs"]
mod structure;
#[path = "plot_transport.rs"]
mod transport;

#[path = "plot_dynamics.rs"]
mod dynamics;

#[path = "plot_sweep.rs"]
mod sweep;

const SIZE: (u32, u32) = (900, 600);

pub(super) type DrawResult<DB> =
    Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A figure that could not be drawn or written: the error says which file and why (the operating system's reason for a write).
fn plot_err<E: std::error::Error + Send + Sync + 'static>(
    path: &Path,
    e: DrawingAreaErrorKind<E>,
) -> CliError {
    let reason = carom::render::drawing_error_reason(&e);
    CliError::Plot(format!("cannot write {}: {reason}", path.display()))
}

/// Draw one figure with `draw` into `dir/name.png` and `dir/name.svg`. A failed
/// file is removed once its backend is dropped (dropping presents it again).
macro_rules! both {
    ($dir:expr, $name:expr, $draw:expr) => {{
        let png = $dir.join(format!("{}.png", $name));
        let drawn = {
            let root = BitMapBackend::new(&png, SIZE).into_drawing_area();
            root.fill(&WHITE)
                .and_then(|()| $draw(&root))
                .and_then(|()| root.present())
                .map_err(|e| plot_err(&png, e))
        };
        drawn.inspect_err(|_| remove(&png))?;
        let svg = $dir.join(format!("{}.svg", $name));
        let drawn = {
            let root = SVGBackend::new(&svg, SIZE).into_drawing_area();
            root.fill(&WHITE)
                .and_then(|()| $draw(&root))
                .and_then(|()| root.present())
                .map_err(|e| plot_err(&svg, e))
        };
        drawn.inspect_err(|_| remove(&svg))?;
    }};
}

/// Remove a figure that could not be written.
fn remove(path: &Path) {
    let _ = std::fs::remove_file(path);
}

/// Write every figure of `report` into `dir` (created if needed). Returns the
/// number of figures (each as PNG and SVG).
pub fn write_all(report: &Report, dir: &Path) -> Result<usize, CliError> {
    std::fs::create_dir_all(dir).map_err(|source| CliError::Io {
        context: format!("cannot create {}", dir.display()),
        source,
    })?;
    carom::render::register_font();
    let mut n = 0;
    for m in &report.maxwell_boltzmann {
        let name = format!("speed_species{}", m.species);
        both!(dir, &name, |root| draw_speed(root, m));
        let name = format!("components_species{}", m.species);
        both!(dir, &name, |root| draw_components(root, m));
        n += 2;
    }
    if report.temperature.series.len() >= 2 {
        both!(dir, "temperature", |root| draw_temperature(root, report));
        n += 1;
    }
    if report
        .pressure
        .as_ref()
        .is_some_and(|p| p.series.len() >= 2)
    {
        both!(dir, "pressure", |root| draw_pressure(root, report));
        n += 1;
    }
    if report
        .pair_correlation
        .as_ref()
        .is_some_and(|p| !p.pairs.is_empty())
    {
        both!(dir, "pair_correlation", |root| draw_pair_correlation(
            root, report
        ));
        n += 1;
    }
    if let Some(b) = report.bond_order.as_ref().filter(|b| b.series.len() >= 2) {
        both!(dir, "bond_order", |root| structure::draw_bond_order(
            root, b
        ));
        n += 1;
    }
    if let Some(g) = &report.orientational_correlation {
        both!(dir, "g6", |root| structure::draw_g6(root, g));
        n += 1;
    }
    if let Some(f) = report.structure_factor.as_ref().filter(|f| f.k.len() >= 2) {
        both!(dir, "structure_factor", |root| structure::draw_sk(root, f));
        n += 1;
    }
    if let Some(t) = &report.transport {
        let e = t.enskog.as_ref();
        both!(dir, "vacf_exact", |root| transport::draw_vacf(root, t));
        both!(dir, "msd_exact", |root| transport::draw_msd(root, t));
        let eta = ("η", "mass/time");
        let visc = e.map(|e| e.viscosity);
        both!(dir, "helfand_viscosity", |root| transport::draw_helfand(
            root,
            &t.viscosity,
            eta,
            visc,
            t.window
        ));
        n += 3;
        if let Some(l) = &t.thermal_conductivity {
            let lambda = ("λ", "1/time, k_B = 1");
            let cond = e.map(|e| e.thermal_conductivity);
            both!(dir, "helfand_conductivity", |root| transport::draw_helfand(
                root, l, lambda, cond, t.window
            ));
            n += 1;
        }
    }
    if let Some(g) = report.gravity.as_ref().filter(|g| g.heights.len() >= 2) {
        both!(dir, "density_profile", |root| draw_density_profile(root, g));
        n += 1;
    }
    if let Some(d) = report.dynamics.as_ref().filter(|d| !d.species.is_empty()) {
        both!(dir, "msd", |root| dynamics::draw_msd(root, d));
        both!(dir, "vacf", |root| dynamics::draw_vacf(root, d));
        n += 2;
        if d.k_star.is_some() {
            both!(dir, "self_scattering", |root| dynamics::draw_fs(root, d));
            n += 1;
        }
    }
    Ok(n)
}

/// Write the figures of a collected sweep into `dir`: `equation_of_state` when
/// the sweep varies a packing fraction and has pressures. Returns their number.
pub fn write_sweep(c: &carom::sweep::Collected, dir: &Path) -> Result<usize, CliError> {
    let Some(eta) = c.axes.iter().find(|a| a.ends_with("packing_fraction")) else {
        return Ok(0);
    };
    let series = sweep::eos_series(c, eta);
    if series.is_empty() {
        return Ok(0);
    }
    std::fs::create_dir_all(dir).map_err(|source| CliError::Io {
        context: format!("cannot create {}", dir.display()),
        source,
    })?;
    carom::render::register_font();
    both!(dir, "equation_of_state", |root| sweep::draw_eos(
        root, &series
    ));
    Ok(1)
}

pub(super) fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if hi.is_nan() || lo.is_nan() || hi <= lo {
        let c = if lo.is_finite() { lo } else { 0.0 };
        return (c - 1.0, c + 1.0);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

/// A chart with f64 axes on both sides.
pub(super) type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The chart every figure uses: a caption, labelled axes over `x` × `y`.
pub(super) fn axes<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x_desc, y_desc): (&str, &str),
    x: Range<f64>,
    y: Range<f64>,
) -> Result<Chart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x, y)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()?;
    Ok(chart)
}

/// A chart with logarithmic axes.
pub(super) type LogChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

/// The log–log chart of a figure: a caption, labelled axes over x0..x1 and
/// 0.8 y0..1.25 y1 (room above and below the data), three-digit tick labels.
pub(super) fn log_axes<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x_desc, y_desc): (&str, &str),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Result<LogChart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (0.8 * y0..1.25 * y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|v| format!("{v:.3}"))
        .y_label_formatter(&|v| format!("{v:.3}"))
        .draw()?;
    Ok(chart)
}

/// The legend of a log–log chart, at the lower left (where decays leave room).
pub(super) fn log_legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut LogChart<'a, DB>,
) -> DrawResult<DB> {
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
}

/// The legend of the labelled series drawn so far.
pub(super) fn legend<'a, DB: DrawingBackend + 'a>(chart: &mut Chart<'a, DB>) -> DrawResult<DB> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
}

/// The largest of `values`, times 1.1 (a density axis's top), at least 10⁻¹².
pub(super) fn top(values: impl Iterator<Item = f64>) -> f64 {
    (values.fold(0.0, f64::max) * 1.1).max(1e-12)
}

fn histogram_series<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    h: &HistogramReport,
    colour: RGBColor,
    label: &str,
) -> DrawResult<DB> {
    let bars =
        h.edges.windows(2).zip(&h.density).map(move |(e, &d)| {
            Rectangle::new([(e[0], 0.0), (e[1], d)], colour.mix(0.35).filled())
        });
    chart.draw_series(bars)?.label(label).legend(move |(x, y)| {
        Rectangle::new([(x, y - 5), (x + 15, y + 5)], colour.mix(0.35).filled())
    });
    Ok(())
}

fn theory_line<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
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
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK.stroke_width(2)));
    Ok(())
}

fn draw_speed<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, m: &SpeciesMb) -> DrawResult<DB> {
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
    legend(&mut chart)
}

fn draw_components<DB: DrawingBackend>(
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
    legend(&mut chart)
}

fn draw_temperature<DB: DrawingBackend>(
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
    chart
        .draw_series(LineSeries::new(
            s.iter().map(|p| (p[0], p[1])),
            BLUE.stroke_width(2),
        ))?
        .label("measured kT")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLUE.stroke_width(2)));
    legend(&mut chart)
}

/// A cooling run's kT against the time since its first record on log–log axes,
/// with Haff's law T0/(1 + t/t0)² (physics.md (8.2)): flat for t ≪ t0, t⁻² after.
fn draw_cooling<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    s: &[[f64; 2]],
    h: &carom::analysis::HaffReport,
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
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLUE.stroke_width(2)));
    let n = 200;
    let curve = (0..=n).map(|k| {
        let t = x0 * (x1 / x0).powf(k as f64 / n as f64);
        (t, haff(t))
    });
    chart
        .draw_series(DashedLineSeries::new(curve, 8, 5, BLACK.stroke_width(2)))?
        .label(format!("Haff's law kT0/(1 + t/t0)², t0 = {:.4}", h.t0))
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK.stroke_width(2)));
    log_legend(&mut chart)
}

fn draw_pressure<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, r: &Report) -> DrawResult<DB> {
    let p = r.pressure.as_ref().expect("checked by the caller");
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
    chart.draw_series(std::iter::once(Rectangle::new(
        [(x0, p.z - p.z_std_error), (x1, p.z + p.z_std_error)],
        GREEN.mix(0.3).filled(),
    )))?;
    chart
        .draw_series(LineSeries::new(
            [(x0, p.z), (x1, p.z)],
            GREEN.stroke_width(2),
        ))?
        .label("mean ± one standard error")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], GREEN.stroke_width(2)));
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
                .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], RED.stroke_width(2)));
        }
    }
    chart
        .draw_series(LineSeries::new(
            s.iter().map(|q| (q[0], q[1])),
            BLUE.stroke_width(1),
        ))?
        .label("Z per interval")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLUE));
    chart.draw_series(
        s.iter()
            .map(|q| Circle::new((q[0], q[1]), 3, BLUE.filled())),
    )?;
    legend(&mut chart)
}

/// g_ab(r) of every species pair, the contact value g(σ⁺) as a dot at σ_ab.
fn draw_pair_correlation<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &Report,
) -> DrawResult<DB> {
    let pc = r.pair_correlation.as_ref().expect("checked by the caller");
    let x1 = pc.r_max;
    let y1 = top(pc.pairs.iter().flat_map(|p| p.g.iter().copied()));
    let caption = match &pc.contact_theorem {
        Some(c) => format!(
            "g(r): contact theorem Z = {:.4} ± {:.4}, virial Z = {:.4} ± {:.4}",
            c.z_structure, c.z_structure_std_error, c.z_virial, c.z_virial_std_error
        ),
        None => format!("pair correlation g(r), {} snapshots", pc.snapshots),
    };
    let axis = (
        "distance r (length)",
        "pair correlation g(r) (dimensionless)",
    );
    let mut chart = axes(root, &caption, axis, 0.0..x1, 0.0..y1)?;
    chart.draw_series(LineSeries::new([(0.0, 1.0), (x1, 1.0)], BLACK.mix(0.4)))?;
    for (k, p) in pc.pairs.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        chart
            .draw_series(LineSeries::new(
                pc.r.iter()
                    .zip(&p.g)
                    .filter(|(_, g)| g.is_finite())
                    .map(|(&r, &g)| (r, g)),
                colour.stroke_width(2),
            ))?
            .label(format!("species {}–{}", p.a, p.b))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 15, y)], colour.stroke_width(2))
            });
        if let Some(c) = &p.contact {
            chart.draw_series(std::iter::once(Circle::new(
                (p.sigma, c.value),
                4,
                colour.filled(),
            )))?;
        }
    }
    legend(&mut chart)
}

/// n(y) per species (bin centres, log scale) and each species' fitted barometric
/// law n(a) e^{−β (y − a)} (physics.md (15.6)), with the known m g/kT in the caption.
fn draw_density_profile<DB: DrawingBackend>(
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
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(y0..y1, (0.8 * lo..1.25 * hi).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("height y (length)")
        .y_desc("n(y) (1/length²)")
        .y_label_formatter(&|v| format!("{v:.3}"))
        .draw()?;
    for (s, pts) in points.iter().enumerate() {
        let color = Palette99::pick(s).to_rgba();
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))?
            .label(format!("species {s}"))
            .legend(move |(x, y)| Circle::new((x + 7, y), 3, color.filled()));
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
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 15, y)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
}
