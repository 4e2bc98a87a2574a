//! What the run looks at between events: its progress (reported through
//! [`Control`](crate::Control)), the room on the log's disk (stop in time to
//! finish the log, or at once when the log would far outgrow the disk) and the
//! watchdog (stop when no collision has happened within its bound, `watchdog.rs`);
//! and the caller's [`Observer`](crate::Observer): when it wants a frame, one is
//! scheduled at the first time after now (`f64::next_up`), so that the frame is
//! the exact state at that instant, the state a run stopped there has, and not a
//! state just after a collision; the instant never passes the stop.

use std::time::Instant;

use crate::disk::{far_too_small, finish_reserve, free_bytes};
use crate::observation::Observation;
use crate::watchdog;
use crate::{Progress, RunError};

use super::Driver;

impl Driver<'_> {
    /// The watchdog's check at `now`: `true` when no collision has happened within
    /// the bound (the run must stop); otherwise the next check is scheduled.
    pub(super) fn quiet_too_long(&mut self, now: f64) -> Result<bool, RunError> {
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

    /// The progress now, reported to the caller's progress callback.
    pub(super) fn progress(&mut self) -> Progress {
        let p = self.progress_now();
        if let Some(cb) = self.control.progress.as_mut() {
            cb(&p);
        }
        self.last_progress = Instant::now();
        p
    }

    /// The progress now.
    fn progress_now(&self) -> Progress {
        Progress::new(
            self.stop,
            self.run_start_time,
            self.engine.now(),
            [self.start_collisions, self.collisions],
            self.started.elapsed().as_secs_f64(),
            self.log_bytes(),
        )
    }

    /// If the caller's observer wants a frame and none is pending, schedule one
    /// at the first time after now, unless that is past `stop_time`.
    pub(super) fn ask_for_frame(&mut self, stop_time: f64) -> Result<(), RunError> {
        if self.live_pending {
            return Ok(());
        }
        let Some(o) = self.control.observer.as_mut() else {
            return Ok(());
        };
        let Some(t) = o.frame_time(self.engine.now(), stop_time) else {
            return Ok(());
        };
        self.schedule(t, Observation::Live)?;
        self.live_pending = true;
        Ok(())
    }

    /// Hand the state now to the caller's observer (the frame it asked for, or
    /// the final state).
    pub(super) fn live_frame(&mut self) {
        self.live_pending = false;
        let p = self.progress_now();
        if let Some(o) = self.control.observer.as_mut() {
            o.frame(&self.engine, &p);
        }
    }

    /// Whether the log, projected to the stop from its growth so far, needs far
    /// more than the room on its disk ([`far_too_small`]), unless the caller
    /// ignores the estimate; if so, say why in the run's detail.
    pub(super) fn disk_far_too_small(&mut self, p: &Progress) -> bool {
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
            crate::disk::FAR_BEYOND_FREE
        ));
        true
    }

    /// The log file's size on disk (bytes; 0 if it cannot be read).
    pub(super) fn log_bytes(&self) -> u64 {
        std::fs::metadata(&self.path).map_or(0, |m| m.len())
    }

    /// Look at the room left on the log's disk, when the clock (`timed`) or the
    /// log's growth says so ([`DiskWatch`]): whether the run must stop now to
    /// finish its log. A disk whose room cannot be told is never low.
    pub(super) fn disk_low(&mut self, timed: bool) -> bool {
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
}
