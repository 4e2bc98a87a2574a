//! Drawing one snapshot: every disc as a filled circle of its own radius (to
//! scale: radius a is a·s pixels; anti-aliased at sub-pixel precision in bitmaps,
//! see `raster`, whole pixels in SVG) with a darker rim, its
//! periodic images where it crosses a periodic edge (the box is then masked so
//! that each disc shows cut at one edge and completed at the other), the box's
//! edges — solid for hard walls, dashed for periodic boundaries — and a title with
//! t, N and the packing fraction η = Σ π a² / (L_x L_y). Colouring by species adds
//! a legend in the title band; colouring by speed a colour bar at the right.

use carom_log::Snapshot;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use super::colours::{scale_colour, species_colour, wheel_colour, BACKGROUND};
use super::layout::{Layout, MARGIN, TITLE};
use super::raster::Raster;

/// How discs are coloured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Colouring {
    /// By species, from a fixed palette.
    Species,
    /// By speed |v|, on the viridis map from 0 to `max`.
    Speed {
        /// The speed at the top of the scale (length/time).
        max: f64,
    },
    /// By the local bond order |ψ6| (physics.md §11), viridis from 0 to 1.
    Psi6,
    /// By the phase arg ψ6 / 6 on a colour wheel.
    Psi6Phase,
}

/// ψ6 of every disc of `s` (Delaunay neighbours, minimum image along periodic axes).
fn psi6_of(s: &Snapshot, periodic: [bool; 2]) -> Vec<[f64; 2]> {
    let mut sim_box = carom_core::SimBox::periodic(s.box_size.x, s.box_size.y);
    for (b, p) in sim_box.boundary.iter_mut().zip(periodic) {
        if !p {
            *b = carom_core::Boundary::Walls { restitution: 1.0 };
        }
    }
    let (x, y): (Vec<f64>, Vec<f64>) = s.positions.iter().map(|p| (p.x, p.y)).unzip();
    carom_analysis::local_psi6(&sim_box, &x, &y)
}

/// How discs are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiscStyle {
    /// Anti-aliased at their exact sizes into a bitmap ([`Raster`]), for PNG and GIF.
    Raster,
    /// As circles (whole-pixel centres and radii), for SVG.
    Vector,
}

/// Drawing result of a backend `DB`.
pub type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// The shifts (in box lengths) at which a disc at `x` with radius `r` is drawn on
/// an axis of length `l`: itself, and its image across a periodic edge it crosses.
fn images(x: f64, r: f64, l: f64, periodic: bool) -> impl Iterator<Item = f64> {
    let lower = periodic && x < r;
    let upper = periodic && x > l - r;
    [Some(0.0), lower.then_some(l), upper.then_some(-l)]
        .into_iter()
        .flatten()
}

fn font(size: u32) -> TextStyle<'static> {
    ("sans-serif", size).into_font().color(&BLACK)
}

/// Draw `s` into `area` (the whole image) with `layout` and `colouring`.
pub fn draw_snapshot<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    s: &Snapshot,
    layout: &Layout,
    colouring: Colouring,
    style: DiscStyle,
) -> DrawResult<DB> {
    area.fill(&BACKGROUND)?;
    let l = s.box_size;
    let periodic = [s.boundary[0] == 0, s.boundary[1] == 0];
    let mut raster = (style == DiscStyle::Raster).then(|| Raster::new(layout, BACKGROUND));
    let psi =
        matches!(colouring, Colouring::Psi6 | Colouring::Psi6Phase).then(|| psi6_of(s, periodic));
    for (i, p) in s.positions.iter().enumerate() {
        let k = s.species[i];
        let r = s.species_radius.get(usize::from(k)).copied().unwrap_or(0.0);
        let colour = match colouring {
            Colouring::Species => species_colour(k),
            Colouring::Speed { max } => scale_colour(s.velocities[i].length(), max),
            Colouring::Psi6 => psi
                .as_ref()
                .map_or(BACKGROUND, |p| scale_colour(p[i][0].hypot(p[i][1]), 1.0)),
            Colouring::Psi6Phase => psi.as_ref().map_or(BACKGROUND, |p| {
                wheel_colour(p[i][1].atan2(p[i][0]) / std::f64::consts::TAU)
            }),
        };
        let radius = r * layout.scale;
        for dx in images(p.x, r, l.x, periodic[0]) {
            for dy in images(p.y, r, l.y, periodic[1]) {
                let (px, py) = layout.pixel(p.x + dx, p.y + dy);
                match &mut raster {
                    Some(raster) => raster.disc(px, py, radius, colour),
                    None => {
                        let centre = (px.round() as i32, py.round() as i32);
                        let rounded = radius.round().max(1.0) as i32;
                        area.draw(&Circle::new(centre, rounded, colour.filled()))?;
                        let rim = RGBColor(colour.0 / 2, colour.1 / 2, colour.2 / 2);
                        area.draw(&Circle::new(centre, rounded, rim.stroke_width(1)))?;
                    }
                }
            }
        }
    }
    if let Some(raster) = &raster {
        if let Some(image) = BitMapElement::with_ref((0, 0), raster.size, &raster.rgb) {
            area.draw(&image)?;
        }
    }
    // Mask what spills over the box (periodic images) with the background.
    let (w, h) = (layout.size.0 as i32, layout.size.1 as i32);
    let ((x0, y0), (x1, y1)) = layout.box_pixels();
    for rect in [
        [(0, 0), (w, y0)],
        [(0, y1), (w, h)],
        [(0, 0), (x0, h)],
        [(x1, 0), (w, h)],
    ] {
        area.draw(&Rectangle::new(rect, BACKGROUND.filled()))?;
    }
    // The box: x's boundary is the left and right edges, y's the bottom and top.
    let edges = [
        (periodic[0], [(x0, y0), (x0, y1)]),
        (periodic[0], [(x1, y0), (x1, y1)]),
        (periodic[1], [(x0, y0), (x1, y0)]),
        (periodic[1], [(x0, y1), (x1, y1)]),
    ];
    for (dashed, [a, b]) in edges {
        if dashed {
            area.draw(&DashedPathElement::new([a, b], 6, 5, BLACK.stroke_width(1)))?;
        } else {
            area.draw(&PathElement::new([a, b], BLACK.stroke_width(2)))?;
        }
    }
    draw_title(area, s, periodic, layout.size.0)?;
    match colouring {
        Colouring::Species => draw_legend(area, s, layout)?,
        Colouring::Speed { max } => draw_bar(area, layout, ("speed |v|", 0.0), max, |v| {
            scale_colour(v, max)
        })?,
        Colouring::Psi6 => draw_bar(area, layout, ("order |ψ6|", 0.0), 1.0, |v| {
            scale_colour(v, 1.0)
        })?,
        // arg ψ6 / 6 in degrees, −30 to 30: the wheel's full turn.
        Colouring::Psi6Phase => draw_bar(area, layout, ("arg ψ6 / 6 (°)", -30.0), 60.0, |v| {
            wheel_colour(v / 60.0 - 0.5)
        })?,
    }
    Ok(())
}

