//! # carom-io
//!
//! Configuration, MCAP logging and reading for carom, in two parts that do not
//! import each other: `config` (the JSON file and `--set` overrides, their one
//! validator, and resolution into the engine's [`RunSpec`]) and `log` (the log
//! format, its writer and its reader). Both share the plain data of `options`.
//! The io crate sees the engine only through plain data (states, events,
//! checkpoints); it knows nothing about queues or cells.

#![warn(missing_docs)]

mod config;
mod log;
mod options;
mod schedule;

pub use options::{
    check_log_options, CollisionDetail, Compression, LogOptions, OptionsError, RunSpec, Stop,
    MAX_RECORDS,
};
pub use schedule::{SchedulePoints, SnapshotSchedule, MAX_SCHEDULE_POINTS, MIN_FIRST_FRACTION};

pub use config::{
    apply_set, load_config, AxisBoundary, BoundaryConfig, BoxConfig, CollisionConfig,
    CollisionDetailConfig, CollisionModel, CompressedPlacementConfig, CompressionConfig, Config,
    ConfigError, FloorConfig, GrowthConfig, LogConfig, PlacementConfig, SnapshotScheduleConfig,
    SpeciesConfig, StopConfig, ThermostatConfig, VelocitiesConfig, DEFAULT_COUNT, DEFAULT_DURATION,
    DEFAULT_PACKING_FRACTION,
};
pub use config::{read_config_text, MAX_CONFIG_BYTES};

pub use log::format::{encode_scene, CH_SCENE, N_CHANNELS, SCENE_UPDATE_MSG, SPECIES_COLORS};
pub use log::format::{
    log_time_ns, now_rfc3339, CdrError, Channel, CollisionBatch, CollisionRecord, DriverState,
    GrowthEvent, GrowthPhase, LogCheckpoint, MetadataError, RunFacts, RunMetadata, Snapshot,
    StopReason, SummaryMetadata, Thermo, CHANNELS, CHECKPOINT_FORMAT_VERSION, CHECKPOINT_MSG,
    CH_CHECKPOINT, CH_COLLISIONS, CH_SNAPSHOT, CH_THERMO, COLLISION_BATCH_MSG, KIND_PAIR,
    KIND_WALL, LOG_FORMAT_VERSION, METADATA_RUN, METADATA_SUMMARY, NO_DISC, SNAPSHOT_MSG,
    THERMO_JSON_SCHEMA, TOPICS,
};
pub use log::format::{seal, CHECKSUM_KEY};
pub use log::format::{
    wall_code, wall_of, CompactBatch, COMPACT_COLLISIONS_CHANNEL, COMPACT_COLLISION_BATCH_MSG,
    READABLE_MAJOR_VERSIONS, WALL_CODE_BASE,
};
pub use log::read::{
    last_checkpoint, last_checkpoint_observed, salvage, scan, scan_indexed, scan_observed,
    Collisions, Events, Filtered, LogEnd, LogEvent, LogInfo, LogMessage, LogReader, LostPart,
    RawMessage, ReadError, ReadOptions, ReadProgress, Salvaged,
};
pub use log::write::{LogWriter, WriteError, WriterOptions, WriterPosition, WriterStats};
