//! The engine against a brute-force O(N²) reference (test code only: no cells, no
//! queue, no delayed states), for small systems (N = 20–60): periodic, walled on both
//! axes and a channel (periodic x, walls y), several seeds, monodisperse and a binary
//! mixture with different radii and masses.
//!
//! Hard discs are chaotic, so two free-running trajectories can only be compared
//! below the chaos horizon. Hence (a) oracle checks ([`oracle_check`]): before every
//! event the brute-force reference gets the engine's exact state and must agree on
//! the next event, its time and the velocities; (b) a free-running comparison over
//! the first 200 events ([`free_running_matches_reference_below_chaos_horizon`]);
//! (c) oracle checks for random dynamics ([`oracle_random_dynamics`]). Tolerances
//! and why: [`time_tol`], [`tie_tol`] and [`conditioning`].

mod engine_common;
use carom_core::boundary::{wall_time, Boundary, SimBox, WallSide};
use carom_core::collision::resolve;
use carom_core::kinematics::contact_time;
use carom_core::{Axis, DVec2, Restitution, Species};
use carom_engine::{
    box_size_for, Engine, EngineError, EngineParams, Event, Neighbours, Placement, State,
    SystemSpec, Velocities,
};
use engine_common::draw_dynamics;

/// An event as the reference names it: pairs unordered (i < j), walls by disc, axis
/// and side.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Key {
    Pair(usize, usize),
    Wall(usize, usize, WallSide),
}

fn pair_key(i: usize, j: usize) -> Key {
    Key::Pair(i.min(j), i.max(j))
}

/// One predicted event: its key, the time until it (from the state's time) and, for a
/// pair, the separation r_j − r_i of the colliding image at the state's time.
#[derive(Debug, Clone, Copy)]
struct Predicted {
    key: Key,
    dt: f64,
    dr: DVec2,
}

/// The plain data the reference needs.
struct Discs<'a> {
    sim_box: SimBox,
    pos: &'a [DVec2],
    vel: &'a [DVec2],
    radius: Vec<f64>,
}

impl<'a> Discs<'a> {
    fn from_state(s: &'a State) -> Self {
        Discs {
            sim_box: s.sim_box,
            pos: &s.positions,
            vel: &s.velocities,
            radius: (0..s.len()).map(|i| s.radius(i)).collect(),
        }
    }
}

/// Image shifts to try along an axis: every neighbouring image on a periodic axis.
fn shifts(b: Boundary) -> &'static [f64] {
    if b.is_periodic() {
        &[-1.0, 0.0, 1.0]
    } else {
        &[0.0]
    }
}

/// Brute force: every pair (all images) and every wall, each with its time from now.
/// For a pair the earliest image is kept.
fn predict_all(d: &Discs) -> Vec<Predicted> {
    let n = d.pos.len();
    let l = d.sim_box.size;
    let mut out = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            let dr0 = d.pos[j] - d.pos[i];
            let dv = d.vel[j] - d.vel[i];
            let sigma = d.radius[i] + d.radius[j];
            let mut best: Option<(f64, DVec2)> = None;
            for &sx in shifts(d.sim_box.boundary[0]) {
                for &sy in shifts(d.sim_box.boundary[1]) {
                    let dr = dr0 + DVec2::new(sx * l.x, sy * l.y);
                    if let Some(t) = contact_time(dr, dv, sigma) {
                        if best.is_none_or(|(bt, _)| t < bt) {
                            best = Some((t, dr));
                        }
                    }
                }
            }
            if let Some((dt, dr)) = best {
                out.push(Predicted {
                    key: Key::Pair(i, j),
                    dt,
                    dr,
                });
            }
        }
        for axis in Axis::BOTH {
            let k = axis.index();
            if let Boundary::Walls { .. } = d.sim_box.boundary[k] {
                if let Some((dt, side)) = wall_time(d.pos[i][k], d.vel[i][k], d.radius[i], l[k]) {
                    out.push(Predicted {
                        key: Key::Wall(i, k, side),
                        dt,
                        dr: DVec2::ZERO,
                    });
                }
            }
        }
    }
    out
}

fn earliest(p: &[Predicted]) -> Predicted {
    *p.iter()
        .min_by(|a, b| a.dt.total_cmp(&b.dt))
        .expect("a system of moving discs always has a next event")
}

