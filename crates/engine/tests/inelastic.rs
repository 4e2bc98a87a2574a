//! Inelastic dynamics (physics.md §4): both pair models, the TC model, collapse
//! detection, and lossy walls.
//!
//! Covered: the exact energy budget and momentum of normal and centre-of-mass
//! restitution ([`budget_run`]); a dense e = 0.5 system that collapses without the
//! TC model (reported as a stall, not a hang) and runs with it; restitution 0 under
//! the TC model; the TC model applied to wall collisions; and lossy walls
//! ([`wall_run`]). Tolerances and why are on the tests and helpers.

use carom_core::boundary::Boundary;
use carom_core::collision::reduced_mass;
use carom_core::{DVec2, Restitution, Species};
use carom_engine::{Engine, EngineError, EngineParams, Event, InvariantChecker, State, SystemSpec};

fn state(n: usize, eta: f64, boundary: [Boundary; 2], seed: u64) -> State {
    let species = vec![Species::reference(n)];
    SystemSpec::square_box(species, eta, boundary, seed)
        .build()
        .expect("valid system")
}

/// A binary mixture, so that the reduced mass differs between pairs.
fn mixture_state(eta: f64, seed: u64) -> State {
    let species = vec![Species::reference(250), Species::new(150, 0.6, 2.0)];
    SystemSpec::square_box(species, eta, [Boundary::Periodic; 2], seed)
        .build()
        .expect("valid system")
}

fn momentum(e: &Engine) -> (DVec2, f64) {
    let mut p = DVec2::ZERO;
    let mut scale = 0.0;
    for i in 0..e.len() {
        let m = e.species()[e.species_of()[i] as usize].mass;
        p += e.velocity(i) * m;
        scale += m * e.velocity(i).length();
    }
    (p, scale)
}

fn mass(e: &Engine, i: u32) -> f64 {
    e.species()[e.species_of()[i as usize] as usize].mass
}

/// Run `collisions` pair collisions with `rule`, checking the energy budget and
/// momentum; returns (E0, E_end).
///
/// Every pair event's `energy_lost` equals the model's closed form computed here
/// from the event's own velocities and normal, and equals the pair's kinetic-energy
/// change (1e-12 of the pair's energy); Σ of the events' losses equals
/// `stats().energy_lost`; E0 − Σ losses equals the engine's current kinetic energy
/// to 1e-9 of E0 (checked every 10⁴ collisions and at the end; relative to E0
/// because the bookkeeping error is a sum of roundings of terms of the size of the
/// energies already subtracted); total momentum stays within 1e-12 of the initial
/// Σ m|v| (the current Σ m|v| shrinks as the gas cools, so the initial one is the
/// scale of the accumulated rounding).
fn budget_run(state0: State, rule: Restitution, collisions: u64) -> (f64, f64) {
    let params = EngineParams {
        restitution: rule,
        ..EngineParams::default()
    };
    let mut engine = Engine::new(state0, params).expect("engine");
    let e0 = engine.kinetic_energy();
    let (p0, scale0) = momentum(&engine);
    let mut lost = 0.0;
    let mut done = 0u64;
    let mut last = engine.now();
    let mut next_check = 10_000u64;
    while done < collisions {
        let ev = engine
            .next_event()
            .unwrap_or_else(|e| panic!("{rule:?}: after {done} collisions: {e}"))
            .expect("events");
        assert!(ev.time() >= last);
        last = ev.time();
        let Event::Pair(p) = ev else {
            panic!("only pair collisions in a periodic box, got {ev:?}")
        };
        done += 1;
        let (mi, mj) = (mass(&engine, p.i), mass(&engine, p.j));
        let mu = reduced_mass(mi, mj);
        let g = p.vi_before - p.vj_before;
        let u = g.dot(p.normal);
        assert!(u > 0.0, "collision of a receding pair: u = {u}");
        let formula = match rule {
            Restitution::Normal(e) => 0.5 * (1.0 - e * e) * mu * u * u,
            Restitution::CentreOfMass(r) => 0.5 * (1.0 - r * r) * mu * g.length_squared(),
            Restitution::Elastic => 0.0,
        };
        let k_before =
            0.5 * (mi * p.vi_before.length_squared() + mj * p.vj_before.length_squared());
        let k_after = 0.5 * (mi * p.vi_after.length_squared() + mj * p.vj_after.length_squared());
        assert!(
            (p.energy_lost - formula).abs() <= 1e-12 * k_before,
            "{rule:?}: reported loss {} vs formula {formula}",
            p.energy_lost
        );
        assert!(
            ((k_before - k_after) - p.energy_lost).abs() <= 1e-12 * k_before,
            "{rule:?}: pair energy {k_before} → {k_after}, reported loss {}",
            p.energy_lost
        );
        lost += p.energy_lost;
        if done == next_check || done == collisions {
            next_check += 10_000;
            let k = engine.kinetic_energy();
            assert!(
                ((e0 - lost) - k).abs() <= 1e-9 * e0,
                "{rule:?}: after {done} collisions E0 − Σ loss = {} but K = {k}",
                e0 - lost
            );
            assert!(
                (engine.stats().energy_lost - lost).abs() <= 1e-12 * e0,
                "{rule:?}: stats().energy_lost {} vs Σ events {lost}",
                engine.stats().energy_lost
            );
            let (p, _) = momentum(&engine);
            assert!(
                (p - p0).length() <= 1e-12 * scale0,
                "{rule:?}: momentum {p0} → {p}"
            );
        }
    }
    let e_end = engine.kinetic_energy();
    assert!(
        ((e0 - engine.stats().energy_lost) - e_end).abs() <= 1e-9 * e0,
        "{rule:?}: E0 − stats().energy_lost ≠ K"
    );
    println!(
        "{rule:?}: {collisions} collisions to t = {:.3}: K {e0:.3} → {e_end:.5}",
        engine.now()
    );
    (e0, e_end)
}

