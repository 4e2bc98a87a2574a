//! Growing discs, Lubachevsky–Stillinger compression (physics.md §17): hand-worked
//! pair and wall collisions of growing discs (times and the speeds they leave
//! at), no overlap beyond rounding at many times of a compression of a few hundred
//! discs, the end at the target packing fraction with the target kT, the
//! checkpoint continuing bit for bit through rescales and the end, a dense
//! compression stopped by the jamming bound, and the configurations refused.

use carom_core::observables::{degrees_of_freedom, packing_fraction, temperature};
use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_engine::{
    box_size_for, Engine, EngineError, EngineParams, Event, Growth, GrowthEnd, Placement, State,
    SystemSpec, Velocities,
};

fn growing(rate: f64, target_scale: f64, rescale_interval: f64) -> EngineParams {
    EngineParams {
        growth: Growth {
            rate,
            target_scale,
            kt: 1.0,
            rescale_interval,
            max_reduced_pressure: f64::INFINITY,
        },
        ..EngineParams::default()
    }
}

/// Discs of radius 0.5 and mass 1 at `positions` with velocities `velocities`.
fn discs(sim_box: SimBox, positions: Vec<DVec2>, velocities: Vec<DVec2>) -> State {
    let n = positions.len();
    State {
        sim_box,
        species: vec![Species::reference(n)],
        species_of: vec![0; n],
        positions,
        velocities,
        images: Vec::new(),
        time: 0.0,
    }
}

/// Two discs of diameter 1 at rest 2 apart, growing at γ = 1/2: the contact
/// distance 1 + t/2 reaches 2 at t = 2 exactly (A = −1/4, B = −1/2, C = 3, D = 1:
/// 3/(1 + 1/2)). They meet at u = 0 with g = σ⁰γ = 1/2 and leave at u' = 2g = 1,
/// each at 1/2 (equal masses); parting faster than they grow, they never meet again.
#[test]
fn two_discs_at_rest_meet_when_grown_and_leave_at_twice_the_growth_rate() {
    let b = SimBox::periodic(10.0, 10.0);
    let s = discs(
        b,
        vec![DVec2::new(4.0, 5.0), DVec2::new(6.0, 5.0)],
        vec![DVec2::ZERO; 2],
    );
    let mut e = Engine::new(s, growing(0.5, 2.5, 100.0)).unwrap();
    let Some(Event::Pair(p)) = e.next_event().unwrap() else {
        panic!("expected the pair collision");
    };
    assert_eq!(p.time, 2.0);
    assert_eq!(p.vi_after, DVec2::new(-0.5, 0.0));
    assert_eq!(p.vj_after, DVec2::new(0.5, 0.0));
    assert_eq!(e.radius_scale(), 2.0);
    assert_eq!(e.state().species[0].radius, 1.0);
    // The energy given: 2 · (1/2)(1/2)² = 1/4, reported as an energy lost of −1/4.
    assert_eq!(p.energy_lost, -0.25);
    e.run_until(2.9).unwrap();
    assert_eq!(e.stats().pair_collisions, 1);
}

/// A disc of radius 1/2 at rest at x = 2 in a walled 10 × 10 box, growing at
/// γ = 1/2 (ȧ = 1/4): 1/2 + t/4 = 2 at t = 6 (low x wall), after which it moves at
/// v' = 2ȧ = 1/2; then 10 − (2 + (t − 6)/2) = 1/2 + t/4 at t = 14 (high x wall),
/// which reverses the speed relative to the moving contact: v' = −v − 2ȧ = −1.
#[test]
fn a_growing_disc_meets_the_walls_and_leaves_faster() {
    let b = SimBox {
        size: DVec2::new(10.0, 10.0),
        boundary: [Boundary::Walls { restitution: 1.0 }; 2],
    };
    let s = discs(b, vec![DVec2::new(2.0, 5.0)], vec![DVec2::ZERO]);
    let mut e = Engine::new(s, growing(0.5, 9.0, 1000.0)).unwrap();
    let Some(Event::Wall(w)) = e.next_event().unwrap() else {
        panic!("expected a wall");
    };
    assert_eq!((w.time, w.v_after), (6.0, DVec2::new(0.5, 0.0)));
    let Some(Event::Wall(w)) = e.next_event().unwrap() else {
        panic!("expected a wall");
    };
    assert_eq!((w.time, w.v_after), (14.0, DVec2::new(-1.0, 0.0)));
    // At t = 14 the radius is 1/2 + 14/4 = 4 and the centre at 10 − 4 = 6.
    assert_eq!(e.position(0), DVec2::new(6.0, 5.0));
}

