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

/// Why a list of species cannot make a system: the species it concerns (`None`: the
/// list as a whole) and which of its settings, what was wrong and what is allowed.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeciesProblem {
    /// The species and setting (`"radius"`, `"mass"`), or `None` for the list.
    pub setting: Option<(usize, &'static str)>,
    /// What was wrong.
    pub problem: String,
    /// What is allowed.
    pub allowed: &'static str,
}

/// The one check of a list of species: at least one and at most 65535 species,
/// finite positive radii and masses, and 1 ≤ N < 2³² − 1 discs in all (disc
/// numbers are `u32`, with `u32::MAX` meaning none). Returns N.
pub fn check_species(species: &[Species]) -> Result<usize, SpeciesProblem> {
    let whole = |problem: String, allowed| SpeciesProblem {
        setting: None,
        problem,
        allowed,
    };
    if species.is_empty() {
        return Err(whole(
            "the list is empty".into(),
            "at least one species {\"count\": N, \"radius\": a, \"mass\": m}",
        ));
    }
    if species.len() > u16::MAX as usize {
        return Err(whole(
            format!("{} species", species.len()),
            "at most 65535 species",
        ));
    }
    let mut n = 0usize;
    for (k, s) in species.iter().enumerate() {
        for (setting, x) in [("radius", s.radius), ("mass", s.mass)] {
            if !(x.is_finite() && x > 0.0) {
                return Err(SpeciesProblem {
                    setting: Some((k, setting)),
                    problem: format!("value {x} is not a positive finite number"),
                    allowed: "finite numbers > 0",
                });
            }
        }
        n = n.saturating_add(s.count);
    }
    if n == 0 {
        return Err(whole(
            "zero discs in total".into(),
            "at least one disc (some species' count ≥ 1)",
        ));
    }
    if n >= u32::MAX as usize {
        return Err(whole(
            format!("{n} discs in total"),
            "fewer than 4294967295 discs",
        ));
    }
    Ok(n)
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

    #[test]
    fn the_species_check_names_what_is_wrong() {
        let ok = [Species::new(3, 0.5, 1.0), Species::new(0, 0.7, 2.0)];
        assert_eq!(check_species(&ok), Ok(3));
        assert_eq!(check_species(&[]).unwrap_err().setting, None);
        let bad_mass = [ok[0], Species::new(2, 0.7, f64::NAN)];
        assert_eq!(
            check_species(&bad_mass).unwrap_err().setting,
            Some((1, "mass"))
        );
        let bad_radius = [Species::new(1, -0.5, 1.0)];
        assert_eq!(
            check_species(&bad_radius).unwrap_err().setting,
            Some((0, "radius"))
        );
        let none = [Species::new(0, 0.5, 1.0)];
        assert!(check_species(&none)
            .unwrap_err()
            .problem
            .contains("zero discs"));
        let many = [Species::new(u32::MAX as usize, 0.5, 1.0)];
        assert_eq!(check_species(&many).unwrap_err().setting, None);
        let kinds = vec![Species::new(1, 0.5, 1.0); 65536];
        assert!(check_species(&kinds)
            .unwrap_err()
            .problem
            .contains("65536 species"));
    }
}
