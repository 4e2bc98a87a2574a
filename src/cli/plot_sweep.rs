//! The figure of `carom collect --plot`: Z = βPA/N against the packing fraction
//! with one standard error per grid point (one series per combination of the
//! other varied values), over the published equation of state of hard discs
//! (physics.md §7): the Kolafa–Rottner table, Li et al.'s Monte Carlo pressures
//! near melting, and Henderson's closed form as a line.

use carom::analysis::{henderson_z, li_2022, KOLAFA_ROTTNER};
use carom::sweep::Collected;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{axes, range, DrawResult};

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

pub(super) fn draw_eos<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    series: &[Series],
) -> DrawResult<DB> {
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
        root,
        "equation of state: carom against the literature",
        axis,
        x0..x1,
        y0..y1,
    )?;
    let line: Vec<(f64, f64)> = (0..=200)
        .map(|k| x0 + (x1.min(0.72) - x0) * k as f64 / 200.0)
        .map(|eta| (eta, henderson_z(eta)))
        .collect();
    chart
        .draw_series(LineSeries::new(line, BLACK.mix(0.5).stroke_width(1)))?
        .label("Henderson (7.6)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK.mix(0.5)));
    chart
        .draw_series(
            KOLAFA_ROTTNER
                .iter()
                .filter(|r| (x0..=x1).contains(&r.0))
                .map(|r| Cross::new((r.0, r.1), 6, BLACK.stroke_width(2))),
        )?
        .label("Kolafa–Rottner")
        .legend(|(x, y)| Cross::new((x + 7, y), 5, BLACK.stroke_width(2)));
    if !li.is_empty() {
        chart
            .draw_series(
                li.iter()
                    .map(|r| TriangleMarker::new((r.2, r.3), 4, MAGENTA.filled())),
            )?
            .label("Li et al. 2022 (Monte Carlo)")
            .legend(|(x, y)| TriangleMarker::new((x + 7, y), 4, MAGENTA.filled()));
    }
    for (k, (label, pts)) in series.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        // One standard error each way, as a vertical bar.
        chart.draw_series(pts.iter().map(|p| {
            PathElement::new(
                vec![(p.0, p.1 - p.2), (p.0, p.1 + p.2)],
                colour.stroke_width(2),
            )
        }))?;
        chart
            .draw_series(
                pts.iter()
                    .map(|p| Circle::new((p.0, p.1), 4, colour.filled())),
            )?
            .label(label.clone())
            .legend(move |(x, y)| Circle::new((x + 7, y), 4, colour.filled()));
    }
    // Upper left: the curve rises to the right.
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
}
