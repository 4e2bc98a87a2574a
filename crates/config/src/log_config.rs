//! The configuration's `log` section: what the MCAP log records and how often.
//! It maps one to one onto carom-log's `LogOptions` (in `resolve`), whose
//! defaults it takes, so a default is stated once; the checks of the intervals
//! (each at least `stop.duration` / 10⁹, at most 10⁹ records per run) are
//! carom-log's `check_log_options`, shared with resume.

use super::count::de_count;
use carom_log::{Compression, LogOptions};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// MCAP chunk compression.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum CompressionConfig {
    /// `"zstd"`: Zstandard (default).
    #[default]
    Zstd,
    /// `"lz4"`: LZ4 frames.
    Lz4,
    /// `"none"`: no compression.
    None,
}

/// What `/collisions` stores per collision (carom-log's `CollisionDetail`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum CollisionDetailConfig {
    /// `"compact"`: time, discs and impulse; velocities replayed from snapshots
    /// (the default with `collision_every` = 1).
    Compact,
    /// `"full"`: velocities before and after, normal, energy lost and virial (the
    /// default, and the only record, with `collision_every` > 1).
    Full,
}

/// `log.snapshot_schedule`: n snapshots inside every block of length T =
/// `log.snapshot_interval`, at offsets δ·(T/δ)^((j−1)/n), j = 1..n, from the block
/// start t₀ + b·T (n + 1 snapshots per T in all; carom-log's `SchedulePoints`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SnapshotScheduleConfig {
    /// n: snapshots added per block. Required; integer 1 ≤ n ≤ 1000.
    #[serde(deserialize_with = "de_count")]
    #[schemars(range(min = 1, max = 1000))]
    pub points: u64,
    /// δ: offset of the first from the block start (time). Required; finite,
    /// 10⁻⁶·T ≤ δ < T.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub first: f64,
}

/// What the MCAP log records and how often (carom-log's `LogOptions`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LogConfig {
    /// Log collisions on `/collisions`. Default true.
    #[serde(default = "default_collisions")]
    pub collisions: bool,
    /// Log every k-th collision. Default 1 (every collision); integer ≥ 1. (With
    /// k > 1 the analysis takes the pressure from the `/thermo` running totals.)
    #[serde(default = "default_collision_every", deserialize_with = "de_count")]
    #[schemars(range(min = 1))]
    pub collision_every: u64,
    /// What each logged collision stores: `"compact"` (time, discs, impulse) or
    /// `"full"` (velocities before and after, normal, energy lost, virial).
    /// Default `"compact"`, or `"full"` when `collision_every` > 1 or with
    /// gravity, a thermostat, compression or a vibrating floor (compact records
    /// replay velocities only from every collision: `"compact"` with
    /// `collision_every` > 1 is refused).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collision_detail: Option<CollisionDetailConfig>,
    /// Simulated time between `/snapshot` messages (time). Default 1; `null` for no
    /// snapshots; otherwise finite, > 0, and at least `stop.duration` / 10⁹ (at
    /// most 10⁹ records per run).
    #[serde(default = "default_snapshot")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub snapshot_interval: Option<f64>,
    /// Log-spaced snapshots added inside every `snapshot_interval`, for
    /// mean-square displacements and correlations over many decades of lag time.
    /// Default none; needs a `snapshot_interval`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshot_schedule: Option<SnapshotScheduleConfig>,
    /// Simulated time between `/thermo` messages (time). Default 0.1; `null` for
    /// none; otherwise finite, > 0, and at least `stop.duration` / 10⁹.
    #[serde(default = "default_thermo")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub thermo_interval: Option<f64>,
    /// Simulated time between `/checkpoint` messages (time). Default 10; `null` for
    /// a checkpoint at the end only; otherwise finite, > 0, and at least
    /// `stop.duration` / 10⁹.
    #[serde(default = "default_checkpoint")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub checkpoint_interval: Option<f64>,
    /// Simulated time between `/scene` frames for Foxglove's 3D panel (time; about
    /// 128 bytes per disc before compression). Default `null` (none); otherwise
    /// finite, > 0, and at least `stop.duration` / 10⁹.
    #[serde(default = "default_scene")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub scene_interval: Option<f64>,
    /// Chunk compression: `"zstd"` (default), `"lz4"` or `"none"`.
    #[serde(default)]
    pub compression: CompressionConfig,
    /// Wall-clock seconds between forced flushes of completed chunks to disk
    /// (seconds). Default 1; allowed: finite, > 0.
    #[serde(default = "default_flush_seconds")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub flush_seconds: f64,
}

impl Default for LogConfig {
    fn default() -> Self {
        let d = LogOptions::default();
        LogConfig {
            collisions: d.collisions,
            collision_every: d.collision_every,
            collision_detail: None,
            snapshot_interval: d.snapshot_interval,
            snapshot_schedule: None,
            thermo_interval: d.thermo_interval,
            checkpoint_interval: d.checkpoint_interval,
            scene_interval: d.scene_interval,
            compression: match d.compression {
                Compression::Zstd => CompressionConfig::Zstd,
                Compression::Lz4 => CompressionConfig::Lz4,
                Compression::None => CompressionConfig::None,
            },
            flush_seconds: d.flush_seconds,
        }
    }
}

// Each default of a field is the log's own (`LogOptions::default()`).
fn default_collisions() -> bool {
    LogOptions::default().collisions
}
fn default_collision_every() -> u64 {
    LogOptions::default().collision_every
}
fn default_snapshot() -> Option<f64> {
    LogOptions::default().snapshot_interval
}
fn default_thermo() -> Option<f64> {
    LogOptions::default().thermo_interval
}
fn default_checkpoint() -> Option<f64> {
    LogOptions::default().checkpoint_interval
}
fn default_scene() -> Option<f64> {
    LogOptions::default().scene_interval
}
fn default_flush_seconds() -> f64 {
    LogOptions::default().flush_seconds
}
