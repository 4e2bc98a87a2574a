//! Issue 51, faults 4 and 5: stops that must be honoured and runs that must not
//! fill the disk. A thermostat or growth schedule whose cost is known in advance
//! is refused at the start, naming the field; a long stretch of thermostat
//! events, or compressed placement, still hears SIGINT; `resume` refuses the
//! collision stop `run` refuses; a log projected to need far more than its disk
//! stops at once with a finished log.

use std::io::Read;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use crate::cli_common::{carom, ok, scratch, BIN};

/// The exit status and standard error of a run expected to be refused.
fn refused(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let out = carom(dir, args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{err}");
    (out.status.code(), err)
}

#[test]
fn thermostat_and_rescale_schedules_beyond_any_run_are_refused_at_the_start() {
    let dir = scratch("schedules");
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/data/");
    let cases = [
        (
            "thermostatted-fluid.json",
            "thermostat.rate=1e300",
            "thermostat.rate",
        ),
        (
            "driven-granular.json",
            "thermostat.interval=1e-9",
            "thermostat.interval",
        ),
        (
            "driven-granular.json",
            "thermostat.interval=1e-300",
            "thermostat.interval",
        ),
        (
            "compression-crystal.json",
            "compression.rescale_interval=1e-9",
            "compression.rescale_interval",
        ),
        (
            "compression-crystal.json",
            "compression.rescale_interval=1e-300",
            "compression.rescale_interval",
        ),
    ];
    for (config, set, field) in cases {
        let config = format!("{data}{config}");
        let (code, err) = refused(
            &dir,
            &[
                "run", &config, "--set", set, "-o", "x.mcap", "--force", "-q",
            ],
        );
        assert_eq!(code, Some(2), "{set}: {err}");
        assert!(err.contains(&format!("{field}:")), "{set}: {err}");
        assert!(err.contains("at most 1e9 events"), "{set}: {err}");
        assert!(!dir.join("x.mcap").exists(), "{set} left a log");
    }
    // Compressed placement whose growth law needs ~10¹⁵⁰ rescales.
    let (code, err) = refused(
        &dir,
        &[
            "run",
            "--set",
            r#"placement={"compressed":{"rate":1,"start_packing_fraction":1e-300}}"#,
            "-o",
            "x.mcap",
            "-q",
        ],
    );
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("placement.compressed.rate"), "{err}");
    // The examples themselves are far inside the bound.
    let (code, err) = refused(
        &dir,
        &[
            "run",
            &format!("{data}thermostatted-fluid.json"),
            "--set",
            "stop.duration=1",
            "-o",
            "ok.mcap",
            "-q",
        ],
    );
    assert_eq!(code, Some(0), "{err}");
}

