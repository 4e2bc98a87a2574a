//! Issue 51, fault 13: a disc at rest on the floor of a field is a valid state.
//! Before, `carom run` of a single disc at `[[5, 0.5]]` (radius 0.5) with velocity
//! `[[0, 0]]` or `[[1, 0]]` and gravity on stopped at t = 0 with the runaway error
//! about "a row of touching discs": its floor hit came at dt = 0 and bounced it to
//! v_y = 0 again, for ever. Now it rests (physics.md (15.9)): the runs below reach
//! their stops with exit 0, the resting disc stays at y = a exactly, the sliding
//! one moves at 1 along the floor between the side walls, K + U is conserved, a
//! disc dropped onto a resting one conserves it too, and a run with resting discs
//! resumes from a cut log bit for bit.

use crate::cli_common::*;
use std::path::Path;

/// A configuration of discs of radius 0.5 and mass 1 at `positions` with
/// `velocities`, g = 1, in a box `size` with walls along y (and along x unless
/// `periodic_x`), run for `duration` with a snapshot every time unit.
fn config(
    size: [f64; 2],
    periodic_x: bool,
    positions: &[[f64; 2]],
    velocities: &[[f64; 2]],
    duration: f64,
) -> String {
    serde_json::json!({
        "species": [{ "count": positions.len(), "radius": 0.5, "mass": 1.0 }],
        "box": {
            "size": size,
            "boundary": { "x": if periodic_x { "periodic" } else { "walls" }, "y": "walls" },
            "wall_restitution": 1.0
        },
        "gravity": 1.0,
        "placement": { "explicit": positions },
        "velocities": { "explicit": velocities },
        "stop": { "duration": duration },
        "log": { "snapshot_interval": 1.0, "checkpoint_interval": 10.0 }
    })
    .to_string()
}

/// One snapshot: time and, per disc, (x, y, v_x, v_y).
type Frame = (f64, Vec<[f64; 4]>);

/// The snapshots of `log` in `dir`, through `carom export --format xyz`.
fn frames(dir: &Path, log: &str) -> Vec<Frame> {
    let xyz = format!("{log}.xyz");
    ok(&carom(
        dir,
        &["export", "--format", "xyz", log, "-o", &xyz, "--force"],
    ));
    let text = std::fs::read_to_string(dir.join(&xyz)).unwrap();
    let mut lines = text.lines();
    let mut out = Vec::new();
    while let Some(count) = lines.next() {
        let n: usize = count.trim().parse().unwrap();
        let header = lines.next().unwrap();
        let time: f64 = header
            .split("Time=")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        let discs = (0..n)
            .map(|_| {
                // species x y z vx vy vz radius mass
                let f: Vec<f64> = lines
                    .next()
                    .unwrap()
                    .split_whitespace()
                    .skip(1)
                    .map(|v| v.parse().unwrap())
                    .collect();
                [f[0], f[1], f[3], f[4]]
            })
            .collect();
        out.push((time, discs));
    }
    out
}

/// K + U (energy) of a frame with m = 1, g = 1.
fn energy(discs: &[[f64; 4]]) -> f64 {
    discs
        .iter()
        .map(|d| 0.5 * (d[2] * d[2] + d[3] * d[3]) + d[1])
        .sum()
}

/// Write `json` as `name` in `dir` and `carom run` it to `name.mcap`; the run
/// must end at its stop with exit 0. Returns the snapshots.
fn run(dir: &Path, name: &str, json: &str, duration: f64) -> Vec<Frame> {
    std::fs::write(dir.join(name), json).unwrap();
    let log = format!("{name}.mcap");
    let out = carom(dir, &["run", name, "--quiet", "--force", "--out", &log]);
    ok(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!("stopped (time) at t = {duration}")),
        "{stderr}"
    );
    let f = frames(dir, &log);
    assert_eq!(f.len(), duration as usize + 1);
    f
}

/// The first case: the disc put at rest on the floor stays there, every
/// snapshot to t = 50, with K + U = 1/2.
#[test]
fn a_disc_at_rest_on_the_floor_stays_there_until_the_stop() {
    let dir = scratch("rest");
    let json = config([10.0, 10.0], false, &[[5.0, 0.5]], &[[0.0, 0.0]], 50.0);
    for (t, d) in run(&dir, "rest.json", &json, 50.0) {
        assert_eq!(d[0], [5.0, 0.5, 0.0, 0.0], "t = {t}");
        assert_eq!(energy(&d), 0.5);
    }
}

/// The second case: sliding at 1 along the floor it is at x0 + t,
/// reflected by the side walls (centre between 0.5 and 9.5), y = a all along.
#[test]
fn a_disc_sliding_along_the_floor_moves_at_its_speed_between_the_side_walls() {
    let dir = scratch("slide");
    let json = config([10.0, 10.0], false, &[[5.0, 0.5]], &[[1.0, 0.0]], 50.0);
    for (t, d) in run(&dir, "slide.json", &json, 50.0) {
        let s = (5.0 + t - 0.5).rem_euclid(18.0);
        let x = 0.5 + if s <= 9.0 { s } else { 18.0 - s };
        let [px, py, vx, vy] = d[0];
        assert!((px - x).abs() < 1e-12, "t = {t}: x = {px}, expected {x}");
        assert_eq!((py, vx.abs(), vy), (0.5, 1.0, 0.0), "t = {t}");
        assert_eq!(energy(&d), 1.0);
    }
}

