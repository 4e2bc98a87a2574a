//! The JSON configuration a physicist writes by hand, and how it becomes a
//! [`RunSpec`].
//!
//! # Pipeline
//!
//! 1. The file (or `{}` when there is none) is parsed as JSON.
//! 2. `--set key=value` overrides are applied to that JSON value ([`apply_set`]):
//!    `key` is a dotted path (`species.0.count`, `log.snapshot_interval`), `value`
//!    is parsed as JSON when it parses and taken as a string otherwise
//!    (`--set placement=random`, `--set box.size=[40,20]`). A path into a
//!    top-level section the file does not have starts from that section's default;
//!    an array index equal to the array's length appends a new element.
//! 3. The result is deserialised into [`Config`] (unknown fields are errors), then
//!    checked ([`Config::validate`]): every error names the field as a dotted path,
//!    says what was wrong and what is allowed.
//! 4. [`Config::to_run_spec`] turns it into the engine's [`RunSpec`]; the fully
//!    resolved configuration ([`Config::canonical_json`]) travels with it and is
//!    stored in the log, so a log always says exactly what ran.
//!
//! # Format (units are the user's; the reference data use σ = 1, m = 1, kT = 1)
//!
//! ```json
//! {
//!   "description": "free text, stored in the log",
//!   "species": [{ "count": 10000, "radius": 0.5, "mass": 1.0 }],
//!   "box": { "packing_fraction": 0.5, "aspect": 1.0, "boundary": "periodic" },
//!   "temperature": 1.0,
//!   "seed": 0,
//!   "placement": "lattice",
//!   "velocities": "maxwell-boltzmann",
//!   "collision": { "model": "elastic", "tc": 0.0, "max_events_without_time_advance": 100000 },
//!   "stop": { "duration": 50.0 },
//!   "log": { "collisions": true, "collision_every": 1, "snapshot_interval": 1.0,
//!            "thermo_interval": 0.1, "checkpoint_interval": 10.0,
//!            "compression": "zstd", "flush_seconds": 1.0 }
//! }
//! ```
//!
//! Every field is optional; the values above are the defaults (a fluid of 10⁴ discs
//! at η = 0.5 running for 50 time units, about 1.75 × 10⁶ collisions, a few seconds
//! of wall time). The fields, their units and allowed values are documented on the
//! structs below and in `data/config.schema.json`.

use std::path::Path;

use carom_core::{Boundary, DVec2, Restitution, SimBox, Species};
use carom_events::{
    box_size_for, largest_radius, EngineParams, InitError, Placement, SystemSpec, Velocities,
};
use serde::{Deserialize, Deserializer, Serialize};
use serde_json::Value;
use thiserror::Error;

use crate::options::{Compression, LogOptions, RunSpec, Stop};

/// Hexagonal close packing π/(2√3), the largest packing fraction discs can reach.
const ETA_CLOSE_PACKED: f64 = 0.906_899_682_117_108_9;

/// A configuration that cannot be read or does not describe a valid run. Every
/// variant that concerns a field names it as a dotted path (`species.0.radius`).
#[derive(Debug, Error)]
pub enum ConfigError {
    /// The configuration file could not be read.
    #[error("cannot read configuration file {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The operating-system error.
        #[source]
        source: std::io::Error,
    },
    /// The text is not JSON.
    #[error("{origin}: not valid JSON at line {line}, column {column}: {message}")]
    Syntax {
        /// File name (or `configuration`).
        origin: String,
        /// Line of the error (1-based).
        line: usize,
        /// Column of the error (1-based).
        column: usize,
        /// What the parser found.
        message: String,
    },
    /// A `--set` argument is malformed or its path does not exist.
    #[error("--set {arg}: {problem}")]
    Set {
        /// The argument as given (`key=value`).
        arg: String,
        /// What was wrong.
        problem: String,
    },
    /// A field has the wrong type, is unknown, missing, or out of range.
    #[error("{field}: {problem} (allowed: {allowed})")]
    Invalid {
        /// Dotted path of the field, e.g. `species.1.radius`; `(top level)` for the
        /// document itself.
        field: String,
        /// What was wrong.
        problem: String,
        /// What is allowed.
        allowed: String,
    },
}

impl ConfigError {
    fn invalid(
        field: impl Into<String>,
        problem: impl Into<String>,
        allowed: impl Into<String>,
    ) -> Self {
        ConfigError::Invalid {
            field: field.into(),
            problem: problem.into(),
            allowed: allowed.into(),
        }
    }

    /// The dotted path of the offending field, when the error concerns one.
    pub fn field(&self) -> Option<&str> {
        match self {
            ConfigError::Invalid { field, .. } => Some(field),
            _ => None,
        }
    }

    /// Translate an error of the initial-state builder ([`SystemSpec::build`]) into
    /// the configuration's field names: `species[1].radius` becomes
    /// `species.1.radius`, `positions[3].x` becomes `placement.explicit.3`,
    /// overlapping explicit discs are reported on `placement.explicit`.
    pub fn from_init(e: InitError) -> Self {
        match e {
            InitError::Invalid {
                field,
                problem,
                allowed,
            } => ConfigError::Invalid {
                field: init_field_to_config(&field),
                problem,
                allowed,
            },
            InitError::Overlap {
                i,
                j,
                distance,
                sigma,
            } => ConfigError::invalid(
                "placement.explicit",
                format!(
                    "discs {i} and {j} overlap (centre distance {distance} < sum of radii {sigma})"
                ),
                "centre distances ≥ the sum of the two radii (minimum image on periodic axes)",
            ),
        }
    }

    /// [`ConfigError::from_init`] for the configuration `config_json` (the text in
    /// [`RunSpec::config_json`](crate::RunSpec)): the builder's `packing_fraction`
    /// is named as the setting that fixed it, `box.size` when the configuration
    /// gives the box's size and `box.packing_fraction` otherwise.
    pub fn from_init_in(e: InitError, config_json: &str) -> Self {
        let mut e = ConfigError::from_init(e);
        if let ConfigError::Invalid { field, .. } = &mut e {
            if field == "box" {
                let sized = serde_json::from_str::<serde_json::Value>(config_json)
                    .ok()
                    .is_some_and(|v| v.pointer("/box/size").is_some());
                *field = if sized {
                    "box.size"
                } else {
                    "box.packing_fraction"
                }
                .to_owned();
            }
        }
        e
    }
}

impl From<InitError> for ConfigError {
    fn from(e: InitError) -> Self {
        ConfigError::from_init(e)
    }
}

/// The box edges (length) for `species` at the packing fraction and aspect ratio
/// of `b` (no `size` given), refused when they come out infinite, zero, or with the
/// shorter edge not longer than the largest diameter: the error then names the
/// setting that made them so, rather than a `box.size` the user never wrote.
fn derived_box_size(species: &[Species], b: &BoxConfig) -> Result<DVec2, ConfigError> {
    let eta = b.packing_fraction.unwrap_or(DEFAULT_PACKING_FRACTION);
    let aspect = b.aspect.unwrap_or(1.0);
    let covered: f64 = species.iter().map(|s| s.count as f64 * s.disc_area()).sum();
    if !covered.is_finite() {
        return Err(ConfigError::invalid(
            "species",
            format!("the discs' total area Σ count π a² is {covered}"),
            "radii and counts whose total area is a finite number",
        ));
    }
    let size = box_size_for(species, eta, aspect);
    if !size.is_finite() || size.min_element() <= 0.0 {
        return Err(ConfigError::invalid(
            "box.packing_fraction",
            format!(
                "η = {eta:?} with these discs gives box edges {:?} × {:?}",
                size.x, size.y
            ),
            "a packing fraction and disc sizes whose box has finite edges",
        ));
    }
    let diameter = 2.0 * largest_radius(species);
    if size.min_element() <= diameter {
        return Err(ConfigError::invalid(
            "box.aspect",
            format!(
                "aspect {aspect} at η = {eta} gives box edges {:.4} × {:.4}, the shorter \
                 not longer than the largest disc diameter {diameter}",
                size.x, size.y
            ),
            "an aspect ratio nearer 1, or more discs, so that both edges exceed the \
             largest diameter",
        ));
    }
    Ok(size)
}

/// Map a field name of [`InitError`] to the configuration's dotted path.
fn init_field_to_config(field: &str) -> String {
    // `name[3].rest` → segments name, 3, rest.
    let dotted = field.replace('[', ".").replace(']', "");
    let mut parts: Vec<&str> = dotted.split('.').filter(|s| !s.is_empty()).collect();
    match parts.first().copied() {
        Some("positions") => {
            // Explicit positions are `[x, y]` pairs: drop the component name.
            parts.truncate(2);
            parts[0] = "placement.explicit";
        }
        Some("velocities") => {
            parts.truncate(2);
            parts[0] = "velocities.explicit";
        }
        Some("box") if parts.get(1) == Some(&"size") => {
            return "box.size".to_owned();
        }
        Some("box") if parts.get(1) == Some(&"boundary") => {
            return "box.wall_restitution".to_owned();
        }
        Some("packing_fraction") => return "box".to_owned(),
        _ => {}
    }
    parts.join(".")
}

