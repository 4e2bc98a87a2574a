//! The configuration as serde structs: every field with its unit, default and
//! allowed values in its doc, and the defaults. The same types, through
//! `#[derive(JsonSchema)]`, make `data/config.schema.json` (`schema`): a field's
//! doc comment is its description there, `#[serde(default)]` its default,
//! `deny_unknown_fields` its `additionalProperties: false`, and the simple
//! bounds (`#[schemars(range)]`, `exclusiveMinimum`) are written beside the
//! field. The checks themselves are in `validate`; the log's section in
//! `log_config`, the box's boundaries in `boundary`.

use super::boundary::BoundaryConfig;
use super::count::{de_count, de_opt_count};
use super::log_config::LogConfig;
use super::neighbours::NeighboursConfig;
use carom_engine::EngineParams;
use schemars::{JsonSchema, Schema};
use serde::{Deserialize, Serialize};

/// Hexagonal close packing π/(2√3), the largest packing fraction discs can reach.
pub(crate) const ETA_CLOSE_PACKED: f64 = 0.906_899_682_117_108_9;

/// Configuration of a carom run (exact event-driven MD of hard discs), as written
/// in a JSON file. Every field is optional; the defaults give a fluid of 10⁴ discs
/// at packing fraction 0.5 for 50 time units. Units are the user's: the reference
/// data use disc diameter 1, mass 1 and kT = 1. `carom run --set key=value`
/// overrides any field by its dotted path (`species.0.count`,
/// `log.snapshot_interval`).
///
/// data/config.schema.json is generated from these types (crates/config/src/model.rs):
/// `cargo run -p carom-config --example write_schema > data/config.schema.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(
    title = "carom run configuration",
    extend("$id" = "https://carom.invalid/config.schema.json")
)]
pub struct Config {
    /// URI of a JSON Schema for editors (`"./config.schema.json"` in data/);
    /// ignored by carom.
    #[serde(rename = "$schema", default, skip_serializing_if = "Option::is_none")]
    pub schema: Option<String>,
    /// Free text describing the run; stored in the log with the configuration.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// The kinds of disc. Default: one species of 10 000 discs, radius 0.5, mass 1.
    /// Discs are numbered species by species, in this order; at least one disc in
    /// total.
    #[serde(default = "default_species")]
    #[schemars(length(min = 1))]
    pub species: Vec<SpeciesConfig>,
    /// The box: its size and boundaries.
    #[serde(rename = "box", default)]
    pub sim_box: BoxConfig,
    /// Temperature kT (energy) of the initial velocities: after drawing, velocities
    /// are scaled so that 2K/f = kT exactly (physics.md §5). Default 1; allowed:
    /// finite, > 0, and at least two discs (drawn velocities have zero total
    /// momentum, which leaves a single disc at rest). Ignored for explicit velocities.
    #[serde(default = "one")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub temperature: f64,
    /// Seed of the random generator (placement and velocities). Default 0; any
    /// integer 0 ≤ seed < 2⁶⁴.
    #[serde(default)]
    #[schemars(extend("maximum" = u64::MAX))]
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
    /// collisions are logged in full (`log.collision_detail` `"compact"` is
    /// refused): compact records cannot replay velocities that change between
    /// collisions.
    #[serde(default, skip_serializing_if = "is_zero")]
    #[schemars(extend("minimum" = 0, "default" = 0))]
    pub gravity: f64,
    /// A thermostat acting on the velocities at exact random or regular times
    /// (physics.md §16). Default: none (constant energy, or cooling when
    /// inelastic). With a thermostat, collisions are logged in full
    /// (`log.collision_detail` `"compact"` is refused).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thermostat: Option<ThermostatConfig>,
    /// Compression as a run mode (Lubachevsky–Stillinger, physics.md §17): every
    /// radius grows as a⁰ (1 + γ t) until `target_packing_fraction`, or until the
    /// virial Z over a rescale interval exceeds `max_reduced_pressure` (jamming);
    /// the velocities are rescaled to `temperature` every `rescale_interval`; then
    /// the discs keep their size. Default: none. In a periodic or walled box; only
    /// with elastic collisions (and elastic walls, `box.wall_restitution` 1), no TC
    /// model, no gravity, no thermostat; collisions are logged in full.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub compression: Option<GrowthConfig>,
    /// A bottom wall that oscillates, h(t) = A (1 − cos 2π f t) (physics.md §18):
    /// it drives a granular bed. Its bounces reverse the velocity relative to the
    /// floor with the wall restitution. Default: none. Only with hard walls along
    /// y, not with compression; collisions are then logged in full.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vibrating_floor: Option<FloorConfig>,
    /// How the engine finds the discs a disc may meet next: `"auto"` (default),
    /// `"cells"` (the cell grid: a disc looks at the 3 × 3 cells around its own)
    /// or `"lists"` (neighbour lists with a skin: a disc looks at the discs listed
    /// near it; fastest for dense fluids and crystals). Both give the same events
    /// up to rounding, and both are exact. `"auto"` chooses lists for dense equal
    /// discs flying straight (no gravity, compression or vibrating floor) from
    /// packing fraction 0.66 (`carom_engine::LISTS_FROM_PACKING`), cells otherwise.
    /// The choice never depends on timing, so a configuration and a seed give one
    /// trajectory. `"lists"` is refused with gravity, compression or a vibrating
    /// floor, and for a mixture that needs a cell grid per size class or a
    /// periodic box less than about 5.1 largest diameters wide.
    #[serde(default, skip_serializing_if = "NeighboursConfig::is_auto")]
    #[schemars(extend("default" = "auto"))]
    pub neighbours: NeighboursConfig,
}

