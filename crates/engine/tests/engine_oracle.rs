//! The engine against an oracle with independent physics (`engine_common/oracle.rs`):
//! a brute-force O(N²) event-driven integrator with the seed's angular contact time
//! (`contact_time_seed`, Eq. 14–17) and component rule (`elastic_seed`, Eq. 8–13),
//! which the engine does not call, and its own free flight, minimum image, event
//! choice, wall time and specular wall rule. Shared with the engine: the initial
//! state, the `DVec2` arithmetic, the disc numbering.
//!
//! Run side by side, every event must be the same (pair, or disc, axis and wall) in
//! the same order while the divergence δ (the largest difference of an event time
//! in τ0, or of a velocity relative to the rms speed) stays below [`SEPARATED`];
//! chaos makes it grow from rounding, so the comparison stops there or at a
//! near-tie. At least [`MIN_AGREED`] events must agree, the first
//! [`ROUNDING_EVENTS`] within [`ROUNDING`], and both paths conserve energy (and
//! momentum along periodic axes) to rounding. Measurements: docs/testing.md, "Oracle".

mod engine_common;
use carom_core::{Boundary, DVec2, SimBox, Species, WallSide};
use carom_engine::{
    box_size_for, Engine, EngineParams, Event, Neighbours, Placement, State, SystemSpec, Velocities,
};
use engine_common::oracle::{earliest, Key, Oracle};
use engine_common::{mixture, mono};

/// The divergence δ (time in τ0, velocity relative to the rms speed) above which the
/// two trajectories count as separated and the comparison stops.
const SEPARATED: f64 = 1e-6;

/// Events that must agree before the trajectories separate (measured: 436 or more
/// in 100 runs; docs/testing.md, "Oracle").
const MIN_AGREED: usize = 300;

/// The first events, compared at rounding level.
const ROUNDING_EVENTS: usize = 50;

/// The largest divergence allowed over the first [`ROUNDING_EVENTS`] events: two
/// paths that differ by rounding only (measured ≤ 3.7e-13 in 100 runs,
/// docs/testing.md).
const ROUNDING: f64 = 1e-11;

/// The largest relative change of kinetic energy, and of momentum along periodic
/// axes (relative to Σ m|v|), over the compared stretch: rounding of at most a few
/// thousand events (measured ≤ 1.3e-15 in 100 runs).
const CONSERVED: f64 = 1e-12;

/// Events after which the comparison ends even if the paths still agree.
const MAX_EVENTS: usize = 5000;

/// The engine's event as a key, with the velocities after it of the discs of the key
/// (for a pair: the lower index first).
fn engine_event(ev: &Event) -> (Key, f64, Vec<DVec2>) {
    match ev {
        Event::Pair(p) => {
            let (i, j) = (p.i as usize, p.j as usize);
            if i < j {
                (Key::Pair(i, j), p.time, vec![p.vi_after, p.vj_after])
            } else {
                (Key::Pair(j, i), p.time, vec![p.vj_after, p.vi_after])
            }
        }
        Event::Wall(w) => (
            Key::Wall(w.i as usize, w.axis.index(), w.side),
            w.time,
            vec![w.v_after],
        ),
        Event::Scheduled { .. } | Event::Pause { .. } => {
            panic!("nothing was scheduled, got {ev:?}")
        }
    }
}

/// The discs of an event.
fn discs_of(key: Key) -> Vec<usize> {
    match key {
        Key::Pair(i, j) => vec![i, j],
        Key::Wall(i, _, _) => vec![i],
    }
}

/// What a side-by-side run saw.
#[derive(Debug, Default)]
struct Comparison {
    /// Events that agreed before the comparison stopped.
    agreed: usize,
    /// Why it stopped: "separated", "near-tie" or "limit".
    stop: &'static str,
    /// Largest divergence over the first [`ROUNDING_EVENTS`] events.
    rounding: f64,
    /// The per-event divergence (time and velocity difference of that event).
    divergence: Vec<f64>,
    /// Largest relative change of kinetic energy (engine, oracle) over the compared
    /// stretch, and of momentum along periodic axes (relative to Σ m |v|).
    energy_drift: [f64; 2],
    momentum_drift: [f64; 2],
    /// Events the oracle predicted through all images (see `safe_predictions`).
    all_images: usize,
}

