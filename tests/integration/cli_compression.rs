//! Compression runs (physics.md §17) and runs in a field (§15) through the binary:
//! the `/thermo` records of log format 2.2 (growth fields and the extra record at
//! each rescale and at the end of growth; U and K + U), `carom analyze` of a
//! compression log (the radii after growth, the window after it, the compression
//! report, refusal inside growth), and `carom resume` of a run killed or stopped
//! while its discs grow, message for message the uninterrupted run.

use crate::cli_common::*;

use carom_log::{GrowthEvent, GrowthPhase, LogMessage, LogReader, Snapshot, Thermo};
use serde_json::Value;
use std::path::Path;

/// 200 discs of σ = 1 from η₀ = 0.3 to 0.6 at γ = 0.01, rescaled every 1: growth
/// ends at t = (√2 − 1)/γ ≈ 41.42, then 58.6 time units at fixed size.
const GROW: &str = r#"{
  "species": [{ "count": 200, "radius": 0.5, "mass": 1.0 }],
  "box": { "packing_fraction": 0.3, "boundary": "periodic" },
  "temperature": 1.0,
  "seed": 3,
  "placement": "random",
  "compression": { "rate": 0.01, "target_packing_fraction": 0.6, "rescale_interval": 1.0, "max_reduced_pressure": 1000.0 },
  "stop": { "duration": 100.0 },
  "log": { "snapshot_interval": 2.0, "thermo_interval": 1.0, "checkpoint_interval": 10.0 }
}"#;

/// The 1 : 1.4 mixture (σ = 1, 1.4) compressed fast towards an unreachable η =
/// 0.9 with a low jamming bound Z > 100: growth stops at a rescale.
const JAM: &str = r#"{
  "species": [{ "count": 50, "radius": 0.5 }, { "count": 50, "radius": 0.7 }],
  "box": { "packing_fraction": 0.3, "boundary": "periodic" },
  "seed": 5,
  "placement": "random",
  "compression": { "rate": 0.05, "target_packing_fraction": 0.9, "rescale_interval": 0.5, "max_reduced_pressure": 100.0 },
  "stop": { "duration": 40.0 },
  "log": { "snapshot_interval": 1.0, "thermo_interval": 1.0 }
}"#;

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// Write `config` to `dir/name.json` and run it into `dir/name.mcap`.
fn run(dir: &Path, name: &str, config: &str, sets: &[&str]) {
    std::fs::write(dir.join(format!("{name}.json")), config).unwrap();
    let (cfg, out) = (format!("{name}.json"), format!("{name}.mcap"));
    let mut args = vec!["run", cfg.as_str(), "--out", out.as_str(), "--quiet"];
    for s in sets {
        args.extend(["--set", s]);
    }
    ok(&carom(dir, &args));
}

/// The `/thermo` records and snapshots of a log.
fn records(path: &Path) -> (Vec<Thermo>, Vec<Snapshot>) {
    let mut r = LogReader::open(path).unwrap();
    let (mut th, mut sn) = (Vec::new(), Vec::new());
    while let Some(m) = r.next_message().unwrap() {
        match m {
            LogMessage::Thermo(t) => th.push(t),
            LogMessage::Snapshot(s) => sn.push(s),
            _ => {}
        }
    }
    (th, sn)
}

/// Every message of a log: (channel, sequence, log time, bytes).
fn raw(path: &Path) -> Vec<(usize, u32, u64, Vec<u8>)> {
    let mut r = LogReader::open(path).unwrap();
    let mut v = Vec::new();
    while let Some(m) = r.next_raw().unwrap() {
        v.push((m.channel, m.sequence, m.log_time, m.data.to_vec()));
    }
    v
}

