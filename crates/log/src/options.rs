//! The description of a run, shared by the configuration reader (which builds it
//! from JSON), the log (which stores it) and the run driver (which executes it):
//! plain data, and the one check of the log options against the stop
//! ([`check_log_options`]), which the configuration's validator and a resume both
//! call.

use crate::options_error::{options_error, OptionsError};
use crate::schedule::{SchedulePoints, SnapshotSchedule};
use carom_engine::{EngineParams, SystemSpec};

/// Compression of MCAP chunks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Compression {
    /// Zstandard (the default).
    #[default]
    Zstd,
    /// LZ4 frames.
    Lz4,
    /// No compression.
    None,
}

/// What `/collisions` stores per collision (physics of the records:
/// docs/log-format.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CollisionDetail {
    /// Time, discs and impulse (and the normal when the rule needs it); velocities
    /// are replayed from a snapshot. Needs every collision logged.
    #[default]
    Compact,
    /// Velocities before and after, normal, energy lost and virial (format 1's record).
    Full,
}

impl CollisionDetail {
    /// The configuration's word: `"compact"` or `"full"`.
    pub fn name(self) -> &'static str {
        match self {
            CollisionDetail::Compact => "compact",
            CollisionDetail::Full => "full",
        }
    }

    /// The detail named `name` (`"compact"` or `"full"`).
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "compact" => Some(CollisionDetail::Compact),
            "full" => Some(CollisionDetail::Full),
            _ => None,
        }
    }
}

/// What the MCAP log records and how often.
#[derive(Debug, Clone, PartialEq)]
pub struct LogOptions {
    /// Log collisions at all (`/collisions`).
    pub collisions: bool,
    /// Log every k-th collision (1 = every collision).
    pub collision_every: u64,
    /// The record asked for; see [`LogOptions::collision_record`] for the one written.
    pub collision_detail: CollisionDetail,
    /// Simulated time between `/snapshot` messages (time); `None` = no snapshots.
    pub snapshot_interval: Option<f64>,
    /// `log.snapshot_schedule`: snapshots added inside every snapshot interval at
    /// log-spaced offsets ([`SnapshotSchedule`]); `None` = none.
    pub snapshot_schedule: Option<SchedulePoints>,
    /// Simulated time between `/thermo` messages (time); `None` = no thermo.
    pub thermo_interval: Option<f64>,
    /// Simulated time between `/checkpoint` messages (time); `None` = only at the start
    /// and the end (a checkpoint is always written at both, so any flushed log resumes).
    pub checkpoint_interval: Option<f64>,
    /// Simulated time between `/scene` frames for Foxglove (time); `None` (the
    /// default) = no scene.
    pub scene_interval: Option<f64>,
    /// Chunk compression.
    pub compression: Compression,
    /// Wall-clock seconds between forced flushes of completed chunks to disk.
    pub flush_seconds: f64,
}

impl Default for LogOptions {
    fn default() -> Self {
        LogOptions {
            collisions: true,
            collision_every: 1,
            collision_detail: CollisionDetail::Compact,
            snapshot_interval: Some(1.0),
            snapshot_schedule: None,
            thermo_interval: Some(0.1),
            checkpoint_interval: Some(10.0),
            scene_interval: None,
            compression: Compression::Zstd,
            flush_seconds: 1.0,
        }
    }
}

impl LogOptions {
    /// The record `/collisions` holds: compact records replay velocities only
    /// from every collision, so with `collision_every` > 1 the log keeps the full
    /// record.
    pub fn collision_record(&self) -> CollisionDetail {
        if self.collision_every > 1 {
            CollisionDetail::Full
        } else {
            self.collision_detail
        }
    }

    /// The snapshot times, when snapshots are logged: every `snapshot_interval`,
    /// with the `snapshot_schedule`'s points inside each.
    pub fn snapshots(&self) -> Option<SnapshotSchedule> {
        self.snapshot_interval
            .map(|t| SnapshotSchedule::new(t, self.snapshot_schedule))
    }

