//! The event loop of a run: takes the engine's events one by one, hands
//! collisions to the log writer, answers the observations it scheduled
//! ([`Observation`]), reports progress, looks at the room on the log's disk, and
//! ends the log cleanly whatever stops the run.
//!
//! What a run writes, in order: the `carom.run` metadata; at the start time a
//! `/snapshot`, a `/thermo` record, a `/checkpoint` and a `/scene` frame (each
//! when enabled, the checkpoint always), then the same at start + k·interval
//! (and snapshots inside each interval at log-spaced offsets with
//! `log.snapshot_schedule`, carom-log's `SnapshotSchedule`);
//! `/collisions` batches in between; at the end a final `/thermo` record and `/checkpoint`, and
//! `carom.summary`. A stop at `t_end` comes after every observation due at `t_end`.
//! While discs grow, an extra `/thermo` record follows the first event after each
//! velocity rescale and after the end of growth (docs/log-format.md, `/thermo`).

use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;
use std::time::Instant;

use carom_engine::{Engine, EngineError, Event, GrowthEnd, State};
use carom_log::{now_rfc3339, StopReason, SummaryMetadata};
use carom_log::{GrowthEvent, LogWriter};
use carom_log::{LogOptions, Stop};

use super::disk::{far_too_small, finish_reserve, free_bytes, DiskWatch};
use super::observation::Observation;
use super::replace::Replace;
use super::thermo::thermo;
use super::watchdog;
use super::{Control, Progress, RunError, RunSummary};

/// The engine's state now, in the arrays of `kept` (the last one written).
fn state_now<'s>(engine: &Engine, kept: &'s mut Option<State>) -> &'s State {
    match kept {
        Some(s) => {
            engine.state_into(s);
            s
        }
        none => none.insert(engine.state()),
    }
}

/// What tells a growth instant: while discs grow, the index k of the next
/// rescale, due at t₀ + k·Δ (rounded, so that the ulps by which the engine's
/// restarted clock moves that time never change it), and the phase; `None`
/// without growth or once it has ended.
fn growth_seen(engine: &Engine, t0: f64) -> Option<(i64, GrowthEnd)> {
    let (g, p) = (engine.growth(), &engine.params().growth);
    if p.rate == 0.0 || g.rate == 0.0 {
        return None;
    }
    let k = ((engine.next_rescale_time() - t0) / p.rescale_interval).round() as i64;
    Some((k, g.ended))
}

/// The state of a run between events.
pub(super) struct Driver<'a> {
    pub(super) engine: Engine,
    pub(super) writer: LogWriter,
    pub(super) log: LogOptions,
    pub(super) stop: Stop,
    pub(super) control: Control<'a>,
    pub(super) run_start_time: f64,
    /// (time, collisions) of the last checkpoint written.
    pub(super) last_checkpoint_at: Option<(f64, u64)>,
    /// (time, collisions) of the last thermo record written.
    pub(super) last_thermo_at: Option<(f64, u64)>,
    pub(super) collisions: u64,
    start_collisions: u64,
    started: Instant,
    last_progress: Instant,
    /// The state written by the last snapshot or scene, kept to reuse its arrays.
    snapshot: Option<State>,
    /// When to look at the room on the log's disk next.
    disk: DiskWatch,
    /// The speed (collisions/s) of the run this one continues, reported again when
    /// this one simulates no collision (a finished log resumed to its own stop).
    pub(super) earlier_speed: Option<f64>,
    /// `stop.max_time_without_collision` as the user set it (`watchdog.rs`).
    pub(super) max_quiet: Option<f64>,
    /// The time of the last collision, or of the start of this process's part.
    last_collision: f64,
    /// Why the watchdog, or the estimate of the log's size, stopped the run.
    quiet_detail: Option<String>,
    /// While discs grow: the index of the engine's next rescale and its phase as
    /// last seen, to tell when a rescale or the end of growth has passed (`None`
    /// otherwise).
    growth_seen: Option<(i64, GrowthEnd)>,
    /// The rename of the new log over an older one, done after the first
    /// checkpoint (`replace.rs`), and the log's path, which it changes.
    pub(super) replace_at_start: Option<Replace>,
    path: PathBuf,
}