#[test]
fn a_compression_log_marks_each_rescale_and_is_analysed_at_its_final_size() {
    let dir = scratch("grow");
    run(&dir, "grow", GROW, &[]);
    let (th, _) = records(&dir.join("grow.mcap"));
    let end = (2f64.sqrt() - 1.0) / 0.01;
    // One extra record after each rescale k = 1..41, at or after k (the first
    // event after it) and before the next; then one at the end of growth.
    let marks: Vec<&Thermo> = th.iter().filter(|t| t.growth_event.is_some()).collect();
    assert_eq!(marks.len(), 42);
    for (k, t) in marks[..41].iter().enumerate() {
        let due = (k + 1) as f64;
        assert_eq!(t.growth_event, Some(GrowthEvent::Rescale));
        assert_eq!(t.growth, Some(GrowthPhase::Growing));
        assert!(
            t.time >= due && t.time < due + 0.05,
            "rescale {due} at {}",
            t.time
        );
        // Just after the rescale kT is the target but for the event's own change.
        assert!((t.temperature - 1.0).abs() < 0.05, "kT {}", t.temperature);
        assert!(t.growth_z.unwrap() > 1.0);
    }
    let last = marks[41];
    assert_eq!(last.growth_event, Some(GrowthEvent::End));
    assert_eq!(last.growth, Some(GrowthPhase::Target));
    assert!(last.time >= end && last.time < end + 0.05, "{}", last.time);
    assert_eq!(last.radius_scale, Some(2f64.sqrt()));
    assert!((last.packing_fraction.unwrap() - 0.6).abs() < 1e-12);
    // Every record of the run carries the growth; none the field's energies.
    for t in &th {
        let s = t.radius_scale.unwrap();
        let want = if t.time < end {
            1.0 + 0.01 * t.time
        } else {
            2f64.sqrt()
        };
        assert!((s - want).abs() < 1e-12, "s = {s} at {}", t.time);
        assert!(t.potential_energy.is_none() && t.total_energy.is_none());
    }

    let r = json_of(&carom(&dir, &["analyze", "grow.mcap", "--quiet", "--json"]));
    let c = &r["compression"];
    assert_eq!(c["ended"], "target", "{c}");
    assert_eq!(c["rescales"], 42, "{c}");
    assert_eq!(f(&c["start_packing_fraction"]), 0.3, "{c}");
    assert!((f(&c["final_packing_fraction"]) - 0.6).abs() < 1e-12, "{c}");
    assert_eq!(f(&c["end_time"]), last.time);
    // The report's η and radii are those after growth, its window after it.
    assert!((f(&r["packing_fraction"]) - 0.6).abs() < 1e-12);
    assert_eq!(f(&r["species"][0]["radius"]), 0.5 * 2f64.sqrt());
    let from = f(&r["window"]["equilibrate"]);
    assert_eq!(from, last.time + 0.1 * (100.0 - last.time));
    // g(σ⁺) is finite at the grown σ, and the contact theorem agrees with the
    // virial pressure (both measure the same Z: physics.md (10.3) against (5.3)).
    let pc = &r["pair_correlation"];
    assert_eq!(f(&pc["pairs"][0]["sigma"]), 2f64.sqrt());
    let g = f(&pc["pairs"][0]["contact"]["value"]);
    assert!(g.is_finite() && g > 2.0, "g(σ⁺) = {g}");
    let ct = &pc["contact_theorem"];
    let apart = f(&ct["difference_std_errors"]);
    assert!(apart.abs() < 3.0, "contact theorem vs virial: {ct}");
    assert!(f(&ct["z_virial"]) > 5.0, "{ct}");

    let text = ok(&carom(&dir, &["analyze", "grow.mcap", "--quiet"]));
    assert!(
        text.contains("  η                     0.3000 → 0.6000 (radii × 1.414214)")
            && text.contains("reached the target η = 0.6000"),
        "{text}"
    );
    assert!(text.contains("rescales              42 logged"), "{text}");
    // A window inside the growth is refused, naming the option and the end.
    let out = carom(
        &dir,
        &["analyze", "grow.mcap", "--quiet", "--equilibrate", "30"],
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--equilibrate 30") && err.contains("grow until t = 41.4"),
        "{err}"
    );
    ok(&carom(
        &dir,
        &["analyze", "grow.mcap", "--quiet", "--equilibrate", "50"],
    ));
}

