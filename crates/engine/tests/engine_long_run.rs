//! A long elastic run at η = 0.5 (N = 1000 monodisperse discs, periodic square box,
//! lattice start, Maxwell–Boltzmann velocities at kT = 1) keeps every invariant, and
//! is reproducible bit for bit.
//!
//! * Every event: the clock never decreases and equals the event's time.
//! * Every 10⁴ collisions: `InvariantChecker::check_conservation` — kinetic energy
//!   within 1e-12 relative of the start, momentum within 1e-12 of Σ m|v| (the
//!   checker's defaults; MB start has zero total momentum, so this is absolute drift).
//! * Every 10⁵ collisions and at the end: `InvariantChecker::check_overlaps` — no pair
//!   overlaps by more than 1e-10 of its contact distance.
//! * Reproducibility: the same seed run again (without the checks, through
//!   `run_collisions`, i.e. with different observation) ends in a state whose
//!   positions, velocities and time have identical bits; a different seed ends
//!   elsewhere.
//!
//! Two sizes: 10⁶ collisions (≈ 1.5 s) and the 10⁷ (≈ 14–30 s in the test
//! profile on 2 cores). Both are in the default suite. (The 10⁷ run caught a
//! systematic energy drift from normalising the contact normal before the
//! collision rule; see `carom_core::collision`.)

use carom_engine::{Engine, EngineParams, Event, InvariantChecker, State, SystemSpec};

const N: usize = 1000;
const ETA: f64 = 0.5;

fn initial_state(seed: u64) -> State {
    SystemSpec::periodic_fluid(N, ETA, seed)
        .build()
        .expect("a valid η = 0.5 system")
}

/// The bits of every position and velocity and of the time.
fn fingerprint(s: &State) -> Vec<u64> {
    let mut out = vec![s.time.to_bits()];
    for (r, v) in s.positions.iter().zip(&s.velocities) {
        out.extend([r.x.to_bits(), r.y.to_bits(), v.x.to_bits(), v.y.to_bits()]);
    }
    out
}

/// Run `collisions` collisions from seed `seed` with every check; return the final
/// state and the state after `snapshot_at` collisions.
fn checked_run(seed: u64, collisions: u64, snapshot_at: u64) -> (State, State) {
    let state = initial_state(seed);
    assert!((state.packing_fraction() - ETA).abs() < 1e-12);
    let engine = Engine::new(state, EngineParams::default()).expect("engine");
    let (end, snapshot) = checked(engine, collisions, snapshot_at);
    println!("seed {seed}: {collisions} collisions");
    (end, snapshot)
}

/// Run `engine` for `collisions` collisions with every check; return the final
/// state and the state after `snapshot_at` collisions.
fn checked(mut engine: Engine, collisions: u64, snapshot_at: u64) -> (State, State) {
    let mut checker = InvariantChecker::new(&engine);
    let mut last = engine.now();
    let mut done = 0u64;
    let mut snapshot = None;
    // Next collision counts at which to check conservation and overlaps.
    let (mut next_conservation, mut next_overlap) = (10_000u64, 100_000u64);
    while done < collisions {
        let ev = engine
            .next_event()
            .unwrap_or_else(|e| panic!("engine error after {done} collisions: {e}"))
            .unwrap_or_else(|| panic!("no more events after {done} collisions"));
        let t = ev.time();
        assert!(t >= last, "time went backwards: {last} → {t}");
        assert_eq!(engine.now(), t);
        last = t;
        match ev {
            Event::Pair(_) => done += 1,
            Event::Wall(w) => assert!(
                !engine.sim_box().boundary[w.axis.index()].is_periodic(),
                "wall collision on a periodic axis: {w:?}"
            ),
            Event::Scheduled { .. } | Event::Pause { .. } => panic!("nothing was scheduled"),
        }
        if done == next_conservation {
            next_conservation += 10_000;
            checker
                .check_conservation(&engine)
                .unwrap_or_else(|v| panic!("after {done} collisions: {v}"));
        }
        if done == next_overlap {
            next_overlap += 100_000;
            checker
                .check_overlaps(&engine)
                .unwrap_or_else(|v| panic!("after {done} collisions: {v}"));
        }
        if done == snapshot_at {
            snapshot = Some(engine.state());
        }
    }
    checker
        .check(&engine)
        .unwrap_or_else(|v| panic!("at the end: {v}"));
    assert_eq!(engine.stats().pair_collisions, collisions);
    println!(
        "{collisions} collisions to t = {:.3}; max energy drift {:e}, max overlap {:e}",
        engine.now(),
        checker.max_energy_drift,
        checker.max_overlap
    );
    (engine.state(), snapshot.expect("snapshot taken"))
}

