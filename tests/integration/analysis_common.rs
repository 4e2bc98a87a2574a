//! Shared helpers of the analysis tests: the analysis of `carom analyze` fed
//! straight from the engine (no log file), and the standard fluid.
#![allow(dead_code)]

use carom_analysis::{AnalysisOptions, Analyzer, Report, RunDescription};
use carom_engine::{Engine, EngineParams, Event, State, SystemSpec, Velocities};

/// Run the engine from `spec` until `t_end`, with a snapshot (and thermo record)
/// every `dt`, feeding every event to an analyzer.
pub fn analyse(
    spec: SystemSpec,
    params: EngineParams,
    t_end: f64,
    dt: f64,
    opts: AnalysisOptions,
) -> Report {
    analyse_state(spec.build().unwrap(), params, t_end, dt, opts, None)
}

/// [`analyse`] from a given state at time 0, with the pair collision rate known
/// beforehand when `pair_rate` is given (as `carom analyze` knows it from the log's
/// thermo records).
pub fn analyse_state(
    state: State,
    params: EngineParams,
    t_end: f64,
    dt: f64,
    opts: AnalysisOptions,
    pair_rate: Option<f64>,
) -> Report {
    analyse_state_with(state, params, (t_end, dt), opts, pair_rate, |_| {}).0
}

/// [`analyse_state`] with `setup` applied to the engine before the run (a
/// thermostat, say); also returns the engine as the run left it.
pub fn analyse_state_with(
    state: State,
    params: EngineParams,
    (t_end, dt): (f64, f64),
    opts: AnalysisOptions,
    pair_rate: Option<f64>,
    setup: impl FnOnce(&mut Engine),
) -> (Report, Engine) {
    assert_eq!(state.time, 0.0);
    let run = RunDescription {
        species: state.species.clone(),
        sim_box: state.sim_box,
        restitution: params.restitution,
        collision_stride: 1,
        totals_from_thermo: false,
        t_start: 0.0,
        t_end,
        pair_rate,
        snapshot_interval: Some(dt),
        snapshot_schedule: None,
        gravity: params.gravity,
    };
    let mut a = Analyzer::new(run, opts).unwrap();
    let mut engine = Engine::new(state, params).unwrap();
    setup(&mut engine);
    feed(&mut engine, &mut a, 0.0, dt, (t_end / dt).round() as u64);
    (a.finish().unwrap(), engine)
}

/// Run `engine` from `t0` to `t0 + steps·dt`, feeding every event to `a`, with a
/// snapshot (positions, velocities and a thermo record) at each multiple of `dt`.
pub fn feed(engine: &mut Engine, a: &mut Analyzer, t0: f64, dt: f64, steps: u64) {
    for k in 0..=steps {
        engine.schedule(t0 + k as f64 * dt, k).unwrap();
    }
    let mut lost = 0.0;
    while let Some(ev) = engine.next_event().unwrap() {
        match ev {
            Event::Pair(p) => {
                lost += p.energy_lost;
                a.pair(p.time, p.virial, p.energy_lost);
                let v = |d: carom_core::DVec2| [d.x, d.y];
                a.pair_detail(
                    p.time,
                    (p.i, p.j),
                    v(p.normal),
                    [v(p.vi_after), v(p.vj_after)],
                );
            }
            Event::Wall(w) => {
                lost += w.energy_lost;
                a.wall(w.time, w.impulse, w.energy_lost);
            }
            Event::Pause { .. } => {}
            Event::Scheduled { time, tag } => {
                let s = engine.state();
                let (vx, vy): (Vec<f64>, Vec<f64>) =
                    s.velocities.iter().map(|v| (v.x, v.y)).unzip();
                let (px, py): (Vec<f64>, Vec<f64>) = s.positions.iter().map(|p| (p.x, p.y)).unzip();
                a.thermo(time, s.kinetic_energy(), Some(lost));
                a.snapshot(time, &s.species_of, &vx, &vy).unwrap();
                a.positions(time, &s.species_of, &px, &py).unwrap();
                if tag == steps {
                    break;
                }
            }
        }
    }
}

pub fn fluid(n: usize, eta: f64, seed: u64, velocities: Velocities) -> SystemSpec {
    SystemSpec {
        velocities,
        ..SystemSpec::periodic_fluid(n, eta, seed)
    }
}