/// Agreement of event times: 1e-9 absolute plus 1e-9 relative.
///
/// Tolerances: event times are sums t = t_prediction + Δt with |t| ≲ 10³ and rounding
/// ≈ 1e-16 |t|; near-grazing contacts amplify the rounding of positions by
/// σ/√(σ² − h²), which stays far below 1e-9 except in vanishingly rare cases. A
/// contact time also moves by the rounding of positions over the approach speed
/// ([`conditioning`]): negligible at ordinary speeds, but an inelastic rule leaves
/// pairs moving together at relative speeds of 10⁻¹³, whose next contact rounding
/// alone decides (one such pair was 2·10⁻³ off); that much is allowed on top.
fn time_tol(t: f64) -> f64 {
    1e-9 * (1.0 + t.abs())
}

/// Exact ties: 1e-12 absolute plus 1e-12 relative (a few hundred ulps at t ≈ 10³).
fn tie_tol(t: f64) -> f64 {
    1e-12 * (1.0 + t.abs())
}

/// How far rounding alone can move the predicted time of `p` (time): positions
/// are known to about 64 ulp of the box size (the engine keeps paths as origin +
/// velocity × time, the reference gets rounded positions), and a contact time moves
/// by that over the approach speed: the normal relative speed at contact for a
/// pair, the normal speed for a wall. Negligible (≈ 10⁻¹³) at ordinary speeds; it
/// matters only for pairs that an inelastic rule left moving together at speeds of
/// order 10⁻¹³, whose next contact rounding alone decides.
fn conditioning(p: &Predicted, d: &Discs) -> f64 {
    let dx = 64.0 * f64::EPSILON * d.sim_box.size.max_element();
    let speed = match p.key {
        Key::Pair(i, j) => {
            let dv = d.vel[j] - d.vel[i];
            let at_contact = p.dr + dv * p.dt;
            at_contact.dot(dv).abs() / (d.radius[i] + d.radius[j])
        }
        Key::Wall(i, k, _) => d.vel[i][k].abs(),
    };
    dx / speed
}

fn key_of(ev: &Event) -> Key {
    match ev {
        Event::Pair(p) => pair_key(p.i as usize, p.j as usize),
        Event::Wall(w) => {
            let side = w.side;
            Key::Wall(w.i as usize, w.axis.index(), side)
        }
        Event::Scheduled { .. } | Event::Pause { .. } => {
            panic!("no events were scheduled, got {ev:?}")
        }
    }
}

/// A test system: species, packing fraction, aspect ratio L_x/L_y, boundaries, seed.
#[derive(Debug, Clone)]
struct System {
    name: &'static str,
    species: Vec<Species>,
    eta: f64,
    aspect: f64,
    walls: [bool; 2],
    seed: u64,
    placement: Placement,
}

impl System {
    fn state(&self) -> State {
        let size = box_size_for(&self.species, self.eta, self.aspect);
        let boundary = self.walls.map(|w| {
            if w {
                Boundary::Walls { restitution: 1.0 }
            } else {
                Boundary::Periodic
            }
        });
        let a_max = self.species.iter().map(|s| s.radius).fold(0.0, f64::max);
        assert!(
            size.min_element() >= 4.0 * 2.0 * a_max,
            "{}: box {size} is narrower than 4 diameters; the nearest image would be ambiguous",
            self.name
        );
        SystemSpec {
            species: self.species.clone(),
            sim_box: SimBox { size, boundary },
            temperature: 1.0,
            seed: self.seed,
            placement: self.placement.clone(),
            velocities: Velocities::MaxwellBoltzmann,
        }
        .build()
        .unwrap_or_else(|e| panic!("{}: {e}", self.name))
    }
}

fn mono(n: usize) -> Vec<Species> {
    vec![Species::reference(n)]
}

/// Binary mixture: small light discs and large heavy ones.
fn mixture(n_small: usize, n_large: usize) -> Vec<Species> {
    vec![Species::reference(n_small), Species::new(n_large, 0.7, 2.5)]
}

const PERIODIC: [bool; 2] = [false, false];
const WALLED: [bool; 2] = [true, true];
const CHANNEL: [bool; 2] = [false, true];

fn sys(
    name: &'static str,
    species: Vec<Species>,
    eta: f64,
    aspect: f64,
    walls: [bool; 2],
    seed: u64,
) -> System {
    System {
        name,
        species,
        eta,
        aspect,
        walls,
        seed,
        placement: Placement::Lattice,
    }
}

/// What the oracle check saw.
#[derive(Debug, Default)]
struct OracleReport {
    /// The run ended in the runaway report (allowed only where it may collapse).
    stalled: bool,
    pairs: u64,
    walls: u64,
    ties: u64,
    max_time_error: f64,
    end_time: f64,
}

