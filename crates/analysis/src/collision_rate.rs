//! The pair collision rate ω = 2 N_pair/(N t) per time bin, averaged with a
//! blocked standard error, and the Enskog consistency check
//! Z − 1 = (√π/4) ω τ0 with τ0 = σ √(m/kT) (physics.md §7), made bin by bin so
//! that the correlation of pressure and rate is in the error (periodic,
//! monodisperse, elastic runs only). An inelastic run's rate changes as it
//! cools (ω ∝ √T in the homogeneous cooling state): its report adds ω over the
//! first and the last sixteenth of the window.

use carom_core::observables::{collision_rate, has_walls};

use super::samples::Samples;
use super::series::{blocked, drift};
use super::stats::StatsError;
use super::thermo_report::{CollisionRateReport, EnskogReport, PressureReport, RateAt};

/// ω of each time bin (logged pair collisions × stride, plus those from running
/// totals).
pub(super) fn omega_per_bin(a: &Samples) -> Vec<f64> {
    let (n, stride) = (a.run.n(), a.run.collision_stride as f64);
    a.bins
        .iter()
        .map(|b| collision_rate(stride * b.pairs as f64 + b.pairs_weighted, n, a.bin_width))
        .collect()
}

/// The collision-rate report from the bins' ω.
pub(super) fn report(
    a: &Samples,
    omega_bins: &[f64],
    elastic: bool,
) -> Result<CollisionRateReport, StatsError> {
    let est = blocked(omega_bins)?;
    Ok(CollisionRateReport {
        per_disc: est.mean,
        std_error: est.std_error,
        logged_pair_collisions: a.pair_total,
        logged_wall_collisions: a.wall_total,
        collision_stride: a.run.collision_stride,
        counted_from: if a.run.totals_from_thermo {
            "thermo"
        } else {
            "collisions"
        },
        window: [a.t_eq, a.run.t_end],
        drift: if elastic { drift(omega_bins) } else { None },
        start: (!elastic).then(|| rate_at(a, omega_bins, false)).flatten(),
        end: (!elastic).then(|| rate_at(a, omega_bins, true)).flatten(),
    })
}

/// ω over the first (`last` false) or last sixteenth of the window's bins, with
/// its blocked error; `None` when the part has too few bins to block.
fn rate_at(a: &Samples, omega_bins: &[f64], last: bool) -> Option<RateAt> {
    let k = omega_bins.len() / 16;
    let first = if last { omega_bins.len() - k } else { 0 };
    let est = blocked(&omega_bins[first..first + k]).ok()?;
    let t0 = a.t_eq + first as f64 * a.bin_width;
    let t1 = t0 + k as f64 * a.bin_width;
    Some(RateAt {
        window: [t0, t1],
        per_disc: est.mean,
        std_error: est.std_error,
        kt: a.kt_at(0.5 * (t0 + t1)).unwrap_or(f64::NAN),
    })
}

