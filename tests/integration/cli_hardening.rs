//! End-to-end tests of issue 33's hardening of the `carom` binary: signals from
//! `timeout`, a file size limit, and messages for wrong input (a byte-order mark,
//! negative or exponent-written options, a resume stop already passed, failed runs
//! and plots that leave no empty files behind).

use crate::cli_common::*;

use std::path::Path;
use std::process::{Command, Output, Stdio};

/// The exit code and standard error of a command expected to fail.
fn failed(out: &Output) -> (Option<i32>, String) {
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "{stderr}");
    (out.status.code(), stderr)
}

/// A small finished log `small.mcap` in `dir` (200 discs to t = 2).
fn small_log(dir: &Path) {
    ok(&carom(
        dir,
        &[
            "run",
            "--set",
            "species.0.count=200",
            "--set",
            "stop.duration=2",
            "--out",
            "small.mcap",
            "-q",
        ],
    ));
}

/// A configuration saved with a UTF-8 byte-order mark reads like one without.
#[test]
fn a_config_with_a_byte_order_mark_is_read() {
    let dir = scratch("bom");
    let config = r#"{"species": [{"count": 100}], "stop": {"duration": 1}}"#;
    std::fs::write(dir.join("bom.json"), format!("\u{feff}{config}")).unwrap();
    let out = carom(&dir, &["run", "bom.json", "--dry-run"]);
    ok(&out);
    let i = carom(&dir, &["run", "bom.json", "-q"]);
    ok(&i);
    assert_eq!(
        json_of(&carom(&dir, &["info", "bom.mcap", "--json"]))["complete"],
        true
    );
}

/// A negative or non-finite `--equilibrate` is refused naming the option and what
/// is allowed, like `--every`.
#[test]
fn a_negative_or_infinite_equilibration_time_is_refused() {
    let dir = scratch("equilibrate");
    small_log(&dir);
    for t in ["-1", "NaN", "inf"] {
        let out = carom(&dir, &["analyze", "small.mcap", "--equilibrate", t, "-q"]);
        let (code, stderr) = failed(&out);
        assert_eq!(code, Some(2), "{t}: {stderr}");
        assert!(
            stderr.contains(&format!("--equilibrate {}", t.parse::<f64>().unwrap()))
                && stderr.contains("finite time ≥ 0"),
            "{t}: {stderr}"
        );
    }
}

/// `resume --collisions` takes the forms a configuration takes (`1e3`), and refuses
/// a count the log has already passed, as `--until` refuses a time in the past.
#[test]
fn resume_collisions_take_exponents_and_refuse_a_count_already_passed() {
    let dir = scratch("resume-collisions");
    small_log(&dir);
    let out = carom(
        &dir,
        &[
            "resume",
            "small.mcap",
            "--collisions",
            "5",
            "--out",
            "back.mcap",
            "-q",
        ],
    );
    let (code, stderr) = failed(&out);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("stop.collisions") && stderr.contains("stop at 5 collisions is below"),
        "{stderr}"
    );
    assert!(!dir.join("back.mcap").exists());
    let i = json_of(&carom(&dir, &["info", "small.mcap", "--json"]));
    let done = i["summary"]["pair_collisions"].as_u64().unwrap()
        + i["summary"]["wall_collisions"].as_u64().unwrap();
    let target = format!("{:e}", (done + 1000) as f64);
    let more = [
        "resume",
        "small.mcap",
        "--collisions",
        &target,
        "--out",
        "more.mcap",
        "-q",
    ];
    ok(&carom(&dir, &more));
    let j = json_of(&carom(&dir, &["info", "more.mcap", "--json"]));
    assert_eq!(j["summary"]["stop_reason"], "collisions");
    let after = j["summary"]["pair_collisions"].as_u64().unwrap()
        + j["summary"]["wall_collisions"].as_u64().unwrap();
    assert_eq!(after, done + 1000);
    let bad = carom(&dir, &["resume", "small.mcap", "--collisions", "1.5"]);
    let (code, stderr) = failed(&bad);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("--collisions") && stderr.contains("whole number"),
        "{stderr}"
    );
}

