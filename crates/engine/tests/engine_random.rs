//! Random systems: the engine keeps its invariants across the whole space of
//! inputs, not only the handful of systems the other tests build.
//!
//! Each case is drawn from a seeded generator (case k uses seed k, so a failure names
//! a reproducible system; see [`draw`]), run with checks at every event and every 500
//! events ([`run`], [`random_systems_keep_every_invariant`]); the same random systems
//! also resume from a checkpoint bit-identically
//! ([`random_systems_resume_bit_identically`]).

mod engine_common;
use carom_core::{Axis, Boundary, SimBox, Species, WallSide};
use carom_engine::{
    box_size_for, Engine, EngineError, EngineParams, Event, InvariantChecker, Neighbours,
    Placement, SystemSpec, Velocities,
};
use engine_common::draw_dynamics;
use rand::{RngExt, SeedableRng};
use rand_pcg::Pcg64;

/// Cases run by [`random_systems_keep_every_invariant`].
const CASES: u64 = 400;

/// Events per case at most.
const EVENTS: u64 = 20_000;

/// A random system and its dynamics, drawn from a generator seeded with `case`: one
/// to three species (radii 0.5–2, masses 0.1–10, up to 120 discs each), lattice
/// placement at η = 0.05–0.65 or random placement at η = 0.02–0.25, aspect ratio
/// 1/4–4, each axis periodic or walled (elastic or lossy walls), elastic pairs or
/// either inelastic model with a coefficient in [0, 1), and the TC model off or on
/// with t_c = 10⁻⁴–10⁻¹.
fn draw(case: u64) -> (SystemSpec, EngineParams) {
    let mut g = Pcg64::seed_from_u64(case);
    let species: Vec<Species> = (0..g.random_range(1..=3usize))
        .map(|_| {
            Species::new(
                g.random_range(1..=120usize),
                0.5 * 4f64.powf(g.random::<f64>()),
                10f64.powf(g.random::<f64>() * 2.0 - 1.0),
            )
        })
        .collect();
    let random = g.random::<bool>();
    let eta = if random {
        g.random_range(0.02..0.25)
    } else {
        g.random_range(0.05..0.65)
    };
    let aspect = 4f64.powf(g.random::<f64>() * 2.0 - 1.0);
    let mut axis = || {
        if g.random::<bool>() {
            Boundary::Periodic
        } else if g.random::<bool>() {
            Boundary::Walls { restitution: 1.0 }
        } else {
            Boundary::Walls {
                restitution: g.random_range(0.0..1.0),
            }
        }
    };
    let boundary = [axis(), axis()];
    let size = box_size_for(&species, eta, aspect);
    let (restitution, tc) = draw_dynamics(&mut g, -4.0..-1.0);
    let spec = SystemSpec {
        species,
        sim_box: SimBox { size, boundary },
        temperature: 1.0,
        seed: case,
        placement: if random {
            Placement::Random
        } else {
            Placement::Lattice
        },
        velocities: Velocities::MaxwellBoltzmann,
    };
    let params = EngineParams {
        restitution,
        tc,
        max_events_without_time_advance: 2_000,
        ..EngineParams::default()
    };
    (spec, params)
}

/// Whether the run can lose energy (so that, without the TC model, it may collapse).
fn dissipative(spec: &SystemSpec, params: &EngineParams) -> bool {
    !params.restitution.is_elastic()
        || spec
            .sim_box
            .boundary
            .iter()
            .any(|b| matches!(b, Boundary::Walls { restitution } if *restitution < 1.0))
}

