//! Unit tests of the [`Analyzer`]'s plumbing: the window, the time bins, the
//! spreading of running totals, the kT series and its interpolation, and which
//! snapshots are used. What `finish` decides from the run (elastic or not) is in
//! `analyzer_finish_tests.rs`, which shares the helpers here. Expected values are
//! worked by hand (stated beside each) or by a direct computation in the test.

use super::*;
use crate::samples::TimeBin;
use carom_core::Species;

pub(super) fn run() -> RunDescription {
    RunDescription::for_tests()
}

/// A run logged over [t_start, t_end].
fn span(t_start: f64, t_end: f64) -> RunDescription {
    RunDescription {
        t_start,
        t_end,
        ..run()
    }
}

pub(super) fn opts(equilibrate: f64, every: Option<f64>, time_bins: usize) -> AnalysisOptions {
    AnalysisOptions {
        equilibrate: Some(equilibrate),
        every,
        time_bins,
        ..Default::default()
    }
}

/// `got` within a relative 10⁻¹² of the finite `want` (an infinite `got` is not).
fn close(got: f64, want: f64) -> bool {
    (got - want).abs() <= 1e-12 * want.abs().max(1.0)
}

#[test]
fn inconsistent_snapshots_are_errors_not_panics() {
    let mut a = Analyzer::new(run(), AnalysisOptions::default()).unwrap();
    assert!(a.snapshot(1.0, &[0, 1], &[1.0, 1.0], &[0.0, 0.0]).is_err());
    assert!(a.snapshot(1.0, &[0], &[1.0, 1.0], &[0.0, 0.0]).is_err());
    // Species and vx agree, vy is one short.
    assert!(a.snapshot(1.0, &[0, 0], &[1.0, 1.0], &[0.0]).is_err());
    assert!(a.snapshot(1.0, &[0, 0], &[1.0, -1.0], &[0.0, 0.0]).is_ok());
    assert!(a.positions(1.0, &[0, 0], &[1.0, 2.0], &[1.0]).is_err());
    assert!(a.positions(1.0, &[0, 1], &[1.0, 2.0], &[1.0, 1.0]).is_err());
    // Only the one consistent snapshot was counted.
    assert_eq!(a.samples.snapshots_seen, 1);
    let mut r = run();
    r.t_end = 0.0;
    assert!(Analyzer::new(r, AnalysisOptions::default()).is_err());
    let opts = AnalysisOptions {
        equilibrate: Some(20.0),
        ..Default::default()
    };
    assert!(Analyzer::new(run(), opts).is_err());
}

/// Without `--equilibrate` the first 10 % of [2, 12] is skipped: from 3; one asked
/// for before the log's start is the start.
#[test]
fn the_window_starts_after_a_tenth_of_the_span_or_where_asked_but_not_before_the_log() {
    let a = Analyzer::new(span(2.0, 12.0), AnalysisOptions::default()).unwrap();
    assert_eq!(a.equilibrated_from(), 3.0);
    let a = Analyzer::new(span(2.0, 12.0), opts(0.5, None, 16)).unwrap();
    assert_eq!(a.equilibrated_from(), 2.0);
    let a = Analyzer::new(span(2.0, 12.0), opts(7.5, None, 16)).unwrap();
    assert_eq!(a.equilibrated_from(), 7.5);
}

