//! Round trips of `/checkpoint` through CDR, and resumes from decoded ones.

use super::calendar::THERMOSTAT_ENTRY_TAG;
use super::lists::encode_neighbours;
use super::*;
use crate::format::cdr::{CdrError, CdrWriter};
use carom_core::vibrating_wall::Floor;
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_engine::{
    box_size_for, Engine, EngineParams, Event, ListsCheckpoint, Neighbours, Placement, SystemSpec,
    Thermostat, Velocities,
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

/// A checkpoint of a run told to use neighbour lists, with made-up list centres
/// (the codec does not ask the engine whether it could be on them): a −0, a
/// subnormal and a negative coordinate among them, so that bit-exactness shows.
fn on_lists() -> LogCheckpoint {
    let spec = SystemSpec::periodic_fluid(6, 0.3, 8);
    let mut e = Engine::new(spec.build().unwrap(), EngineParams::default()).unwrap();
    e.run_collisions(20).unwrap();
    let mut engine = e.checkpoint();
    engine.params.neighbours = Neighbours::Lists;
    let mut centres: Vec<DVec2> = (0..engine.positions.len())
        .map(|k| DVec2::new(0.375 + k as f64, 1.0 / (k + 3) as f64))
        .collect();
    centres[1] = DVec2::new(-0.0, f64::MIN_POSITIVE / 8.0);
    centres[2].y = -2.5;
    engine.lists = Some(ListsCheckpoint {
        skin: 0.15,
        centres,
    });
    LogCheckpoint {
        driver: DriverState::default(),
        engine,
    }
}

/// The bytes of the neighbour block [`on_lists`] ends with, on their own (its
/// length is that of the tail: the block starts 8-aligned in both).
fn neighbour_block(lc: &LogCheckpoint) -> Vec<u8> {
    let mut w = CdrWriter::new();
    encode_neighbours(
        &mut w,
        lc.engine.params.neighbours,
        lc.engine.lists.as_ref(),
    );
    w.bytes()[4..].to_vec()
}

#[test]
fn a_checkpoint_on_neighbour_lists_round_trips_bit_for_bit() {
    let lc = on_lists();
    let (bytes, back) = round_trip(&lc);
    let mut w2 = CdrWriter::new();
    back.encode(&mut w2);
    assert_eq!(bytes, w2.bytes());
    let lists = back.engine.lists.unwrap();
    assert_eq!(lists.centres[1].x.to_bits(), (-0.0f64).to_bits());
    assert_eq!(back.engine.params.neighbours, Neighbours::Lists);
    assert!(bytes.ends_with(&neighbour_block(&lc)));
    // The setting alone (the cell path) round-trips too, with no lists.
    for neighbours in [Neighbours::Auto, Neighbours::Cells, Neighbours::Lists] {
        let mut cells = on_lists();
        cells.engine.params.neighbours = neighbours;
        cells.engine.lists = None;
        let (_, back) = round_trip(&cells);
        assert_eq!(back.engine.params.neighbours, neighbours);
    }
}

/// A checkpoint of format 5 (before the neighbour search) reads with the
/// setting auto and no lists: the run resumes on cells.
#[test]
fn a_format_5_checkpoint_reads_without_lists() {
    let lc = on_lists();
    let mut w = CdrWriter::new();
    lc.encode(&mut w);
    let bytes = w.bytes();
    let mut old = bytes[..bytes.len() - neighbour_block(&lc).len()].to_vec();
    old[4..8].copy_from_slice(&5u32.to_le_bytes());
    let back = LogCheckpoint::decode(&old).unwrap();
    let mut want = lc;
    want.engine.params.neighbours = Neighbours::Auto;
    want.engine.lists = None;
    assert_eq!(back, want);
    // Without the version's bump the same bytes are a truncated format 6.
    old[4..8].copy_from_slice(&CHECKPOINT_FORMAT_VERSION.to_le_bytes());
    assert!(matches!(
        LogCheckpoint::decode(&old),
        Err(CdrError::Truncated {
            field: "neighbours",
            ..
        })
    ));
}

/// Neighbour data no engine writes is refused, naming the field and saying
/// what is allowed.
#[test]
fn bad_neighbour_data_is_refused_naming_the_field() {
    type Spoil = fn(&mut ListsCheckpoint);
    let cases: [(Spoil, &str, &str); 7] = [
        (
            |l| l.centres.truncate(5),
            "lists_centre_x",
            "5 list centres for 6 discs",
        ),
        (
            |l| l.centres.push(DVec2::ZERO),
            "lists_centre_x",
            "7 list centres for 6 discs",
        ),
        (
            |l| l.skin = f64::NAN,
            "lists_skin",
            "skin NaN (allowed: 0 on the cell grid",
        ),
        (|l| l.skin = f64::INFINITY, "lists_skin", "skin inf"),
        (|l| l.skin = -0.25, "lists_skin", "skin -0.25"),
        (
            |l| l.centres[3].x = f64::NEG_INFINITY,
            "lists_centre_x",
            "slot 3 is -inf",
        ),
        (
            |l| l.centres[4].y = f64::NAN,
            "lists_centre_y",
            "slot 4 is NaN",
        ),
    ];
    let refused = |lc: &LogCheckpoint| {
        let mut w = CdrWriter::new();
        lc.encode(&mut w);
        match LogCheckpoint::decode(w.bytes()) {
            Err(CdrError::Invalid { field, problem }) => (field, problem),
            other => panic!("accepted: {other:?}"),
        }
    };
    for (spoil, field, says) in cases {
        let mut lc = on_lists();
        spoil(lc.engine.lists.as_mut().unwrap());
        let (f, problem) = refused(&lc);
        assert_eq!(f, field, "{problem}");
        assert!(problem.contains(says), "{problem}");
    }
    // Centres with skin 0 (which means the cell grid).
    let mut lc = on_lists();
    lc.engine.lists.as_mut().unwrap().skin = 0.0;
    let (f, problem) = refused(&lc);
    assert_eq!(f, "lists_centre_x");
    assert!(
        problem.contains("6 list centres, but `lists_skin` is 0"),
        "{problem}"
    );
    // An unknown setting: "lists" spelt "lisps" in the bytes.
    let lc = on_lists();
    let mut w = CdrWriter::new();
    lc.encode(&mut w);
    let mut bytes = w.bytes().to_vec();
    let name = bytes.len() - neighbour_block(&lc).len() + 4;
    assert_eq!(&bytes[name..name + 6], b"lists\0");
    bytes[name + 3] = b'p';
    match LogCheckpoint::decode(&bytes) {
        Err(CdrError::Invalid { field, problem }) => {
            assert_eq!(field, "neighbours");
            assert_eq!(
                problem,
                "unknown setting \"lisps\" (allowed: auto, cells, lists)"
            );
        }
        other => panic!("accepted: {other:?}"),
    }
}
