//! `carom sweep` and `carom collect` end to end, on this machine: a 2 × 2 sweep
//! (two packing fractions, two replicas) runs, is found finished by a second
//! sweep, and collects into a table whose numbers are those `carom analyze` gives
//! for each log, replicas combined by their spread; an interrupted sweep resumes
//! and ends bit for bit where an uninterrupted run ends; a failing point is
//! reported without stopping the others; bad plans are refused naming the field.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::cli_common::{carom, json_of, ok, python_with, scratch, BIN};
use carom_log::last_checkpoint;
use serde_json::Value;

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

const PLAN: &str = r#"{
  "base": {"species": [{"count": 100}], "stop": {"duration": 20},
           "log": {"snapshot_interval": 0.5}},
  "vary": {"box.packing_fraction": [0.2, 0.4]},
  "replicas": 2
}"#;

#[test]
fn a_two_by_two_sweep_runs_then_collects_what_analyze_says() {
    let dir = scratch("grid");
    write(&dir, "plan.json", PLAN);
    let dry = ok(&carom(
        &dir,
        &["sweep", "plan.json", "--out", "out", "--dry-run"],
    ));
    assert!(dry.contains("4 points"), "{dry}");
    assert!(!dir.join("out").exists(), "a dry run writes nothing");

    ok(&carom(
        &dir,
        &["sweep", "plan.json", "--out", "out", "--jobs", "2", "-q"],
    ));
    let names = [
        "packing_fraction=0.2,seed=1",
        "packing_fraction=0.2,seed=2",
        "packing_fraction=0.4,seed=1",
        "packing_fraction=0.4,seed=2",
    ];
    let status = json_of(&carom(&dir, &["sweep", "status", "out", "--json"]));
    let states: Vec<(&str, &str)> = status["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p["name"].as_str().unwrap(), p["state"].as_str().unwrap()))
        .collect();
    assert_eq!(
        states,
        names.iter().map(|n| (*n, "done")).collect::<Vec<_>>()
    );
    // Each point's log is the run of its own configuration: η and seed set.
    let cfg: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("out").join(names[3]).join("config.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(
        (
            cfg["box"]["packing_fraction"].as_f64(),
            cfg["seed"].as_u64()
        ),
        (Some(0.4), Some(2))
    );

    // A second sweep finds everything finished and rewrites no log.
    let log = dir.join("out").join(names[0]).join("run.mcap");
    let before = std::fs::metadata(&log).unwrap().modified().unwrap();
    let again = carom(&dir, &["sweep", "plan.json", "--out", "out"]);
    let text = String::from_utf8_lossy(&again.stderr);
    assert!(
        again.status.success() && text.matches("skipped").count() == 4,
        "{text}"
    );
    assert_eq!(std::fs::metadata(&log).unwrap().modified().unwrap(), before);

    // The table: each replica's Z is what `carom analyze` says of its log, and the
    // grid point's value is their mean with the standard error of their spread.
    let c = json_of(&carom(
        &dir,
        &["collect", "out", "--json", "--no-structure", "-q"],
    ));
    let points = c["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    for (g, p) in points.iter().enumerate() {
        assert_eq!(p["runs"].as_array().unwrap().len(), 2);
        let mut zs = Vec::new();
        for (r, run) in p["runs"].as_array().unwrap().iter().enumerate() {
            assert_eq!(run.as_str().unwrap(), names[2 * g + r]);
            let a = json_of(&carom(
                &dir,
                &[
                    "analyze",
                    &format!("out/{}/run.mcap", names[2 * g + r]),
                    "--json",
                    "--no-structure",
                    "-q",
                ],
            ));
            let z = a["pressure"]["z"].as_f64().unwrap();
            assert_eq!(p["replicas"][r]["Z"][0].as_f64().unwrap(), z);
            zs.push(z);
        }
        let z = &p["results"]["Z"];
        let mean = (zs[0] + zs[1]) / 2.0;
        assert!((z["value"].as_f64().unwrap() - mean).abs() <= 1e-12 * mean);
        let spread = (zs[0] - zs[1]).abs() / 2f64.sqrt();
        assert!((z["spread"].as_f64().unwrap() - spread).abs() <= 1e-12 * mean);
        assert!((z["std_error"].as_f64().unwrap() - spread / 2f64.sqrt()).abs() <= 1e-12 * mean);
    }
    // CSV: a header and one row per grid point; the figure of Z(η).
    let csv = ok(&carom(
        &dir,
        &[
            "collect",
            "out",
            "--csv",
            "--no-structure",
            "-q",
            "--plot",
            "figs",
        ],
    ));
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 3, "{csv}");
    assert!(
        lines[0].starts_with("box.packing_fraction,replicas,"),
        "{}",
        lines[0]
    );
    assert!(
        lines[1].starts_with("0.2,2,") && lines[2].starts_with("0.4,2,"),
        "{csv}"
    );
    assert!(dir.join("figs/equation_of_state.png").exists());
    assert!(dir.join("figs/equation_of_state.svg").exists());
    // Read back as a user would: Python's csv and pandas give the JSON's value in
    // every column (a header one column short once shifted every value).
    if let Some(py) = python_with(&["pandas"]) {
        let json = ok(&carom(
            &dir,
            &["collect", "out", "--json", "--no-structure", "-q"],
        ));
        write(&dir, "table.csv", &csv);
        write(&dir, "table.json", &json);
        let script =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/python/check_collect_csv.py");
        let out = Command::new(py)
            .arg(script)
            .args([dir.join("table.csv"), dir.join("table.json")])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

#[test]
fn an_interrupted_sweep_resumes_and_ends_where_an_uninterrupted_run_ends() {
    let dir = scratch("interrupted");
    write(
        &dir,
        "plan.json",
        r#"{"base": {"species": [{"count": 300}], "box": {"packing_fraction": 0.3},
                     "stop": {"duration": 10000},
                     "log": {"collisions": false, "snapshot_interval": 500}},
            "vary": {"temperature": [1, 2]}}"#,
    );
    let sweep = Command::new(BIN)
        .args(["sweep", "plan.json", "--out", "out", "--jobs", "2", "-q"])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let logs = ["temperature=1", "temperature=2"].map(|n| dir.join("out").join(n).join("run.mcap"));
    let start = Instant::now();
    while !logs.iter().all(|l| l.exists()) {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the points never started"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    // Each point runs for seconds (3.6·10⁶ collisions): stop them early on.
    std::thread::sleep(Duration::from_millis(300));
    Command::new("kill")
        .args(["-TERM", &sweep.id().to_string()])
        .status()
        .unwrap();
    let out = sweep.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    let status = json_of(&carom(&dir, &["sweep", "status", "out", "--json"]));
    for p in status["points"].as_array().unwrap() {
        assert_eq!(p["state"], "interrupted", "{status}");
    }

    ok(&carom(&dir, &["sweep", "plan.json", "--out", "out", "-q"]));
    let status = json_of(&carom(&dir, &["sweep", "status", "out", "--json"]));
    for p in status["points"].as_array().unwrap() {
        assert_eq!(p["state"], "done", "{status}");
    }
    // The resumed point ends exactly where its configuration run straight ends.
    ok(&carom(
        &dir,
        &[
            "run",
            "out/temperature=2/config.json",
            "-o",
            "straight.mcap",
            "-q",
        ],
    ));
    let (resumed, _, _) = last_checkpoint(&logs[1]).unwrap();
    let (straight, _, _) = last_checkpoint(&dir.join("straight.mcap")).unwrap();
    let (a, b) = (&resumed.engine, &straight.engine);
    assert_eq!(a.now, b.now);
    assert_eq!(a.positions, b.positions);
    assert_eq!(a.velocities, b.velocities);
    assert_eq!(a.stats.pair_collisions, b.stats.pair_collisions);
}

#[test]
fn a_failing_point_is_reported_and_the_others_finish() {
    let dir = scratch("failing");
    // 3·10⁹ discs pass the configuration's checks but not the run's memory check.
    write(
        &dir,
        "plan.json",
        r#"{"base": {"stop": {"duration": 5}},
            "vary": {"species.0.count": [50, 3000000000]}}"#,
    );
    let out = carom(&dir, &["sweep", "plan.json", "--out", "out", "--jobs", "2"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("FAILED   count=3000000000") && stderr.contains("memory"),
        "{stderr}"
    );
    let status = ok(&carom(&dir, &["sweep", "status", "out"]));
    assert!(status.contains("done        count=50"), "{status}");
    assert!(
        status.contains("failed      count=3000000000") && status.contains("memory"),
        "{status}"
    );
    // collect takes what finished and says what it left out.
    let c = carom(&dir, &["collect", "out", "--json", "--no-structure", "-q"]);
    let stderr = String::from_utf8_lossy(&c.stderr);
    assert!(
        stderr.contains("left out count=3000000000: not finished (failed)"),
        "{stderr}"
    );
    assert_eq!(json_of(&c)["points"].as_array().unwrap().len(), 1);
}

#[test]
fn bad_plans_and_directories_are_refused_with_the_field() {
    let dir = scratch("refusals");
    let cases = [
        (
            r#"{"base": {}, "vary": {"box.packing_fraction": [0.3, 0.95]}}"#,
            "packing_fraction=0.95",
        ),
        (
            r#"{"base": {}, "vary": {"temperature": {"from": 1, "to": 2}}}"#,
            "vary.temperature",
        ),
        (r#"{"base": "missing.json"}"#, "missing.json"),
        (r#"{"base": {}, "replicas": 0}"#, "replicas"),
        (
            r#"{"base": {}, "vary": {"no_such_field": [1]}}"#,
            "no_such_field",
        ),
    ];
    for (plan, field) in cases {
        write(&dir, "bad.json", plan);
        let out = carom(&dir, &["sweep", "bad.json", "--out", "o"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{plan}: {stderr}");
        assert!(stderr.contains(field), "{plan}: {stderr}");
    }
    // A directory holding another plan's sweep is not overwritten.
    write(
        &dir,
        "a.json",
        r#"{"base": {"species": [{"count": 30}], "stop": {"duration": 1}}}"#,
    );
    write(
        &dir,
        "b.json",
        r#"{"base": {"species": [{"count": 40}], "stop": {"duration": 1}}}"#,
    );
    ok(&carom(&dir, &["sweep", "a.json", "--out", "same", "-q"]));
    let out = carom(&dir, &["sweep", "b.json", "--out", "same", "-q"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && stderr.contains("another plan"),
        "{stderr}"
    );
    let out = carom(&dir, &["sweep", "status", "nowhere"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("holds no sweep"));
}
