//! `carom.Simulation`: a run held in memory. The configuration is the JSON of
//! `carom run` (a dict, or its text), checked and resolved by carom-config and
//! placed by the engine exactly as the command does, so the same configuration
//! and seed give the command's trajectory bit for bit: observing a state, like
//! the command's snapshots, never disturbs it (carom-engine's `Engine::state`).
//!
//! `run` hands the engine to a thread without the GIL in slices of [`SLICE`]
//! events; between slices it takes the GIL back to look at signals, so Ctrl-C
//! raises `KeyboardInterrupt` between two events (the state is consistent and
//! the run can go on). Stops and callbacks are scheduled events of the engine,
//! at exact times: a callback at t sees the state at t, not at the next collision.

use carom_config::{Config, ConfigError};
use carom_engine::{Engine, Event};
use carom_log::{RunSpec, Stop};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::path::PathBuf;

use crate::arrays::Arrays;
use crate::errors;
use crate::logged;

/// Events (collisions, scheduled and internal pauses) between two looks at the
/// signals: about a millisecond of work at N = 10⁴.
const SLICE: u32 = 20_000;

/// A hard-disc system in memory, built from the JSON configuration's fields.
#[pyclass(module = "carom._carom")]
pub struct Simulation {
    engine: Engine,
    /// The run's stop from the configuration (`stop.duration` or `stop.collisions`).
    stop: Stop,
    /// The resolved configuration (JSON text, every default filled in).
    config_json: String,
    /// What a logged run hands to carom-run (`logged.rs`).
    spec: RunSpec,
    /// The log whose final state the simulation holds, after a logged run.
    log: Option<PathBuf>,
    /// Whether the simulation has run (logged or not) since it was built.
    ran: bool,
    /// The next unused tag of a scheduled event; each `run` takes two, so that an
    /// interrupted run's stop is never mistaken for a later run's. Counted from 1,
    /// below carom-run's observation tags (from 2⁵⁶), which an engine restored
    /// from a log's checkpoint still holds and `run` passes over.
    next_tag: u64,
}

/// How a slice of the run ended.
enum Slice {
    /// The stop time, or the collisions asked for, was reached.
    Done,
    /// A callback time was reached: call back, then go on.
    Callback,
    /// The slice's events are used up: look at the signals, then go on.
    More,
    /// Nothing will ever happen again.
    Exhausted,
}

/// The tags of one `run`: its stop and its callbacks.
#[derive(Clone, Copy)]
struct Tags {
    stop: u64,
    every: u64,
}

/// Process events until the stop, a callback, the end of the slice or the end of
/// all events; `left` counts the collisions still wanted.
fn slice(engine: &mut Engine, tags: Tags, left: &mut u64) -> Result<Slice, String> {
    for _ in 0..SLICE {
        if *left == 0 {
            return Ok(Slice::Done);
        }
        match engine.next_event().map_err(|e| e.to_string())? {
            None => return Ok(Slice::Exhausted),
            Some(Event::Pair(_) | Event::Wall(_)) => *left -= 1,
            Some(Event::Scheduled { tag, .. }) if tag == tags.stop => return Ok(Slice::Done),
            Some(Event::Scheduled { tag, .. }) if tag == tags.every => return Ok(Slice::Callback),
            // A pause (long unobservable work), or an interrupted run's stop.
            Some(Event::Scheduled { .. } | Event::Pause { .. }) => {}
        }
    }
    Ok(Slice::More)
}

impl Simulation {
    /// The configuration as JSON text: a `str` as it is, anything else through
    /// `json.dumps`.
    fn config_text(config: Option<&Bound<'_, PyAny>>) -> PyResult<String> {
        let Some(c) = config else {
            return Ok("{}".into());
        };
        if let Ok(s) = c.cast::<PyString>() {
            return Ok(s.to_str()?.to_owned());
        }
        let json = c.py().import("json")?;
        json.call_method1("dumps", (c,))?.extract()
    }

