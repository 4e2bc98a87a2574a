//! The event loop of a run: takes the engine's events one by one, hands
//! collisions to the log writer, answers the observations it scheduled
//! ([`Observation`], `observe`), looks at progress, the disk and the watchdog
//! between events (`watch`), and ends the log cleanly whatever stops it (`finish`).
//! A caller's [`Observer`](crate::Observer) gets frames at exact instants it asks
//! for (`watch`) and every `/thermo` record (`observe`); the trajectory and the
//! records are those of a run without it (a checkpoint written while a frame is
//! due lists that frame's instant, which a resume without an observer passes over).
//!
//! What a run writes, in order: the `carom.run` metadata; at the start time a
//! `/snapshot`, a `/thermo` record, a `/checkpoint` and a `/scene` frame (each when
//! enabled, the checkpoint always), then the same at start + k·interval (snapshots
//! on carom-log's `SnapshotSchedule`); `/collisions` batches in between; at the end
//! a final `/thermo` record, `/checkpoint` and `carom.summary`. A stop at `t_end`
//! comes after every observation due at `t_end`. Growth's extra `/thermo`: `observe`.

mod finish;
mod observe;
mod watch;

use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::time::Instant;

use carom_engine::{Engine, EngineError, Event, GrowthEnd, State};
use carom_log::{LogOptions, LogWriter, Stop, StopReason};

use crate::disk::DiskWatch;
use crate::observation::Observation;
use crate::replace::Replace;
use crate::{Control, RunError, RunSummary};

/// The state of a run between events.
pub(crate) struct Driver<'a> {
    pub(crate) engine: Engine,
    pub(crate) writer: LogWriter,
    pub(crate) log: LogOptions,
    pub(crate) stop: Stop,
    pub(crate) control: Control<'a>,
    pub(crate) run_start_time: f64,
    /// (time, collisions) of the last checkpoint written.
    pub(crate) last_checkpoint_at: Option<(f64, u64)>,
    /// (time, collisions) of the last thermo record written.
    pub(crate) last_thermo_at: Option<(f64, u64)>,
    pub(crate) collisions: u64,
    start_collisions: u64,
    started: Instant,
    last_progress: Instant,
    /// The state written by the last snapshot or scene, kept to reuse its arrays.
    snapshot: Option<State>,
    /// When to look at the room on the log's disk next.
    disk: DiskWatch,
    /// The speed (collisions/s) of the run this one continues, reported again when
    /// this one simulates no collision (a finished log resumed to its own stop).
    pub(crate) earlier_speed: Option<f64>,
    /// `stop.max_time_without_collision` as the user set it (`watchdog.rs`).
    pub(crate) max_quiet: Option<f64>,
    /// The time of the last collision, or of the start of this process's part.
    last_collision: f64,
    /// Why the watchdog, or the estimate of the log's size, stopped the run.
    quiet_detail: Option<String>,
    /// While discs grow: the index of the engine's next rescale and its phase as
    /// last seen, to tell when a rescale or the end of growth has passed (`None`
    /// otherwise).
    growth_seen: Option<(i64, GrowthEnd)>,
    /// Whether a frame for the caller's observer is scheduled and not yet taken.
    live_pending: bool,
    /// The rename of the new log over an older one, done after the first
    /// checkpoint (`replace.rs`), and the log's path, which it changes.
    pub(crate) replace_at_start: Option<Replace>,
    path: PathBuf,
}

impl<'a> Driver<'a> {
    pub(crate) fn new(
        engine: Engine,
        writer: LogWriter,
        log: LogOptions,
        stop: Stop,
        control: Control<'a>,
    ) -> Self {
        let s = engine.stats();
        let collisions = s.pair_collisions + s.wall_collisions;
        let engine_now = engine.now();
        let path = writer.path().to_path_buf();
        Driver {
            engine,
            writer,
            log,
            stop,
            control,
            run_start_time: 0.0,
            last_checkpoint_at: None,
            last_thermo_at: None,
            collisions,
            start_collisions: collisions,
            started: Instant::now(),
            last_progress: Instant::now(),
            snapshot: None,
            disk: DiskWatch::new(0),
            earlier_speed: None,
            max_quiet: None,
            last_collision: engine_now,
            quiet_detail: None,
            growth_seen: None,
            live_pending: false,
            replace_at_start: None,
            path,
        }
    }

    fn engine_err(&self, source: EngineError) -> RunError {
        RunError::Engine {
            source,
            time: self.engine.now(),
            log: self.path.clone(),
        }
    }

    /// Put the log on the disk and rename it over the older log it replaces
    /// (`replace.rs`).
    pub(crate) fn replace(&mut self, r: Replace) -> Result<(), RunError> {
        self.writer.sync()?;
        self.path = r.apply()?;
        Ok(())
    }

