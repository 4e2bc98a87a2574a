//! Inelastic runs: the energy budget E(t_end) = E(t_start) − dissipated, and
//! Haff's law of homogeneous cooling T(t) = T0/(1 + t/t0)² with
//! 1/t0 = (1 − e²)(1 + 3a2/16) ω(T0)/4 (physics.md §8), checked twice: for
//! self-consistency with ω(T0) from the measured collision rate scaled as √T
//! (which already holds the distribution's (1 − a2/16)), and from first
//! principles with Enskog's ω_E and the measured a2 (`haff_enskog.rs`). The
//! temperature against time is the temperature report's series. The velocities
//! of a cooling gas are tested in its homogeneous cooling state, each snapshot
//! scaled by its own thermal speed √(kT(t)/m), and their Sonine coefficient
//! a2 = ⟨v⁴⟩/(2⟨v²⟩²) − 1 (mass-weighted, physics.md (8.5)) is compared with the
//! second Sonine approximation (`hcs_sonine.rs`) and, as the familiar
//! first-order approximation, van Noije & Ernst's (8.4).

use carom_core::Restitution;

use super::haff_enskog::haff_enskog;
use super::hcs_sonine::a2_sonine;
use super::inelastic_report::{EnergyBudget, HaffReport, InelasticReport, SonineReport};
use super::samples::Samples;
use super::series::blocked;

/// a2 of the homogeneous cooling state of 2D hard discs with normal restitution
/// `e` in the first Sonine approximation (van Noije & Ernst 1998; physics.md
/// (8.4)): an approximation, 10–20 % off near e = 0.8–0.9.
pub(super) fn a2_theory(e: f64) -> f64 {
    16.0 * (1.0 - e) * (1.0 - 2.0 * e * e) / (57.0 - 25.0 * e + 30.0 * e * e * (1.0 - e))
}

/// a2 = ⟨(m v²)²⟩/(2⟨m v²⟩²) − 1 of one snapshot (physics.md (8.5); 0 for a 2D
/// Maxwellian of any temperature); NaN without motion.
pub(super) fn sonine_a2(masses: &[f64], species_of: &[u16], vx: &[f64], vy: &[f64]) -> f64 {
    let (mut s2, mut s4) = (0.0, 0.0);
    for (&s, (&x, &y)) in species_of.iter().zip(vx.iter().zip(vy)) {
        let e = masses[s as usize] * (x * x + y * y);
        s2 += e;
        s4 += e * e;
    }
    let n = vx.len() as f64;
    (s4 / n) / (2.0 * (s2 / n).powi(2)) - 1.0
}

/// Scale each snapshot's velocities by √(kt/kT(t)), kT(t) that snapshot's
/// temperature: the homogeneous cooling state at the common temperature `kt`.
pub(super) fn scale_to(a: &mut Samples, kt: f64) {
    let snapshots = a.snapshots_used.len();
    for s in 0..a.speeds.len() {
        let per = a.speeds[s].len() / snapshots.max(1);
        if per == 0 {
            continue;
        }
        for v in [&mut a.speeds[s], &mut a.vx[s], &mut a.vy[s]] {
            for (chunk, &kt_k) in v.chunks_mut(per).zip(&a.snapshot_kt) {
                let f = (kt / kt_k).sqrt();
                if f.is_finite() {
                    chunk.iter_mut().for_each(|x| *x *= f);
                }
            }
        }
    }
}

/// The measured a2 over the snapshots used, with a blocked standard error (the
/// plain error of the mean with fewer than 16 snapshots); `None` with fewer than 2.
fn sonine(a: &Samples) -> Option<SonineReport> {
    let x: Vec<f64> = a
        .snapshot_a2
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .collect();
    if x.len() < 2 {
        return None;
    }
    let (mean, se, is_blocked) = match blocked(&x) {
        Ok(b) => (b.mean, b.std_error, true),
        Err(_) => {
            let n = x.len() as f64;
            let m = x.iter().sum::<f64>() / n;
            let var = x.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (n - 1.0);
            (m, (var / n).sqrt(), false)
        }
    };
    Some(SonineReport {
        a2: mean,
        std_error: se,
        std_error_blocked: is_blocked,
        snapshots: x.len(),
        theory: match a.run.restitution {
            Restitution::Normal(e) if e < 1.0 => Some(a2_theory(e)),
            _ => None,
        },
        theory_second_order: match a.run.restitution {
            Restitution::Normal(e) if e < 1.0 => Some(a2_sonine(e)[1]),
            _ => None,
        },
    })
}