/// Normal restitution e = 0.9 (N = 400, η = 0.25, periodic, monodisperse and a binary
/// mixture): the checks of [`budget_run`]. 50–100 collisions per disc, over which the
/// gas cools by a factor of 10³–10⁶ — much longer and it is frozen and clustered,
/// and the check becomes trivial.
#[test]
fn normal_restitution_energy_budget_and_momentum() {
    let (e0, e1) = budget_run(
        state(400, 0.25, [Boundary::Periodic; 2], 1),
        Restitution::Normal(0.9),
        40_000,
    );
    assert!(e1 < 0.5 * e0, "the gas must cool: {e0} → {e1}");
    let (e0, e1) = budget_run(mixture_state(0.25, 2), Restitution::Normal(0.9), 20_000);
    assert!(e1 < e0);
}

/// The centre-of-mass model R = 0.9, same systems and run lengths as
/// [`normal_restitution_energy_budget_and_momentum`]: the checks of [`budget_run`].
#[test]
fn centre_of_mass_restitution_energy_budget_and_momentum() {
    let (e0, e1) = budget_run(
        state(400, 0.25, [Boundary::Periodic; 2], 3),
        Restitution::CentreOfMass(0.9),
        40_000,
    );
    assert!(e1 < 0.5 * e0, "the gas must cool: {e0} → {e1}");
    let (e0, e1) = budget_run(
        mixture_state(0.25, 4),
        Restitution::CentreOfMass(0.9),
        20_000,
    );
    assert!(e1 < e0);
}

fn dense_params(tc: f64) -> EngineParams {
    EngineParams {
        restitution: Restitution::Normal(0.5),
        tc,
        max_events_without_time_advance: 10_000,
        ..EngineParams::default()
    }
}

