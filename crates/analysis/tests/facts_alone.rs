//! A log's thermostat, growth and floor come from its run facts (log format 2.4
//! on), never from its stored configuration: logs written by hand with an empty
//! configuration `{}`, which names none of them, are analysed with them. A log
//! of format 2.3 (facts without them) has them derived once, by the caller's
//! `OldLogFacts`, and without one it has none.

use std::cell::Cell;
use std::path::{Path, PathBuf};

use carom_analysis::{analyze_log, analyze_log_with, AnalysisOptions, ReadObserver, Report};
use carom_core::vibrating_wall::Floor;
use carom_core::{DVec2, SimBox, Species};
use carom_engine::{EngineParams, Growth, State, Thermostat};
use carom_log::{
    GrowthPhase, LogOptions, LogWriter, ReadProgress, RunFacts, RunMetadata, Stop, StopReason,
    SummaryMetadata, Thermo, WriterOptions, WriterPosition,
};

struct Quiet;

impl ReadObserver for Quiet {
    fn pass(&mut self, _: &'static str) {}
    fn progress(&mut self, _: ReadProgress) {}
    fn warn(&mut self, _: &str) {}
}

/// A log file removed when dropped.
struct TmpLog(PathBuf);

impl Drop for TmpLog {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

/// Four discs of radius 0.5, mass 1.
const SPECIES: Species = Species::new(4, 0.5, 1.0);

/// Periodic along x, walls along y (a floor and a field need them).
fn sim_box() -> SimBox {
    let mut b = SimBox::walled(10.0, 10.0, 1.0);
    b.boundary[0] = carom_core::Boundary::Periodic;
    b
}

/// A log over [0, 10] of format `format` with the facts `facts` and the
/// configuration `{}`: thermo records every 0.5 (with the growth fields of a
/// growth that reached its target, when the run `grows` discs), one snapshot at 2.
fn write_log(name: &str, format: &str, facts: RunFacts, grows: bool) -> TmpLog {
    let path = std::env::temp_dir().join(format!(
        "carom-facts-alone-{}-{name}.mcap",
        std::process::id()
    ));
    let log = LogOptions {
        collisions: false,
        snapshot_interval: Some(10.0),
        thermo_interval: Some(0.5),
        checkpoint_interval: None,
        scene_interval: None,
        ..LogOptions::default()
    };
    let meta = RunMetadata {
        log_format: format.into(),
        carom_version: "0.0.0-test".into(),
        config: "{}".into(),
        seed: 1,
        start_time: String::new(),
        n_discs: 4,
        stop: Stop::Time(10.0),
        max_time_without_collision: None,
        log: log.clone(),
        resumed_from: None,
        resumed_at: None,
        run_facts: Some(facts),
    };
    let options = WriterOptions::from_log_options(&log);
    let mut w =
        LogWriter::create(&path, options, &meta.to_map(), WriterPosition::default()).unwrap();
    let v = DVec2::new(0.5, 0.5);
    for k in 0..=20 {
        let t = 0.5 * k as f64;
        w.write_thermo(&Thermo {
            time: t,
            kinetic_energy: 1.0,
            pair_collisions: 10 * k,
            virial_sum: 2.0 * t,
            growth: grows.then_some(GrowthPhase::Target),
            radius_scale: grows.then_some(1.0),
            packing_fraction: grows.then_some(0.0314),
            growth_z: grows.then_some(1.5),
            ..Default::default()
        })
        .unwrap();
        if k == 4 {
            w.write_snapshot(&State {
                sim_box: sim_box(),
                species: vec![SPECIES],
                species_of: vec![0; 4],
                positions: (0..4)
                    .map(|i| DVec2::new(1.0 + 2.0 * i as f64, 3.0))
                    .collect(),
                velocities: vec![v, -v, v, -v],
                images: Vec::new(),
                time: t,
            })
            .unwrap();
        }
    }
    let summary = SummaryMetadata {
        end_time: String::new(),
        stop_reason: StopReason::Time,
        error: None,
        sim_time: 10.0,
        pair_collisions: 200,
        wall_collisions: 0,
        logged_collisions: 0,
        kinetic_energy: 1.0,
        energy_lost: 0.0,
        virial_sum: 20.0,
        wall_seconds: 1.0,
        collisions_per_second: 1.0,
        potential_energy: None,
    };
    w.finish(&summary.to_map()).unwrap();
    TmpLog(path)
}

/// The facts of a run with the engine's `params` and `thermostat`.
fn facts(params: &EngineParams, thermostat: Option<Thermostat>) -> RunFacts {
    RunFacts::new(&[SPECIES], &sim_box(), params, &LogOptions::default())
        .with_thermostat(thermostat)
}

const ANDERSEN: Thermostat = Thermostat::Andersen { kt: 1.5, rate: 0.2 };

fn growth() -> EngineParams {
    EngineParams {
        growth: Growth {
            rate: 0.01,
            target_scale: 1.0,
            ..Growth::default()
        },
        ..EngineParams::default()
    }
}

fn floor() -> EngineParams {
    EngineParams {
        gravity: 1.0,
        floor: Some(Floor {
            amplitude: 0.1,
            omega: 2.0,
        }),
        ..EngineParams::default()
    }
}

fn analyse(path: &Path, old_log: &dyn Fn(&str) -> Result<RunFacts, String>) -> Report {
    analyze_log_with(path, AnalysisOptions::default(), old_log, &mut Quiet)
        .unwrap()
        .0
}

/// What the dynamics did to a report: the thermostat's target kT, the growth's
/// rate, and whether the floor took the barometric tests out (a driven bed is
/// not in equilibrium).
fn dynamics_seen(r: &Report) -> (Option<f64>, Option<f64>, bool) {
    let floor_seen = r.gravity.as_ref().is_some_and(|g| {
        !g.barometric.is_empty() && g.barometric.iter().all(|b| b.not_applicable.is_some())
    });
    (
        r.thermostat.as_ref().and_then(|t| t.target_kt),
        r.compression.as_ref().map(|c| c.rate),
        floor_seen,
    )
}

#[test]
fn the_dynamics_come_from_the_facts_alone() {
    let never =
        |_: &str| -> Result<RunFacts, String> { panic!("the configuration of a 2.4 log was read") };
    let cases = [
        (
            "thermostat",
            facts(&EngineParams::default(), Some(ANDERSEN)),
            (Some(1.5), None, false),
        ),
        ("growth", facts(&growth(), None), (None, Some(0.01), false)),
        ("floor", facts(&floor(), None), (None, None, true)),
    ];
    for (name, facts, want) in cases {
        let log = write_log(name, "2.4", facts, name == "growth");
        let r = analyse(&log.0, &never);
        assert_eq!(dynamics_seen(&r), want, "{name}");
        // Without any way to read a configuration: the same report.
        let (plain, _) = analyze_log(&log.0, AnalysisOptions::default(), &mut Quiet).unwrap();
        assert_eq!(
            serde_json::to_string(&plain).unwrap(),
            serde_json::to_string(&r).unwrap(),
            "{name}"
        );
    }
}

/// The same runs in logs of format 2.3, whose facts hold no dynamics: the
/// caller's derivation gives them, asked exactly once per log; without it there
/// are none.
#[test]
fn an_old_logs_dynamics_are_derived_once_by_the_caller() {
    let cases = [
        (
            "old-thermostat",
            facts(&EngineParams::default(), Some(ANDERSEN)),
            (Some(1.5), None, false),
        ),
        (
            "old-growth",
            facts(&growth(), None),
            (None, Some(0.01), false),
        ),
        ("old-floor", facts(&floor(), None), (None, None, true)),
    ];
    for (name, full, want) in cases {
        let stored = RunFacts {
            thermostat: None,
            growth: None,
            floor: None,
            ..full.clone()
        };
        let log = write_log(name, "2.3", stored, name == "old-growth");
        let asked = Cell::new(0);
        let derive = |config: &str| {
            assert_eq!(config, "{}");
            asked.set(asked.get() + 1);
            Ok(full.clone())
        };
        let r = analyse(&log.0, &derive);
        assert_eq!((dynamics_seen(&r), asked.get()), (want, 1), "{name}");
        let (plain, _) = analyze_log(&log.0, AnalysisOptions::default(), &mut Quiet).unwrap();
        assert_eq!(dynamics_seen(&plain), (None, None, false), "{name}");
    }
}