    /// Schedule `tag` at `t`, refusing a time before now in words.
    fn schedule(&mut self, t: f64, tag: u64) -> PyResult<()> {
        self.engine
            .schedule(t, tag)
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// Where `run(until, collisions)` stops: at time `until`, after `collisions`
    /// more collisions (a total since the start), or with neither at the
    /// configuration's stop.
    fn stop_at(&self, until: Option<f64>, collisions: Option<u64>) -> PyResult<Stop> {
        Ok(match (until, collisions) {
            (Some(t), None) => Stop::Time(t),
            (None, Some(n)) => Stop::Collisions(self.collisions_now().saturating_add(n)),
            (None, None) => self.stop,
            _ => return Err(PyValueError::new_err("give until or collisions, not both")),
        })
    }

    /// `run` with a log (`logged.rs`).
    fn run_logged(
        &mut self,
        py: Python<'_>,
        until: Option<f64>,
        collisions: Option<u64>,
        path: &std::path::Path,
    ) -> PyResult<u64> {
        let stop = self.stop_at(until, collisions)?;
        let start = logged::start(&self.spec, self.log.as_deref(), !self.ran, path)?;
        let before = self.collisions_now();
        let (engine, signal) = logged::run(py, start, stop, path, &self.config_json)?;
        self.engine = engine;
        self.ran = true;
        self.log = Some(path.to_path_buf());
        match signal {
            Some(e) => Err(e),
            None => Ok(self.collisions_now() - before),
        }
    }

    fn collisions_now(&self) -> u64 {
        let s = self.engine.stats();
        s.pair_collisions + s.wall_collisions
    }
}

#[pymethods]
impl Simulation {
    /// Build the system of `config` (a dict with the fields of carom's JSON
    /// configuration, or its text; `None`: the built-in default). A configuration
    /// the command refuses raises `ValueError` with the command's message, which
    /// names the field (`species.0.radius: …`).
    #[new]
    #[pyo3(signature = (config=None))]
    fn new(config: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let text = Self::config_text(config)?;
        let spec = Config::from_json_with_sets(&text, "configuration", &[])
            .and_then(|c| c.to_run_spec())
            .map_err(errors::config)?;
        carom_run::check_memory(&spec).map_err(errors::config)?;
        let state = spec
            .system
            .build()
            .map_err(|e| errors::config(ConfigError::from_init_in(e, &spec.config_json)))?;
        let mut engine = Engine::new(state, spec.params).map_err(errors::config)?;
        engine
            .set_thermostat(spec.thermostat, spec.system.seed)
            .map_err(errors::config)?;
        Ok(Simulation {
            engine,
            stop: spec.stop,
            config_json: spec.config_json.clone(),
            spec,
            log: None,
            ran: false,
            next_tag: 1,
        })
    }

