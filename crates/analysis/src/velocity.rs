//! The velocity distribution of each species against the 2D Maxwell–Boltzmann
//! distribution at the measured kT (physics.md §6): a χ² test of the speed
//! histogram and KS tests of the speeds and of each component. Velocities of one
//! disc in snapshots too close in time are correlated, and correlated samples make
//! the tests reject too often: with the default spacing a species whose velocities
//! still correlate between the snapshots used (a heavy species) is tested on every
//! k-th snapshot only. See docs/performance.md, 'analyze defaults'.

use super::samples::Samples;
use super::stats::{ks_test, mb_speed_test, Histogram, StatsError};
use super::velocity_report::{
    ChiSquareReport, HistogramReport, KsReport, SpeciesMb, SpeciesUntested,
};
#[cfg(doc)]
use super::{AnalysisOptions, DECORRELATION_COLLISIONS};

/// Family-wise significance level of the Maxwell–Boltzmann verdict: every test
/// made (per species the speed χ², the speed KS and the KS of v_x and of v_y) is
/// counted, and a species is rejected when its smallest p-value is below
/// α/m, m the number of tests made over all species (Bonferroni; physics.md §6).
pub const MB_FAMILY_ALPHA: f64 = 0.01;

/// Tests made per species for the Maxwell–Boltzmann verdict ([`MB_FAMILY_ALPHA`]).
pub const MB_TESTS_PER_SPECIES: usize = 4;

/// The largest correlation of a species' velocities between the snapshots its
/// Maxwell–Boltzmann tests use. The default spacing ([`DECORRELATION_COLLISIONS`])
/// is set by the collision rate of all discs, but a heavy disc keeps its velocity
/// over about M/m collisions with light ones. A species whose velocities correlate
/// more than this from one snapshot to the next is tested on every k-th snapshot
/// only, k the smallest for which ρ^k falls to this (only with the default spacing;
/// an [`AnalysisOptions::every`] asked for is used as it is). See
/// docs/performance.md, 'analyze defaults'.
pub const MAX_SNAPSHOT_CORRELATION: f64 = 0.05;

/// The centre-of-mass velocity u = Σ m_i v_i / Σ m_i of a snapshot (`masses` per
/// species). The velocity tests take velocities relative to it (physics.md §6,
/// "Centre of mass"): where momentum is not conserved (a thermostat, walls) it
/// wanders slowly by √(kT/(N m)), and pooled snapshots sharing its offset would
/// make the tests reject too often; with momentum conserved it is 0.
pub(super) fn centre_of_mass_velocity(
    masses: &[f64],
    species_of: &[u16],
    vx: &[f64],
    vy: &[f64],
) -> (f64, f64) {
    let (mut px, mut py, mut mass) = (0.0, 0.0, 0.0);
    for (&s, (&x, &y)) in species_of.iter().zip(vx.iter().zip(vy)) {
        let m = masses[s as usize];
        (px, py, mass) = (px + m * x, py + m * y, mass + m);
    }
    (px / mass, py / mass)
}

/// The correlation of a species' velocities between consecutive snapshots: `vx`,
/// `vy` hold `per` discs' components per snapshot, snapshot after snapshot, each
/// disc at the same place in every snapshot. Components are taken relative to
/// their mean over all snapshots. `None` with fewer than two snapshots or no
/// variation.
pub(super) fn snapshot_correlation(vx: &[f64], vy: &[f64], per: usize) -> Option<f64> {
    let snapshots = vx.len().checked_div(per)?;
    if snapshots < 2 {
        return None;
    }
    let (mut cross, mut before, mut after) = (0.0, 0.0, 0.0);
    for v in [vx, vy] {
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        for (a, b) in v.iter().zip(&v[per..]) {
            let (a, b) = (a - mean, b - mean);
            cross += a * b;
            before += a * a;
            after += b * b;
        }
    }
    let rho = cross / (before * after).sqrt();
    rho.is_finite().then_some(rho)
}

