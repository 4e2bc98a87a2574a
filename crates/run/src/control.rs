//! How a caller steers a run and hears from it: the stop flag, the progress
//! callbacks (placement, reading the input of a resume, the run itself), the
//! answer to "how much room is left on the log's disk", and how often to ask.
//!
//! The driver calls these about every [`Control::progress_interval`] of wall time;
//! nothing here changes the trajectory. An [`Observer`] (a live viewer) is asked
//! between events whether it wants a frame, and gets one at an exact instant.

use std::sync::atomic::AtomicBool;
use std::time::Duration;

use carom_engine::{Engine, PlacementProgress};
use carom_log::ReadProgress;
use carom_log::{Stop, Thermo};

use super::disk::FreeSpace;
#[cfg(doc)]
use super::{disk_low, far_too_small, free_space_for, resume};
#[cfg(doc)]
use carom_log::StopReason;

/// A progress report, handed to the caller's callback about every
/// [`Control::progress_interval`] of wall time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Current simulated time (time).
    pub sim_time: f64,
    /// Collisions (pair + wall) since the start of the run, including before a resume.
    pub collisions: u64,
    /// Collisions of this process per wall-clock second so far.
    pub collisions_per_second: f64,
    /// Wall-clock seconds since this process started the run.
    pub wall_seconds: f64,
    /// Fraction of the run done (0–1), from the stop criterion.
    pub fraction: f64,
    /// The stop criterion.
    pub stop: Stop,
    /// Bytes of the log file on disk so far (what has reached the file; the
    /// writer's buffers and the chunk being filled are not counted yet).
    pub log_bytes: u64,
}

impl Progress {
    /// The progress of a run towards `stop` that began at `run_start_time` with
    /// `start_collisions` collisions behind it (those of a resumed log) and has
    /// now reached time `now` and `collisions`, after `wall_seconds` of wall time:
    /// the fraction done by the stop criterion, and this process's rate.
    pub fn new(
        stop: Stop,
        run_start_time: f64,
        now: f64,
        [start_collisions, collisions]: [u64; 2],
        wall_seconds: f64,
        log_bytes: u64,
    ) -> Progress {
        let fraction = match stop {
            Stop::Time(t) if t - run_start_time > 0.0 => {
                ((now - run_start_time) / (t - run_start_time)).clamp(0.0, 1.0)
            }
            Stop::Collisions(c) if c > 0 => (collisions as f64 / c as f64).min(1.0),
            _ => 1.0,
        };
        let done = collisions - start_collisions;
        Progress {
            sim_time: now,
            collisions,
            collisions_per_second: if wall_seconds > 0.0 {
                done as f64 / wall_seconds
            } else {
                0.0
            },
            wall_seconds,
            fraction,
            stop,
            log_bytes,
        }
    }

    /// The size (bytes) the log would reach at the stop if it kept growing at the
    /// rate it has so far, once that rate says something: from 1 % of the run, or
    /// from 64 MB written (the first snapshot and checkpoint, written at the start,
    /// would otherwise weigh too much). A log of a cooling gas grows more slowly
    /// later, so this is an upper estimate there.
    pub fn projected_log_bytes(&self) -> Option<f64> {
        let sure = self.fraction >= 0.01 || self.log_bytes >= 64 << 20;
        (sure && self.fraction > 0.0).then(|| self.log_bytes as f64 / self.fraction)
    }
}

/// Who watches a run while it runs (a live viewer, `carom run --live`): frames of
/// the exact state at instants it asks for, and every `/thermo` record. Nothing
/// it does changes the trajectory; it must not block, since the run waits for it.
pub trait Observer {
    /// Whether a frame is wanted now. Asked between events, about every 1024
    /// events (and after each pause), so it must be cheap; it decides the rate.
    fn frame_due(&mut self) -> bool;
    /// The instant at which to take a frame asked for at `now`: the first time
    /// after `now` (so that no event lies between), unless that is past
    /// `stop_time` or no frame is due. The rule of every front end's frames.
    fn frame_time(&mut self, now: f64, stop_time: f64) -> Option<f64> {
        let t = now.next_up();
        (t <= stop_time && self.frame_due()).then_some(t)
    }
    /// The frame asked for: the engine at an exact instant (scheduled at the
    /// first time after the one at which [`Observer::frame_due`] said yes, so
    /// that a run stopped at `engine.now()` has this very state), and the
    /// progress then. Also called once at the end of the run, at the final state.
    fn frame(&mut self, engine: &Engine, progress: &Progress);
    /// Each `/thermo` record, as the log writes it, right after it is written
    /// (none when the log has no `/thermo`).
    fn thermo(&mut self, record: &Thermo);
}

