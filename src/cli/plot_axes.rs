//! What every figure shares: the chart (linear or logarithmic axes), its ticks,
//! the legend and its keys, and one standard error drawn as a band or as bars.
//!
//! A log axis is ticked at the decades 10^k and labelled "10ᵏ" in superscripts
//! (DejaVu Sans, the embedded font, has them); at most [`MAX_DECADE_LABELS`]
//! decades are labelled (every second, third, … when it spans more), and an axis
//! holding fewer than three decades is labelled at 1, 2 and 5 × 10^k (or at
//! every m × 10^k when even those are fewer than two). The light grid is at
//! m × 10^k, m = 1…9. The legend goes to the corner of the plot holding the
//! fewest data points, and each key is drawn in its series' style (solid,
//! dashed, dot, band or bar).

use std::ops::Range;

use plotters::coord::combinators::{BindKeyPoints, LogCoord, WithKeyPoints};
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters_backend::BackendCoord;

use super::DrawResult;

/// The most decades labelled on one log axis (thinned to every k-th beyond).
pub(super) const MAX_DECADE_LABELS: usize = 8;

/// A log axis ticked by [`log_ticks`].
pub(super) type LogRange = WithKeyPoints<LogCoord<f64>>;
/// A linear axis.
pub(super) type Lin = RangedCoordf64;
/// A chart over x × y axes of either kind.
pub(super) type Fig<'a, DB, X, Y> = ChartContext<'a, DB, Cartesian2d<X, Y>>;
/// A chart with linear axes on both sides.
pub(super) type Chart<'a, DB> = Fig<'a, DB, Lin, Lin>;
/// A chart with logarithmic axes on both sides.
pub(super) type LogChart<'a, DB> = Fig<'a, DB, LogRange, LogRange>;

/// An f64 axis of a figure, logarithmic or not.
pub(super) trait Axis: Ranged<ValueType = f64> + ValueFormatter<f64> {
    /// Whether it is logarithmic (labelled by [`pow10_label`]).
    const LOG: bool;
}
impl Axis for LogRange {
    const LOG: bool = true;
}
impl Axis for Lin {
    const LOG: bool = false;
}

/// The (labelled, light-grid) ticks of a log axis over [lo, hi], lo > 0.
pub(super) fn log_ticks(lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>) {
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let inside = |v: &f64| *v >= lo * (1.0 - 1e-9) && *v <= hi * (1.0 + 1e-9);
    let at = |m: f64, k: i32| m * 10f64.powi(k);
    let with = |ms: &[f64]| -> Vec<f64> {
        (k0..=k1)
            .flat_map(|k| ms.iter().map(move |&m| at(m, k)))
            .filter(inside)
            .collect()
    };
    let all = with(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]);
    let decades: Vec<i32> = (k0..=k1).filter(|&k| inside(&at(1.0, k))).collect();
    if decades.len() >= 3 {
        let stride = decades.len().div_ceil(MAX_DECADE_LABELS) as i32;
        let major = decades
            .iter()
            .filter(|k| k.rem_euclid(stride) == 0)
            .map(|&k| at(1.0, k))
            .collect();
        let light = if stride == 1 {
            all
        } else {
            decades.iter().map(|&k| at(1.0, k)).collect()
        };
        return (major, light);
    }
    let one_two_five = with(&[1.0, 2.0, 5.0]);
    if one_two_five.len() >= 2 {
        (one_two_five, all)
    } else {
        (all.clone(), all)
    }
}

/// `v` = m × 10^k as "10ᵏ" (m = 1) or "m×10ᵏ", the exponent in superscripts.
pub(super) fn pow10_label(v: f64) -> String {
    if !(v.is_finite() && v > 0.0) {
        return String::new();
    }
    let mut k = (v.log10() + 1e-9).floor() as i32;
    let mut m = (v / 10f64.powi(k)).round();
    if m >= 10.0 {
        (m, k) = (1.0, k + 1);
    }
    let sup: String = k
        .to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            d => ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'][d as usize - '0' as usize],
        })
        .collect();
    if m == 1.0 {
        format!("10{sup}")
    } else {
        format!("{m}×10{sup}")
    }
}

/// A log axis over [lo, hi] ticked by [`log_ticks`].
pub(super) fn log_range(lo: f64, hi: f64) -> LogRange {
    let (major, light) = log_ticks(lo, hi);
    (lo..hi)
        .log_scale()
        .with_key_points(major)
        .with_light_points(light)
}

