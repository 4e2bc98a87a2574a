//! What a disc is made of.

/// One kind of disc: how many there are, their radius and their mass.
///
/// Radius is in the user's length unit (the reference data use diameter σ = 1,
/// i.e. radius 0.5); mass in the user's mass unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Species {
    /// Number of discs of this species.
    pub count: usize,
    /// Disc radius `a` (length).
    pub radius: f64,
    /// Disc mass `m` (mass).
    pub mass: f64,
}

impl Species {
    /// `count` discs of radius `radius` (length) and mass `mass` (mass).
    pub const fn new(count: usize, radius: f64, mass: f64) -> Species {
        Species {
            count,
            radius,
            mass,
        }
    }

    /// `count` discs of the reference data's size and mass (physics.md): diameter
    /// σ = 1 (radius 0.5) and mass 1.
    pub const fn reference(count: usize) -> Species {
        Species::new(count, 0.5, 1.0)
    }

    /// `count` discs `ratio` times as wide as the reference disc (diameter
    /// `ratio` σ) and as heavy as their area (mass `ratio²`): the same mass per
    /// area as [`Species::reference`].
    pub fn scaled(count: usize, ratio: f64) -> Species {
        Species::new(count, 0.5 * ratio, ratio * ratio)
    }

    /// Area covered by one disc, π a² (length²).
    pub fn disc_area(&self) -> f64 {
        std::f64::consts::PI * self.radius * self.radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaled_discs_keep_the_reference_mass_per_area() {
        let unit = Species::reference(7);
        assert_eq!((unit.count, unit.radius, unit.mass), (7, 0.5, 1.0));
        for ratio in [0.5, 1.0, 1.4, 3.0, 10.0] {
            let s = Species::scaled(3, ratio);
            assert_eq!(s.count, 3);
            assert_eq!(2.0 * s.radius, ratio, "diameter ratio {ratio}");
            let per_area = s.mass / s.disc_area();
            let unit_per_area = unit.mass / unit.disc_area();
            assert!(
                (per_area / unit_per_area - 1.0).abs() < 1e-15,
                "ratio {ratio}: {per_area} against {unit_per_area}"
            );
        }
        assert_eq!(Species::scaled(5, 1.0), Species::reference(5));
    }
}