// ---------------------------------------------------------------------------
// The configuration structs
// ---------------------------------------------------------------------------

/// A whole run, as written in a JSON configuration file. Every field is optional.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Config {
    /// URI of a JSON Schema for editors (`data/config.schema.json`); ignored.
    #[serde(rename = "$schema", default, skip_serializing_if = "Option::is_none")]
    pub schema: Option<String>,
    /// Free text describing the run; stored in the log with the configuration.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// The kinds of disc. Default: one species of 10 000 discs, radius 0.5, mass 1.
    /// Discs are numbered species by species, in this order.
    #[serde(default = "default_species")]
    pub species: Vec<SpeciesConfig>,
    /// The box: its size and boundaries.
    #[serde(rename = "box", default)]
    pub sim_box: BoxConfig,
    /// Temperature kT (energy) of the initial velocities: after drawing, velocities
    /// are scaled so that 2K/f = kT exactly (physics.md §5). Default 1; allowed:
    /// finite, > 0, and at least two discs (drawn velocities have zero total
    /// momentum, which leaves a single disc at rest). Ignored for explicit velocities.
    #[serde(default = "one")]
    pub temperature: f64,
    /// Seed of the random generator (placement and velocities). Default 0; any
    /// integer 0 ≤ seed < 2⁶⁴.
    #[serde(default)]
    pub seed: u64,
    /// Where the discs start. Default `"lattice"`.
    #[serde(default)]
    pub placement: PlacementConfig,
    /// How the initial velocities are drawn. Default `"maxwell-boltzmann"`.
    #[serde(default)]
    pub velocities: VelocitiesConfig,
    /// The pair collision rule and the inelastic-collapse safeguards.
    #[serde(default)]
    pub collision: CollisionConfig,
    /// When the run ends. Default `{"duration": 50}`.
    #[serde(default)]
    pub stop: StopConfig,
    /// What the MCAP log records and how often.
    #[serde(default)]
    pub log: LogConfig,
}

/// One kind of disc.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeciesConfig {
    /// Number of discs (required). Integer ≥ 0 (`1e4` is accepted); the total over
    /// all species must be ≥ 1.
    #[serde(deserialize_with = "de_count")]
    pub count: u64,
    /// Disc radius a (length). Default 0.5 (diameter σ = 1); allowed: finite, > 0.
    #[serde(default = "half")]
    pub radius: f64,
    /// Disc mass m (mass). Default 1; allowed: finite, > 0.
    #[serde(default = "one")]
    pub mass: f64,
}

/// The simulation box [0, L_x) × [0, L_y). Its size comes either from
/// `packing_fraction` and `aspect` (the default: η = 0.5, aspect 1) or from an
/// explicit `size`; not both.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxConfig {
    /// Packing fraction η = Σ N_s π a_s² / (L_x L_y) (dimensionless). Default 0.5
    /// when `size` is not given; allowed: 0 < η < 0.9069 (close packing). Lattice
    /// placement reaches 0.72, random placement only low densities (η ≲ 0.4),
    /// relaxed placement about 0.8.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub packing_fraction: Option<f64>,
    /// Aspect ratio L_x / L_y (dimensionless), with `packing_fraction`. Default 1;
    /// allowed: 0.01 ≤ aspect ≤ 100.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aspect: Option<f64>,
    /// Explicit edge lengths `[L_x, L_y]` (length), instead of `packing_fraction`
    /// and `aspect`. Each finite and longer than the largest disc diameter.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<[f64; 2]>,
    /// Boundary conditions: `"periodic"` (default), `"walls"`, or per axis
    /// `{"x": "periodic", "y": "walls"}`.
    #[serde(default)]
    pub boundary: BoundaryConfig,
    /// Restitution e_w of the hard walls (dimensionless): a disc leaves a wall with
    /// its normal velocity times −e_w. Default 1 (elastic); allowed 0 ≤ e_w ≤ 1.
    /// Only with walls on at least one axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_restitution: Option<f64>,
}

/// The boundary condition of one axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AxisBoundary {
    /// Periodic: minimum-image distances, discs re-enter on the other side.
    Periodic,
    /// Hard walls at 0 and L: disc centres stay in [a, L − a].
    Walls,
}

/// Boundaries of both axes: the same on both or one per axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoundaryConfig {
    /// The same boundary on x and y (`"periodic"` or `"walls"`).
    Both(AxisBoundary),
    /// One per axis (`{"x": "periodic", "y": "walls"}`: a channel).
    PerAxis {
        /// Boundary of the x axis.
        x: AxisBoundary,
        /// Boundary of the y axis.
        y: AxisBoundary,
    },
}

impl Default for BoundaryConfig {
    fn default() -> Self {
        BoundaryConfig::Both(AxisBoundary::Periodic)
    }
}

impl BoundaryConfig {
    /// The boundaries of the x and y axes.
    pub fn axes(&self) -> [AxisBoundary; 2] {
        match *self {
            BoundaryConfig::Both(b) => [b, b],
            BoundaryConfig::PerAxis { x, y } => [x, y],
        }
    }
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PerAxis {
    x: AxisBoundary,
    y: AxisBoundary,
}

impl Serialize for BoundaryConfig {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match *self {
            BoundaryConfig::Both(b) => b.serialize(s),
            BoundaryConfig::PerAxis { x, y } => PerAxis { x, y }.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for BoundaryConfig {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = BoundaryConfig;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(
                    "\"periodic\", \"walls\" or an object {\"x\": ..., \"y\": ...} \
                     with \"periodic\" or \"walls\" per axis",
                )
            }
            fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<Self::Value, E> {
                match s {
                    "periodic" => Ok(BoundaryConfig::Both(AxisBoundary::Periodic)),
                    "walls" => Ok(BoundaryConfig::Both(AxisBoundary::Walls)),
                    _ => Err(E::invalid_value(serde::de::Unexpected::Str(s), &self)),
                }
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<Self::Value, A::Error> {
                let p = PerAxis::deserialize(serde::de::value::MapAccessDeserializer::new(map))?;
                Ok(BoundaryConfig::PerAxis { x: p.x, y: p.y })
            }
        }
        d.deserialize_any(V)
    }
}

/// Where the discs start.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum PlacementConfig {
    /// `"lattice"`: the best-fitting square or triangular lattice (any η ≤ 0.72 from
    /// 34 discs on, and for fewer wherever a lattice fits; a mixture's sites are
    /// spaced for its largest disc).
    #[default]
    Lattice,
    /// `"random"`: uniformly random without overlap, largest discs first (low
    /// density, η ≲ 0.4).
    Random,
    /// `"relaxed"`: uniformly random positions at the requested density, made free
    /// of overlaps by minimizing a soft overlap energy (disordered; any mixture up
    /// to η ≈ 0.8).
    Relaxed,
    /// `{"explicit": [[x, y], ...]}`: one centre position per disc (length), in the
    /// order of the species; inside the box and not overlapping.
    Explicit(Vec<[f64; 2]>),
}

/// How the initial velocities are chosen.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum VelocitiesConfig {
    /// `"maxwell-boltzmann"`: Gaussian components of variance kT/m, zero total
    /// momentum, scaled to 2K/f = kT (physics.md §6).
    #[default]
    MaxwellBoltzmann,
    /// `"equal-speed"`: all discs of a species at one speed, random directions, with
    /// 2K/f = kT — a deliberately non-equilibrium start.
    EqualSpeed,
    /// `{"explicit": [[vx, vy], ...]}`: one velocity per disc (length/time).
    Explicit(Vec<[f64; 2]>),
}

/// The pair collision rule (physics.md §3–4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CollisionModel {
    /// Elastic collisions (physics.md §3); `coefficient` must be absent or 1.
    #[default]
    Elastic,
    /// Normal restitution e: u' = −e u (physics.md §4b, granular convention).
    Normal,
    /// The seed's centre-of-mass restitution R (physics.md §4a).
    #[serde(alias = "center-of-mass")]
    CentreOfMass,
}

