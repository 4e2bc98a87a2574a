//! Issue 51, faults 6, 10, 11 and four small ones of 14, reproduced as a hostile
//! user met them: standard error or output that cannot be written (`2>/dev/full`,
//! a pipe whose reader has gone), a small disk (a 16 MB tmpfs), an address-space
//! limit (`ulimit -v`), f64s of hundreds of digits in error messages, a
//! configuration read from /dev/zero, and `export --out /dev/null`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

use crate::cli_common::{carom, json_of, ok, scratch, sh, BIN};

/// The exit code and standard error of a finished command.
fn code_and_stderr(out: &Output) -> (Option<i32>, String) {
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `carom info --verify --json` of `log`, which must succeed.
fn verified(dir: &Path, log: &str) -> serde_json::Value {
    let info = json_of(&carom(dir, &["info", "--verify", "--json", log]));
    assert_eq!(info["complete"], true, "{info}");
    info
}

/// A small finished log `small.mcap` in `dir` (500 discs, t = 5).
fn small_log(dir: &Path) {
    ok(&carom(
        dir,
        &[
            "run",
            "--out",
            "small.mcap",
            "-q",
            "--set",
            "species.0.count=500",
            "--set",
            "stop.duration=5",
        ],
    ));
}

/// Fault 6: standard error on a full disk. The run's progress, warning and
/// closing lines cannot be written: they are dropped, and the run finishes with
/// its log and the exit status of a normal run (before: a panic, status 101).
#[cfg(target_os = "linux")]
#[test]
fn a_run_whose_standard_error_is_full_finishes_its_log() {
    let dir = scratch("stderr-full");
    let out = sh(
        &dir,
        &format!("exec '{BIN}' run --out s.mcap --set stop.duration=5 2>/dev/full"),
    );
    assert_eq!(out.status.code(), Some(0), "{:?}", out.status);
    let info = verified(&dir, "s.mcap");
    assert_eq!(info["summary"]["stop_reason"], "time", "{info}");
    // An error that cannot be printed still gives the error's exit status.
    let out = sh(
        &dir,
        &format!("exec '{BIN}' run --out t.mcap --set stop.duration=-1 2>/dev/full"),
    );
    assert_eq!(out.status.code(), Some(2), "{:?}", out.status);
}

/// Fault 6: standard error into a pipe whose reader has gone (`2>&1 | head`): the
/// run finishes its log, exit 0.
#[test]
fn a_run_whose_standard_error_reader_has_gone_finishes_its_log() {
    let dir = scratch("stderr-pipe");
    let mut child = Command::new(BIN)
        .args(["run", "--out", "p.mcap", "--set", "stop.duration=5"])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The reader goes before the first line is written.
    drop(child.stderr.take());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(0), "{status:?}");
    let info = verified(&dir, "p.mcap");
    assert_eq!(info["summary"]["stop_reason"], "time", "{info}");
}