/// `n` discs (an equimolar 1 : 1.4 mixture if `mixture`) at packing fraction `eta`
/// placed at random in a periodic box.
fn fluid(n: usize, eta: f64, mixture: bool, seed: u64) -> State {
    let species = if mixture {
        vec![Species::reference(n / 2), Species::scaled(n - n / 2, 1.4)]
    } else {
        vec![Species::reference(n)]
    };
    let size = box_size_for(&species, eta, 1.0);
    SystemSpec {
        species,
        sim_box: SimBox::periodic(size.x, size.y),
        temperature: 1.0,
        seed,
        placement: Placement::Random,
        velocities: Velocities::MaxwellBoltzmann,
    }
    .build()
    .unwrap()
}

/// The largest relative overlap 1 − r_ij/σ_ij over all pairs of `s` (0 if none).
fn worst_overlap(s: &State) -> f64 {
    let mut worst = 0.0f64;
    for i in 0..s.len() {
        for j in i + 1..s.len() {
            let d = s.sim_box.minimum_image(s.positions[j] - s.positions[i]);
            let sigma = s.radius(i) + s.radius(j);
            worst = worst.max(1.0 - d.length() / sigma);
        }
    }
    worst
}

/// 300 discs of a 1 : 1.4 mixture compressed from η = 0.2 to 0.6 at γ = 0.02
/// (rescales every 0.5): at 40 times on the way no pair overlaps by more than
/// rounding (10⁻¹² of σ), the growth ends at the target with the target kT, and
/// the discs then keep their size and their energy.
#[test]
fn a_compression_never_overlaps_and_ends_at_the_target() {
    let s = fluid(300, 0.2, true, 3);
    let eta0 = packing_fraction(&s.species, &s.sim_box);
    let scale = (0.6f64 / eta0).sqrt();
    let mut e = Engine::new(s, growing(0.02, scale, 0.5)).unwrap();
    let t_end = (scale - 1.0) / 0.02;
    for k in 1..=40 {
        e.run_until(t_end * 1.1 * k as f64 / 40.0).unwrap();
        let w = worst_overlap(&e.state());
        assert!(w < 1e-12, "overlap {w:e} at t = {}", e.now());
    }
    assert_eq!(e.growth().ended, GrowthEnd::Target);
    let st = e.state();
    let eta = packing_fraction(&st.species, &st.sim_box);
    assert!((eta - 0.6).abs() < 1e-12, "η = {eta}");
    let dof = degrees_of_freedom(st.len(), &st.sim_box);
    let kt = temperature(e.kinetic_energy(), dof);
    assert!((kt - 1.0).abs() < 1e-12, "kT = {kt} after the end");
    let before = e.kinetic_energy();
    e.run_until(e.now() + 10.0).unwrap();
    let rel = (e.kinetic_energy() - before).abs() / before;
    assert!(rel < 1e-12, "energy drifted by {rel:e} at fixed size");
    assert_eq!(e.radius_scale(), scale);
    assert!(worst_overlap(&e.state()) < 1e-12);
}