/// The pair collision rule and the inelastic-collapse safeguards.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CollisionConfig {
    /// `"elastic"` (default), `"normal"` or `"centre-of-mass"` (also spelt
    /// `"center-of-mass"`).
    #[serde(default)]
    pub model: CollisionModel,
    /// Restitution coefficient e or R (dimensionless), 0 ≤ coefficient ≤ 1.
    /// Required for `"normal"` and `"centre-of-mass"`; 1 (or absent) for
    /// `"elastic"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coefficient: Option<f64>,
    /// TC model duration t_c (time, physics.md §4): a collision is elastic when either
    /// disc collided less than t_c ago, and so is a wall collision of a disc that
    /// collided (with a disc or a wall) less than t_c ago. Default 0 (off); allowed: finite, ≥ 0, and
    /// much shorter than the mean free time.
    #[serde(default)]
    pub tc: f64,
    /// Collisions allowed at one instant before the engine stops with a runaway
    /// (inelastic collapse) error instead of hanging. Default 100 000; integer ≥ 1.
    #[serde(default = "default_max_events", deserialize_with = "de_count")]
    pub max_events_without_time_advance: u64,
}

impl Default for CollisionConfig {
    fn default() -> Self {
        CollisionConfig {
            model: CollisionModel::Elastic,
            coefficient: None,
            tc: 0.0,
            max_events_without_time_advance: default_max_events(),
        }
    }
}

/// When the run ends: exactly one of `duration` and `collisions`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopConfig {
    /// Simulated time to run for (time). Default 50 when `collisions` is not
    /// given; allowed: finite, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration: Option<f64>,
    /// Number of collisions (pair + wall) to run for, instead of `duration`.
    /// Integer ≥ 1 (`1e9` is accepted).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "de_opt_count"
    )]
    pub collisions: Option<u64>,
}

/// MCAP chunk compression.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CompressionConfig {
    /// Zstandard (default).
    #[default]
    Zstd,
    /// LZ4 frames.
    Lz4,
    /// No compression.
    None,
}

/// What the MCAP log records and how often (maps to [`LogOptions`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LogConfig {
    /// Log collisions on `/collisions`. Default true.
    #[serde(default = "yes")]
    pub collisions: bool,
    /// Log every k-th collision. Default 1 (every collision); integer ≥ 1. (With
    /// k > 1 the analysis takes the pressure from the `/thermo` running totals.)
    #[serde(default = "default_one_u64", deserialize_with = "de_count")]
    pub collision_every: u64,
    /// Simulated time between `/snapshot` messages (time). Default 1; `null` for no
    /// snapshots; otherwise finite, > 0, and at least `stop.duration` /
    /// [`MAX_RECORDS`].
    #[serde(default = "default_snapshot")]
    pub snapshot_interval: Option<f64>,
    /// Simulated time between `/thermo` messages (time). Default 0.1; `null` for
    /// none; otherwise finite, > 0, and at least `stop.duration` / [`MAX_RECORDS`].
    #[serde(default = "default_thermo")]
    pub thermo_interval: Option<f64>,
    /// Simulated time between `/checkpoint` messages (time). Default 10; `null` for
    /// a checkpoint at the end only; otherwise finite, > 0, and at least
    /// `stop.duration` / [`MAX_RECORDS`].
    #[serde(default = "default_checkpoint")]
    pub checkpoint_interval: Option<f64>,
    /// Chunk compression: `"zstd"` (default), `"lz4"` or `"none"`.
    #[serde(default)]
    pub compression: CompressionConfig,
    /// Wall-clock seconds between forced flushes of completed chunks to disk
    /// (seconds). Default 1; allowed: finite, > 0.
    #[serde(default = "one")]
    pub flush_seconds: f64,
}

impl Default for LogConfig {
    fn default() -> Self {
        let d = LogOptions::default();
        LogConfig {
            collisions: d.collisions,
            collision_every: d.collision_every,
            snapshot_interval: d.snapshot_interval,
            thermo_interval: d.thermo_interval,
            checkpoint_interval: d.checkpoint_interval,
            compression: match d.compression {
                Compression::Zstd => CompressionConfig::Zstd,
                Compression::Lz4 => CompressionConfig::Lz4,
                Compression::None => CompressionConfig::None,
            },
            flush_seconds: d.flush_seconds,
        }
    }
}

/// Default run length in simulated time: at η = 0.5, N = 10⁴ there are about
/// 3.5 × 10⁴ collisions per unit time, so 50 time units are ~1.75 × 10⁶ collisions,
/// a few seconds at ~10⁶ collisions/s.
pub const DEFAULT_DURATION: f64 = 50.0;

/// The most records of one kind (snapshots, thermo or checkpoints) a run of
/// `stop.duration` may ask for through its log interval: far more than any
/// analysis reads (10⁹ thermo records are about 100 GB), so only a mistyped
/// interval meets it.
pub const MAX_RECORDS: f64 = 1e9;
/// Default packing fraction η when the box size is not given.
pub const DEFAULT_PACKING_FRACTION: f64 = 0.5;
/// Default number of discs (one species).
pub const DEFAULT_COUNT: u64 = 10_000;

fn one() -> f64 {
    1.0
}
fn half() -> f64 {
    0.5
}
fn yes() -> bool {
    true
}
fn default_one_u64() -> u64 {
    1
}
fn default_max_events() -> u64 {
    EngineParams::default().max_events_without_time_advance
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
fn default_species() -> Vec<SpeciesConfig> {
    vec![SpeciesConfig {
        count: DEFAULT_COUNT,
        radius: 0.5,
        mass: 1.0,
    }]
}

impl Default for Config {
    fn default() -> Self {
        Config {
            schema: None,
            description: None,
            species: default_species(),
            sim_box: BoxConfig::default(),
            temperature: 1.0,
            seed: 0,
            placement: PlacementConfig::default(),
            velocities: VelocitiesConfig::default(),
            collision: CollisionConfig::default(),
            stop: StopConfig::default(),
            log: LogConfig::default(),
        }
    }
}

/// A count: a non-negative integer, also accepted as an integral float such as
/// `1e9` (physicists write those) up to 2⁵³.
fn de_count<'de, D: Deserializer<'de>>(d: D) -> Result<u64, D::Error> {
    struct V;
    impl serde::de::Visitor<'_> for V {
        type Value = u64;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a non-negative integer")
        }
        fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<u64, E> {
            Ok(v)
        }
        fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<u64, E> {
            u64::try_from(v).map_err(|_| E::invalid_value(serde::de::Unexpected::Signed(v), &self))
        }
        fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<u64, E> {
            if v.fract() == 0.0 && (0.0..=9_007_199_254_740_992.0).contains(&v) {
                Ok(v as u64)
            } else {
                Err(E::invalid_value(serde::de::Unexpected::Float(v), &self))
            }
        }
    }
    d.deserialize_any(V)
}

fn de_opt_count<'de, D: Deserializer<'de>>(d: D) -> Result<Option<u64>, D::Error> {
    de_count(d).map(Some)
}

// ---------------------------------------------------------------------------
// Reading
// ---------------------------------------------------------------------------

/// Read a configuration file (or the built-in default when `path` is `None`),
/// apply the `--set key=value` overrides in order, check everything and build the
/// [`RunSpec`]. This is what `carom run` calls.
pub fn load(path: Option<&Path>, sets: &[String]) -> Result<RunSpec, ConfigError> {
    let (text, origin) = match path {
        Some(p) => (
            std::fs::read_to_string(p).map_err(|source| ConfigError::Io {
                path: p.display().to_string(),
                source,
            })?,
            p.display().to_string(),
        ),
        None => ("{}".to_owned(), "built-in default".to_owned()),
    };
    let config = Config::from_json_with_sets(&text, &origin, sets)?;
    config.to_run_spec()
}

/// Parse JSON text into a [`Value`], reporting syntax errors with line and column.
fn parse_json(text: &str, origin: &str) -> Result<Value, ConfigError> {
    let value = serde_json::from_str(text).map_err(|e| ConfigError::Syntax {
        origin: origin.to_owned(),
        line: e.line(),
        column: e.column(),
        message: strip_position(&e.to_string()).to_owned(),
    })?;
    // A JSON object read into a Value keeps the last of two equal keys without a
    // word; reading the text straight into the configuration's structs notices.
    // (Any other error of that reading is left to the checks that follow, which
    // see the `--set` overrides too.)
    let mut de = serde_json::Deserializer::from_str(text);
    if let Err(e) = serde_path_to_error::deserialize::<_, Config>(&mut de) {
        let message = e.inner().to_string();
        if let Some(rest) = message.strip_prefix("duplicate field `") {
            let key = rest.split('`').next().unwrap_or_default();
            let parent = dotted(e.path());
            let field = if parent == "(top level)" || parent.ends_with(key) {
                key.to_owned()
            } else {
                format!("{parent}.{key}")
            };
            return Err(ConfigError::invalid(
                field,
                format!("given twice ({})", strip_position(&message)),
                "each key once per object",
            ));
        }
    }
    Ok(value)
}