    /// The event loop; ends the log whatever happens, except when writing it fails:
    /// that is reported as [`RunError::LogCut`].
    pub(crate) fn run_loop(mut self, log_path: &Path) -> Result<RunSummary, RunError> {
        self.run_events(log_path).map_err(|e| match e {
            RunError::Write(source) => RunError::LogCut {
                source,
                time: self.engine.now(),
                log: log_path.to_path_buf(),
            },
            e => e,
        })
    }

    /// The body of [`Driver::run_loop`].
    fn run_events(&mut self, log_path: &Path) -> Result<RunSummary, RunError> {
        let stop_flag = self.control.stop;
        let max_collisions = match self.stop {
            Stop::Collisions(c) => c,
            Stop::Time(_) => u64::MAX,
        };
        let stop_time = match self.stop {
            Stop::Time(t) => t,
            Stop::Collisions(_) => f64::INFINITY,
        };
        let mut reason = if self.collisions >= max_collisions {
            Some(StopReason::Collisions)
        } else {
            None
        };
        let mut failure = None;
        let mut tick: u32 = 0;
        self.disk = DiskWatch::new(self.log_bytes());
        self.growth_seen = observe::growth_seen(&self.engine, self.run_start_time);
        if let Some(started) = self.control.started.take() {
            started(&self.engine);
        }
        while reason.is_none() {
            if stop_flag.is_some_and(|f| f.load(Ordering::Relaxed)) {
                reason = Some(StopReason::Interrupted);
                break;
            }
            let ev = match self.engine.next_event() {
                Ok(Some(ev)) => ev,
                Ok(None) => {
                    reason = Some(StopReason::Exhausted);
                    break;
                }
                Err(e) => {
                    failure = Some(e);
                    reason = Some(StopReason::Error);
                    break;
                }
            };
            match ev {
                Event::Pair(c) => {
                    self.collisions += 1;
                    self.last_collision = c.time;
                    self.writer.observe_pair(&c)?;
                }
                Event::Wall(c) => {
                    self.collisions += 1;
                    self.last_collision = c.time;
                    self.writer.observe_wall(&c)?;
                }
                Event::Pause { .. } => {}
                Event::Scheduled { time, tag } => match Observation::decode(tag) {
                    Some(Observation::Snapshot(k)) => {
                        self.schedule_next_snapshot(k)?;
                        self.write_snapshot()?;
                    }
                    Some(Observation::Thermo(k)) => {
                        let interval = self.log.thermo_interval;
                        self.schedule_next(Observation::Thermo, k, interval)?;
                        self.write_thermo()?;
                    }
                    Some(Observation::Checkpoint(k)) => {
                        let interval = self.log.checkpoint_interval;
                        self.schedule_next(Observation::Checkpoint, k, interval)?;
                        self.write_checkpoint()?;
                        if let Some(r) = self.replace_at_start.take() {
                            self.replace(r)?;
                        }
                    }
                    Some(Observation::Scene(k)) => {
                        let interval = self.log.scene_interval;
                        self.schedule_next(Observation::Scene, k, interval)?;
                        self.write_scene(k)?;
                    }
                    // Let every observation due at this very time come first.
                    Some(Observation::Stop) if time >= stop_time => {
                        self.schedule(time, Observation::FinalStop)?;
                    }
                    Some(Observation::FinalStop) if time >= stop_time => {
                        reason = Some(StopReason::Time);
                    }
                    Some(Observation::Watchdog) if self.quiet_too_long(time)? => {
                        reason = Some(StopReason::NoCollision);
                    }
                    Some(Observation::Live) => self.live_frame(),
                    _ => {}
                },
            }
            // A pause (the engine handing back control during long unobservable
            // work) marks no instant of the run: the growth's record waits for the
            // next event.
            let paused = matches!(ev, Event::Pause { .. });
            if self.growth_seen.is_some() && !paused {
                self.growth_record()?;
            }
            if self.collisions >= max_collisions {
                reason = Some(StopReason::Collisions);
            }
            tick = tick.wrapping_add(1);
            if tick.is_multiple_of(1024) || paused {
                self.writer.maybe_flush()?;
                let timed = self.last_progress.elapsed() >= self.control.progress_interval;
                if timed {
                    let p = self.progress();
                    if reason.is_none() && self.disk_far_too_small(&p) {
                        reason = Some(StopReason::DiskFull);
                    }
                }
                if reason.is_none() && self.disk_low(timed) {
                    reason = Some(StopReason::DiskFull);
                }
                if reason.is_none() {
                    self.ask_for_frame(stop_time)?;
                }
            }
        }
        let reason = reason.unwrap_or(StopReason::Error);
        self.finish(reason, failure, log_path)
    }
}
