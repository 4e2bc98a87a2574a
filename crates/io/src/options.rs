//! The description of a run, shared by the configuration reader (which builds it
//! from JSON) and the run driver (which executes it). Plain data.

use carom_events::{EngineParams, SystemSpec};

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

/// What the MCAP log records and how often.
#[derive(Debug, Clone, PartialEq)]
pub struct LogOptions {
    /// Log collisions at all (`/collisions`).
    pub collisions: bool,
    /// Log every k-th collision (1 = every collision).
    pub collision_every: u64,
    /// Simulated time between `/snapshot` messages (time); `None` = no snapshots.
    pub snapshot_interval: Option<f64>,
    /// Simulated time between `/thermo` messages (time); `None` = no thermo.
    pub thermo_interval: Option<f64>,
    /// Simulated time between `/checkpoint` messages (time); `None` = only at the start
    /// and the end (a checkpoint is always written at both, so any flushed log resumes).
    pub checkpoint_interval: Option<f64>,
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
            snapshot_interval: Some(1.0),
            thermo_interval: Some(0.1),
            checkpoint_interval: Some(10.0),
            compression: Compression::Zstd,
            flush_seconds: 1.0,
        }
    }
}

impl LogOptions {
    /// The three record intervals with their configuration names: snapshot,
    /// thermo and checkpoint (time; `None` for none).
    pub fn intervals(&self) -> [(&'static str, Option<f64>); 3] {
        [
            ("log.snapshot_interval", self.snapshot_interval),
            ("log.thermo_interval", self.thermo_interval),
            ("log.checkpoint_interval", self.checkpoint_interval),
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
    /// What to log.
    pub log: LogOptions,
    /// The user's configuration as JSON text, stored verbatim in the log's metadata.
    pub config_json: String,
}
