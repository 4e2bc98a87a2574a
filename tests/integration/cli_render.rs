//! `carom render` through the command: it renders the snapshot asked for (or the
//! nearest, or the last beside the log) at the width asked for, in PNG, SVG or as
//! a movie of one frame per kept snapshot; bad times, a log without snapshots and
//! an unwritable output fail cleanly, leaving no file behind. The colours and the
//! layout of a picture are checked on the same two discs by the binary's unit
//! tests (src/render/tests.rs).

use std::path::{Path, PathBuf};

use crate::cli_common::*;

/// Width given to every render here.
const WIDTH: u32 = 640;

/// A log of two discs in a 20 × 10 box: species A (a = 3) at (1, 5) moving at
/// speed 0.5 — across the periodic edge x = 0 — and species B (a = 2) at (12, 5)
/// at speed 0.25; snapshots at t = 0, 1, 2 (`snapshots`: or none).
fn two_disc_log(dir: &Path, boundary: &str, snapshots: bool) -> PathBuf {
    let config = serde_json::json!({
        "species": [{"count": 1, "radius": 3.0, "mass": 1.0},
                    {"count": 1, "radius": 2.0, "mass": 2.0}],
        "box": {"size": [20.0, 10.0], "boundary": boundary},
        "placement": {"explicit": [[if boundary == "periodic" { 1.0 } else { 4.0 }, 5.0], [12.0, 5.0]]},
        "velocities": {"explicit": [[0.0, 0.5], [0.0, -0.25]]},
        "stop": {"duration": 2.0},
        "log": {"snapshot_interval": if snapshots { serde_json::json!(1.0) } else { serde_json::Value::Null }}
    });
    std::fs::write(dir.join("two.json"), config.to_string()).unwrap();
    ok(&carom(
        dir,
        &["run", "--quiet", "two.json", "--out", "two.mcap"],
    ));
    dir.join("two.mcap")
}

#[test]
fn a_picture_of_the_time_asked_for_is_as_wide_as_asked_for() {
    let dir = scratch("species");
    two_disc_log(&dir, "periodic", true);
    let w = WIDTH.to_string();
    let out = ok(&carom(
        &dir,
        &[
            "render", "two.mcap", "--time", "0", "--size", &w, "-o", "a.png",
        ],
    ));
    assert!(out.contains("t = 0, N = 2"), "{out}");
    let img = image::open(dir.join("a.png")).unwrap().to_rgb8();
    assert_eq!(img.width(), WIDTH);
}

#[test]
fn nearest_snapshots_are_chosen_and_the_default_is_the_last_beside_the_log() {
    let dir = scratch("speed");
    two_disc_log(&dir, "walls", true);
    let w = WIDTH.to_string();
    let out = ok(&carom(
        &dir,
        &[
            "render", "two.mcap", "--time", "0", "--color", "speed", "--size", &w, "-o", "s.png",
        ],
    ));
    assert!(out.contains("t = 0"), "{out}");
    assert_eq!(image::open(dir.join("s.png")).unwrap().width(), WIDTH);
    for (t, nearest) in [("1.4", "t = 1,"), ("1.6", "t = 2,"), ("1.5", "t = 1,")] {
        let out = ok(&carom(
            &dir,
            &["render", "two.mcap", "--time", t, "-o", "n.png", "-f"],
        ));
        assert!(out.contains(nearest), "--time {t}: {out}");
    }
    // Default: the last snapshot, beside the log.
    let out = ok(&carom(&dir, &["render", "two.mcap"]));
    assert!(out.contains("two.png") && out.contains("t = 2,"), "{out}");
    assert!(dir.join("two.png").exists());
}

