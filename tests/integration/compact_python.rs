//! An independent reader replays a compact log: `tests/python/replay_compact_log.py`,
//! using only the Python `mcap` + `mcap-ros2-support` packages, starts from the
//! first snapshot, applies free flight and the logged impulses, and matches every
//! later snapshot's velocities bit for bit and positions to 1e-12 (periodic wrap
//! included): a periodic monodisperse run, a walled two-species mixture, and
//! inelastic runs with each restitution rule.
//!
//! Python is `$CAROM_PYTHON` if set (then the packages must be there), else
//! `python3`; without the packages the test skips, loudly, or fails when `CI` is
//! set (tests/readers_common).

use crate::mcap_common::*;
use carom_core::{Boundary, Restitution, Species};
use carom_engine::{EngineParams, SystemSpec};
use carom_log::{LogOptions, Stop};
use carom_run::{run, Control};
use serde_json::Value;
use std::path::Path;
use std::process::Command;

fn replay_with_python(py: &str, path: &Path) -> Value {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/python/replay_compact_log.py");
    let out = Command::new(py)
        .arg(script)
        .arg(path)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "python replay failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("python prints JSON")
}

#[test]
fn python_replays_compact_logs_bit_for_bit() {
    let Some(py) = python() else { return };
    // A walled mixture: walls on both axes (one of them inelastic), two species
    // of different radius and mass.
    let walled = SystemSpec::square_box(
        vec![Species::new(60, 0.5, 1.0), Species::new(40, 0.7, 1.96)],
        0.35,
        [
            Boundary::Walls { restitution: 1.0 },
            Boundary::Walls { restitution: 0.95 },
        ],
        11,
    );
    let inelastic = |rule| EngineParams {
        restitution: rule,
        tc: 1e-4,
        ..EngineParams::default()
    };
    let cases = [
        (
            "periodic monodisperse",
            system(150, 0.45, false, false, 2),
            EngineParams::default(),
        ),
        ("walled mixture", walled, EngineParams::default()),
        (
            "normal restitution e = 0.9",
            system(200, 0.4, false, true, 6),
            inelastic(Restitution::Normal(0.9)),
        ),
        (
            "centre-of-mass restitution R = 0.9",
            system(200, 0.4, false, true, 7),
            inelastic(Restitution::CentreOfMass(0.9)),
        ),
    ];
    for (name, sys, params) in cases {
        let out = tmp("replay.mcap");
        let log = LogOptions {
            snapshot_interval: Some(0.25),
            ..LogOptions::default()
        };
        let mut s = spec(sys, Stop::Time(3.0), log);
        s.params = params;
        run(&s, &out, Control::default()).unwrap();
        let r = replay_with_python(&py, &out);
        eprintln!("{name}: {r}");
        assert_eq!(
            r["schema"], "carom_msgs/msg/CompactCollisionBatch",
            "{name}"
        );
        assert!(r["collisions"].as_u64().unwrap() > 300, "{name}: {r}");
        assert!(
            r["snapshots_checked"].as_u64().unwrap() >= 12,
            "{name}: {r}"
        );
        assert_eq!(r["velocity_mismatches"], 0, "{name}: {r}");
        let err = r["max_position_error"].as_f64().unwrap();
        assert!(err <= 1e-12, "{name}: positions off by {err:e}");
        if name == "walled mixture" {
            assert!(r["walls"].as_u64().unwrap() > 0, "{name}: {r}");
        }
        let _ = std::fs::remove_file(&out);
    }
}