/// The vibrating floor (`vibrating_floor`; physics.md §18).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FloorConfig {
    /// Amplitude A (length): the floor moves between 0 and 2A. Required; allowed:
    /// finite, > 0, with 2A plus the largest diameter at most half the box height.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub amplitude: f64,
    /// Frequency f (1/time): ω = 2π f. Required; allowed: finite, > 0.
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub frequency: f64,
}

/// Compression during a run (`compression`; physics.md §17).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GrowthConfig {
    /// Relative growth rate γ (1/time): every radius a(t) = a⁰ (1 + γ t). Required;
    /// allowed: finite, > 0. Slow (near equilibrium) when γ·(largest diameter) ≪
    /// √(kT/m).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub rate: f64,
    /// Packing fraction at which growth stops. Required; allowed: at or above the
    /// start's, below 0.9069 (hexagonal close packing).
    #[schemars(extend("exclusiveMinimum" = 0, "exclusiveMaximum" = ETA_CLOSE_PACKED))]
    pub target_packing_fraction: f64,
    /// Time between two rescales of the velocities to `temperature` (time).
    /// Default 1; allowed: finite, > 0.
    #[serde(default = "one")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub rescale_interval: f64,
    /// Jamming bound: growth stops at a rescale where the virial Z = βPA/N over the
    /// interval just ended exceeds it (physics.md (17.7)). Default 1000; allowed: > 1.
    #[serde(default = "default_max_reduced_pressure")]
    #[schemars(extend("exclusiveMinimum" = 1))]
    pub max_reduced_pressure: f64,
}

fn default_max_reduced_pressure() -> f64 {
    1e3
}

/// Compressed placement (`{"compressed": {...}}`; physics.md §17).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CompressedPlacementConfig {
    /// Relative growth rate γ (1/time): radii a⁰ (1 + γ t). Default 0.01; allowed:
    /// finite, > 0.
    #[serde(default = "default_growth_rate")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub rate: f64,
    /// Packing fraction of the random start. Default 0.3 (or the box's own, if
    /// lower); allowed: 0 < start ≤ the box's packing fraction, and low enough for
    /// random placement (about 0.4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub start_packing_fraction: Option<f64>,
}

fn default_growth_rate() -> f64 {
    0.01
}

