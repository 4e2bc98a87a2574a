//! The engine's internal clock restarts at each renumbering of the discs (see
//! `Engine::rebase_clock`), so contact times keep the precision of short times
//! however long the run or however late it starts, while the caller sees one
//! continuous, non-decreasing time.
//!
//! * The same system started at t = 0 and at t = 10⁹ follows the same trajectory
//!   bit for bit (only the reported times differ). With one absolute clock, times
//!   near 10⁹ carry rounding of ulp(10⁹) ≈ 1.2e-7, and collisions would happen up
//!   to ~1e-7 σ apart from contact.
//! * The late start keeps every disc pair within 1e-10 of its contact distance.
//! * Across several clock restarts, observations scheduled at exact times are
//!   delivered at exactly those times, and event times never decrease.

use carom_engine::{Engine, EngineParams, Event, InvariantChecker, State, SystemSpec};

const N: usize = 400;

fn start(time: f64) -> Engine {
    let mut state: State = SystemSpec::periodic_fluid(N, 0.5, 11)
        .build()
        .expect("valid system");
    state.time = time;
    Engine::new(state, EngineParams::default()).expect("engine")
}

fn bits(e: &Engine) -> Vec<u64> {
    let s = e.state();
    s.positions
        .iter()
        .zip(&s.velocities)
        .flat_map(|(r, v)| [r.x, r.y, v.x, v.y].map(f64::to_bits))
        .collect()
}

#[test]
fn late_start_follows_the_same_trajectory_with_full_precision() {
    let collisions = 300_000u64; // 4 renumberings (every 65 536 pair collisions)
    let mut early = start(0.0);
    let mut late = start(1e9);
    let mut checker = InvariantChecker::new(&late);
    let mut done = 0;
    let mut last = late.now();
    while done < collisions {
        early.run_collisions(1000).expect("runs");
        done += late.run_collisions(1000).expect("runs");
        assert!(late.now() >= last, "time went backwards");
        last = late.now();
        checker
            .check(&late)
            .unwrap_or_else(|v| panic!("after {done} collisions: {v}"));
    }
    assert!(late.stats().pair_collisions > 4 * 65_536);
    assert_eq!(bits(&early), bits(&late), "trajectories differ");
    // The reported clocks agree to the rounding of 10⁹.
    let gap = (late.now() - 1e9 - early.now()).abs();
    assert!(gap < 1e-6, "reported times differ by {gap}");
}

#[test]
fn observations_keep_their_exact_times_across_clock_restarts() {
    let mut e = start(12.345);
    let t0 = e.now();
    let dt = 0.37;
    let mut next_k = 1u64;
    e.schedule(t0 + dt, next_k).unwrap();
    let mut last = t0;
    let mut seen = 0;
    while e.stats().pair_collisions < 3 * 65_536 {
        let ev = e.next_event().unwrap().expect("events keep coming");
        let t = ev.time();
        assert!(t >= last, "time went backwards: {last} -> {t}");
        assert_eq!(e.now(), t, "now() must be the event's time");
        last = t;
        if let Event::Scheduled { time, tag } = ev {
            assert_eq!(tag, next_k);
            assert_eq!(time, t0 + next_k as f64 * dt, "observation {tag} moved");
            seen += 1;
            next_k += 1;
            e.schedule(t0 + next_k as f64 * dt, next_k).unwrap();
        }
    }
    assert!(seen > 100, "only {seen} observations");
    // The internal clock restarted at the last renumbering (not at the start).
    let cp = e.checkpoint();
    assert!(
        cp.clock < 0.5 * (cp.now - t0),
        "internal clock {} not restarted ({} since the start)",
        cp.clock,
        cp.now - t0
    );
    assert!((cp.epoch + cp.clock - cp.now).abs() <= 1e-12 * cp.now);
}

/// Two discs drifting together across a periodic box (speed ≈ 1 along y) while they
/// close in on each other at 5·10⁻⁸ along x meet after 10⁷ time units, having
/// crossed the box 10⁶ times with no other collision, so the renumbering every
/// 65 536 pair collisions never comes. Positions are computed from path origins
/// r0 = r − v t, which on one clock would lie 10⁷ away and round to 2·10⁻⁹ (the
/// pair then met 2.2·10⁻¹² σ off contact); the engine restarts its clock once an
/// origin lies 4096 cells out, so the pair meets at contact to 10⁻¹³ σ. (Found by the random-dynamics oracle in
/// `tests/engine_reference.rs`: a cooled cluster drifting with the rounding residue
/// of its momentum had collisions 10⁻⁹ off contact.)
#[test]
fn a_drifting_pair_meets_at_contact_however_far_it_drifted() {
    use carom_core::{DVec2, SimBox, Species};
    let delta = 2.5e-8;
    let state = State {
        sim_box: SimBox::periodic(10.0, 10.0),
        species: vec![Species::reference(2)],
        species_of: vec![0, 0],
        positions: vec![DVec2::new(3.0, 5.0), DVec2::new(4.5, 5.0)],
        // Slightly different drift speeds, so that the two origins differ and
        // round differently (B falls behind by 0.01 over the run).
        velocities: vec![DVec2::new(delta, 1.0), DVec2::new(-delta, 1.0 - 1e-9)],
        images: Vec::new(),
        time: 0.0,
    };
    let mut engine = Engine::new(state, EngineParams::default()).expect("engine");
    engine.schedule(2e7, 0).expect("schedule");
    let Ok(Some(Event::Pair(p))) = engine.next_event() else {
        panic!("the pair must meet first");
    };
    // Gap 0.5 closed at 2δ.
    assert!((p.time - 1e7).abs() < 1e-3 * 1e7, "met at t = {}", p.time);
    let d = engine
        .sim_box()
        .minimum_image(engine.position(p.j as usize) - engine.position(p.i as usize))
        .length();
    // 3e-15 off with the restarts; 2.2e-12 on one clock.
    assert!((d - 1.0).abs() <= 1e-13, "distance {d} at contact, σ = 1");
}

#[test]
fn the_state_holds_each_discs_own_position_and_velocity() {
    // After renumberings (every 65 536 pair collisions) the engine stores the
    // discs in another order than their indices: the state must still list each
    // disc's own position and velocity, also when written into a reused state.
    let mut e = start(0.0);
    let mut reused = SystemSpec::periodic_fluid(900, 0.3, 2).build().unwrap();
    for _ in 0..3 {
        e.run_collisions(70_000).unwrap();
        // The records are stored out of index order (else the test proves nothing).
        let labels = e.checkpoint().labels;
        assert!(labels.iter().enumerate().any(|(k, &l)| l as usize != k));
        let s = e.state();
        assert_eq!(s.len(), N);
        assert_eq!(s.time, e.now());
        for i in 0..N {
            assert_eq!(
                s.positions[i].to_array().map(f64::to_bits),
                e.position(i).to_array().map(f64::to_bits)
            );
            assert_eq!(
                s.velocities[i].to_array().map(f64::to_bits),
                e.velocity(i).to_array().map(f64::to_bits)
            );
            assert!((0..2).all(|k| (0.0..s.sim_box.size[k]).contains(&s.positions[i][k])));
        }
        e.state_into(&mut reused);
        assert_eq!(reused, s);
    }
}
