//! The engine with gravity against a brute-force O(N²) reference written here (no
//! cells, no queue, no delayed states, no path origins): small walled boxes and
//! channels (periodic x, walls y), one and two species, elastic and inelastic.
//!
//! (a) Oracle check, 5000 consecutive events per system: before every event the
//!     engine's state (true positions and velocities at `now()`) goes to the
//!     reference, which predicts every pair contact (relative motion is straight in
//!     a uniform field: `kinematics::contact_time` of Δr + Δv t, all images on a
//!     periodic x) and every wall hit: along x on the straight line, along y by the
//!     textbook roots of y + u t − g t²/2 = a (floor: (u + √(u² + 2g(y − a)))/g) and
//!     = L − a (ceiling: (u − √(u² − 2g(L − a − y)))/g). The engine's next event
//!     must be one the reference predicts, at its time within 1e-9 (1 + t), and the
//!     reference's earliest up to a tie within 1e-12 (1 + t); its velocities before
//!     must be the state's velocities less g Δt along y, within 1e-9.
//!
//! (b) Free-running: the reference integrates on its own (every disc moved on its
//!     parabola to the next event, resolved with `collision::resolve` or the wall
//!     rule) from the same start; both must report the same 150 events at times
//!     within 1e-9 (1 + t) and end within 1e-8 in positions and velocities (below
//!     the chaos horizon, see engine_reference.rs).

use carom_core::collision::resolve;
use carom_core::kinematics::contact_time;
use carom_core::{Axis, Boundary, DVec2, Restitution, SimBox, Species, WallSide};
use carom_engine::{
    box_size_for, Engine, EngineParams, Event, Placement, State, SystemSpec, Velocities,
};

#[derive(Debug, Clone, Copy, PartialEq)]
enum Key {
    Pair(usize, usize),
    Wall(usize, usize, WallSide),
}

/// The textbook floor time: the later root of h + u t − g t²/2 = 0 (h ≥ 0 is the
/// height above the line), 0 if already at or below it and falling.
fn floor_time(h: f64, u: f64, g: f64) -> f64 {
    if h <= 0.0 && u <= 0.0 {
        return 0.0;
    }
    (u + (u * u + 2.0 * g * h).max(0.0).sqrt()) / g
}

/// The textbook ceiling time: the earlier root of H − u t + g t²/2 = 0, if any.
fn ceiling_time(big_h: f64, u: f64, g: f64) -> Option<f64> {
    let d = u * u - 2.0 * g * big_h;
    (u > 0.0 && d >= 0.0).then(|| ((u - d.sqrt()) / g).max(0.0))
}

/// Every event of state `s` in the field `g`: (key, time from now).
fn predict(s: &State, g: f64) -> Vec<(Key, f64)> {
    let n = s.len();
    let size = s.sim_box.size;
    let periodic_x = s.sim_box.boundary[0].is_periodic();
    let mut out = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            let sigma = s.radius(i) + s.radius(j);
            let shifts: &[f64] = if periodic_x {
                &[-1.0, 0.0, 1.0]
            } else {
                &[0.0]
            };
            for &sx in shifts {
                let dr = s.positions[j] + DVec2::new(sx * size.x, 0.0) - s.positions[i];
                if let Some(t) = contact_time(dr, s.velocities[j] - s.velocities[i], sigma) {
                    out.push((Key::Pair(i, j), t));
                }
            }
        }
        let (r, v, a) = (s.positions[i], s.velocities[i], s.radius(i));
        if !periodic_x {
            if v.x > 0.0 {
                out.push((
                    Key::Wall(i, 0, WallSide::High),
                    ((size.x - a - r.x) / v.x).max(0.0),
                ));
            } else if v.x < 0.0 {
                out.push((Key::Wall(i, 0, WallSide::Low), ((a - r.x) / v.x).max(0.0)));
            }
        }
        out.push((Key::Wall(i, 1, WallSide::Low), floor_time(r.y - a, v.y, g)));
        if let Some(t) = ceiling_time(size.y - a - r.y, v.y, g) {
            out.push((Key::Wall(i, 1, WallSide::High), t));
        }
    }
    out
}

fn earliest(p: &[(Key, f64)]) -> (Key, f64) {
    *p.iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("some event")
}

fn key_of(ev: &Event) -> Key {
    match ev {
        Event::Pair(p) => Key::Pair(p.i.min(p.j) as usize, p.i.max(p.j) as usize),
        Event::Wall(w) => Key::Wall(w.i as usize, if w.axis == Axis::X { 0 } else { 1 }, w.side),
        Event::Scheduled { .. } | Event::Pause { .. } => unreachable!("nothing scheduled"),
    }
}