/// A thermostat, by its `kind`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ThermostatConfig {
    /// `{"kind": "andersen", "kT": 2, "rate": 0.1}`: each disc's velocity is
    /// redrawn from Maxwell–Boltzmann at `kT` at the events of a Poisson process of
    /// `rate` per disc (physics.md §16.1).
    Andersen {
        /// Target temperature kT (energy). Required; allowed: finite, > 0.
        #[serde(rename = "kT")]
        #[schemars(extend("exclusiveMinimum" = 0))]
        kt: f64,
        /// Redraws per disc and unit time ν (1/time). Required; allowed: finite, > 0.
        #[schemars(extend("exclusiveMinimum" = 0))]
        rate: f64,
    },
    /// `{"kind": "driven", "xi2": 0.01, "interval": 0.01}`: stochastic driving
    /// (van Noije & Ernst): every `interval` each disc gets a Gaussian velocity
    /// kick of variance `xi2 · interval` per component, with the kicks' total
    /// momentum removed (physics.md §16.2).
    Driven {
        /// Driving strength ξ² (length²/time³): velocity variance added per
        /// component and unit time. Required; allowed: finite, > 0.
        #[schemars(extend("exclusiveMinimum" = 0))]
        xi2: f64,
        /// Time between kicks Δt (time). Required; allowed: finite, > 0, and small
        /// against the mean free time for the steady state of §16.2.
        #[schemars(extend("exclusiveMinimum" = 0))]
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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SpeciesConfig {
    /// Number of discs (required). Integer ≥ 0 (`1e4` is accepted); the total over
    /// all species must be ≥ 1.
    #[serde(deserialize_with = "de_count")]
    pub count: u64,
    /// Disc radius a (length). Default 0.5 (diameter σ = 1); allowed: finite, > 0.
    #[serde(default = "half")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub radius: f64,
    /// Disc mass m (mass). Default 1; allowed: finite, > 0.
    #[serde(default = "one")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub mass: f64,
}

/// The simulation box [0, L_x) × [0, L_y). Its size comes either from
/// `packing_fraction` and `aspect` (the default: η = 0.5, aspect 1) or from an
/// explicit `size`; not both. Default boundaries: periodic.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(extend("not" = {"required": ["size", "packing_fraction"]}))]
pub struct BoxConfig {
    /// Packing fraction η = Σ N_s π a_s² / (L_x L_y) (dimensionless). Default 0.5
    /// when `size` is not given; allowed: 0 < η < 0.9069 (close packing). Lattice
    /// placement reaches at least 0.72 and up to the densest lattice that fits the
    /// box, random placement only low densities (η ≲ 0.4), relaxed placement about 0.8.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0, "exclusiveMaximum" = ETA_CLOSE_PACKED))]
    pub packing_fraction: Option<f64>,
    /// Aspect ratio L_x / L_y (dimensionless), with `packing_fraction`. Default 1;
    /// allowed: 0.01 ≤ aspect ≤ 100.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0.01, max = 100))]
    pub aspect: Option<f64>,
    /// Explicit edge lengths `[L_x, L_y]` (length), instead of `packing_fraction`
    /// and `aspect`. Each finite and longer than the largest disc diameter.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<[f64; 2]>,
    /// Boundary conditions: `"periodic"` (default), `"walls"`, or per axis
    /// `{"x": "periodic", "y": "walls"}` (a channel).
    #[serde(default)]
    pub boundary: BoundaryConfig,
    /// Restitution e_w of the hard walls (dimensionless): a disc leaves a wall with
    /// its normal velocity times −e_w. Default 1 (elastic); allowed 0 ≤ e_w ≤ 1.
    /// Only with walls on at least one axis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0, max = 1))]
    pub wall_restitution: Option<f64>,
}

/// Where the discs start.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum PlacementConfig {
    /// `"lattice"`: the best-fitting square or triangular lattice (any η ≤ 0.72 from
    /// 34 discs on at aspect 1/4–4, denser up to the densest lattice that fits the
    /// box, and for fewer discs wherever a lattice fits, else try `"relaxed"`; a
    /// mixture's sites are spaced for its largest disc).
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
    /// engine (Lubachevsky–Stillinger, physics.md §17), velocities rescaled to
    /// `temperature` on the way: a crystal when slow (monodisperse discs above
    /// η = 0.72), a disordered packing when fast. Refused, with the packing
    /// fraction reached, if the discs jam first (Z > 10⁴).
    Compressed(CompressedPlacementConfig),
}