/// Energy put in besides the collisions' losses (a thermostat, a vibrating
/// floor): the energy budget and Haff's law, which assume none, are not made,
/// and the measured a2 is compared with `a2_theory` (the driven gas's, or none)
/// instead of the cooling state's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Driven {
    /// The a2 the driving predicts, if any (physics.md (16.7)).
    pub(super) a2_theory: Option<f64>,
}

/// The inelastic section of `a`, driven by `driven` when energy is put in.
pub(super) fn report(a: &Samples, driven: Option<Driven>) -> InelasticReport {
    if let Some(d) = driven {
        return InelasticReport {
            energy: None,
            haff: None,
            sonine: sonine(a).map(|s| SonineReport {
                theory: d.a2_theory,
                ..s
            }),
        };
    }
    let first = a.energy_series.first().copied();
    let last = a.energy_series.last().copied();
    let (e0, e1) = (first.map(|e| e.1), last.map(|e| e.1));
    // Dissipated energy between the first and last record: exact when the
    // source reports running totals, else the sum over logged collisions.
    let lost = match (first, last) {
        (Some((_, _, Some(a))), Some((_, _, Some(b)))) => Some(b - a),
        _ => None,
    };
    let lost_source = if lost.is_some() {
        "running total of the thermo records"
    } else {
        "sum over logged collisions × stride"
    };
    let lost = lost.unwrap_or(a.lost_from_collisions);
    // In a field the budget needs the potential energy, which the thermo records
    // do not carry (the gravity report has K + U at the snapshots).
    let budget = match (e0, e1) {
        _ if a.run.gravity > 0.0 => None,
        (Some(e0), Some(e1)) => Some(EnergyBudget {
            initial: e0,
            final_: e1,
            dissipated: lost,
            dissipated_source: lost_source,
            residual: e0 - lost - e1,
            relative_residual: (e0 - lost - e1) / e0,
        }),
        _ => None,
    };
    let sonine = sonine(a);
    let haff = match a.run.restitution {
        Restitution::Normal(e) if e < 1.0 => haff(a, e).map(|mut h| {
            h.enskog = sonine.as_ref().and_then(|s| haff_enskog(a, e, s.a2));
            h
        }),
        _ => None,
    };
    InelasticReport {
        energy: budget,
        haff,
        sonine,
    }
}