/// Without a cure, a dense e = 0.5 system collapses; the engine must say so. The
/// dense system (N = 500, η = 0.6) without the TC model returns
/// `Err(EngineError::Stalled)` with the configured limit (10⁴ events without time
/// advancing) within a bounded number of calls, instead of hanging.
#[test]
fn dense_collapse_without_tc_is_reported_as_stalled() {
    let mut engine = Engine::new(
        state(500, 0.6, [Boundary::Periodic; 2], 5),
        dense_params(0.0),
    )
    .expect("engine");
    // Bounded work: at most 10⁷ calls (the stall must come long before; a hang or a
    // run that never detects the collapse fails here instead of spinning forever).
    const MAX_CALLS: u64 = 10_000_000;
    let mut last = engine.now();
    let mut outcome = None;
    for call in 0..MAX_CALLS {
        match engine.next_event() {
            Ok(Some(ev)) => {
                assert!(ev.time() >= last, "time went backwards at call {call}");
                last = ev.time();
            }
            Ok(None) => panic!("the system came to rest instead of collapsing"),
            Err(e) => {
                outcome = Some((call, e));
                break;
            }
        }
    }
    let (calls, err) = outcome.expect("no Stalled error within 10⁷ events: collapse not detected");
    match err {
        EngineError::Stalled {
            time,
            events,
            limit,
            dissipative,
        } => {
            assert_eq!(limit, 10_000);
            assert!(
                dissipative,
                "an inelastic rule without the TC model dissipates"
            );
            assert!(
                events > limit,
                "stalled after {events} ≤ limit {limit} events"
            );
            assert!(time.is_finite() && time >= 0.0);
            println!("collapse at t = {time} after {calls} events");
        }
        other => panic!("expected Stalled, got {other:?}"),
    }
    let msg = err.to_string();
    assert!(msg.contains("max_events_without_time_advance"), "{msg}");
    assert!(msg.contains("inelastic collapse"), "{msg}");
}

/// With the TC model the same system runs on, without overlap and with an exact
/// energy budget (TC collisions are elastic and lose nothing): with t_c = 10⁻⁴ τ0
/// (about 10⁻³ of the initial mean free time) it runs 2·10⁵ collisions with no
/// overlap beyond 1e-10 of σ.
#[test]
fn dense_system_with_tc_model_runs_without_overlap() {
    let tc = 1e-4;
    let mut engine = Engine::new(
        state(500, 0.6, [Boundary::Periodic; 2], 5),
        dense_params(tc),
    )
    .expect("engine");
    let mut checker = InvariantChecker::new(&engine);
    let e0 = engine.kinetic_energy();
    let mut lost = 0.0;
    let mut elastic_by_tc = 0u64;
    let mut last_collision = vec![f64::NEG_INFINITY; engine.len()];
    const TARGET: u64 = 200_000;
    let mut done = 0;
    let mut next_check = 10_000u64;
    while done < TARGET {
        let ev = engine
            .next_event()
            .unwrap_or_else(|e| panic!("TC run failed after {done} collisions: {e}"))
            .expect("events");
        let Event::Pair(p) = ev else {
            panic!("unexpected {ev:?}")
        };
        done += 1;
        // The TC rule, checked from the outside: elastic iff either disc collided less
        // than t_c ago.
        let (i, j) = (p.i as usize, p.j as usize);
        let recent = p.time - last_collision[i] < tc || p.time - last_collision[j] < tc;
        let u = (p.vi_before - p.vj_before).dot(p.normal);
        let u_after = (p.vi_after - p.vj_after).dot(p.normal);
        let want = if recent { -u } else { -0.5 * u };
        assert!(
            (u_after - want).abs()
                <= 1e-12 * (u.abs() + p.vi_before.length() + p.vj_before.length()),
            "collision {done}: u {u} → {u_after}, expected {want} (recent: {recent})"
        );
        if recent {
            elastic_by_tc += 1;
            assert_eq!(p.energy_lost, 0.0);
        }
        last_collision[i] = p.time;
        last_collision[j] = p.time;
        lost += p.energy_lost;
        if done == next_check {
            next_check += 10_000;
            checker
                .check_conservation(&engine)
                .unwrap_or_else(|v| panic!("after {done}: {v}"));
            checker
                .check_overlaps(&engine)
                .unwrap_or_else(|v| panic!("after {done}: {v}"));
        }
    }
    checker
        .check(&engine)
        .unwrap_or_else(|v| panic!("at the end: {v}"));
    let k = engine.kinetic_energy();
    assert!(
        ((e0 - lost) - k).abs() <= 1e-9 * e0,
        "E0 − Σ loss {} vs K {k}",
        e0 - lost
    );
    println!(
        "TC run: {TARGET} collisions to t = {:.4}, {elastic_by_tc} made elastic by TC, K {e0:.2} → {k:.3e}, max overlap {:e}",
        engine.now(),
        checker.max_overlap
    );
}

