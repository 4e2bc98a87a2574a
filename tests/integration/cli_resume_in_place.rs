//! A resume in place that fails part way (issue 33, item 5) removes its
//! `.resume-tmp`, leaves the input intact, and advises resuming the input.

use crate::cli_common::sh;

use std::path::Path;
use std::process::{Command, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_carom");

#[cfg(unix)]
#[test]
fn a_failed_resume_in_place_removes_its_temp_file_and_advises_the_input() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("resume-in-place-fails");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let run = Command::new(BIN)
        .args(["run", "--quiet", "--out", "live.mcap"])
        .args(["--set", "species.0.count=4000", "--set", "stop.duration=4"])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let log = dir.join("live.mcap");
    let before = std::fs::read(&log).unwrap();
    // A file size limit a little above the input's (in 512- or 1024-byte blocks,
    // as the shell counts them): the copy fits, the continuation to t = 60 not.
    let blocks = before.len() as u64 * 3 / 2 / 512;
    let script = format!(
        "trap '' XFSZ; ulimit -f {blocks}; exec '{BIN}' resume live.mcap --until 60 --quiet"
    );
    let out = sh(&dir, &script);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("File too large"), "{stderr}");
    assert!(stderr.contains("`carom resume live.mcap`"), "{stderr}");
    assert!(!stderr.contains("resume live.mcap.resume-tmp"), "{stderr}");
    assert!(!dir.join("live.mcap.resume-tmp").exists());
    assert_eq!(std::fs::read(&log).unwrap(), before, "the input changed");
}