/// The Enskog check from the bins' Z, ω and kT; `None` unless the run is
/// periodic, monodisperse and `elastic`, and has a pressure.
pub(super) fn enskog(
    a: &Samples,
    elastic: bool,
    pressure: Option<&PressureReport>,
    [z_bins, omega_bins, kt_bins]: [&[f64]; 3],
) -> Result<Option<EnskogReport>, StatsError> {
    let mut present = a.run.species.iter().filter(|s| s.count > 0);
    let (Some(sp), None, Some(pr)) = (present.next(), present.next(), pressure) else {
        return Ok(None);
    };
    if has_walls(&a.run.sim_box) || !elastic {
        return Ok(None);
    }
    let sigma = 2.0 * sp.radius;
    let c = std::f64::consts::PI.sqrt() / 4.0;
    let rhs: Vec<f64> = (0..z_bins.len())
        .map(|k| c * omega_bins[k] * sigma * (sp.mass / kt_bins[k]).sqrt())
        .collect();
    let d: Vec<f64> = (0..z_bins.len())
        .map(|k| (z_bins[k] - 1.0) - rhs[k])
        .collect();
    let d_est = blocked(&d)?;
    let rhs_est = blocked(&rhs)?;
    Ok(Some(EnskogReport {
        z_minus_1: pr.z - 1.0,
        rate_term: rhs_est.mean,
        rate_term_std_error: rhs_est.std_error,
        difference: d_est.mean,
        difference_std_error: d_est.std_error,
        relation: "Z − 1 = (√π/4) ω τ0, τ0 = σ √(m/kT) (physics.md §7)",
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::RunDescription;
    use crate::AnalysisOptions;
    use crate::Analyzer;
    use carom_core::Species;

    /// A pressure report with only Z set (the Enskog check reads nothing else).
    fn pressure_report(z: f64) -> PressureReport {
        PressureReport {
            estimator: "test",
            z,
            z_std_error: 0.0,
            beta_p: 0.0,
            beta_p_std_error: 0.0,
            p: 0.0,
            area: 100.0,
            blocks: 16,
            block_time: 1.0,
            converged: true,
            series: vec![],
            drift: None,
        }
    }

    /// ω per bin counts each logged pair `stride` times and adds the pairs of
    /// running totals: 2 (stride·logged + totals) / (N Δt), by hand.
    #[test]
    fn each_bin_counts_logged_pairs_by_the_stride_and_adds_the_totals() {
        let run = RunDescription {
            collision_stride: 3,
            ..RunDescription::for_tests()
        };
        let opts = AnalysisOptions {
            equilibrate: Some(0.0),
            ..Default::default()
        };
        let mut a = Analyzer::new(run, opts).unwrap();
        // 2 discs, t in [0, 10): logged pairs at 0.5, 0.55, 1.0 and 9.0; 5 pairs of
        // running totals spread evenly over [0, 5).
        for t in [0.5, 0.55, 1.0, 9.0] {
            a.pair(t, 1.0, 0.0);
        }
        a.increment(0.0, 5.0, 0.0, 0.0, 5);
        let omega = omega_per_bin(&a.samples);
        let h = a.samples.bin_width;
        let expected: Vec<f64> = (0..omega.len())
            .map(|k| {
                let (lo, hi) = (k as f64 * h, (k + 1) as f64 * h);
                let logged = [0.5, 0.55, 1.0, 9.0]
                    .iter()
                    .filter(|&&t| lo <= t && t < hi)
                    .count();
                let totals = 5.0 * (hi.min(5.0) - lo).max(0.0) / 5.0;
                2.0 * (3.0 * logged as f64 + totals) / (2.0 * h)
            })
            .collect();
        assert!(omega.len() >= 4);
        for (w, e) in omega.iter().zip(&expected) {
            assert!((w - e).abs() < 1e-12, "{omega:?} against {expected:?}");
        }
    }

    /// The Enskog rate term (√π/4) ω σ √(m/kT), bin by bin, for discs of
    /// diameter 1.4 and mass 2 at kT = 0.5 beside a species with no discs (which
    /// does not make the run a mixture).
    #[test]
    fn the_enskog_rate_term_uses_the_species_diameter_and_mass() {
        let run = RunDescription {
            species: vec![Species::new(0, 0.3, 1.0), Species::new(50, 0.7, 2.0)],
            ..RunDescription::for_tests()
        };
        let a = Analyzer::new(run, AnalysisOptions::default()).unwrap();
        let pressure = pressure_report(3.0);
        let n = 64;
        let z: Vec<f64> = (0..n).map(|k| 3.0 + 0.01 * (k % 3) as f64).collect();
        let omega: Vec<f64> = (0..n).map(|k| 1.5 + 0.02 * (k % 5) as f64).collect();
        let kt = vec![0.5; n];
        let e = enskog(&a.samples, true, Some(&pressure), [&z, &omega, &kt])
            .unwrap()
            .expect("one species with discs, periodic, elastic");
        let c = std::f64::consts::PI.sqrt() / 4.0;
        let mean_omega = omega.iter().sum::<f64>() / n as f64;
        let expected = c * mean_omega * 1.4 * (2.0f64 / 0.5).sqrt();
        assert!(
            (e.rate_term - expected).abs() < 1e-12,
            "{} against {expected}",
            e.rate_term
        );
        assert_eq!(e.z_minus_1, 2.0);
        // The difference (Z − 1) − rate term, bin by bin, averages to
        // ⟨Z⟩ − 1 − the mean rate term.
        let mean_z = z.iter().sum::<f64>() / n as f64;
        assert!((e.difference - (mean_z - 1.0 - expected)).abs() < 1e-12);
    }

    /// The Enskog check needs one species with discs, a pressure, a periodic box
    /// and elastic collisions: a channel, an inelastic run, a mixture and a run
    /// without a pressure get none.
    #[test]
    fn the_enskog_check_is_made_only_for_periodic_elastic_one_species_runs() {
        use carom_core::{Boundary, SimBox};
        let channel = SimBox {
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
            ..SimBox::periodic(10.0, 10.0)
        };
        let pressure = pressure_report(2.0);
        let (z, omega, kt) = (vec![2.0; 16], vec![1.0; 16], vec![1.0; 16]);
        let check = |run: RunDescription, elastic, pr: Option<&PressureReport>| {
            let a = Analyzer::new(run, AnalysisOptions::default()).unwrap();
            enskog(&a.samples, elastic, pr, [&z, &omega, &kt]).unwrap()
        };
        let base = RunDescription::for_tests;
        assert!(check(base(), true, Some(&pressure)).is_some());
        assert!(check(base(), false, Some(&pressure)).is_none());
        assert!(check(base(), true, None).is_none());
        let walled = RunDescription {
            sim_box: channel,
            ..base()
        };
        assert!(check(walled, true, Some(&pressure)).is_none());
        let mixture = RunDescription {
            species: vec![Species::reference(2), Species::new(3, 0.7, 2.0)],
            ..base()
        };
        assert!(check(mixture, true, Some(&pressure)).is_none());
    }
}