/// Walls with restitution e_w < 1 (walled box and channel, elastic pairs): every
/// wall hit reverses and scales the normal velocity by e_w, keeps the tangential
/// one, reports the impulse m (1 + e_w)|v_n| and dissipates exactly
/// ½ m (1 − e_w²) v_n², which is also the engine's kinetic-energy change.
fn wall_run(boundary: [Boundary; 2], seed: u64, events: u64) {
    let s = state(100, 0.2, boundary, seed);
    let mut engine = Engine::new(s, EngineParams::default()).expect("engine");
    let e0 = engine.kinetic_energy();
    let (p0, scale0) = momentum(&engine);
    let mut k_prev = e0;
    let mut lost = 0.0;
    let mut wall_hits = 0;
    let mut impulse_sum = [[0.0f64; 2]; 2];
    for _ in 0..events {
        let ev = engine.next_event().expect("engine").expect("events");
        let k = engine.kinetic_energy();
        match ev {
            Event::Wall(w) => {
                wall_hits += 1;
                let ax = w.axis.index();
                let e = match boundary[ax] {
                    Boundary::Walls { restitution } => restitution,
                    Boundary::Periodic => panic!("wall hit on a periodic axis"),
                };
                let m = mass(&engine, w.i);
                let vn = w.v_before[ax];
                // Applied from the impulse (exactly v + Δp/m): the normal
                // component reversed and scaled to rounding, the tangential kept.
                assert_eq!(w.v_after, w.v_before + w.impulse_vector() / m);
                assert_eq!(w.v_after[1 - ax], w.v_before[1 - ax]);
                assert!(
                    (w.v_after[ax] + e * vn).abs() <= 4.0 * f64::EPSILON * vn.abs(),
                    "normal reversed and scaled: {} vs {}",
                    w.v_after[ax],
                    -e * vn
                );
                let expected = 0.5 * m * (1.0 - e * e) * vn * vn;
                assert!(
                    (w.energy_lost - expected).abs() <= 1e-14 * expected.max(1e-300),
                    "wall loss {} vs ½ m (1 − e²) v_n² = {expected}",
                    w.energy_lost
                );
                assert!((w.impulse - m * (1.0 + e) * vn.abs()).abs() <= 1e-14 * w.impulse);
                impulse_sum[ax][(w.side == carom_core::WallSide::High) as usize] += w.impulse;
                assert!(
                    ((k_prev - k) - w.energy_lost).abs() <= 1e-12 * e0,
                    "engine energy {k_prev} → {k} vs wall loss {}",
                    w.energy_lost
                );
                lost += w.energy_lost;
            }
            Event::Pair(p) => {
                assert_eq!(p.energy_lost, 0.0);
                assert!((k_prev - k).abs() <= 1e-12 * e0, "elastic pair changed K");
            }
            Event::Scheduled { .. } | Event::Pause { .. } => unreachable!(),
        }
        k_prev = k;
    }
    assert!(wall_hits > 100, "only {wall_hits} wall hits");
    let k = engine.kinetic_energy();
    assert!(((e0 - lost) - k).abs() <= 1e-9 * e0);
    assert!((engine.stats().energy_lost - lost).abs() <= 1e-12 * e0);
    for (ax, sides) in impulse_sum.iter().enumerate() {
        for (side, &sum) in sides.iter().enumerate() {
            let s = engine.stats().wall_impulse[ax][side];
            assert!(
                (s - sum).abs() <= 1e-12 * sum.max(1.0),
                "wall impulse [{ax}][{side}]"
            );
        }
    }
    // Along a periodic axis momentum is still conserved.
    let (p, _) = momentum(&engine);
    for ax in 0..2 {
        if boundary[ax].is_periodic() {
            assert!(
                (p[ax] - p0[ax]).abs() <= 1e-12 * scale0,
                "momentum along {ax}"
            );
        }
    }
    assert!(k < e0, "lossy walls must cool the gas");
}

