//! Sweeps under hostile use (issue 51): a point's log that is not its run (copied
//! from another point, left by an unrelated run, or unreadable) is named, left out
//! of `collect` (which then fails) and moved aside — never overwritten — by the
//! next sweep; plans too large are refused before they are expanded; a point's
//! directory is made when it runs; `--jobs` never exceeds the cores; a sweep whose
//! output pipe closes finishes its points; points outlive a sweep killed with
//! SIGKILL and finish their logs; a second sweep into a running one's directory
//! is refused; point names that cannot be directories and replica seeds that
//! would wrap are refused by `--dry-run`.

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::cli_common::{carom, json_of, ok, scratch, BIN};
use serde_json::Value;

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

/// Each point's (name, state, detail), from `carom sweep status DIR --json`.
fn states(dir: &Path, out: &str) -> Vec<(String, String, String)> {
    try_states(dir, out).expect("a sweep directory")
}

/// [`states`], or `None` while the directory holds no sweep yet.
fn try_states(dir: &Path, out: &str) -> Option<Vec<(String, String, String)>> {
    let o = carom(dir, &["sweep", "status", out, "--json"]);
    if !o.status.success() {
        return None;
    }
    let s: Value = serde_json::from_slice(&o.stdout).unwrap();
    let points = s["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let text = |k: &str| p[k].as_str().unwrap_or_default().to_owned();
            (text("name"), text("state"), text("detail"))
        })
        .collect();
    Some(points)
}

/// Wait (up to two minutes) until `done` holds.
fn wait_for(what: &str, mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(start.elapsed() < Duration::from_secs(120), "never: {what}");
        std::thread::sleep(Duration::from_millis(50));
    }
}

fn spawn(dir: &Path, args: &[&str]) -> Child {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

fn kill(signal: &str, pid: u32) {
    Command::new("kill")
        .args([signal, &pid.to_string()])
        .status()
        .unwrap();
}

/// Points that each run for several seconds (3·10⁶ collisions).
const LONG: &str = r#"{"base": {"species": [{"count": 300}], "box": {"packing_fraction": 0.3},
                       "stop": {"duration": 3000},
                       "log": {"collisions": false, "snapshot_interval": 500}},
                       "vary": {"temperature": [1, 2]}}"#;

#[test]
fn a_log_that_is_not_the_points_run_is_named_left_out_and_moved_aside() {
    let dir = scratch("mismatch");
    write(
        &dir,
        "plan.json",
        r#"{"base": {"species": [{"count": 300}], "stop": {"duration": 20},
                     "log": {"snapshot_interval": 1}},
            "vary": {"box.packing_fraction": [0.3, 0.4, 0.5]}}"#,
    );
    ok(&carom(&dir, &["sweep", "plan.json", "--out", "out", "-q"]));
    let collected = json_of(&carom(
        &dir,
        &["collect", "out", "--json", "--no-structure", "-q"],
    ));
    let z_of = |c: &Value, eta: f64| {
        c["points"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["values"]["box.packing_fraction"] == eta)
            .map(|p| p["results"]["Z"]["value"].as_f64().unwrap())
    };
    let z04 = z_of(&collected, 0.4).unwrap();
    assert!(z_of(&collected, 0.3).unwrap() < z04);

    // The η = 0.4 log copied into η = 0.3; a run of 500 discs (the plan says
    // 300) into η = 0.5.
    let point = |eta: &str| dir.join(format!("out/packing_fraction={eta}"));
    std::fs::copy(point("0.4").join("run.mcap"), point("0.3").join("run.mcap")).unwrap();
    ok(&carom(
        &dir,
        &[
            "run",
            "--set",
            "species.0.count=500",
            "--set",
            "stop.duration=20",
            "--out",
            "other.mcap",
            "-q",
        ],
    ));
    std::fs::copy(dir.join("other.mcap"), point("0.5").join("run.mcap")).unwrap();

    let st = states(&dir, "out");
    assert_eq!(st[0].1, "mismatch", "{st:?}");
    assert!(st[0].2.contains("box.packing_fraction is 0.4"), "{st:?}");
    assert_eq!(st[1].1, "done", "{st:?}");
    assert_eq!(st[2].1, "mismatch", "{st:?}");
    assert!(st[2].2.contains("species.0.count is 500"), "{st:?}");

    let c = carom(&dir, &["collect", "out", "--json", "--no-structure", "-q"]);
    let stderr = String::from_utf8_lossy(&c.stderr);
    assert_eq!(c.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("left out packing_fraction=0.3: another run's log")
            && stderr.contains("left out packing_fraction=0.5: another run's log"),
        "{stderr}"
    );
    let c: Value = serde_json::from_slice(&c.stdout).unwrap();
    assert_eq!(c["points"].as_array().unwrap().len(), 1, "{c}");
    assert_eq!(z_of(&c, 0.4), Some(z04));
    assert_eq!(
        z_of(&c, 0.3),
        None,
        "the copied log is not counted for η = 0.3"
    );

    // A log that cannot be read is not overwritten either.
    let garbage = b"not a log at all".to_vec();
    std::fs::write(point("0.4").join("run.mcap"), &garbage).unwrap();
    assert_eq!(states(&dir, "out")[1].1, "unreadable");

    let before = [
        std::fs::read(point("0.3").join("run.mcap")).unwrap(),
        garbage,
        std::fs::read(point("0.5").join("run.mcap")).unwrap(),
    ];
    let again = carom(&dir, &["sweep", "plan.json", "--out", "out", "-q"]);
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(again.status.success(), "{stderr}");
    for (eta, old) in ["0.3", "0.4", "0.5"].iter().zip(&before) {
        let aside = point(eta).join("run.set-aside-1.mcap");
        assert!(
            stderr.contains(&format!("moved it aside to {}", aside.display())),
            "{stderr}"
        );
        assert_eq!(&std::fs::read(&aside).unwrap(), old, "{eta}");
    }
    for (name, state, _) in states(&dir, "out") {
        assert_eq!(state, "done", "{name}");
    }
    let c = json_of(&carom(
        &dir,
        &["collect", "out", "--json", "--no-structure", "-q"],
    ));
    assert_eq!(c["points"].as_array().unwrap().len(), 3);
    assert_eq!(z_of(&c, 0.4), Some(z04), "the re-run point is the same run");
}

