//! Round trips of `/checkpoint` through CDR, and resumes from decoded ones.

use super::calendar::THERMOSTAT_ENTRY_TAG;
use super::*;
use crate::format::cdr::CdrWriter;
use carom_core::vibrating_wall::Floor;
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_engine::{
    box_size_for, Engine, EngineParams, Event, Placement, SystemSpec, Thermostat, Velocities,
};

#[test]
fn checkpoint_round_trips_bit_for_bit() {
    let species = vec![Species::reference(40), Species::new(10, 0.8, 3.0)];
    let size = box_size_for(&species, 0.4, 1.0);
    let spec = SystemSpec {
        species,
        sim_box: SimBox {
            size,
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 0.9 }],
        },
        temperature: 1.0,
        seed: 3,
        placement: Placement::Lattice,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let params = EngineParams {
        restitution: Restitution::Normal(0.95),
        tc: 1e-4,
        max_events_without_time_advance: 1000,
        ..EngineParams::default()
    };
    let mut e = Engine::new(spec.build().unwrap(), params).unwrap();
    e.run_collisions(500).unwrap();
    e.schedule(e.now() + 1.0, 42).unwrap();
    let lc = LogCheckpoint {
        driver: DriverState {
            run_start_time: 0.0,
            logged_collisions: 250,
            next_sequence: [1, 2, 3, 4],
        },
        engine: e.checkpoint(),
    };
    let (bytes, back) = round_trip(&lc);
    // PartialEq on f64 would accept -0.0 == 0.0; compare the encodings too.
    let mut w2 = CdrWriter::new();
    back.encode(&mut w2);
    assert_eq!(bytes, w2.bytes());
    // Truncations are clean errors.
    for cut in [0, 3, 4, 10, 100, bytes.len() - 1] {
        assert!(LogCheckpoint::decode(&bytes[..cut]).is_err());
    }
}

/// `lc` encoded, and decoded back equal to it: (the bytes, the decoded checkpoint).
fn round_trip(lc: &LogCheckpoint) -> (Vec<u8>, LogCheckpoint) {
    let mut w = CdrWriter::new();
    lc.encode(&mut w);
    let back = LogCheckpoint::decode(w.bytes()).unwrap();
    assert_eq!(&back, lc);
    (w.bytes().to_vec(), back)
}

/// A shaken bed's checkpoint (gravity, vibrating floor) round-trips with the
/// floor, its phase origin and its work, and resumes into the same engine.
#[test]
fn a_checkpoint_with_a_vibrating_floor_round_trips() {
    let species = vec![Species::reference(60)];
    let spec = SystemSpec {
        species,
        sim_box: SimBox {
            size: DVec2::new(12.0, 30.0),
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 0.9 }],
        },
        temperature: 1.0,
        seed: 4,
        placement: Placement::Random,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let params = EngineParams {
        restitution: Restitution::Normal(0.9),
        tc: 1e-4,
        gravity: 1.0,
        floor: Some(Floor {
            amplitude: 0.4,
            omega: 3.0,
        }),
        ..EngineParams::default()
    };
    let mut e = Engine::new(spec.build().unwrap(), params).unwrap();
    e.run_collisions(3_000).unwrap();
    assert!(e.stats().floor_work != 0.0);
    let lc = LogCheckpoint {
        driver: DriverState {
            run_start_time: 0.0,
            logged_collisions: 3_000,
            next_sequence: [1, 2, 3, 4],
        },
        engine: e.checkpoint(),
    };
    let (_, back) = round_trip(&lc);
    let mut b = Engine::from_checkpoint(back.engine).unwrap();
    for _ in 0..2_000 {
        assert_eq!(e.next_event().unwrap(), b.next_event().unwrap());
    }
}

/// A run with a driven thermostat (kicks every 0.25) and the caller's events at
/// kick times, one with the tag the thermostat's entry is stored with, stopped
/// between kicks.
fn thermostatted() -> Engine {
    let spec = SystemSpec::periodic_fluid(150, 0.3, 9);
    let mut e = Engine::new(spec.build().unwrap(), EngineParams::default()).unwrap();
    let driven = Thermostat::Driven {
        xi2: 0.1,
        interval: 0.25,
    };
    e.set_thermostat(Some(driven), 9).unwrap();
    for (k, tag) in [(1, 7), (3, 8), (3, THERMOSTAT_ENTRY_TAG), (12, 9)] {
        e.schedule(0.25 * k as f64, tag).unwrap();
    }
    e.run_until(0.6).unwrap();
    e
}

/// The next `n` events of `a` and `b` (pauses left out) are the same.
fn same_events(a: &mut Engine, b: &mut Engine, n: usize) {
    let next = |e: &mut Engine| loop {
        match e.next_event().unwrap().unwrap() {
            Event::Pause { .. } => {}
            ev => return ev,
        }
    };
    for _ in 0..n {
        assert_eq!(next(a), next(b));
    }
}

/// The thermostat's next event and the caller's (even with the tag it is stored
/// with) round-trip apart, and the run resumes from the decoded checkpoint bit
/// for bit.
#[test]
fn a_thermostatted_checkpoint_round_trips_and_resumes() {
    let mut a = thermostatted();
    let lc = LogCheckpoint {
        driver: DriverState::default(),
        engine: a.checkpoint(),
    };
    let tags: Vec<u64> = lc.engine.scheduled.iter().map(|s| s.2).collect();
    assert_eq!(tags, [8, THERMOSTAT_ENTRY_TAG, 9]);
    assert_eq!(lc.engine.thermostat.unwrap().next.unwrap().0, 0.75);
    let (_, back) = round_trip(&lc);
    let mut b = Engine::from_checkpoint(back.engine).unwrap();
    same_events(&mut a, &mut b, 3_000);
    assert_eq!(a.checkpoint(), b.checkpoint());
}

/// A checkpoint as written before log format 2.5 — the thermostat's next event
/// among the caller's in time order, with its reserved tag — reads back with
/// that event apart and resumes bit for bit.
#[test]
fn a_checkpoint_of_the_older_order_resumes_bit_identically() {
    let mut cp = thermostatted().checkpoint();
    // Older carom refused the caller's events with the reserved tag.
    cp.scheduled.retain(|s| s.2 != THERMOSTAT_ENTRY_TAG);
    let mut a_old = Engine::from_checkpoint(cp.clone()).unwrap();
    let (t, seq) = cp.thermostat.unwrap().next.unwrap();
    let mut old: Vec<(f64, u64, u64)> = cp.scheduled.clone();
    old.push((t, seq, THERMOSTAT_ENTRY_TAG));
    old.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    assert!(
        old.last().unwrap().2 != THERMOSTAT_ENTRY_TAG,
        "not the older order"
    );
    let lc = LogCheckpoint {
        driver: DriverState::default(),
        engine: cp,
    };
    let mut w = CdrWriter::new();
    lc.encode_with(&mut w, &old);
    let back = LogCheckpoint::decode(w.bytes()).unwrap();
    assert_eq!(back, lc);
    let mut b = Engine::from_checkpoint(back.engine).unwrap();
    same_events(&mut a_old, &mut b, 3_000);
    assert_eq!(a_old.checkpoint(), b.checkpoint());
}