/// [2, 10] in 16 bins of 0.5; stride 3. A collision at t goes into bin
/// ⌊(t − 2)/0.5⌋ (t = 10 into the last, 15), weighted by 3; collisions before 2 or
/// after 10 into none, but they are counted and their energy lost is summed.
#[test]
fn collisions_go_into_the_bin_of_their_time_weighted_by_the_stride() {
    let r = RunDescription {
        collision_stride: 3,
        ..run()
    };
    let mut a = Analyzer::new(r.clone(), opts(2.0, None, 16)).unwrap();
    // (t, bin): 5.3 → ⌊6.6⌋ = 6, 2 (the window's first instant) → 0.
    let events = [
        (1.9, None),
        (2.0, Some(0)),
        (5.3, Some(6)),
        (10.0, Some(15)),
    ];
    for (k, &(t, _)) in events.iter().enumerate() {
        a.pair(t, 0.7 + k as f64, 0.25 * k as f64);
        a.wall(t, 0.2 + k as f64, 0.5);
    }
    a.pair(10.5, 1.0, 0.0);
    a.wall(10.5, 1.0, 0.0);
    assert_eq!((a.samples.pair_total, a.samples.wall_total), (5, 5));
    // Energy lost: 3·(0.25·(0 + 1 + 2 + 3)) + 3·(4·0.5) = 4.5 + 6.
    assert!(close(a.samples.lost_from_collisions, 10.5));
    let mut expected = [TimeBin::default(); 16];
    for (k, &(_, bin)) in events.iter().enumerate() {
        if let Some(b) = bin {
            expected[b].virial = 3.0 * (0.7 + k as f64);
            expected[b].wall_impulse = 3.0 * (0.2 + k as f64);
            expected[b].pairs = 1;
            expected[b].walls = 1;
        }
    }
    for (b, e) in a.samples.bins.iter().zip(&expected) {
        assert!(close(b.virial, e.virial) && close(b.wall_impulse, e.wall_impulse));
        assert_eq!(
            (b.pairs, b.walls, b.pairs_weighted),
            (e.pairs, e.walls, 0.0)
        );
    }
    // With the totals from the thermo records, collisions are only counted.
    let mut a = Analyzer::new(
        RunDescription {
            totals_from_thermo: true,
            ..r
        },
        opts(2.0, None, 16),
    )
    .unwrap();
    a.pair(5.3, 1.0, 1.0);
    a.wall(5.3, 1.0, 1.0);
    assert_eq!((a.samples.pair_total, a.samples.wall_total), (1, 1));
    assert_eq!(a.samples.lost_from_collisions, 0.0);
    assert!(a
        .samples
        .bins
        .iter()
        .all(|b| b.pairs + b.walls == 0 && b.virial == 0.0));
}

#[test]
fn increments_spread_over_time_bins_keep_their_total() {
    let mut a = Analyzer::new(run(), opts(0.0, None, 16)).unwrap();
    a.increment(0.3, 7.1, 68.0, 0.0, 34);
    let v: f64 = a.samples.bins.iter().map(|b| b.virial).sum();
    let p: f64 = a.samples.bins.iter().map(|b| b.pairs_weighted).sum();
    assert!((v - 68.0).abs() < 1e-9 && (p - 34.0).abs() < 1e-9);
    // Bin 0 ([0, 0.625)) holds the overlap 0.325 of 6.8.
    assert!((a.samples.bins[0].virial - 68.0 * 0.325 / 6.8).abs() < 1e-9);
}

/// [1, 3.3] over the window from 2 in bins of 0.5: 0.5, 0.5 and 0.3 of its 2.3 in
/// bins 0, 1, 2 (the part before 2 in none): virial 4.6 → 1, 1, 0.6; impulse
/// 2.3 → 0.5, 0.5, 0.3; 23 pairs → 5, 5, 3.
#[test]
fn an_increment_is_shared_by_the_bins_in_proportion_to_their_overlap() {
    let mut a = Analyzer::new(run(), opts(2.0, None, 16)).unwrap();
    a.increment(1.0, 3.3, 4.6, 2.3, 23);
    assert_eq!(a.samples.pairs_from_increments, 23);
    let want = [(1.0, 0.5, 5.0), (1.0, 0.5, 5.0), (0.6, 0.3, 3.0)];
    for (k, b) in a.samples.bins.iter().enumerate() {
        let (v, w, p) = want.get(k).copied().unwrap_or_default();
        assert!(close(b.virial, v) && close(b.wall_impulse, w), "bin {k}");
        assert!(close(b.pairs_weighted, p), "bin {k}");
    }
    // Empty, reversed or undefined intervals add nothing, not even to the count.
    let before = a.samples.bins.clone();
    a.increment(3.0, 3.0, 1.0, 1.0, 7);
    a.increment(4.0, 3.0, 1.0, 1.0, 7);
    a.increment(f64::NAN, 5.0, 1.0, 1.0, 7);
    a.increment(3.0, f64::NAN, 1.0, 1.0, 7);
    assert_eq!(a.samples.pairs_from_increments, 23);
    // Wholly before the window: counted, in no bin.
    a.increment(0.5, 1.5, 1.0, 1.0, 7);
    assert_eq!(a.samples.pairs_from_increments, 30);
    for (b, e) in a.samples.bins.iter().zip(&before) {
        assert_eq!(
            (b.virial, b.wall_impulse, b.pairs_weighted),
            (e.virial, e.wall_impulse, e.pairs_weighted)
        );
    }
}

