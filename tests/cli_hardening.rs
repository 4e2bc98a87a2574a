//! End-to-end tests of issue 33's hardening of the `carom` binary: signals from
//! `timeout`, a file size limit, and messages for wrong input (a byte-order mark,
//! negative or exponent-written options, a resume stop already passed, failed runs
//! and plots that leave no empty files behind).

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_carom");

/// A fresh directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("hardening-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn carom(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .output()
        .unwrap()
}

fn ok(out: &Output) -> String {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "exit {:?}: {stderr}", out.status);
    assert!(!stderr.contains("panicked"), "{stderr}");
    String::from_utf8(out.stdout.clone()).unwrap()
}

fn json_of(out: &Output) -> Value {
    serde_json::from_str(&ok(out)).unwrap()
}

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