impl Comparison {
    /// The first event whose divergence exceeds `level`.
    fn first_above(&self, level: f64) -> Option<usize> {
        self.divergence.iter().position(|&d| d > level)
    }

    /// The growth rate of the divergence (e-folds per event), from the events where
    /// it first exceeds 10⁻¹² and 10⁻⁸.
    fn growth(&self) -> f64 {
        match (self.first_above(1e-12), self.first_above(1e-8)) {
            (Some(a), Some(b)) if b > a => 4.0 * std::f64::consts::LN_10 / (b - a) as f64,
            _ => f64::NAN,
        }
    }
}

/// Run the engine and the oracle side by side from `state` and compare them event by
/// event (see the file's doc).
fn compare(name: &str, state: State, neighbours: Neighbours) -> Comparison {
    let mut oracle = Oracle::new(&state);
    let periodic = oracle.periodic;
    let (e0, p0) = oracle.energy_momentum();
    let p_scale: f64 = oracle
        .vel
        .iter()
        .zip(&oracle.mass)
        .map(|(v, m)| m * v.length())
        .sum();
    let v_rms = (oracle.vel.iter().map(|v| v.length_squared()).sum::<f64>()
        / oracle.vel.len() as f64)
        .sqrt();
    let params = EngineParams {
        neighbours,
        ..EngineParams::default()
    };
    let mut engine = Engine::new(state, params).expect("engine");
    assert_eq!(engine.neighbour_lists(), neighbours == Neighbours::Lists);
    let mut c = Comparison::default();
    let mut delta: f64 = 0.0;
    let drift = |e: f64, p: DVec2| {
        let dp = (0..2)
            .filter(|&k| periodic[k])
            .map(|k| (p[k] - p0[k]).abs())
            .fold(0.0, f64::max);
        ((e - e0).abs() / e0, dp / p_scale)
    };
    for step in 0..MAX_EVENTS {
        let predicted = oracle.safe_predictions();
        let mine = earliest(&predicted);
        let ev = engine.next_event().expect("engine").expect("an event");
        let (key, t, v_after) = engine_event(&ev);
        if key != mine.key {
            // The same event list must hold unless the two events are closer in time
            // than the divergence so far can resolve.
            let theirs = predicted.iter().find(|p| p.key == key);
            let gap = theirs.map_or(f64::INFINITY, |p| p.dt - mine.dt);
            let resolvable = 10.0 * delta.max(1e-13 * (1.0 + t.abs()));
            assert!(
                gap <= resolvable,
                "{name}: event {step}: engine {key:?} at {t}, oracle {:?} at {} \
                 (engine's event {gap:e} later in the oracle; divergence so far {delta:e})",
                mine.key,
                oracle.time + mine.dt
            );
            c.stop = "near-tie";
            break;
        }
        oracle.perform(mine);
        let dt = (t - oracle.time).abs();
        let dv = discs_of(key)
            .iter()
            .zip(&v_after)
            .map(|(&i, v)| (*v - oracle.vel[i]).length() / v_rms)
            .fold(0.0, f64::max);
        let d = dt.max(dv);
        c.divergence.push(d);
        delta = delta.max(d);
        if step < ROUNDING_EVENTS {
            c.rounding = delta;
        }
        let (de, dp) = drift(engine.kinetic_energy(), engine.state().momentum());
        let (oe, op) = oracle.energy_momentum();
        let (de_o, dp_o) = drift(oe, op);
        c.energy_drift = [c.energy_drift[0].max(de), c.energy_drift[1].max(de_o)];
        c.momentum_drift = [c.momentum_drift[0].max(dp), c.momentum_drift[1].max(dp_o)];
        if delta > SEPARATED {
            c.stop = "separated";
            break;
        }
        c.agreed = step + 1;
    }
    c.all_images = oracle.all_images;
    if c.stop.is_empty() {
        c.stop = "limit";
    }
    c
}

/// A test system: species at packing fraction 0.4 in a square box with the given
/// boundaries (elastic walls), placed at random without overlap, Maxwell–Boltzmann
/// velocities at kT = 1.
fn system(species: Vec<Species>, boundary: [Boundary; 2], seed: u64) -> State {
    let size = box_size_for(&species, 0.4, 1.0);
    SystemSpec {
        species,
        sim_box: SimBox { size, boundary },
        temperature: 1.0,
        seed,
        placement: Placement::Random,
        velocities: Velocities::MaxwellBoltzmann,
    }
    .build()
    .expect("system")
}

