//! `carom.Simulation`: a run held in memory. The configuration is the JSON of
//! `carom run` (a dict, or its text), checked and resolved by carom-config and
//! placed by the engine exactly as the command does, so the same configuration
//! and seed give the command's trajectory bit for bit: observing a state, like
//! the command's snapshots, never disturbs it (carom-engine's `Engine::state`).
//!
//! `run` without a log is `stepping.rs`'s loop: the GIL released, Ctrl-C
//! between two events, callbacks at exact times; with a log it is carom-run's
//! (`logged.rs`).
//! With `live`, the run is served to a viewer as `carom run --live` serves it
//! (`live.rs`); without, the loop does no more than before.

use carom_config::{Config, ConfigError};
use carom_engine::{Engine, InitError, State};
use carom_log::{RunSpec, Stop};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyString};
use std::path::PathBuf;

use crate::arrays::Columns;
use crate::errors;
use crate::from_arrays;
use crate::live::{self, Asked, Serving};
use crate::logged;

mod stepping;

use stepping::{Every, Tags, TAGS_PER_RUN};

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
    /// The next unused tag of a scheduled event; each `run` takes four, so that an
    /// interrupted run's stop is never mistaken for a later run's. Counted from 1,
    /// below carom-run's observation tags (from 2⁵⁶), which an engine restored
    /// from a log's checkpoint still holds and `run` passes over.
    next_tag: u64,
    /// The user's index of each engine disc, when they differ: discs given by
    /// `from_arrays` with unsorted species are grouped by species in the engine
    /// (and in a log), as `placement.explicit` orders them.
    user_of: Option<Vec<u32>>,
    /// The simulation's start time (t₀ of its `/thermo` series when served live).
    start_time: f64,
    /// The live server, while the simulation serves (`live.rs`).
    live: Option<Serving>,
}

/// A configuration's text made into the command's run and its initial state
/// (resolved, memory checked, discs placed), or the command's error; `init`
/// names a builder's error in the caller's terms.
fn prepare(
    text: &str,
    init: impl FnOnce(InitError, &str) -> ConfigError,
) -> Result<(RunSpec, State), ConfigError> {
    let spec = Config::from_json_with_sets(text, "configuration", &[])?.to_run_spec()?;
    carom_run::check_memory(&spec)?;
    let state = spec
        .system
        .build()
        .map_err(|e| init(e, &spec.config_json))?;
    Ok((spec, state))
}

/// A Python value (a dict, list, number or text) as JSON, through `json.dumps`.
fn to_json(name: &str, v: &Bound<'_, PyAny>) -> PyResult<serde_json::Value> {
    let text: String = v
        .py()
        .import("json")?
        .call_method1("dumps", (v,))?
        .extract()?;
    serde_json::from_str(&text).map_err(|e| PyValueError::new_err(format!("{name}: {e}")))
}