/// (a) The oracle check for `events` consecutive events of `system` (elastic).
///
/// Why oracle checks. Hard discs are chaotic: a perturbation grows by a factor of
/// order ℓ/σ (mean free path over diameter) at every collision, so two independently
/// integrated trajectories that start one ulp apart — and the engine (which moves
/// each disc only at its own events and predicts from earlier states) rounds
/// differently from any other integrator — separate visibly after a few dozen
/// collisions per disc. Comparing two free-running trajectories over 10⁴ events would
/// therefore test nothing but the Lyapunov exponent. Instead, 10⁴ consecutive events
/// per system (see [`run_oracle`]): before every event the engine's exact state
/// (`Engine::state()`, positions at `now()`) is handed to the brute-force reference,
/// which computes the time of every pair contact (all periodic images with shifts
/// −1, 0, +1 per periodic axis, which contains the minimum image; boxes are ≥ 4
/// largest diameters wide, so the nearest image is unambiguous) and every wall
/// contact with the `carom_core` formulas. Then `next_event()` must report an event
/// the reference predicts, at the reference's time within 1e-9 (1 + t) (absolute 1e-9
/// plus relative 1e-9, [`time_tol`]), and that event must be the reference's
/// earliest: a different order is accepted only when the two times are equal within
/// 1e-12 (1 + t) (a genuine tie, [`tie_tol`]). The velocities the engine reports
/// before and after are also checked against `collision::resolve` (or the wall rule)
/// at the reference's contact normal, to 1e-9 of the velocity scale. Along the way
/// the engine's clock must never decrease.
fn oracle_check(system: &System, events: usize) -> OracleReport {
    oracle(system.state(), EngineParams::default(), system.name, events)
}

