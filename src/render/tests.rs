//! The colours and the layout of a rendered snapshot, checked where they must be:
//! at each disc's centre its species' (or speed's) colour, far from every disc the
//! background, a disc across a periodic edge also at the other edge, an SVG disc a
//! circle of its colour, and a movie frame the layout's size. The snapshot is the
//! one `tests/integration/cli_render.rs` logs and renders through the command.

use std::path::PathBuf;

use carom_core::DVec2;
use carom_log::Snapshot;

use super::colours::{scale_colour, BACKGROUND, SPECIES};
use super::*;

/// Width given to every render here.
const WIDTH: u32 = 640;

/// An empty scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("carom-render-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Two discs in a 20 × 10 box at t = 0: species A (a = 3) at (1, 5) moving at
/// speed 0.5 — across the periodic edge x = 0 — (at (4, 5) between walls) and
/// species B (a = 2) at (12, 5) at speed 0.25.
fn two_discs(walls: bool) -> Snapshot {
    Snapshot {
        time: 0.0,
        box_size: DVec2::new(20.0, 10.0),
        boundary: if walls { [1, 1] } else { [0, 0] },
        species_radius: vec![3.0, 2.0],
        species_mass: vec![1.0, 2.0],
        species: vec![0, 1],
        positions: vec![
            DVec2::new(if walls { 4.0 } else { 1.0 }, 5.0),
            DVec2::new(12.0, 5.0),
        ],
        velocities: vec![DVec2::new(0.0, 0.5), DVec2::new(0.0, -0.25)],
        images: vec![[0; 2]; 2],
    }
}

/// Render `s` as a PNG `name` in `dir`; the picture and its layout.
fn png(dir: &std::path::Path, name: &str, s: &Snapshot, by: ColourBy) -> (image::RgbImage, Layout) {
    let out = dir.join(name);
    let layout = render_snapshot(s, &out, ImageFormat::Png, WIDTH, by).unwrap();
    (image::open(&out).unwrap().to_rgb8(), layout)
}

fn rgb_at(img: &image::RgbImage, layout: &Layout, x: f64, y: f64) -> [u8; 3] {
    let (px, py) = layout.pixel(x, y);
    img.get_pixel(px.round() as u32, py.round() as u32).0
}

fn rgb(c: RGBColor) -> [u8; 3] {
    [c.0, c.1, c.2]
}

#[test]
fn discs_have_their_species_colour_and_the_rest_is_background() {
    let dir = scratch("species");
    let (img, layout) = png(&dir, "a.png", &two_discs(false), ColourBy::Species);
    assert_eq!(layout, Layout::new(WIDTH, DVec2::new(20.0, 10.0), false));
    assert_eq!(img.dimensions(), layout.size);
    let a = rgb(SPECIES[0]);
    let b = rgb(SPECIES[1]);
    assert_eq!(rgb_at(&img, &layout, 1.0, 5.0), a);
    assert_eq!(rgb_at(&img, &layout, 1.0, 7.5), a);
    assert_eq!(rgb_at(&img, &layout, 12.0, 5.0), b);
    assert_eq!(rgb_at(&img, &layout, 13.5, 5.0), b);
    // A reaches 2 past x = 0: its image shows at the right edge.
    assert_eq!(rgb_at(&img, &layout, 19.5, 5.0), a);
    assert_eq!(rgb_at(&img, &layout, 7.0, 9.0), rgb(BACKGROUND));
    assert_eq!(rgb_at(&img, &layout, 16.0, 2.0), rgb(BACKGROUND));
    // Outside the box, left of x = 0, A's overhang is masked.
    let (px, py) = layout.pixel(0.0, 5.0);
    assert_eq!(img.get_pixel(px as u32 - 4, py as u32).0, rgb(BACKGROUND));

    // Walls: A (now at x = 4) is drawn once, nothing at the far edge.
    let (img, layout) = png(&dir, "w.png", &two_discs(true), ColourBy::Species);
    assert_eq!(rgb_at(&img, &layout, 4.0, 5.0), a);
    assert_eq!(rgb_at(&img, &layout, 19.5, 5.0), rgb(BACKGROUND));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn scale_colours_follow_the_speeds() {
    let dir = scratch("speed");
    let (img, layout) = png(&dir, "s.png", &two_discs(true), ColourBy::Speed);
    assert_eq!(layout, Layout::new(WIDTH, DVec2::new(20.0, 10.0), true));
    assert_eq!(img.dimensions(), layout.size);
    // The scale's top is the faster disc's speed.
    assert_eq!(rgb_at(&img, &layout, 4.0, 5.0), rgb(scale_colour(0.5, 0.5)));
    assert_eq!(
        rgb_at(&img, &layout, 12.0, 5.0),
        rgb(scale_colour(0.25, 0.5))
    );
    assert_ne!(scale_colour(0.5, 0.5), scale_colour(0.25, 0.5));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn svg_pictures_hold_the_discs_as_circles_of_their_colour() {
    let dir = scratch("svg");
    let out = dir.join("a.svg");
    let s = two_discs(true);
    let layout = render_snapshot(&s, &out, ImageFormat::Svg, WIDTH, ColourBy::Species).unwrap();
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..100]);
    assert!(svg.contains(&format!(
        "width=\"{}\" height=\"{}\"",
        layout.size.0, layout.size.1
    )));
    let (px, py) = layout.pixel(4.0, 5.0);
    let radius = (3.0 * layout.scale).round();
    let circle = format!(
        "<circle cx=\"{}\" cy=\"{}\" r=\"{radius}\" opacity=\"1\" fill=\"#1F77B4\"",
        px.round(),
        py.round()
    );
    assert!(svg.contains(&circle), "no {circle} in\n{svg}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn movie_frames_have_the_layout_size() {
    let dir = scratch("movie");
    let out = dir.join("m.gif");
    let s = two_discs(false);
    {
        let mut movie = Movie::create(&out, &s, 320, ColourBy::Species, 100).unwrap();
        assert_eq!(
            movie.layout(),
            &Layout::new(320, DVec2::new(20.0, 10.0), false)
        );
        movie.push(&s).unwrap();
        movie.push(&s).unwrap();
    }
    let file = std::fs::File::open(&out).unwrap();
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(file).unwrap();
    let layout = Layout::new(320, DVec2::new(20.0, 10.0), false);
    assert_eq!(
        (u32::from(decoder.width()), u32::from(decoder.height())),
        layout.size
    );
    let mut n = 0;
    while decoder.read_next_frame().unwrap().is_some() {
        n += 1;
    }
    assert_eq!(n, 2);
    let _ = std::fs::remove_dir_all(&dir);
}
