//! The `/thermo` channel: running thermodynamics as JSON, with the JSON Schema
//! [`THERMO_JSON_SCHEMA`].

use serde::{Deserialize, Serialize};

/// JSON Schema `carom.Thermo` of the `/thermo` records.
pub const THERMO_JSON_SCHEMA: &str = r#"{
  "$schema": "https://json-schema.org/draft/2020-12/schema",
  "title": "carom.Thermo",
  "description": "Thermodynamics of a carom run at one simulated time. Running quantities average over the run so far (from run_start_time). A value that is not finite (a run that broke down) is the string NaN, Infinity or -Infinity.",
  "type": "object",
  "properties": {
    "time": {"type": "number", "description": "simulated time (time)"},
    "kinetic_energy": {"type": "number", "description": "K = sum m v^2 / 2 (energy)"},
    "temperature": {"type": "number", "description": "kT = 2K/f with f = 2N - (periodic axes) (energy)"},
    "collisions": {"type": "integer", "description": "pair + wall collisions since the start of the run"},
    "pair_collisions": {"type": "integer", "description": "pair collisions since the start of the run"},
    "wall_collisions": {"type": "integer", "description": "wall collisions since the start of the run"},
    "energy_lost": {"type": "number", "description": "kinetic energy dissipated since the start of the run (energy)"},
    "virial_sum": {"type": "number", "description": "sum over pair collisions of r_ij . dp_i since the start of the run (length*momentum)"},
    "wall_impulse": {"type": "number", "description": "momentum given to all walls since the start of the run (momentum)"},
    "pressure": {"type": "number", "description": "running pressure estimate P (energy/length^2) over the run so far (t = time - run start); periodic box: P A = N kT + W with W = virial_sum/(2 t); walls: P = z N kT / A with A = N / sum_s (N_s / A_s), A_s the area the centres of species s reach (physics.md (5.8)); absent while t = 0 or kT = 0"},
    "z": {"type": "number", "description": "running compressibility factor beta P A / N (periodic: 1 + W/(N kT)); with walls J / (2 t kT sum over walled axes k and species s of N_s / (L_k - 2 a_s)), J the impulse on all walls, exact for mixtures (physics.md (5.8)); absent like pressure"},
    "collision_rate": {"type": "number", "description": "pair collisions per disc per unit time over the run so far, 2 N_pair / (N t) (1/time); absent while t = 0"},
    "potential_energy": {"type": "number", "description": "runs in a field only: U = sum m g y (energy; physics.md section 15); log format 2.2 on"},
    "total_energy": {"type": "number", "description": "runs in a field only: K + U (energy); log format 2.2 on"},
    "radius_scale": {"type": "number", "description": "runs with growing discs only: radii now / configured radii (physics.md section 17); log format 2.2 on"},
    "packing_fraction": {"type": "number", "description": "runs with growing discs only: packing fraction of the radii now; log format 2.2 on"},
    "growth": {"type": "string", "enum": ["growing", "target", "jammed"], "description": "runs with growing discs only: growing, or why growth ended; log format 2.2 on"},
    "growth_z": {"type": "number", "description": "runs with growing discs only: virial Z over the last interval between rescales (0 before the first); log format 2.2 on"},
    "growth_event": {"type": "string", "enum": ["rescale", "end"], "description": "only in the extra record written at the first event after a velocity rescale (rescale) or the end of growth (end); log format 2.2 on"}
  },
  "required": ["time", "kinetic_energy", "temperature", "collisions", "pair_collisions", "wall_collisions", "energy_lost", "virial_sum", "wall_impulse"]
}"#;

/// A `/thermo` record (JSON, schema [`THERMO_JSON_SCHEMA`]). Running quantities
/// average over the run so far, from its start time. A non-finite value is the
/// string `"NaN"`, `"Infinity"` or `"-Infinity"` (the log's rule for numbers,
/// `super::number`).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Thermo {
    /// Simulated time (time).
    #[serde(with = "super::number::float")]
    pub time: f64,
    /// K = Σ m v²/2 (energy).
    #[serde(with = "super::number::float")]
    pub kinetic_energy: f64,
    /// kT = 2K/f, f = 2N − (periodic axes) (energy; physics.md §5).
    #[serde(with = "super::number::float")]
    pub temperature: f64,
    /// Pair + wall collisions since the start of the run.
    pub collisions: u64,
    /// Pair collisions since the start of the run.
    pub pair_collisions: u64,
    /// Wall collisions since the start of the run.
    pub wall_collisions: u64,
    /// Kinetic energy dissipated since the start (energy).
    #[serde(with = "super::number::float")]
    pub energy_lost: f64,
    /// Σ r_ij·Δp_i over pair collisions since the start (length·momentum).
    #[serde(with = "super::number::float")]
    pub virial_sum: f64,
    /// Momentum given to all walls since the start (momentum).
    #[serde(with = "super::number::float")]
    pub wall_impulse: f64,
    /// Running pressure estimate P (energy/length²), see [`THERMO_JSON_SCHEMA`];
    /// absent (`None`) while no simulated time has passed or kT = 0.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "super::number::opt_float"
    )]
    pub pressure: Option<f64>,
    /// Running compressibility factor βPA/N (dimensionless); absent like `pressure`.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "super::number::opt_float"
    )]
    pub z: Option<f64>,
    /// Pair collisions per disc per unit time, 2 N_pair/(N t) (1/time); absent
    /// while no simulated time has passed.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "super::number::opt_float"
    )]
    pub collision_rate: Option<f64>,
    /// Runs in a field only: potential energy U = Σ m g y (energy; physics.md §15).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "super::number::opt_float"
    )]
    pub potential_energy: Option<f64>,
    /// Runs in a field only: K + U (energy).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "super::number::opt_float"
    )]
    pub total_energy: Option<f64>,
    /// Runs with growing discs only: radii now / configured radii (physics.md §17).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "super::number::opt_float"
    )]
    pub radius_scale: Option<f64>,
    /// Runs with growing discs only: the packing fraction of the radii now.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "super::number::opt_float"
    )]
    pub packing_fraction: Option<f64>,
    /// Runs with growing discs only: growing, or why growth ended.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub growth: Option<GrowthPhase>,
    /// Runs with growing discs only: the virial Z over the last interval between
    /// rescales (0 before the first).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        with = "super::number::opt_float"
    )]
    pub growth_z: Option<f64>,
    /// Set only in the extra record written at the first event after a rescale
    /// or after the end of growth.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub growth_event: Option<GrowthEvent>,
}

/// Whether discs grow, or why they stopped (`/thermo` field `growth`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GrowthPhase {
    /// Still growing.
    Growing,
    /// Growth ended at the target packing fraction.
    Target,
    /// Growth ended because Z over an interval exceeded the jamming bound.
    Jammed,
}

/// What the extra `/thermo` record of a growth instant marks (field `growth_event`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GrowthEvent {
    /// The velocities were rescaled to the target kT.
    Rescale,
    /// Growth ended (the record's `growth` says why).
    End,
}

impl Thermo {
    /// Decode a `/thermo` message (JSON).
    pub fn decode(data: &[u8]) -> Result<Thermo, serde_json::Error> {
        serde_json::from_slice(data)
    }
}