/// Lossy walls, walled box and channel, elastic pairs: the checks of [`wall_run`].
#[test]
fn lossy_walls_dissipate_half_m_one_minus_e2_vn2() {
    wall_run([Boundary::Walls { restitution: 0.7 }; 2], 7, 20_000);
    // Different restitution per axis.
    wall_run(
        [
            Boundary::Walls { restitution: 0.95 },
            Boundary::Walls { restitution: 0.3 },
        ],
        8,
        20_000,
    );
    // A channel: periodic x, lossy walls in y.
    wall_run(
        [Boundary::Periodic, Boundary::Walls { restitution: 0.5 }],
        9,
        20_000,
    );
}

/// The runaway guard counts collisions at one instant, and nothing else: a clock
/// moved on by a cell crossing, a recomputed prediction or an observation starts a
/// new instant. With a limit of one collision per instant, a strongly inelastic
/// system (where rounding leaves pairs in contact, meeting again at once) must only
/// ever stop at an instant that really held a second collision.
#[test]
fn runaway_guard_counts_only_collisions_at_one_instant() {
    let params = EngineParams {
        restitution: Restitution::Normal(0.1),
        tc: 0.0,
        max_events_without_time_advance: 1,
        ..EngineParams::default()
    };
    let mut stops = 0;
    for seed in 1..=8 {
        let mut engine =
            Engine::new(state(400, 0.3, [Boundary::Periodic; 2], seed), params).expect("engine");
        // Collisions returned so far at the time of the last one.
        let (mut last, mut at_instant) = (f64::NEG_INFINITY, 0u64);
        for _ in 0..300_000 {
            match engine.next_event() {
                Ok(Some(Event::Scheduled { .. })) => {}
                Ok(Some(ev)) => {
                    if ev.time() == last {
                        at_instant += 1;
                    } else {
                        (last, at_instant) = (ev.time(), 1);
                    }
                }
                Ok(None) => break,
                Err(EngineError::Stalled {
                    time,
                    events,
                    limit,
                    ..
                }) => {
                    assert_eq!(limit, 1);
                    assert_eq!(
                        (time, events),
                        (last, at_instant + 1),
                        "seed {seed}: stopped at t = {time} after {events} collisions there, \
                         but the stream holds {at_instant} at its last collision time {last}"
                    );
                    stops += 1;
                    break;
                }
                Err(e) => panic!("seed {seed}: {e}"),
            }
        }
    }
    // The scenario must actually exercise the guard.
    assert!(
        stops > 0,
        "no seed reached a second collision at one instant"
    );
}

/// Two discs meeting along (3, 4)/5 (σ = 5) while sliding past each other at unit
/// speed, inside the box or across its periodic edge, in 200 variants of their
/// approach speed, under the TC model. With e = 0 or R = 0 the rule leaves them
/// without normal relative velocity, which rounding may leave slightly
/// approaching; they must not then meet again at the same instant (before, they
/// did, and the TC model's elastic collision could not change their velocities by
/// so little: a stall). Each of the two sides' views is needed.
#[test]
fn a_pair_left_without_normal_velocity_does_not_meet_again_at_once() {
    let n = DVec2::new(0.6, 0.8);
    for rule in [Restitution::Normal(0.0), Restitution::CentreOfMass(0.0)] {
        let mut collided = 0;
        for m in 0..200u32 {
            let approach = 0.5 * (1.0 + f64::from(m) * 1e-3);
            let v0 = DVec2::new(0.8, -0.6) + n * approach;
            let v1 = DVec2::new(-0.8, 0.6) - n * approach;
            // Inside the box, or across its periodic edge (then the two discs see
            // each other through images shifted by ∓L, rounded differently).
            let r0 = if m % 2 == 0 {
                DVec2::new(10.0, 10.0)
            } else {
                DVec2::new(39.9, 10.0)
            };
            let mut r1 = r0 + n * 5.01;
            r1.x %= 40.0;
            let state = State {
                sim_box: carom_core::SimBox::periodic(40.0, 40.0),
                species: vec![Species::new(2, 2.5, 1.0)],
                species_of: vec![0, 0],
                positions: vec![r0, r1],
                velocities: vec![v0, v1],
                images: Vec::new(),
                time: 0.0,
            };
            let params = EngineParams {
                restitution: rule,
                tc: 1e-3,
                max_events_without_time_advance: 10,
                ..EngineParams::default()
            };
            let mut engine = Engine::new(state, params).expect("engine");
            engine.schedule(10.0, 0).expect("schedule");
            let mut times = Vec::new();
            loop {
                match engine.next_event() {
                    Ok(Some(Event::Pair(p))) => {
                        times.push(p.time);
                        let (before, after) = (p.vi_before + p.vj_before, p.vi_after + p.vj_after);
                        assert!(
                            (after - before).length() <= 4.0 * f64::EPSILON,
                            "{rule:?}, m = {m}: momentum {before} → {after}"
                        );
                    }
                    Ok(Some(Event::Scheduled { .. })) => break,
                    Ok(other) => panic!("{rule:?}, m = {m}: unexpected {other:?}"),
                    Err(e) => panic!("{rule:?}, m = {m}: {e}"),
                }
            }
            // They meet after about 0.01 time units, and once: sliding apart, they
            // do not meet again before t = 10.
            assert_eq!(times.len(), 1, "{rule:?}, m = {m}: collisions at {times:?}");
            collided += 1;
        }
        assert_eq!(collided, 200);
    }
}

