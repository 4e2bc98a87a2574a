//! What a run observes at the times it scheduled: snapshots, `/thermo` records,
//! checkpoints and scene frames, each series t₀ + k·interval (snapshots on
//! carom-log's `SnapshotSchedule`), each observation scheduling the next as it is
//! written; and while discs grow, the extra `/thermo` record after each rescale and
//! after the end of growth (docs/log-format.md, `/thermo`).

use carom_engine::{Engine, GrowthEnd, State};
use carom_log::{GrowthEvent, Stop};

use super::Driver;
use crate::observation::Observation;
use crate::thermo::thermo;
use crate::watchdog;
use crate::RunError;

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
pub(super) fn growth_seen(engine: &Engine, t0: f64) -> Option<(i64, GrowthEnd)> {
    let (g, p) = (engine.growth(), &engine.params().growth);
    if p.rate == 0.0 || g.rate == 0.0 {
        return None;
    }
    let k = ((engine.next_rescale_time() - t0) / p.rescale_interval).round() as i64;
    Some((k, g.ended))
}

impl Driver<'_> {
    /// Schedule the observations at the start time and the stop.
    pub(crate) fn schedule_initial(&mut self) -> Result<(), RunError> {
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
    pub(crate) fn schedule_watchdog(&mut self) -> Result<(), RunError> {
        if let Some(b) = watchdog::bound(&self.engine, self.max_quiet, self.stop) {
            let t = (self.last_collision + b).max(self.engine.now());
            self.schedule(t, Observation::Watchdog)?;
        }
        Ok(())
    }

    /// Schedule `what` at time `t`.
    pub(crate) fn schedule(&mut self, t: f64, what: Observation) -> Result<(), RunError> {
        self.engine
            .schedule(t, what.encode())
            .map_err(|e| self.engine_err(e))
    }

    /// Schedule observation k + 1 of a series `interval` apart (`next(k + 1)`),
    /// unless the series is off or its time has passed.
    pub(super) fn schedule_next(
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
    pub(super) fn schedule_next_snapshot(&mut self, k: u64) -> Result<(), RunError> {
        if let Some(s) = self.log.snapshots() {
            let t = s.time(self.run_start_time, k + 1);
            if t >= self.engine.now() {
                self.schedule(t, Observation::Snapshot(k + 1))?;
            }
        }
        Ok(())
    }

    pub(super) fn write_snapshot(&mut self) -> Result<(), RunError> {
        let state = state_now(&self.engine, &mut self.snapshot);
        self.writer.write_snapshot(state)?;
        Ok(())
    }

    pub(super) fn write_scene(&mut self, frame: u64) -> Result<(), RunError> {
        let state = state_now(&self.engine, &mut self.snapshot);
        self.writer.write_scene(frame, state)?;
        Ok(())
    }

    pub(super) fn write_thermo(&mut self) -> Result<(), RunError> {
        let th = thermo(&self.engine, self.run_start_time);
        self.writer.write_thermo(&th)?;
        self.last_thermo_at = Some((self.engine.now(), self.collisions));
        self.thermo_observed(&th);
        Ok(())
    }

    /// While discs grow, after each event: if a rescale or the end of growth has
    /// passed since the last event, write the extra `/thermo` record that marks it
    /// (the state now, just after that instant).
    pub(super) fn growth_record(&mut self) -> Result<(), RunError> {
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
        self.thermo_observed(&th);
        Ok(())
    }

    /// Hand a `/thermo` record just written to the caller's observer.
    fn thermo_observed(&mut self, th: &carom_log::Thermo) {
        if let Some(o) = self.control.observer.as_mut() {
            o.thermo(th);
        }
    }

    pub(super) fn write_checkpoint(&mut self) -> Result<(), RunError> {
        let cp = self.engine.checkpoint();
        self.writer.write_checkpoint(cp, self.run_start_time)?;
        self.last_checkpoint_at = Some((self.engine.now(), self.collisions));
        Ok(())
    }
}