/// A linear axis over `r`.
pub(super) fn lin(r: Range<f64>) -> Lin {
    r.into()
}

/// The chart of a figure: a caption and labelled axes over `x` × `y`.
pub(super) fn chart<'a, DB: DrawingBackend, X: Axis, Y: Axis>(
    root: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x_desc, y_desc): (&str, &str),
    x: X,
    y: Y,
) -> Result<Fig<'a, DB, X, Y>, DrawingAreaErrorKind<DB::ErrorType>> {
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", 22))
        .margin(15)
        .margin_right(30)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x, y)?;
    let log = |v: &f64| pow10_label(*v);
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(x_desc)
        .y_desc(y_desc)
        .label_style(("sans-serif", 14));
    if X::LOG {
        mesh.x_label_formatter(&log);
    }
    if Y::LOG {
        mesh.y_label_formatter(&log);
    }
    mesh.draw()?;
    Ok(chart)
}

/// A chart with linear axes over `x` × `y`.
pub(super) fn axes<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    caption: &str,
    desc: (&str, &str),
    x: Range<f64>,
    y: Range<f64>,
) -> Result<Chart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    chart(root, caption, desc, lin(x), lin(y))
}

/// The log–log chart of a figure over x0..x1 and 0.8 y0..1.25 y1 (room above
/// and below the data).
pub(super) fn log_axes<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    caption: &str,
    desc: (&str, &str),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Result<LogChart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    chart(
        root,
        caption,
        desc,
        log_range(x0, x1),
        log_range(0.8 * y0, 1.25 * y1),
    )
}

/// Draw the legend of the labelled series in the corner (of six places) that
/// holds the fewest of `data` (the points drawn), within a box of about half
/// the plot's width and a third of its height.
pub(super) fn legend<'a, DB: DrawingBackend + 'a, X: Axis, Y: Axis>(
    chart: &mut Fig<'a, DB, X, Y>,
    data: &[(f64, f64)],
) -> DrawResult<DB> {
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let (w, h) = ((xr.end - xr.start) as f64, (yr.end - yr.start) as f64);
    let pixels: Vec<(f64, f64)> = data
        .iter()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .map(|p| chart.backend_coord(p))
        .map(|(x, y)| ((x - xr.start) as f64 / w, (y - yr.start) as f64 / h))
        .collect();
    use SeriesLabelPosition::*;
    // (place, its box as fractions of the plot: x from, x to, y from, y to)
    let places = [
        (UpperRight, 0.5, 1.0, 0.0, 0.35),
        (UpperLeft, 0.0, 0.5, 0.0, 0.35),
        (LowerRight, 0.5, 1.0, 0.65, 1.0),
        (LowerLeft, 0.0, 0.5, 0.65, 1.0),
        (UpperMiddle, 0.25, 0.75, 0.0, 0.35),
        (LowerMiddle, 0.25, 0.75, 0.65, 1.0),
    ];
    let count = |&(_, x0, x1, y0, y1): &(SeriesLabelPosition, f64, f64, f64, f64)| {
        pixels
            .iter()
            .filter(|p| (x0..=x1).contains(&p.0) && (y0..=y1).contains(&p.1))
            .count()
    };
    let best = places
        .iter()
        .min_by_key(|p| count(p))
        .map_or(UpperRight, |p| p.0.clone());
    chart
        .configure_series_labels()
        .position(best)
        .label_font(("sans-serif", 14))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
}

/// The key of a solid line.
pub(super) fn line_key(style: ShapeStyle) -> impl Fn(BackendCoord) -> PathElement<BackendCoord> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style)
}

/// A dashed key: the points of a 21-pixel line from `(x, y)`, dashed 5 on 3.
type Dashes = DashedPathElement<std::array::IntoIter<BackendCoord, 2>, i32>;

/// The key of a dashed line.
pub(super) fn dash_key(style: ShapeStyle) -> impl Fn(BackendCoord) -> Dashes {
    move |(x, y)| DashedPathElement::new([(x, y), (x + 21, y)], 5, 3, style)
}

/// The key of a dot (a marker of radius `r`).
pub(super) fn dot_key(
    style: ShapeStyle,
    r: i32,
) -> impl Fn(BackendCoord) -> Circle<BackendCoord, i32> {
    move |(x, y)| Circle::new((x + 10, y), r, style)
}