/// Render a serde_path_to_error path as a dotted path (`species.0.count`).
fn dotted(path: &serde_path_to_error::Path) -> String {
    use serde_path_to_error::Segment;
    let parts: Vec<String> = path
        .iter()
        .filter_map(|s| match s {
            Segment::Seq { index } => Some(index.to_string()),
            Segment::Map { key } => Some(key.clone()),
            Segment::Enum { variant } => Some(variant.clone()),
            Segment::Unknown => None,
        })
        .collect();
    if parts.is_empty() {
        "(top level)".to_owned()
    } else {
        parts.join(".")
    }
}

/// Drop serde_json's trailing " at line L column C" (reported separately).
fn strip_position(msg: &str) -> &str {
    match msg.rfind(" at line ") {
        Some(k) if msg[k..].contains(" column ") => &msg[..k],
        _ => msg,
    }
}

/// serde's name of an expected Rust type in words a user of the config reads
/// ("f64" is "a number"); anything else as it is.
fn plain_type(expected: &str) -> String {
    match expected {
        "f64" | "f32" => "a number".to_owned(),
        "u64" | "u32" | "usize" | "u16" => "a non-negative integer".to_owned(),
        "i64" | "i32" => "an integer".to_owned(),
        "a boolean" | "bool" => "true or false".to_owned(),
        _ => expected.to_owned(),
    }
}

/// Split serde's message "problem, expected X" into (problem, allowed).
fn split_serde_message(msg: &str) -> (String, String) {
    // serde_json appends " at line L column C" only when parsing text; from a Value
    // there is none, but strip it in case.
    let msg = strip_position(msg);
    if msg.starts_with("invalid length") {
        // Only the [x, y] pairs (box.size, explicit positions and velocities) have
        // a fixed length; serde's "expected fewer elements" says too little.
        let problem = msg.split(", expected").next().unwrap_or(msg);
        return (
            format!("{problem} numbers"),
            "an array of exactly 2 numbers [x, y]".to_owned(),
        );
    }
    match msg.find(", expected ") {
        Some(k) => (
            msg[..k].to_owned(),
            plain_type(&msg[k + ", expected ".len()..]),
        ),
        None => {
            if msg.starts_with("missing field") {
                (msg.to_owned(), "the field is required here".to_owned())
            } else {
                (msg.to_owned(), "see data/config.schema.json".to_owned())
            }
        }
    }
}

impl Config {
    /// Parse and check a configuration from JSON text (no overrides).
    pub fn from_json_str(text: &str) -> Result<Config, ConfigError> {
        Config::from_json_with_sets(text, "configuration", &[])
    }

    /// Parse JSON text, apply `--set key=value` overrides in order, deserialise and
    /// check. `origin` names the text in syntax errors (a file name).
    pub fn from_json_with_sets(
        text: &str,
        origin: &str,
        sets: &[String],
    ) -> Result<Config, ConfigError> {
        let mut value = parse_json(text, origin)?;
        for s in sets {
            apply_set(&mut value, s)?;
        }
        Config::from_value(value)
    }

    /// Deserialise a JSON value and check it ([`Config::validate`]).
    pub fn from_value(value: Value) -> Result<Config, ConfigError> {
        if !value.is_object() {
            return Err(ConfigError::invalid(
                "(top level)",
                format!("the configuration is {}", kind_of(&value)),
                "a JSON object {...}",
            ));
        }
        let config: Config = serde_path_to_error::deserialize(value).map_err(|e| {
            let mut field = dotted(e.path());
            let message = e.inner().to_string();
            // For an unknown field the path ends at the enclosing object; name the
            // field itself.
            if let Some(rest) = message.strip_prefix("unknown field `") {
                if let Some(end) = rest.find('`') {
                    let key = &rest[..end];
                    if !field.ends_with(key) {
                        field = if field == "(top level)" {
                            key.to_owned()
                        } else {
                            format!("{field}.{key}")
                        };
                    }
                }
            }
            let (problem, allowed) = split_serde_message(&message);
            ConfigError::invalid(field, problem, allowed)
        })?;
        config.validate()?;
        Ok(config)
    }

    /// Check every value against its allowed range. Errors name the field.
    /// (Placement feasibility and overlaps are checked when the state is built,
    /// see [`ConfigError::from_init`].)
    pub fn validate(&self) -> Result<(), ConfigError> {
        if self.species.is_empty() {
            return Err(ConfigError::invalid(
                "species",
                "the list is empty",
                "at least one species {\"count\": N, \"radius\": a, \"mass\": m}",
            ));
        }
        let mut total: u64 = 0;
        for (k, s) in self.species.iter().enumerate() {
            positive_finite(&format!("species.{k}.radius"), s.radius)?;
            positive_finite(&format!("species.{k}.mass"), s.mass)?;
            total = total.saturating_add(s.count);
        }
        if total == 0 {
            return Err(ConfigError::invalid(
                "species",
                "zero discs in total",
                "at least one disc (some species.N.count ≥ 1)",
            ));
        }
        if total >= u32::MAX as u64 {
            return Err(ConfigError::invalid(
                "species",
                format!("{total} discs in total"),
                "fewer than 4294967295 discs",
            ));
        }
        let b = &self.sim_box;
        if let Some(size) = b.size {
            for (k, name) in ["box.packing_fraction", "box.aspect"].iter().enumerate() {
                let given = if k == 0 { b.packing_fraction } else { b.aspect };
                if given.is_some() {
                    return Err(ConfigError::invalid(
                        *name,
                        "given together with box.size",
                        "either box.size, or box.packing_fraction (with optional box.aspect)",
                    ));
                }
            }
            let d_max = 2.0 * self.species.iter().map(|s| s.radius).fold(0.0, f64::max);
            for (k, l) in size.iter().enumerate() {
                if !l.is_finite() || *l <= d_max {
                    return Err(ConfigError::invalid(
                        format!("box.size.{k}"),
                        format!("edge length {l}"),
                        format!("finite and longer than the largest disc diameter {d_max}"),
                    ));
                }
            }
        } else {
            if let Some(eta) = b.packing_fraction {
                if !(eta.is_finite() && eta > 0.0 && eta < ETA_CLOSE_PACKED) {
                    return Err(ConfigError::invalid(
                        "box.packing_fraction",
                        format!("value {eta}"),
                        "0 < η < 0.9069 (hexagonal close packing); lattice placement reaches 0.72",
                    ));
                }
            }
            if let Some(a) = b.aspect {
                if !(a.is_finite() && (0.01..=100.0).contains(&a)) {
                    return Err(ConfigError::invalid(
                        "box.aspect",
                        format!("value {a}"),
                        "0.01 ≤ L_x/L_y ≤ 100",
                    ));
                }
            }
        }
        if let Some(e) = b.wall_restitution {
            if !b.boundary.axes().contains(&AxisBoundary::Walls) {
                return Err(ConfigError::invalid(
                    "box.wall_restitution",
                    "given but no axis has walls",
                    "only with box.boundary \"walls\" or walls on one axis",
                ));
            }
            if !(0.0..=1.0).contains(&e) {
                return Err(ConfigError::invalid(
                    "box.wall_restitution",
                    format!("value {e}"),
                    "0 ≤ e_w ≤ 1",
                ));
            }
        }
        if !(self.temperature.is_finite() && self.temperature > 0.0) {
            return Err(ConfigError::invalid(
                "temperature",
                format!("value {}", self.temperature),
                "finite kT > 0",
            ));
        }
        let n = total as usize;
        let check_list = |field: &str, list: &[[f64; 2]], what: &str| {
            if list.len() != n {
                return Err(ConfigError::invalid(
                    field,
                    format!("{} {what} given for {n} discs", list.len()),
                    format!("exactly one [x, y] pair per disc ({n})"),
                ));
            }
            Ok(())
        };
        if let PlacementConfig::Explicit(p) = &self.placement {
            check_list("placement.explicit", p, "positions")?;
        }
        if let VelocitiesConfig::Explicit(v) = &self.velocities {
            check_list("velocities.explicit", v, "velocities")?;
        }
        let c = &self.collision;
        match (c.model, c.coefficient) {
            (CollisionModel::Elastic, Some(e)) if e != 1.0 => {
                return Err(ConfigError::invalid(
                    "collision.coefficient",
                    format!("{e} with model \"elastic\""),
                    "1 (or absent) for \"elastic\"; set collision.model to \"normal\" or \
                     \"centre-of-mass\" for inelastic collisions",
                ))
            }
            (CollisionModel::Normal | CollisionModel::CentreOfMass, None) => {
                return Err(ConfigError::invalid(
                    "collision.coefficient",
                    "missing for an inelastic model",
                    "a restitution coefficient 0 ≤ e ≤ 1",
                ))
            }
            (_, Some(e)) if !(0.0..=1.0).contains(&e) => {
                return Err(ConfigError::invalid(
                    "collision.coefficient",
                    format!("value {e}"),
                    "0 ≤ coefficient ≤ 1",
                ))
            }
            _ => {}
        }
        if !(c.tc.is_finite() && c.tc >= 0.0) {
            return Err(ConfigError::invalid(
                "collision.tc",
                format!("value {}", c.tc),
                "finite t_c ≥ 0 (0 switches the TC model off)",
            ));
        }
        if c.max_events_without_time_advance == 0 {
            return Err(ConfigError::invalid(
                "collision.max_events_without_time_advance",
                "value 0",
                "an integer ≥ 1",
            ));
        }
        match (self.stop.duration, self.stop.collisions) {
            (Some(_), Some(_)) => {
                return Err(ConfigError::invalid(
                    "stop",
                    "both duration and collisions given",
                    "exactly one of stop.duration and stop.collisions",
                ))
            }
            (Some(t), None) if !(t.is_finite() && t > 0.0) => {
                return Err(ConfigError::invalid(
                    "stop.duration",
                    format!("value {t}"),
                    "finite simulated time > 0",
                ))
            }
            (None, Some(0)) => {
                return Err(ConfigError::invalid(
                    "stop.collisions",
                    "value 0",
                    "an integer ≥ 1",
                ))
            }
            (None, Some(_))
                if self
                    .species
                    .iter()
                    .map(|s| s.count)
                    .filter(|&c| c > 0)
                    .eq([1])
                    && !self.sim_box.boundary.axes().contains(&AxisBoundary::Walls) =>
            {
                // It would run forever, filling the disk with snapshots.
                return Err(ConfigError::invalid(
                    "stop.collisions",
                    "a single disc in a periodic box never collides",
                    "stop.duration, or walls, or more than one disc",
                ));
            }
            _ => {}
        }
        let l = &self.log;
        if l.collision_every == 0 {
            return Err(ConfigError::invalid(
                "log.collision_every",
                "value 0",
                "an integer ≥ 1 (use log.collisions = false to log none)",
            ));
        }
        // A run of known length: how long it lasts, to count its records.
        let duration = match (self.stop.duration, self.stop.collisions) {
            (Some(t), _) => Some(t),
            (None, None) => Some(DEFAULT_DURATION),
            (None, Some(_)) => None,
        };
        for (name, v) in [
            ("log.snapshot_interval", l.snapshot_interval),
            ("log.thermo_interval", l.thermo_interval),
            ("log.checkpoint_interval", l.checkpoint_interval),
        ] {
            if let Some(x) = v {
                if !(x.is_finite() && x > 0.0) {
                    return Err(ConfigError::invalid(
                        name,
                        format!("value {x}"),
                        "finite simulated time > 0, or null for none",
                    ));
                }
                // An exponent mistyped (1e-17 for 1e-1) would otherwise start a
                // run that crawls while it fills the disk with records.
                if let Some(t) = duration.filter(|&t| t / x > MAX_RECORDS) {
                    return Err(ConfigError::invalid(
                        name,
                        format!(
                            "value {x:e} would write {:.1e} records over stop.duration = {t}",
                            t / x
                        ),
                        format!(
                            "an interval ≥ stop.duration / {MAX_RECORDS:.0e} = {:e}, \
                             at most {MAX_RECORDS:.0e} records of a kind per run; or null for none",
                            t / MAX_RECORDS
                        ),
                    ));
                }
            }
        }
        if !(l.flush_seconds.is_finite() && l.flush_seconds > 0.0) {
            return Err(ConfigError::invalid(
                "log.flush_seconds",
                format!("value {}", l.flush_seconds),
                "finite wall-clock seconds > 0",
            ));
        }
        Ok(())
    }