/// Haff's law (physics.md §8) with the collision frequency measured over the
/// run: in homogeneous cooling ω ∝ √T, so c = ω/√T = (2 N_pair/N) / ∫ √kT dt.
fn haff(a: &Samples, e: f64) -> Option<HaffReport> {
    let s = &a.kt_series;
    if s.len() < 3 {
        return None;
    }
    let (t0, kt0) = s[0];
    let integral: f64 = s
        .windows(2)
        .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1.max(0.0).sqrt() + w[1].1.max(0.0).sqrt()))
        .sum();
    let pairs = a.pairs_counted();
    if integral <= 0.0 || pairs == 0.0 {
        return None;
    }
    let c = 2.0 * pairs / a.run.n() as f64 / integral;
    let a2 = a2_theory(e);
    let omega0 = c * kt0.sqrt();
    let inv_t0 = (1.0 - e * e) * (1.0 + 3.0 * a2 / 16.0) * omega0 / 4.0;
    let (t_last, kt_last) = s[s.len() - 1];
    let predicted = kt0 / (1.0 + (t_last - t0) * inv_t0).powi(2);
    Some(HaffReport {
        check: "self-consistency: ω(T0) is the measured collision rate scaled as √T, which \
                already holds the distribution's (1 − a2/16); with van Noije & Ernst's a2",
        enskog: None,
        a2,
        collision_frequency_initial: omega0,
        t0: 1.0 / inv_t0,
        kt_final_predicted: predicted,
        kt_final_measured: kt_last,
        ratio: kt_last / predicted,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::RunDescription;
    use crate::AnalysisOptions;
    use crate::Analyzer;
    use carom_core::Species;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    fn analyzer(run: RunDescription) -> Analyzer {
        let opts = AnalysisOptions {
            equilibrate: Some(0.0),
            every: Some(1.0),
            ..Default::default()
        };
        Analyzer::new(run, opts).unwrap()
    }

    /// (8.4) by hand: e = 0: 16/57; e = 1/2: 16·½·½/(57 − 12.5 + 30·¼·½) =
    /// 4/48.25 = 16/193; e = 0.8: 16·0.2·(−0.28)/(37 + 30·0.64·0.2) =
    /// −0.896/40.84 = −112/5105; 0 where 1 − 2e² = 0 and at e = 1; −0.0269 at
    /// e = 0.9 (physics.md §8). Also van Noije & Ernst's form in d dimensions,
    /// 16(1 − e)(1 − 2e²)/[9 + 24d − (41 − 8d)e + 30e²(1 − e)], at d = 2.
    #[test]
    fn a2_theory_is_van_noije_and_ernst_in_two_dimensions() {
        assert!(close(a2_theory(0.0), 16.0 / 57.0, 1e-15));
        assert!(close(a2_theory(0.5), 16.0 / 193.0, 1e-15));
        assert!(close(a2_theory(0.8), -112.0 / 5105.0, 1e-14));
        assert!(a2_theory(0.5f64.sqrt()).abs() < 1e-15);
        assert_eq!(a2_theory(1.0), 0.0);
        assert!((a2_theory(0.9) + 0.0269).abs() < 5e-5);
        let d = 2.0;
        for e in [0.1f64, 0.3, 0.6, 0.95] {
            let general = 16.0 * (1.0 - e) * (1.0 - 2.0 * e.powi(2))
                / (9.0 + 24.0 * d - (41.0 - 8.0 * d) * e + 30.0 * e.powi(2) * (1.0 - e));
            assert!(close(a2_theory(e), general, 1e-14), "e = {e}");
        }
    }

    /// (8.5) by hand for discs of unequal mass: m v² = 2·(1 + 9) = 20,
    /// 0.5·(9 + 1) = 5, 2·(0.25 + 2.25) = 5; ⟨m v²⟩ = 10, ⟨(m v²)²⟩ = 450/3 = 150,
    /// a2 = 150/(2·100) − 1 = −1/4. Equal energies give ⟨ε²⟩/(2⟨ε⟩²) − 1 = −1/2;
    /// a2 does not depend on the temperature or a common mass scale.
    #[test]
    fn sonine_a2_is_the_fourth_moment_of_the_energies_of_all_discs() {
        let masses = [2.0, 0.5];
        let (species, vx, vy) = ([0, 1, 0], [1.0, 3.0, 0.5], [3.0, -1.0, 1.5]);
        let a2 = sonine_a2(&masses, &species, &vx, &vy);
        assert!(close(a2, -0.25, 1e-15), "{a2}");
        let (vx3, vy3) = (vx.map(|v| 3.0 * v), vy.map(|v| 3.0 * v));
        assert!(close(
            sonine_a2(&masses, &species, &vx3, &vy3),
            -0.25,
            1e-14
        ));
        assert!(close(
            sonine_a2(&[10.0, 2.5], &species, &vx, &vy),
            -0.25,
            1e-14
        ));
        // m = 1 at (2, 0) and m = 4 at (0, 1): both m v² = 4.
        let equal = sonine_a2(&[1.0, 4.0], &[0, 1], &[2.0, 0.0], &[0.0, 1.0]);
        assert!(close(equal, -0.5, 1e-15), "{equal}");
        assert!(sonine_a2(&masses, &[0, 1], &[0.0; 2], &[0.0; 2]).is_nan());
    }

    /// Two snapshots of three discs (masses 2, 0.5, 2; f = 2·3 − 2 = 4), the second
    /// with every velocity tripled: K = ½·2·2 + ½·0.5·8 + ½·2·1 = 5, kT = 2.5, and
    /// 45, kT = 22.5. Scaled to kT = 10, the first is multiplied by √(10/2.5) = 2
    /// and the second by √(10/22.5) = 2/3: both become twice the first.
    #[test]
    fn each_snapshot_is_scaled_to_the_common_temperature_by_its_own() {
        let run = RunDescription {
            species: vec![
                Species::new(2, 0.3, 2.0),
                Species::new(1, 0.6, 0.5),
                Species::new(0, 0.4, 1.0),
            ],
            restitution: Restitution::Normal(0.8),
            ..RunDescription::for_tests()
        };
        let mut a = analyzer(run);
        let (species, vx, vy) = ([0, 1, 0], [1.0, 2.0, -1.0], [1.0, -2.0, 0.0]);
        a.snapshot(1.0, &species, &vx, &vy).unwrap();
        a.snapshot(2.0, &species, &vx.map(|v| 3.0 * v), &vy.map(|v| 3.0 * v))
            .unwrap();
        assert_eq!(a.samples.snapshot_kt, [2.5, 22.5]);
        // a2 does not change with the temperature.
        assert!(close(
            a.samples.snapshot_a2[0],
            a.samples.snapshot_a2[1],
            1e-14
        ));
        scale_to(&mut a.samples, 10.0);
        // Velocities relative to the centre of mass, u = (2, 2)/9 (masses 2, 0.5,
        // 2; 3u at the second snapshot), times √(10/2.5) = √(10/22.5)·3 = 2.
        let (ux, uy) = (2.0 / 9.0, 2.0 / 9.0);
        let scaled = |k: usize| (2.0 * (vx[k] - ux), 2.0 * (vy[k] - uy));
        let (d0, d1, d2) = (scaled(0), scaled(1), scaled(2));
        let want_vx = [vec![d0.0, d2.0, d0.0, d2.0], vec![d1.0, d1.0], vec![]];
        let want_vy = [vec![d0.1, d2.1, d0.1, d2.1], vec![d1.1, d1.1], vec![]];
        let sp = |d: (f64, f64)| d.0.hypot(d.1);
        let want_speed = [
            vec![sp(d0), sp(d2), sp(d0), sp(d2)],
            vec![sp(d1), sp(d1)],
            vec![],
        ];
        for (got, want) in [
            (&a.samples.vx, want_vx),
            (&a.samples.vy, want_vy),
            (&a.samples.speeds, want_speed),
        ] {
            for s in 0..3 {
                assert_eq!(got[s].len(), want[s].len());
                for (g, w) in got[s].iter().zip(&want[s]) {
                    assert!(close(*g, *w, 1e-14), "{got:?} against {want:?}");
                }
            }
        }
    }

    /// The mean of the finite per-snapshot a2 and its plain standard error
    /// √(Σ(a − ā)²/((n − 1) n)) below 16 snapshots: 0.1, −0.2, 0.4 have mean 0.1
    /// and Σ(a − ā)² = 0.18, so √(0.09/3); 0.3, −0.1: √(0.08/2) = 0.2. The theory
    /// only for normal restitution e < 1: 16/193 at e = 1/2.
    #[test]
    fn sonine_averages_the_snapshots_with_the_error_of_the_mean() {
        let with = |restitution, a2: &[f64]| {
            let run = RunDescription {
                restitution,
                ..RunDescription::for_tests()
            };
            let mut a = analyzer(run);
            a.samples.snapshot_a2 = a2.to_vec();
            sonine(&a.samples)
        };
        let half = Restitution::Normal(0.5);
        let s = with(half, &[0.1, f64::NAN, -0.2, 0.4]).unwrap();
        assert!(close(s.a2, 0.1, 1e-15) && close(s.std_error, 0.03f64.sqrt(), 1e-14));
        assert_eq!((s.snapshots, s.std_error_blocked), (3, false));
        assert!(close(s.theory.unwrap(), 16.0 / 193.0, 1e-15));
        let s = with(half, &[0.3, -0.1]).unwrap();
        assert!(close(s.a2, 0.1, 1e-15) && close(s.std_error, 0.2, 1e-14));
        assert_eq!(s.snapshots, 2);
        assert!(with(half, &[0.3, f64::NAN]).is_none());
        assert!(with(half, &[]).is_none());
        // 16 snapshots: blocked, about the same mean 0.05·(0 + 1 + … + 15)/16 = 0.375.
        let x: Vec<f64> = (0..16).map(|k| 0.05 * k as f64).collect();
        let s = with(half, &x).unwrap();
        assert!(s.std_error_blocked && close(s.a2, 0.375, 1e-14));
        for r in [
            Restitution::Elastic,
            Restitution::Normal(1.0),
            Restitution::CentreOfMass(0.5),
        ] {
            assert_eq!(with(r, &[0.3, -0.1]).unwrap().theory, None, "{r:?}");
        }
    }

    /// The energy budget: K from 10 to 5.5 while the running total of the
    /// dissipated energy goes from 1 to 5, so 4 dissipated and a residual of
    /// 10 − 4 − 5.5 = 0.5, 0.05 relative. Without running totals: the logged
    /// collisions' losses × stride 3, 3·(0.5 + 0.25) = 2.25, residual 10 − 2.25 − 7.
    #[test]
    fn the_energy_budget_closes_with_the_running_total_or_the_logged_losses() {
        let run = |stride| RunDescription {
            restitution: Restitution::Normal(0.5),
            collision_stride: stride,
            ..RunDescription::for_tests()
        };
        let mut a = analyzer(run(1));
        a.pair(1.0, 0.0, 2.0);
        a.thermo(0.0, 10.0, Some(1.0));
        a.thermo(5.0, 7.0, Some(3.0));
        a.thermo(10.0, 5.5, Some(5.0));
        let e = report(&a.samples, None).energy.unwrap();
        assert_eq!((e.initial, e.final_, e.dissipated), (10.0, 5.5, 4.0));
        assert_eq!(e.dissipated_source, "running total of the thermo records");
        assert!(close(e.residual, 0.5, 1e-15) && close(e.relative_residual, 0.05, 1e-15));

        let mut a = analyzer(run(3));
        a.pair(1.0, 0.0, 0.5);
        a.pair(2.0, 0.0, 0.25);
        a.thermo(0.0, 10.0, None);
        a.thermo(10.0, 7.0, None);
        let e = report(&a.samples, None).energy.unwrap();
        assert_eq!(e.dissipated, 2.25);
        assert_eq!(e.dissipated_source, "sum over logged collisions × stride");
        assert!(close(e.residual, 0.75, 1e-15) && close(e.relative_residual, 0.075, 1e-15));

        assert!(report(&analyzer(run(1)).samples, None).energy.is_none());
    }

    /// Haff's law by hand. kT = 4, 1, 1/4 at t = 1, 2, 4: ∫√kT dt by trapezoids =
    /// ½·1·(2 + 1) + ½·2·(1 + ½) = 3. 2 logged pairs × stride 3 + 5 from running
    /// totals = 11 among N = 4: c = 2·11/4/3 = 11/6, ω(T0) = c·√4 = 11/3. e = ½:
    /// a2 = 16/193, 1/t0 = (3/4)(1 + 3/193)(11/3)/4 = (11/16)(196/193) = 539/772;
    /// kT(4) = 4/(1 + 3·539/772)² = 4·(772/2389)².
    #[test]
    fn haff_predicts_the_final_temperature_from_the_measured_rate() {
        let run = |totals_from_thermo| RunDescription {
            species: vec![Species::new(4, 0.3, 2.0)],
            restitution: Restitution::Normal(0.5),
            collision_stride: 3,
            totals_from_thermo,
            ..RunDescription::for_tests()
        };
        let with = |totals, series: &[(f64, f64)], logged, increments| {
            let mut a = analyzer(run(totals));
            a.samples.kt_series = series.to_vec();
            a.samples.pair_total = logged;
            a.samples.pairs_from_increments = increments;
            haff(&a.samples, 0.5)
        };
        let series = [(1.0, 4.0), (2.0, 1.0), (4.0, 0.25)];
        let h = with(false, &series, 2, 5).unwrap();
        let predicted = 4.0 * (772.0f64 / 2389.0).powi(2);
        assert!(close(h.a2, 16.0 / 193.0, 1e-15));
        assert!(close(h.collision_frequency_initial, 11.0 / 3.0, 1e-14));
        assert!(close(h.t0, 772.0 / 539.0, 1e-14));
        assert!(close(h.kt_final_predicted, predicted, 1e-14));
        assert_eq!(h.kt_final_measured, 0.25);
        assert!(close(h.ratio, 0.25 / predicted, 1e-14));
        // Running totals count every collision: the logged ones are not added,
        // c = 2·5/4/3 = 5/6 and ω(T0) = 5/3.
        let h = with(true, &series, 2, 5).unwrap();
        assert!(close(h.collision_frequency_initial, 5.0 / 3.0, 1e-14));
        // Too few points, no motion, no collisions: no prediction.
        assert!(with(false, &series[..2], 2, 5).is_none());
        assert!(with(false, &[(1.0, 0.0), (2.0, 0.0), (4.0, 0.0)], 2, 5).is_none());
        assert!(with(false, &series, 0, 0).is_none());
    }

    /// Haff's law and the theory of a2 only for normal restitution below 1.
    #[test]
    fn the_report_checks_haff_only_for_normal_restitution_below_one() {
        let with = |restitution| {
            let run = RunDescription {
                restitution,
                ..RunDescription::for_tests()
            };
            let mut a = analyzer(run);
            a.pair(1.0, 0.0, 0.1);
            for (t, k) in [(0.0, 4.0), (5.0, 2.0), (10.0, 1.0)] {
                a.thermo(t, k, None);
            }
            report(&a.samples, None).haff
        };
        assert!(with(Restitution::Normal(0.5)).is_some());
        assert!(with(Restitution::Normal(1.0)).is_none());
        assert!(with(Restitution::CentreOfMass(0.5)).is_none());
    }
}
