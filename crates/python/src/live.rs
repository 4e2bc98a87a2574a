//! `sim.run(..., live=True)`: a simulation served while it runs to Foxglove or
//! Lichtblick over Foxglove's WebSocket protocol, by carom-live's [`Live`], the
//! server of `carom run --live`, with its channels `/scene`, `/thermo` and
//! `/progress`. The server belongs to the simulation: it stays up across `run`
//! calls (a viewer is not dropped between them) until `stop_live()` or the end of
//! the simulation.
//!
//! A logged run hands the server to carom-run as its observer (`logged.rs`). A run
//! without a log does what carom-run's driver does ([`Watch`]): about every
//! [`LOOK_EVERY`] events it asks the server whether a frame is due and, if so,
//! schedules one at the first instant after now (`f64::next_up`, never past the
//! stop), so a frame is the exact state at its time; `/thermo` records come at
//! t₀ + k·Δ (Δ the configuration's `log.thermo_interval`, t₀ the simulation's
//! start) and at the end of each run, made by carom-run's own rule
//! (`carom_run::thermo`), so they are the records a log of the run holds.

use std::time::Instant;

use carom_engine::{Engine, EngineError};
use carom_live::{Live, LiveError, LiveOptions, DEFAULT_ADDR};
use carom_log::Stop;
use carom_run::{Observer, Progress};
use pyo3::exceptions::{PyOSError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyInt, PyString};

/// Events between two questions to the server whether a frame is due, as in
/// carom-run's driver.
pub const LOOK_EVERY: u32 = 1024;

/// `live` as a Python caller gives it: `None` (as before), `False` (not this
/// run), `True` (the default address), a port, or `"HOST:PORT"`.
pub enum Asked {
    /// Serve if the simulation serves already.
    AsBefore,
    /// Do not serve this run.
    Off,
    /// Serve at these options.
    At(LiveOptions),
}