#[test]
fn svg_pictures_hold_the_discs_as_circles_of_their_colour() {
    let dir = scratch("svg");
    two_disc_log(&dir, "walls", true);
    let w = WIDTH.to_string();
    ok(&carom(
        &dir,
        &[
            "render", "two.mcap", "--time", "0", "--size", &w, "-o", "a.svg",
        ],
    ));
    let svg = std::fs::read_to_string(dir.join("a.svg")).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..100]);
    assert!(svg.contains(&format!("width=\"{WIDTH}\"")), "{svg}");
    // Each species' disc is a circle of its colour (A blue, B orange), larger
    // than the legend's 6-pixel markers.
    let discs: Vec<&str> = svg
        .lines()
        .filter(|l| l.starts_with("<circle") && !l.contains("r=\"6\""))
        .collect();
    for fill in ["#1F77B4", "#FF7F0E"] {
        let f = format!("fill=\"{fill}\"");
        assert!(
            discs.iter().any(|l| l.contains(&f)),
            "no disc {f} in\n{svg}"
        );
    }
}

#[test]
fn a_movie_has_one_frame_per_kept_snapshot() {
    let dir = scratch("movie");
    two_disc_log(&dir, "periodic", true);
    for (args, frames) in [
        (&[][..], 3),
        (&["--every", "2"][..], 2),
        (&["--from", "0.5"][..], 2),
    ] {
        let mut a = vec![
            "render", "two.mcap", "--movie", "--size", "320", "-o", "m.gif", "-f",
        ];
        a.extend_from_slice(args);
        let out = ok(&carom(&dir, &a));
        assert!(out.contains(&format!("{frames} frames")), "{out}");
        let file = std::fs::File::open(dir.join("m.gif")).unwrap();
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = options.read_info(file).unwrap();
        assert_eq!(u32::from(decoder.width()), 320);
        let mut n = 0;
        while decoder.read_next_frame().unwrap().is_some() {
            n += 1;
        }
        assert_eq!(n, frames, "{args:?}");
    }
}

#[test]
fn bad_times_missing_snapshots_and_unwritable_outputs_fail_cleanly() {
    let dir = scratch("errors");
    two_disc_log(&dir, "walls", true);
    let fails = |args: &[&str], code: i32, words: &[&str]| {
        let out = carom(&dir, args);
        let err = String::from_utf8_lossy(&out.stderr).to_string();
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        for w in words {
            assert!(err.contains(w), "{args:?}: {w:?} not in {err}");
        }
    };
    fails(
        &["render", "two.mcap", "--time", "-1", "-o", "x.png"],
        2,
        &["--time -1", "≥ 0"],
    );
    fails(
        &["render", "two.mcap", "--time", "nan", "-o", "x.png"],
        2,
        &["--time"],
    );
    fails(
        &["render", "two.mcap", "--time", "9", "-o", "x.png"],
        2,
        &["--time 9", "last snapshot at t = 2"],
    );
    fails(
        &["render", "two.mcap", "-o", "x.jpg"],
        2,
        &["--out x.jpg", ".png, .svg"],
    );
    fails(
        &["render", "two.mcap", "--movie", "-o", "x.png"],
        2,
        &["--movie", ".gif"],
    );
    fails(
        &[
            "render", "two.mcap", "--movie", "--every", "0", "-o", "x.gif",
        ],
        2,
        &["--every 0"],
    );
    fails(
        &[
            "render", "two.mcap", "--movie", "--from", "5", "-o", "x.gif",
        ],
        2,
        &["span t = 0 … 2"],
    );
    fails(
        &["render", "two.mcap", "-o", "no/such/dir/x.png"],
        1,
        &["cannot write no/such/dir/x.png"],
    );
    fails(
        &["render", "two.mcap", "-o", "two.mcap"],
        2,
        &["the log being read"],
    );
    fails(
        &["render", "two.mcap", "--movie", "-o", "no/dir/x.gif"],
        1,
        &["cannot write no/dir/x.gif"],
    );
    for f in ["x.png", "x.gif"] {
        assert!(!dir.join(f).exists(), "{f} left behind");
    }
    ok(&carom(&dir, &["render", "two.mcap", "-o", "x.png"]));
    fails(
        &["render", "two.mcap", "-o", "x.png"],
        2,
        &["x.png exists", "--force"],
    );

    let dir = scratch("no-snapshots");
    two_disc_log(&dir, "walls", false);
    let out = carom(&dir, &["render", "two.mcap", "-o", "x.png"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("holds no snapshots"), "{err}");
    assert!(!dir.join("x.png").exists());
}
