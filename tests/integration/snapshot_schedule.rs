//! `log.snapshot_schedule`: the snapshot times a run writes with log-spaced points
//! inside each snapshot interval (hand-worked), the unchanged times without one,
//! a cut or extended run resumed onto the same schedule, and the analysis using
//! only the block starts for structure.

use crate::mcap_common::*;
use carom_analysis::{analyze_log, AnalysisOptions, ReadObserver, Report};
use carom_log::{
    Compression, LogMessage, LogOptions, LogReader, ReadProgress, SchedulePoints, Stop,
};
use carom_run::{resume, run, Control, ResumeOptions};
use std::path::Path;

/// T = 1, thermo every 0.5, a checkpoint every 2, and `schedule` inside each T.
fn log_opts(interval: f64, schedule: Option<SchedulePoints>) -> LogOptions {
    LogOptions {
        snapshot_interval: Some(interval),
        snapshot_schedule: schedule,
        thermo_interval: Some(0.5),
        checkpoint_interval: Some(2.0),
        compression: Compression::Zstd,
        ..LogOptions::default()
    }
}

/// n = 2, δ = 0.01 (with T = 1: offsets 0.01 and 0.01·(1/0.01)^(1/2) = 0.1).
const TWO: SchedulePoints = SchedulePoints {
    points: 2,
    first: 0.01,
};

fn snapshot_times(path: &Path) -> Vec<f64> {
    let mut r = LogReader::open(path).unwrap();
    r.snapshots()
        .map(|m| match m.unwrap() {
            LogMessage::Snapshot(s) => s.time,
            other => panic!("not a snapshot: {other:?}"),
        })
        .collect()
}

fn run_to(log: LogOptions, t_end: f64, name: &str) -> std::path::PathBuf {
    let out = tmp(name);
    run(
        &spec(system(120, 0.4, false, false, 7), Stop::Time(t_end), log),
        &out,
        Control::default(),
    )
    .unwrap();
    out
}

#[test]
fn snapshots_fall_at_block_starts_and_the_log_spaced_offsets() {
    let out = run_to(log_opts(1.0, Some(TWO)), 3.0, "sched.mcap");
    let got = snapshot_times(&out);
    // t0 = 0: blocks at 0, 1, 2, each with 0.01 and 0.1 after it; the stop at 3
    // comes after the block start due then.
    let want = [0.0, 0.01, 0.1, 1.0, 1.01, 1.1, 2.0, 2.01, 2.1, 3.0];
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (t, w) in got.iter().zip(want) {
        assert!((t - w).abs() < 1e-12, "{got:?}");
    }
    // Block starts are exactly b·T.
    for b in 0..4 {
        assert_eq!(got[3 * b], b as f64);
    }
    // The log says which schedule it ran.
    let r = LogReader::open(&out).unwrap();
    assert_eq!(r.run().log.snapshot_schedule, Some(TWO));
    std::fs::remove_file(&out).unwrap();
}

#[test]
fn without_a_schedule_snapshots_stay_at_t0_plus_k_interval() {
    // T = 0.3: the driver's times are 0 + k as f64 * 0.3, to the bit (a running
    // sum of 0.3 would differ from the 3rd on), up to and including the stop at 3.
    let t_end = 3.0;
    let out = run_to(log_opts(0.3, None), t_end, "plain.mcap");
    let got: Vec<u64> = snapshot_times(&out).iter().map(|t| t.to_bits()).collect();
    let want: Vec<u64> = (0u64..)
        .map(|k| 0.0 + k as f64 * 0.3)
        .take_while(|t| *t <= t_end)
        .map(f64::to_bits)
        .collect();
    assert_eq!(got, want);
    let r = LogReader::open(&out).unwrap();
    assert_eq!(r.run().log.snapshot_schedule, None);
    assert!(!r.run_map()["log_options"].contains("snapshot_schedule"));
    std::fs::remove_file(&out).unwrap();
}