/// Three discs resting side by side (not touching) and a fourth dropped from
/// y = 5 beside them, bouncing for ever on the elastic floor: the three never
/// move, the fourth keeps its energy 5 (it comes back to 5), the total is 6.5.
#[test]
fn discs_resting_side_by_side_stay_while_another_bounces_beside_them() {
    let dir = scratch("row");
    let json = config(
        [10.0, 10.0],
        false,
        &[[1.0, 0.5], [2.5, 0.5], [4.0, 0.5], [8.0, 5.0]],
        &[[0.0; 2]; 4],
        100.0,
    );
    let f = run(&dir, "row.json", &json, 100.0);
    let mut top: f64 = 0.0;
    for (t, d) in &f {
        for (k, x) in [1.0, 2.5, 4.0].iter().enumerate() {
            assert_eq!(d[k], [*x, 0.5, 0.0, 0.0], "disc {k} at t = {t}");
        }
        assert_eq!(d[3][0], 8.0);
        assert!((energy(&d[3..]) - 5.0).abs() < 1e-12, "t = {t}");
        top = top.max(d[3][1]);
    }
    // The bounce takes 2·√8 ≈ 5.66: some snapshots are near its top, 5.
    assert!(top > 4.9, "{top}");
}

/// A disc dropped beside the top of a resting one hits it, knocks it off the
/// floor and the two go on colliding with each other and the walls: K + U stays
/// 4 (its start) to rounding and no two discs overlap in any snapshot.
#[test]
fn a_disc_dropped_onto_a_resting_one_keeps_the_energy() {
    let dir = scratch("drop");
    let json = config(
        [10.0, 10.0],
        false,
        &[[5.0, 0.5], [5.3, 3.5]],
        &[[0.0; 2]; 2],
        200.0,
    );
    let f = run(&dir, "drop.json", &json, 200.0);
    let mut moved = false;
    for (t, d) in &f {
        assert!((energy(d) - 4.0).abs() < 1e-12, "t = {t}: {}", energy(d));
        let gap = ((d[0][0] - d[1][0]).powi(2) + (d[0][1] - d[1][1]).powi(2)).sqrt();
        assert!(gap >= 1.0 - 1e-12, "overlap at t = {t}: {gap}");
        moved |= d[0][0] != 5.0;
    }
    assert!(moved, "the dropped disc knocks the resting one");
}

/// Three discs resting and one bouncing beside them, the log cut in half and
/// resumed: the resumed log has the uninterrupted run's snapshots byte for byte
/// and the same collisions (the resting flag is in the checkpoint: a resumed disc
/// that forgot it would be laid to rest again by a floor hit more).
#[test]
fn a_run_with_resting_discs_resumes_from_a_cut_log_bit_for_bit() {
    let dir = scratch("resume");
    let json = config(
        [10.0, 10.0],
        false,
        &[[1.0, 0.5], [2.5, 0.5], [4.0, 0.5], [8.0, 5.0]],
        &[[0.0; 2]; 4],
        100.0,
    );
    run(&dir, "row.json", &json, 100.0);
    let bytes = std::fs::read(dir.join("row.json.mcap")).unwrap();
    std::fs::write(dir.join("cut.mcap"), &bytes[..bytes.len() / 2]).unwrap();
    ok(&carom(
        &dir,
        &[
            "resume",
            "cut.mcap",
            "--out",
            "resumed.mcap",
            "--quiet",
            "--force",
        ],
    ));
    let summary = |log: &str| {
        let info = ok(&carom(&dir, &["info", log]));
        let line = info
            .lines()
            .find(|l| l.contains("summary: stopped"))
            .unwrap()
            .to_string();
        // The rate (collisions/s) differs from run to run.
        line.split(" collisions,").next().unwrap().to_string()
    };
    assert_eq!(summary("resumed.mcap"), summary("row.json.mcap"));
    // Three floor hits at t = 0 lay the row to rest; the bouncer, 4.5 above the
    // floor, lands at 3 and every 6 after: 17 hits by t = 100.
    assert!(summary("resumed.mcap").contains("0 pair + 20 wall"));
    let (full, resumed) = (frames(&dir, "row.json.mcap"), frames(&dir, "resumed.mcap"));
    assert_eq!(full.len(), 101);
    assert!(full == resumed);
}

/// Not handled: a disc put at rest on top of a resting one (a stack). It is
/// refused, not run wrong: the runaway error, which names the case.
#[test]
fn a_disc_stacked_on_a_resting_one_is_refused_with_the_runaway_error_naming_it() {
    let dir = scratch("stack");
    let json = config(
        [10.0, 10.0],
        false,
        &[[5.0, 0.5], [5.0, 1.5]],
        &[[0.0; 2]; 2],
        10.0,
    );
    std::fs::write(dir.join("stack.json"), json).unwrap();
    let out = carom(&dir, &["run", "stack.json", "--quiet", "--force"]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("runaway") && err.contains("a disc at rest on top of another"),
        "{err}"
    );
}