    /// The configuration with every default made explicit: the box's packing
    /// fraction and aspect (when no size is given), the stop criterion, the wall
    /// restitution (when there are walls) and the elastic coefficient. Parsing its
    /// JSON gives the same run.
    pub fn resolved(&self) -> Config {
        let mut c = self.clone();
        if c.sim_box.size.is_none() {
            c.sim_box
                .packing_fraction
                .get_or_insert(DEFAULT_PACKING_FRACTION);
            c.sim_box.aspect.get_or_insert(1.0);
        }
        if c.sim_box.boundary.axes().contains(&AxisBoundary::Walls) {
            c.sim_box.wall_restitution.get_or_insert(1.0);
        }
        if c.stop.duration.is_none() && c.stop.collisions.is_none() {
            c.stop.duration = Some(DEFAULT_DURATION);
        }
        c.collision.coefficient.get_or_insert(1.0);
        c
    }

    /// The fully resolved configuration ([`Config::resolved`]) as pretty JSON: what
    /// is stored in the log.
    pub fn canonical_json(&self) -> String {
        serde_json::to_string_pretty(&self.resolved()).expect("a Config always serialises")
    }

    /// The engine's view of the configuration: the system to build, the dynamics,
    /// the stop criterion and the log options, with [`Config::canonical_json`] as
    /// `config_json`. Checks the configuration first.
    pub fn to_run_spec(&self) -> Result<RunSpec, ConfigError> {
        self.validate()?;
        let c = self.resolved();
        let species: Vec<Species> = c
            .species
            .iter()
            .map(|s| Species::new(s.count as usize, s.radius, s.mass))
            .collect();
        let size = match c.sim_box.size {
            Some([lx, ly]) => DVec2::new(lx, ly),
            None => derived_box_size(&species, &c.sim_box)?,
        };
        let restitution = c.sim_box.wall_restitution.unwrap_or(1.0);
        let axes = c.sim_box.boundary.axes();
        let boundary = axes.map(|a| match a {
            AxisBoundary::Periodic => Boundary::Periodic,
            AxisBoundary::Walls => Boundary::Walls { restitution },
        });
        let to_vecs = |l: &[[f64; 2]]| l.iter().map(|&[x, y]| DVec2::new(x, y)).collect();
        let system = SystemSpec {
            species,
            sim_box: SimBox { size, boundary },
            temperature: c.temperature,
            seed: c.seed,
            placement: match &c.placement {
                PlacementConfig::Lattice => Placement::Lattice,
                PlacementConfig::Random => Placement::Random,
                PlacementConfig::Relaxed => Placement::Relaxed,
                PlacementConfig::Explicit(p) => Placement::Explicit(to_vecs(p)),
            },
            velocities: match &c.velocities {
                VelocitiesConfig::MaxwellBoltzmann => Velocities::MaxwellBoltzmann,
                VelocitiesConfig::EqualSpeed => Velocities::EqualSpeed,
                VelocitiesConfig::Explicit(v) => Velocities::Explicit(to_vecs(v)),
            },
        };
        let e = c.collision.coefficient.unwrap_or(1.0);
        let params = EngineParams {
            restitution: match c.collision.model {
                CollisionModel::Elastic => Restitution::Elastic,
                CollisionModel::Normal => Restitution::Normal(e),
                CollisionModel::CentreOfMass => Restitution::CentreOfMass(e),
            },
            tc: c.collision.tc,
            max_events_without_time_advance: c.collision.max_events_without_time_advance,
        };
        let stop = match (c.stop.duration, c.stop.collisions) {
            (_, Some(n)) => Stop::Collisions(n),
            (Some(t), None) => Stop::Time(t),
            (None, None) => Stop::Time(DEFAULT_DURATION),
        };
        let l = c.log;
        let log = LogOptions {
            collisions: l.collisions,
            collision_every: l.collision_every,
            snapshot_interval: l.snapshot_interval,
            thermo_interval: l.thermo_interval,
            checkpoint_interval: l.checkpoint_interval,
            compression: match l.compression {
                CompressionConfig::Zstd => Compression::Zstd,
                CompressionConfig::Lz4 => Compression::Lz4,
                CompressionConfig::None => Compression::None,
            },
            flush_seconds: l.flush_seconds,
        };
        Ok(RunSpec {
            system,
            params,
            stop,
            log,
            config_json: self.canonical_json(),
        })
    }
}

fn positive_finite(field: &str, x: f64) -> Result<(), ConfigError> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(ConfigError::invalid(
            field,
            format!("value {x}"),
            "a finite number > 0",
        ))
    }
}