/// The systems: (box x boundary, species, η, rule, TC duration, g, seed).
fn systems() -> Vec<(SystemSpec, EngineParams)> {
    let mut out = Vec::new();
    let cases = [
        (
            Boundary::Walls { restitution: 1.0 },
            false,
            0.3,
            Restitution::Elastic,
            0.0,
            1.0,
            1,
        ),
        (
            Boundary::Periodic,
            false,
            0.4,
            Restitution::Elastic,
            0.0,
            0.3,
            2,
        ),
        (
            Boundary::Walls { restitution: 1.0 },
            true,
            0.35,
            Restitution::Elastic,
            0.0,
            2.0,
            3,
        ),
        (
            Boundary::Periodic,
            true,
            0.25,
            Restitution::Normal(0.9),
            1e-3,
            0.7,
            4,
        ),
        (
            Boundary::Walls { restitution: 0.8 },
            false,
            0.2,
            Restitution::CentreOfMass(0.95),
            1e-4,
            1.5,
            5,
        ),
    ];
    for (bx, mixed, eta, rule, tc, g, seed) in cases {
        let species = if mixed {
            vec![Species::reference(30), Species::new(10, 0.7, 2.5)]
        } else {
            vec![Species::reference(40)]
        };
        let spec = SystemSpec {
            sim_box: SimBox {
                size: box_size_for(&species, eta, 1.0),
                boundary: [bx, Boundary::Walls { restitution: 1.0 }],
            },
            species,
            temperature: 1.0,
            seed,
            placement: Placement::Random,
            velocities: Velocities::MaxwellBoltzmann,
        };
        let params = EngineParams {
            restitution: rule,
            tc,
            gravity: g,
            max_events_without_time_advance: 1000,
            ..EngineParams::default()
        };
        out.push((spec, params));
    }
    out
}

#[test]
fn every_event_is_the_references_earliest_at_its_time() {
    for (k, (spec, params)) in systems().into_iter().enumerate() {
        let g = params.gravity;
        let mut e = Engine::new(spec.build().unwrap(), params).unwrap();
        let mut floor_hits = 0;
        for step in 0..5000 {
            let s = e.state();
            let p = predict(&s, g);
            let (_, best) = earliest(&p);
            let ev = e.next_event().unwrap().expect("an event");
            let key = key_of(&ev);
            let t = ev.time();
            let tol = 1e-9 * (1.0 + t);
            let dt = p
                .iter()
                .filter(|(q, _)| *q == key)
                .map(|&(_, dt)| dt)
                .min_by(|a, b| a.total_cmp(b))
                .unwrap_or_else(|| panic!("system {k} step {step}: {key:?} not predicted"));
            assert!(
                (s.time + dt - t).abs() < tol,
                "system {k} step {step}: {key:?} at {t}, the reference says {}",
                s.time + dt
            );
            assert!(
                dt - best <= 1e-12 * (1.0 + t),
                "system {k} step {step}: {key:?} after {dt}, the reference's earliest after {best}"
            );
            let fall = |i: usize| s.velocities[i] - DVec2::new(0.0, g * dt);
            let vscale = 1e-9 * (1.0 + s.velocities.iter().map(|v| v.length()).fold(0.0, f64::max));
            match ev {
                Event::Pair(c) => {
                    assert!(
                        (c.vi_before - fall(c.i as usize)).length() < vscale,
                        "system {k} step {step}"
                    );
                    assert!(
                        (c.vj_before - fall(c.j as usize)).length() < vscale,
                        "system {k} step {step}"
                    );
                }
                Event::Wall(w) => {
                    assert!(
                        (w.v_before - fall(w.i as usize)).length() < vscale,
                        "system {k} step {step}"
                    );
                    floor_hits += usize::from(w.axis == Axis::Y && w.side == WallSide::Low);
                }
                Event::Scheduled { .. } | Event::Pause { .. } => unreachable!(),
            }
        }
        assert!(floor_hits > 50, "system {k}: only {floor_hits} floor hits");
    }
}

/// The reference on its own: every disc moved on its parabola by `dt`.
fn advance(s: &mut State, dt: f64, g: f64) {
    for (r, v) in s.positions.iter_mut().zip(s.velocities.iter_mut()) {
        *r += *v * dt - DVec2::new(0.0, 0.5 * g * dt * dt);
        v.y -= g * dt;
        if s.sim_box.boundary[0].is_periodic() {
            r.x = r.x.rem_euclid(s.sim_box.size.x);
        }
    }
    s.time += dt;
}

#[test]
fn free_running_reference_follows_the_same_events() {
    for (k, (spec, params)) in systems().into_iter().enumerate() {
        if !params.restitution.is_elastic() {
            continue;
        }
        let g = params.gravity;
        let mut s = spec.build().unwrap();
        let mut e = Engine::new(s.clone(), params).unwrap();
        for step in 0..150 {
            let (key, dt) = earliest(&predict(&s, g));
            advance(&mut s, dt, g);
            match key {
                Key::Pair(i, j) => {
                    let mut dr = s.positions[j] - s.positions[i];
                    if s.sim_box.boundary[0].is_periodic() {
                        dr.x -= s.sim_box.size.x * (dr.x / s.sim_box.size.x).round();
                    }
                    let res = resolve(
                        s.velocities[i],
                        s.velocities[j],
                        s.mass(i),
                        s.mass(j),
                        dr,
                        Restitution::Elastic,
                    );
                    s.velocities[i] = res.vi;
                    s.velocities[j] = res.vj;
                }
                Key::Wall(i, axis, _) => s.velocities[i][axis] = -s.velocities[i][axis],
            }
            let ev = e.next_event().unwrap().expect("an event");
            assert_eq!(key_of(&ev), key, "system {k} step {step}");
            assert!(
                (ev.time() - s.time).abs() < 1e-9 * (1.0 + s.time),
                "system {k} step {step}"
            );
        }
        let es = e.state();
        for i in 0..s.len() {
            assert!(
                (es.positions[i] - s.positions[i]).length() < 1e-8,
                "system {k} disc {i}"
            );
            assert!(
                (es.velocities[i] - s.velocities[i]).length() < 1e-8,
                "system {k} disc {i}"
            );
        }
    }
}
