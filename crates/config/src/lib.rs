//! The JSON configuration a physicist writes by hand, and how it becomes a
//! [`RunSpec`](carom_log::RunSpec): `front` parses the file (or `{}`), applies the
//! `--set key=value` overrides ([`apply_set`]) and deserialises a [`Config`]
//! (`model`; unknown fields are errors); `validate` checks every value against its
//! range, each [`ConfigError`] naming the field's dotted path, what was wrong and
//! what is allowed; `resolve` ([`Config::to_run_spec`]) makes every default explicit,
//! and the resolved configuration ([`Config::canonical_json`]) travels into the log.
//!
//! Every field is optional (the default: 10⁴ discs at η = 0.5 for 50 time units);
//! fields, units and ranges are documented on the structs of `model`, from which
//! `data/config.schema.json` is generated ([`config_schema`]).

#![deny(missing_docs)]

mod boundary;
mod count;
mod error;
mod floor;
mod front;
mod log_config;
mod model;
mod neighbours;
mod old_log;
mod resolve;
mod schema;
mod validate;

pub use boundary::{AxisBoundary, BoundaryConfig};
pub use error::ConfigError;
pub use front::{apply_set, load_config, read_config_text, MAX_CONFIG_BYTES};
pub use log_config::{CollisionDetailConfig, CompressionConfig, LogConfig, SnapshotScheduleConfig};
pub use model::{
    BoxConfig, CollisionConfig, CollisionModel, CompressedPlacementConfig, Config, FloorConfig,
    GrowthConfig, PlacementConfig, SpeciesConfig, StopConfig, ThermostatConfig, VelocitiesConfig,
    DEFAULT_COUNT, DEFAULT_DURATION, DEFAULT_PACKING_FRACTION,
};
pub use neighbours::NeighboursConfig;
pub use old_log::derive_facts_for_old_log;
pub use schema::{config_schema, config_schema_json};

#[cfg(test)]
mod compression_tests;
#[cfg(test)]
mod error_tests;
#[cfg(test)]
mod gravity_tests;
#[cfg(test)]
mod neighbours_tests;
#[cfg(test)]
mod schedule_tests;
#[cfg(test)]
mod schema_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod thermostat_tests;