/// How the caller steers a run: a stop flag (for Ctrl-C) and a progress callback.
pub struct Control<'a> {
    /// When this becomes `true` the run stops at the next event and finishes its log
    /// (final checkpoint and summary, `stop_reason = interrupted`).
    pub stop: Option<&'a AtomicBool>,
    /// Called about every `progress_interval` of wall time, and once at the end.
    pub progress: Option<&'a mut dyn FnMut(&Progress)>,
    /// Called about every `progress_interval` of wall time while relaxed placement
    /// minimizes (before the run starts and its log exists), and once when it ends.
    pub placing: Option<&'a mut dyn FnMut(&PlacementProgress)>,
    /// Called while [`resume`] reads its input, before the run goes on: in each
    /// [`ResumePass`] with the input reader's progress, about once per MiB read and
    /// at the end of the pass (the whole log is read once and most of it copied,
    /// about a minute each for a log of 10⁶ discs).
    pub reading: Option<&'a mut dyn FnMut(ResumePass, ReadProgress)>,
    /// How many bytes the disk of the log file given as argument still has free for
    /// this user, asked with every progress report (also without a callback). `None`
    /// asks the file system ([`free_space_for`]); a
    /// caller with a quota of its own, or a test, answers here. When the room left
    /// falls to what finishing the log needs (see [`disk_low`]) the run stops
    /// with [`StopReason::DiskFull`] and a finished log, instead of dying later with
    /// a write error and a log cut at its last flush.
    pub free_space: Option<&'a mut FreeSpace<'a>>,
    /// Wall time between progress calls, and between looks at the room left on
    /// the log's disk.
    pub progress_interval: Duration,
    /// Run on when the log, projected from its growth so far, would need far
    /// more than its disk's room ([`far_too_small`]); by default such a run
    /// stops with [`StopReason::DiskFull`] and a finished log as soon as the
    /// projection says so (`--ignore-disk-estimate` on the command line).
    pub ignore_disk_estimate: bool,
    /// Who watches the run while it runs (a live viewer), if anyone.
    pub observer: Option<&'a mut dyn Observer>,
    /// Called once with the engine as the run's events begin (after placement,
    /// or after a resume has read its input): for a front end to say how the
    /// run is set up (`Engine::neighbour_lists`, the cells).
    pub started: Option<&'a mut dyn FnMut(&Engine)>,
}

/// What [`resume`] is doing with its input before the run goes on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ResumePass {
    /// Reading the whole log to find its last complete checkpoint.
    FindingCheckpoint,
    /// Copying the messages up to that checkpoint into the output.
    Copying,
}

impl ResumePass {
    /// One word for people, to stand before the file's name ("searching
    /// run.mcap", "copying run.mcap").
    pub fn as_str(self) -> &'static str {
        match self {
            ResumePass::FindingCheckpoint => "searching",
            ResumePass::Copying => "copying",
        }
    }
}

impl Default for Control<'_> {
    fn default() -> Self {
        Control {
            stop: None,
            progress: None,
            placing: None,
            reading: None,
            free_space: None,
            progress_interval: Duration::from_millis(200),
            ignore_disk_estimate: false,
            observer: None,
            started: None,
        }
    }
}

impl<'a> Control<'a> {
    /// A stop flag and a progress callback, with reports every 200 ms.
    pub fn new(stop: &'a AtomicBool, progress: &'a mut dyn FnMut(&Progress)) -> Self {
        Control {
            stop: Some(stop),
            progress: Some(progress),
            placing: None,
            reading: None,
            free_space: None,
            progress_interval: Duration::from_millis(200),
            ignore_disk_estimate: false,
            observer: None,
            started: None,
        }
    }
}

impl std::fmt::Debug for Control<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Control")
            .field("stop", &self.stop)
            .field("progress", &self.progress.is_some())
            .field("placing", &self.placing.is_some())
            .field("free_space", &self.free_space.is_some())
            .field("reading", &self.reading.is_some())
            .field("progress_interval", &self.progress_interval)
            .field("ignore_disk_estimate", &self.ignore_disk_estimate)
            .field("observer", &self.observer.is_some())
            .field("started", &self.started.is_some())
            .finish()
    }
}
