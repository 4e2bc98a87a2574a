//! Issue 51, faults 1 and 2. (1) Every command that writes a file takes the lock
//! a run takes on its log: `repair --out`, `export --out` and `render --out`
//! onto a log a run is writing are refused, name the run, and leave its log as
//! it was. (2) `carom run --force` over an older log keeps that log until the new
//! run has started: a run that fails at its start (the engine refuses the
//! configuration, or the process aborts for want of memory) leaves it as it was.
//! The figures of `analyze --plot` and `collect --plot` take the same lock, and
//! `resume --out OTHER --force` keeps an older OTHER until the copied prefix of
//! the new log is on the disk.

use crate::cli_common::*;

use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use carom_log::LogReader;
use carom_run::{resume, Control, ResumeOptions, ResumePass, RunError};

/// A run of 300 discs that lasts until it is interrupted, logging no collisions
/// (a small log), into `out`.
fn long_run(dir: &Path, out: &str) -> Child {
    Command::new(BIN)
        .args(["run", "--quiet", "--force", "--out", out])
        .args(["--set", "species.0.count=300", "--set", "stop.duration=1e7"])
        .args(["--set", "log.collisions=false"])
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// Whether another process holds the lock on `path`.
fn locked(path: &Path) -> bool {
    std::fs::File::open(path)
        .is_ok_and(|f| matches!(f.try_lock_shared(), Err(std::fs::TryLockError::WouldBlock)))
}

/// Wait (up to a minute) until `name` in `dir` is the locked log of a run that
/// has started: no temporary file left beside it.
fn wait_started(dir: &Path, name: &str) {
    let start = Instant::now();
    let started = || locked(&dir.join(name)) && !dir.join(format!("{name}.run-tmp")).exists();
    while !started() {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the run into {name} did not start"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Stop `child` with SIGINT; it finishes its log (exit status 130).
fn interrupt(child: Child) {
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A small complete log of 64 discs, `name`, in `dir`.
fn small_log(dir: &Path, name: &str) {
    ok(&carom(
        dir,
        &[
            "run",
            "--quiet",
            "--force",
            "--out",
            name,
            "--set",
            "species.0.count=64",
            "--set",
            "stop.duration=2",
        ],
    ));
}

/// The number of discs of the log `name` in `dir`, and whether it is complete.
fn discs(dir: &Path, name: &str) -> (u64, bool) {
    let i = json_of(&carom(dir, &["info", name, "--json"]));
    (i["run"]["n_discs"].as_u64().unwrap(), i["complete"] == true)
}

fn refused(out: &Output, file: &str, pid: u32, what: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{what}: {stderr}");
    assert!(
        stderr.contains(&format!("{file} is being written by")),
        "{what}: {stderr}"
    );
    #[cfg(target_os = "linux")]
    assert!(
        stderr.contains(&format!("process {pid} (")),
        "{what}: {stderr}"
    );
}

#[test]
fn repair_and_export_onto_a_log_a_run_is_writing_are_refused() {
    let dir = scratch("repair-export");
    small_log(&dir, "small.mcap");
    // An older log at s.mcap: the run replaces it once started, and holds the lock
    // on the new one.
    small_log(&dir, "s.mcap");
    let run = long_run(&dir, "s.mcap");
    let pid = run.id();
    wait_started(&dir, "s.mcap");
    let writers: [&[&str]; 3] = [
        &["repair", "small.mcap", "--out", "s.mcap", "--force"],
        &[
            "export",
            "small.mcap",
            "--format",
            "xyz",
            "--out",
            "s.mcap",
            "--force",
            "-q",
        ],
        &[
            "export",
            "small.mcap",
            "--format",
            "gsd",
            "--out",
            "s.mcap",
            "--force",
            "-q",
        ],
    ];
    for args in writers {
        refused(&carom(&dir, args), "s.mcap", pid, &args.join(" "));
    }
    interrupt(run);
    // The run's log, whole: not the 64 discs of small.mcap.
    assert_eq!(discs(&dir, "s.mcap"), (300, true));
    let verify = carom(&dir, &["info", "s.mcap", "--verify"]);
    assert!(ok(&verify).contains("complete"), "{}", ok(&verify));
    assert!(!dir.join("s.mcap.run-tmp").exists());
}

#[test]
fn render_onto_a_file_a_run_is_writing_is_refused() {
    let dir = scratch("render");
    small_log(&dir, "small.mcap");
    let run = long_run(&dir, "s.png");
    let pid = run.id();
    wait_started(&dir, "s.png");
    let args = ["render", "small.mcap", "-o", "s.png", "--force", "-q"];
    refused(&carom(&dir, &args), "s.png", pid, "render");
    let movie = ["render", "small.mcap", "--movie", "-o", "s.png", "--force"];
    // A movie must be a .gif: refused for that before the lock is looked at.
    assert_eq!(carom(&dir, &movie).status.code(), Some(2));
    interrupt(run);
    assert_eq!(discs(&dir, "s.png"), (300, true));
    // Once the run has ended, render writes over it.
    ok(&carom(&dir, &args));
    assert!(std::fs::read(dir.join("s.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
}

#[test]
fn a_refused_writer_creates_nothing_and_a_writer_that_fails_leaves_nothing() {
    let dir = scratch("nothing");
    // repair of a file that is no log: refused after the lock was taken on the new
    // file, which is removed again.
    std::fs::write(dir.join("junk.mcap"), b"not a log").unwrap();
    let out = carom(&dir, &["repair", "junk.mcap", "--out", "r.mcap"]);
    assert!(!out.status.success());
    assert!(!dir.join("r.mcap").exists());
    let out = carom(
        &dir,
        &["export", "junk.mcap", "--format", "xyz", "--out", "r.xyz"],
    );
    assert!(!out.status.success());
    assert!(!dir.join("r.xyz").exists());
}

/// Run `carom ARGS` onto the older log s.mcap in `dir` (through `sh`, for
/// `ulimit`), which must fail and leave s.mcap byte for byte as it was.
fn fails_and_keeps(dir: &Path, script: &str) -> String {
    let before = std::fs::read(dir.join("s.mcap")).unwrap();
    let out = sh(dir, script);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "{script}: {stderr}");
    assert!(
        std::fs::read(dir.join("s.mcap")).unwrap() == before,
        "{script} changed the older log: {stderr}"
    );
    stderr
}

#[test]
fn a_force_run_that_fails_at_its_start_keeps_the_older_log() {
    let dir = scratch("force-fails");
    let bed = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/vibrated-bed.json");
    let bed = bed.display();
    small_log(&dir, "s.mcap");
    for set in [
        "vibrating_floor.amplitude=100",
        "vibrating_floor.frequency=1e300",
    ] {
        let stderr = fails_and_keeps(
            &dir,
            &format!("exec {BIN} run {bed} --set {set} --out s.mcap --force -q"),
        );
        assert!(stderr.contains("vibrating_floor"), "{stderr}");
        assert!(
            stderr.contains("no log was written; s.mcap is as it was"),
            "{stderr}"
        );
        assert!(!dir.join("s.mcap.run-tmp").exists(), "{set}");
    }
    // An abort for want of memory while the first snapshot and checkpoint of 10⁶
    // discs are written (the memory check, which would refuse it, skipped).
    let stderr = fails_and_keeps(
        &dir,
        &format!(
            "ulimit -v 500000; CAROM_IGNORE_MEMORY_CHECK=1 exec {BIN} run --set \
             species.0.count=1e6 --set stop.duration=1 --out s.mcap --force -q"
        ),
    );
    assert!(stderr.contains("memory allocation"), "{stderr}");
    // The abort left the new log's beginning beside the older one, under a name
    // that says what it is; the next run over s.mcap replaces it.
    assert!(dir.join("s.mcap.run-tmp").exists());
    small_log(&dir, "s.mcap");
    assert!(!dir.join("s.mcap.run-tmp").exists());
    assert_eq!(discs(&dir, "s.mcap"), (64, true));
}

#[test]
fn a_run_without_force_still_refuses_an_existing_log() {
    let dir = scratch("no-force");
    small_log(&dir, "s.mcap");
    let before = std::fs::read(dir.join("s.mcap")).unwrap();
    let out = carom(&dir, &["run", "-q", "--out", "s.mcap"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--force"));
    assert_eq!(std::fs::read(dir.join("s.mcap")).unwrap(), before);
    assert!(!dir.join("s.mcap.run-tmp").exists());
}

/// Every message of the log at `path`: channel, sequence, times and bytes.
fn messages(path: &Path) -> Vec<(usize, u32, u64, u64, Vec<u8>)> {
    let mut r = LogReader::open(path).unwrap();
    let mut all = Vec::new();
    while let Some(m) = r.next_raw().unwrap() {
        all.push((
            m.channel,
            m.sequence,
            m.log_time,
            m.publish_time,
            m.data.to_vec(),
        ));
    }
    all
}

#[test]
fn a_force_run_over_an_older_log_writes_the_same_messages_as_a_fresh_run() {
    let dir = scratch("same");
    let run = |out: &str| {
        ok(&carom(
            &dir,
            &[
                "run",
                "-q",
                "--force",
                "--out",
                out,
                "--set",
                "species.0.count=400",
                "--set",
                "stop.duration=5",
                "--set",
                "seed=7",
            ],
        ))
    };
    run("fresh.mcap");
    small_log(&dir, "over.mcap");
    run("over.mcap");
    let (a, b) = (
        messages(&dir.join("fresh.mcap")),
        messages(&dir.join("over.mcap")),
    );
    assert!(a.len() > 10, "{}", a.len());
    assert!(a == b, "{} and {} messages differ", a.len(), b.len());
    assert!(!dir.join("over.mcap.run-tmp").exists());
}

#[test]
fn a_force_run_killed_after_its_start_leaves_its_own_log_resumable_in_place() {
    let dir = scratch("killed");
    small_log(&dir, "s.mcap");
    let mut run = long_run(&dir, "s.mcap");
    wait_started(&dir, "s.mcap");
    run.kill().unwrap();
    run.wait().unwrap();
    // s.mcap is the new run's log (300 discs), cut, with its first checkpoint.
    assert_eq!(discs(&dir, "s.mcap"), (300, false));
    let i = json_of(&carom(&dir, &["info", "s.mcap", "--json"]));
    let until = format!("{}", i["last_checkpoint_time"].as_f64().unwrap() + 0.5);
    ok(&carom(&dir, &["resume", "s.mcap", "--until", &until, "-q"]));
    assert_eq!(discs(&dir, "s.mcap"), (300, true));
}

#[test]
fn figures_onto_files_a_run_is_writing_are_refused() {
    let dir = scratch("figures");
    small_log(&dir, "small.mcap");
    std::fs::create_dir_all(dir.join("figs")).unwrap();
    // `analyze --plot`: its first figure is a run's log.
    let run = long_run(&dir, "figs/speed_species0.png");
    let pid = run.id();
    wait_started(&dir, "figs/speed_species0.png");
    let args = ["analyze", "small.mcap", "--plot", "figs", "-q"];
    refused(&carom(&dir, &args), "speed_species0.png", pid, "analyze");
    interrupt(run);
    assert_eq!(discs(&dir, "figs/speed_species0.png"), (300, true));
    // `collect --plot`: the equation of state of a two-point sweep.
    std::fs::write(
        dir.join("plan.json"),
        r#"{"base": {"species": [{"count": 64}], "stop": {"duration": 2}},
            "vary": {"box.packing_fraction": [0.2, 0.3]}}"#,
    )
    .unwrap();
    ok(&carom(&dir, &["sweep", "plan.json", "--out", "out", "-q"]));
    let run = long_run(&dir, "figs/equation_of_state.svg");
    let pid = run.id();
    wait_started(&dir, "figs/equation_of_state.svg");
    let args = ["collect", "out", "--plot", "figs", "--no-structure", "-q"];
    refused(&carom(&dir, &args), "equation_of_state.svg", pid, "collect");
    interrupt(run);
    assert_eq!(discs(&dir, "figs/equation_of_state.svg"), (300, true));
    // Once the runs have ended, the figures are written over them.
    ok(&carom(&dir, &args));
    let svg = std::fs::read_to_string(dir.join("figs/equation_of_state.svg")).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..40.min(svg.len())]);
}

#[test]
fn a_resume_over_an_older_log_keeps_it_until_the_copy_is_on_the_disk() {
    let dir = scratch("resume-over");
    ok(&carom(
        &dir,
        &[
            "run",
            "-q",
            "--out",
            "in.mcap",
            "--set",
            "species.0.count=400",
            "--set",
            "stop.duration=4",
            "--set",
            "log.checkpoint_interval=1",
        ],
    ));
    small_log(&dir, "old.mcap");
    let (input, old) = (dir.join("in.mcap"), dir.join("old.mcap"));
    let before = std::fs::read(&old).unwrap();
    let later = ResumeOptions {
        stop: Some(carom_log::Stop::Time(6.0)),
    };
    // No room for the copy: refused, the older log as it was, nothing beside it.
    let mut no_room = |_: &Path| -> std::io::Result<u64> { Ok(1000) };
    let e = resume(
        &input,
        &old,
        &later,
        Control {
            free_space: Some(&mut no_room),
            ..Control::default()
        },
    )
    .unwrap_err();
    assert!(matches!(e, RunError::NoRoom { .. }), "{e:?}");
    assert_eq!(std::fs::read(&old).unwrap(), before);
    assert!(!dir.join("old.mcap.run-tmp").exists());
    // While the prefix is copied the older log is untouched; the result is the
    // resume a fresh file gets, message for message.
    let mut looked = 0;
    let mut watch = |pass: ResumePass, _| {
        if pass == ResumePass::Copying {
            looked += 1;
            assert_eq!(std::fs::read(&old).unwrap(), before);
        }
    };
    resume(
        &input,
        &old,
        &later,
        Control {
            reading: Some(&mut watch),
            ..Control::default()
        },
    )
    .unwrap();
    assert!(looked > 0);
    resume(&input, &dir.join("fresh.mcap"), &later, Control::default()).unwrap();
    assert!(messages(&old) == messages(&dir.join("fresh.mcap")));
    assert!(!dir.join("old.mcap.run-tmp").exists());
}