/// The oracle check for `events` consecutive events from `state0` with the dynamics
/// `params`. The rule the reference expects for each collision follows the TC
/// model: elastic if a disc of it collided (pair or wall) less than t_c before,
/// else the configured pair rule or the wall's restitution. A dissipative run
/// without the TC model may end early in the runaway report (`stalled`).
fn oracle(state0: State, params: EngineParams, name: &str, events: usize) -> OracleReport {
    let masses: Vec<f64> = (0..state0.len()).map(|i| state0.mass(i)).collect();
    let restitution_of = |k: usize| match state0.sim_box.boundary[k] {
        Boundary::Walls { restitution } => restitution,
        Boundary::Periodic => panic!("wall event on a periodic axis"),
    };
    let may_collapse = params.tc == 0.0
        && (!params.restitution.is_elastic()
            || (0..2).any(|k| {
                matches!(state0.sim_box.boundary[k], Boundary::Walls { restitution } if restitution < 1.0)
            }));
    // Time of each disc's last collision, for the TC model.
    let mut last = vec![f64::NEG_INFINITY; state0.len()];
    let within_tc = |last: &[f64], i: usize, t: f64| params.tc > 0.0 && t - last[i] < params.tc;
    let mut engine = Engine::new(state0.clone(), params).expect("engine");
    let mut report = OracleReport::default();
    let mut last_time = engine.now();
    for step in 0..events {
        let st = engine.state();
        let now = st.time;
        assert_eq!(now, engine.now());
        let discs = Discs::from_state(&st);
        let predicted = predict_all(&discs);
        let first = earliest(&predicted);
        let t_first = now + first.dt;

        let ev = match engine.next_event() {
            Ok(Some(ev)) => ev,
            Ok(None) => panic!("{name}: engine ran out of events"),
            Err(EngineError::Stalled { .. }) if may_collapse => {
                report.stalled = true;
                break;
            }
            Err(e) => panic!("{name}: engine error at step {step}: {e}"),
        };
        let t = ev.time();
        assert!(
            t >= last_time,
            "{}: time went backwards at step {step}: {last_time} → {t}",
            name
        );
        assert_eq!(engine.now(), t, "{}: clock ≠ event time", name);
        last_time = t;
        let key = key_of(&ev);
        let Some(mine) = predicted.iter().find(|p| p.key == key) else {
            panic!(
                "{}: step {step} at t = {t}: engine reports {key:?}, which the brute-force \
                 reference does not predict at all (reference's next: {:?} at {t_first})",
                name, first.key
            );
        };
        let t_ref = now + mine.dt;
        let err = (t - t_ref).abs();
        report.max_time_error = report.max_time_error.max(err);
        assert!(
            err <= time_tol(t_ref) + conditioning(mine, &discs),
            "{}: step {step}: {key:?} at {t}, reference says {t_ref} (error {err:e})",
            name
        );
        if key != first.key {
            // Only a genuine tie (or one that rounding decides) may come in a
            // different order.
            assert!(
                t_ref - t_first
                    <= tie_tol(t_first) + conditioning(mine, &discs) + conditioning(&first, &discs),
                "{}: step {step}: engine reports {key:?} at {t} but the reference's earliest \
                 event is {:?} at {t_first} ({:e} earlier)",
                name,
                first.key,
                t_ref - t_first
            );
            report.ties += 1;
        }
        let vscale = st.velocities.iter().map(|v| v.length()).fold(0.0, f64::max);
        match ev {
            Event::Pair(p) => {
                report.pairs += 1;
                let (i, j) = (p.i as usize, p.j as usize);
                assert_eq!(p.vi_before, st.velocities[i]);
                assert_eq!(p.vj_before, st.velocities[j]);
                // The reference's contact normal from i to j: the separation of the
                // colliding image at contact.
                let dr_ij = if i < j { mine.dr } else { -mine.dr };
                let at_contact = dr_ij + (st.velocities[j] - st.velocities[i]) * mine.dt;
                let sigma = discs.radius[i] + discs.radius[j];
                assert!(
                    (at_contact.length() - sigma).abs() <= 1e-9 * sigma,
                    "reference contact distance {} vs σ {sigma}",
                    at_contact.length()
                );
                let n = at_contact.normalize();
                // The contact point moves with the contact time: by |Δv| times the
                // time's rounding allowance.
                let dv = (st.velocities[j] - st.velocities[i]).length();
                let slide = if dv > 0.0 {
                    dv * conditioning(mine, &discs) / sigma
                } else {
                    0.0 // no relative motion: the contact point does not move
                };
                assert!(
                    (p.normal - n).length() <= 1e-9 + slide,
                    "{}: step {step}: normal {} vs reference {n}",
                    name,
                    p.normal
                );
                let rule = if within_tc(&last, i, t) || within_tc(&last, j, t) {
                    Restitution::Elastic
                } else {
                    params.restitution
                };
                (last[i], last[j]) = (t, t);
                let want = resolve(p.vi_before, p.vj_before, masses[i], masses[j], n, rule);
                // The velocities after are exactly those the logged impulse gives.
                assert_eq!(p.vi_after, p.vi_before + p.impulse / masses[i]);
                assert_eq!(p.vj_after, p.vj_before - p.impulse / masses[j]);
                let e = (p.vi_after - want.vi)
                    .length()
                    .max((p.vj_after - want.vj).length());
                assert!(
                    e <= 1e-9 * vscale,
                    "{}: step {step}: velocities after {:?} vs reference {:?}",
                    name,
                    (p.vi_after, p.vj_after),
                    (want.vi, want.vj)
                );
            }
            Event::Wall(w) => {
                report.walls += 1;
                let (i, k) = (w.i as usize, w.axis.index());
                assert_eq!(w.v_before, st.velocities[i]);
                let e = if within_tc(&last, i, t) {
                    1.0
                } else {
                    restitution_of(k)
                };
                last[i] = t;
                // v' = v + Δp/m exactly (what a reader of the log repeats), and
                // −e v_k to rounding of v_k along the wall's axis (v_k − (1 + e) v_k
                // cancels: relative to e v_k the error is ~ε (1 + e)/e); the other
                // component is kept.
                let dp = w.impulse_vector();
                assert_eq!(
                    w.v_after,
                    w.v_before + dp / masses[i],
                    "{}: wall impulse",
                    name
                );
                assert_eq!(dp[1 - k], 0.0, "{}: wall impulse off its axis", name);
                let want = -e * w.v_before[k];
                assert!(
                    (w.v_after[k] - want).abs() <= 4.0 * f64::EPSILON * w.v_before[k].abs(),
                    "{}: wall rule: {} vs {want}",
                    name,
                    w.v_after[k]
                );
                // Moving towards the wall it hits.
                let towards = match w.side {
                    WallSide::Low => w.v_before[k] < 0.0,
                    WallSide::High => w.v_before[k] > 0.0,
                };
                assert!(towards, "{}: wall hit while moving away", name);
            }
            Event::Scheduled { .. } | Event::Pause { .. } => unreachable!(),
        }
    }
    report.end_time = engine.now();
    report
}

fn run_oracle(systems: &[System]) {
    for s in systems {
        let r = oracle_check(s, 10_000);
        println!(
            "{} (seed {}): {} pair + {} wall events to t = {:.3}, {} ties, max |Δt| = {:e}",
            s.name, s.seed, r.pairs, r.walls, r.end_time, r.ties, r.max_time_error
        );
        assert_eq!(r.pairs + r.walls, 10_000);
        assert!(r.pairs > 0);
        if s.walls.iter().any(|&w| w) {
            assert!(r.walls > 0, "{}: walled box but no wall events", s.name);
        } else {
            assert_eq!(r.walls, 0);
        }
    }
}