/// Past a file size limit (`ulimit -f`, without the shell ignoring SIGXFSZ as the
/// test in cli.rs does) the run stops with the write error naming the file and the
/// system's reason, exit status 1, instead of being killed by SIGXFSZ (153).
#[cfg(unix)]
#[test]
fn a_file_size_limit_is_reported_not_fatal() {
    let dir = scratch("ulimit");
    let script = format!(
        "ulimit -f 200; exec '{BIN}' run --out big.mcap --quiet \
         --set species.0.count=2000 --set stop.duration=40"
    );
    let out = sh(&dir, &script);
    let (code, stderr) = failed(&out);
    assert_eq!(code, Some(1), "{:?}: {stderr}", out.status);
    assert!(stderr.contains("File too large"), "{stderr}");
    assert!(stderr.contains("big.mcap"), "{stderr}");
}

/// GNU `timeout` sends SIGTERM to carom and then to its process group, microseconds
/// apart: the second signal is the same stop, not a second Ctrl-C, and every log
/// is finished.
#[cfg(unix)]
#[test]
fn timeout_stops_the_run_cleanly_every_time() {
    let dir = scratch("timeout");
    for i in 0..6 {
        let log = format!("t{i}.mcap");
        let out = Command::new("timeout")
            .args([
                "0.4",
                BIN,
                "run",
                "--out",
                &log,
                "--quiet",
                "--ignore-disk-estimate",
            ])
            .args([
                "--set",
                "species.0.count=1000",
                "--set",
                "stop.duration=1e6",
            ])
            .current_dir(&dir)
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let (code, stderr) = failed(&out);
        assert_eq!(code, Some(124), "{i}: {stderr}");
        assert!(!stderr.contains("interrupted again"), "{i}: {stderr}");
        let info = json_of(&carom(&dir, &["info", &log, "--json"]));
        assert_eq!(info["complete"], true, "{i}: {stderr}");
        assert_eq!(info["summary"]["stop_reason"], "interrupted", "{i}");
    }
}

/// A run that fails before anything is written (here no room at all: `ulimit -f
/// 0`) leaves no empty log behind, so the next attempt needs no --force.
#[cfg(unix)]
#[test]
fn a_run_failing_before_writing_leaves_no_empty_log() {
    let dir = scratch("empty-log");
    let script = format!(
        "ulimit -f 0; exec '{BIN}' run --out none.mcap --quiet \
         --set species.0.count=100 --set stop.duration=1"
    );
    let out = sh(&dir, &script);
    let (code, stderr) = failed(&out);
    assert_eq!(code, Some(1), "{:?}: {stderr}", out.status);
    assert!(stderr.contains("none.mcap"), "{stderr}");
    assert!(!dir.join("none.mcap").exists(), "{stderr}");
    ok(&carom(
        &dir,
        &[
            "run",
            "--out",
            "none.mcap",
            "-q",
            "--set",
            "species.0.count=100",
            "--set",
            "stop.duration=1",
        ],
    ));
}

/// Resuming a finished log to its own stop simulates nothing: the summary keeps
/// the run's speed rather than 0 collisions/s.
#[test]
fn resuming_a_finished_log_keeps_its_speed() {
    let dir = scratch("resume-speed");
    small_log(&dir);
    let speed = |file: &str| {
        let i = json_of(&carom(&dir, &["info", file, "--json"]));
        i["summary"]["collisions_per_second"].as_f64().unwrap()
    };
    let before = speed("small.mcap");
    assert!(before > 0.0);
    ok(&carom(
        &dir,
        &["resume", "small.mcap", "--out", "again.mcap", "-q"],
    ));
    assert_eq!(speed("again.mcap"), before);
}

/// A figure that cannot be written (no room: `ulimit -f 0`) is named with the
/// system's reason, not Rust debug text, and leaves no empty file.
#[cfg(unix)]
#[test]
fn a_plot_that_cannot_be_written_says_why_and_leaves_no_empty_file() {
    let dir = scratch("plot-error");
    small_log(&dir);
    let script = format!("ulimit -f 0; exec '{BIN}' analyze small.mcap --plot figs -q");
    let out = sh(&dir, &script);
    let (code, stderr) = failed(&out);
    assert_eq!(code, Some(1), "{:?}: {stderr}", out.status);
    assert!(stderr.contains("File too large"), "{stderr}");
    assert!(stderr.contains(".png"), "{stderr}");
    assert!(
        !stderr.contains("Os {") && !stderr.contains("IOError"),
        "{stderr}"
    );
    for entry in std::fs::read_dir(dir.join("figs")).unwrap() {
        let path = entry.unwrap().path();
        assert!(
            std::fs::metadata(&path).unwrap().len() > 0,
            "{path:?} is empty"
        );
    }
}