/// The same seed without checks, through `run_collisions`.
fn plain_run(seed: u64, collisions: u64) -> State {
    let mut engine = Engine::new(initial_state(seed), EngineParams::default()).expect("engine");
    assert_eq!(engine.run_collisions(collisions).expect("run"), collisions);
    engine.state()
}

fn long_run(collisions: u64) {
    const SNAPSHOT: u64 = 100_000;
    // The checked run and its plain repeat are independent: run them side by side.
    let ((end, snap), repeat, other) = std::thread::scope(|s| {
        let repeat = s.spawn(|| plain_run(1, collisions));
        let other = s.spawn(|| plain_run(2, SNAPSHOT));
        let checked = checked_run(1, collisions, SNAPSHOT);
        (
            checked,
            repeat.join().expect("repeat run"),
            other.join().expect("other seed"),
        )
    });
    assert!(
        fingerprint(&end) == fingerprint(&repeat),
        "the same seed gave a different final state"
    );
    // A different seed: a different trajectory (compare at the same collision count;
    // every disc should be elsewhere, demand at least most of them).
    let same = snap
        .positions
        .iter()
        .zip(&other.positions)
        .filter(|(a, b)| a.x.to_bits() == b.x.to_bits() && a.y.to_bits() == b.y.to_bits())
        .count();
    assert!(
        same < N / 10,
        "seeds 1 and 2 share {same} of {N} positions after {SNAPSHOT} collisions"
    );
    assert_ne!(fingerprint(&snap), fingerprint(&other));
}

#[test]
fn elastic_run_1e6_keeps_invariants_and_is_reproducible() {
    long_run(1_000_000);
}

/// Takes ≈ 14–30 s (depending on load) in the test profile on the 2-core machine
/// (the checked run and its repeat run in parallel threads).
#[test]
fn elastic_run_1e7_keeps_invariants_and_is_reproducible() {
    long_run(10_000_000);
}

/// A mixture of 2000 small discs and 20 of eight times their diameter (η = 0.45, a
/// channel: periodic in x, walls in y), where each size has its own cell grid and
/// every scan also reads the other grid: 10⁶ collisions keep every invariant, and
/// the same start run again ends in the same bits.
#[test]
fn size_classes_keep_invariants_and_are_reproducible() {
    use carom_core::{Boundary, SimBox, Species};
    use carom_engine::{box_size_for, Placement, Velocities};
    let species = vec![Species::reference(2000), Species::new(20, 4.0, 64.0)];
    let spec = SystemSpec {
        sim_box: SimBox {
            size: box_size_for(&species, 0.45, 1.0),
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
        },
        species,
        temperature: 1.0,
        seed: 5,
        placement: Placement::Relaxed,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let state = spec.build().expect("a valid mixture");
    let engine = Engine::new(state.clone(), EngineParams::default()).expect("engine");
    assert_eq!(engine.grid_count(), 2, "a grid per size class");
    const COLLISIONS: u64 = 1_000_000;
    std::thread::scope(|s| {
        let repeat = s.spawn(|| {
            let mut e = Engine::new(state.clone(), EngineParams::default()).expect("engine");
            // Pair collisions only, as `checked` counts them (`run_collisions`
            // counts wall collisions too).
            while e.stats().pair_collisions < COLLISIONS {
                e.next_event().expect("run").expect("an event");
            }
            e.state()
        });
        let (end, _) = checked(engine, COLLISIONS, COLLISIONS / 2);
        let repeat = repeat.join().expect("repeat run");
        assert!(
            fingerprint(&end) == fingerprint(&repeat),
            "the same start gave a different final state"
        );
    });
}