/// The oracle check of [`oracle_check`] with the engine on neighbour lists
/// (engine::listed): dense and dilute, periodic, walled and channel boxes, and a
/// mixture of near sizes. A list that overflowed would hand back a pause, which
/// fails the check: every system stays on lists.
#[test]
fn oracle_on_neighbour_lists() {
    let systems = [
        sys(
            "lists periodic mono N=100 η=0.7",
            mono(100),
            0.7,
            1.0,
            PERIODIC,
            41,
        ),
        sys(
            "lists periodic mono N=40 η=0.35",
            mono(40),
            0.35,
            1.0,
            PERIODIC,
            42,
        ),
        sys(
            "lists walled mono N=100 η=0.72",
            mono(100),
            0.72,
            1.0,
            WALLED,
            43,
        ),
        sys(
            "lists channel mono N=60 η=0.45",
            mono(60),
            0.45,
            1.5,
            CHANNEL,
            44,
        ),
        sys(
            "lists periodic mix 40+10 η=0.6 ratio 1.1",
            vec![Species::new(40, 0.5, 1.0), Species::new(10, 0.55, 1.5)],
            0.6,
            1.0,
            PERIODIC,
            45,
        ),
    ];
    let lists = EngineParams {
        neighbours: Neighbours::Lists,
        ..EngineParams::default()
    };
    for s in &systems {
        let on = Engine::new(s.state(), lists).map(|e| e.neighbour_lists());
        assert_eq!(on, Ok(true), "{}", s.name);
        let r = oracle(s.state(), lists, s.name, 10_000);
        println!(
            "{}: {} pair + {} wall events to t = {:.3}, {} ties, max |Δt| = {:e}",
            s.name, r.pairs, r.walls, r.end_time, r.ties, r.max_time_error
        );
        assert_eq!(r.pairs + r.walls, 10_000);
        assert!(r.pairs > 0);
        assert_eq!(r.walls > 0, s.walls.iter().any(|&w| w), "{}", s.name);
    }
}

#[test]
fn oracle_periodic_monodisperse() {
    run_oracle(&[
        sys(
            "periodic mono N=40 η=0.35",
            mono(40),
            0.35,
            1.0,
            PERIODIC,
            1,
        ),
        sys(
            "periodic mono N=40 η=0.35",
            mono(40),
            0.35,
            1.0,
            PERIODIC,
            2,
        ),
        sys("periodic mono N=20 η=0.2", mono(20), 0.2, 1.0, PERIODIC, 3),
        System {
            placement: Placement::Random,
            ..sys(
                "periodic mono N=60 η=0.15 random",
                mono(60),
                0.15,
                1.5,
                PERIODIC,
                4,
            )
        },
    ]);
}

#[test]
fn oracle_walled_monodisperse() {
    run_oracle(&[
        sys("walled mono N=30 η=0.3", mono(30), 0.3, 1.0, WALLED, 11),
        sys("walled mono N=50 η=0.4", mono(50), 0.4, 0.7, WALLED, 12),
        sys("walled mono N=20 η=0.15", mono(20), 0.15, 1.3, WALLED, 13),
    ]);
}

#[test]
fn oracle_channel_monodisperse() {
    run_oracle(&[
        sys("channel mono N=40 η=0.3", mono(40), 0.3, 2.0, CHANNEL, 21),
        sys("channel mono N=60 η=0.45", mono(60), 0.45, 1.5, CHANNEL, 22),
    ]);
}

#[test]
fn oracle_periodic_mixture() {
    run_oracle(&[
        sys(
            "periodic mix 20+20 η=0.3",
            mixture(20, 20),
            0.3,
            1.0,
            PERIODIC,
            31,
        ),
        sys(
            "periodic mix 40+10 η=0.4",
            mixture(40, 10),
            0.4,
            1.0,
            PERIODIC,
            32,
        ),
    ]);
}

#[test]
fn oracle_walled_mixture() {
    run_oracle(&[
        sys(
            "walled mix 20+20 η=0.3",
            mixture(20, 20),
            0.3,
            1.0,
            WALLED,
            41,
        ),
        sys(
            "walled mix 15+15 η=0.25",
            mixture(15, 15),
            0.25,
            0.8,
            WALLED,
            42,
        ),
    ]);
}

#[test]
fn oracle_channel_mixture() {
    run_oracle(&[
        sys(
            "channel mix 25+25 η=0.35",
            mixture(25, 25),
            0.35,
            1.8,
            CHANNEL,
            51,
        ),
        sys(
            "channel mix 30+10 η=0.3",
            mixture(30, 10),
            0.3,
            1.2,
            CHANNEL,
            52,
        ),
    ]);
}