/// The bins an increment reaches, against the overlap of [t0, t1] with each bin
/// [t_eq + kΔ, t_eq + (k + 1)Δ] computed directly for every bin: windows from a
/// start below 1, with bins 2 wide; from a negative start, with bins narrower
/// than 1; increments starting inside a bin and running past the log's end.
#[test]
fn an_increment_reaches_exactly_the_bins_it_overlaps() {
    let cases = [
        // (t_start, t_eq, t_end, [(t0, t1)]), 16 bins.
        (0.0, 0.5, 32.5, vec![(1.5, 7.5), (20.2, 40.0), (9.0, 9.7)]),
        (-4.0, -3.0, 4.0, vec![(-2.5, 1.3), (-3.5, -2.9), (2.0, 4.0)]),
        (1.0, 4.0, 8.0, vec![(4.6, 5.2), (4.1, 4.2), (6.9, 7.7)]),
    ];
    for (t_start, t_eq, t_end, increments) in cases {
        for (t0, t1) in increments {
            let mut a = Analyzer::new(span(t_start, t_end), opts(t_eq, None, 16)).unwrap();
            a.increment(t0, t1, 3.0, 5.0, 16);
            let width = (t_end - t_eq) / 16.0;
            for (k, b) in a.samples.bins.iter().enumerate() {
                let (lo, hi) = (t_eq + k as f64 * width, t_eq + (k + 1) as f64 * width);
                let overlap = (t1.min(hi).min(t_end) - t0.max(lo)).max(0.0);
                let share = overlap / (t1 - t0);
                let ok = (b.virial - 3.0 * share).abs() < 1e-12
                    && (b.wall_impulse - 5.0 * share).abs() < 1e-12
                    && (b.pairs_weighted - 16.0 * share).abs() < 1e-12;
                assert!(
                    ok,
                    "[{t0}, {t1}] in bin {k} of {t_eq}..{t_end}: {b:?}, share {share}"
                );
            }
        }
    }
}

