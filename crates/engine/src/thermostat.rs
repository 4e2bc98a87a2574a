//! Thermostats: what the engine does to velocities besides collisions.
//!
//! * Andersen (physics.md §16.1): each disc's velocity is redrawn from the
//!   Maxwell–Boltzmann distribution at kT, v_x, v_y ~ N(0, kT/m), at the events of a
//!   Poisson process of rate ν per disc. The engine runs one process of rate N ν
//!   (waits Δt = −ln(U)/(N ν)) and picks a uniformly random disc at each event.
//! * Driven (physics.md §16.2, van Noije & Ernst's stochastic thermostat): every
//!   `interval` Δt each disc gets an independent Gaussian kick Δv_k ~ N(0, ξ² Δt)
//!   per component, minus the kicks' mass-weighted mean so that the total momentum
//!   does not random-walk; on average it injects (d/2) m ξ² (1 − 1/N) per disc and
//!   unit time (equal masses).
//!
//! These are the plain values a caller sets ([`crate::Engine::set_thermostat`]) and
//! a [`crate::Checkpoint`] stores; the engine's events are in `engine/thermostat.rs`.

/// A thermostat acting on the discs' velocities at exact event times.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Thermostat {
    /// Andersen: velocities redrawn from Maxwell–Boltzmann at `kt`, at rate `rate`
    /// per disc.
    Andersen {
        /// Target temperature kT (energy), > 0.
        kt: f64,
        /// Thermostat events per disc and unit time ν (1/time), > 0.
        rate: f64,
    },
    /// Stochastic driving: Gaussian velocity kicks of variance `xi2 · interval`
    /// per component to every disc, every `interval`.
    Driven {
        /// Driving strength ξ² (length²/time³): velocity variance added per
        /// component and unit time, > 0.
        xi2: f64,
        /// Time between kicks Δt (time), > 0.
        interval: f64,
    },
}

impl Thermostat {
    /// The name used in configurations and logs: `andersen` or `driven`.
    pub fn kind(&self) -> &'static str {
        match self {
            Thermostat::Andersen { .. } => "andersen",
            Thermostat::Driven { .. } => "driven",
        }
    }

    /// Check the parameters: each must be finite and > 0. The error names the
    /// field, the value and what is allowed.
    pub fn validate(&self) -> Result<(), String> {
        let fields = match *self {
            Thermostat::Andersen { kt, rate } => [("kT", kt), ("rate", rate)],
            Thermostat::Driven { xi2, interval } => [("xi2", xi2), ("interval", interval)],
        };
        for (name, x) in fields {
            if !(x.is_finite() && x > 0.0) {
                return Err(format!(
                    "thermostat.{name}: value {x} (allowed: a finite number > 0)"
                ));
            }
        }
        Ok(())
    }
}

/// What a thermostat has done since it was set (running totals).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ThermostatStats {
    /// Thermostat events: Andersen redraws, or driving kicks (each of every disc).
    pub events: u64,
    /// Kinetic energy the thermostat added, Σ ΔK over its velocity changes
    /// (energy; negative when it removed energy).
    pub energy_added: f64,
}

/// A thermostat's complete state, for a bit-identical resume: its parameters, its
/// random generator (a `rand_pcg` `Pcg64Mcg`, whose state is one 128-bit number)
/// its totals and its next event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThermostatState {
    /// The thermostat.
    pub thermostat: Thermostat,
    /// The generator's state.
    pub rng: u128,
    /// Its running totals.
    pub stats: ThermostatStats,
    /// The time it was set (time): driving kick k comes at `origin` + k Δt.
    pub origin: f64,
    /// Its next event: (time, sequence number among the engine's scheduled
    /// events, which orders it against the caller's at the same time); `None`
    /// when the wait is infinite (a rate so small that N ν rounds to 0).
    pub next: Option<(f64, u64)>,
}
