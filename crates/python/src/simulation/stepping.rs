//! The event loop of an unlogged `run`: the engine runs without the GIL in
//! slices of [`SLICE`] events, and between slices the GIL is taken back to look
//! at signals (Ctrl-C raises `KeyboardInterrupt` between two events, the state
//! consistent) and to call back. The stop and the callbacks are scheduled events
//! at exact times, under tags of their own ([`Tags`]), so a callback at t sees the
//! state at t. Served live (`live.rs`), the loop also looks every [`LOOK_EVERY`]
//! events whether a frame is due, as carom-run's driver does for a logged run.

use carom_engine::{Engine, Event};
use carom_live::LiveOptions;
use carom_log::Stop;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use super::Simulation;
use crate::errors;
use crate::live::{Asked, Serving, Watch, LOOK_EVERY};

/// Events (collisions, scheduled and internal pauses) between two looks at the
/// signals, in chunks of [`LOOK_EVERY`] (after each, a live run looks whether a
/// frame is due): about a millisecond of work at N = 10⁴.
const SLICE: u32 = 20 * LOOK_EVERY;

/// How a slice of the run ended.
pub(super) enum Slice {
    /// The stop time, or the collisions asked for, was reached.
    Done,
    /// A callback time was reached: call back, then go on.
    Callback,
    /// The slice's events are used up: look at the signals, then go on.
    More,
    /// Nothing will ever happen again.
    Exhausted,
}

/// The tags of one `run`: its stop, its callbacks, and its live frames and
/// `/thermo` records.
#[derive(Clone, Copy)]
pub(super) struct Tags {
    pub(super) stop: u64,
    pub(super) every: u64,
    pub(super) live: [u64; 2],
}

/// The callback times of a run: t0 + k·dt (k = 1, 2, …), with a stop at `until`.
pub(super) struct Every {
    pub(super) t0: f64,
    pub(super) dt: Option<f64>,
    pub(super) until: Option<f64>,
}

impl Every {
    /// Callback k's time, if the run calls back.
    fn at(&self, k: u64) -> Option<f64> {
        self.dt.map(|dt| self.t0 + k as f64 * dt)
    }

    /// Callback k's time, if it comes before the stop time (one at the stop
    /// itself is called after the stop's event).
    pub(super) fn due(&self, k: u64) -> Option<f64> {
        self.at(k).filter(|&t| self.until.is_none_or(|u| t < u))
    }
}

/// Tags each `run` takes.
pub(super) const TAGS_PER_RUN: u64 = 4;

/// Process events until the stop, a callback, the end of the slice or the end of
/// all events; `left` counts the collisions still wanted. A live `watch` gets its
/// scheduled events, and a look after every [`LOOK_EVERY`] events.
fn slice(
    engine: &mut Engine,
    tags: Tags,
    left: &mut u64,
    mut watch: Option<&mut Watch<'_>>,
) -> Result<Slice, String> {
    for _ in 0..SLICE / LOOK_EVERY {
        for _ in 0..LOOK_EVERY {
            if *left == 0 {
                return Ok(Slice::Done);
            }
            let event = engine.next_event().map_err(|e| {
                if let Some(w) = watch.as_deref_mut() {
                    w.fail();
                }
                e.to_string()
            })?;
            match event {
                None => return Ok(Slice::Exhausted),
                Some(Event::Pair(_) | Event::Wall(_)) => *left -= 1,
                Some(Event::Scheduled { tag, .. }) if tag == tags.stop => return Ok(Slice::Done),
                Some(Event::Scheduled { tag, .. }) if tag == tags.every => {
                    return Ok(Slice::Callback)
                }
                // A live frame or record, or an interrupted run's stop.
                Some(Event::Scheduled { tag, .. }) => {
                    if let Some(w) = watch.as_deref_mut() {
                        w.scheduled(engine, tag).map_err(|e| e.to_string())?;
                    }
                }
                // A pause: long unobservable work.
                Some(Event::Pause { .. }) => {}
            }
        }
        if let Some(w) = watch.as_deref_mut() {
            w.look(engine).map_err(|e| e.to_string())?;
        }
    }
    Ok(Slice::More)
}

impl Simulation {
    /// The events of an unlogged run, watched live if `serving`: its frames,
    /// records, and a last frame at the end (unless the engine failed).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn watched(
        &mut self,
        py: Python<'_>,
        tags: Tags,
        left: &mut u64,
        every: &Every,
        callback: Option<Py<PyAny>>,
        serving: Option<&mut Serving>,
        stop: Stop,
    ) -> PyResult<()> {
        let mut watch = match serving {
            Some(s) => {
                Some(Watch::start(s, &mut self.engine, stop, tags.live).map_err(errors::engine)?)
            }
            None => None,
        };
        let ran = self.events(py, tags, left, every, callback, watch.as_mut());
        if let Some(w) = watch.as_mut() {
            w.finish(&self.engine);
        }
        ran
    }

    /// Run the events, slice by slice, calling back at the times of `every`.
    fn events(
        &mut self,
        py: Python<'_>,
        tags: Tags,
        left: &mut u64,
        every: &Every,
        callback: Option<Py<PyAny>>,
        mut watch: Option<&mut Watch<'_>>,
    ) -> PyResult<()> {
        // Callback k is due at t0 + k·every; `k` is the next one's.
        let mut k = 1;
        loop {
            let engine = &mut self.engine;
            let w = watch.as_deref_mut();
            let ended = py.detach(|| slice(engine, tags, left, w));
            match ended.map_err(errors::engine)? {
                Slice::Done => {
                    // A callback due at the stop time itself comes last.
                    if let (Some(cb), Some(t), Some(u)) = (&callback, every.at(k), every.until) {
                        if t <= u && *left > 0 {
                            cb.call1(py, (self.state(py)?,))?;
                        }
                    }
                    return Ok(());
                }
                Slice::Callback => {
                    if let Some(cb) = &callback {
                        cb.call1(py, (self.state(py)?,))?;
                    }
                    k += 1;
                    if let Some(t) = every.due(k) {
                        self.schedule(t, tags.every)?;
                    }
                }
                Slice::More => {}
                Slice::Exhausted => return Ok(()),
            }
            py.check_signals()?;
        }
    }

    /// Serve as `asked` (starting the server, or keeping the one serving);
    /// whether this run is served.
    pub(super) fn serve(&mut self, asked: Asked) -> PyResult<bool> {
        let options = match asked {
            Asked::Off => return Ok(false),
            Asked::AsBefore => return Ok(self.live.is_some()),
            Asked::At(o) => o,
        };
        match &self.live {
            Some(s) if s.serves(&options) => {}
            Some(s) => {
                return Err(PyValueError::new_err(format!(
                    "live: this simulation serves {} already, at {} frames/s; call \
                     stop_live() first to serve at another address or rate",
                    s.url(),
                    s.frame_rate()
                )))
            }
            None => self.live = Some(self.start_serving(options)?),
        }
        Ok(true)
    }

    /// A live server at `options` for this simulation.
    fn start_serving(&self, options: LiveOptions) -> PyResult<Serving> {
        Serving::start(options, self.spec.log.thermo_interval, self.start_time)
    }
}
