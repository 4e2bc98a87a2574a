//! What a run did besides moving and colliding its discs, which some sections
//! of the report need and its events do not say: its thermostat (with the pair
//! rule it works against, physics.md §16), how its discs grew (read from the
//! log before the analysis, §17), and its vibrating floor with the engine's
//! energy totals at the checkpoints (§18). [`Analyzer::finish_with`] takes
//! them; each becomes an input of the sections it changes (a thermostat or a
//! floor voids the energy budget and Haff's law, a thermostat the replayed
//! transport, a floor the barometric law's known value), not a later edit.

use carom_core::vibrating_wall::Floor;
use carom_core::Restitution;
use carom_log::Thermostat;

use super::compression::CompressionReport;
#[cfg(doc)]
use super::Analyzer;

/// A run's thermostat, compression and floor; the default: none of them.
#[derive(Debug, Clone, Default)]
pub struct RunDynamics {
    /// The thermostat and the pair collision rule of the run.
    pub thermostat: Option<(Thermostat, Restitution)>,
    /// How the discs grew (a compression run).
    pub compression: Option<CompressionReport>,
    /// The vibrating floor.
    pub floor: Option<FloorRun>,
}

/// A vibrating floor and the energy it put in.
#[derive(Debug, Clone)]
pub struct FloorRun {
    /// The floor's motion.
    pub floor: Floor,
    /// The field g (length/time²).
    pub gravity: f64,
    /// (time, work the floor did, energy dissipated) of each checkpoint: the
    /// engine's running totals.
    pub totals: Vec<(f64, f64, f64)>,
}