/// Restitution 0 with the TC model is a granular gas that must run: before the pair
/// was separated after a collision, N = 400 at η = 0.3 with e = 0 and t_c = 10⁻³
/// stalled at t ≈ 0.53 (a pair left approaching by rounding met again at once, and
/// the elastic TC collision could not change velocities by less than their ulp).
/// It must run to t = 20 without stalling or overlap, keeping momentum.
#[test]
fn restitution_zero_with_the_tc_model_runs_without_stalling() {
    for rule in [Restitution::Normal(0.0), Restitution::CentreOfMass(0.0)] {
        let params = EngineParams {
            restitution: rule,
            tc: 1e-3,
            max_events_without_time_advance: 100_000,
            ..EngineParams::default()
        };
        let mut engine =
            Engine::new(state(400, 0.3, [Boundary::Periodic; 2], 0), params).expect("engine");
        let mut checker = InvariantChecker::new(&engine);
        let (p0, scale) = momentum(&engine);
        let collisions = engine
            .run_until(20.0)
            .unwrap_or_else(|e| panic!("{rule:?}: {e}"));
        assert!(collisions > 1000, "{rule:?}: only {collisions} collisions");
        assert_eq!(engine.now(), 20.0);
        checker
            .check_overlaps(&engine)
            .unwrap_or_else(|v| panic!("{rule:?}: {v}"));
        let (p, _) = momentum(&engine);
        assert!(
            (p - p0).length() <= 1e-12 * scale,
            "{rule:?}: momentum {p0} → {p}"
        );
    }
}

/// Discs wedged between inelastic walls, with elastic pairs: four discs of
/// diameter 1.30 in a channel 2.39 wide (walls in x with e_w = 0.0123, periodic
/// in y), so no two of them fit side by side. Discs 0 and 3 slide down together,
/// each against its wall and touching the other along a line at 34° to the x
/// axis; disc 2 comes up into disc 3. Every pair collision then drives the wedged
/// discs into their walls and the walls send them back into each other, ever
/// faster: the wall version of inelastic collapse, ending in collisions at one
/// instant that never stop. (The state of a random walled system, found by a
/// randomized search, 6.5·10⁻⁵ time units before it collapsed.)
fn wedge(tc: f64) -> Engine {
    let state = State {
        sim_box: carom_core::SimBox {
            size: DVec2::new(2.3867422009521384, 5.704801131163117),
            boundary: [
                Boundary::Walls {
                    restitution: 0.012269529814032287,
                },
                Boundary::Periodic,
            ],
        },
        species: vec![Species::new(4, 0.6508663969821852, 4.232897751275343)],
        species_of: vec![0; 4],
        positions: vec![
            DVec2::new(1.7358758039699538, 2.425801893747888),
            DVec2::new(0.6602195228521368, 3.4639416712672393),
            DVec2::new(1.7178294675284531, 0.9608661194699044),
            DVec2::new(0.6508663969821852, 1.7065920122596423),
        ],
        velocities: vec![
            DVec2::new(0.0, -0.017698938385505084),
            DVec2::new(0.0008304908487400463, -0.039108038592824884),
            DVec2::new(-0.0009972062904777955, 0.07450591536383498),
            DVec2::new(0.0, -0.017698938385505084),
        ],
        images: Vec::new(),
        time: 0.0,
    };
    let params = EngineParams {
        restitution: Restitution::Elastic,
        tc,
        max_events_without_time_advance: 10_000,
        ..EngineParams::default()
    };
    Engine::new(state, params).expect("engine")
}

