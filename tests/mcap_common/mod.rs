//! Shared helpers of the MCAP log tests: small systems, temporary paths, and a
//! bare-engine reference trajectory.
#![allow(dead_code)]

use carom::core::{Boundary, DVec2, SimBox, Species};
use carom::events::{box_size_for, Engine, EngineParams, Event, Placement, SystemSpec, Velocities};
use carom::io::{LogOptions, RunSpec, Stop};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

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
    let mut species = vec![Species {
        count: n,
        radius: 0.5,
        mass: 1.0,
    }];
    if mixture {
        species[0].count = n - n / 5;
        species.push(Species {
            count: n / 5,
            radius: 0.7,
            mass: 3.0,
        });
    }
    let size = box_size_for(&species, eta, 1.0);
    SystemSpec {
        species,
        sim_box: SimBox {
            size,
            boundary: [
                Boundary::Periodic,
                if walls {
                    Boundary::Walls { restitution: 1.0 }
                } else {
                    Boundary::Periodic
                },
            ],
        },
        temperature: 1.0,
        seed,
        placement: Placement::Lattice,
        velocities: Velocities::MaxwellBoltzmann,
    }
}

/// A run description around `system`.
pub fn spec(system: SystemSpec, stop: Stop, log: LogOptions) -> RunSpec {
    RunSpec {
        config_json: format!("{{\"test\": true, \"seed\": {}}}", system.seed),
        system,
        params: EngineParams::default(),
        stop,
        log,
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