#[test]
fn a_resumed_run_continues_the_schedule() {
    let log = log_opts(1.0, Some(TWO));
    let full = run_to(log.clone(), 7.0, "sched-full.mcap");
    let want = snapshot_times(&full);
    // 7 blocks of 3 and the block start at 7.
    assert_eq!(want.len(), 22);
    // Cut mid-run (a crash), resumed from the last checkpoint.
    let bytes = std::fs::read(&full).unwrap();
    let cut = tmp("sched-cut.mcap");
    std::fs::write(&cut, &bytes[..bytes.len() * 6 / 10]).unwrap();
    let resumed = tmp("sched-resumed.mcap");
    resume(
        &cut,
        &resumed,
        &ResumeOptions::default(),
        Control::default(),
    )
    .unwrap();
    assert_eq!(snapshot_times(&resumed), want);
    // A finished shorter run extended to the same stop.
    let short = run_to(log, 4.5, "sched-short.mcap");
    let extended = tmp("sched-extended.mcap");
    let until = ResumeOptions {
        stop: Some(Stop::Time(7.0)),
    };
    resume(&short, &extended, &until, Control::default()).unwrap();
    assert_eq!(snapshot_times(&extended), want);
    for p in [&full, &cut, &resumed, &short, &extended] {
        std::fs::remove_file(p).unwrap();
    }
}

struct Quiet;
impl ReadObserver for Quiet {
    fn pass(&mut self, _: &'static str) {}
    fn progress(&mut self, _: ReadProgress) {}
    fn warn(&mut self, _: &str) {}
}

fn analyze(path: &Path) -> Report {
    let opts = AnalysisOptions {
        equilibrate: Some(2.0),
        ..AnalysisOptions::default()
    };
    analyze_log(path, opts, &mut Quiet).unwrap().0
}

#[test]
fn the_structure_and_velocity_tests_use_only_block_starts() {
    let with = run_to(log_opts(1.0, Some(TWO)), 20.0, "sched-an.mcap");
    let without = run_to(log_opts(1.0, None), 20.0, "plain-an.mcap");
    let (a, b) = (analyze(&with), analyze(&without));
    // 20 blocks of 3 and the block start at 20 are read; g(r) uses the 19 block
    // starts t = 2, 3, ..., 20 from the equilibration time on.
    assert_eq!(a.window.snapshots_seen, 61);
    assert_eq!(b.window.snapshots_seen, 21);
    let (ga, gb) = (
        a.pair_correlation.as_ref().unwrap(),
        b.pair_correlation.as_ref().unwrap(),
    );
    assert_eq!((ga.snapshots, gb.snapshots), (19, 19));
    // Logging does not touch the trajectory, so the structure from the block
    // starts is that of the run without the schedule, to the bit. (Not the
    // contact theorem's virial Z: the in-block snapshots do add kT points, which
    // the pressure interpolates.)
    assert!(ga.pairs == gb.pairs, "g(r) differs");
    assert!(a.bond_order == b.bond_order, "ψ6 differs");
    // g6 sums ψ6 products over pairs in parallel, in no fixed order: equal to
    // rounding, from the same number of snapshots.
    let (sa, sb) = (
        a.orientational_correlation.as_ref().unwrap(),
        b.orientational_correlation.as_ref().unwrap(),
    );
    assert_eq!((sa.snapshots, sb.snapshots), (19, 19));
    for (x, y) in sa.g6.iter().zip(&sb.g6) {
        assert!(
            (x.is_nan() && y.is_nan()) || (x - y).abs() <= 1e-9 * x.abs().max(1e-12),
            "g6 {x} ≠ {y}"
        );
    }
    assert!(a.structure_factor == b.structure_factor, "S(k) differs");
    assert!(a.structure_factor.is_some() && a.bond_order.is_some());
    // The velocity tests too: the same block starts, whole numbers.
    assert_eq!(a.window.snapshot_times, b.window.snapshot_times);
    assert!(!a.window.snapshot_times.is_empty());
    assert!(a.window.snapshot_times.iter().all(|t| t.fract() == 0.0));
    for p in [&with, &without] {
        std::fs::remove_file(p).unwrap();
    }
}