#[test]
fn plans_too_large_are_refused_before_they_are_expanded() {
    let dir = scratch("too-large");
    let base = r#"{"species": [{"count": 20}], "stop": {"duration": 1}}"#;
    let plans = [
        (
            format!(r#"{{"base": {base}, "replicas": 1000000000}}"#),
            "1000000000 points",
        ),
        (
            format!(
                r#"{{"base": {base}, "vary": {{
                   "temperature": {{"from": 1, "to": 2, "count": 100000}},
                   "box.packing_fraction": {{"from": 0.1, "to": 0.2, "count": 100000}}}}}}"#
            ),
            "10000000000 points",
        ),
    ];
    for (plan, count) in plans {
        write(&dir, "big.json", &plan);
        for dry in [true, false] {
            let mut args = vec!["sweep", "big.json", "--out", "out"];
            if dry {
                args.push("--dry-run");
            }
            let out = carom(&dir, &args);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{stderr}");
            assert!(
                stderr.contains(count) && stderr.contains("more than the 100000"),
                "{stderr}"
            );
            assert!(!dir.join("out").exists());
        }
    }
}

#[test]
fn a_points_directory_is_made_when_the_point_runs() {
    let dir = scratch("lazy-dirs");
    // 10⁴ points, one at a time; the first runs for seconds.
    write(
        &dir,
        "plan.json",
        r#"{"base": {"species": [{"count": 300}], "box": {"packing_fraction": 0.3},
                     "stop": {"duration": 3000},
                     "log": {"collisions": false, "snapshot_interval": 500}},
            "replicas": 10000}"#,
    );
    let sweep = spawn(
        &dir,
        &["sweep", "plan.json", "--out", "out", "--jobs", "1", "-q"],
    );
    let first = dir.join("out/seed=1/run.mcap");
    wait_for("the first point started", || first.exists());
    let dirs = std::fs::read_dir(dir.join("out"))
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().is_dir())
        .count();
    kill("-TERM", sweep.id());
    let out = sweep.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130));
    assert_eq!(dirs, 1, "only the running point has its directory");
}

#[test]
fn jobs_are_capped_at_the_cores() {
    let dir = scratch("jobs");
    write(
        &dir,
        "plan.json",
        r#"{"base": {"species": [{"count": 100}], "stop": {"duration": 20}},
            "vary": {"box.packing_fraction": [0.2, 0.3, 0.4]}}"#,
    );
    let cores = std::thread::available_parallelism().unwrap().get();
    let out = carom(
        &dir,
        &["sweep", "plan.json", "--out", "out", "--jobs", "1000"],
    );
    ok(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!("--jobs 1000: capped at the {cores} core"))
            && stderr.contains(&format!("with {cores} at a time")),
        "{stderr}"
    );
    // collect: the threads of the process, sampled while it runs, never exceed
    // the cores by more than the few threads of its own (1,007 before).
    let mut c = spawn(&dir, &["collect", "out", "--jobs", "1000", "-q"]);
    let status = format!("/proc/{}/status", c.id());
    let mut most = 0;
    while c.try_wait().unwrap().is_none() {
        if let Ok(s) = std::fs::read_to_string(&status) {
            if let Some(n) = s
                .lines()
                .find_map(|l| l.strip_prefix("Threads:"))
                .and_then(|n| n.trim().parse::<usize>().ok())
            {
                most = most.max(n);
            }
        }
    }
    let out = c.wait_with_output().unwrap();
    ok(&out);
    assert!(most <= cores + 8, "{most} threads on {cores} cores");
    assert!(String::from_utf8_lossy(&out.stderr)
        .contains(&format!("--jobs 1000: capped at the {cores} core")));
}