    /// The record intervals with their configuration names: snapshot, thermo,
    /// checkpoint and scene (time; `None` for none).
    pub fn intervals(&self) -> [(&'static str, Option<f64>); 4] {
        [
            ("log.snapshot_interval", self.snapshot_interval),
            ("log.thermo_interval", self.thermo_interval),
            ("log.checkpoint_interval", self.checkpoint_interval),
            ("log.scene_interval", self.scene_interval),
        ]
    }
}

/// When a run ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stop {
    /// At this simulated time (time).
    Time(f64),
    /// After this many collisions (pair + wall).
    Collisions(u64),
}

/// Everything needed to execute a run.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSpec {
    /// The initial state to build.
    pub system: SystemSpec,
    /// The dynamics.
    pub params: EngineParams,
    /// When to stop.
    pub stop: Stop,
    /// The longest simulated time without a collision before the run stops with an
    /// error (time); `None`: the default of `stop.max_time_without_collision`.
    pub max_time_without_collision: Option<f64>,
    /// What to log.
    pub log: LogOptions,
    /// The user's configuration as JSON text, stored verbatim in the log's metadata.
    pub config_json: String,
    /// The thermostat, if any (its generator is seeded from `system.seed`).
    pub thermostat: Option<carom_engine::Thermostat>,
}

/// The most records of one kind a run may ask for through its log interval
/// (defined with the engine's scheduled events, `carom_engine::MAX_RECORDS`).
pub use carom_engine::MAX_RECORDS;