/// Fault 6: standard output into a pipe whose reader has gone (`carom info x |
/// head`): the output ends quietly, no panic, exit 0.
#[test]
fn output_into_a_closed_pipe_ends_quietly() {
    let dir = scratch("stdout-pipe");
    small_log(&dir);
    for args in [
        &["info", "small.mcap"][..],
        &["analyze", "small.mcap", "-q", "--no-structure"],
        &["run", "--dry-run"],
    ] {
        let mut child = Command::new(BIN)
            .args(args)
            .current_dir(&dir)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let (code, stderr) = code_and_stderr(&out);
        assert_eq!(code, Some(0), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}

/// Fault 11: under `ulimit -v` a run larger than the address space allows is
/// refused at the start, naming the limit, with no log left behind (before: the
/// memory check saw only /proc/meminfo and the cgroup, and the run aborted with
/// status 134 and a 0-byte log). 3·10⁶ discs need about 1.7 GB; the limit is
/// 1 GB, below the memory of any machine that runs the tests.
#[cfg(target_os = "linux")]
#[test]
fn a_run_larger_than_the_address_space_limit_is_refused_naming_it() {
    let dir = scratch("ulimit-v");
    let out = sh(
        &dir,
        &format!(
            "ulimit -v 1000000; exec '{BIN}' run --out big.mcap -q \
             --set species.0.count=3e6 --set stop.duration=1"
        ),
    );
    let (code, stderr) = code_and_stderr(&out);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("species.0.count"), "{stderr}");
    assert!(stderr.contains("ulimit -v"), "{stderr}");
    assert!(!dir.join("big.mcap").exists());
    // A run that fits runs under the same limit.
    let out = sh(
        &dir,
        &format!("ulimit -v 1000000; exec '{BIN}' run --out fits.mcap -q --set stop.duration=1"),
    );
    ok(&out);
}

/// A tmpfs of `size` mounted on `dir` for the life of the value.
struct Tmpfs(PathBuf);

impl Tmpfs {
    /// Mount one, or say why not (then the caller skips its test, with the reason
    /// printed).
    fn mount(dir: &Path, size: &str) -> Result<Tmpfs, String> {
        std::fs::create_dir_all(dir).unwrap();
        let out = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
            .arg(dir)
            .output()
            .map_err(|e| format!("cannot run mount: {e}"))?;
        if !out.status.success() {
            return Err(format!(
                "mount -t tmpfs failed: {}",
                String::from_utf8_lossy(&out.stderr)
            ));
        }
        Ok(Tmpfs(dir.to_path_buf()))
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
    }
}

/// Fault 10: on disks of 4 to 16 MB a run of 2000 discs logging every collision
/// (about 25 MB/s, more than such a disk holds between two looks at the clock's
/// pace) stops with `disk_full` and a complete log (before: "No space left on
/// device" and a log cut at its last flush, depending on the timing).
#[cfg(target_os = "linux")]
#[test]
fn a_run_on_a_small_disk_stops_with_a_complete_log() {
    let dir = scratch("small-disk");
    for size in ["4m", "8m", "12m", "16m"] {
        let disk = dir.join(size);
        let _mounted = match Tmpfs::mount(&disk, size) {
            Ok(m) => m,
            Err(why) => {
                eprintln!("skipped: no tmpfs to fill ({why})");
                return;
            }
        };
        let out = carom(
            &disk,
            &[
                "run",
                "--out",
                "r.mcap",
                "-q",
                "--set",
                "species.0.count=2000",
                "--set",
                "stop.duration=1000",
            ],
        );
        let (code, stderr) = code_and_stderr(&out);
        assert_eq!(code, Some(1), "{size}: {stderr}");
        assert!(stderr.contains("disk_full"), "{size}: {stderr}");
        assert!(!stderr.contains("No space left"), "{size}: {stderr}");
        let info = verified(&disk, "r.mcap");
        assert_eq!(
            info["summary"]["stop_reason"], "disk_full",
            "{size}: {info}"
        );
    }
}

/// Fault 10: an in-place resume on a disk with room for the copy of the log but
/// not for finishing it is refused before writing anything, the log unchanged
/// (before: it ran out of room, lost the resumed part and said wrongly that the
/// log was "readable up to its last flush"); with room to spare it runs until
/// the disk is nearly full and replaces the log with a longer, complete one.
#[cfg(target_os = "linux")]
#[test]
fn a_resume_in_place_on_a_small_disk_is_refused_or_finishes() {
    let dir = scratch("small-disk-resume");
    ok(&carom(
        &dir,
        &[
            "run",
            "--out",
            "r0.mcap",
            "-q",
            "--set",
            "species.0.count=2000",
            "--set",
            "stop.duration=10",
        ],
    ));
    let original = std::fs::read(dir.join("r0.mcap")).unwrap();
    // 3 MB of log: a 7 MB disk holds its copy, not the copy and the reserve.
    let tight = dir.join("tight");
    let _m = match Tmpfs::mount(&tight, "7m") {
        Ok(m) => m,
        Err(why) => {
            eprintln!("skipped: no tmpfs to fill ({why})");
            return;
        }
    };
    std::fs::write(tight.join("r.mcap"), &original).unwrap();
    let out = carom(&tight, &["resume", "r.mcap", "--until", "1000", "-q"]);
    let (code, stderr) = code_and_stderr(&out);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("cannot resume into r.mcap"), "{stderr}");
    assert!(
        !stderr.contains("readable up to its last flush"),
        "{stderr}"
    );
    assert_eq!(std::fs::read(tight.join("r.mcap")).unwrap(), original);
    assert!(!tight.join("r.mcap.resume-tmp").exists());
    // A 16 MB disk: the resume runs on and stops with disk_full, complete.
    let roomy = dir.join("roomy");
    let _m = Tmpfs::mount(&roomy, "16m").unwrap();
    std::fs::write(roomy.join("r.mcap"), &original).unwrap();
    let out = carom(&roomy, &["resume", "r.mcap", "--until", "1000", "-q"]);
    let (code, stderr) = code_and_stderr(&out);
    assert_eq!(code, Some(1), "{stderr}");
    let info = verified(&roomy, "r.mcap");
    assert_eq!(info["summary"]["stop_reason"], "disk_full", "{info}");
    assert!(
        info["summary"]["sim_time"].as_f64().unwrap() > 10.0,
        "{info}"
    );
    assert!(!roomy.join("r.mcap.resume-tmp").exists());
}

