//! The vibrating floor (physics.md §18): a disc dropped on it hits at the time an
//! independent bisection finds and leaves at w − e (v − w); a bed of inelastic
//! discs on it never sinks below it and keeps K + U − floor work + losses constant
//! to rounding; a run resumes bit for bit from its checkpoint; bad floors are
//! refused.

use carom_core::vibrating_wall::Floor;
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_engine::{
    Engine, EngineError, EngineParams, Event, Growth, InvariantChecker, Placement, State,
    SystemSpec, Velocities,
};
use std::f64::consts::TAU;

fn floor(amplitude: f64, frequency: f64) -> Option<Floor> {
    Some(Floor {
        amplitude,
        omega: TAU * frequency,
    })
}

/// One disc of radius 0.5 and mass 1 at `p` with velocity `v` in a walled box.
fn one(size: [f64; 2], e_wall: f64, p: DVec2, v: DVec2) -> State {
    State {
        sim_box: SimBox {
            size: DVec2::new(size[0], size[1]),
            boundary: [Boundary::Walls {
                restitution: e_wall,
            }; 2],
        },
        species: vec![Species::reference(1)],
        species_of: vec![0],
        positions: vec![p],
        velocities: vec![v],
        images: Vec::new(),
        time: 0.0,
    }
}

/// The first time the centre at `y0` moving at `u0` in the field `g` comes down
/// to 0.5 + A (1 − cos ω t), by scanning a fine grid and bisecting, with the
/// floor's height written out here rather than taken from carom.
fn first_touch(y0: f64, u0: f64, g: f64, a: f64, w: f64) -> f64 {
    let f = |t: f64| y0 + u0 * t - 0.5 * g * t * t - 0.5 - a * (1.0 - (w * t).cos());
    let (mut lo, mut t) = (0.0, 0.0);
    while f(t) > 0.0 {
        lo = t;
        t += 1e-5;
    }
    let mut hi = t;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// Dropped from rest at height 4 with g = 1 on a floor of amplitude 0.3 and
/// frequency 0.7 (with and without a field): the first hit comes when the
/// bisection says, to 10⁻¹¹, and the disc leaves at w − e (v − w) with
/// w = A ω sin ω t; the floor's work is m (v'² − v²)/2.
#[test]
fn a_dropped_disc_hits_the_floor_when_bisection_says_and_bounces_in_its_frame() {
    for (g, u0, e_wall) in [(1.0, 0.0, 1.0), (1.0, 0.5, 0.8), (0.0, -1.0, 0.9)] {
        let (a, f) = (0.3, 0.7);
        let w = TAU * f;
        let state = one(
            [5.0, 10.0],
            e_wall,
            DVec2::new(2.5, 4.0),
            DVec2::new(0.0, u0),
        );
        let params = EngineParams {
            gravity: g,
            floor: floor(a, f),
            ..EngineParams::default()
        };
        let mut e = Engine::new(state, params).unwrap();
        let Some(Event::Wall(hit)) = e.next_event().unwrap() else {
            panic!("expected the floor");
        };
        let want = first_touch(4.0, u0, g, a, w);
        assert!(
            (hit.time - want).abs() < 1e-11,
            "g {g}: hit at {} vs {want}",
            hit.time
        );
        let v = u0 - g * want;
        assert!(
            (hit.v_before.y - v).abs() < 1e-10,
            "{} vs {v}",
            hit.v_before.y
        );
        let uw = a * w * (w * hit.time).sin();
        let after = uw - e_wall * (hit.v_before.y - uw);
        assert!((hit.v_after.y - after).abs() < 1e-12, "{hit:?}");
        let work = 0.5 * (hit.v_after.y.powi(2) - hit.v_before.y.powi(2));
        assert!((e.stats().floor_work - work).abs() < 1e-12);
        assert_eq!(hit.energy_lost, -e.stats().floor_work);
        assert!((e.position(0).y - 0.5 - e.floor_height()).abs() < 1e-12);
    }
}

/// A bed of 200 discs (e = 0.9, walls e = 0.95) in g = 1 on a floor of amplitude
/// 0.5 shaken at Γ = A ω²/g = 3.
fn bed(seed: u64) -> Engine {
    let species = vec![Species::reference(200)];
    let spec = SystemSpec {
        sim_box: SimBox {
            size: DVec2::new(20.0, 60.0),
            boundary: [Boundary::Periodic, Boundary::Walls { restitution: 0.95 }],
        },
        species,
        temperature: 1.0,
        seed,
        placement: Placement::Random,
        velocities: Velocities::MaxwellBoltzmann,
    };
    let params = EngineParams {
        restitution: Restitution::Normal(0.9),
        tc: 1e-4,
        gravity: 1.0,
        floor: floor(0.5, (6.0f64).sqrt() / TAU),
        ..EngineParams::default()
    };
    Engine::new(spec.build().unwrap(), params).unwrap()
}

/// Over 2 · 10⁵ collisions of the bed: no disc below the floor or overlapping
/// another, and K + U − (floor work) + (energy lost) stays at its start to 10⁻¹⁰
/// of the energy that flowed through; the floor did work (it drives the bed).
#[test]
fn a_shaken_bed_stays_above_the_floor_and_its_energy_balance_closes() {
    let mut e = bed(5);
    let mut check = InvariantChecker::new(&e);
    let start = e.kinetic_energy() + e.potential_energy();
    for _ in 0..40 {
        e.run_collisions(5_000).unwrap();
        check.check(&e).unwrap();
        let s = e.stats();
        let now = e.kinetic_energy() + e.potential_energy();
        let flow = s.floor_work.abs() + s.energy_lost + start.abs();
        let residue = now - start - s.floor_work + s.energy_lost;
        assert!(
            residue.abs() < 1e-10 * flow,
            "residue {residue:e} of {flow:e} at t = {}",
            e.now()
        );
    }
    assert!(e.stats().floor_work > 0.1 * e.stats().energy_lost);
}

/// The bed resumed from its checkpoint follows the same events bit for bit and
/// ends in the same checkpoint: the floor, its phase origin and its work are in
/// it, across the clock's restarts.
#[test]
fn a_shaken_bed_resumes_bit_identically_from_its_checkpoint() {
    let mut a = bed(9);
    a.run_collisions(20_000).unwrap();
    let mut b = Engine::from_checkpoint(a.checkpoint()).unwrap();
    for _ in 0..60_000 {
        assert_eq!(a.next_event().unwrap(), b.next_event().unwrap());
    }
    assert_eq!(a.checkpoint(), b.checkpoint());
    assert_eq!(a.state(), b.state());
}

/// Zero, negative or non-finite amplitudes and frequencies, a periodic y, a floor
/// whose travel and a diameter pass half the box, and growing discs are refused.
#[test]
fn bad_floors_are_refused() {
    let s = || one([5.0, 10.0], 1.0, DVec2::new(2.5, 4.0), DVec2::ZERO);
    let with = |fl: Option<Floor>| EngineParams {
        floor: fl,
        ..EngineParams::default()
    };
    for (fl, says) in [
        (floor(0.0, 1.0), "amplitude"),
        (floor(-1.0, 1.0), "amplitude"),
        (floor(f64::NAN, 1.0), "amplitude"),
        (floor(0.5, 0.0), "frequency"),
        (floor(0.5, f64::INFINITY), "frequency"),
        (floor(2.1, 1.0), "half the box"),
    ] {
        let Err(err) = Engine::new(s(), with(fl)) else {
            panic!("accepted {fl:?}");
        };
        assert!(matches!(err, EngineError::BadFloor(_)), "{err}");
        assert!(err.to_string().contains(says), "{err}");
    }
    let mut periodic = s();
    periodic.sim_box.boundary[1] = Boundary::Periodic;
    let err = Engine::new(periodic, with(floor(0.5, 1.0))).unwrap_err();
    assert!(err.to_string().contains("periodic"), "{err}");
    let growing = EngineParams {
        growth: Growth {
            rate: 0.01,
            ..Growth::default()
        },
        ..with(floor(0.5, 1.0))
    };
    assert!(Engine::new(s(), growing).is_err());
}

/// Validation (physics.md §18, docs/validation.md): the bed of [`bed`] reaches a
/// steady state in which the floor's mean power equals the dissipation rate. Over
/// t ∈ [200, 1200], in 10 blocks, the floor's power P_in = ΔW_floor/Δt and the loss
/// rate P_out = ΔE_lost/Δt are measured independently; their block means agree
/// within 3 standard errors of the difference (and K + U ends where it started
/// within that error times the span).
#[test]
#[ignore = "long validation: cargo test --release -p carom-engine --test engine_floor -- --ignored"]
fn a_shaken_bed_reaches_a_steady_state_where_floor_power_equals_dissipation() {
    let mut e = bed(21);
    e.run_until(200.0).unwrap();
    let mut diffs = Vec::new();
    let (mut sum_in, mut sum_out) = (0.0, 0.0);
    for k in 0..10 {
        let (w0, l0, t0) = (e.stats().floor_work, e.stats().energy_lost, e.now());
        e.run_until(300.0 + 100.0 * k as f64).unwrap();
        let dt = e.now() - t0;
        let (p_in, p_out) = (
            (e.stats().floor_work - w0) / dt,
            (e.stats().energy_lost - l0) / dt,
        );
        println!("block {k}: P_in = {p_in:.5}, P_out = {p_out:.5}");
        sum_in += p_in;
        sum_out += p_out;
        diffs.push(p_in - p_out);
    }
    let n = diffs.len() as f64;
    let mean = diffs.iter().sum::<f64>() / n;
    let var = diffs.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let se = (var / n).sqrt();
    println!(
        "P_in = {:.5}, P_out = {:.5}, difference {mean:.5} ± {se:.5}",
        sum_in / n,
        sum_out / n
    );
    assert!(sum_in > 0.0 && sum_out > 0.0);
    assert!(mean.abs() < 3.0 * se + 1e-3 * sum_in / n, "{mean} ± {se}");
}