/// Three discs of mass 2 in a periodic box: f = 2·3 − 2 = 4, kT = K/2. A thermo
/// record and a snapshot at the same time give one point of kT (the later) and one
/// energy record (the thermo record's, which knows the energy lost).
#[test]
fn records_at_the_same_time_give_one_point() {
    let r = RunDescription {
        species: vec![Species::new(3, 0.4, 2.0)],
        ..run()
    };
    let mut a = Analyzer::new(r, opts(0.0, Some(0.0), 16)).unwrap();
    a.thermo(1.0, 6.0, Some(0.5));
    a.thermo(1.0, 8.0, None);
    assert_eq!(a.samples.kt_series, [(1.0, 4.0)]);
    assert_eq!(a.samples.energy_series, [(1.0, 8.0, Some(0.5))]);
    // K = ½·2·(1 + 1 + 4) = 6 → kT 3.
    a.snapshot(1.0, &[0, 0, 0], &[1.0, 0.0, 2.0], &[0.0, -1.0, 0.0])
        .unwrap();
    assert_eq!(a.samples.kt_series, [(1.0, 3.0)]);
    assert_eq!(a.samples.energy_series, [(1.0, 8.0, Some(0.5))]);
    // K = ½·2·(4 + 0 + 1) = 5 at t = 2: a new point.
    a.snapshot(2.0, &[0, 0, 0], &[2.0, 0.0, 0.0], &[0.0, 0.0, 1.0])
        .unwrap();
    assert_eq!(a.samples.kt_series, [(1.0, 3.0), (2.0, 2.5)]);
    assert_eq!(
        a.samples.energy_series,
        [(1.0, 8.0, Some(0.5)), (2.0, 5.0, None)]
    );
    a.thermo(2.0, 9.0, Some(0.75));
    a.thermo(3.0, 10.0, None);
    assert_eq!(a.samples.kt_series, [(1.0, 3.0), (2.0, 4.5), (3.0, 5.0)]);
    assert_eq!(
        a.samples.energy_series,
        [
            (1.0, 8.0, Some(0.5)),
            (2.0, 9.0, Some(0.75)),
            (3.0, 10.0, None)
        ]
    );
}

/// Masses 2 and 0.5, three discs, periodic: f = 4. K = ½·2·(1 + 0.25)
/// + ½·0.5·(4 + 1) + ½·0.5·(0.25 + 9) = 1.25 + 1.25 + 2.3125 = 4.8125, kT = 2K/4.
#[test]
fn a_snapshot_s_kinetic_energy_weighs_each_disc_by_its_species_mass() {
    let r = RunDescription {
        species: vec![Species::new(1, 0.4, 2.0), Species::new(2, 0.3, 0.5)],
        ..run()
    };
    let mut a = Analyzer::new(r, opts(0.0, Some(0.0), 16)).unwrap();
    let (s, vx, vy) = ([0, 1, 1], [1.0, -2.0, 0.5], [0.5, 1.0, -3.0]);
    a.snapshot(1.0, &s, &vx, &vy).unwrap();
    assert_eq!(a.samples.kt_series, [(1.0, 2.40625)]);
    assert_eq!(a.samples.energy_series, [(1.0, 4.8125, None)]);
    assert_eq!(
        (a.samples.mb_kinetic, a.samples.snapshot_kt.clone()),
        (4.8125, vec![2.40625])
    );
    // The velocity tests see velocities relative to the centre of mass:
    // u = (2·1 + 0.5·(−2) + 0.5·0.5, 2·0.5 + 0.5·1 + 0.5·(−3))/3 = (5/12, 0).
    let u = 5.0 / 12.0;
    let near = |a: &[f64], b: &[f64]| {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-15)
    };
    assert!(near(&a.samples.vx[0], &[1.0 - u]) && near(&a.samples.vy[0], &[0.5]));
    assert!(near(&a.samples.vx[1], &[-2.0 - u, 0.5 - u]) && near(&a.samples.vy[1], &[1.0, -3.0]));
    assert!(near(
        &a.samples.speeds[1],
        &[(-2.0 - u).hypot(1.0), (0.5 - u).hypot(-3.0)]
    ));
    // A second snapshot adds its K (½·2·4 + 0 + 0 = 4) to the sum.
    a.snapshot(2.0, &s, &[0.0, 0.0, 0.0], &[2.0, 0.0, 0.0])
        .unwrap();
    assert_eq!(a.samples.mb_kinetic, 8.8125);
    assert_eq!(a.samples.snapshot_a2.len(), 2);
}