/// Fault 10: a resume in place whose writing fails part way (here past a file
/// size limit) says what is true: the continuation is lost and the log is as it
/// was, not "readable up to its last flush".
#[cfg(unix)]
#[test]
fn a_resume_in_place_cut_short_says_the_log_is_as_it_was() {
    let dir = scratch("resume-cut");
    ok(&carom(
        &dir,
        &[
            "run",
            "--out",
            "r.mcap",
            "-q",
            "--set",
            "species.0.count=2000",
            "--set",
            "stop.duration=10",
        ],
    ));
    let original = std::fs::read(dir.join("r.mcap")).unwrap();
    // Room (in 512-byte blocks) for the copy and a little more.
    let blocks = original.len() * 3 / 2 / 512;
    let out = sh(
        &dir,
        &format!("ulimit -f {blocks}; exec '{BIN}' resume r.mcap --until 1000 -q"),
    );
    let (code, stderr) = code_and_stderr(&out);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("File too large"), "{stderr}");
    assert!(
        stderr.contains("its continuation is lost, and r.mcap is as it was"),
        "{stderr}"
    );
    assert!(
        !stderr.contains("readable up to its last flush"),
        "{stderr}"
    );
    assert_eq!(std::fs::read(dir.join("r.mcap")).unwrap(), original);
    assert!(!dir.join("r.mcap.resume-tmp").exists());
}

/// Fault 14: an f64 that an error message prints in full (1e308 is 309 digits)
/// is written in scientific notation.
#[test]
fn huge_and_tiny_numbers_in_errors_are_written_compactly() {
    let dir = scratch("numbers");
    small_log(&dir);
    for args in [
        &["run", "--dry-run", "--set", "stop.duration=1e308"][..],
        &["run", "--dry-run", "--set", "stop.duration=-1e308"],
        &["run", "--dry-run", "--set", "log.thermo_interval=1e-300"],
        &["render", "small.mcap", "--time", "1e308", "-o", "x.png"],
    ] {
        let (code, stderr) = code_and_stderr(&carom(&dir, args));
        assert_eq!(code, Some(2), "{args:?}: {stderr}");
        let longest = stderr
            .split(|c: char| !c.is_ascii_digit())
            .map(str::len)
            .max()
            .unwrap_or(0);
        assert!(
            longest <= 20,
            "{args:?}: a number of {longest} digits: {stderr}"
        );
        assert!(
            stderr.contains("e308") || stderr.contains("e-300"),
            "{args:?}: {stderr}"
        );
    }
}

/// Fault 14: a configuration, sweep plan or sweep base read from /dev/zero is
/// refused once more than the limit is read (before: read until memory ran out).
#[cfg(unix)]
#[test]
fn a_configuration_without_end_is_refused_at_the_size_limit() {
    let dir = scratch("dev-zero");
    let (code, stderr) = code_and_stderr(&carom(&dir, &["run", "/dev/zero", "--dry-run"]));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("/dev/zero") && stderr.contains("256 MiB"),
        "{stderr}"
    );
    let (code, stderr) = code_and_stderr(&carom(
        &dir,
        &["sweep", "/dev/zero", "--out", "s", "--dry-run"],
    ));
    assert!(code.is_some_and(|c| c != 0), "{stderr}");
    assert!(stderr.contains("256 MiB"), "{stderr}");
    std::fs::write(
        dir.join("plan.json"),
        r#"{"base": "/dev/zero", "vary": {"box.packing_fraction": [0.3]}}"#,
    )
    .unwrap();
    let (code, stderr) = code_and_stderr(&carom(
        &dir,
        &["sweep", "plan.json", "--out", "s", "--dry-run"],
    ));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("base") && stderr.contains("256 MiB"),
        "{stderr}"
    );
}

/// Fault 14: `export --out /dev/null` writes XYZ frames into it (before:
/// "Invalid argument" from syncing a device) and refuses GSD, which needs a
/// regular file, saying so; /dev/null stays a device.
#[cfg(unix)]
#[test]
fn export_to_dev_null_works_for_xyz_and_is_refused_clearly_for_gsd() {
    use std::os::unix::fs::FileTypeExt;
    let dir = scratch("dev-null");
    small_log(&dir);
    let out = carom(
        &dir,
        &[
            "export",
            "small.mcap",
            "--format",
            "xyz",
            "--out",
            "/dev/null",
            "--force",
            "-q",
        ],
    );
    let text = ok(&out);
    assert!(
        text.contains("wrote /dev/null: 6 frames of 500 discs"),
        "{text}"
    );
    let (code, stderr) = code_and_stderr(&carom(
        &dir,
        &[
            "export",
            "small.mcap",
            "--format",
            "gsd",
            "--out",
            "/dev/null",
            "--force",
            "-q",
        ],
    ));
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("not a regular file"), "{stderr}");
    let null = std::fs::metadata("/dev/null").unwrap();
    assert!(null.file_type().is_char_device());
}