/// The TC model covers wall collisions (physics.md §4: a collision is elastic if
/// the disc collided less than t_c ago, whatever it collided with). Without the TC
/// model the wedge collapses and the engine reports it; with it, the same start
/// runs on, and every wall collision follows the rule: elastic within t_c of the
/// disc's previous collision (pair or wall), with the wall's restitution otherwise.
/// Four discs wedged in a channel with lossy walls (e_w = 0.012) and elastic pairs,
/// t_c = 10⁻³. (Before wall collisions were covered, the wedge collapsed with the TC
/// model on, and so did 13 of 600 random walled systems with inelastic walls and
/// t_c > 0.)
#[test]
fn the_tc_model_covers_wall_collisions() {
    let mut without = wedge(0.0);
    without.schedule(5.0, 0).expect("schedule");
    let stalled = loop {
        match without.next_event() {
            Ok(Some(Event::Scheduled { .. })) => break None,
            Ok(Some(_)) => {}
            Ok(None) => break None,
            Err(e) => break Some(e),
        }
    };
    assert!(
        matches!(stalled, Some(EngineError::Stalled { .. })),
        "without the TC model the wedge must collapse: {stalled:?}"
    );

    let tc = 1e-3;
    let mut engine = wedge(tc);
    let mut checker = InvariantChecker::new(&engine);
    engine.schedule(5.0, 0).expect("schedule");
    let mut last = [f64::NEG_INFINITY; 4];
    let (mut elastic_hits, mut lossy_hits, mut pairs) = (0, 0, 0);
    loop {
        match engine.next_event() {
            Ok(Some(Event::Pair(p))) => {
                pairs += 1;
                last[p.i as usize] = p.time;
                last[p.j as usize] = p.time;
            }
            Ok(Some(Event::Wall(w))) => {
                let k = match w.axis {
                    carom_core::Axis::X => 0,
                    carom_core::Axis::Y => 1,
                };
                let i = w.i as usize;
                if w.time - last[i] < tc {
                    elastic_hits += 1;
                    assert_eq!(w.v_after[k], -w.v_before[k], "{w:?}");
                    assert_eq!(w.energy_lost, 0.0, "{w:?}");
                } else {
                    lossy_hits += 1;
                    let want = -0.012269529814032287 * w.v_before[k];
                    // Applied from the impulse: −e v_k to rounding of v_k.
                    assert!(
                        (w.v_after[k] - want).abs() <= 4.0 * f64::EPSILON * w.v_before[k].abs(),
                        "{w:?}"
                    );
                    assert!(w.energy_lost > 0.0, "{w:?}");
                }
                assert_eq!(w.v_after[1 - k], w.v_before[1 - k], "{w:?}");
                last[i] = w.time;
            }
            Ok(Some(Event::Scheduled { .. })) => break,
            Ok(other) => panic!("unexpected {other:?}"),
            Err(e) => panic!("with the TC model (t_c = {tc}) the wedge must run on: {e}"),
        }
        checker.check_overlaps(&engine).expect("no overlap");
    }
    assert_eq!(engine.now(), 5.0);
    assert!(
        elastic_hits > 0 && lossy_hits > 0 && pairs > 0,
        "both kinds of wall collision: {elastic_hits} elastic, {lossy_hits} lossy, {pairs} pair"
    );
}
