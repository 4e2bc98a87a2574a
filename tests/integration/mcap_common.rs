//! Shared helpers of the MCAP log tests: small systems, temporary paths, and a
//! bare-engine reference trajectory.
#![allow(dead_code)]

use carom_core::{Boundary, DVec2, Species};
use carom_engine::{Engine, EngineParams, Event, SystemSpec};
use carom_log::{LogOptions, RunSpec, Stop};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

pub use crate::readers_common::{node_with, python_with};

/// A fresh path under Cargo's per-test temporary directory.
pub fn tmp(name: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let k = N.fetch_add(1, Ordering::Relaxed);
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "{}-{}-{k}-{name}",
        std::process::id(),
        module_path!().replace("::", "_")
    ))
}

/// N discs of diameter 1 (plus a few heavy ones when `mixture`) at packing `eta`,
/// periodic in x; walls in y when `walls`.
pub fn system(n: usize, eta: f64, walls: bool, mixture: bool, seed: u64) -> SystemSpec {
    let mut species = vec![Species::reference(n)];
    if mixture {
        species[0].count = n - n / 5;
        species.push(Species::new(n / 5, 0.7, 3.0));
    }
    let y = if walls {
        Boundary::Walls { restitution: 1.0 }
    } else {
        Boundary::Periodic
    };
    SystemSpec::square_box(species, eta, [Boundary::Periodic, y], seed)
}

/// A run description around `system`.
pub fn spec(system: SystemSpec, stop: Stop, log: LogOptions) -> RunSpec {
    RunSpec {
        config_json: format!("{{\"test\": true, \"seed\": {}}}", system.seed),
        thermostat: None,
        system,
        params: EngineParams::default(),
        stop,
        max_time_without_collision: None,
        log,
    }
}

/// `carom.run` metadata for a log written directly with a `LogWriter` in a test.
pub fn test_run_metadata(n_discs: u64) -> carom_log::RunMetadata {
    carom_log::RunMetadata {
        log_format: carom_log::LOG_FORMAT_VERSION.into(),
        carom_version: "test".into(),
        config: "{}".into(),
        seed: 1,
        start_time: "2024-01-01T00:00:00.000Z".into(),
        n_discs,
        stop: Stop::Time(1.0),
        max_time_without_collision: None,
        log: LogOptions::default(),
        resumed_from: None,
        resumed_at: None,
        run_facts: None,
    }
}

/// Every collision of a bare engine (no log) up to and including time `t_end`.
pub fn reference_collisions(
    system: &SystemSpec,
    params: EngineParams,
    t_end: f64,
) -> (Vec<Event>, Engine) {
    let mut e = Engine::new(system.build().unwrap(), params).unwrap();
    e.schedule(t_end, u64::MAX).unwrap();
    let mut out = Vec::new();
    while let Some(ev) = e.next_event().unwrap() {
        match ev {
            Event::Scheduled { tag: u64::MAX, .. } => break,
            Event::Scheduled { .. } => {}
            ev => out.push(ev),
        }
    }
    (out, e)
}

/// Bit patterns of a list of vectors (exact comparison, -0.0 ≠ 0.0).
pub fn bits(v: &[DVec2]) -> Vec<u64> {
    v.iter()
        .flat_map(|p| [p.x.to_bits(), p.y.to_bits()])
        .collect()
}

/// The Python interpreter with `mcap` and `mcap-ros2-support`, or `None` to skip
/// (a failure under `CI`: [`skip_or_fail`]).
pub fn python() -> Option<String> {
    python_with(&["mcap", "mcap_ros2.decoder"])
}

/// Run the helper script on `path` and parse its JSON.
pub fn read_with_python(py: &str, path: &Path, streaming: bool) -> Value {
    python_reader(py, path, if streaming { &["--streaming"] } else { &[] })
}

/// Run `tests/python/read_carom_log.py` on `path` with `flags` (`--streaming`,
/// `--fields`) and parse its JSON.
pub fn python_reader(py: &str, path: &Path, flags: &[&str]) -> Value {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/python/read_carom_log.py");
    let out = Command::new(py)
        .arg(script)
        .arg(path)
        .args(flags)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "python reader failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("python prints JSON")
}

/// `@mcap/core`'s stream reader on `path`, or `None` to skip (a failure under
/// `CI`: [`skip_or_fail`]).
pub fn node_read(path: &Path) -> Option<Value> {
    let dir = node_with("@mcap/core")?;
    let out = Command::new("node")
        .arg(dir.join("read.mjs"))
        .arg(path)
        .output()
        .expect("node runs");
    assert!(
        out.status.success(),
        "@mcap/core rejects {}:\n{}",
        path.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    Some(serde_json::from_slice(&out.stdout).expect("read.mjs prints JSON"))
}

/// Whether a logged collision is the engine's event `ev`: time, discs and every
/// velocity bit for bit; the normal, virial and energy lost equal in a full
/// record and to rounding (1e-12 relative) in a replayed compact one, which
/// derives them (docs/log-format.md); a compact record's impulse bit for bit
/// (a full record has none for a pair).
pub fn same_as_engine(rec: &carom_log::CollisionRecord, ev: &Event) -> bool {
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1e-300);
    let near = |a: DVec2, b: DVec2| (a - b).length() <= 1e-12 * a.length().max(1.0);
    let (p, impulse) = match ev {
        Event::Pair(p) => match rec.as_pair() {
            Some(_) => (*p, p.impulse),
            None => return false,
        },
        Event::Wall(w) => match rec.as_wall() {
            Some(_) => {
                let c = carom_log::CollisionRecord::from_wall(w, rec.ordinal);
                (c.collision, w.impulse_vector())
            }
            None => return false,
        },
        Event::Scheduled { .. } | Event::Pause { .. } => return false,
    };
    let c = &rec.collision;
    let exact = bits(&[c.vi_before, c.vj_before, c.vi_after, c.vj_after])
        == bits(&[p.vi_before, p.vj_before, p.vi_after, p.vj_after])
        && (c.time.to_bits(), c.i, c.j) == (p.time.to_bits(), p.i, p.j);
    // A full record stores no pair impulse (zero); a wall's follows from |Δp|.
    let compact = c.impulse != DVec2::ZERO && rec.kind == carom_log::KIND_PAIR;
    exact
        && (rec.kind == carom_log::KIND_PAIR || c.impulse == impulse)
        && if compact {
            bits(&[c.impulse]) == bits(&[impulse])
                && near(c.normal, p.normal)
                && close(c.virial, p.virial)
                && (c.energy_lost - p.energy_lost).abs()
                    <= 1e-12
                        * (c.vi_before.length_squared() + c.vj_before.length_squared() + 1e-300)
        } else {
            (c.normal, c.virial, c.energy_lost) == (p.normal, p.virial, p.energy_lost)
        }
}
