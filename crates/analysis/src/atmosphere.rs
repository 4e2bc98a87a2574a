//! Gravity in `analyze` (physics.md §15): the potential energy U = Σ m g y and
//! K + U of the snapshots, the density profile n(y) per species, and per
//! species the barometric fit of (15.8),
//!     n(y) ∝ e^{−β_g y},   against the dilute gas's β_g = m g/kT (15.6),
//! and for one species against the hydrostatic profile (15.7) with the equation
//! of state ([`hydrostatic_beta`]), which a dense column follows instead.
//! Heights come from the block-start snapshots after the equilibration time (as
//! for g(r)); β_g is the mean over up to [`BLOCKS`] consecutive groups of
//! snapshots with the error of their spread (groups correlate much less than
//! neighbouring snapshots). A driven bed (vibrating floor) is in no equilibrium:
//! `not_applicable` says so and no known value is compared.

use carom_core::gravity::barometric_beta;
use serde::Serialize;

use super::hydrostatic::hydrostatic_beta;

/// Why the barometric law has no known value on a vibrating floor.
pub const NOT_IN_EQUILIBRIUM: &str = "the barometric and hydrostatic laws hold in equilibrium; \
     a bed driven by a vibrating floor and cooled by its collisions is not";

/// Groups of snapshots the fit's standard error comes from.
pub const BLOCKS: usize = 16;

/// Bins of the density profile per smallest diameter.
const BINS_PER_DIAMETER: f64 = 2.0;

/// One snapshot's heights: its time, U, and per species the sum of heights above
/// a and the number of discs.
type Heights = (f64, f64, Vec<(f64, usize)>);

/// The heights seen so far.
#[derive(Debug, Clone)]
pub(super) struct Atmosphere {
    g: f64,
    size: [f64; 2],
    masses: Vec<f64>,
    radii: Vec<f64>,
    bin_width: f64,
    /// Centres per species per height bin, summed over snapshots.
    counts: Vec<Vec<f64>>,
    /// Per snapshot (see [`Heights`]).
    snapshots: Vec<Heights>,
}

/// The barometric fit of one species.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BarometricFit {
    /// Species index.
    pub species: usize,
    /// Fitted β_g (1/length), the mean over groups of snapshots of (15.8).
    pub beta: f64,
    /// Its standard error from the groups' spread (`null` with one group).
    pub beta_std_error: Option<f64>,
    /// m g/kT with kT = 2K/f of the same snapshots (1/length): the ideal gas's
    /// β_g, the law (15.6) of a dilute atmosphere.
    pub beta_expected: f64,
    /// (beta − beta_expected)/beta_std_error; `null` when not applicable.
    pub deviation_se: Option<f64>,
    /// The β_g that (15.8) gives for the hydrostatic profile (15.7) of this
    /// column with Henderson's Z(η) at the same kT: the known value for a gas
    /// that is not dilute (one species only; `null` otherwise).
    pub beta_hydrostatic: Option<f64>,
    /// (beta − beta_hydrostatic)/beta_std_error.
    pub deviation_hydrostatic_se: Option<f64>,
    /// Why no known value applies (a driven, non-equilibrium run), else `null`.
    pub not_applicable: Option<&'static str>,
    /// n at the floor of the fitted law, n(a) = N β/(L_x (1 − e^{−β D})) (1/length²).
    pub floor_density: f64,
    /// The lowest height a centre reaches, the radius a (length).
    pub floor: f64,
}

/// What `analyze` reports about a run in a field.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GravityReport {
    /// g along −y (length/time²).
    pub g: f64,
    /// Snapshots used.
    pub snapshots: usize,
    /// Mean potential energy U = Σ m g y over them (energy).
    pub potential_energy: f64,
    /// K + U at the first and the last of them (energy; `null` when a snapshot's
    /// kinetic energy is unknown).
    pub total_energy_first: Option<f64>,
    /// See `total_energy_first`.
    pub total_energy_last: Option<f64>,
    /// Height of the bins' lower edges (length), bins of `bin_width`.
    pub heights: Vec<f64>,
    /// Bin width (length).
    pub bin_width: f64,
    /// n(y) per species: mean centres per unit area in each bin (1/length²).
    pub density: Vec<Vec<f64>>,
    /// The barometric fit per species with discs.
    pub barometric: Vec<BarometricFit>,
}

impl Atmosphere {
    /// An empty profile for discs of `masses` and `radii` in a box of `size` in the
    /// field `g` (> 0).
    pub(super) fn new(g: f64, size: [f64; 2], masses: Vec<f64>, radii: Vec<f64>) -> Self {
        let smallest = radii.iter().copied().fold(f64::INFINITY, f64::min);
        let nbins =
            ((size[1] * BINS_PER_DIAMETER / (2.0 * smallest)).ceil() as usize).clamp(1, 100_000);
        Atmosphere {
            g,
            size,
            counts: vec![vec![0.0; nbins]; masses.len()],
            bin_width: size[1] / nbins as f64,
            masses,
            radii,
            snapshots: Vec::new(),
        }
    }

    /// Add the heights `y` of a snapshot at time `t` (species of each disc in
    /// `species_of`, checked by the caller).
    pub(super) fn add(&mut self, t: f64, species_of: &[u16], y: &[f64]) {
        let nbins = self.counts[0].len();
        let mut per = vec![(0.0, 0usize); self.masses.len()];
        let mut u = 0.0;
        for (&s, &h) in species_of.iter().zip(y) {
            let s = s as usize;
            u += self.masses[s] * self.g * h;
            per[s].0 += h - self.radii[s];
            per[s].1 += 1;
            let b = ((h / self.bin_width).floor().max(0.0) as usize).min(nbins - 1);
            self.counts[s][b] += 1.0;
        }
        self.snapshots.push((t, u, per));
    }