#[test]
fn a_sweep_whose_output_pipe_closes_finishes_its_points() {
    let dir = scratch("pipe");
    write(
        &dir,
        "plan.json",
        r#"{"base": {"species": [{"count": 200}], "stop": {"duration": 30}},
            "vary": {"box.packing_fraction": [0.2, 0.3, 0.4]}}"#,
    );
    let out = Command::new("bash")
        .args([
            "-c",
            &format!(
                "'{BIN}' sweep plan.json --out out 2>&1 | head -2 >/dev/null; \
                 echo \"${{PIPESTATUS[0]}}\""
            ),
        ])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), "0");
    for (name, state, detail) in states(&dir, "out") {
        assert_eq!(state, "done", "{name}: {detail}");
    }
}

#[test]
fn points_outlive_a_killed_sweep_and_finish_their_logs() {
    let dir = scratch("killed-parent");
    // Long enough (≈ 8 s) that each point prints progress (every 5 s) after the
    // sweep is gone: it used to die of that write, its log cut short.
    write(&dir, "plan.json", &LONG.replace("3000", "15000"));
    let sweep = spawn(&dir, &["sweep", "plan.json", "--out", "out", "-q"]);
    wait_for("both points running", || {
        try_states(&dir, "out").is_some_and(|s| s.iter().all(|s| s.1 == "running"))
    });
    kill("-KILL", sweep.id());
    let out = sweep.wait_with_output().unwrap();
    assert_eq!(out.status.code(), None, "killed");
    // A sweep started now leaves the running points to themselves.
    let again = carom(&dir, &["sweep", "plan.json", "--out", "out"]);
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(
        stderr.contains("skipped  temperature=1 (running)"),
        "{stderr}"
    );
    wait_for("both points ended", || {
        states(&dir, "out").iter().all(|s| s.1 != "running")
    });
    for (name, state, detail) in states(&dir, "out") {
        assert_eq!(state, "done", "{name}: {detail}");
        // What the point printed after the sweep died is in its carom.log.
        let log = std::fs::read_to_string(dir.join("out").join(&name).join("carom.log")).unwrap();
        assert!(log.contains("stopped (time) at t = 15000"), "{log}");
    }
}

#[test]
fn a_second_sweep_into_a_running_ones_directory_is_refused() {
    let dir = scratch("two-sweeps");
    write(&dir, "plan.json", LONG);
    // Started at the same moment: one runs (for seconds), the other is refused.
    let mut sweeps = vec![
        spawn(&dir, &["sweep", "plan.json", "--out", "out", "-q"]),
        spawn(&dir, &["sweep", "plan.json", "--out", "out", "-q"]),
    ];
    let mut ended = None;
    wait_for("one sweep ended", || {
        ended = sweeps
            .iter_mut()
            .position(|c| c.try_wait().unwrap().is_some());
        ended.is_some()
    });
    let refused = sweeps.remove(ended.unwrap()).wait_with_output().unwrap();
    let running = sweeps.pop().unwrap();
    wait_for("the other sweep's points running", || {
        try_states(&dir, "out").is_some_and(|s| s.iter().all(|s| s.1 == "running"))
    });
    kill("-TERM", running.id());
    let running = running.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert_eq!(refused.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("another sweep is running in this directory")
            && !stderr.contains("No such file"),
        "{stderr}"
    );
    assert_eq!(
        running.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&running.stderr)
    );
    // Its points were stopped cleanly and resume.
    for (name, state, _) in states(&dir, "out") {
        assert_eq!(state, "interrupted", "{name}");
    }
}

#[test]
fn names_that_cannot_be_directories_and_wrapping_seeds_are_refused_by_a_dry_run() {
    let dir = scratch("names-seeds");
    let base = r#"{"species": [{"count": 20}], "stop": {"duration": 1}}"#;
    let long = "a".repeat(300);
    let cases = [
        (
            format!(r#"{{"base": {base}, "vary": {{"description": ["{long}"]}}}}"#),
            "more than the 255",
        ),
        (
            format!(r#"{{"base": {base}, "vary": {{"description": ["a\u0000b"]}}}}"#),
            "U+0000",
        ),
        (
            format!(r#"{{"base": {base}, "replicas": 2, "seed": 18446744073709551615}}"#),
            "seed: 18446744073709551615 with 2 replicas",
        ),
    ];
    for (plan, why) in cases {
        write(&dir, "bad.json", &plan);
        for dry in [true, false] {
            let mut args = vec!["sweep", "bad.json", "--out", "out", "-q"];
            if dry {
                args.push("--dry-run");
            }
            let out = carom(&dir, &args);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{plan}: {stderr}");
            assert!(stderr.contains(why), "{stderr}");
            assert!(!dir.join("out").exists(), "nothing is laid out");
        }
    }
    // The corrected plan runs in the same directory.
    write(
        &dir,
        "good.json",
        &format!(r#"{{"base": {base}, "vary": {{"description": ["short"]}}}}"#),
    );
    ok(&carom(&dir, &["sweep", "good.json", "--out", "out", "-q"]));
    assert_eq!(states(&dir, "out")[0].1, "done");
}
