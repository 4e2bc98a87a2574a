//! Errors of the initial-state builder and of the engine.

use thiserror::Error;

/// A request for an initial state that cannot be met. Every variant names the field
/// that is wrong, what was wrong with it and what is allowed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum InitError {
    /// A field has a value outside what is allowed.
    #[error("{field}: {problem} (allowed: {allowed})")]
    Invalid {
        /// Dotted path of the offending field, e.g. `species[1].radius`.
        field: String,
        /// What was wrong with the value.
        problem: String,
        /// What values are allowed.
        allowed: String,
    },
    /// Two discs of an explicit configuration overlap.
    #[error(
        "positions: discs {i} and {j} overlap (centre distance {distance} < contact distance {sigma}) \
         (allowed: centre distance ≥ sum of radii)"
    )]
    Overlap {
        /// First disc index.
        i: usize,
        /// Second disc index.
        j: usize,
        /// Minimum-image distance of their centres (length).
        distance: f64,
        /// Sum of their radii (length).
        sigma: f64,
    },
}

impl InitError {
    /// Shorthand for [`InitError::Invalid`].
    pub fn invalid(
        field: impl Into<String>,
        problem: impl Into<String>,
        allowed: impl Into<String>,
    ) -> Self {
        InitError::Invalid {
            field: field.into(),
            problem: problem.into(),
            allowed: allowed.into(),
        }
    }
}

/// A failure of the running engine.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EngineError {
    /// Too many collisions happened at one instant: an inelastic collapse
    /// (physics.md §4) or a degenerate configuration.
    #[error(
        "runaway: {events} collisions at time {time} without time advancing \
         (limit max_events_without_time_advance = {limit}); {}",
        stall_cause(*.dissipative)
    )]
    Stalled {
        /// Simulation time at which the clock stopped (time).
        time: f64,
        /// Collisions processed at that time.
        events: u64,
        /// The configured limit.
        limit: u64,
        /// Whether the collisions dissipate energy (an inelastic rule without the
        /// TC model): then the runaway is an inelastic collapse; otherwise discs
        /// started, or were put, in contact in a way that never resolves.
        dissipative: bool,
    },
    /// A caller asked for an observation before the current time.
    #[error("scheduled time {time} is before the current simulation time {now} (allowed: ≥ now, finite)")]
    ScheduleInPast {
        /// The requested time.
        time: f64,
        /// The engine's current time.
        now: f64,
    },
    /// A checkpoint could not be restored.
    #[error("checkpoint: {0}")]
    BadCheckpoint(String),
    /// A gravity the engine cannot run (physics.md §15).
    #[error(
        "gravity: {0} (allowed: finite g ≥ 0, and g > 0 only with hard walls along y: \
         box.boundary {{\"x\": …, \"y\": \"walls\"}} or \"walls\")"
    )]
    BadGravity(String),
    /// A thermostat with a bad parameter, or a caller's use of its reserved tag.
    #[error("{0}")]
    BadThermostat(String),
    /// Growing discs (compression) with parameters out of range or with dynamics
    /// they do not support.
    #[error("compression: {0}")]
    BadGrowth(String),
    /// A vibrating floor with parameters out of range or with dynamics it does not
    /// support (physics.md §18).
    #[error("vibrating_floor: {0}")]
    BadFloor(String),
    /// Neighbour lists were asked for (`neighbours: "lists"`) where the engine
    /// cannot use them; the text says why.
    #[error("neighbours: \"lists\" cannot be used {0} (allowed: \"auto\" or \"cells\")")]
    ListsRefused(String),
}

/// What a runaway of [`EngineError::Stalled`] is and what cures it, for a run whose
/// collisions do (`dissipative`) or do not dissipate energy.
fn stall_cause(dissipative: bool) -> &'static str {
    if dissipative {
        "this is inelastic collapse — enable the TC model (tc > 0) or lengthen tc, raise \
         the restitution, or lower the density"
    } else {
        "without dissipation this means discs in contact whose collisions at one instant \
         never end, such as a row of touching discs (round the periodic box, or from wall \
         to wall) passing its momentum on forever, or in a field a disc at rest on top of \
         another (discs rest on the floor only, physics.md §15) — start with gaps between \
         the discs (a slightly lower density, or relaxed placement)"
    }
}
