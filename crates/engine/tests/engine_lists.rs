//! The neighbour-list path (engine::listed) against the cell path and the
//! invariants: the same events up to rounding, energy and no overlap, the
//! choice of path, bit-identical resume through renumberings, and the return to
//! cells when a list overflows. The brute-force reference runs on lists in
//! engine_reference.rs, the 400 random systems in engine_random.rs.

use carom_core::{Boundary, Restitution, SimBox, Species};
use carom_engine::{
    Engine, EngineError, EngineParams, Event, InvariantChecker, Neighbours, Placement, State,
    SystemSpec, Thermostat, Velocities,
};

fn params(neighbours: Neighbours) -> EngineParams {
    EngineParams {
        neighbours,
        ..EngineParams::default()
    }
}

fn fluid(n: usize, eta: f64, seed: u64, boundary: [Boundary; 2]) -> State {
    let mut spec = SystemSpec::periodic_fluid(n, eta, seed);
    spec.sim_box.boundary = boundary;
    spec.build().expect("a valid system")
}

const PERIODIC: [Boundary; 2] = [Boundary::Periodic, Boundary::Periodic];
const WALLED: [Boundary; 2] = [
    Boundary::Walls { restitution: 1.0 },
    Boundary::Walls { restitution: 1.0 },
];
const CHANNEL: [Boundary; 2] = [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }];

/// The bits of every position and velocity and of the time.
fn fingerprint(s: &State) -> Vec<u64> {
    let mut out = vec![s.time.to_bits()];
    for (r, v) in s.positions.iter().zip(&s.velocities) {
        out.extend([r.x.to_bits(), r.y.to_bits(), v.x.to_bits(), v.y.to_bits()]);
    }
    out
}

/// The discs and time of an event (pair: both discs; wall: the disc).
fn key(e: &Event) -> (u32, u32, f64) {
    match e {
        Event::Pair(p) => (p.i.min(p.j), p.i.max(p.j), p.time),
        Event::Wall(w) => (w.i, u32::MAX, w.time),
        other => panic!("unexpected {other:?}"),
    }
}

/// The first `n` events of `e`, in groups of events at one instant (times
/// within 1e-9 of the group's first): the discs of each group sorted, and the
/// group's time. Ties (a lattice start has many) are broken by internal index,
/// which follows each path's own grid, so only their set is compared.
fn groups(e: &mut Engine, n: usize) -> Vec<(Vec<(u32, u32)>, f64)> {
    let mut out: Vec<(Vec<(u32, u32)>, f64)> = Vec::new();
    for _ in 0..n {
        let (i, j, t) = key(&e.next_event().unwrap().unwrap());
        match out.last_mut() {
            Some((discs, t0)) if (t - *t0).abs() <= 1e-9 * (1.0 + t) => discs.push((i, j)),
            _ => out.push((vec![(i, j)], t)),
        }
    }
    out.pop(); // may be cut short
    for (discs, _) in &mut out {
        discs.sort_unstable();
    }
    out
}

/// From the same state, lists and cells report the same first events: the same
/// discs at times equal to 1e-9 (the two paths compute the same contact times
/// at different instants, so they differ in the last bits, and chaos amplifies
/// that only after many collisions per disc).
#[test]
fn lists_and_cells_give_the_same_events() {
    for (boundary, name) in [
        (PERIODIC, "periodic"),
        (WALLED, "walled"),
        (CHANNEL, "channel"),
    ] {
        for eta in [0.5, 0.7] {
            let state = fluid(400, eta, 5, boundary);
            let mut cells = Engine::new(state.clone(), params(Neighbours::Cells)).unwrap();
            let mut lists = Engine::new(state, params(Neighbours::Lists)).unwrap();
            assert!(!cells.neighbour_lists() && lists.neighbour_lists());
            let (a, b) = (groups(&mut cells, 400), groups(&mut lists, 400));
            assert!(a.len() > 50, "{name} η = {eta}: {} instants", a.len());
            for (k, (x, y)) in a.iter().zip(&b).enumerate() {
                assert_eq!(x.0, y.0, "{name} η = {eta}: instant {k}");
                assert!(
                    (x.1 - y.1).abs() <= 1e-9 * (1.0 + x.1),
                    "{name} η = {eta}: instant {k} at {} and {}",
                    x.1,
                    y.1
                );
            }
        }
    }
}

