//! The `neighbours` field: how the engine finds the discs a disc may meet next,
//! `"auto"` (the default), `"cells"` or `"lists"` (carom-engine's
//! [`Neighbours`], whose names these are). Both searches give the same events up
//! to rounding; they differ in speed. `"auto"` is left out of the stored
//! configuration, so the configurations of runs made before the field existed
//! read the same. `"lists"` is refused here where it can never work (a field,
//! growth, a vibrating floor: lists need straight flights of discs of fixed
//! size); the engine refuses the rest when it builds the run (a mixture that
//! needs a grid per size class, a periodic box narrower than three list cells).

use super::{Config, ConfigError};
use carom_engine::Neighbours;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The neighbour search (`neighbours`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum NeighboursConfig {
    /// `"auto"`: neighbour lists for dense discs of equal size flying straight
    /// (no gravity, compression or vibrating floor) from packing fraction `carom_engine::LISTS_FROM_PACKING` = 0.66,
    /// cells otherwise.
    #[default]
    Auto,
    /// `"cells"`: the cell grid; a disc looks at the discs of the 3 × 3 cells
    /// around its own, and crossing a cell edge is an event.
    Cells,
    /// `"lists"`: neighbour lists with a skin; a disc looks at the discs listed
    /// near it, and leaving its skin is an event. Refused with gravity,
    /// compression or a vibrating floor, and by the engine for a mixture that
    /// needs a grid per size class or a periodic box less than about 5.1 largest
    /// diameters wide.
    Lists,
}

impl NeighboursConfig {
    /// The engine's setting.
    pub fn neighbours(self) -> Neighbours {
        match self {
            NeighboursConfig::Auto => Neighbours::Auto,
            NeighboursConfig::Cells => Neighbours::Cells,
            NeighboursConfig::Lists => Neighbours::Lists,
        }
    }

    /// Whether this is the default, `"auto"` (left out of the stored configuration).
    pub(super) fn is_auto(&self) -> bool {
        *self == NeighboursConfig::Auto
    }
}

impl Config {
    /// `"lists"` only with straight flights of discs of fixed size.
    pub(super) fn check_neighbours(&self) -> Result<(), ConfigError> {
        if self.neighbours != NeighboursConfig::Lists {
            return Ok(());
        }
        let conflict = if self.gravity > 0.0 {
            Some("gravity")
        } else if self.compression.is_some() {
            Some("compression")
        } else if self.vibrating_floor.is_some() {
            Some("a vibrating floor")
        } else {
            None
        };
        match conflict {
            None => Ok(()),
            Some(what) => Err(ConfigError::invalid(
                "neighbours",
                format!(
                    "\"lists\" cannot be used with {what} (neighbour lists need straight \
                     flights of discs of fixed size)"
                ),
                "\"auto\" or \"cells\"",
            )),
        }
    }
}