/// Log [2, 12], window from 4: the tolerance for a snapshot's time rounded below
/// the window's start is 10⁻¹² × max(|4|, span 10) = 10⁻¹¹. A snapshot 8·10⁻¹²
/// early counts, one 1.2·10⁻¹¹ early does not, nor one at 3; one at 7 does.
#[test]
fn snapshots_count_from_the_window_start_within_a_rounding_tolerance() {
    let times = [3.0, 4.0 - 1.2e-11, 4.0 - 8e-12, 7.0];
    let mut a = Analyzer::new(span(2.0, 12.0), opts(4.0, Some(0.0), 16)).unwrap();
    for t in times {
        a.snapshot(t, &[0, 0], &[1.0, -1.0], &[0.5, 0.0]).unwrap();
    }
    assert_eq!(a.samples.snapshots_used, [times[2], times[3]]);
    assert_eq!(a.samples.snapshots_seen, 4);
    assert_eq!(a.samples.kt_series.len(), 4);
    // The same rule for positions (into g(r) and ψ6): a 16-disc lattice.
    let (sim_box, x, y) = crate::test_lattice::triangular(4, 4, 2.0);
    let r = RunDescription {
        species: vec![Species::reference(16)],
        sim_box,
        ..span(2.0, 12.0)
    };
    let mut a = Analyzer::new(r, opts(4.0, Some(0.0), 16)).unwrap();
    for t in times {
        a.positions(t, &[0; 16], &x, &y).unwrap();
    }
    assert_eq!(a.structure.pair_correlation.snapshot_count(), 2);
}

/// Snapshots at least `every` = 2.5 apart, to a relative 10⁻⁹: after 4, not 5;
/// 6.5; then 9 − 1.5·10⁻⁹, within 2.5·10⁻⁹ of 6.5 + 2.5.
#[test]
fn snapshots_used_are_at_least_every_apart() {
    let mut a = Analyzer::new(run(), opts(0.0, Some(2.5), 16)).unwrap();
    let times = [4.0, 5.0, 6.5, 9.0 - 1.5e-9];
    for t in times {
        a.snapshot(t, &[0, 0], &[1.0, 0.0], &[0.0, 2.0]).unwrap();
    }
    assert_eq!(a.samples.snapshots_used, [times[0], times[2], times[3]]);
    assert_eq!(
        (a.samples.snapshot_kt.len(), a.samples.speeds[0].len()),
        (3, 6)
    );
}

/// kT = K here (2 discs, periodic: f = 2). Records (1, 2), (3, 5), (7, 1): before
/// the first the first, after the last the last, between them linear: at 2, 3.5;
/// at 4, 5 − 4/4 = 4.
#[test]
fn kt_is_interpolated_linearly_between_records() {
    let mut a = Analyzer::new(run(), opts(0.0, None, 16)).unwrap();
    assert_eq!(a.samples.kt_at(1.0), None);
    for (t, k) in [(1.0, 2.0), (3.0, 5.0), (7.0, 1.0)] {
        a.thermo(t, k, None);
    }
    let at = [
        (0.5, 2.0),
        (1.0, 2.0),
        (2.0, 3.5),
        (3.0, 5.0),
        (4.0, 4.0),
        (6.0, 2.0),
    ];
    for (t, kt) in at.into_iter().chain([(7.0, 1.0), (8.0, 1.0)]) {
        assert_eq!(a.samples.kt_at(t), Some(kt), "t = {t}");
    }
}

/// kT = 1 + t (K = 1 + t, f = 2) over [0, 10]; window from 2 in 16 bins of 0.5:
/// bin k's middle is 2 + 0.5(k + 0.5), its kT 3.25 + 0.5 k.
#[test]
fn each_bin_takes_kt_at_its_middle() {
    let mut a = Analyzer::new(run(), opts(2.0, None, 16)).unwrap();
    a.thermo(0.0, 1.0, None);
    a.thermo(10.0, 11.0, None);
    let kt = a.samples.kt_per_bin();
    assert_eq!(kt.len(), 16);
    for (k, v) in kt.iter().enumerate() {
        assert!(close(*v, 3.25 + 0.5 * k as f64), "bin {k}: {v}");
    }
}