/// How the initial velocities are chosen.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum VelocitiesConfig {
    /// `"maxwell-boltzmann"`: Gaussian components of variance kT/m, zero total
    /// momentum, scaled to 2K/f = kT (physics.md §6).
    #[default]
    MaxwellBoltzmann,
    /// `"equal-speed"`: all discs of a species at one speed, random directions, with
    /// 2K/f = kT — a deliberately non-equilibrium start.
    EqualSpeed,
    /// `{"explicit": [[vx, vy], ...]}`: one velocity per disc (length/time), in the
    /// order of the species.
    Explicit(Vec<[f64; 2]>),
}

/// The pair collision rule (physics.md §3–4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum CollisionModel {
    /// `"elastic"`: elastic collisions (physics.md §3); `coefficient` must be
    /// absent or 1.
    #[default]
    Elastic,
    /// `"normal"`: normal restitution e, u' = −e u (physics.md §4b, granular
    /// convention).
    Normal,
    /// `"centre-of-mass"` (also spelt `"center-of-mass"`): the seed's restitution R
    /// about the centre-of-mass velocity (physics.md §4a).
    #[serde(alias = "center-of-mass")]
    #[schemars(transform = centre_of_mass_spellings)]
    CentreOfMass,
}

/// The schema of `"centre-of-mass"` also admits serde's alias (schemars lists
/// only the primary name).
fn centre_of_mass_spellings(schema: &mut Schema) {
    schema.remove("const");
    schema.insert(
        "enum".into(),
        serde_json::json!(["centre-of-mass", "center-of-mass"]),
    );
}

/// The pair collision rule (physics.md §3–4) and the inelastic-collapse safeguards.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
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
    #[schemars(range(min = 0, max = 1))]
    pub coefficient: Option<f64>,
    /// TC model duration t_c (time, physics.md §4): a collision is elastic when
    /// either disc collided less than t_c ago, and so is a wall collision of a disc
    /// that collided (with a disc or a wall) less than t_c ago. Default 0 (off);
    /// allowed: finite, ≥ 0, and much shorter than the mean free time.
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub tc: f64,
    /// Collisions allowed at one instant before the engine stops with a runaway
    /// (inelastic collapse) error instead of hanging. Default 100 000; integer ≥ 1.
    #[serde(default = "default_max_events", deserialize_with = "de_count")]
    #[schemars(range(min = 1))]
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

/// When the run ends: exactly one of `duration` and `collisions` (default
/// `{"duration": 50}`), and the watchdog `max_time_without_collision`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(extend("not" = {"required": ["duration", "collisions"]}))]
pub struct StopConfig {
    /// Simulated time to run for (time). Default 50 when `collisions` is not
    /// given; allowed: finite, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub duration: Option<f64>,
    /// Number of collisions (pair + wall) to run for, instead of `duration`.
    /// Integer ≥ 1 (`1e9` is accepted); refused when no disc can ever collide
    /// (one disc in a periodic box, every explicit velocity [0, 0]).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "de_opt_count"
    )]
    #[schemars(with = "u64", range(min = 1))]
    pub collisions: Option<u64>,
    /// The longest stretch of simulated time without any collision before the run
    /// stops with an error (time), for either stop. Absent: with a collision stop,
    /// 100 mean free times expected from the density and the current temperature
    /// (physics.md (7.10)); with a time stop, no bound. Allowed: finite, > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub max_time_without_collision: Option<f64>,
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
fn default_max_events() -> u64 {
    EngineParams::default().max_events_without_time_advance
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
            neighbours: NeighboursConfig::Auto,
        }
    }
}

/// Whether `x` is 0 (a field left out of the stored configuration).
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}