/// Check the log options and the stop of a run that is at time `now` (0 for a
/// fresh run): each interval finite and > 0 (or none), `collision_every` ≥ 1,
/// `flush_seconds` finite and > 0, a snapshot schedule only with snapshots and
/// within its bounds ([`SchedulePoints::check`]), a stop time finite and ≥ `now`, and at most
/// [`MAX_RECORDS`] records of a kind between `now` and the stop time. `stop_field`
/// names the setting that fixed the stop time in errors: `stop.time` (a resume's
/// `--until`) or `stop.duration` (a configuration, from time 0). A run stopped by
/// its collision count has no known length: its records are not counted.
pub fn check_log_options(
    log: &LogOptions,
    stop: &Stop,
    now: f64,
    stop_field: &'static str,
) -> Result<(), OptionsError> {
    for (field, v) in log.intervals() {
        if let Some(x) = v.filter(|x| !(x.is_finite() && *x > 0.0)) {
            return Err(options_error(
                field,
                format!("value {x}"),
                "finite simulated time > 0, or null for none",
            ));
        }
    }
    if let Some(p) = &log.snapshot_schedule {
        p.check(log.snapshot_interval)?;
    }
    if log.collision_every == 0 {
        return Err(options_error(
            "log.collision_every",
            "value 0".into(),
            "an integer ≥ 1 (use log.collisions = false to log none)",
        ));
    }
    if !(log.flush_seconds.is_finite() && log.flush_seconds > 0.0) {
        return Err(options_error(
            "log.flush_seconds",
            format!("value {}", log.flush_seconds),
            "finite wall-clock seconds > 0",
        ));
    }
    let Stop::Time(t) = *stop else {
        return Ok(());
    };
    if !t.is_finite() || t < now {
        return Err(options_error(
            stop_field,
            format!("stop time {t} is not a finite time ≥ the current time {now}"),
            "finite times ≥ the start time",
        ));
    }
    // An exponent mistyped (1e-17 for 1e-1, or `--until 1e12`) would otherwise
    // start a run that crawls while it fills the disk with records.
    // A snapshot schedule writes n + 1 snapshots per interval.
    let per_interval = |name: &str| match log.snapshots() {
        Some(s) if name == "log.snapshot_interval" => s.per_block() as f64,
        _ => 1.0,
    };
    let smallest = log
        .intervals()
        .into_iter()
        .filter_map(|(name, x)| Some((name, x?, per_interval(name))))
        .min_by(|a, b| (a.1 / a.2).total_cmp(&(b.1 / b.2)));
    match smallest {
        Some((name, x, per)) if (t - now) / x * per > MAX_RECORDS => Err(options_error(
            name,
            format!(
                "value {x:e}{} would write {:.1e} records from time {now} to the stop time \
                 {t} ({stop_field}), more than {MAX_RECORDS:.0e}; the latest stop time is {}",
                if per > 1.0 {
                    format!(" with {per} snapshots per interval (log.snapshot_schedule)")
                } else {
                    String::new()
                },
                (t - now) / x * per,
                now + MAX_RECORDS * x / per
            ),
            format!(
                "an interval ≥ (stop time − current time) / {MAX_RECORDS:.0e} = {:e}, or \
                 null for none; or an earlier stop time",
                (t - now) * per / MAX_RECORDS
            ),
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn field_of(log: &LogOptions, stop: Stop, now: f64) -> Option<&'static str> {
        check_log_options(log, &stop, now, "stop.time")
            .err()
            .map(|e| e.field)
    }

    #[test]
    fn log_options_are_checked_against_the_stop() {
        let d = LogOptions::default();
        assert_eq!(field_of(&d, Stop::Time(50.0), 0.0), None);
        assert_eq!(field_of(&d, Stop::Collisions(10), 0.0), None);
        let zero_flush = LogOptions {
            flush_seconds: 0.0,
            ..d.clone()
        };
        assert_eq!(
            field_of(&zero_flush, Stop::Time(1.0), 0.0),
            Some("log.flush_seconds")
        );
        let every = LogOptions {
            collision_every: 0,
            ..d.clone()
        };
        assert_eq!(
            field_of(&every, Stop::Time(1.0), 0.0),
            Some("log.collision_every")
        );
        let nan = LogOptions {
            snapshot_interval: Some(f64::NAN),
            ..d.clone()
        };
        assert_eq!(
            field_of(&nan, Stop::Time(1.0), 0.0),
            Some("log.snapshot_interval")
        );
        assert_eq!(field_of(&d, Stop::Time(2.0), 3.0), Some("stop.time"));
        // Thermo's 0.1 is the smallest interval: 10⁹ of them from time 3 is the limit.
        assert_eq!(field_of(&d, Stop::Time(3.0 + 1e8), 3.0), None);
        let e = check_log_options(&d, &Stop::Time(1e12), 3.0, "stop.time").unwrap_err();
        assert_eq!(e.field, "log.thermo_interval");
        let text = e.to_string();
        assert!(
            text.contains("stop.time") && text.contains("records"),
            "{text}"
        );
        // A run stopped by its collision count has no known length.
        let tiny = LogOptions {
            thermo_interval: Some(1e-17),
            ..d
        };
        assert_eq!(field_of(&tiny, Stop::Collisions(10), 0.0), None);
    }

    #[test]
    fn a_snapshot_schedule_multiplies_the_snapshots_counted() {
        // T = 1 with 19 points: 20 snapshots per unit time, more than thermo's 10.
        // 10⁹ of them last until t = 5·10⁷; to 6·10⁷ they are 1.2·10⁹.
        let d = LogOptions::default();
        let sched = LogOptions {
            snapshot_schedule: Some(SchedulePoints {
                points: 19,
                first: 0.01,
            }),
            ..d.clone()
        };
        assert_eq!(field_of(&sched, Stop::Time(5e7), 0.0), None);
        assert_eq!(
            field_of(&sched, Stop::Time(6e7), 0.0),
            Some("log.snapshot_interval")
        );
        // Without the schedule thermo writes 6·10⁸ records: allowed.
        assert_eq!(field_of(&d, Stop::Time(6e7), 0.0), None);
        // The schedule's own check runs here, for a resume too.
        let none = LogOptions {
            snapshot_interval: None,
            ..sched
        };
        assert_eq!(
            field_of(&none, Stop::Time(1.0), 0.0),
            Some("log.snapshot_schedule")
        );
    }
}