/// Run case `case`; `Ok(true)` if it ran to its end, `Ok(false)` if it collapsed
/// where that is allowed, `Err` with what went wrong otherwise.
///
/// Runs up to [`EVENTS`] events and checks, at every event:
///
/// * time never decreases, and the current time is the event's time;
/// * a pair collision happens at contact, |r_i − r_j| = a_i + a_j (minimum image)
///   to 1e-9 relative, with the discs approaching before and not after (normal
///   relative velocity, to rounding), and momentum conserved;
/// * a wall collision happens with the disc touching the wall, to 1e-9 of its
///   radius;
///
/// and every 500 events, with the [`InvariantChecker`]: no overlap beyond 1e-10
/// of the contact distance, energy conserved to 1e-12 in elastic runs, momentum
/// along periodic axes to 1e-12.
///
/// The only error allowed is the runaway report (`EngineError::Stalled`) of a
/// dissipative run without the TC model, which is how inelastic collapse must end.
/// With the TC model a dissipative run must go on: before the TC model covered wall
/// collisions, 13 of 600 such random systems with lossy walls stalled.
fn run(case: u64, neighbours: Neighbours) -> Result<bool, String> {
    let (spec, params) = draw(case);
    let params = EngineParams {
        neighbours,
        ..params
    };
    let Ok(state) = spec.build() else {
        // Mixtures at densities the lattice cannot reach are refused with an
        // error (tested in tests/initial_states.rs); nothing to run.
        return Ok(true);
    };
    let radius = |e: &Engine, i: u32| e.species()[e.species_of()[i as usize] as usize].radius;
    let mass = |e: &Engine, i: u32| e.species()[e.species_of()[i as usize] as usize].mass;
    let mut e = Engine::new(state, params).map_err(|err| err.to_string())?;
    let mut checker = InvariantChecker::new(&e);
    e.schedule(1e6, 0).map_err(|err| err.to_string())?;
    let size = e.sim_box().size;
    for k in 1..=EVENTS {
        let before = e.now();
        let event = match e.next_event() {
            Ok(Some(event)) => event,
            Ok(None) => return Err("the queue ran dry before the scheduled stop".into()),
            Err(EngineError::Stalled { .. }) if dissipative(&spec, &params) && params.tc == 0.0 => {
                return Ok(false)
            }
            Err(err) => return Err(format!("event {k}: {err}")),
        };
        if e.now() < before {
            return Err(format!("time went back from {before} to {}", e.now()));
        }
        match event {
            Event::Pair(p) => {
                let sigma = radius(&e, p.i) + radius(&e, p.j);
                let d = e
                    .sim_box()
                    .minimum_image(e.position(p.j as usize) - e.position(p.i as usize));
                if (d.length() - sigma).abs() > 1e-9 * sigma {
                    return Err(format!(
                        "{p:?}: distance {} at contact σ = {sigma}",
                        d.length()
                    ));
                }
                let u_before = (p.vj_before - p.vi_before).dot(p.normal);
                let u_after = (p.vj_after - p.vi_after).dot(p.normal);
                let scale = p.vi_before.length() + p.vj_before.length();
                if u_before > 1e-12 * scale || u_after < -1e-12 * scale {
                    return Err(format!("{p:?}: normal velocity {u_before} → {u_after}"));
                }
                let (mi, mj) = (mass(&e, p.i), mass(&e, p.j));
                let dp = (p.vi_after - p.vi_before) * mi + (p.vj_after - p.vj_before) * mj;
                if dp.length() > 1e-12 * scale * (mi + mj) {
                    return Err(format!("{p:?}: momentum changed by {dp}"));
                }
            }
            Event::Wall(w) => {
                let (k, r) = match w.axis {
                    Axis::X => (0, e.position(w.i as usize).x),
                    Axis::Y => (1, e.position(w.i as usize).y),
                };
                let a = radius(&e, w.i);
                let gap = match w.side {
                    WallSide::Low => r - a,
                    WallSide::High => size[k] - a - r,
                };
                if gap.abs() > 1e-9 * a {
                    return Err(format!("{w:?}: {gap} from the wall at contact"));
                }
            }
            Event::Scheduled { .. } | Event::Pause { .. } => return Ok(true),
        }
        if k % 500 == 0 {
            checker.check(&e).map_err(|v| format!("event {k}: {v}"))?;
        }
    }
    checker.check(&e).map_err(|v| format!("at the end: {v}"))?;
    Ok(true)
}

