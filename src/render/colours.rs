//! The colours of a picture: a fixed palette for species (Tableau's ten
//! categorical colours, distinguishable in print and by most colour-blind
//! readers; species k > 9 reuse them) and the viridis map for speeds, which is
//! perceptually uniform: equal steps in speed look like equal steps in colour.
//! Speeds map linearly from 0 to a maximum v_max, faster ones get v_max's colour.

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

/// The colour of `speed` on a scale from 0 to `max`.
pub fn speed_colour(speed: f64, max: f64) -> RGBColor {
    let h = if max > 0.0 { speed / max } else { 0.0 };
    ViridisRGB::get_color(h.clamp(0.0, 1.0))
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
        let slow = speed_colour(0.0, 2.0);
        let fast = speed_colour(2.0, 2.0);
        let luma =
            |c: RGBColor| 0.3 * f64::from(c.0) + 0.59 * f64::from(c.1) + 0.11 * f64::from(c.2);
        assert!(luma(slow) < luma(speed_colour(1.0, 2.0)));
        assert!(luma(speed_colour(1.0, 2.0)) < luma(fast));
        assert_eq!(speed_colour(5.0, 2.0), fast);
        for a in 0..10 {
            for b in 0..a {
                assert_ne!(species_colour(a), species_colour(b));
            }
        }
        let mut v: Vec<f64> = (0..=100).map(f64::from).collect();
        assert_eq!(speed_scale(&mut v), 99.0);
        assert_eq!(speed_scale(&mut [0.0, 0.0]), 1.0);
    }
}
