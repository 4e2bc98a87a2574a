//! A thermostatted run through the log: a log cut anywhere resumes from its last
//! checkpoint to the same bytes (the thermostat's generator is in the checkpoint),
//! collisions are logged in full, and `carom analyze` reports the thermostat's
//! target in place of an energy budget.

use crate::mcap_common::tmp;
use carom_analysis::{analyze_log, AnalysisOptions, ReadObserver};
use carom_config::load_config;
use carom_log::{CollisionDetail, LogEnd, LogReader, ReadProgress};
use carom_run::{resume, run, Control, ResumeOptions};
use std::path::Path;

struct Quiet;
impl ReadObserver for Quiet {
    fn pass(&mut self, _: &'static str) {}
    fn progress(&mut self, _: ReadProgress) {}
    fn warn(&mut self, _: &str) {}
}

fn raw_messages(path: &Path) -> Vec<(usize, u32, u64, Vec<u8>)> {
    let mut r = LogReader::open(path).unwrap();
    let mut v = Vec::new();
    while let Some(m) = r.next_raw().unwrap() {
        v.push((m.channel, m.sequence, m.log_time, m.data.to_vec()));
    }
    assert_eq!(*r.end(), LogEnd::Complete);
    v
}

/// `data/<name>` with 300 discs for 12 time units, a checkpoint every 2.
fn example(name: &str) -> carom_log::RunSpec {
    example_with(name, &[])
}

/// [`example`] with more `--set`s.
fn example_with(name: &str, more: &[&str]) -> carom_log::RunSpec {
    let data = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data")
        .join(name);
    let sets: Vec<String> = [
        "species.0.count=300",
        "stop.duration=12",
        "log.checkpoint_interval=2",
        "log.snapshot_interval=0.5",
    ]
    .iter()
    .chain(more)
    .map(|s| s.to_string())
    .collect();
    load_config(Some(&data), &sets).unwrap()
}

#[test]
fn a_cut_thermostatted_log_resumes_to_the_same_bytes() {
    for name in ["thermostatted-fluid.json", "driven-granular.json"] {
        let spec = example(name);
        assert!(spec.thermostat.is_some());
        assert_eq!(spec.log.collision_record(), CollisionDetail::Full);
        let full = tmp(&format!("thermo-full-{name}.mcap"));
        run(&spec, &full, Control::default()).unwrap();
        let expected = raw_messages(&full);
        let bytes = std::fs::read(&full).unwrap();
        for frac in [0.35, 0.8] {
            let cut = tmp(&format!("thermo-cut-{name}.mcap"));
            std::fs::write(&cut, &bytes[..(bytes.len() as f64 * frac) as usize]).unwrap();
            let out = tmp(&format!("thermo-resumed-{name}.mcap"));
            let s = resume(&cut, &out, &ResumeOptions::default(), Control::default()).unwrap();
            assert!(s.collisions_this_process > 0);
            let got = raw_messages(&out);
            assert_eq!(got.len(), expected.len(), "{name} cut at {frac}");
            for (k, (a, b)) in got.iter().zip(&expected).enumerate() {
                assert!(a == b, "{name}: message {k} differs after a cut at {frac}");
            }
            for p in [&cut, &out] {
                std::fs::remove_file(p).unwrap();
            }
        }
        std::fs::remove_file(&full).unwrap();
    }
}

#[test]
fn analyze_reports_the_thermostat_in_place_of_the_energy_budget() {
    let spec = example("driven-granular.json");
    let path = tmp("thermo-analyze-driven.mcap");
    run(&spec, &path, Control::default()).unwrap();
    let (r, complete) = analyze_log(&path, AnalysisOptions::default(), &mut Quiet).unwrap();
    assert!(complete);
    let t = r.thermostat.as_ref().expect("a thermostat report");
    assert_eq!(t.kind, "driven");
    assert_eq!((t.xi2, t.interval), (Some(0.17), Some(0.02)));
    let (measured, predicted) = (
        t.granular_temperature.unwrap(),
        t.predicted_temperature.unwrap(),
    );
    // 300 discs over 12 time units: T within 15 % of (16.6) (one snapshot's T
    // has spread 1/√300 = 6 %).
    assert!((measured / predicted - 1.0).abs() < 0.15, "{t:?}");
    let i = r.inelastic.as_ref().unwrap();
    assert!(i.energy.is_none() && i.haff.is_none(), "{i:?}");
    // What the thermostat took out is listed, with the thermostat as the reason.
    let why = |q: &str| {
        r.not_computed
            .iter()
            .find(|n| n.quantity == q)
            .map(|n| n.why.clone())
            .unwrap_or_else(|| panic!("{q} not listed: {:?}", r.not_computed))
    };
    for q in ["inelastic.energy", "inelastic.haff", "transport"] {
        assert!(why(q).contains("thermostat"), "{q}: {}", why(q));
    }
    std::fs::remove_file(&path).unwrap();

    let spec = example("thermostatted-fluid.json");
    let path = tmp("thermo-analyze-andersen.mcap");
    run(&spec, &path, Control::default()).unwrap();
    let (r, _) = analyze_log(&path, AnalysisOptions::default(), &mut Quiet).unwrap();
    let t = r.thermostat.as_ref().expect("a thermostat report");
    assert_eq!((t.kind, t.target_kt), ("andersen", Some(2.0)));
    assert!(r.transport.is_none());
    let transport = r.not_computed.iter().find(|n| n.quantity == "transport");
    assert!(
        transport.is_some_and(|n| n.why.contains("thermostat")),
        "{:?}",
        r.not_computed
    );
    std::fs::remove_file(&path).unwrap();

    // The same run without its thermostat: no report, and compact collisions.
    let spec = example_with("thermostatted-fluid.json", &["thermostat=null"]);
    assert_eq!(spec.log.collision_record(), CollisionDetail::Compact);
    run(&spec, &path, Control::default()).unwrap();
    let (r, _) = analyze_log(&path, AnalysisOptions::default(), &mut Quiet).unwrap();
    assert!(r.thermostat.is_none());
    std::fs::remove_file(&path).unwrap();
}