/// [`CASES`] random systems ([`draw`]), each run and checked by [`run`].
#[test]
fn random_systems_keep_every_invariant() {
    let mut failures = Vec::new();
    let mut collapsed = 0;
    for case in 0..CASES {
        match run(case, Neighbours::Auto) {
            Ok(true) => {}
            Ok(false) => collapsed += 1,
            Err(why) => {
                let (spec, params) = draw(case);
                failures.push(format!(
                    "case {case}: {why}\n  {params:?}\n  {:?}\n  {:?} {:?}",
                    spec.sim_box, spec.placement, spec.species
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {CASES} random systems failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
    eprintln!("{CASES} random systems: {collapsed} collapsed without the TC model, as allowed");
    // The search must reach collapses too, or it would not test their handling.
    assert!(collapsed > 0, "no case collapsed");
}

/// The same [`CASES`] random systems on neighbour lists (engine::listed),
/// where the engine can use them (one cell grid for all sizes, no box narrower
/// than three list cells): every invariant of [`run`] holds there too.
#[test]
fn random_systems_on_lists_keep_every_invariant() {
    let mut failures = Vec::new();
    let mut on_lists = 0;
    for case in 0..CASES {
        let (spec, params) = draw(case);
        let Ok(state) = spec.build() else { continue };
        let p = EngineParams {
            neighbours: Neighbours::Lists,
            ..params
        };
        match Engine::new(state, p) {
            Err(EngineError::ListsRefused(_)) => continue,
            Err(e) => panic!("case {case}: {e}"),
            Ok(_) => on_lists += 1,
        }
        if let Err(why) = run(case, Neighbours::Lists) {
            failures.push(format!("case {case}: {why}"));
        }
    }
    assert!(failures.is_empty(), "on lists:\n{}", failures.join("\n"));
    eprintln!("{on_lists} of {CASES} random systems ran on lists");
    assert!(
        on_lists >= CASES / 4,
        "only {on_lists} systems could use lists"
    );
}

/// Cases run by [`random_systems_resume_bit_identically`].
const RESUME_CASES: u64 = 150;

/// A checkpoint taken anywhere holds the whole dynamical state: for random systems,
/// on cells and (where the engine can use them) on neighbour lists
/// (as above), an engine restored from a checkpoint taken after 2000 events produces
/// the same next 3000 events, bit for bit, as the engine it was taken from
/// (including errors: a collapse is reported at the same event).
#[test]
fn random_systems_resume_bit_identically() {
    let mut compared = 0;
    let mut on_lists = 0;
    for (case, neighbours) in
        (0..RESUME_CASES).flat_map(|c| [(c, Neighbours::Auto), (c, Neighbours::Lists)])
    {
        let (spec, params) = draw(case);
        let Ok(state) = spec.build() else { continue };
        let params = EngineParams {
            neighbours,
            ..params
        };
        let mut a = match Engine::new(state, params) {
            Err(EngineError::ListsRefused(_)) => continue,
            made => made.expect("engine"),
        };
        on_lists += a.neighbour_lists() as usize;
        a.schedule(1e6, 0).expect("schedule");
        let mut ran = true;
        for _ in 0..2000 {
            if !matches!(a.next_event(), Ok(Some(Event::Pair(_) | Event::Wall(_)))) {
                ran = false;
                break;
            }
        }
        if !ran {
            continue;
        }
        let mut b = Engine::from_checkpoint(a.checkpoint()).expect("restored engine");
        for k in 0..3000 {
            let (x, y) = (a.next_event(), b.next_event());
            // Debug output of f64 is the shortest text that reads back to the same
            // bits, so equal texts mean bit-identical events.
            let (tx, ty) = (format!("{x:?}"), format!("{y:?}"));
            assert_eq!(
                tx, ty,
                "case {case}: event {k} after the checkpoint differs"
            );
            if x.is_err() {
                break;
            }
        }
        compared += 1;
    }
    assert!(
        compared > RESUME_CASES / 2 && on_lists > RESUME_CASES as usize / 4,
        "only {compared} cases compared, {on_lists} on lists"
    );
}