impl<'a> Driver<'a> {
    pub(super) fn new(
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

    /// Schedule the observations at the start time and the stop.
    pub(super) fn schedule_initial(&mut self) -> Result<(), RunError> {
        let t0 = self.run_start_time;
        let mut due = Vec::new();
        if self.log.snapshot_interval.is_some() {
            due.push(Observation::Snapshot(0));
        }
        if self.log.thermo_interval.is_some() {
            due.push(Observation::Thermo(0));
        }
        if self.log.scene_interval.is_some() {
            due.push(Observation::Scene(0));
        }
        due.push(Observation::Checkpoint(0));
        for o in due {
            self.schedule(t0, o)?;
        }
        if let Stop::Time(t) = self.stop {
            self.schedule(t, Observation::Stop)?;
        }
        self.schedule_watchdog()
    }

    /// Schedule the watchdog's check one bound after the last collision, if the
    /// run has a bound (`watchdog.rs`).
    pub(super) fn schedule_watchdog(&mut self) -> Result<(), RunError> {
        if let Some(b) = watchdog::bound(&self.engine, self.max_quiet, self.stop) {
            let t = (self.last_collision + b).max(self.engine.now());
            self.schedule(t, Observation::Watchdog)?;
        }
        Ok(())
    }

    /// The watchdog's check at `now`: `true` when no collision has happened within
    /// the bound (the run must stop); otherwise the next check is scheduled.
    fn quiet_too_long(&mut self, now: f64) -> Result<bool, RunError> {
        let Some(b) = watchdog::bound(&self.engine, self.max_quiet, self.stop) else {
            return Ok(false);
        };
        let next = self.last_collision + b;
        if now - self.last_collision >= b || next <= now {
            self.quiet_detail = Some(watchdog::explain(
                self.last_collision,
                now,
                b,
                self.max_quiet,
            ));
            return Ok(true);
        }
        self.schedule(next, Observation::Watchdog)?;
        Ok(false)
    }

    /// Schedule `what` at time `t`.
    pub(super) fn schedule(&mut self, t: f64, what: Observation) -> Result<(), RunError> {
        self.engine
            .schedule(t, what.encode())
            .map_err(|e| self.engine_err(e))
    }

    /// Schedule observation k + 1 of a series `interval` apart (`next(k + 1)`),
    /// unless the series is off or its time has passed.
    fn schedule_next(
        &mut self,
        next: fn(u64) -> Observation,
        k: u64,
        interval: Option<f64>,
    ) -> Result<(), RunError> {
        if let Some(dt) = interval {
            let t = self.run_start_time + (k + 1) as f64 * dt;
            if t >= self.engine.now() {
                self.schedule(t, next(k + 1))?;
            }
        }
        Ok(())
    }

    /// Schedule snapshot k + 1 at its time in the snapshot schedule (carom-log's
    /// `SnapshotSchedule`: t₀ + k·T without `log.snapshot_schedule`), unless
    /// snapshots are off or its time has passed.
    fn schedule_next_snapshot(&mut self, k: u64) -> Result<(), RunError> {
        if let Some(s) = self.log.snapshots() {
            let t = s.time(self.run_start_time, k + 1);
            if t >= self.engine.now() {
                self.schedule(t, Observation::Snapshot(k + 1))?;
            }
        }
        Ok(())
    }

    fn write_snapshot(&mut self) -> Result<(), RunError> {
        let state = state_now(&self.engine, &mut self.snapshot);
        self.writer.write_snapshot(state)?;
        Ok(())
    }

    fn write_scene(&mut self, frame: u64) -> Result<(), RunError> {
        let state = state_now(&self.engine, &mut self.snapshot);
        self.writer.write_scene(frame, state)?;
        Ok(())
    }

    fn write_thermo(&mut self) -> Result<(), RunError> {
        let th = thermo(&self.engine, self.run_start_time);
        self.writer.write_thermo(&th)?;
        self.last_thermo_at = Some((self.engine.now(), self.collisions));
        Ok(())
    }

    /// While discs grow, after each event: if a rescale or the end of growth has
    /// passed since the last event, write the extra `/thermo` record that marks it
    /// (the state now, just after that instant).
    fn growth_record(&mut self) -> Result<(), RunError> {
        let now = growth_seen(&self.engine, self.run_start_time);
        if now == self.growth_seen {
            return Ok(());
        }
        self.growth_seen = now;
        let mut th = thermo(&self.engine, self.run_start_time);
        th.growth_event = Some(match self.engine.growth().ended {
            GrowthEnd::Growing => GrowthEvent::Rescale,
            _ => GrowthEvent::End,
        });
        self.writer.write_thermo(&th)?;
        Ok(())
    }

    fn write_checkpoint(&mut self) -> Result<(), RunError> {
        let cp = self.engine.checkpoint();
        self.writer.write_checkpoint(cp, self.run_start_time)?;
        self.last_checkpoint_at = Some((self.engine.now(), self.collisions));
        Ok(())
    }

    fn progress(&mut self) -> Progress {
        let wall = self.started.elapsed().as_secs_f64();
        let done = self.collisions - self.start_collisions;
        let fraction = match self.stop {
            Stop::Time(t) => {
                let span = t - self.run_start_time;
                if span > 0.0 {
                    ((self.engine.now() - self.run_start_time) / span).clamp(0.0, 1.0)
                } else {
                    1.0
                }
            }
            Stop::Collisions(c) => {
                if c > 0 {
                    (self.collisions as f64 / c as f64).min(1.0)
                } else {
                    1.0
                }
            }
        };
        let p = Progress {
            sim_time: self.engine.now(),
            collisions: self.collisions,
            collisions_per_second: if wall > 0.0 { done as f64 / wall } else { 0.0 },
            wall_seconds: wall,
            fraction,
            stop: self.stop,
            log_bytes: self.log_bytes(),
        };
        if let Some(cb) = self.control.progress.as_mut() {
            cb(&p);
        }
        self.last_progress = Instant::now();
        p
    }

    /// Whether the log, projected to the stop from its growth so far, needs far
    /// more than the room on its disk ([`far_too_small`]), unless the caller
    /// ignores the estimate; if so, say why in the run's detail.
    fn disk_far_too_small(&mut self, p: &Progress) -> bool {
        if self.control.ignore_disk_estimate || p.fraction >= 1.0 {
            return false;
        }
        let Some(projected) = p.projected_log_bytes() else {
            return false;
        };
        let Ok(free) = free_bytes(&mut self.control.free_space, self.writer.path()) else {
            return false;
        };
        if !far_too_small(p.log_bytes, projected, free) {
            return false;
        }
        self.quiet_detail = Some(format!(
            "at the rate it grew over its first {:.3e} time units ({} bytes), the log would \
             reach about {projected:.3e} bytes by the stop, more than {} times the {free} bytes \
             free on its disk: stopped at once with a finished log (log fewer collisions or \
             records, stop sooner, or run with --ignore-disk-estimate to go on until the disk \
             is nearly full)",
            p.sim_time - self.run_start_time,
            p.log_bytes,
            super::disk::FAR_BEYOND_FREE
        ));
        true
    }

    /// The log file's size on disk (bytes; 0 if it cannot be read).
    fn log_bytes(&self) -> u64 {
        std::fs::metadata(&self.path).map_or(0, |m| m.len())
    }

    /// Look at the room left on the log's disk, when the clock (`timed`) or the
    /// log's growth says so ([`DiskWatch`]): whether the run must stop now to
    /// finish its log. A disk whose room cannot be told is never low.
    fn disk_low(&mut self, timed: bool) -> bool {
        let bytes = self.log_bytes();
        if !timed && !self.disk.due(bytes) {
            return false;
        }
        let free = free_bytes(&mut self.control.free_space, &self.path);
        let finish = finish_reserve(
            self.writer.finish_bound(bytes),
            self.writer.stats().largest_message,
            self.engine.len() as u64,
        );
        self.disk.look(bytes, free, finish)
    }

    /// The event loop; ends the log whatever happens, except when writing it fails:
    /// that is reported as [`RunError::LogCut`].
    /// Put the log on the disk and rename it over the older log it replaces
    /// (`replace.rs`).
    pub(super) fn replace(&mut self, r: Replace) -> Result<(), RunError> {
        self.writer.sync()?;
        self.path = r.apply()?;
        Ok(())
    }

    pub(super) fn run_loop(mut self, log_path: &Path) -> Result<RunSummary, RunError> {
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
        self.growth_seen = growth_seen(&self.engine, self.run_start_time);
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
            }
        }
        let reason = reason.unwrap_or(StopReason::Error);
        // Finish the log.
        if failure.is_none() {
            let now = self.engine.now();
            if self.log.thermo_interval.is_some()
                && self.last_thermo_at != Some((now, self.collisions))
            {
                self.write_thermo()?;
            }
            if self.last_checkpoint_at != Some((now, self.collisions)) {
                self.write_checkpoint()?;
            }
        }
        self.progress();
        let wall = self.started.elapsed().as_secs_f64();
        let s = *self.engine.stats();
        let this = self.collisions - self.start_collisions;
        let cps = match self.earlier_speed {
            Some(v) if this == 0 => v,
            _ if wall > 0.0 => this as f64 / wall,
            _ => 0.0,
        };
        let kinetic_energy = self.engine.kinetic_energy();
        let potential_energy =
            (self.engine.gravity() != 0.0).then(|| self.engine.potential_energy());
        let logged = self.writer.stats().logged_collisions;
        let sm = SummaryMetadata {
            end_time: now_rfc3339(),
            stop_reason: reason,
            error: failure
                .as_ref()
                .map(|e| e.to_string())
                .or(self.quiet_detail.clone()),
            sim_time: self.engine.now(),
            pair_collisions: s.pair_collisions,
            wall_collisions: s.wall_collisions,
            logged_collisions: logged,
            kinetic_energy,
            energy_lost: s.energy_lost,
            virial_sum: s.virial_sum,
            wall_seconds: wall,
            collisions_per_second: cps,
            potential_energy,
        };
        let file_bytes = self.writer.finish(&sm.to_map())?;
        if let Some(source) = failure {
            return Err(RunError::Engine {
                source,
                time: self.engine.now(),
                log: log_path.to_path_buf(),
            });
        }
        Ok(RunSummary {
            log: log_path.to_path_buf(),
            stop_reason: reason,
            sim_time: self.engine.now(),
            pair_collisions: s.pair_collisions,
            wall_collisions: s.wall_collisions,
            logged_collisions: logged,
            collisions_this_process: this,
            wall_seconds: wall,
            collisions_per_second: cps,
            kinetic_energy,
            potential_energy,
            energy_lost: s.energy_lost,
            file_bytes,
            detail: self.quiet_detail.take(),
        })
    }
}
