//! Unit tests of what [`Analyzer::finish`] decides from the run: whether it is
//! elastic (and so gets the contact theorem and unscaled snapshots) or inelastic
//! (and so gets the cooling report and snapshots scaled to a common temperature),
//! and how the window reports its closest snapshots. Helpers are shared with the
//! plumbing tests in `analyzer_tests.rs`. Expected values are worked by hand.

use super::tests::{opts, run};
use super::*;
use carom_core::{Boundary, Restitution, SimBox, Species};

/// An analyzer over [0, 10] from 2 (16 bins of 0.5) with kT known throughout and
/// one logged pair at the middle of every bin: ω = 2·1/(2·0.5) = 2 in each.
fn fed(r: RunDescription, every: Option<f64>) -> Analyzer {
    let mut a = Analyzer::new(r, opts(2.0, every, 16)).unwrap();
    a.thermo(0.0, 3.0, Some(0.0));
    a.thermo(10.0, 3.0, Some(0.0));
    for k in 0..16 {
        a.pair(2.25 + 0.5 * k as f64, 0.1, 0.0);
    }
    a
}

/// Elastic only when the pair rule is elastic and every wall has restitution 1;
/// only an inelastic run gets the cooling report.
#[test]
fn a_run_is_elastic_only_when_pairs_and_walls_conserve_energy() {
    let cases = [
        (Restitution::Elastic, SimBox::periodic(10.0, 10.0), true),
        (
            Restitution::Normal(0.8),
            SimBox::periodic(10.0, 10.0),
            false,
        ),
        (Restitution::Elastic, SimBox::walled(10.0, 10.0, 0.9), false),
        (Restitution::Elastic, SimBox::walled(10.0, 10.0, 1.0), true),
        (
            Restitution::Elastic,
            SimBox {
                boundary: [Boundary::Periodic, Boundary::Walls { restitution: 0.5 }],
                ..SimBox::periodic(10.0, 10.0)
            },
            false,
        ),
    ];
    for (restitution, sim_box, elastic) in cases {
        let r = RunDescription {
            restitution,
            sim_box,
            ..run()
        };
        let report = fed(r, None).finish().unwrap();
        assert_eq!(report.elastic, elastic, "{restitution:?} {sim_box:?}");
        assert_eq!(report.inelastic.is_some(), !elastic);
    }
}

/// Snapshots used at 2, 5, 6.5 and 9: the smallest gap 1.5 at ω = 2 is 3
/// collisions per disc.
#[test]
fn the_window_reports_the_closest_snapshots_in_collisions_per_disc() {
    let mut a = fed(run(), Some(0.0));
    for t in [2.0, 5.0, 6.5, 9.0] {
        a.snapshot(t, &[0, 0], &[1.0, -1.0], &[1.0, 1.0]).unwrap();
    }
    let r = a.finish().unwrap();
    assert_eq!(r.collision_rate.per_disc, 2.0);
    let w = r.window;
    assert_eq!(w.spacing_collisions, Some(3.0));
    assert_eq!((w.t_start, w.t_end, w.equilibrate), (0.0, 10.0, 2.0));
    assert_eq!(
        (w.every, w.every_default, w.every_from_budget),
        (Some(0.0), false, false)
    );
    assert_eq!(
        (w.snapshots_seen, w.snapshot_times),
        (4, vec![2.0, 5.0, 6.5, 9.0])
    );
    assert_eq!(w.max_velocities, crate::MAX_VELOCITIES);
}

/// The contact theorem Z = 1 + (π/2) n Σ x_a x_b σ_ab² g_ab(σ⁺) holds for an
/// elastic gas in a periodic box only: with walls or inelastic collisions there
/// is g(r) but no comparison with the virial pressure.
#[test]
fn the_contact_theorem_is_made_only_for_elastic_periodic_runs() {
    // Lattice spacing 1.1 σ: every disc has neighbours in the contact fit range.
    let (periodic, x, y) = crate::test_lattice::triangular(4, 4, 1.1);
    let walled = SimBox {
        boundary: [Boundary::Walls { restitution: 1.0 }; 2],
        ..periodic
    };
    for (restitution, sim_box, theorem) in [
        (Restitution::Elastic, periodic, true),
        (Restitution::Elastic, walled, false),
        (Restitution::Normal(0.9), periodic, false),
    ] {
        let r = RunDescription {
            species: vec![Species::reference(16)],
            sim_box,
            restitution,
            ..run()
        };
        let mut a = fed(r, None);
        for t in [3.0, 6.0] {
            a.positions(t, &[0; 16], &x, &y).unwrap();
        }
        let pc = a.finish().unwrap().pair_correlation.unwrap();
        assert_eq!(
            pc.contact_theorem.is_some(),
            theorem,
            "{restitution:?} {sim_box:?}"
        );
    }
}

/// A cooling gas: 1000 discs of mass 2 at kT = 1, then at kT = 9 (Gaussian
/// components of variance kT/m). Pooled as they are they are no Maxwell–Boltzmann
/// distribution; each scaled to the mean kT, as for an inelastic run, they are.
/// An elastic run's snapshots are tested as they are.
#[test]
fn only_an_inelastic_run_s_snapshots_are_scaled_to_a_common_temperature() {
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    let n = 1000;
    let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
    let species = vec![0u16; n];
    let draws: Vec<(Vec<f64>, Vec<f64>)> = [1.0f64, 9.0]
        .iter()
        .map(|kt| {
            let s = (kt / 2.0).sqrt();
            let mut g =
                || s * <StandardNormal as Distribution<f64>>::sample(&StandardNormal, &mut rng);
            ((0..n).map(|_| g()).collect(), (0..n).map(|_| g()).collect())
        })
        .collect();
    let mb = |restitution| {
        let r = RunDescription {
            species: vec![Species::new(n, 0.5, 2.0)],
            sim_box: SimBox::periodic(100.0, 100.0),
            restitution,
            ..run()
        };
        let mut a = Analyzer::new(r, opts(0.0, Some(0.0), 16)).unwrap();
        for (k, (vx, vy)) in draws.iter().enumerate() {
            a.snapshot(1.0 + k as f64, &species, vx, vy).unwrap();
        }
        a.finish().unwrap().maxwell_boltzmann.remove(0)
    };
    let cooling = mb(Restitution::Normal(0.9));
    assert!(cooling.scaled_to_snapshot_temperature);
    assert!(cooling.passed, "{cooling:?}");
    assert_eq!(cooling.ks.n, 2 * n);
    let elastic = mb(Restitution::Elastic);
    assert!(!elastic.scaled_to_snapshot_temperature);
    assert!(
        !elastic.passed && elastic.ks.p_value < 1e-6,
        "{:?}",
        elastic.ks
    );
}