    /// Run until time `until`, or for `collisions` more collisions (pair +
    /// wall); with neither, to the configuration's stop. With `every` and
    /// `callback`, call `callback(state)` at now + k·every (k = 1, 2, …, up to
    /// the stop). Releases the GIL; Ctrl-C raises `KeyboardInterrupt` between
    /// two events. Returns the number of collisions run.
    ///
    /// With `log`, the run writes the log `carom run` writes (`logged.rs`): from
    /// a simulation at its start, or continuing the log its last run wrote.
    #[pyo3(signature = (until=None, collisions=None, every=None, callback=None, log=None))]
    fn run(
        &mut self,
        py: Python<'_>,
        until: Option<f64>,
        collisions: Option<u64>,
        every: Option<f64>,
        callback: Option<Py<PyAny>>,
        log: Option<PathBuf>,
    ) -> PyResult<u64> {
        if let Some(path) = log {
            if every.is_some() || callback.is_some() {
                return Err(PyValueError::new_err(
                    "a logged run takes no callback (read its snapshots with open_log)",
                ));
            }
            return self.run_logged(py, until, collisions, &path);
        }
        self.ran = true;
        self.log = None;
        let (until, mut left) = match self.stop_at(until, collisions)? {
            Stop::Time(t) => (Some(t), u64::MAX),
            Stop::Collisions(n) => (None, n.saturating_sub(self.collisions_now())),
        };
        let every = match (every, &callback) {
            (Some(dt), Some(_)) if dt.is_finite() && dt > 0.0 => Some(dt),
            (Some(dt), Some(_)) => {
                return Err(PyValueError::new_err(format!(
                    "every = {dt}: not a positive finite time"
                )))
            }
            (None, None) => None,
            _ => return Err(PyValueError::new_err("every and callback go together")),
        };
        let tags = Tags {
            stop: self.next_tag,
            every: self.next_tag + 1,
        };
        self.next_tag += 2;
        let start = self.collisions_now();
        let t0 = self.engine.now();
        if let Some(t) = until {
            if !(t.is_finite() && t >= t0) {
                return Err(PyValueError::new_err(format!(
                    "until = {t}: not a finite time at or after now ({t0})"
                )));
            }
            self.schedule(t, tags.stop)?;
        }
        // Callback k is due at t0 + k·every; `k` is the next one's.
        let due = |k: u64| every.map(|dt| t0 + k as f64 * dt);
        let mut k = 1;
        let in_run = |t: f64| until.is_none_or(|u| t < u);
        if let Some(t) = due(k).filter(|&t| in_run(t)) {
            self.schedule(t, tags.every)?;
        }
        loop {
            let engine = &mut self.engine;
            let ended = py.detach(|| slice(engine, tags, &mut left));
            match ended.map_err(errors::engine)? {
                Slice::Done => {
                    // A callback due at the stop time itself comes last.
                    if let (Some(cb), Some(t), Some(u)) = (&callback, due(k), until) {
                        if t <= u && left > 0 {
                            cb.call1(py, (self.state(py)?,))?;
                        }
                    }
                    break;
                }
                Slice::Callback => {
                    if let Some(cb) = &callback {
                        cb.call1(py, (self.state(py)?,))?;
                    }
                    k += 1;
                    if let Some(t) = due(k).filter(|&t| in_run(t)) {
                        self.schedule(t, tags.every)?;
                    }
                }
                Slice::More => {}
                Slice::Exhausted => break,
            }
            py.check_signals()?;
        }
        Ok(self.collisions_now() - start)
    }

    /// The state now: a dict of numpy arrays `x`, `y`, `vx`, `vy` (float64),
    /// `image` (int32, N × 2), `species` (int32), `radius`, `mass` (float64),
    /// with `time` and `box`; disc i is the configuration's disc i.
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.engine.state();
        let radius: Vec<f64> = s.species.iter().map(|sp| sp.radius).collect();
        let mass: Vec<f64> = s.species.iter().map(|sp| sp.mass).collect();
        Arrays {
            time: s.time,
            box_size: s.sim_box.size,
            species_radius: &radius,
            species_mass: &mass,
            species: &s.species_of,
            positions: &s.positions,
            velocities: &s.velocities,
            images: &s.images,
        }
        .to_dict(py)
    }

    /// Simulated time now.
    #[getter]
    fn time(&self) -> f64 {
        self.engine.now()
    }

    /// Collisions (pair + wall) since the start.
    #[getter]
    fn collisions(&self) -> u64 {
        self.collisions_now()
    }

    /// Pair collisions since the start.
    #[getter]
    fn pair_collisions(&self) -> u64 {
        self.engine.stats().pair_collisions
    }

    /// Wall collisions since the start.
    #[getter]
    fn wall_collisions(&self) -> u64 {
        self.engine.stats().wall_collisions
    }

    /// Kinetic energy K = Σ m v²/2.
    #[getter]
    fn kinetic_energy(&self) -> f64 {
        self.engine.kinetic_energy()
    }

    /// Potential energy U = Σ m g y in the field (0 without one).
    #[getter]
    fn potential_energy(&self) -> f64 {
        self.engine.potential_energy()
    }

    /// Kinetic energy dissipated in collisions since the start.
    #[getter]
    fn energy_lost(&self) -> f64 {
        self.engine.stats().energy_lost
    }

    /// Number of discs N.
    fn __len__(&self) -> usize {
        self.engine.len()
    }

    /// The resolved configuration (every default filled in) as JSON text.
    #[getter]
    fn config_json(&self) -> &str {
        &self.config_json
    }
}