fn draw_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    s: &Snapshot,
    periodic: [bool; 2],
    width: u32,
) -> DrawResult<DB> {
    let covered: f64 = s
        .species
        .iter()
        .map(|&k| {
            let a = s.species_radius.get(usize::from(k)).copied().unwrap_or(0.0);
            std::f64::consts::PI * a * a
        })
        .sum();
    let eta = covered / (s.box_size.x * s.box_size.y);
    let edges = match periodic {
        [true, true] => "periodic",
        [false, false] => "walls",
        [true, false] => "periodic x, walls y",
        [false, true] => "walls x, periodic y",
    };
    let title = format!(
        "t = {}   N = {}   η = {eta:.3}   ({edges})",
        crate::frames::time_text(s.time),
        s.positions.len()
    );
    // About 45 characters: smaller type in narrow pictures.
    area.draw(&Text::new(
        title,
        (MARGIN as i32, 6),
        font((width / 26).clamp(10, 20)),
    ))
}

/// Species legend on the title band's second line: a dot and "A  a = 0.5".
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    s: &Snapshot,
    _layout: &Layout,
) -> DrawResult<DB> {
    let n = s.species_radius.len();
    if n < 2 {
        return Ok(());
    }
    let shown = n.min(6);
    let mut x = MARGIN as i32 + 7;
    let y = TITLE as i32 - 14;
    for k in 0..shown {
        area.draw(&Circle::new((x, y), 6, species_colour(k as u16).filled()))?;
        let label = format!(
            "{}  a = {}",
            crate::export::type_name(k),
            s.species_radius[k]
        );
        area.draw(&Text::new(label, (x + 11, y - 8), font(15)))?;
        x += 120;
    }
    if n > shown {
        area.draw(&Text::new(format!("… {n} species"), (x, y - 8), font(15)))?;
    }
    Ok(())
}

/// A colour bar label: three significant digits of the scale's top `max`.
fn tick(v: f64, max: f64) -> String {
    let decimals = (2.0 - max.log10().floor()).clamp(0.0, 8.0) as usize;
    format!("{v:.decimals$}")
}

/// A colour bar titled `label`: `colour(v)` for v from 0 (bottom) to `max` (top),
/// labelled v + `offset`.
fn draw_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    layout: &Layout,
    (label, offset): (&str, f64),
    max: f64,
    colour: impl Fn(f64) -> RGBColor,
) -> DrawResult<DB> {
    let Some((x, y, w, h)) = layout.bar else {
        return Ok(());
    };
    for row in 0..h {
        let v = max * f64::from(h - 1 - row) / f64::from((h - 1).max(1));
        area.draw(&Rectangle::new(
            [(x, y + row), (x + w, y + row + 1)],
            colour(v).filled(),
        ))?;
    }
    area.draw(&Rectangle::new(
        [(x, y), (x + w, y + h)],
        BLACK.stroke_width(1),
    ))?;
    for j in 0..=4 {
        let v = max * f64::from(j) / 4.0;
        let py = y + h - 1 - ((h - 1) * j) / 4;
        area.draw(&PathElement::new([(x + w, py), (x + w + 5, py)], BLACK))?;
        area.draw(&Text::new(
            tick(v + offset, max),
            (x + w + 8, py - 7),
            font(14),
        ))?;
    }
    area.draw(&Text::new(label.to_owned(), (x - 16, y - 22), font(15)))
}

#[cfg(test)]
mod tests {
    use super::{images, tick};

    #[test]
    fn colour_bar_labels_keep_three_digits_of_the_scale() {
        assert_eq!(tick(0.001, 0.00213), "0.00100");
        assert_eq!(tick(1.5, 2.5), "1.50");
        assert_eq!(tick(250.0, 400.0), "250");
    }

    #[test]
    fn a_disc_across_a_periodic_edge_is_drawn_twice_and_once_by_a_wall() {
        let v: Vec<f64> = images(0.2, 0.5, 10.0, true).collect();
        assert_eq!(v, [0.0, 10.0]);
        let v: Vec<f64> = images(9.9, 0.5, 10.0, true).collect();
        assert_eq!(v, [0.0, -10.0]);
        let v: Vec<f64> = images(0.2, 0.5, 10.0, false).collect();
        assert_eq!(v, [0.0]);
        let v: Vec<f64> = images(5.0, 0.5, 10.0, true).collect();
        assert_eq!(v, [0.0]);
    }
}