/// Small discs (diameter 1, mass 1) and a few much larger ones (diameter `ratio`,
/// mass ∝ area): each size gets its own cell grid (a grid per size class).
fn asymmetric(n_small: usize, n_large: usize, ratio: f64) -> Vec<Species> {
    vec![Species::reference(n_small), Species::scaled(n_large, ratio)]
}

/// Mixtures of very different sizes, where the engine keeps a cell grid per size
/// class and every disc also scans the other class's grid: the same events as the
/// brute-force reference, periodic, walled and in a channel. Each system is checked
/// to have two grids, so that the test exercises the scans across grids.
#[test]
fn oracle_size_classes() {
    let relaxed = |s: System| System {
        placement: Placement::Relaxed,
        ..s
    };
    let systems = [
        relaxed(sys(
            "periodic 200 + 4 diameter ratio 6 η=0.35",
            asymmetric(200, 4, 6.0),
            0.35,
            1.0,
            PERIODIC,
            61,
        )),
        relaxed(sys(
            "walled 200 + 3 diameter ratio 5 η=0.3",
            asymmetric(200, 3, 5.0),
            0.3,
            1.0,
            WALLED,
            62,
        )),
        relaxed(sys(
            "channel 240 + 4 diameter ratio 5 η=0.3",
            asymmetric(240, 4, 5.0),
            0.3,
            1.5,
            CHANNEL,
            63,
        )),
    ];
    for s in &systems {
        let e = Engine::new(s.state(), EngineParams::default()).unwrap();
        assert_eq!(e.grid_count(), 2, "{}: one grid per size class", s.name);
    }
    run_oracle(&systems);
}

/// The oracle check for random dynamics: 40 small systems (2–60 discs of one or two
/// species, radii 0.5–1, masses 0.2–5, η = 0.05–0.45, aspect 1/2–2, each axis
/// periodic or walled with restitution 1 or random, elastic pairs or either
/// inelastic model with a random coefficient, and the TC model off or on with
/// t_c = 10⁻³–10⁻¹), 2000 events each: every collision is the reference's next
/// event, at its time, resolved by the rule the TC model calls for. Seeded: case k
/// uses seed k. The reference also tracks each disc's last collision to know which
/// rule the TC model calls for (random boundaries include lossy walls).
#[test]
fn oracle_random_dynamics() {
    use rand::{RngExt, SeedableRng};
    let (mut checked, mut stalled, mut elastic_tc, mut lossy) = (0, 0, 0, 0);
    for case in 0..40u64 {
        let mut g = rand_pcg::Pcg64::seed_from_u64(case);
        let species: Vec<Species> = (0..g.random_range(1..=2usize))
            .map(|_| {
                Species::new(
                    g.random_range(1..=30usize),
                    g.random_range(0.5..1.0),
                    g.random_range(0.2..5.0),
                )
            })
            .collect();
        let eta = g.random_range(0.05..0.45);
        let aspect = 2f64.powf(g.random_range(-1.0..1.0));
        let mut axis = || match g.random_range(0..3) {
            0 => Boundary::Periodic,
            1 => Boundary::Walls { restitution: 1.0 },
            _ => Boundary::Walls {
                restitution: g.random_range(0.0..1.0),
            },
        };
        let boundary = [axis(), axis()];
        let (restitution, tc) = draw_dynamics(&mut g, -3.0..-1.0);
        let size = box_size_for(&species, eta, aspect);
        let a_max = species.iter().map(|s| s.radius).fold(0.0, f64::max);
        if size.min_element() < 8.0 * a_max || species.iter().map(|s| s.count).sum::<usize>() < 2 {
            continue; // the nearest image must be unambiguous (see `System::state`)
        }
        let Ok(state) = (SystemSpec {
            species,
            sim_box: SimBox { size, boundary },
            temperature: 1.0,
            seed: case,
            placement: Placement::Lattice,
            velocities: Velocities::MaxwellBoltzmann,
        })
        .build() else {
            continue;
        };
        let params = EngineParams {
            restitution,
            tc,
            max_events_without_time_advance: 1000,
            ..EngineParams::default()
        };
        let name = format!(
            "random case {case}: {params:?} {:?} {:?}",
            state.sim_box, state.species
        );
        let r = oracle(state, params, &name, 2000);
        assert!(r.stalled || r.pairs + r.walls == 2000, "case {case}: {r:?}");
        checked += 1;
        stalled += r.stalled as u32;
        elastic_tc += (tc > 0.0) as u32;
        lossy += (!restitution.is_elastic()) as u32;
    }
    println!("{checked} random systems checked: {stalled} collapsed, {elastic_tc} with TC, {lossy} with lossy pairs");
    assert!(
        checked >= 25 && elastic_tc >= 5 && lossy >= 5,
        "{checked} checked, {elastic_tc} TC, {lossy} lossy"
    );
}