const PERIODIC: [Boundary; 2] = [Boundary::Periodic; 2];
const WALLED: [Boundary; 2] = [Boundary::Walls { restitution: 1.0 }; 2];
const CHANNEL: [Boundary; 2] = [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }];

/// The systems compared: one species or the mixture, periodic, walled on both axes
/// or a channel (periodic x, walls normal to y); N = 60 at η = 0.4.
fn systems() -> [(&'static str, Vec<Species>, [Boundary; 2]); 5] {
    [
        ("periodic N=60", mono(60), PERIODIC),
        ("walled N=60", mono(60), WALLED),
        ("periodic mixture 30+30", mixture(30, 30), PERIODIC),
        ("walled mixture 30+30", mixture(30, 30), WALLED),
        ("channel mixture 30+30", mixture(30, 30), CHANNEL),
    ]
}

/// Compare, print the measurements and assert the file's criteria.
fn check(name: &str, state: State, neighbours: Neighbours) -> Comparison {
    let n = state.len() as f64;
    let c = compare(name, state, neighbours);
    println!(
        "{name}: {} events agreed (stop: {}); divergence ≤ {:.1e} over the first \
         {ROUNDING_EVENTS}; first above 1e-12 / 1e-9 / 1e-6 at event {:?} / {:?} / {:?}; \
         growth {:.3} per event ({:.2} × 1/N); energy drift engine {:.1e} oracle {:.1e}; \
         momentum drift engine {:.1e} oracle {:.1e}; all images searched {} times",
        c.agreed,
        c.stop,
        c.rounding,
        c.first_above(1e-12),
        c.first_above(1e-9),
        c.first_above(1e-6),
        c.growth(),
        c.growth() * n,
        c.energy_drift[0],
        c.energy_drift[1],
        c.momentum_drift[0],
        c.momentum_drift[1],
        c.all_images,
    );
    assert!(
        c.rounding <= ROUNDING,
        "{name}: the first {ROUNDING_EVENTS} events already differ by {:e} (> {ROUNDING:e})",
        c.rounding
    );
    assert!(
        c.agreed >= MIN_AGREED,
        "{name}: only {} events agreed before the trajectories separated ({})",
        c.agreed,
        c.stop
    );
    for (what, x) in [("energy", c.energy_drift), ("momentum", c.momentum_drift)] {
        assert!(
            x[0] <= CONSERVED && x[1] <= CONSERVED,
            "{name}: {what} not conserved to rounding: engine {:e}, oracle {:e}",
            x[0],
            x[1]
        );
    }
    c
}

/// Every system, one seed each, against the oracle (about 1 s).
#[test]
fn engine_follows_the_seed_physics() {
    for (k, (name, species, boundary)) in systems().into_iter().enumerate() {
        let seed = k as u64 + 1;
        check(
            &format!("{name} seed {seed}"),
            system(species, boundary, seed),
            Neighbours::Cells,
        );
    }
}

/// The same on neighbour lists (engine::listed), for every system one cell grid
/// serves (the mixture's sizes, 1 and 1.4, share one).
#[test]
fn engine_on_lists_follows_the_seed_physics() {
    for (k, (name, species, boundary)) in systems().into_iter().enumerate() {
        let seed = k as u64 + 1;
        check(
            &format!("{name} seed {seed}, lists"),
            system(species, boundary, seed),
            Neighbours::Lists,
        );
    }
}

/// The horizons over 20 seeds per system, for docs/testing.md ("Oracle").
#[test]
#[ignore = "a survey of 100 runs for docs/testing.md (about 12 s of CPU); the default test runs one seed per system"]
fn survey_of_horizons() {
    for (name, species, boundary) in systems() {
        let runs: Vec<Comparison> = (100..120)
            .map(|seed| {
                check(
                    &format!("{name} seed {seed}"),
                    system(species.clone(), boundary, seed),
                    Neighbours::Cells,
                )
            })
            .collect();
        let mut agreed: Vec<usize> = runs.iter().map(|c| c.agreed).collect();
        agreed.sort();
        let mut growth: Vec<f64> = runs.iter().map(|c| c.growth()).collect();
        growth.sort_by(f64::total_cmp);
        let rounding = runs.iter().map(|c| c.rounding).fold(0.0, f64::max);
        let energy = runs
            .iter()
            .map(|c| c.energy_drift[0].max(c.energy_drift[1]))
            .fold(0.0, f64::max);
        let ties = runs.iter().filter(|c| c.stop == "near-tie").count();
        let images: usize = runs.iter().map(|c| c.all_images).sum();
        println!(
            "SURVEY {name}: events agreed min {} median {} max {}; growth per event median {:.3} \
             (range {:.3}–{:.3}); largest divergence over the first {ROUNDING_EVENTS} {rounding:.1e}; \
             largest energy drift {energy:.1e}; {ties} near-ties; all images searched {images} times",
            agreed[0], agreed[10], agreed[19], growth[10], growth[0], growth[19]
        );
    }
}

/// The oracle on cases with a known answer, so that the comparison above is against
/// the seed's physics and not against nonsense: two discs meeting head-on through
/// the periodic edge, and a disc reaching a wall one radius away and reflecting.
#[test]
fn oracle_knows_simple_answers() {
    let state = |sim_box: SimBox, positions: Vec<DVec2>, velocities: Vec<DVec2>| {
        let n = positions.len();
        SystemSpec {
            species: vec![Species::reference(n)],
            sim_box,
            temperature: 1.0,
            seed: 0,
            placement: Placement::Explicit(positions),
            velocities: Velocities::Explicit(velocities),
        }
        .build()
        .expect("state")
    };
    // Centres at x = 1.5 and 8.5 in a periodic box 10 wide: 3 apart through the
    // edge x = 0 ≡ 10, so a gap of 2 closing at relative speed 2: contact at t = 1.
    let mut o = Oracle::new(&state(
        SimBox::periodic(10.0, 10.0),
        vec![DVec2::new(1.5, 5.0), DVec2::new(8.5, 5.0)],
        vec![DVec2::new(-1.0, 0.0), DVec2::new(1.0, 0.0)],
    ));
    let first = earliest(&o.safe_predictions());
    assert_eq!(first.key, Key::Pair(0, 1));
    assert!((first.dt - 1.0).abs() < 1e-14, "{}", first.dt);
    o.perform(first);
    // Equal masses head-on: the velocities are exchanged; positions wrapped.
    assert!(
        (o.vel[0] - DVec2::new(1.0, 0.0)).length() < 1e-14,
        "{}",
        o.vel[0]
    );
    assert!(
        (o.vel[1] - DVec2::new(-1.0, 0.0)).length() < 1e-14,
        "{}",
        o.vel[1]
    );
    assert!(
        (o.pos[0] - DVec2::new(0.5, 5.0)).length() < 1e-14,
        "{}",
        o.pos[0]
    );
    assert!(
        (o.pos[1] - DVec2::new(9.5, 5.0)).length() < 1e-14,
        "{}",
        o.pos[1]
    );

    // Centres 4 apart (x = 3 and 7) moving apart: the nearest image recedes, and
    // they meet through the edge after the gap 10 − 4 − 1 = 5 closes at relative
    // speed 2 (every image is searched).
    let mut o = Oracle::new(&state(
        SimBox::periodic(10.0, 10.0),
        vec![DVec2::new(3.0, 5.0), DVec2::new(7.0, 5.0)],
        vec![DVec2::new(-1.0, 0.0), DVec2::new(1.0, 0.0)],
    ));
    let first = earliest(&o.safe_predictions());
    assert_eq!((first.key, o.all_images), (Key::Pair(0, 1), 1));
    assert!((first.dt - 2.5).abs() < 1e-14, "{}", first.dt);

    // A disc of radius 0.5 at y = 7 moving up at 2 in a box of height 10 touches the
    // wall when its centre is at 9.5: t = 1.25; then v_y reverses, v_x is kept.
    let mut o = Oracle::new(&state(
        SimBox::walled(10.0, 10.0, 1.0),
        vec![DVec2::new(5.0, 7.0)],
        vec![DVec2::new(0.5, 2.0)],
    ));
    let first = earliest(&o.safe_predictions());
    assert_eq!(first.key, Key::Wall(0, 1, WallSide::High));
    assert_eq!(first.dt, 1.25);
    o.perform(first);
    assert_eq!(o.vel[0], DVec2::new(0.5, -2.0));
    assert_eq!(o.pos[0], DVec2::new(5.625, 9.5));
}