fn kind_of(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

// ---------------------------------------------------------------------------
// --set
// ---------------------------------------------------------------------------

/// Apply one `--set key=value` override to a configuration's JSON value.
///
/// `key` is a dotted path: object keys, and array indices for arrays
/// (`species.1.radius`). `value` is parsed as JSON if it parses, otherwise taken
/// as a string (`placement=random`). Missing top-level sections start from their
/// default (`species.0.count=500` on an empty configuration edits the default
/// species), missing objects below are created, and an index equal to an array's
/// length appends an element. Whether the resulting key is known is checked when
/// the value is deserialised, which names the field.
pub fn apply_set(config: &mut Value, arg: &str) -> Result<(), ConfigError> {
    let bad = |problem: String| ConfigError::Set {
        arg: arg.to_owned(),
        problem,
    };
    let (key, raw) = arg
        .split_once('=')
        .ok_or_else(|| bad("expected key=value (e.g. species.0.count=500)".to_owned()))?;
    let key = key.trim();
    if key.is_empty() || key.split('.').any(str::is_empty) {
        return Err(bad(format!(
            "`{key}` is not a dotted path (e.g. log.snapshot_interval)"
        )));
    }
    let new: Value = serde_json::from_str(raw).unwrap_or_else(|_| Value::String(raw.to_owned()));
    if !config.is_object() {
        return Err(bad("the configuration is not a JSON object".to_owned()));
    }
    let defaults = serde_json::to_value(Config::default()).expect("a Config always serialises");
    let segments: Vec<&str> = key.split('.').collect();
    let mut here = config;
    for (depth, seg) in segments.iter().enumerate() {
        let last = depth + 1 == segments.len();
        let path_so_far = segments[..=depth].join(".");
        here = match here {
            Value::Object(map) => {
                if !map.contains_key(*seg) {
                    // A top-level section missing from the file starts from its
                    // default; anything else missing starts empty.
                    let fill = if depth == 0 {
                        defaults.get(*seg).cloned()
                    } else {
                        None
                    };
                    map.insert(
                        (*seg).to_owned(),
                        fill.unwrap_or_else(|| Value::Object(Default::default())),
                    );
                }
                map.get_mut(*seg).expect("inserted above")
            }
            Value::Array(items) => {
                let idx: usize = seg.parse().map_err(|_| {
                    bad(format!(
                        "`{path_so_far}`: `{seg}` is not an index into the list (use 0, 1, ...)"
                    ))
                })?;
                if idx > items.len() {
                    return Err(bad(format!(
                        "`{path_so_far}`: index {idx} is beyond the list of {} (indices 0..={} \
                         allowed; {} appends)",
                        items.len(),
                        items.len(),
                        items.len()
                    )));
                }
                if idx == items.len() {
                    items.push(Value::Object(Default::default()));
                }
                &mut items[idx]
            }
            other => {
                return Err(bad(format!(
                    "`{}` is {}, not an object or list, so it has no field `{seg}`",
                    segments[..depth].join("."),
                    kind_of(other)
                )))
            }
        };
        if last {
            *here = new;
            return Ok(());
        }
    }
    unreachable!("the loop returns at the last segment")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    fn data_dir() -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data")
    }

    fn err_of(text: &str, sets: &[&str]) -> ConfigError {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        match Config::from_json_with_sets(text, "test", &sets).and_then(|c| c.to_run_spec()) {
            Ok(_) => panic!("expected an error for {text} {sets:?}"),
            Err(e) => e,
        }
    }

    fn field_of(text: &str, sets: &[&str]) -> String {
        let e = err_of(text, sets);
        e.field()
            .unwrap_or_else(|| panic!("no field in {e}"))
            .to_owned()
    }

    #[test]
    fn type_errors_say_what_is_allowed_in_words() {
        for (text, sets, allowed) in [
            (r#"{"temperature": "warm"}"#, vec![], "allowed: a number"),
            ("{}", vec!["temperature=abc"], "allowed: a number"),
            (r#"{"seed": -1}"#, vec![], "allowed: a non-negative integer"),
            (
                r#"{"log": {"collisions": 3}}"#,
                vec![],
                "allowed: true or false",
            ),
        ] {
            let msg = err_of(text, &sets).to_string();
            assert!(msg.contains(allowed), "{text} {sets:?}: {msg}");
            assert!(!msg.contains("f64") && !msg.contains("u64"), "{msg}");
        }
    }

    #[test]
    fn default_is_fluid_of_ten_thousand_at_half_packing() {
        let spec = load(None, &[]).unwrap();
        assert_eq!(spec.system.species.len(), 1);
        assert_eq!(spec.system.species[0].count, 10_000);
        let s = &spec.system.species[0];
        let eta = s.count as f64 * s.disc_area() / spec.system.sim_box.area();
        assert!((eta - 0.5).abs() < 1e-12, "η = {eta}");
        assert!((spec.system.sim_box.size.x - spec.system.sim_box.size.y).abs() < 1e-9);
        assert_eq!(spec.stop, Stop::Time(DEFAULT_DURATION));
        assert_eq!(spec.params, EngineParams::default());
        assert_eq!(spec.log, LogOptions::default());
        assert_eq!(spec.system.placement, Placement::Lattice);
        assert_eq!(spec.system.velocities, Velocities::MaxwellBoltzmann);
    }

    #[test]
    fn canonical_json_round_trips_to_the_same_run() {
        for text in [
            "{}",
            r#"{"box": {"size": [20, 10], "boundary": {"x": "periodic", "y": "walls"}}}"#,
            r#"{"collision": {"model": "normal", "coefficient": 0.8, "tc": 1e-6}, "stop": {"collisions": 1e6}}"#,
        ] {
            let a = Config::from_json_str(text).unwrap().to_run_spec().unwrap();
            let b = Config::from_json_str(&a.config_json)
                .unwrap()
                .to_run_spec()
                .unwrap();
            assert_eq!(a, b, "{text}");
        }
    }

    #[test]
    fn set_overrides_nested_fields_and_parses_values() {
        let sets: Vec<String> = [
            "species.0.count=500",
            "log.snapshot_interval=0.5",
            "collision.model=normal",
            "collision.coefficient=0.9",
            "placement=random",
            "box.packing_fraction=0.2",
            "log.thermo_interval=null",
            "species.1.count=20",
            "species.1.radius=0.7",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let c = Config::from_json_with_sets("{}", "test", &sets).unwrap();
        assert_eq!(c.species.len(), 2);
        assert_eq!(c.species[0].count, 500);
        assert_eq!(c.species[1].count, 20);
        assert_eq!(c.species[1].radius, 0.7);
        assert_eq!(c.species[1].mass, 1.0);
        assert_eq!(c.log.snapshot_interval, Some(0.5));
        assert_eq!(c.log.thermo_interval, None);
        assert_eq!(c.placement, PlacementConfig::Random);
        let spec = c.to_run_spec().unwrap();
        assert_eq!(spec.params.restitution, Restitution::Normal(0.9));
        // Explicit box size via --set on a config that had none.
        let c = Config::from_json_with_sets("{}", "t", &["box.size=[30,15]".to_owned()]).unwrap();
        assert_eq!(c.sim_box.size, Some([30.0, 15.0]));
    }

    #[test]
    fn set_errors_name_the_key() {
        assert!(matches!(err_of("{}", &["nokey"]), ConfigError::Set { .. }));
        assert!(matches!(
            err_of("{}", &["species.5.count=1"]),
            ConfigError::Set { .. }
        ));
        assert!(matches!(
            err_of("{}", &["species.x.count=1"]),
            ConfigError::Set { .. }
        ));
        assert!(matches!(
            err_of("{}", &["temperature.x=1"]),
            ConfigError::Set { .. }
        ));
        assert_eq!(field_of("{}", &["bogus=1"]), "bogus");
        assert_eq!(field_of("{}", &["log.bogus=1"]), "log.bogus");
        assert_eq!(field_of("{}", &["species.0.colour=1"]), "species.0.colour");
        assert_eq!(field_of("{}", &["temperature=hot"]), "temperature");
    }

    #[test]
    fn wrong_types_name_the_field() {
        let cases = [
            (r#"{"species": [{"count": "many"}]}"#, "species.0.count"),
            (
                r#"{"species": [{"count": 10, "radius": "big"}]}"#,
                "species.0.radius",
            ),
            (r#"{"species": [{"count": 1.5}]}"#, "species.0.count"),
            (r#"{"species": [{"count": -3}]}"#, "species.0.count"),
            (r#"{"species": {"count": 3}}"#, "species"),
            (r#"{"species": [{"radius": 0.5}]}"#, "species.0"),
            (r#"{"temperature": "warm"}"#, "temperature"),
            (r#"{"seed": -1}"#, "seed"),
            (r#"{"box": {"size": [1, 2, 3]}}"#, "box.size"),
            (r#"{"box": {"boundary": "sticky"}}"#, "box.boundary"),
            (r#"{"box": {"boundary": {"x": "walls"}}}"#, "box.boundary"),
            (
                r#"{"box": {"boundary": {"x": "walls", "y": "hole"}}}"#,
                "box.boundary.y",
            ),
            (r#"{"placement": "hexagonal"}"#, "placement"),
            (
                r#"{"placement": {"explicit": [[1, "a"]]}}"#,
                "placement.explicit.0.1",
            ),
            (r#"{"velocities": "fast"}"#, "velocities"),
            (r#"{"collision": {"model": "plastic"}}"#, "collision.model"),
            (r#"{"stop": {"duration": "long"}}"#, "stop.duration"),
            (r#"{"log": {"collisions": "yes"}}"#, "log.collisions"),
            (r#"{"log": {"compression": "gzip"}}"#, "log.compression"),
        ];
        for (text, field) in cases {
            assert_eq!(field_of(text, &[]), field, "{text}");
        }
        let e = err_of(r#"{"box": {"size": [1, 2, 3]}}"#, &[]).to_string();
        assert!(e.contains("exactly 2 numbers"), "{e}");
    }

    #[test]
    fn unknown_fields_are_named() {
        let cases = [
            (r#"{"speices": []}"#, "speices"),
            (r#"{"box": {"eta": 0.3}}"#, "box.eta"),
            (
                r#"{"species": [{"count": 1, "charge": 2}]}"#,
                "species.0.charge",
            ),
            (
                r#"{"collision": {"model": "normal", "e": 0.9}}"#,
                "collision.e",
            ),
            (r#"{"stop": {"time": 3}}"#, "stop.time"),
            (r#"{"log": {"snapshots": 3}}"#, "log.snapshots"),
            (
                r#"{"box": {"boundary": {"x": "walls", "y": "walls", "z": "walls"}}}"#,
                "box.boundary.z",
            ),
        ];
        for (text, field) in cases {
            let e = err_of(text, &[]);
            assert_eq!(e.field(), Some(field), "{text}: {e}");
            assert!(e.to_string().contains("unknown field"), "{e}");
        }
        // The message lists what is allowed.
        let e = err_of(r#"{"log": {"snapshots": 3}}"#, &[]).to_string();
        assert!(e.contains("snapshot_interval"), "{e}");
    }

    #[test]
    fn out_of_range_values_are_named() {
        let cases = [
            (r#"{"species": []}"#, "species"),
            (r#"{"species": [{"count": 0}]}"#, "species"),
            (
                r#"{"species": [{"count": 5, "radius": 0}]}"#,
                "species.0.radius",
            ),
            (
                r#"{"species": [{"count": 5}, {"count": 5, "mass": -1}]}"#,
                "species.1.mass",
            ),
            (r#"{"temperature": 1, "temperature": 2}"#, "temperature"),
            (
                r#"{"species": [{"count": 5, "radius": 0.5, "radius": 1}]}"#,
                "species.0.radius",
            ),
            // Boxes derived from η and the aspect: the setting that spoils them is
            // named, not the box.size nobody wrote.
            (r#"{"species": [{"count": 5, "radius": 1e200}]}"#, "species"),
            (
                r#"{"box": {"packing_fraction": 1e-320}}"#,
                "box.packing_fraction",
            ),
            (
                r#"{"species": [{"count": 4}], "box": {"aspect": 100}}"#,
                "box.aspect",
            ),
            (
                r#"{"box": {"packing_fraction": 0.95}}"#,
                "box.packing_fraction",
            ),
            (
                r#"{"box": {"packing_fraction": 0}}"#,
                "box.packing_fraction",
            ),
            (r#"{"box": {"aspect": 0}}"#, "box.aspect"),
            (
                r#"{"box": {"size": [10, 10], "packing_fraction": 0.3}}"#,
                "box.packing_fraction",
            ),
            (r#"{"box": {"size": [0.5, 10]}}"#, "box.size.0"),
            (
                r#"{"box": {"wall_restitution": 0.5}}"#,
                "box.wall_restitution",
            ),
            (
                r#"{"box": {"boundary": "walls", "wall_restitution": 1.5}}"#,
                "box.wall_restitution",
            ),
            (r#"{"temperature": 0}"#, "temperature"),
            (r#"{"temperature": -1}"#, "temperature"),
            (
                r#"{"collision": {"model": "normal"}}"#,
                "collision.coefficient",
            ),
            (
                r#"{"collision": {"model": "normal", "coefficient": 1.2}}"#,
                "collision.coefficient",
            ),
            (
                r#"{"collision": {"coefficient": 0.9}}"#,
                "collision.coefficient",
            ),
            (r#"{"collision": {"tc": -1}}"#, "collision.tc"),
            (
                r#"{"collision": {"max_events_without_time_advance": 0}}"#,
                "collision.max_events_without_time_advance",
            ),
            (r#"{"stop": {"duration": 1, "collisions": 5}}"#, "stop"),
            (r#"{"stop": {"duration": -1}}"#, "stop.duration"),
            (r#"{"stop": {"collisions": 0}}"#, "stop.collisions"),
            (
                r#"{"species": [{"count": 1}], "stop": {"collisions": 10}}"#,
                "stop.collisions",
            ),
            (r#"{"log": {"collision_every": 0}}"#, "log.collision_every"),
            (
                r#"{"log": {"snapshot_interval": 0}}"#,
                "log.snapshot_interval",
            ),
            (r#"{"log": {"flush_seconds": 0}}"#, "log.flush_seconds"),
            (
                r#"{"log": {"thermo_interval": 1e-17}}"#,
                "log.thermo_interval",
            ),
            (
                r#"{"stop": {"duration": 1e3}, "log": {"checkpoint_interval": 1e-7}}"#,
                "log.checkpoint_interval",
            ),
            (
                r#"{"species": [{"count": 2}], "placement": {"explicit": [[1, 1]]}}"#,
                "placement.explicit",
            ),
            (
                r#"{"species": [{"count": 1}], "velocities": {"explicit": []}}"#,
                "velocities.explicit",
            ),
            ("[1, 2]", "(top level)"),
        ];
        for (text, field) in cases {
            let e = err_of(text, &[]);
            assert_eq!(e.field(), Some(field), "{text}: {e}");
            assert!(e.to_string().contains("allowed"), "{e}");
        }
    }

    #[test]
    fn log_intervals_give_at_most_a_billion_records_per_run() {
        let ok = |text: &str| Config::from_json_str(text).unwrap().to_run_spec().unwrap();
        // 10⁹ snapshots over the run: allowed; one interval's width less: refused.
        ok(r#"{"stop": {"duration": 1000}, "log": {"snapshot_interval": 1e-6}}"#);
        let e = err_of(
            r#"{"stop": {"duration": 1000}, "log": {"snapshot_interval": 0.99e-6}}"#,
            &[],
        );
        assert_eq!(e.field(), Some("log.snapshot_interval"), "{e}");
        assert!(e.to_string().contains("1.0e9 records"), "{e}");
        // The default duration (50) counts too.
        let e = err_of(r#"{"log": {"thermo_interval": 1e-8}}"#, &[]);
        assert_eq!(e.field(), Some("log.thermo_interval"), "{e}");
        // A run stopped by its collision count has no known length: not checked.
        ok(r#"{"stop": {"collisions": 10}, "log": {"thermo_interval": 1e-17}}"#);
    }

    #[test]
    fn syntax_errors_give_line_and_column() {
        let e = err_of("{\n  \"seed\": 1,\n  oops\n}", &[]);
        match e {
            ConfigError::Syntax { line, .. } => assert_eq!(line, 3),
            other => panic!("{other}"),
        }
    }

    #[test]
    fn build_errors_map_to_config_fields() {
        // Overlapping explicit discs.
        let text = r#"{"species": [{"count": 2}], "box": {"size": [10, 10]},
            "placement": {"explicit": [[1, 1], [1.5, 1]]}}"#;
        let spec = Config::from_json_str(text).unwrap().to_run_spec().unwrap();
        let e = ConfigError::from_init(spec.system.build().unwrap_err());
        assert_eq!(e.field(), Some("placement.explicit"));
        assert!(e.to_string().contains("overlap"), "{e}");
        // A disc outside a walled box.
        let text = r#"{"species": [{"count": 2}], "box": {"size": [10, 10], "boundary": "walls"},
            "placement": {"explicit": [[1, 1], [0.2, 5]]}}"#;
        let spec = Config::from_json_str(text).unwrap().to_run_spec().unwrap();
        let e = ConfigError::from_init(spec.system.build().unwrap_err());
        assert_eq!(e.field(), Some("placement.explicit.1"), "{e}");
        // Random placement that cannot fit.
        let spec = Config::from_json_with_sets(
            "{}",
            "t",
            &[
                "placement=random".to_owned(),
                "box.packing_fraction=0.85".to_owned(),
                "species.0.count=200".to_owned(),
            ],
        )
        .unwrap()
        .to_run_spec()
        .unwrap();
        let e = ConfigError::from_init(spec.system.build().unwrap_err());
        assert_eq!(e.field(), Some("placement"), "{e}");
        // A lattice that does not fit is the packing fraction's fault, or the
        // box size's when the configuration gives that.
        let too_dense = |sets: &[&str]| {
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            let spec = Config::from_json_with_sets("{}", "t", &sets)
                .unwrap()
                .to_run_spec()
                .unwrap();
            ConfigError::from_init_in(spec.system.build().unwrap_err(), &spec.config_json)
        };
        let e = too_dense(&["species.0.count=7", "box.packing_fraction=0.72"]);
        assert_eq!(e.field(), Some("box.packing_fraction"), "{e}");
        let e = too_dense(&["species.0.count=1020", "box.size=[30, 30]"]);
        assert_eq!(e.field(), Some("box.size"), "{e}");
        assert_eq!(
            init_field_to_config("species[1].radius"),
            "species.1.radius"
        );
        assert_eq!(
            init_field_to_config("velocities[4]"),
            "velocities.explicit.4"
        );
    }

    fn example_paths() -> Vec<std::path::PathBuf> {
        let mut v: Vec<_> = std::fs::read_dir(data_dir())
            .expect("data/ exists")
            .map(|e| e.unwrap().path())
            .filter(|p| {
                p.extension().is_some_and(|e| e == "json")
                    && !p.to_string_lossy().ends_with(".schema.json")
            })
            .collect();
        v.sort();
        v
    }

    #[test]
    fn every_example_config_parses_and_builds() {
        let paths = example_paths();
        let names: BTreeSet<String> = paths
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        for required in [
            "dilute-gas.json",
            "dense-fluid.json",
            "binary-mixture.json",
            "granular-cooling.json",
            "channel.json",
        ] {
            assert!(names.contains(required), "data/{required} missing");
        }
        for p in &paths {
            let spec = load(Some(p), &[]).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            let state = spec
                .system
                .build()
                .unwrap_or_else(|e| panic!("{}: {}", p.display(), ConfigError::from_init(e)));
            assert_eq!(
                state.positions.len(),
                spec.system.species.iter().map(|s| s.count).sum::<usize>()
            );
        }
    }

    #[test]
    fn examples_are_what_their_names_say() {
        let get = |name: &str| load(Some(&data_dir().join(name)), &[]).unwrap();
        let eta = |s: &RunSpec| {
            s.system
                .species
                .iter()
                .map(|sp| sp.count as f64 * sp.disc_area())
                .sum::<f64>()
                / s.system.sim_box.area()
        };
        assert!((eta(&get("dense-fluid.json")) - 0.68).abs() < 1e-9);
        assert!(eta(&get("dilute-gas.json")) < 0.1);
        assert!(get("binary-mixture.json").system.species.len() >= 2);
        let glass = get("glass-mixture.json");
        assert!(glass.system.species.len() >= 2 && eta(&glass) > 0.75);
        assert_eq!(glass.system.placement, Placement::Relaxed);
        assert!(matches!(
            get("granular-cooling.json").params.restitution,
            Restitution::Normal(e) if e < 1.0
        ));
        let ch = get("channel.json").system.sim_box.boundary;
        assert!(ch[0].is_periodic() && !ch[1].is_periodic());
    }

    // ---- schema agreement ----

    /// Every object key path a JSON value contains (`*` for array elements).
    fn value_paths(v: &Value, prefix: &str, out: &mut BTreeSet<String>) {
        match v {
            Value::Object(m) => {
                for (k, x) in m {
                    let p = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    out.insert(p.clone());
                    value_paths(x, &p, out);
                }
            }
            Value::Array(a) => {
                for x in a {
                    value_paths(x, &format!("{prefix}.*"), out);
                }
            }
            _ => {}
        }
    }

    /// Every property path a JSON Schema declares, following `$ref`, `oneOf`,
    /// `anyOf` and `items`. Also checks that every object schema with properties
    /// forbids additional ones (as `deny_unknown_fields` does).
    fn schema_paths(schema: &Value, root: &Value, prefix: &str, out: &mut BTreeSet<String>) {
        if let Some(r) = schema.get("$ref").and_then(Value::as_str) {
            let ptr = r.strip_prefix('#').expect("local $ref");
            let target = root.pointer(ptr).unwrap_or_else(|| panic!("bad $ref {r}"));
            return schema_paths(target, root, prefix, out);
        }
        for key in ["oneOf", "anyOf", "allOf"] {
            if let Some(list) = schema.get(key).and_then(Value::as_array) {
                for s in list {
                    schema_paths(s, root, prefix, out);
                }
            }
        }
        if let Some(items) = schema.get("items") {
            schema_paths(items, root, &format!("{prefix}.*"), out);
        }
        if let Some(props) = schema.get("properties").and_then(Value::as_object) {
            assert_eq!(
                schema.get("additionalProperties"),
                Some(&Value::Bool(false)),
                "schema object at `{prefix}` must set additionalProperties: false"
            );
            for (k, s) in props {
                let p = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                out.insert(p.clone());
                schema_paths(s, root, &p, out);
            }
        }
    }

    fn load_schema() -> Value {
        let text = std::fs::read_to_string(data_dir().join("config.schema.json")).unwrap();
        serde_json::from_str(&text).unwrap()
    }

    /// A configuration in which every optional field is present (as far as fields
    /// can coexist in one value), serialised.
    fn maximal_values() -> Vec<Value> {
        let mut c = Config {
            schema: Some("x".into()),
            description: Some("x".into()),
            sim_box: BoxConfig {
                packing_fraction: Some(0.5),
                aspect: Some(1.0),
                size: Some([1.0, 1.0]),
                wall_restitution: Some(1.0),
                ..BoxConfig::default()
            },
            stop: StopConfig {
                duration: Some(1.0),
                collisions: Some(1),
            },
            ..Config::default()
        };
        c.collision.coefficient = Some(1.0);
        let mut d = c.clone();
        c.placement = PlacementConfig::Explicit(vec![[0.0, 0.0]]);
        c.velocities = VelocitiesConfig::Explicit(vec![[0.0, 0.0]]);
        d.sim_box.boundary = BoundaryConfig::PerAxis {
            x: AxisBoundary::Periodic,
            y: AxisBoundary::Walls,
        };
        vec![
            serde_json::to_value(c).unwrap(),
            serde_json::to_value(d).unwrap(),
        ]
    }

    #[test]
    fn schema_lists_exactly_the_fields_rust_accepts() {
        let schema = load_schema();
        let mut from_schema = BTreeSet::new();
        schema_paths(&schema, &schema, "", &mut from_schema);
        let mut from_rust = BTreeSet::new();
        for v in maximal_values() {
            value_paths(&v, "", &mut from_rust);
        }
        // Array elements that are numbers (positions, size) have no key paths.
        let missing: Vec<_> = from_rust.difference(&from_schema).collect();
        let extra: Vec<_> = from_schema.difference(&from_rust).collect();
        assert!(
            missing.is_empty(),
            "fields missing from the schema: {missing:?}"
        );
        assert!(extra.is_empty(), "schema fields Rust rejects: {extra:?}");
        // And Rust accepts each of them: the maximal values deserialise (only the
        // range checks would object).
        for v in maximal_values() {
            let _: Config = serde_json::from_value(v).unwrap();
        }
    }

    /// Every string the schema enumerates for a field is accepted by Rust there,
    /// and a string it does not list is rejected.
    #[test]
    fn schema_enums_match_rust_spellings() {
        fn enums(schema: &Value, root: &Value, prefix: &str, out: &mut Vec<(String, String)>) {
            if let Some(r) = schema.get("$ref").and_then(Value::as_str) {
                let target = root.pointer(r.strip_prefix('#').unwrap()).unwrap();
                return enums(target, root, prefix, out);
            }
            if let Some(list) = schema.get("enum").and_then(Value::as_array) {
                for s in list.iter().filter_map(Value::as_str) {
                    out.push((prefix.to_owned(), s.to_owned()));
                }
            }
            for key in ["oneOf", "anyOf"] {
                if let Some(list) = schema.get(key).and_then(Value::as_array) {
                    for s in list {
                        enums(s, root, prefix, out);
                    }
                }
            }
            if let Some(props) = schema.get("properties").and_then(Value::as_object) {
                for (k, s) in props {
                    let p = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    enums(s, root, &p, out);
                }
            }
        }
        let schema = load_schema();
        let mut list = Vec::new();
        enums(&schema, &schema, "", &mut list);
        assert!(list.len() >= 12, "{list:?}");
        for (path, s) in &list {
            let with = |value: &str| {
                let mut v = serde_json::json!({});
                // Per-axis boundaries need both axes.
                if let Some(parent) = path.strip_suffix(".x").or(path.strip_suffix(".y")) {
                    apply_set(&mut v, &format!("{parent}={{}}")).unwrap();
                    for axis in ["x", "y"] {
                        apply_set(&mut v, &format!("{parent}.{axis}=periodic")).unwrap();
                    }
                }
                apply_set(
                    &mut v,
                    &format!("{path}={}", Value::String(value.to_owned())),
                )
                .unwrap();
                serde_json::from_value::<Config>(v)
            };
            let r = with(s);
            assert!(
                r.is_ok(),
                "schema allows {path} = {s:?} but Rust says {r:?}"
            );
            let r = with(&format!("{s}-not"));
            assert!(r.is_err(), "{path} = {s}-not accepted");
        }
    }
}