    /// The report, with the kinetic energies `kinetic` (time, K) of the snapshots
    /// and kT (energy) of the snapshots used, `kt`; `None` without snapshots. A
    /// run that is not in `equilibrium` (driven by a vibrating floor) has its
    /// fits compared with no known value.
    pub(super) fn report(
        &self,
        kinetic: &[(f64, f64)],
        kt: Option<f64>,
        equilibrium: bool,
    ) -> Option<GravityReport> {
        let m = self.snapshots.len();
        if m == 0 {
            return None;
        }
        let k_at = |t: f64| kinetic.iter().find(|e| e.0 == t).map(|e| e.1);
        let total = |i: usize| {
            let (t, u, _) = &self.snapshots[i];
            k_at(*t).map(|k| k + u)
        };
        let area = self.size[0] * self.bin_width * m as f64;
        let groups = BLOCKS.min(m);
        let span_of = |s: usize| self.size[1] - 2.0 * self.radii[s];
        let barometric = (0..self.masses.len())
            .filter(|&s| self.snapshots[0].2[s].1 > 0)
            .map(|s| {
                let betas: Vec<f64> = (0..groups)
                    .map(|g| {
                        let part = &self.snapshots[g * m / groups..(g + 1) * m / groups];
                        let (sum, count) = part
                            .iter()
                            .fold((0.0, 0usize), |a, p| (a.0 + p.2[s].0, a.1 + p.2[s].1));
                        barometric_beta(sum / count as f64, span_of(s))
                    })
                    .collect();
                let mean = betas.iter().sum::<f64>() / groups as f64;
                let se = (groups > 1).then(|| {
                    let var = betas.iter().map(|b| (b - mean) * (b - mean)).sum::<f64>()
                        / (groups - 1) as f64;
                    (var / groups as f64).sqrt()
                });
                let expected = kt.map_or(f64::NAN, |kt| self.masses[s] * self.g / kt);
                let n = self.snapshots[0].2[s].1 as f64;
                let hydrostatic = (self.masses.len() == 1)
                    .then(|| {
                        hydrostatic_beta(expected, n / self.size[0], self.radii[s], span_of(s))
                    })
                    .filter(|b| b.is_finite());
                let (se_known, hydrostatic) = match equilibrium {
                    true => (se, hydrostatic),
                    false => (None, None),
                };
                BarometricFit {
                    species: s,
                    beta: mean,
                    beta_std_error: se,
                    beta_expected: expected,
                    deviation_se: se_known.map(|se| (mean - expected) / se),
                    beta_hydrostatic: hydrostatic,
                    deviation_hydrostatic_se: se_known
                        .zip(hydrostatic)
                        .map(|(se, h)| (mean - h) / se),
                    not_applicable: (!equilibrium).then_some(NOT_IN_EQUILIBRIUM),
                    floor_density: n * mean / (self.size[0] * -(-mean * span_of(s)).exp_m1()),
                    floor: self.radii[s],
                }
            })
            .collect();
        Some(GravityReport {
            g: self.g,
            snapshots: m,
            potential_energy: self.snapshots.iter().map(|p| p.1).sum::<f64>() / m as f64,
            total_energy_first: total(0),
            total_energy_last: total(m - 1),
            heights: (0..self.counts[0].len())
                .map(|b| b as f64 * self.bin_width)
                .collect(),
            bin_width: self.bin_width,
            density: self
                .counts
                .iter()
                .map(|c| c.iter().map(|x| x / area).collect())
                .collect(),
            barometric,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two snapshots of three discs (radius 0.5, mass 2) in a 10 × 4 box, g = 3:
    /// U = 2·3·(0.5 + 1.5 + 2.5) = 27 and 2·3·(0.5 + 1 + 1.5) = 18, mean 22.5; the
    /// mean heights above a are 1 and 0.5, one group each, so β_g is the mean of
    /// [`barometric_beta`] of those over the span 3; the profile counts centres per
    /// bin of 0.5 over the area 10 · 0.5 · 2 snapshots.
    #[test]
    fn potential_energy_profile_and_fit_of_a_hand_made_atmosphere() {
        let mut a = Atmosphere::new(3.0, [10.0, 4.0], vec![2.0], vec![0.5]);
        a.add(1.0, &[0, 0, 0], &[0.5, 1.5, 2.5]);
        a.add(2.0, &[0, 0, 0], &[0.5, 1.0, 1.5]);
        let r = a
            .report(&[(1.0, 5.0), (2.0, 14.0)], Some(2.0), true)
            .unwrap();
        assert_eq!(r.potential_energy, 22.5);
        assert_eq!(
            (r.total_energy_first, r.total_energy_last),
            (Some(32.0), Some(32.0))
        );
        assert_eq!(r.bin_width, 0.5);
        assert_eq!(r.density[0][1..6], [0.2, 0.1, 0.2, 0.0, 0.1]);
        let b = &r.barometric[0];
        let (b1, b2) = (barometric_beta(1.0, 3.0), barometric_beta(0.5, 3.0));
        assert_eq!(b.beta, (b1 + b2) / 2.0);
        assert!(b.beta_std_error.unwrap() > 0.0);
        // m g/kT = 2 · 3/2.
        assert_eq!(b.beta_expected, 3.0);
    }
}
