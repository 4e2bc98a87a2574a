//! # carom-log
//!
//! The carom log: an MCAP file with four channels and two metadata records, and
//! the plain data of what a run logs (`options`: stop, log options, the resolved
//! [`RunSpec`]; `schedule`: snapshot schedules).
//!
//! `format` is in the middle: the channel table (topics, schemas, encodings), the
//! version constants, the metadata records with the resolved run, and each
//! message's Rust form with its CDR or JSON codec. `write` (the [`LogWriter`]) and
//! `read` (the [`LogReader`] and whole-file scans) each use the format and never
//! each other, as the `mcap` crate's writer and reader share its `records.rs`.
//! `docs/log-format.md` documents the format for other languages. The log sees
//! the engine only through plain data (states, events, checkpoints).

#![deny(missing_docs)]

mod format;
mod options;
mod options_error;
mod read;
mod schedule;
mod write;

pub use options::{
    check_log_options, CollisionDetail, Compression, LogOptions, RunSpec, Stop, MAX_RECORDS,
};
pub use options_error::OptionsError;
pub use schedule::{SchedulePoints, SnapshotSchedule, MAX_SCHEDULE_POINTS, MIN_FIRST_FRACTION};

/// The engine's parameter types the run facts hold ([`RunFacts`]), so that a
/// reader of logs needs no dependency on the engine.
pub use carom_engine::{Growth, Thermostat};
pub use format::{
    box_outline, disc_size, encode_scene, scene_stamp, species_color, BOX_COLOR, BOX_LINE_PIXELS,
    CH_SCENE, N_CHANNELS, SCENE_ENTITY, SCENE_FRAME, SCENE_UPDATE_MSG, SPECIES_COLORS,
};
pub use format::{
    log_time_ns, now_rfc3339, CdrError, Channel, CollisionBatch, CollisionRecord, DriverState,
    GrowthEvent, GrowthPhase, LogCheckpoint, MetadataError, RunFacts, RunMetadata, Snapshot,
    StopReason, SummaryMetadata, Thermo, CHANNELS, CHECKPOINT_FORMAT_VERSION, CHECKPOINT_MSG,
    CH_CHECKPOINT, CH_COLLISIONS, CH_SNAPSHOT, CH_THERMO, COLLISION_BATCH_MSG, KIND_PAIR,
    KIND_WALL, LOG_FORMAT_VERSION, METADATA_RUN, METADATA_SUMMARY, NO_DISC, SNAPSHOT_MSG,
    THERMO_JSON_SCHEMA, TOPICS,
};
pub use format::{seal, CHECKSUM_KEY};
pub use format::{
    wall_code, wall_of, CompactBatch, COMPACT_COLLISIONS_CHANNEL, COMPACT_COLLISION_BATCH_MSG,
    READABLE_MAJOR_VERSIONS, WALL_CODE_BASE,
};
pub use read::{
    last_checkpoint, last_checkpoint_observed, salvage, scan, scan_indexed, scan_observed,
    Collisions, Events, Filtered, LogEnd, LogEvent, LogInfo, LogMessage, LogReader, LostPart,
    RawMessage, ReadError, ReadOptions, ReadProgress, Salvaged,
};
pub use write::{LogWriter, WriteError, WriterOptions, WriterPosition, WriterStats};
