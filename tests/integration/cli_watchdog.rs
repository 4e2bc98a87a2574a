//! Runs that could never reach their stop (issue 33, item 4): discs that no longer
//! meet stop with `no_collision` and a finished log once no collision came within
//! `stop.max_time_without_collision` (or its default with a collision stop), and a
//! collision stop that would write more than 10⁹ records at the expected collision
//! rate is refused before anything is written.

use crate::cli_common::*;

use std::path::Path;
use std::process::Output;

/// The exit code and standard error of a command expected to fail.
fn failed(out: &Output) -> (Option<i32>, String) {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "{stderr}");
    (out.status.code(), stderr)
}

/// Four discs in a row moving together: they never meet.
fn write_convoy(dir: &Path, stop: &str) {
    let config = format!(
        r#"{{"species": [{{"count": 4}}], "box": {{"size": [20, 20]}},
            "placement": {{"explicit": [[2, 2], [2, 6], [2, 10], [2, 14]]}},
            "velocities": {{"explicit": [[1, 0], [1, 0], [1, 0], [1, 0]]}},
            "stop": {stop}}}"#
    );
    std::fs::write(dir.join("convoy.json"), config).unwrap();
}

/// The `carom.summary` of a finished log, which `info` must find complete.
fn summary(dir: &Path, log: &str) -> serde_json::Value {
    let info = json_of(&carom(dir, &["info", log, "--json", "--verify"]));
    assert_eq!(info["complete"], true, "{info}");
    info["summary"].clone()
}

#[test]
fn discs_moving_together_stop_a_collision_run_with_a_finished_log() {
    let dir = scratch("convoy");
    write_convoy(&dir, r#"{"collisions": 10}"#);
    let out = carom(&dir, &["run", "convoy.json", "-q"]);
    let (code, stderr) = failed(&out);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("no collision since t = 0"), "{stderr}");
    assert!(
        stderr.contains("stop.max_time_without_collision"),
        "{stderr}"
    );
    let s = summary(&dir, "convoy.mcap");
    assert_eq!(s["stop_reason"], "no_collision", "{s}");
    assert_eq!(s["pair_collisions"], 0);
    // The default bound: 100 mean free times at this density and temperature,
    // t_free = 1 / (2 σ n g √(πkT/m)) with n = 3/400 partners per area, kT = 2/3
    // (f = 2N − 2) and Henderson's g at η = π/400 (physics.md (7.9), (7.10)).
    let eta = std::f64::consts::PI / 400.0;
    let g = (1.0 - 7.0 * eta / 16.0) / (1.0 - eta).powi(2);
    let omega = 2.0 * (3.0 / 400.0) * g * (std::f64::consts::PI * 2.0 / 3.0).sqrt();
    let t_end = s["sim_time"].as_f64().unwrap();
    assert!(
        (t_end * omega / 100.0 - 1.0).abs() < 1e-9,
        "stopped at {t_end}"
    );
}

#[test]
fn a_user_bound_stops_a_timed_run_of_discs_that_never_meet_at_exactly_the_bound() {
    let dir = scratch("bound");
    write_convoy(
        &dir,
        r#"{"duration": 100, "max_time_without_collision": 7.5}"#,
    );
    let (code, stderr) = failed(&carom(&dir, &["run", "convoy.json", "-q"]));
    assert_eq!(code, Some(1), "{stderr}");
    let s = summary(&dir, "convoy.mcap");
    assert_eq!(s["stop_reason"], "no_collision");
    assert_eq!(s["sim_time"], 7.5);
    // Without the bound the same run reaches its stop time (no watchdog on a
    // time stop by default).
    write_convoy(&dir, r#"{"duration": 10}"#);
    ok(&carom(&dir, &["run", "convoy.json", "-q", "--force"]));
    assert_eq!(summary(&dir, "convoy.mcap")["stop_reason"], "time");
}

#[test]
fn colliding_discs_keep_running_past_the_bound() {
    // Once started from its lattice, this fluid collides every ~10⁻³ time
    // units: a bound of 0.3 never fires, though the run lasts 20 bounds.
    let dir = scratch("fluid");
    ok(&carom(
        &dir,
        &[
            "run",
            "--set",
            "species.0.count=400",
            "--set",
            "stop.duration=6",
            "--set",
            "stop.max_time_without_collision=0.3",
            "--out",
            "fluid.mcap",
            "-q",
        ],
    ));
    assert_eq!(summary(&dir, "fluid.mcap")["stop_reason"], "time");
}

#[test]
fn a_collision_stop_out_of_reach_of_a_dilute_gas_is_refused_up_front() {
    // At η = 10⁻¹² the first collision of 10⁴ discs is ~4·10⁷ time units away.
    let dir = scratch("dilute");
    let out = carom(
        &dir,
        &[
            "run",
            "--set",
            "box.packing_fraction=1e-12",
            "--set",
            "stop.collisions=1e6",
            "--out",
            "dilute.mcap",
        ],
    );
    let (code, stderr) = failed(&out);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("stop.collisions"), "{stderr}");
    assert!(
        stderr.contains("snapshots at log.snapshot_interval = 1"),
        "{stderr}"
    );
    assert!(stderr.contains("allowed: at most 1e9 records"), "{stderr}");
    assert!(
        !dir.join("dilute.mcap").exists(),
        "a refused run leaves no log"
    );
    // With the records in reach, a user bound ends the same gas at once.
    let out = carom(
        &dir,
        &[
            "run",
            "--set",
            "box.packing_fraction=1e-12",
            "--set",
            "stop.collisions=1",
            "--set",
            "log.thermo_interval=null",
            "--set",
            "stop.max_time_without_collision=5",
            "--out",
            "dilute.mcap",
            "-q",
        ],
    );
    assert_eq!(failed(&out).0, Some(1));
    let s = summary(&dir, "dilute.mcap");
    assert_eq!(
        (s["stop_reason"].as_str(), s["sim_time"].as_f64()),
        (Some("no_collision"), Some(5.0))
    );
}
