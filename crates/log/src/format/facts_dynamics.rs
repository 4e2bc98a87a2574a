//! The JSON form of the resolved dynamics in the run facts (log format 2.4 on):
//! the thermostat (physics.md §16), the growth of the radii (compression,
//! physics.md §17) and the vibrating floor (physics.md §18), each as the engine
//! holds it, so that a reader learns them without the configuration front end.
//!
//! `"thermostat": {"kind": "andersen", "kt", "rate"}` or `{"kind": "driven",
//! "xi2", "interval"}`; `"growth": {"rate", "target_scale", "kt",
//! "rescale_interval", "max_reduced_pressure"}` (the engine's `Growth`: radii
//! a_i(t) = a_i⁰ (1 + γ t) up to `target_scale`); `"floor": {"amplitude",
//! "omega"}` (h(t) = A (1 − cos ω t)). Each only when the run had it; numbers
//! under the log's rule (`super::number`).

use carom_core::vibrating_wall::Floor;
use carom_engine::{Growth, Thermostat};
use serde::{Deserialize, Serialize};

/// [`Thermostat`] as JSON.
#[derive(Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub(super) enum ThermostatJson {
    Andersen {
        #[serde(with = "super::number::float")]
        kt: f64,
        #[serde(with = "super::number::float")]
        rate: f64,
    },
    Driven {
        #[serde(with = "super::number::float")]
        xi2: f64,
        #[serde(with = "super::number::float")]
        interval: f64,
    },
}

impl From<Thermostat> for ThermostatJson {
    fn from(t: Thermostat) -> Self {
        match t {
            Thermostat::Andersen { kt, rate } => ThermostatJson::Andersen { kt, rate },
            Thermostat::Driven { xi2, interval } => ThermostatJson::Driven { xi2, interval },
        }
    }
}

impl From<ThermostatJson> for Thermostat {
    fn from(t: ThermostatJson) -> Self {
        match t {
            ThermostatJson::Andersen { kt, rate } => Thermostat::Andersen { kt, rate },
            ThermostatJson::Driven { xi2, interval } => Thermostat::Driven { xi2, interval },
        }
    }
}

/// [`Growth`] as JSON.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GrowthJson {
    #[serde(with = "super::number::float")]
    rate: f64,
    #[serde(with = "super::number::float")]
    target_scale: f64,
    #[serde(with = "super::number::float")]
    kt: f64,
    #[serde(with = "super::number::float")]
    rescale_interval: f64,
    #[serde(with = "super::number::float")]
    max_reduced_pressure: f64,
}

impl From<Growth> for GrowthJson {
    fn from(g: Growth) -> Self {
        GrowthJson {
            rate: g.rate,
            target_scale: g.target_scale,
            kt: g.kt,
            rescale_interval: g.rescale_interval,
            max_reduced_pressure: g.max_reduced_pressure,
        }
    }
}

impl From<GrowthJson> for Growth {
    fn from(g: GrowthJson) -> Self {
        Growth {
            rate: g.rate,
            target_scale: g.target_scale,
            kt: g.kt,
            rescale_interval: g.rescale_interval,
            max_reduced_pressure: g.max_reduced_pressure,
        }
    }
}

/// [`Floor`] as JSON.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FloorJson {
    #[serde(with = "super::number::float")]
    amplitude: f64,
    #[serde(with = "super::number::float")]
    omega: f64,
}

impl From<Floor> for FloorJson {
    fn from(f: Floor) -> Self {
        FloorJson {
            amplitude: f.amplitude,
            omega: f.omega,
        }
    }
}

impl From<FloorJson> for Floor {
    fn from(f: FloorJson) -> Self {
        Floor {
            amplitude: f.amplitude,
            omega: f.omega,
        }
    }
}
