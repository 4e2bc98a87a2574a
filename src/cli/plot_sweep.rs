//! The figure of `carom collect --plot`: Z = βPA/N against the packing fraction
//! with one standard error per grid point (one series per combination of the
//! other varied values), over the published equation of state of hard discs
//! (physics.md §7): the Kolafa–Rottner table, Li et al.'s Monte Carlo pressures
//! near melting, and Henderson's closed form as a line; under it the residual
//! of each point against its reference in standard errors.

use carom_analysis::{henderson_z, kolafa_rottner, li_2022, KOLAFA_ROTTNER};
use carom_run::sweep::Collected;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{axes, bars, dot_key, legend, line_key};
use super::{range, DrawResult};

/// One series of the figure: its label and its points (η, Z, one standard error).
pub(super) type Series = (String, Vec<(f64, f64, f64)>);

/// One series per combination of the other varied values, from the collected
/// grid points with Z.
pub(super) fn eos_series(c: &Collected, eta_axis: &str) -> Vec<Series> {
    let mut series: Vec<Series> = Vec::new();
    for p in &c.points {
        let (Some(eta), Some(z)) = (p.values[eta_axis].as_f64(), p.results.get("Z")) else {
            continue;
        };
        let label: Vec<String> = c
            .axes
            .iter()
            .filter(|a| a.as_str() != eta_axis)
            .map(|a| format!("{a} = {}", p.values[a]))
            .collect();
        let label = if label.is_empty() {
            "carom".to_owned()
        } else {
            label.join(", ")
        };
        let point = (eta, z.value, z.std_error.unwrap_or(0.0));
        match series.iter_mut().find(|s| s.0 == label) {
            Some(s) => s.1.push(point),
            None => series.push((label, vec![point])),
        }
    }
    for s in &mut series {
        s.1.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    series
}

/// The reference Z at η and its error: Kolafa–Rottner at the table's η, else
/// Li et al. 2022 at theirs (the first row at that η), else none.
fn reference(eta: f64) -> Option<(f64, f64, &'static str)> {
    if let Some((z, e)) = kolafa_rottner(eta) {
        return Some((z, e, "Kolafa–Rottner"));
    }
    li_2022()
        .into_iter()
        .find(|r| (r.2 - eta).abs() < 1e-9)
        .map(|r| (r.3, r.4, "Li et al."))
}

/// Z(η) over the references (upper panel) and, under it, each point's
/// residual (Z − Z_ref)/SE against its reference with SE² = SE_carom² +
/// SE_ref², with ±2 marked.
pub(super) fn draw_eos<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    series: &[Series],
) -> DrawResult<DB> {
    let (upper, lower) = root.split_vertically(root.dim_in_pixel().1 * 68 / 100);
    let all = || series.iter().flat_map(|s| s.1.iter());
    let (x0, x1) = range(all().map(|p| p.0));
    let (x0, x1) = (x0.max(0.0), x1);
    let li: Vec<_> = li_2022()
        .into_iter()
        .filter(|r| (x0..=x1).contains(&r.2))
        .collect();
    let (y0, y1) = range(
        all()
            .flat_map(|p| [p.1 - p.2, p.1 + p.2])
            .chain(li.iter().map(|r| r.3))
            .chain([henderson_z(x0), henderson_z(x1.min(0.72))]),
    );
    let axis = ("packing fraction η", "Z = βPA/N");
    let mut chart = axes(
        &upper,
        "equation of state: carom against the literature",
        axis,
        x0..x1,
        y0..y1,
    )?;
    let line: Vec<(f64, f64)> = (0..=200)
        .map(|k| x0 + (x1.min(0.72) - x0) * k as f64 / 200.0)
        .map(|eta| (eta, henderson_z(eta)))
        .collect();
    let grey = BLACK.mix(0.5).stroke_width(1);
    chart
        .draw_series(LineSeries::new(line.iter().copied(), grey))?
        .label("Henderson (7.6)")
        .legend(line_key(grey));
    chart
        .draw_series(
            KOLAFA_ROTTNER
                .iter()
                .filter(|r| (x0..=x1).contains(&r.0))
                .map(|r| Cross::new((r.0, r.1), 6, BLACK.stroke_width(2))),
        )?
        .label("Kolafa–Rottner")
        .legend(|(x, y)| Cross::new((x + 10, y), 5, BLACK.stroke_width(2)));
    if !li.is_empty() {
        chart
            .draw_series(
                li.iter()
                    .map(|r| TriangleMarker::new((r.2, r.3), 5, MAGENTA.filled())),
            )?
            .label("Li et al. 2022 (Monte Carlo)")
            .legend(|(x, y)| TriangleMarker::new((x + 10, y), 5, MAGENTA.filled()));
    }
    for (k, (label, pts)) in series.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        let bar_label = (k == 0).then_some("± one standard error");
        bars(
            &mut chart,
            pts.iter().copied(),
            colour.stroke_width(2),
            bar_label,
        )?;
        chart
            .draw_series(
                pts.iter()
                    .map(|p| Circle::new((p.0, p.1), 4, colour.filled())),
            )?
            .label(label.clone())
            .legend(dot_key(colour.filled(), 4));
    }
    let data: Vec<(f64, f64)> = all().map(|p| (p.0, p.1)).chain(line).collect();
    legend(&mut chart, &data)?;

    let residuals: Vec<Vec<(f64, f64)>> = series
        .iter()
        .map(|(_, pts)| {
            pts.iter()
                .filter_map(|&(eta, z, e)| {
                    let (zr, er, _) = reference(eta)?;
                    let se = (e * e + er * er).sqrt();
                    (se > 0.0).then(|| (eta, (z - zr) / se))
                })
                .collect()
        })
        .collect();
    let big = residuals
        .iter()
        .flatten()
        .map(|p| p.1.abs())
        .fold(3.0, f64::max)
        * 1.15;
    let axis = ("packing fraction η", "(Z − Z_ref)/SE");
    let mut chart = axes(
        &lower,
        "residual (Z − Z_ref)/√(SE² + SE_ref²), Z_ref: Kolafa–Rottner or Li et al.",
        axis,
        x0..x1,
        -big..big,
    )?;
    let grey = BLACK.mix(0.5).stroke_width(1);
    chart.draw_series(LineSeries::new([(x0, 0.0), (x1, 0.0)], grey))?;
    let dashed = BLACK.mix(0.5).stroke_width(1);
    for v in [-2.0, 2.0] {
        chart.draw_series(DashedLineSeries::new([(x0, v), (x1, v)], 6, 4, dashed))?;
    }
    for (k, r) in residuals.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        chart.draw_series(r.iter().map(|&p| Circle::new(p, 4, colour.filled())))?;
    }
    Ok(())
}