/// Every how many snapshots a species whose velocities correlate `rho` between
/// consecutive snapshots is tested ([`MAX_SNAPSHOT_CORRELATION`]); `usize::MAX`
/// (the first snapshot only) when they hardly change.
pub(super) fn snapshot_step(rho: Option<f64>) -> usize {
    match rho {
        Some(r) if r > MAX_SNAPSHOT_CORRELATION => {
            let k = (MAX_SNAPSHOT_CORRELATION.ln() / r.min(1.0).ln()).ceil();
            if k.is_finite() && k < 1e9 {
                k as usize
            } else {
                usize::MAX
            }
        }
        _ => 1,
    }
}

/// The values of every `step`-th snapshot of `v` (`per` values per snapshot).
pub(super) fn every_nth_snapshot(v: &[f64], per: usize, step: usize) -> Vec<f64> {
    v.chunks(per.max(1))
        .step_by(step)
        .flatten()
        .copied()
        .collect()
}

/// The Maxwell–Boltzmann tests of every species with speeds in the window, at
/// `kt` (`None`: no snapshot used, nothing tested), and the species that could not
/// be tested. Thins the analyzer's samples of a correlated species.
pub(super) fn maxwell_boltzmann(
    a: &mut Samples,
    kt: Option<f64>,
    scaled: bool,
) -> Result<(Vec<SpeciesMb>, Vec<SpeciesUntested>), StatsError> {
    let mut maxwell_boltzmann = Vec::new();
    let mut maxwell_boltzmann_untested = Vec::new();
    let Some(kt) = kt else {
        return Ok((maxwell_boltzmann, maxwell_boltzmann_untested));
    };
    let species = a.run.species.clone();
    for (s, sp) in species.iter().enumerate() {
        if a.speeds[s].len() < 2 {
            continue;
        }
        // Discs of this species per snapshot. With the default spacing its
        // samples are thinned to snapshots far enough apart for its own
        // velocities to decorrelate; a spacing asked for is used as it is.
        let per = a.speeds[s].len() / a.snapshots_used.len().max(1);
        let correlation = snapshot_correlation(&a.vx[s], &a.vy[s], per);
        let step = if a.every_default {
            snapshot_step(correlation)
        } else {
            1
        };
        if step > 1 {
            for v in [&mut a.speeds[s], &mut a.vx[s], &mut a.vy[s]] {
                *v = every_nth_snapshot(v, per, step);
            }
        }
        let snapshots = a.speeds[s].len() / per.max(1);
        // Discs at rest (placed so with explicit velocities) have no
        // distribution to test.
        if kt <= 0.0 {
            maxwell_boltzmann_untested.push(SpeciesUntested {
                species: s,
                samples: a.speeds[s].len(),
                reason: format!("no thermal motion (kT = {kt})"),
            });
            continue;
        }
        // A species with too few speeds for the χ² test (a handful of
        // discs in a short window) is reported as untested; the other
        // species and the rest of the analysis go on.
        let t = match mb_speed_test(&a.speeds[s], sp.mass, kt, a.opts.speed_bins, true) {
            Err(StatsError::NotEnoughData(why)) => {
                maxwell_boltzmann_untested.push(SpeciesUntested {
                    species: s,
                    samples: a.speeds[s].len(),
                    reason: why,
                });
                continue;
            }
            r => r?,
        };
        let mb = t.reference;
        let comp_hist = |v: &[f64]| {
            let l = 4.5 * mb.scale();
            Histogram::from_values(v.iter().copied(), -l, l, a.opts.speed_bins)
        };
        let ks_x = ks_test(&a.vx[s], |v| mb.component_cdf(v))?;
        let ks_y = ks_test(&a.vy[s], |v| mb.component_cdf(v))?;
        let min_p = [
            t.chi_square.p_value,
            t.ks.p_value,
            ks_x.p_value,
            ks_y.p_value,
        ]
        .into_iter()
        .fold(f64::INFINITY, f64::min);
        maxwell_boltzmann.push(SpeciesMb {
            species: s,
            mass: sp.mass,
            radius: sp.radius,
            samples: a.speeds[s].len(),
            snapshots,
            snapshot_correlation: correlation,
            snapshot_step: step.min(a.snapshots_used.len()),
            kt,
            scaled_to_snapshot_temperature: scaled,
            speed_histogram: HistogramReport::new(&t.histogram, |v| mb.speed_pdf(v)),
            vx_histogram: HistogramReport::new(&comp_hist(&a.vx[s])?, |v| mb.component_pdf(v)),
            vy_histogram: HistogramReport::new(&comp_hist(&a.vy[s])?, |v| mb.component_pdf(v)),
            chi_square: ChiSquareReport {
                statistic: t.chi_square.statistic,
                dof: t.chi_square.dof,
                p_value: t.chi_square.p_value,
                bins: t.chi_square.bins,
            },
            ks: KsReport::from(&t.ks),
            ks_vx: KsReport::from(&ks_x),
            ks_vy: KsReport::from(&ks_y),
            min_p_value: min_p,
            tests: 0,
            p_threshold: 0.0,
            passed: false,
        });
    }
    // The verdict counts every test made over all species (Bonferroni).
    let tests = MB_TESTS_PER_SPECIES * maxwell_boltzmann.len();
    for m in &mut maxwell_boltzmann {
        m.tests = tests;
        m.p_threshold = MB_FAMILY_ALPHA / tests as f64;
        m.passed = m.min_p_value >= m.p_threshold;
    }
    Ok((maxwell_boltzmann, maxwell_boltzmann_untested))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Analyzer;
    use crate::{AnalysisOptions, RunDescription};
    use carom_core::{SimBox, Species};

    fn run() -> RunDescription {
        RunDescription::for_tests()
    }

    #[test]
    fn snapshot_thinning_follows_the_correlation() {
        // Two discs, three snapshots: the same velocities each time, then reversed.
        let same = [1.0, -1.0, 1.0, -1.0, 1.0, -1.0];
        let zeros = [0.0; 6];
        let rho = snapshot_correlation(&same, &zeros, 2).unwrap();
        assert!((rho - 1.0).abs() < 1e-12, "{rho}");
        let flip = [1.0, -1.0, -1.0, 1.0, 1.0, -1.0];
        let rho = snapshot_correlation(&flip, &zeros, 2).unwrap();
        assert!((rho + 1.0).abs() < 1e-12, "{rho}");
        assert_eq!(snapshot_correlation(&same[..2], &zeros[..2], 2), None);
        assert_eq!(snapshot_correlation(&zeros, &zeros, 2), None);
        // ρ^k ≤ 0.05: k = 1 below it, ⌈ln 0.05 / ln ρ⌉ above, the first only at 1.
        assert_eq!(snapshot_step(None), 1);
        assert_eq!(snapshot_step(Some(-0.9)), 1);
        assert_eq!(snapshot_step(Some(0.05)), 1);
        assert_eq!(snapshot_step(Some(0.5)), 5);
        assert_eq!(snapshot_step(Some(0.9)), 29);
        assert_eq!(snapshot_step(Some(1.0)), usize::MAX);
        assert_eq!(
            every_nth_snapshot(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], 2, 2),
            vec![1.0, 2.0, 5.0, 6.0]
        );
        assert_eq!(every_nth_snapshot(&flip, 2, usize::MAX), vec![1.0, -1.0]);
    }

    /// A heavy species whose velocities do not change between snapshots is tested on
    /// one snapshot, not on the same velocities counted again and again (which fails
    /// the tests however Maxwellian they are); the light species keeps every
    /// snapshot. A spacing asked for is used as it is, and then the heavy species
    /// fails.
    #[test]
    fn a_species_with_frozen_velocities_is_tested_once_per_disc() {
        use rand::SeedableRng;
        use rand_distr::{Distribution, StandardNormal};
        let (light, heavy, snapshots) = (2000, 400, 20);
        let mut r = run();
        r.species = vec![Species::reference(light), Species::new(heavy, 0.5, 100.0)];
        r.sim_box = SimBox::periodic(100.0, 100.0);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        let mut gauss = |m: f64| {
            let g: f64 = StandardNormal.sample(&mut rng);
            g / m.sqrt()
        };
        let species: Vec<u16> = (0..light + heavy).map(|k| u16::from(k >= light)).collect();
        let frozen: Vec<(f64, f64)> = (0..heavy).map(|_| (gauss(100.0), gauss(100.0))).collect();
        let taken: Vec<(Vec<f64>, Vec<f64>)> = (0..snapshots)
            .map(|_| {
                let (mut vx, mut vy) = (Vec::new(), Vec::new());
                for _ in 0..light {
                    vx.push(gauss(1.0));
                    vy.push(gauss(1.0));
                }
                for &(x, y) in &frozen {
                    vx.push(x);
                    vy.push(y);
                }
                (vx, vy)
            })
            .collect();
        let analyse = |every: Option<f64>| {
            // Without `every` the default spacing; no collision rate is known, so
            // it keeps every snapshot.
            let opts = AnalysisOptions {
                equilibrate: Some(0.0),
                every,
                ..Default::default()
            };
            let mut a = Analyzer::new(r.clone(), opts).unwrap();
            for (k, (vx, vy)) in taken.iter().enumerate() {
                a.snapshot(k as f64 * 0.5, &species, vx, vy).unwrap();
            }
            a.finish().unwrap().maxwell_boltzmann
        };
        let report = analyse(None);
        let [l, h] = &report[..] else {
            panic!("two species tested");
        };
        assert_eq!(
            (l.snapshot_step, l.snapshots, l.samples),
            (1, snapshots, light * snapshots)
        );
        assert!(l.snapshot_correlation.unwrap().abs() < 0.05);
        assert_eq!((h.snapshots, h.samples), (1, heavy));
        assert_eq!(h.snapshot_step, snapshots);
        assert!(h.snapshot_correlation.unwrap() > 0.999);
        assert!(l.passed && h.passed, "{l:?}\n{h:?}");
        let asked = analyse(Some(0.0));
        let h = &asked[1];
        assert_eq!((h.snapshot_step, h.snapshots), (1, snapshots));
        assert!(h.snapshot_correlation.unwrap() > 0.999);
        assert!(!h.passed, "{h:?}");
    }

    /// Velocities whose speeds are exactly Rayleigh but whose directions lie on
    /// the axes (each vector turned to the nearest axis, the speed unchanged, the
    /// mean still 0): the speed tests pass, the v_x test fails, and the verdict
    /// counts it.
    #[test]
    fn a_failed_component_test_fails_the_verdict() {
        use rand::SeedableRng;
        use rand_distr::{Distribution, StandardNormal};
        use std::f64::consts::FRAC_PI_2;
        let n = 2000;
        let mut r = run();
        r.species = vec![Species::reference(n)];
        r.sim_box = SimBox::periodic(100.0, 100.0);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(11);
        let species = vec![0u16; n];
        let verdict = |fold: bool, rng: &mut rand_pcg::Pcg64| {
            let opts = AnalysisOptions {
                equilibrate: Some(0.0),
                every: Some(0.0),
                ..Default::default()
            };
            let mut a = Analyzer::new(r.clone(), opts).unwrap();
            for k in 0..5 {
                let mut g = || -> f64 { StandardNormal.sample(rng) };
                let (vx, vy): (Vec<f64>, Vec<f64>) = (0..n)
                    .map(|_| (g(), g()))
                    .map(|(x, y)| {
                        if fold {
                            // The speed kept, the direction moved to the nearest axis.
                            let (s, q) = (x.hypot(y), (y.atan2(x) / FRAC_PI_2).round());
                            (s * (q * FRAC_PI_2).cos(), s * (q * FRAC_PI_2).sin())
                        } else {
                            (x, y)
                        }
                    })
                    .unzip();
                a.snapshot(k as f64, &species, &vx, &vy).unwrap();
            }
            a.finish().unwrap().maxwell_boltzmann.remove(0)
        };
        let good = verdict(false, &mut rng);
        assert!(good.passed, "{good:?}");
        assert_eq!(good.tests, 4);
        assert!((good.p_threshold - 0.01 / 4.0).abs() < 1e-15);
        let bad = verdict(true, &mut rng);
        assert!(
            bad.chi_square.p_value > 0.01 && bad.ks.p_value > 0.01,
            "{bad:?}"
        );
        assert!(bad.ks_vx.p_value < 1e-6, "{:?}", bad.ks_vx);
        assert!(!bad.passed);
        assert_eq!(bad.min_p_value, bad.ks_vx.p_value);
    }

    /// Twenty snapshots of N = 2000 independent Maxwell–Boltzmann velocities
    /// (kT = 1) that share one centre-of-mass offset u_x = 0.05 ≈ 2√(kT/(N m)), as
    /// a thermostatted gas's slowly wandering centre of mass does: the velocities
    /// relative to each snapshot's centre of mass pass; the offset itself is not
    /// what the test is about (physics.md §6, "Centre of mass").
    #[test]
    fn a_shared_centre_of_mass_offset_does_not_fail_the_test() {
        use rand::SeedableRng;
        use rand_distr::{Distribution, StandardNormal};
        let n = 2000;
        let mut r = run();
        r.species = vec![Species::reference(n)];
        r.sim_box = SimBox::periodic(100.0, 100.0);
        let mut rng = rand_pcg::Pcg64::seed_from_u64(40);
        let species = vec![0u16; n];
        let opts = AnalysisOptions {
            equilibrate: Some(0.0),
            every: Some(0.0),
            ..Default::default()
        };
        let mut a = Analyzer::new(r, opts).unwrap();
        for k in 0..20 {
            let mut g = || -> f64 { StandardNormal.sample(&mut rng) };
            let vx: Vec<f64> = (0..n).map(|_| g() + 0.05).collect();
            let vy: Vec<f64> = (0..n).map(|_| g()).collect();
            a.snapshot(k as f64, &species, &vx, &vy).unwrap();
        }
        let m = a.finish().unwrap().maxwell_boltzmann.remove(0);
        assert!(m.passed, "{m:?}");
        // Without the subtraction the pooled v_x would sit 0.05 off: KS's D
        // ≈ 0.05 φ(0) ≈ 0.02 against a critical 1.63/√40000 ≈ 0.008.
        assert!(m.ks_vx.statistic < 0.01, "{:?}", m.ks_vx);
    }

    /// Two discs, two snapshots, components with non-zero means (v_x 2, v_y −3),
    /// worked by hand: deviations v_x (1, −2) then (3, −2), v_y (2, 0) then
    /// (−1, −1); Σab = 3 + 4 − 2 + 0 = 5, Σa² = 1 + 4 + 4 + 0 = 9,
    /// Σb² = 9 + 4 + 1 + 1 = 15, so ρ = 5/√135 = √15/9.
    #[test]
    fn the_snapshot_correlation_is_taken_about_each_components_mean() {
        let vx = [3.0, 0.0, 5.0, 0.0];
        let vy = [-1.0, -3.0, -4.0, -4.0];
        let rho = snapshot_correlation(&vx, &vy, 2).unwrap();
        assert!((rho - 15f64.sqrt() / 9.0).abs() < 1e-15, "{rho}");
        // Fewer values than one snapshot, or no disc per snapshot: nothing to
        // correlate (and no slice past the end).
        assert_eq!(snapshot_correlation(&[1.0], &[2.0], 2), None);
        assert_eq!(snapshot_correlation(&vx, &vy, 0), None);
        // ρ = 0.2: ln 0.05/ln 0.2 = 1.86, so every second snapshot (0.2² = 0.04).
        assert_eq!(snapshot_step(Some(0.2)), 2);
    }

    /// `n` discs of mass `m` at `kt` with Maxwellian speeds, deterministic: the
    /// speed at the quantile (i + ½)/n of the Rayleigh CDF (6.3),
    /// v = √(−2 (kT/m) ln(1 − u)), in a direction turned by the golden angle from
    /// disc to disc and by `turn` as a whole.
    fn maxwellian(n: usize, m: f64, kt: f64, turn: f64) -> (Vec<f64>, Vec<f64>) {
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        (0..n)
            .map(|i| {
                let u = (i as f64 + 0.5) / n as f64;
                let v = (-2.0 * kt / m * (-u).ln_1p()).sqrt();
                let phi = golden * i as f64 + turn;
                (v * phi.cos(), v * phi.sin())
            })
            .unzip()
    }

    /// An analyzer holding `snapshots` snapshots of every species (`discs`
    /// Maxwellian velocities each at `kt`, turned from snapshot to snapshot), with
    /// the spacing asked for (`every_default` false) unless `default_spacing`.
    fn holding(
        species: Vec<Species>,
        snapshots: usize,
        kt: f64,
        default_spacing: bool,
    ) -> Analyzer {
        let mut r = run();
        r.species = species;
        r.sim_box = SimBox::periodic(40.0, 40.0);
        let opts = AnalysisOptions {
            equilibrate: Some(0.0),
            every: Some(0.0),
            ..Default::default()
        };
        let mut a = Analyzer::new(r.clone(), opts).unwrap();
        a.samples.every_default = default_spacing;
        for k in 0..snapshots {
            a.samples.snapshots_used.push(k as f64);
            for (s, sp) in r.species.iter().enumerate() {
                let (vx, vy) = maxwellian(sp.count, sp.mass, kt, 0.7 * k as f64);
                a.samples.speeds[s].extend(vx.iter().zip(&vy).map(|(x, y)| x.hypot(*y)));
                a.samples.vx[s].extend(vx);
                a.samples.vy[s].extend(vy);
            }
        }
        a
    }

    /// Two species tested at kT = 2 (masses 0.5 and 4.5, unequal counts) and one
    /// without discs between them: the verdict counts 4 tests per species tested,
    /// m = 8, threshold α/m = 0.01/8; each species is reported with its own
    /// snapshots (3), samples (3 × count) and component range ±4.5 √(kT/m):
    /// √(2/0.5) = 2 gives ±9, √(2/4.5) = 2/3 gives ±3.
    #[test]
    fn every_species_tested_counts_in_the_verdict_with_its_own_range() {
        let kt = 2.0;
        let species = vec![
            Species::new(60, 0.3, 0.5),
            Species::new(0, 0.5, 1.0),
            Species::new(40, 0.9, 4.5),
        ];
        let mut a = holding(species, 3, kt, false);
        let (tested, untested) = maxwell_boltzmann(&mut a.samples, Some(kt), false).unwrap();
        assert!(untested.is_empty(), "{untested:?}");
        let [light, heavy] = &tested[..] else {
            panic!("two species tested: {tested:?}");
        };
        for (m, s, count, mass, radius, l) in
            [(light, 0, 60, 0.5, 0.3, 9.0), (heavy, 2, 40, 4.5, 0.9, 3.0)]
        {
            assert_eq!((m.species, m.mass, m.radius, m.kt), (s, mass, radius, kt));
            assert_eq!((m.snapshots, m.samples, m.snapshot_step), (3, 3 * count, 1));
            assert_eq!((m.tests, m.p_threshold), (8, 0.01 / 8.0));
            assert!(!m.scaled_to_snapshot_temperature);
            for h in [&m.vx_histogram, &m.vy_histogram] {
                let (lo, hi) = (h.edges[0], h.edges[h.edges.len() - 1]);
                assert!(
                    (lo + l).abs() < 1e-12 && (hi - l).abs() < 1e-12,
                    "{lo} {hi}"
                );
                assert_eq!(h.counts.iter().sum::<u64>(), 3 * count as u64);
            }
            // The smallest of the four p-values, and the verdict against it.
            let p = [
                m.chi_square.p_value,
                m.ks.p_value,
                m.ks_vx.p_value,
                m.ks_vy.p_value,
            ];
            assert_eq!(m.min_p_value, p.into_iter().fold(1.0, f64::min));
            assert_eq!(m.passed, m.min_p_value >= 0.01 / 8.0);
        }
    }

    /// A species with one disc in two snapshots (2 speeds: one χ² bin, no degree
    /// of freedom) is reported untested with its 2 samples; a species without discs
    /// is in neither list; at kT = 0 every species with speeds is untested.
    #[test]
    fn species_with_too_few_speeds_or_no_motion_are_untested() {
        let species = vec![Species::new(1, 0.5, 2.0), Species::new(0, 0.5, 1.0)];
        let mut a = holding(species.clone(), 2, 1.5, false);
        let (tested, untested) = maxwell_boltzmann(&mut a.samples, Some(1.5), false).unwrap();
        assert!(tested.is_empty(), "{tested:?}");
        assert_eq!(untested.len(), 1, "{untested:?}");
        assert_eq!((untested[0].species, untested[0].samples), (0, 2));
        let mut a = holding(species, 2, 1.5, false);
        let (tested, untested) = maxwell_boltzmann(&mut a.samples, Some(0.0), false).unwrap();
        assert!(tested.is_empty());
        assert_eq!(untested.len(), 1, "{untested:?}");
        assert!(untested[0].reason.contains("no thermal motion"));
        let mut a = holding(vec![Species::new(50, 0.5, 2.0)], 2, 1.5, false);
        assert_eq!(
            maxwell_boltzmann(&mut a.samples, None, false).unwrap(),
            (vec![], vec![])
        );
    }
}