/// (b) An independent integrator: every disc is advanced to every event.
struct Reference {
    sim_box: SimBox,
    pos: Vec<DVec2>,
    vel: Vec<DVec2>,
    radius: Vec<f64>,
    mass: Vec<f64>,
    time: f64,
}

impl Reference {
    fn new(s: &State) -> Self {
        Reference {
            sim_box: s.sim_box,
            pos: s.positions.clone(),
            vel: s.velocities.clone(),
            radius: (0..s.len()).map(|i| s.radius(i)).collect(),
            mass: (0..s.len()).map(|i| s.mass(i)).collect(),
            time: s.time,
        }
    }

    /// Find, advance to and resolve the next event; return it with its time.
    ///
    /// Exact ties (several events within `tie_tol` of the earliest, e.g. lattice discs
    /// that start touching a wall and all hit it at t = 0) may be processed in any
    /// order; the reference then takes `prefer` (the engine's choice) if it is one of
    /// the tied events, so that the two runs stay comparable.
    fn step(&mut self, prefer: Key) -> (Key, f64) {
        let discs = Discs {
            sim_box: self.sim_box,
            pos: &self.pos,
            vel: &self.vel,
            radius: self.radius.clone(),
        };
        let all = predict_all(&discs);
        let mut ev = earliest(&all);
        if ev.key != prefer {
            let t_first = self.time + ev.dt;
            if let Some(p) = all
                .iter()
                .find(|p| p.key == prefer && self.time + p.dt - t_first <= tie_tol(t_first))
            {
                ev = *p;
            }
        }
        for (r, v) in self.pos.iter_mut().zip(&self.vel) {
            *r = self.sim_box.wrap(*r + *v * ev.dt);
        }
        self.time += ev.dt;
        match ev.key {
            Key::Pair(i, j) => {
                let at_contact = ev.dr + (self.vel[j] - self.vel[i]) * ev.dt;
                let n = at_contact.normalize();
                let r = resolve(
                    self.vel[i],
                    self.vel[j],
                    self.mass[i],
                    self.mass[j],
                    n,
                    Restitution::Elastic,
                );
                self.vel[i] = r.vi;
                self.vel[j] = r.vj;
            }
            Key::Wall(i, k, _) => {
                let e = match self.sim_box.boundary[k] {
                    Boundary::Walls { restitution } => restitution,
                    Boundary::Periodic => unreachable!(),
                };
                self.vel[i][k] *= -e;
            }
        }
        (ev.key, self.time)
    }
}

/// Run engine and reference side by side for `events` events; return the largest
/// time difference and the largest velocity difference at the end.
fn free_run(system: &System, events: usize) -> (f64, f64) {
    let state = system.state();
    let mut reference = Reference::new(&state);
    let mut engine = Engine::new(state, EngineParams::default()).expect("engine");
    let mut max_dt: f64 = 0.0;
    for step in 0..events {
        let ev = engine.next_event().expect("engine").expect("an event");
        let key = key_of(&ev);
        let (key_ref, t_ref) = reference.step(key);
        let t = ev.time();
        assert_eq!(
            key, key_ref,
            "{}: event {step}: engine {key:?} at {t}, reference {key_ref:?} at {t_ref}",
            system.name
        );
        let err = (t - t_ref).abs();
        assert!(
            err <= time_tol(t_ref),
            "{}: event {step}: {key:?} at {t} vs reference {t_ref}",
            system.name
        );
        max_dt = max_dt.max(err);
    }
    let max_dv = (0..reference.vel.len())
        .map(|i| (engine.velocity(i) - reference.vel[i]).length())
        .fold(0.0, f64::max);
    // Positions too: the whole state agrees, not just the event list.
    let st = engine.state();
    for i in 0..reference.pos.len() {
        let d = st.sim_box.minimum_image(st.positions[i] - reference.pos[i]);
        assert!(
            d.length() <= 1e-9,
            "{}: disc {i} at {} vs reference {}",
            system.name,
            st.positions[i],
            reference.pos[i]
        );
    }
    (max_dt, max_dv)
}

