//! How a live frame colours the discs: by species, with the log's `/scene`
//! palette (`carom_log::species_color`), or by speed |v| on a fixed scale, so that
//! colours mean the same from frame to frame within a run: |v| / v₀ with
//! v₀ = 3·√(kT/m̄) at the frame's own kT = K/N per degree of freedom (for a gas in
//! equilibrium, P(|v| > v₀) = e^(−9/2) ≈ 1 %, physics.md §5), through matplotlib's
//! `viridis` (dark blue slow, yellow fast). Speeds above v₀ take its top colour.

use carom_engine::State;

/// What colours the discs of a live `/scene` frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Colouring {
    /// By species, as in the log's `/scene` (`carom_log::SPECIES_COLORS`).
    #[default]
    Species,
    /// By speed |v|, from dark blue (at rest) to yellow (3 thermal speeds).
    Speed,
}

impl Colouring {
    /// The name on the command line and in messages (`species`, `speed`).
    pub fn name(self) -> &'static str {
        match self {
            Colouring::Species => "species",
            Colouring::Speed => "speed",
        }
    }

    /// The colouring of a name, or what names there are.
    pub fn from_name(name: &str) -> Result<Self, String> {
        match name {
            "species" => Ok(Colouring::Species),
            "speed" => Ok(Colouring::Speed),
            other => Err(format!("{other:?}: colour by species or speed")),
        }
    }
}

/// `viridis` at 0, ¼, ½, ¾ and 1 (RGB in [0, 1]); between stops, linear.
const VIRIDIS: [[f64; 3]; 5] = [
    [0.267, 0.005, 0.329],
    [0.229, 0.322, 0.546],
    [0.128, 0.567, 0.551],
    [0.369, 0.789, 0.383],
    [0.993, 0.906, 0.144],
];

/// `viridis` at `x` (clamped to [0, 1]).
fn viridis(x: f64) -> [f64; 3] {
    let x = if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    let f = x * (VIRIDIS.len() - 1) as f64;
    let i = (f.floor() as usize).min(VIRIDIS.len() - 2);
    let w = f - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    [0, 1, 2].map(|k| a[k] + w * (b[k] - a[k]))
}

/// The speed scale v₀ = 3·√(kT/m̄) of `state`, kT = K/N per degree of freedom
/// (2 per disc) and m̄ the mean mass; 1 for a system at rest.
fn speed_scale(state: &State) -> f64 {
    let n = state.positions.len().max(1) as f64;
    let (mut k, mut m) = (0.0, 0.0);
    for (v, &s) in state.velocities.iter().zip(&state.species_of) {
        let mass = state.species[s as usize].mass;
        k += 0.5 * mass * v.length_squared();
        m += mass;
    }
    let kt = k / n;
    let scale = 3.0 * (kt / (m / n)).sqrt();
    if scale > 0.0 && scale.is_finite() {
        scale
    } else {
        1.0
    }
}

/// The colour of every disc of `state` under `colouring`.
pub(crate) fn colours(state: &State, colouring: Colouring) -> Vec<[f64; 3]> {
    match colouring {
        Colouring::Species => state
            .species_of
            .iter()
            .map(|&s| carom_log::species_color(s))
            .collect(),
        Colouring::Speed => {
            let v0 = speed_scale(state);
            state
                .velocities
                .iter()
                .map(|v| viridis(v.length() / v0))
                .collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_runs_through_its_stops_and_clamps() {
        assert_eq!(viridis(0.0), VIRIDIS[0]);
        assert_eq!(viridis(0.5), VIRIDIS[2]);
        assert_eq!(viridis(1.0), VIRIDIS[4]);
        assert_eq!(viridis(7.0), VIRIDIS[4]);
        assert_eq!(viridis(-1.0), VIRIDIS[0]);
        let mid = viridis(0.125);
        for k in 0..3 {
            assert!((mid[k] - 0.5 * (VIRIDIS[0][k] + VIRIDIS[1][k])).abs() < 1e-12);
        }
    }

    #[test]
    fn names_round_trip_and_a_wrong_one_says_what_there_is() {
        for c in [Colouring::Species, Colouring::Speed] {
            assert_eq!(Colouring::from_name(c.name()), Ok(c));
        }
        let e = Colouring::from_name("rainbow").unwrap_err();
        assert!(e.contains("species or speed"), "{e}");
    }
}