#[test]
fn a_jammed_compression_is_reported_with_its_last_z() {
    let dir = scratch("jam");
    run(&dir, "jam", JAM, &[]);
    let r = json_of(&carom(&dir, &["analyze", "jam.mcap", "--quiet", "--json"]));
    let c = &r["compression"];
    assert_eq!(c["ended"], "jammed", "{c}");
    let z = f(&c["last_z"]);
    assert!(z > 100.0, "{c}");
    // Growth stops at a rescale k·0.5: after k rescales, s = 1 + 0.05·k/2.
    let k = c["rescales"].as_u64().unwrap();
    let s = f(&c["final_radius_scale"]);
    assert!((s - (1.0 + 0.025 * k as f64)).abs() < 1e-12, "{c}");
    let t = f(&c["end_time"]);
    assert!(t >= 0.5 * k as f64 && t < 0.5 * k as f64 + 0.05, "{c}");
    let eta = f(&c["final_packing_fraction"]);
    assert!((eta - 0.3 * s * s).abs() < 1e-12, "{c}");
    assert!(eta > 0.7 && eta < 0.9, "jammed at η = {eta}");
    let text = ok(&carom(&dir, &["analyze", "jam.mcap", "--quiet"]));
    assert!(
        text.contains("jammed: Z of the last interval above the bound 100"),
        "{text}"
    );

    // A log that ends while the discs still grow has no window at fixed size.
    run(&dir, "short", JAM, &["stop.duration=5"]);
    let out = carom(&dir, &["analyze", "short.mcap", "--quiet"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("grow until the end of the log"), "{err}");
}

#[test]
fn resume_while_the_discs_grow_continues_the_uninterrupted_run() {
    let dir = scratch("resume");
    run(&dir, "full", GROW, &[]);
    let expected = raw(&dir.join("full.mcap"));

    // Killed mid-growth: the log cut at a third, its last checkpoint at t < 41.
    let bytes = std::fs::read(dir.join("full.mcap")).unwrap();
    std::fs::write(dir.join("cut.mcap"), &bytes[..bytes.len() / 3]).unwrap();
    ok(&carom(
        &dir,
        &["resume", "cut.mcap", "--out", "resumed.mcap", "--quiet"],
    ));
    let i = json_of(&carom(&dir, &["info", "resumed.mcap", "--json"]));
    let at = f(&i["run"]["resumed_at"]);
    assert!(at > 0.0 && at < 41.0, "resumed at {at}");
    let got = raw(&dir.join("resumed.mcap"));
    assert_eq!(got.len(), expected.len());
    for (k, (a, b)) in got.iter().zip(&expected).enumerate() {
        assert!(a == b, "message {k} differs after the resume at {at}");
    }

    // Stopped mid-growth at t = 25, resumed to 100: every message after 25 but
    // the checkpoints (whose series differs: one more at 25) is the full run's.
    run(&dir, "part", GROW, &["stop.duration=25"]);
    let until = [
        "resume",
        "part.mcap",
        "--out",
        "more.mcap",
        "--until",
        "100",
    ];
    ok(&carom(&dir, &[&until[..], &["--quiet"]].concat()));
    let after = |v: Vec<(usize, u32, u64, Vec<u8>)>| -> Vec<_> {
        v.into_iter()
            .filter(|m| m.2 > 25_000_000_000 && m.0 != 3)
            .collect()
    };
    let (a, b) = (after(raw(&dir.join("more.mcap"))), after(expected));
    assert!(a.len() > 100, "{} messages after 25", a.len());
    assert_eq!(a.len(), b.len());
    for (k, (x, y)) in a.iter().zip(&b).enumerate() {
        assert!(x == y, "message {k} after t = 25 differs");
    }
}

#[test]
fn thermo_records_in_a_field_carry_u_and_k_plus_u() {
    let dir = scratch("field");
    let sets = [
        "species.0.count=60",
        "box.size=[200,60]",
        "box.boundary={\"x\":\"periodic\",\"y\":\"walls\"}",
        "gravity=0.1",
        "placement=\"random\"",
        "stop.duration=20",
        "log.snapshot_interval=1",
        "log.thermo_interval=1",
    ];
    let mut args = vec!["run", "--quiet", "--out", "g.mcap"];
    for s in &sets {
        args.extend(["--set", s]);
    }
    ok(&carom(&dir, &args));
    let (th, sn) = records(&dir.join("g.mcap"));
    assert_eq!(sn.len(), 21);
    for s in &sn {
        let t = th.iter().find(|t| t.time == s.time).expect("a record");
        // U = Σ m g y of the snapshot, summed in another order: rounding only.
        let u: f64 = s.positions.iter().map(|p| 1.0 * 0.1 * p.y).sum();
        let got = t.potential_energy.unwrap();
        assert!((got - u).abs() <= 1e-12 * u, "U = {got}, Σ m g y = {u}");
        assert_eq!(t.total_energy, Some(t.kinetic_energy + got));
        assert!(t.radius_scale.is_none() && t.growth.is_none());
    }
    // K + U is conserved to rounding (elastic walls and pairs, physics.md §15).
    let e: Vec<f64> = th.iter().map(|t| t.total_energy.unwrap()).collect();
    for x in &e {
        assert!((x - e[0]).abs() < 1e-9 * e[0], "K + U {x} against {}", e[0]);
    }
    let i = json_of(&carom(&dir, &["info", "g.mcap", "--json"]));
    let last = th.last().unwrap();
    assert_eq!(
        f(&i["summary"]["potential_energy"]),
        last.potential_energy.unwrap()
    );
    let text = ok(&carom(&dir, &["info", "g.mcap"]));
    assert!(text.contains("energy in the field: K = "), "{text}");
}