/// (b) Free-running comparison below the chaos horizon. An independent reference
/// integrator ([`Reference`]: advance every disc to the next event, resolve it with
/// `collision::resolve`, repeat) runs side by side with the engine from the same
/// initial state; the two must report the same events (unordered pairs, walls) in
/// the same order at times within 1e-9 (1 + t) for the first 200 events, and end
/// with positions and velocities within 1e-9. The systems are moderately dense
/// (η = 0.4–0.5, N = 60): a perturbation grows at each collision by a factor of
/// order ℓ/σ, so counted in events the horizon is shortest in *dilute* systems.
/// Measured with this reference: at η = 0.1 (N = 30–40) the runs first differ by
/// more than 1e-9 after ≈ 100–170 events, at η = 0.4–0.5 (N = 60) after ≈ 320–640
/// events; after 200 events they agree to ≈ 1e-13–2e-12 in event times. The test
/// also asserts the time difference stays below 1e-10, so a systematic error
/// cannot hide behind chaos. Exactly simultaneous events (lattice discs that start
/// touching a wall all hit it at t = 0) may come in either order; the reference
/// then follows the engine's choice among the tied events.
#[test]
fn free_running_matches_reference_below_chaos_horizon() {
    let systems = [
        sys("periodic mono N=60 η=0.4", mono(60), 0.4, 1.0, PERIODIC, 61),
        sys("periodic mono N=60 η=0.4", mono(60), 0.4, 1.0, PERIODIC, 62),
        sys("walled mono N=60 η=0.5", mono(60), 0.5, 1.0, WALLED, 63),
        sys("channel mono N=60 η=0.4", mono(60), 0.4, 1.5, CHANNEL, 64),
        sys(
            "periodic mix 30+30 η=0.5",
            mixture(30, 30),
            0.5,
            1.0,
            PERIODIC,
            65,
        ),
        sys(
            "walled mix 30+30 η=0.5",
            mixture(30, 30),
            0.5,
            1.0,
            WALLED,
            66,
        ),
        sys(
            "channel mix 30+30 η=0.5",
            mixture(30, 30),
            0.5,
            1.5,
            CHANNEL,
            67,
        ),
    ];
    for s in &systems {
        let (max_dt, max_dv) = free_run(s, 200);
        println!(
            "{} (seed {}): 200 events identical, max |Δt| = {max_dt:e}, final max |Δv| = {max_dv:e}",
            s.name, s.seed
        );
        // Well inside the chaos horizon the two integrations differ by rounding only:
        // event times 10× better than the 1e-9 tolerance (measured ≤ 2.2e-12).
        assert!(
            max_dt <= 1e-10 && max_dv <= 1e-9,
            "{}: the runs already diverge (|Δt| {max_dt:e}, |Δv| {max_dv:e})",
            s.name
        );
    }
}

/// The reference itself, on a case with a known answer: two discs approaching head-on
/// in a periodic box meet when the gap closes, and a disc flying at a wall hits it
/// when its centre is one radius away. (If the reference were wrong, the oracle
/// checks above would compare the engine against nonsense.)
#[test]
fn reference_predicts_known_events() {
    let pos = [DVec2::new(2.0, 5.0), DVec2::new(6.0, 5.0)];
    let vel = [DVec2::new(1.0, 0.0), DVec2::new(-1.0, 0.0)];
    let discs = Discs {
        sim_box: SimBox::periodic(10.0, 10.0),
        pos: &pos,
        vel: &vel,
        radius: vec![0.5, 0.5],
    };
    let p = predict_all(&discs);
    // Direct approach: gap 3 closes at speed 2 → t = 1.5. Through the periodic image
    // (separation 6 the other way, also approaching) → t = 2.5; the earliest is kept.
    let e = earliest(&p);
    assert_eq!(e.key, Key::Pair(0, 1));
    assert_eq!(e.dt, 1.5);
    assert_eq!(e.dr, DVec2::new(4.0, 0.0));

    // Receding directly, approaching through the image: separation 10 − 4 = 6 → 2.5.
    let vel = [DVec2::new(-1.0, 0.0), DVec2::new(1.0, 0.0)];
    let discs = Discs { vel: &vel, ..discs };
    let e = earliest(&predict_all(&discs));
    assert_eq!(e.key, Key::Pair(0, 1));
    assert_eq!(e.dt, 2.5);

    let pos = [DVec2::new(2.0, 5.0)];
    let vel = [DVec2::new(-0.5, 0.0)];
    let discs = Discs {
        sim_box: SimBox::walled(10.0, 10.0, 1.0),
        pos: &pos,
        vel: &vel,
        radius: vec![0.5],
    };
    let e = earliest(&predict_all(&discs));
    assert_eq!(e.key, Key::Wall(0, 0, WallSide::Low));
    assert_eq!(e.dt, 3.0);
}
