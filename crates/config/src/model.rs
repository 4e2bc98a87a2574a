//! The configuration as serde structs: every field with its unit, default and
//! allowed values in its doc, the defaults, and the count parser that accepts
//! `1e9`. `data/config.schema.json` lists the same fields (a test checks it).

use carom_engine::EngineParams;
use carom_log::{Compression, LogOptions};
use serde::{Deserialize, Deserializer, Serialize};

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
    /// Uniform gravity g along −y (length/time²; physics.md §15): every disc falls,
    /// y(t) = y + u t − g t²/2, and the potential energy m g y counts in the
    /// energy. Default 0 (none); allowed: finite, ≥ 0, and > 0 only with hard walls
    /// along y (`box.boundary` `"walls"` or `{"x": …, "y": "walls"}`). With a field,
    /// collisions are logged in full (`log.collision_detail` `"full"`): compact
    /// records cannot replay velocities that change between collisions.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub gravity: f64,
    /// A thermostat acting on the velocities at exact random or regular times
    /// (physics.md §16). Default: none (constant energy, or cooling when inelastic).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermostat: Option<ThermostatConfig>,
    /// Compression as a run mode (physics.md §17): the discs grow during the run
    /// until a target packing fraction or jamming, then keep their size. Default:
    /// none. Only with elastic collisions and walls, no TC model and no gravity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compression: Option<GrowthConfig>,
    /// A bottom wall that oscillates, h(t) = A (1 − cos 2π f t) (physics.md §18):
    /// it drives a granular bed. Default: none. Only with hard walls along y, not
    /// with compression; collisions are then logged in full.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vibrating_floor: Option<FloorConfig>,
}

/// The vibrating floor (`vibrating_floor`; physics.md §18).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FloorConfig {
    /// Amplitude A (length): the floor moves between 0 and 2A. Allowed: finite,
    /// > 0, with 2A plus the largest diameter at most half the box height.
    pub amplitude: f64,
    /// Frequency f (1/time): ω = 2π f. Allowed: finite, > 0.
    pub frequency: f64,
}

/// Compression during a run (`compression`; physics.md §17).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GrowthConfig {
    /// Relative growth rate γ (1/time): every radius a(t) = a⁰ (1 + γ t). Allowed:
    /// finite, > 0. Slow (near equilibrium) when γ·(largest diameter) ≪ √(kT/m).
    pub rate: f64,
    /// Packing fraction at which growth stops. Allowed: above the start's, below
    /// 0.9069 (hexagonal close packing).
    pub target_packing_fraction: f64,
    /// Time between two rescales of the velocities to `temperature` (time).
    /// Default 1; allowed: finite, > 0.
    #[serde(default = "one")]
    pub rescale_interval: f64,
    /// Jamming bound: growth stops at a rescale where the virial Z = βPA/N over the
    /// interval just ended exceeds it (physics.md (17.7)). Default 1000; allowed: > 1.
    #[serde(default = "default_max_reduced_pressure")]
    pub max_reduced_pressure: f64,
}

fn default_max_reduced_pressure() -> f64 {
    1e3
}

/// Compressed placement (`{"compressed": {...}}`; physics.md §17).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompressedPlacementConfig {
    /// Relative growth rate γ (1/time). Default 0.01; allowed: finite, > 0.
    #[serde(default = "default_growth_rate")]
    pub rate: f64,
    /// Packing fraction of the random start. Default 0.3 (or the box's own, if
    /// lower); allowed: 0 < start ≤ the box's packing fraction, and low enough for
    /// random placement (about 0.4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start_packing_fraction: Option<f64>,
}

fn default_growth_rate() -> f64 {
    0.01
}

/// A thermostat, by its `kind`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ThermostatConfig {
    /// `{"kind": "andersen", "kT": 2, "rate": 0.1}`: each disc's velocity is
    /// redrawn from Maxwell–Boltzmann at `kT` at the events of a Poisson process of
    /// `rate` per disc (physics.md §16.1).
    Andersen {
        /// Target temperature kT (energy); allowed: finite, > 0.
        #[serde(rename = "kT")]
        kt: f64,
        /// Redraws per disc and unit time ν (1/time); allowed: finite, > 0.
        rate: f64,
    },
    /// `{"kind": "driven", "xi2": 0.01, "interval": 0.01}`: every `interval` each
    /// disc gets a Gaussian velocity kick of variance `xi2 · interval` per component,
    /// with the kicks' total momentum removed (physics.md §16.2).
    Driven {
        /// Driving strength ξ² (length²/time³); allowed: finite, > 0.
        xi2: f64,
        /// Time between kicks Δt (time); allowed: finite, > 0, and small against the
        /// mean free time for the steady state of §16.2.
        interval: f64,
    },
}