/// A long dense run on lists (N = 1000, η = 0.72, 2·10⁵ collisions, through
/// twelve renumberings) conserves energy and momentum to 1e-12 and never lets
/// two discs overlap, elastic; with an inelastic rule under the TC model it
/// loses energy and still never overlaps. Periodic, walled and channel boxes.
#[test]
fn a_long_dense_run_on_lists_keeps_every_invariant() {
    for boundary in [PERIODIC, WALLED, CHANNEL] {
        let state = fluid(1000, 0.72, 9, boundary);
        let mut e = Engine::new(state, params(Neighbours::Auto)).unwrap();
        assert!(e.neighbour_lists(), "auto chooses lists at η = 0.72");
        let mut checker = InvariantChecker::new(&e);
        for _ in 0..20 {
            e.run_collisions(10_000).unwrap();
            checker.check(&e).unwrap();
        }
        assert!(e.neighbour_lists(), "no list overflowed");
        assert!(e.stats().cell_crossings > 0, "discs left their skins");
    }
    let state = fluid(1000, 0.7, 4, PERIODIC);
    let p = EngineParams {
        restitution: Restitution::Normal(0.8),
        tc: 1e-3,
        ..params(Neighbours::Lists)
    };
    let mut e = Engine::new(state, p).unwrap();
    let k0 = e.kinetic_energy();
    let mut checker = InvariantChecker::new(&e);
    e.run_collisions(50_000).unwrap();
    checker.check_overlaps(&e).unwrap();
    assert!(e.kinetic_energy() < 0.5 * k0 && e.kinetic_energy() > 0.0);
    let lost = k0 - e.kinetic_energy();
    assert!(
        (lost - e.stats().energy_lost).abs() < 1e-9 * k0,
        "the totals say what was lost"
    );
}

/// A checkpoint on lists stores the centres; an engine restored from it is on
/// lists and continues bit for bit, through renumberings (every 16 N
/// collisions), with the periodic images of the discs.
#[test]
fn a_run_on_lists_resumes_bit_identically() {
    for boundary in [PERIODIC, CHANNEL] {
        let mut a = Engine::new(fluid(500, 0.7, 3, boundary), params(Neighbours::Auto)).unwrap();
        a.run_collisions(7_777).unwrap();
        let cp = a.checkpoint();
        assert_eq!(cp.lists.as_ref().map(|l| l.centres.len()), Some(500));
        let mut b = Engine::from_checkpoint(cp).unwrap();
        assert!(b.neighbour_lists());
        for _ in 0..4 {
            a.run_collisions(10_000).unwrap();
            b.run_collisions(10_000).unwrap();
            assert_eq!(fingerprint(&a.state()), fingerprint(&b.state()));
            assert_eq!(a.state().images, b.state().images);
        }
        // The same configuration and seed give the same trajectory.
        let mut c = Engine::new(fluid(500, 0.7, 3, boundary), params(Neighbours::Auto)).unwrap();
        c.run_collisions(47_777).unwrap();
        assert_eq!(fingerprint(&a.state()), fingerprint(&c.state()));
    }
}

/// A checkpoint whose centres do not fit its discs is refused, naming the lists.
#[test]
fn a_checkpoint_with_bad_centres_is_refused() {
    let mut a = Engine::new(fluid(400, 0.7, 3, PERIODIC), params(Neighbours::Lists)).unwrap();
    a.run_collisions(1000).unwrap();
    let good = a.checkpoint();
    let mut cp = good.clone();
    cp.lists.as_mut().unwrap().centres[7].x += 0.5;
    let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
    assert!(
        err.contains("lists: disc 7") && err.contains("skin"),
        "{err}"
    );
    let mut cp = good.clone();
    cp.lists.as_mut().unwrap().centres.pop();
    let err = Engine::from_checkpoint(cp).unwrap_err().to_string();
    assert!(err.contains("399 centres for 400 discs"), "{err}");
    let mut cp = good;
    cp.lists.as_mut().unwrap().skin = f64::NAN;
    assert!(Engine::from_checkpoint(cp).is_err());
}