impl Simulation {
    /// A simulation of `spec` from its initial `state`; `user_of` as the field.
    fn start(spec: RunSpec, state: State, user_of: Option<Vec<u32>>) -> PyResult<Self> {
        let mut engine = Engine::new(state, spec.params).map_err(errors::config)?;
        engine
            .set_thermostat(spec.thermostat, spec.system.seed)
            .map_err(errors::config)?;
        Ok(Simulation {
            start_time: engine.now(),
            live: None,
            engine,
            stop: spec.stop,
            config_json: spec.config_json.clone(),
            spec,
            log: None,
            ran: false,
            next_tag: 1,
            user_of,
        })
    }

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
        served: bool,
    ) -> PyResult<u64> {
        let stop = self.stop_at(until, collisions)?;
        let start = logged::start(&self.spec, self.log.as_deref(), !self.ran, path)?;
        let before = self.collisions_now();
        let observer = self.live.as_mut().filter(|_| served).map(Serving::observer);
        let (engine, signal) = logged::run(py, start, stop, path, &self.config_json, observer)?;
        self.engine = engine;
        if let Some(s) = self.live.as_mut().filter(|_| served) {
            s.logged(&self.engine);
        }
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
        let (spec, state) = prepare(&text, ConfigError::from_init_in).map_err(errors::config)?;
        Self::start(spec, state, None)
    }

    /// Build the system of arrays: disc i at (`x[i]`, `y[i]`) moving at
    /// (`vx[i]`, `vy[i]`), in a box of size `box` = (L_x, L_y) with `boundaries`
    /// (`"periodic"`, `"walls"`, or per axis `{"x": ..., "y": ...}`). Radii and
    /// masses: `radius` and `mass` (a number for all discs or one per disc;
    /// default 0.5 and 1), or `species` (an integer per disc) indexing
    /// `species_radius` and `species_mass` (default 1). `collision` is the
    /// configuration's `collision` dict, `wall_restitution` its
    /// `box.wall_restitution`; any other field of the configuration (`seed`,
    /// `stop`, `log`, `gravity`, `thermostat`, ...) is a keyword argument.
    ///
    /// The system is the one `carom run` builds from the configuration with
    /// `placement.explicit` and `velocities.explicit` (`config_json` shows it),
    /// with its checks; errors raise `ValueError` naming the argument and the
    /// disc (`x[3]: value 11 lies outside the box ...`). Disc i of `state` is
    /// disc i of the arrays; a log lists the discs species by species.
    #[staticmethod]
    #[pyo3(signature = (x, y, vx, vy, *, r#box, radius=None, mass=None, species=None,
                        species_radius=None, species_mass=None, boundaries=None,
                        wall_restitution=None, collision=None, **config))]
    #[allow(clippy::too_many_arguments)]
    fn from_arrays(
        x: &Bound<'_, PyAny>,
        y: &Bound<'_, PyAny>,
        vx: &Bound<'_, PyAny>,
        vy: &Bound<'_, PyAny>,
        r#box: (f64, f64),
        radius: Option<&Bound<'_, PyAny>>,
        mass: Option<&Bound<'_, PyAny>>,
        species: Option<&Bound<'_, PyAny>>,
        species_radius: Option<&Bound<'_, PyAny>>,
        species_mass: Option<&Bound<'_, PyAny>>,
        boundaries: Option<&Bound<'_, PyAny>>,
        wall_restitution: Option<f64>,
        collision: Option<&Bound<'_, PyAny>>,
        config: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        use from_arrays::{floats, per_disc, Kinds};
        let columns = [
            floats("x", x)?,
            floats("y", y)?,
            floats("vx", vx)?,
            floats("vy", vy)?,
        ];
        let kinds = match (species, species_radius) {
            (Some(s), Some(r)) => {
                if radius.is_some() || mass.is_some() {
                    return Err(PyValueError::new_err(
                        "radius, mass: give them per disc, or species with species_radius \
                         (and species_mass), not both",
                    ));
                }
                let radius = floats("species_radius", r)?;
                let mass = match species_mass {
                    Some(m) => floats("species_mass", m)?,
                    None => vec![1.0; radius.len()],
                };
                let species = floats("species", s)?;
                Kinds::Species {
                    species,
                    radius,
                    mass,
                }
            }
            (None, None) if species_mass.is_none() => Kinds::Discs {
                radius: per_disc("radius", radius, 0.5)?,
                mass: per_disc("mass", mass, 1.0)?,
            },
            _ => {
                return Err(PyValueError::new_err(
                    "species: species (an index per disc) and species_radius (a radius per \
                     species) go together, species_mass optional",
                ))
            }
        };
        let mut sim_box = serde_json::Map::new();
        sim_box.insert("size".into(), serde_json::json!([r#box.0, r#box.1]));
        if let Some(b) = boundaries {
            sim_box.insert("boundary".into(), to_json("boundaries", b)?);
        }
        if let Some(e) = wall_restitution {
            sim_box.insert("wall_restitution".into(), e.into());
        }
        let mut rest = serde_json::Map::new();
        if let Some(c) = collision {
            rest.insert("collision".into(), to_json("collision", c)?);
        }
        for (k, v) in config.into_iter().flat_map(|c| c.iter()) {
            let k: String = k.extract()?;
            let v = to_json(&k, &v)?;
            rest.insert(k, v);
        }
        let p = from_arrays::prepare(columns, kinds, sim_box, rest)?;
        let (spec, state) = prepare(&p.text, |e, json| p.init_error(e, json))
            .map_err(|e| errors::config(p.config_error(e)))?;
        Self::start(spec, state, p.user_of)
    }

    /// Run until time `until`, or for `collisions` more collisions (pair +
    /// wall); with neither, to the configuration's stop. With `every` and
    /// `callback`, call `callback(state)` at now + k·every (k = 1, 2, …, up to
    /// the stop). Releases the GIL; Ctrl-C raises `KeyboardInterrupt` between
    /// two events. Returns the number of collisions run.
    ///
    /// With `log`, the run writes the log `carom run` writes (`logged.rs`): from
    /// a simulation at its start, or continuing the log its last run wrote.
    ///
    /// With `live` (`True`: 127.0.0.1:8765; a port, 0 for any free one; or
    /// `"HOST:PORT"`), the run is served to Foxglove or Lichtblick as `carom run
    /// --live` serves it (`/scene`, `/thermo`, `/progress`), at most `live_rate`
    /// frames a second (default 10). The server stays up for later runs (which
    /// are served too unless `live=False`) until `stop_live()`; `live_url` says
    /// where.
    #[pyo3(signature = (until=None, collisions=None, every=None, callback=None, log=None,
                        live=None, live_rate=None))]
    #[allow(clippy::too_many_arguments)]
    fn run(
        &mut self,
        py: Python<'_>,
        until: Option<f64>,
        collisions: Option<u64>,
        every: Option<f64>,
        callback: Option<Py<PyAny>>,
        log: Option<PathBuf>,
        live: Option<&Bound<'_, PyAny>>,
        live_rate: Option<f64>,
    ) -> PyResult<u64> {
        let served = self.serve(live::asked(live, live_rate)?)?;
        if let Some(path) = log {
            if every.is_some() || callback.is_some() {
                return Err(PyValueError::new_err(
                    "a logged run takes no callback (read its snapshots with open_log)",
                ));
            }
            return self.run_logged(py, until, collisions, &path, served);
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
            live: [self.next_tag + 2, self.next_tag + 3],
        };
        self.next_tag += TAGS_PER_RUN;
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
        let every = Every {
            t0,
            dt: every,
            until,
        };
        if let Some(t) = every.due(1) {
            self.schedule(t, tags.every)?;
        }
        let stop = match until {
            Some(t) => Stop::Time(t),
            None => Stop::Collisions(start.saturating_add(left)),
        };
        // The server is the run's while it runs, and the simulation's again after.
        let mut serving = if served { self.live.take() } else { None };
        let ran = self.watched(
            py,
            tags,
            &mut left,
            &every,
            callback,
            serving.as_mut(),
            stop,
        );
        if serving.is_some() {
            self.live = serving;
        }
        ran?;
        Ok(self.collisions_now() - start)
    }

    /// The state now: a dict of numpy arrays `x`, `y`, `vx`, `vy` (float64),
    /// `image` (int32, N × 2), `species` (int32), `radius`, `mass` (float64),
    /// with `time` and `box`; disc i is the configuration's disc i.
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let e = &self.engine;
        // The user's index of the engine's disc k.
        let user = |k: usize| self.user_of.as_ref().map_or(k, |u| u[k] as usize);
        let columns = Columns::zeros(py, e.len());
        columns.write(|w| {
            for d in e.discs_now() {
                w.disc(user(d.index), d.position, d.velocity, d.image);
            }
            for (k, &s) in e.species_of().iter().enumerate() {
                w.species[user(k)] = i32::from(s);
            }
        })?;
        let species = e.species_now();
        let radius: Vec<f64> = species.iter().map(|sp| sp.radius).collect();
        let mass: Vec<f64> = species.iter().map(|sp| sp.mass).collect();
        columns.into_dict(py, e.now(), e.sim_box().size, &radius, &mass)
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

    /// Whether the engine finds partners on neighbour lists (`True`) or on the
    /// cell grid (`False`): the configuration's `neighbours`, with `"auto"`
    /// decided by the engine from the system alone (data/README.md).
    #[getter]
    fn neighbour_lists(&self) -> bool {
        self.engine.neighbour_lists()
    }

    /// Serve the simulation live at `live` (as `run`'s `live`: `True` for
    /// 127.0.0.1:8765, a port, 0 for any free one, or `"HOST:PORT"`), at most
    /// `rate` frames a second (default 10), from now on: later runs are served
    /// (unless `live=False`) until `stop_live()`. Returns the URL a viewer opens,
    /// `ws://HOST:PORT`. A simulation already serving there keeps its server.
    #[pyo3(signature = (live=None, rate=None))]
    fn start_live<'py>(
        &mut self,
        py: Python<'py>,
        live: Option<&Bound<'py, PyAny>>,
        rate: Option<f64>,
    ) -> PyResult<String> {
        let default = PyBool::new(py, true).to_owned().into_any();
        let asked = live::asked(Some(live.unwrap_or(&default)), rate)?;
        if !matches!(asked, Asked::At(_)) {
            return Err(PyValueError::new_err(
                "live: start_live serves somewhere; give True, a port or \"HOST:PORT\"",
            ));
        }
        self.serve(asked)?;
        Ok(self.live.as_ref().map(Serving::url).unwrap_or_default())
    }

    /// Stop serving live: connected viewers get the last frame and are
    /// disconnected. Nothing happens when the simulation does not serve.
    fn stop_live(&mut self, py: Python<'_>) {
        if let Some(s) = self.live.take() {
            py.detach(|| s.finish());
        }
    }

    /// Where the simulation serves live, `ws://HOST:PORT` (`None` when it does not).
    #[getter]
    fn live_url(&self) -> Option<String> {
        self.live.as_ref().map(Serving::url)
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