/// A checkpoint taken during the growth resumes bit for bit: the same events
/// through rescales, renumberings and the end of the growth, and the same state.
#[test]
fn a_checkpoint_during_growth_resumes_bit_identically() {
    let s = fluid(200, 0.4, false, 5);
    // The end at t = 200, after the first renumbering (65 536 pair collisions),
    // which restarts the clock and with it the growth's origin.
    let mut a = Engine::new(s, growing(0.0015, 1.3, 0.25)).unwrap();
    a.run_until(1.1).unwrap();
    let mut b = Engine::from_checkpoint(a.checkpoint()).unwrap();
    let mut events = 0;
    while a.now() < 201.0 {
        let (ea, eb) = (a.next_event().unwrap(), b.next_event().unwrap());
        assert_eq!(ea, eb);
        events += 1;
    }
    assert!(a.stats().pair_collisions > 65_536, "{events} events");
    assert_eq!(a.growth().ended, GrowthEnd::Target);
    assert_eq!(a.checkpoint(), b.checkpoint());
}

/// Compressed fast towards η = 0.95, the discs stop growing at the first rescale
/// where Z over the interval exceeds the bound, below the target and below the
/// densest packing, and without overlaps.
#[test]
fn a_fast_compression_stops_at_the_jamming_bound() {
    let s = fluid(200, 0.5, true, 9);
    let eta0 = packing_fraction(&s.species, &s.sim_box);
    let mut p = growing(0.05, (0.95f64 / eta0).sqrt(), 0.2);
    p.growth.max_reduced_pressure = 100.0;
    let mut e = Engine::new(s, p).unwrap();
    while e.growth().ended == GrowthEnd::Growing {
        e.run_until(e.now() + 0.2).unwrap();
    }
    assert_eq!(e.growth().ended, GrowthEnd::Jammed);
    assert!(e.growth().last_z > 100.0);
    let st = e.state();
    let eta = packing_fraction(&st.species, &st.sim_box);
    assert!(eta > 0.75 && eta < 0.9069, "stopped at η = {eta}");
    assert!(worst_overlap(&st) < 1e-12);
}

#[test]
fn growth_with_unsupported_dynamics_or_values_is_refused() {
    let s = || fluid(50, 0.3, false, 1);
    let mut p = growing(0.1, 1.2, 0.5);
    p.restitution = Restitution::Normal(0.9);
    let err = Engine::new(s(), p).unwrap_err();
    assert!(matches!(err, EngineError::BadGrowth(_)));
    assert!(err.to_string().contains("elastic"), "{err}");
    for (name, p) in [
        ("rate", growing(f64::NAN, 1.2, 0.5)),
        ("target scale", growing(0.1, 0.9, 0.5)),
        ("rescale interval", growing(0.1, 1.2, 0.0)),
    ] {
        let err = Engine::new(s(), p).unwrap_err().to_string();
        assert!(err.contains(name), "{name}: {err}");
    }
}

/// Compressed placement: 200 discs from a random start at η = 0.3 grown to the
/// requested radii at η = 0.65; the state has the species' radii, no overlap
/// beyond rounding, and the requested kT. A rate that is not positive is refused,
/// naming the field.
#[test]
fn compressed_placement_reaches_the_requested_radii_without_overlap() {
    let species = vec![Species::reference(200)];
    let size = box_size_for(&species, 0.65, 1.0);
    let mut spec = SystemSpec {
        species,
        sim_box: SimBox::periodic(size.x, size.y),
        temperature: 1.0,
        seed: 2,
        placement: Placement::Compressed {
            rate: 0.05,
            start: 0.3,
        },
        velocities: Velocities::MaxwellBoltzmann,
    };
    let s = spec.build().unwrap();
    assert_eq!(s.species[0].radius, 0.5);
    let w = worst_overlap(&s);
    assert!(w < 1e-12, "overlap {w:e}");
    assert!(Engine::new(s, EngineParams::default()).is_ok());
    spec.placement = Placement::Compressed {
        rate: 0.0,
        start: 0.3,
    };
    let err = spec.build().unwrap_err().to_string();
    assert!(err.contains("placement.compressed.rate"), "{err}");
}
