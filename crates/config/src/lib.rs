//! The JSON configuration a physicist writes by hand, and how it becomes a
//! [`RunSpec`](carom_log::RunSpec).
//!
//! 1. `front`: the file (or `{}` when there is none) is parsed as JSON, the
//!    `--set key=value` overrides are applied to that value ([`apply_set`]), and
//!    the result is deserialised into [`Config`] (`model`; unknown fields are errors).
//! 2. `validate`: every value is checked against its allowed range; the log
//!    options through [`check_log_options`](carom_log::check_log_options), shared with
//!    resume. Every error ([`ConfigError`], `error`) names the field as a dotted
//!    path, says what was wrong and what is allowed.
//! 3. `resolve`: [`Config::to_run_spec`] makes every default explicit and builds
//!    the engine's spec; the resolved configuration ([`Config::canonical_json`])
//!    travels with it into the log, so a log always says exactly what ran.
//!
//! Every field is optional; the defaults are a fluid of 10⁴ discs at η = 0.5 for
//! 50 time units. The fields, their units and allowed values are documented on the
//! structs of `model`; `data/config.schema.json` is generated from them
//! ([`config_schema`]; `cargo run -p carom-config --example write_schema`).

#![deny(missing_docs)]

mod boundary;
mod count;
mod error;
mod floor;
mod front;
mod log_config;
mod model;
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
pub use old_log::derive_facts_for_old_log;
pub use schema::{config_schema, config_schema_json};

#[cfg(test)]
mod compression_tests;
#[cfg(test)]
mod gravity_tests;
#[cfg(test)]
mod schedule_tests;
#[cfg(test)]
mod schema_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod thermostat_tests;