/// Start `carom ARGS` in `dir` with standard error piped.
fn start(dir: &Path, args: &[&str]) -> Child {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

/// Wait (generously) for `child` to exit; its status code, or `None` if it is
/// still running after `limit` (then it is killed).
fn exit_within(child: &mut Child, limit: Duration) -> Option<i32> {
    let t0 = Instant::now();
    while t0.elapsed() < limit {
        if let Some(s) = child.try_wait().unwrap() {
            return s.code();
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let _ = child.kill();
    let _ = child.wait();
    None
}

/// Send SIGINT to `child` (with the `kill` command: no unsafe code).
fn interrupt(child: &Child) {
    let s = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(s.success(), "kill -INT failed");
}

#[test]
fn a_lone_disc_under_a_fast_thermostat_stops_at_an_interrupt() {
    // 10⁹ Andersen redraws (the most allowed) of one disc that never collides,
    // with nothing observed before t = 10: without the engine handing back
    // control, the stop would be heard only at t = 10, minutes later.
    let dir = scratch("lone-andersen");
    std::fs::write(
        dir.join("lone.json"),
        r#"{"species":[{"count":1,"radius":0.5,"mass":1.0}],
            "box":{"size":[10.0,10.0],"boundary":"periodic"},
            "placement":{"explicit":[[5.0,5.0]]},"velocities":{"explicit":[[1.0,0.3]]},
            "thermostat":{"kind":"andersen","kT":1.0,"rate":1e8},
            "stop":{"duration":10.0},
            "log":{"snapshot_interval":null,"thermo_interval":null,"scene_interval":null,
                   "checkpoint_interval":10.0}}"#,
    )
    .unwrap();
    let mut child = start(&dir, &["run", "lone.json", "-o", "l.mcap", "-q"]);
    // The log exists once the run has started (placement is instantaneous).
    let t0 = Instant::now();
    while !dir.join("l.mcap").exists() && t0.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(300));
    interrupt(&child);
    let code = exit_within(&mut child, Duration::from_secs(60));
    assert_eq!(code, Some(130), "the run did not stop at the interrupt");
    let info = ok(&carom(&dir, &["info", "l.mcap", "--json"]));
    assert!(info.contains("interrupted"), "{info}");
}

#[test]
fn compressed_placement_shows_progress_and_stops_at_an_interrupt() {
    let dir = scratch("compressed-interrupt");
    // γ = 10⁻⁹: ~3·10⁸ rescale intervals of growth, within the bound, for ever in
    // practice.
    let mut child = start(
        &dir,
        &[
            "run",
            "--set",
            r#"placement={"compressed":{"rate":1e-9}}"#,
            "--set",
            "species.0.count=2000",
            "-o",
            "c.mcap",
        ],
    );
    let mut err = child.stderr.take().unwrap();
    // Read standard error until the placement's first progress line.
    let mut seen = Vec::new();
    let mut buf = [0u8; 256];
    while !String::from_utf8_lossy(&seen).contains("(compressed placement): packing fraction") {
        let k = err.read(&mut buf).unwrap();
        assert!(k > 0, "no progress: {}", String::from_utf8_lossy(&seen));
        seen.extend_from_slice(&buf[..k]);
    }
    interrupt(&child);
    let reader = std::thread::spawn(move || {
        let mut rest = String::new();
        let _ = err.read_to_string(&mut rest);
        rest
    });
    let code = exit_within(&mut child, Duration::from_secs(60));
    let rest = reader.join().unwrap();
    assert_eq!(code, Some(130), "placement went on after SIGINT: {rest}");
    assert!(
        rest.contains("interrupted while placing the discs"),
        "{rest}"
    );
    assert!(!dir.join("c.mcap").exists());
}

#[test]
fn resume_refuses_the_collision_stop_that_run_refuses() {
    let dir = scratch("resume-collisions");
    ok(&carom(
        &dir,
        &[
            "run",
            "--set",
            "species.0.count=500",
            "--set",
            "stop.duration=5",
            "-o",
            "small.mcap",
            "-q",
        ],
    ));
    let (run_code, run_err) = refused(
        &dir,
        &[
            "run",
            "--set",
            "species.0.count=500",
            "--set",
            "stop.collisions=1000000000000000",
            "-o",
            "big.mcap",
            "-q",
        ],
    );
    let (code, err) = refused(
        &dir,
        &[
            "resume",
            "small.mcap",
            "--collisions",
            "1000000000000000",
            "--out",
            "r.mcap",
            "-q",
        ],
    );
    assert_eq!(run_code, Some(2), "{run_err}");
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("at most 1e9 records"), "{err}");
    assert!(!dir.join("r.mcap").exists());
}

#[test]
fn a_log_projected_far_beyond_the_free_disk_stops_at_once_with_a_finished_log() {
    // The default fluid, every collision logged (≈ 1.5 MB per time unit), to t = 5·10⁷:
    // a log of ≈ 7·10¹³ bytes, more than ten times any disk this runs on. (The
    // issue's atmosphere at kT = 10⁻²⁰⁰ now rests on its floor: physics.md (15.9).)
    let dir = scratch("disk-estimate");
    let out = carom(
        &dir,
        &["run", "--set", "stop.duration=5e7", "-o", "t.mcap", "-q"],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("--ignore-disk-estimate"), "{err}");
    assert!(err.contains("times the"), "{err}");
    let info = ok(&carom(&dir, &["info", "t.mcap", "--verify"]));
    assert!(info.contains("disk_full"), "{info}");
    // The log is finished, well short of the disk.
    let bytes = std::fs::metadata(dir.join("t.mcap")).unwrap().len();
    assert!(bytes < 1 << 30, "{bytes} bytes");
}