impl ThermostatConfig {
    /// The engine's thermostat.
    pub fn thermostat(&self) -> carom_engine::Thermostat {
        match *self {
            ThermostatConfig::Andersen { kt, rate } => {
                carom_engine::Thermostat::Andersen { kt, rate }
            }
            ThermostatConfig::Driven { xi2, interval } => {
                carom_engine::Thermostat::Driven { xi2, interval }
            }
        }
    }
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
    /// placement reaches at least 0.72 and up to the densest lattice that fits the
    /// box, random placement only low densities (η ≲ 0.4), relaxed placement about 0.8.
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
    /// 34 discs on, denser up to the densest lattice that fits the box, and for
    /// fewer discs wherever a lattice fits; a mixture's sites are spaced for its
    /// largest disc).
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
    /// `{"compressed": {"rate": γ, "start_packing_fraction": η₀}}`: random at η₀,
    /// then compressed to the box's packing fraction by growing the discs in the
    /// engine (Lubachevsky–Stillinger, physics.md §17): a crystal when slow, a
    /// disordered packing when fast, up to just below jamming.
    Compressed(CompressedPlacementConfig),
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

/// When the run ends: exactly one of `duration` and `collisions`, and the watchdog
/// `max_time_without_collision`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopConfig {
    /// Simulated time to run for (time). Default 50 when `collisions` is not
    /// given; allowed: finite, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub duration: Option<f64>,
    /// Number of collisions (pair + wall) to run for, instead of `duration`.
    /// Integer ≥ 1 (`1e9` is accepted); refused when no disc can ever collide
    /// (one disc in a periodic box, every explicit velocity [0, 0]).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "de_opt_count"
    )]
    pub collisions: Option<u64>,
    /// The longest stretch of simulated time without any collision before the run
    /// stops with an error (time), for either stop. Absent: with a collision stop,
    /// 100 mean free times expected from the density and the current temperature
    /// (physics.md (7.10)); with a time stop, no bound. Allowed: finite, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_time_without_collision: Option<f64>,
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

/// What `/collisions` stores per collision (maps to [`carom_log::CollisionDetail`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CollisionDetailConfig {
    /// Time, discs and impulse; velocities replayed from snapshots (the default
    /// with `collision_every` = 1).
    Compact,
    /// Velocities before and after, normal, energy lost and virial (the default,
    /// and the only record, with `collision_every` > 1).
    Full,
}

/// `log.snapshot_schedule`: n snapshots inside every block of length T =
/// `log.snapshot_interval`, at offsets δ·(T/δ)^((j−1)/n), j = 1..n, from the block
/// start (maps to [`carom_log::SchedulePoints`]; the times: [`carom_log::SnapshotSchedule`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SnapshotScheduleConfig {
    /// n: snapshots added per block. Required; integer 1 ≤ n ≤ 1000.
    #[serde(deserialize_with = "de_count")]
    pub points: u64,
    /// δ: offset of the first from the block start (time). Required; finite,
    /// 10⁻⁶·T ≤ δ < T.
    pub first: f64,
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
    /// What each logged collision stores: `"compact"` (time, discs, impulse) or
    /// `"full"` (velocities before and after, normal, energy lost, virial).
    /// Default `"compact"`, or `"full"` when `collision_every` > 1 (compact
    /// records replay velocities only from every collision: `"compact"` with
    /// `collision_every` > 1 is refused).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub collision_detail: Option<CollisionDetailConfig>,
    /// Simulated time between `/snapshot` messages (time). Default 1; `null` for no
    /// snapshots; otherwise finite, > 0, and at least `stop.duration` /
    /// [`MAX_RECORDS`](carom_log::MAX_RECORDS).
    #[serde(default = "default_snapshot")]
    pub snapshot_interval: Option<f64>,
    /// Log-spaced snapshots added inside every `snapshot_interval`, for
    /// mean-square displacements and correlations over many decades of lag time.
    /// Default none; needs a `snapshot_interval`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub snapshot_schedule: Option<SnapshotScheduleConfig>,
    /// Simulated time between `/thermo` messages (time). Default 0.1; `null` for
    /// none; otherwise finite, > 0, and at least `stop.duration` / [`MAX_RECORDS`](carom_log::MAX_RECORDS).
    #[serde(default = "default_thermo")]
    pub thermo_interval: Option<f64>,
    /// Simulated time between `/checkpoint` messages (time). Default 10; `null` for
    /// a checkpoint at the end only; otherwise finite, > 0, and at least
    /// `stop.duration` / [`MAX_RECORDS`](carom_log::MAX_RECORDS).
    #[serde(default = "default_checkpoint")]
    pub checkpoint_interval: Option<f64>,
    /// Simulated time between `/scene` frames for Foxglove's 3D panel (time).
    /// Default `null` (none); otherwise finite, > 0, and at least `stop.duration`
    /// / [`MAX_RECORDS`](carom_log::MAX_RECORDS).
    #[serde(default)]
    pub scene_interval: Option<f64>,
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

/// Default run length in simulated time: at η = 0.5, N = 10⁴ there are about
/// 3.5 × 10⁴ collisions per unit time, so 50 time units are ~1.75 × 10⁶ collisions,
/// a few seconds at ~10⁶ collisions/s.
pub const DEFAULT_DURATION: f64 = 50.0;

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
            gravity: 0.0,
            thermostat: None,
            compression: None,
            vibrating_floor: None,
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

/// Whether `x` is 0 (a field left out of the stored configuration).
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}