/// A live error as the Python exception it is: a bad address or rate is a
/// `ValueError`, an address that cannot be served an `OSError`.
fn live_error(e: LiveError) -> PyErr {
    match e {
        LiveError::Serve { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// What `live` and `live_rate` ask for.
pub fn asked(live: Option<&Bound<'_, PyAny>>, rate: Option<f64>) -> PyResult<Asked> {
    let usage = || {
        PyTypeError::new_err(format!(
            "live: give True ({DEFAULT_ADDR}), a port number (0: any free port), \
             \"HOST:PORT\", or False"
        ))
    };
    let addr = match live {
        None => None,
        Some(v) if v.is_instance_of::<PyBool>() => {
            v.extract::<bool>()?.then(|| DEFAULT_ADDR.into())
        }
        Some(v) if v.is_instance_of::<PyInt>() => {
            let port: i64 = v.extract()?;
            if !(0..=65535).contains(&port) {
                return Err(PyValueError::new_err(format!(
                    "live = {port}: a port is 0 to 65535 (0: any free port)"
                )));
            }
            Some(port.to_string())
        }
        Some(v) if v.is_instance_of::<PyString>() => Some(v.extract::<String>()?),
        Some(_) => return Err(usage()),
    };
    match (addr, live) {
        (Some(a), _) => {
            let mut options = LiveOptions::at(&a).map_err(live_error)?;
            if let Some(r) = rate {
                options.frame_rate = r;
            }
            Ok(Asked::At(options))
        }
        (None, Some(_)) if rate.is_none() => Ok(Asked::Off),
        (None, None) if rate.is_none() => Ok(Asked::AsBefore),
        (None, _) => Err(PyValueError::new_err(
            "live_rate: goes with live (True, a port or \"HOST:PORT\")",
        )),
    }
}

/// A simulation's live server and the `/thermo` series it serves.
pub struct Serving {
    live: Live,
    /// The options it was started with.
    options: LiveOptions,
    /// Time between `/thermo` records (the configuration's `log.thermo_interval`).
    thermo_interval: Option<f64>,
    /// t₀ of the series t₀ + k·Δ: the simulation's start.
    start_time: f64,
    /// k of the next record of the series.
    next: u64,
    /// (time, collisions) of the last record sent, to send none twice.
    last_at: Option<(f64, u64)>,
}

impl Serving {
    /// Start serving at `options`; records every `thermo_interval` from `start_time`.
    pub fn start(
        options: LiveOptions,
        thermo_interval: Option<f64>,
        start_time: f64,
    ) -> PyResult<Self> {
        Ok(Serving {
            live: Live::start(&options).map_err(live_error)?,
            options,
            thermo_interval,
            start_time,
            next: 0,
            last_at: None,
        })
    }

    /// Whether this server is the one `options` asks for (a port 0 asks for any).
    pub fn serves(&self, options: &LiveOptions) -> bool {
        let same_addr = options.addr == self.options.addr || options.addr == self.live.addr();
        same_addr && options.frame_rate == self.options.frame_rate
    }

    /// The most frames per wall second.
    pub fn frame_rate(&self) -> f64 {
        self.options.frame_rate
    }

    /// `ws://HOST:PORT`.
    pub fn url(&self) -> String {
        self.live.url()
    }

    /// The server, for a logged run's `Control::observer`.
    pub fn observer(&mut self) -> &mut Live {
        &mut self.live
    }

    /// After a logged run, which sent the log's records itself (its last at the
    /// final state of `engine`): the series goes on after it.
    pub fn logged(&mut self, engine: &Engine) {
        if self.thermo_interval.is_some() {
            self.last_at = Some((engine.now(), collisions(engine)));
        }
    }

    /// Stop serving: clients are disconnected (after the last frame is sent).
    pub fn finish(self) {
        self.live.finish();
    }
}

/// Pair + wall collisions since the start.
fn collisions(engine: &Engine) -> u64 {
    let s = engine.stats();
    s.pair_collisions + s.wall_collisions
}

/// One unlogged run watched live: the frames it schedules, the `/thermo` series,
/// and the progress reported with each frame.
pub struct Watch<'a> {
    serving: &'a mut Serving,
    /// The tags of this run's frame and `/thermo` events.
    frame_tag: u64,
    thermo_tag: u64,
    /// A frame is scheduled and not yet taken.
    frame_pending: bool,
    /// Where the run stops.
    stop: Stop,
    stop_time: f64,
    /// When and where (time, collisions) the run started.
    started: Instant,
    t0: f64,
    start_collisions: u64,
    /// The engine failed: no last frame.
    failed: bool,
}

impl<'a> Watch<'a> {
    /// Watch a run of `engine` to `stop`, its frames and records tagged
    /// `tags` (two tags of the run's own); the first `/thermo` record due is
    /// scheduled.
    pub fn start(
        serving: &'a mut Serving,
        engine: &mut Engine,
        stop: Stop,
        tags: [u64; 2],
    ) -> Result<Self, EngineError> {
        let stop_time = match stop {
            Stop::Time(t) => t,
            Stop::Collisions(_) => f64::INFINITY,
        };
        let mut w = Watch {
            serving,
            frame_tag: tags[0],
            thermo_tag: tags[1],
            frame_pending: false,
            stop,
            stop_time,
            started: Instant::now(),
            t0: engine.now(),
            start_collisions: collisions(engine),
            failed: false,
        };
        // The series' first record not before now.
        if let Some(dt) = w.serving.thermo_interval {
            let (s, now) = (&mut *w.serving, engine.now());
            let below = ((now - s.start_time) / dt).floor() as u64;
            s.next = s.next.max(below.saturating_sub(1));
            while s.start_time + s.next as f64 * dt < now {
                s.next += 1;
            }
        }
        w.schedule_thermo(engine)?;
        Ok(w)
    }

    /// Schedule the series' next `/thermo` record, unless past the stop.
    fn schedule_thermo(&mut self, engine: &mut Engine) -> Result<(), EngineError> {
        let s = &self.serving;
        if let Some(dt) = s.thermo_interval {
            let t = s.start_time + s.next as f64 * dt;
            if t <= self.stop_time {
                engine.schedule(t, self.thermo_tag)?;
            }
        }
        Ok(())
    }

    /// Between events (every [`LOOK_EVERY`]): schedule a frame at the first
    /// instant after now if the server wants one, none is pending, and that
    /// instant is not past the stop.
    pub fn look(&mut self, engine: &mut Engine) -> Result<(), EngineError> {
        if self.frame_pending {
            return Ok(());
        }
        if let Some(t) = self.serving.live.frame_time(engine.now(), self.stop_time) {
            engine.schedule(t, self.frame_tag)?;
            self.frame_pending = true;
        }
        Ok(())
    }

    /// A scheduled event with `tag`: this run's frame or `/thermo` record, sent
    /// now; any other tag is not this watch's.
    pub fn scheduled(&mut self, engine: &mut Engine, tag: u64) -> Result<(), EngineError> {
        if tag == self.frame_tag {
            self.frame(engine);
        } else if tag == self.thermo_tag {
            self.thermo(engine);
            self.serving.next += 1;
            self.schedule_thermo(engine)?;
        }
        Ok(())
    }

    /// The engine failed: its state is not one to show.
    pub fn fail(&mut self) {
        self.failed = true;
    }

    /// The end of the run: a last `/thermo` record and, if one is due, a frame
    /// at the final state (neither after a failure of the engine).
    pub fn finish(&mut self, engine: &Engine) {
        if self.failed {
            return;
        }
        if self.serving.thermo_interval.is_some() {
            self.thermo(engine);
        }
        // The last frame too keeps to the rate: a loop of short runs would
        // otherwise send one per run.
        if self.serving.live.frame_due() {
            self.frame(engine);
        }
    }

    /// Send the frame of the state now.
    fn frame(&mut self, engine: &Engine) {
        self.frame_pending = false;
        let p = self.progress(engine);
        self.serving.live.frame(engine, &p);
    }

    /// Send the `/thermo` record of the state now, unless it was just sent.
    fn thermo(&mut self, engine: &Engine) {
        let at = (engine.now(), collisions(engine));
        if self.serving.last_at != Some(at) {
            let record = carom_run::thermo(engine, self.serving.start_time);
            self.serving.live.thermo(&record);
            self.serving.last_at = Some(at);
        }
    }

    /// The run's progress now: the fraction done by its stop, as the command
    /// reports it.
    fn progress(&self, engine: &Engine) -> Progress {
        Progress::new(
            self.stop,
            self.t0,
            engine.now(),
            [self.start_collisions, collisions(engine)],
            self.started.elapsed().as_secs_f64(),
            0,
        )
    }
}