/// The key of a filled band.
pub(super) fn fill_key(colour: RGBAColor) -> impl Fn(BackendCoord) -> Rectangle<BackendCoord> {
    move |(x, y)| Rectangle::new([(x, y - 6), (x + 20, y + 6)], colour.filled())
}

/// The key of an error bar: an I with its caps.
pub(super) fn bar_key(style: ShapeStyle) -> impl Fn(BackendCoord) -> PathElement<BackendCoord> {
    move |(x, y)| {
        let c = x + 10;
        PathElement::new(
            vec![
                (c - 4, y - 7),
                (c + 4, y - 7),
                (c, y - 7),
                (c, y + 7),
                (c - 4, y + 7),
                (c + 4, y + 7),
            ],
            style,
        )
    }
}

/// The fill of a band of one standard error around a series of `colour`.
pub(super) fn band_colour(colour: RGBAColor) -> RGBAColor {
    colour.mix(0.25)
}

/// One standard error around a curve as a filled band between y − SE and
/// y + SE, for the points (x, y, SE) with all three finite (on a log y axis
/// the lower edge is kept inside the axis). `label` names it in the legend.
pub(super) fn band<'a, DB: DrawingBackend + 'a, X: Axis, Y: Axis>(
    chart: &mut Fig<'a, DB, X, Y>,
    points: impl Iterator<Item = (f64, f64, f64)>,
    colour: RGBAColor,
    label: Option<&str>,
) -> DrawResult<DB> {
    let pts: Vec<(f64, f64, f64)> = points
        .filter(|p| p.0.is_finite() && p.1.is_finite() && p.2.is_finite())
        .collect();
    if pts.len() < 2 {
        return Ok(());
    }
    let floor = if Y::LOG {
        chart.y_range().start
    } else {
        f64::NEG_INFINITY
    };
    let upper = pts.iter().map(|p| (p.0, p.1 + p.2));
    let lower = pts.iter().rev().map(|p| (p.0, (p.1 - p.2).max(floor)));
    let fill = band_colour(colour);
    let drawn = chart.draw_series(std::iter::once(Polygon::new(
        upper.chain(lower).collect::<Vec<_>>(),
        fill.filled(),
    )))?;
    if let Some(l) = label {
        drawn.label(l).legend(fill_key(fill));
    }
    Ok(())
}

/// One standard error at each point (x, y, SE) with SE finite and positive, as
/// a vertical bar from y − SE to y + SE. `label` names it in the legend.
pub(super) fn bars<'a, DB: DrawingBackend + 'a, X: Axis, Y: Axis>(
    chart: &mut Fig<'a, DB, X, Y>,
    points: impl Iterator<Item = (f64, f64, f64)>,
    style: ShapeStyle,
    label: Option<&str>,
) -> DrawResult<DB> {
    let floor = if Y::LOG {
        chart.y_range().start
    } else {
        f64::NEG_INFINITY
    };
    let drawn = chart.draw_series(
        points
            .filter(|p| p.0.is_finite() && p.1.is_finite() && p.2.is_finite() && p.2 > 0.0)
            .map(|(x, y, e)| PathElement::new(vec![(x, (y - e).max(floor)), (x, y + e)], style)),
    )?;
    if let Some(l) = label {
        drawn.label(l).legend(bar_key(style));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Decade labels are distinct powers of ten inside the range; a narrow
    /// range is labelled at 1, 2, 5 × 10^k.
    #[test]
    fn log_ticks_are_decades_or_one_two_five() {
        let (major, _) = log_ticks(1.3e-3, 2.4);
        let labels: Vec<String> = major.iter().map(|&v| pow10_label(v)).collect();
        assert_eq!(labels, ["10⁻²", "10⁻¹", "10⁰"]);
        let (major, _) = log_ticks(1.0, 40.0);
        let labels: Vec<String> = major.iter().map(|&v| pow10_label(v)).collect();
        assert_eq!(labels, ["10⁰", "2×10⁰", "5×10⁰", "10¹", "2×10¹"]);
        let (major, _) = log_ticks(0.15, 0.9);
        let labels: Vec<String> = major.iter().map(|&v| pow10_label(v)).collect();
        assert_eq!(labels, ["2×10⁻¹", "5×10⁻¹"]);
        let (major, _) = log_ticks(1e-20, 1e5);
        assert!(major.len() <= MAX_DECADE_LABELS, "{}", major.len());
        assert!(major.iter().all(|v| pow10_label(*v).starts_with("10")));
    }
}
