//! Fetching ahead (the engine's look-ahead) is a speed setting: it only issues
//! prefetch hints, so it must never change a trajectory. By default it is off below
//! 20 000 discs and chosen by timing above, so the systems here switch it on
//! explicitly, and every event of
//! the run (kind, discs, time, velocities, bit for bit) and the final state must be
//! identical with and without it. Periodic and walled boxes, a narrow box (cells
//! seen through two images, where the look-ahead's block wraps), a mixture and an
//! inelastic run with the TC model cover every event kind the look-ahead reads.

use carom_core::{Boundary, Restitution, SimBox, Species};
use carom_engine::{Engine, EngineParams, SystemSpec};

mod engine_common;
use engine_common::{lattice_spec, mono};

/// Run `events` events of `spec` with the look-ahead off and on; panic at the first
/// difference.
fn same_with_and_without(name: &str, spec: SystemSpec, params: EngineParams, events: usize) {
    let state = spec
        .build()
        .unwrap_or_else(|e| panic!("{name}: initial state: {e}"));
    let mut plain = Engine::new(state.clone(), params).expect("engine");
    let mut ahead = Engine::new(state, params).expect("engine");
    plain.set_look_ahead(false);
    ahead.set_look_ahead(true);
    for k in 0..events {
        let a = plain.next_event().expect("no runaway");
        let b = ahead.next_event().expect("no runaway");
        assert_eq!(a, b, "{name}: event {k} differs");
        if a.is_none() {
            break;
        }
    }
    let (sa, sb) = (plain.state(), ahead.state());
    assert_eq!(sa.time.to_bits(), sb.time.to_bits(), "{name}: final time");
    for i in 0..sa.len() {
        for (x, y) in [
            (sa.positions[i].x, sb.positions[i].x),
            (sa.positions[i].y, sb.positions[i].y),
            (sa.velocities[i].x, sb.velocities[i].x),
            (sa.velocities[i].y, sb.velocities[i].y),
        ] {
            assert_eq!(x.to_bits(), y.to_bits(), "{name}: disc {i} differs");
        }
    }
    let s = ahead.stats();
    assert!(
        s.pair_collisions > 0 && s.cell_crossings > 0 && s.stale_events > 0,
        "{name}: every event kind must be exercised: {s:?}"
    );
}

#[test]
fn periodic_fluids_are_unchanged() {
    for (n, eta, seed) in [(2000, 0.5, 11), (1500, 0.7, 12), (400, 0.2, 13)] {
        same_with_and_without(
            &format!("periodic N = {n}, eta = {eta}"),
            SystemSpec::periodic_fluid(n, eta, seed),
            EngineParams::default(),
            100_000,
        );
    }
}

#[test]
fn walled_mixture_is_unchanged() {
    let species = vec![Species::new(300, 0.4, 1.0), Species::new(100, 0.8, 3.0)];
    let s = lattice_spec(species, SimBox::walled(40.0, 25.0, 0.95), 14);
    same_with_and_without("walled mixture", s, EngineParams::default(), 60_000);
}

#[test]
fn narrow_periodic_channel_is_unchanged() {
    // Two cells across along x (the block wraps onto itself), walls along y.
    let mut b = SimBox::walled(2.4, 40.0, 1.0);
    b.boundary[0] = Boundary::Periodic;
    same_with_and_without(
        "channel 2.4 wide",
        lattice_spec(mono(40), b, 15),
        EngineParams::default(),
        60_000,
    );
}

#[test]
fn inelastic_tc_run_is_unchanged() {
    let params = EngineParams {
        restitution: Restitution::Normal(0.9),
        tc: 1e-3,
        ..EngineParams::default()
    };
    same_with_and_without(
        "inelastic N = 1000, eta = 0.3",
        SystemSpec::periodic_fluid(1000, 0.3, 16),
        params,
        60_000,
    );
}

#[test]
fn look_ahead_is_on_only_for_large_systems() {
    let small = Engine::new(
        SystemSpec::periodic_fluid(10_000, 0.5, 1).build().unwrap(),
        EngineParams::default(),
    )
    .unwrap();
    assert!(!small.look_ahead_enabled());
    let large = Engine::new(
        SystemSpec::periodic_fluid(200_000, 0.5, 1).build().unwrap(),
        EngineParams::default(),
    )
    .unwrap();
    assert!(large.look_ahead_enabled());
}

/// From 20 000 discs on the event loop times windows of 2¹⁶ events: the first
/// window runs on the first guess (off below 170 000 discs), then the trial: one
/// window with fetching ahead on, two off, one on. A caller's choice is kept, and
/// small systems are never switched.
#[test]
fn the_event_loop_tries_both_settings_unless_told() {
    let build = |n| {
        Engine::new(
            SystemSpec::periodic_fluid(n, 0.5, 3).build().unwrap(),
            EngineParams::default(),
        )
        .unwrap()
    };
    // Settings seen every 1000 collisions over about seven windows.
    let seen = |e: &mut Engine| {
        (0..300)
            .map(|_| {
                e.run_collisions(1000).unwrap();
                e.look_ahead_enabled()
            })
            .collect::<Vec<bool>>()
    };
    let tuned = seen(&mut build(20_000));
    let first_on = tuned.iter().position(|&s| s).expect("a trial with it on");
    assert!(first_on > 0, "the first window runs on the guess (off)");
    let back_off = tuned[first_on..].iter().position(|&s| !s);
    assert!(back_off.is_some(), "a trial with it off follows");
    let mut told = build(20_000);
    told.set_look_ahead(false);
    assert!(seen(&mut told).iter().all(|&s| !s));
    assert!(seen(&mut build(10_000)).iter().all(|&s| !s));
}