/// Auto chooses lists for dense equal discs flying straight and cells
/// otherwise; lists asked for where they cannot be used are refused with why.
#[test]
fn the_path_is_chosen_from_the_configuration() {
    let on = |state: State, p: EngineParams| Engine::new(state, p).map(|e| e.neighbour_lists());
    assert_eq!(
        on(fluid(400, 0.7, 1, PERIODIC), params(Neighbours::Auto)),
        Ok(true)
    );
    assert_eq!(
        on(fluid(400, 0.5, 1, PERIODIC), params(Neighbours::Auto)),
        Ok(false)
    );
    assert_eq!(
        on(fluid(400, 0.5, 1, PERIODIC), params(Neighbours::Lists)),
        Ok(true)
    );
    assert_eq!(
        on(fluid(400, 0.7, 1, PERIODIC), params(Neighbours::Cells)),
        Ok(false)
    );
    // In a field: cells, and lists refused.
    let walled = fluid(400, 0.7, 1, WALLED);
    let g = |n| EngineParams {
        gravity: 1.0,
        ..params(n)
    };
    assert_eq!(on(walled.clone(), g(Neighbours::Auto)), Ok(false));
    let err = Engine::new(walled, g(Neighbours::Lists)).unwrap_err();
    assert!(matches!(err, EngineError::ListsRefused(_)), "{err}");
    assert!(err.to_string().contains("gravity"), "{err}");
    // A box too narrow for three list cells (16 discs at η = 0.7: L ≈ 4.2).
    let err = Engine::new(fluid(16, 0.7, 1, PERIODIC), params(Neighbours::Lists)).unwrap_err();
    assert!(
        err.to_string().contains("fewer than three list cells"),
        "{err}"
    );
    assert_eq!(
        on(fluid(16, 0.7, 1, PERIODIC), params(Neighbours::Auto)),
        Ok(false)
    );
    // A mixture whose sizes need a grid each.
    let species = vec![Species::new(2000, 0.5, 1.0), Species::new(10, 5.0, 100.0)];
    let spec = SystemSpec {
        species,
        sim_box: SimBox::periodic(120.0, 120.0),
        temperature: 1.0,
        seed: 1,
        placement: Placement::Random,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let state = spec.build().unwrap();
    let e = Engine::new(state.clone(), params(Neighbours::Cells)).unwrap();
    assert!(e.grid_count() > 1);
    let err = Engine::new(state, params(Neighbours::Lists)).unwrap_err();
    assert!(err.to_string().contains("mixture"), "{err}");
}

/// A list that would pass its capacity sends the run back to cells for good,
/// deterministically, with every invariant kept: small discs sharing one grid
/// with a few large ones (lists sized for the large contact distance) crowd
/// their lists.
#[test]
fn an_overflowing_list_sends_the_run_back_to_cells() {
    let species = vec![Species::new(600, 0.2, 1.0), Species::new(8, 0.5, 2.0)];
    let spec = SystemSpec {
        species,
        sim_box: SimBox::periodic(33.0, 33.0),
        temperature: 1.0,
        seed: 2,
        placement: Placement::Relaxed,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let state = spec.build().unwrap();
    let run = || {
        let mut e = Engine::new(state.clone(), params(Neighbours::Lists)).unwrap();
        assert_eq!(e.grid_count(), 1);
        let started = e.neighbour_lists();
        let mut checker = InvariantChecker::new(&e);
        let mut left_at = None;
        for k in 0..60 {
            e.run_collisions(1000).unwrap();
            checker.check(&e).unwrap();
            if left_at.is_none() && !e.neighbour_lists() {
                left_at = Some(k);
            }
        }
        (started, left_at, fingerprint(&e.state()))
    };
    let (started, left_at, a) = run();
    assert!(started, "lists at the start");
    assert!(left_at.is_some(), "a list overflowed");
    let (_, left_again, b) = run();
    assert_eq!((left_at, a), (left_again, b), "deterministic");
}

/// Thermostats change velocities between collisions: on lists each redraw or kick
/// predicts the disc again over its list (the skin exit moves with v). Andersen
/// at kT = 2 on a dense fluid at kT = 1, and driving on a cooling granular one:
/// no overlap, on lists throughout, and the kinetic energy is the start's plus
/// what the thermostat added less what the collisions took.
#[test]
fn thermostats_act_on_lists() {
    for (thermostat, restitution) in [
        (
            Thermostat::Andersen { kt: 2.0, rate: 0.5 },
            Restitution::Elastic,
        ),
        (
            Thermostat::Driven {
                xi2: 1.0,
                interval: 0.01,
            },
            Restitution::Normal(0.9),
        ),
    ] {
        let p = EngineParams {
            restitution,
            ..params(Neighbours::Auto)
        };
        let mut e = Engine::new(fluid(900, 0.7, 8, PERIODIC), p).unwrap();
        e.set_thermostat(Some(thermostat), 3).unwrap();
        let k0 = e.kinetic_energy();
        let mut checker = InvariantChecker::new(&e);
        e.run_until(4.0).unwrap();
        checker.check_overlaps(&e).unwrap();
        assert!(e.neighbour_lists());
        // The energy balance: what the thermostat added less what collisions took.
        let added = e.thermostat_stats().energy_added;
        let balance = k0 + added - e.stats().energy_lost;
        assert!(added > 0.0, "{thermostat:?}");
        assert!(
            (e.kinetic_energy() - balance).abs() < 1e-9 * (k0 + added),
            "{thermostat:?}: K = {}, K0 + added − lost = {balance}",
            e.kinetic_energy()
        );
    }
}
