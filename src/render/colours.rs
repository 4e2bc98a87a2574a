//! The colours of a picture: a fixed palette for species (Tableau's ten
//! categorical colours, distinguishable in print and by most colour-blind
//! readers; species k > 9 reuse them) and the viridis map for speeds, which is
//! perceptually uniform: equal steps in speed look like equal steps in colour.
//! Speeds map linearly from 0 to a maximum v_max, faster ones get v_max's colour;
//! the local order |ψ6| maps from 0 to 1 the same way. The phase of ψ6 (a
//! bond direction modulo 60°) is an angle, so it gets a colour wheel: hue
//! from the angle, the two ends of the range the same colour.

use plotters::style::colors::colormaps::ViridisRGB;
use plotters::style::RGBColor;

/// Species colours in order.
pub const SPECIES: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// The background outside the discs.
pub const BACKGROUND: RGBColor = RGBColor(255, 255, 255);

/// The colour of species `k`.
pub fn species_colour(k: u16) -> RGBColor {
    SPECIES[usize::from(k) % SPECIES.len()]
}

/// The colour of `value` on a scale from 0 to `max` (viridis).
pub fn scale_colour(value: f64, max: f64) -> RGBColor {
    let h = if max > 0.0 { value / max } else { 0.0 };
    ViridisRGB::get_color(h.clamp(0.0, 1.0))
}

/// The colour of the fraction `turn` of a full turn on a colour wheel (hue
/// 360° × turn at saturation 0.8, value 0.95): 0 and 1 give the same colour.
pub fn wheel_colour(turn: f64) -> RGBColor {
    let h = 6.0 * turn.rem_euclid(1.0);
    let (s, v) = (0.8, 0.95);
    let f = h - h.floor();
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - s * f), v * (1.0 - s * (1.0 - f)));
    let (r, g, b) = match h as u32 {
        0 => (v, t, p),
        1 => (q, v, p),
        2 => (p, v, t),
        3 => (p, q, v),
        4 => (t, p, v),
        _ => (v, p, q),
    };
    let byte = |c: f64| (255.0 * c).round() as u8;
    RGBColor(byte(r), byte(g), byte(b))
}

/// The top of the speed scale for a set of speeds: their 99th percentile (so one
/// fast disc does not wash out the rest), or 1 if all are 0.
pub fn speed_scale(speeds: &mut [f64]) -> f64 {
    if speeds.is_empty() {
        return 1.0;
    }
    let k = ((speeds.len() - 1) as f64 * 0.99).round() as usize;
    let (_, v, _) = speeds.select_nth_unstable_by(k, f64::total_cmp);
    if *v > 0.0 {
        *v
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn speeds_map_from_dark_to_light_and_species_differ() {
        let slow = scale_colour(0.0, 2.0);
        let fast = scale_colour(2.0, 2.0);
        let luma =
            |c: RGBColor| 0.3 * f64::from(c.0) + 0.59 * f64::from(c.1) + 0.11 * f64::from(c.2);
        assert!(luma(slow) < luma(scale_colour(1.0, 2.0)));
        assert!(luma(scale_colour(1.0, 2.0)) < luma(fast));
        assert_eq!(scale_colour(5.0, 2.0), fast);
        for a in 0..10 {
            for b in 0..a {
                assert_ne!(species_colour(a), species_colour(b));
            }
        }
        let mut v: Vec<f64> = (0..=100).map(f64::from).collect();
        assert_eq!(speed_scale(&mut v), 99.0);
        assert_eq!(speed_scale(&mut [0.0, 0.0]), 1.0);
    }

    #[test]
    fn the_wheel_closes_and_its_hues_differ() {
        assert_eq!(wheel_colour(0.0), wheel_colour(1.0));
        assert_eq!(wheel_colour(-0.25), wheel_colour(0.75));
        let c: Vec<RGBColor> = (0..6).map(|k| wheel_colour(k as f64 / 6.0)).collect();
        for a in 0..6 {
            for b in a + 1..6 {
                assert_ne!(c[a], c[b]);
            }
        }
    }
}
