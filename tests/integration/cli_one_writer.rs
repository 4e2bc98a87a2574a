//! One writer per log (issue 33, item 3): while a process holds the lock on a
//! log, `carom run --force` and `carom resume` of it are refused at once, name
//! the holder, and leave the log as it was.

use crate::cli_common::*;

use std::fs::File;
use std::process::Output;

const SMALL: [&str; 4] = ["--set", "species.0.count=64", "--set", "stop.duration=2"];

#[test]
fn a_second_writer_is_refused_and_the_first_log_is_intact() {
    let dir = scratch("refused");
    let run = |extra: &[&str]| {
        let mut args = vec!["run", "--quiet", "--out", "s.mcap"];
        args.extend(SMALL);
        args.extend(extra);
        carom(&dir, &args)
    };
    assert!(run(&[]).status.success());
    let log = dir.join("s.mcap");
    let before = std::fs::read(&log).unwrap();
    // This test process is the first writer: it holds the lock as a run would.
    let held = File::options().read(true).write(true).open(&log).unwrap();
    held.try_lock().unwrap();
    let refused = |out: &Output, what: &str| {
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{what}: {stderr}");
        assert!(
            stderr.contains("s.mcap is being written by"),
            "{what}: {stderr}"
        );
        #[cfg(target_os = "linux")]
        assert!(
            stderr.contains(&format!("process {}", std::process::id())),
            "{what}: {stderr}"
        );
        assert_eq!(
            std::fs::read(&log).unwrap(),
            before,
            "{what} changed the log"
        );
    };
    refused(&run(&["--force"]), "run --force");
    refused(&carom(&dir, &["resume", "--quiet", "s.mcap"]), "resume");
    refused(
        &carom(&dir, &["resume", "--quiet", "s.mcap", "--out", "t.mcap"]),
        "resume --out",
    );
    assert!(!dir.join("t.mcap").exists());
    assert!(!dir.join("s.mcap.resume-tmp").exists());
    // A resume writing over the locked log is refused too.
    std::fs::copy(&log, dir.join("u.mcap")).unwrap();
    refused(
        &carom(
            &dir,
            &["resume", "--quiet", "u.mcap", "--out", "s.mcap", "--force"],
        ),
        "resume --out onto it",
    );
    drop(held);
    assert!(run(&["--force"]).status.success());
}
