//! `carom export`: GSD and extended XYZ frames of a log's snapshots. The Python
//! `gsd` package reads the GSD file and a small parser the XYZ file, and both are
//! compared with the snapshots as the independent `mcap` packages decode them
//! (tests/python/check_export.py); without those packages that part is skipped.
//! Ranges, --every, and failures (no snapshots, an unwritable output) are checked
//! on the XYZ text directly.

use std::path::Path;

use crate::cli_common::*;

/// A run of `sets` with snapshots every 0.5 up to t = 3, logged to `name`.
fn log(dir: &Path, name: &str, sets: &[&str]) {
    let mut args = vec!["run", "--quiet", "--out", name];
    let mut all = vec!["stop.duration=3", "log.snapshot_interval=0.5", "seed=3"];
    all.extend_from_slice(sets);
    for s in &all {
        args.extend(["--set", s]);
    }
    ok(&carom(dir, &args));
}

/// (N, comment line) of each frame of an XYZ file.
fn xyz_frames(path: &Path) -> Vec<(usize, String)> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let mut frames = Vec::new();
    while let Some(n) = lines.next() {
        let n: usize = n.parse().unwrap();
        let comment = lines.next().unwrap().to_string();
        for _ in 0..n {
            assert_eq!(lines.next().unwrap().split(' ').count(), 9);
        }
        frames.push((n, comment));
    }
    frames
}

#[test]
fn gsd_and_xyz_hold_each_snapshot_as_the_independent_readers_see_it() {
    let Some(py) = python_with(&["gsd.hoomd", "numpy", "mcap", "mcap_ros2.decoder"]) else {
        return;
    };
    let dir = scratch("python");
    log(
        &dir,
        "p.mcap",
        &["species.0.count=300", "box.packing_fraction=0.4"],
    );
    log(
        &dir,
        "w.mcap",
        &[
            "species.0.count=150",
            "species.1.count=60",
            "species.1.radius=0.8",
            "species.1.mass=3",
            "box.packing_fraction=0.3",
            "box.boundary=walls",
            "placement=random",
        ],
    );
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/python/check_export.py");
    for (name, every, frames) in [("p", "0", 7), ("w", "1", 4)] {
        let mcap = format!("{name}.mcap");
        let (gsd, xyz) = (format!("{name}.gsd"), format!("{name}.xyz"));
        let mut extra = vec![];
        if every != "0" {
            extra = vec!["--every", every];
        }
        for (format, out) in [("gsd", &gsd), ("xyz", &xyz)] {
            let mut a = vec!["export", &mcap, "--format", format, "-o", out, "-q"];
            a.extend_from_slice(&extra);
            let text = ok(&carom(&dir, &a));
            assert!(text.contains(&format!("{frames} frames")), "{text}");
        }
        let out = std::process::Command::new(&py)
            .arg(&script)
            .args([&mcap, &gsd, &xyz, every])
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["frames"], frames, "{v}");
    }
}

#[test]
fn ranges_and_every_choose_the_frames_and_the_header_names_the_box() {
    let dir = scratch("ranges");
    log(
        &dir,
        "w.mcap",
        &[
            "species.0.count=100",
            "box.size=[30,20]",
            "box.boundary=walls",
            "placement=random",
        ],
    );
    ok(&carom(&dir, &["export", "w.mcap", "--format", "xyz", "-q"]));
    let all = xyz_frames(&dir.join("w.xyz"));
    assert_eq!(all.len(), 7);
    assert!(all.iter().all(|(n, _)| *n == 100));
    let c = &all[0].1;
    assert!(
        c.starts_with(
            "Lattice=\"30 0 0 0 20 0 0 0 1\" Properties=species:S:1:pos:R:3:velo:R:3:radius:R:1"
        ),
        "{c}"
    );
    assert!(c.contains("Time=0 ") && c.ends_with("pbc=\"F F F\""), "{c}");
    let times = |args: &[&str]| {
        let mut a = vec![
            "export", "w.mcap", "--format", "xyz", "-q", "-f", "-o", "r.xyz",
        ];
        a.extend_from_slice(args);
        ok(&carom(&dir, &a));
        xyz_frames(&dir.join("r.xyz"))
            .iter()
            .map(|(_, c)| {
                c.split("Time=")
                    .nth(1)
                    .unwrap()
                    .split(' ')
                    .next()
                    .unwrap()
                    .to_string()
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(times(&["--from", "1", "--to", "2"]), ["1", "1.5", "2"]);
    assert_eq!(times(&["--every", "1"]), ["0", "1", "2", "3"]);
    assert_eq!(
        times(&["--every", "0.9", "--from", "0.2"]),
        ["0.5", "1.5", "2.5"]
    );
}

#[test]
fn exports_without_snapshots_or_room_fail_and_leave_no_file() {
    let dir = scratch("errors");
    log(
        &dir,
        "w.mcap",
        &["species.0.count=50", "box.packing_fraction=0.2"],
    );
    log(
        &dir,
        "none.mcap",
        &["species.0.count=50", "log.snapshot_interval=null"],
    );
    let fails = |args: &[&str], code: i32, words: &[&str], left: &str| {
        let out = carom(&dir, args);
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        for w in words {
            assert!(err.contains(w), "{args:?}: {w:?} not in {err}");
        }
        assert!(!dir.join(left).exists(), "{left} left behind");
    };
    for f in ["gsd", "xyz"] {
        let out = format!("x.{f}");
        fails(
            &["export", "none.mcap", "--format", f, "-o", &out],
            1,
            &["holds no snapshots"],
            &out,
        );
        fails(
            &[
                "export", "w.mcap", "--format", f, "--every", "0", "-o", &out,
            ],
            2,
            &["--every 0"],
            &out,
        );
        fails(
            &["export", "w.mcap", "--format", f, "--from", "9", "-o", &out],
            2,
            &["no snapshot", "t = 0 … 3"],
            &out,
        );
        let bad = format!("no/such/x.{f}");
        fails(
            &["export", "w.mcap", "--format", f, "-o", &bad],
            1,
            &["cannot write no/such/x."],
            &bad,
        );
    }
    fails(
        &["export", "w.mcap", "--format", "tiff"],
        2,
        &["--format"],
        "w.tiff",
    );
    // Past a file size limit: the partial file is removed, the message says why.
    let out = sh(
        &dir,
        &format!("ulimit -f 2; exec {BIN} export w.mcap --format xyz -o big.xyz -q"),
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("cannot write big.xyz") && err.contains("too large"),
        "{err}"
    );
    assert!(!dir.join("big.xyz").exists());
}
