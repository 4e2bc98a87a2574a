//! The report of `carom analyze`: plain serialisable data, one section per
//! observable, serialised as the JSON object that `carom analyze --json` prints.
//! Every field says what it holds and in which units (the run's: length, time,
//! mass; energies as kT). The sections are defined beside their observables;
//! this module only gathers them.

use serde::Serialize;

use super::atmosphere::GravityReport;
use super::bond_correlation::BondCorrelationReport;
use super::bond_order::BondOrderReport;
use super::compression::CompressionReport;
use super::contact::PairCorrelationReport;
use super::dynamics_report::DynamicsReport;
use super::floor::FloorReport;
use super::inelastic_report::InelasticReport;
use super::structure_factor::StructureFactorReport;
use super::thermo_report::{CollisionRateReport, EnskogReport, PressureReport, TemperatureReport};
use super::thermostat::ThermostatReport;
use super::transport_report::TransportReport;
use super::velocity_report::{SpeciesMb, SpeciesUntested};
#[cfg(doc)]
use super::DECORRELATION_COLLISIONS;

/// Everything `carom analyze` reports. Serialised as one JSON object; units are
/// the run's (length, time, mass; energies as kT).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Number of discs N.
    pub n: usize,
    /// The species.
    pub species: Vec<SpeciesInfo>,
    /// Packing fraction η = Σ N_s π a_s² / (L_x L_y).
    pub packing_fraction: f64,
    /// Box edge lengths [L_x, L_y] (length).
    pub box_size: [f64; 2],
    /// Whether the x and y axes are periodic (else hard walls).
    pub periodic: [bool; 2],
    /// True when pair and wall collisions conserve energy.
    pub elastic: bool,
    /// Which part of the log was used.
    pub window: WindowReport,
    /// Temperature and its degrees-of-freedom convention.
    pub temperature: TemperatureReport,
    /// Velocity distribution against Maxwell–Boltzmann, one entry per species with
    /// enough samples for the tests (the others are in
    /// `maxwell_boltzmann_untested`).
    pub maxwell_boltzmann: Vec<SpeciesMb>,
    /// Species with speeds but too few for the Maxwell–Boltzmann tests.
    pub maxwell_boltzmann_untested: Vec<SpeciesUntested>,
    /// Pressure and compressibility factor; `null` when no temperature is known.
    pub pressure: Option<PressureReport>,
    /// Pair collisions per disc per unit time.
    pub collision_rate: CollisionRateReport,
    /// Enskog consistency check (periodic, monodisperse, elastic runs only).
    pub enskog: Option<EnskogReport>,
    /// Inelastic runs only: cooling and energy budget.
    pub inelastic: Option<InelasticReport>,
    /// Pair correlation g(r), contact values and the contact theorem
    /// (physics.md §10); `null` without snapshots after the equilibration time.
    pub pair_correlation: Option<PairCorrelationReport>,
    /// Bond-orientational order ψ6, |Ψ6| and χ6 (physics.md §11); `null` with
    /// fewer than two snapshots after the equilibration time.
    pub bond_order: Option<BondOrderReport>,
    /// g6(r) and its decay (physics.md §11); `null` without snapshots.
    pub orientational_correlation: Option<BondCorrelationReport>,
    /// S(k) and the translational order (physics.md §11); `null` unless the box
    /// is periodic and there are snapshots.
    pub structure_factor: Option<StructureFactorReport>,
    /// MSD and D per species, the VACF at the snapshots and F_s(k*, τ) with τ_α
    /// (physics.md §13); `null` without time origins after the equilibration time.
    pub dynamics: Option<DynamicsReport>,
    /// D, η and λ from the collision log, with the exact VACF (physics.md §14);
    /// `null` unless the run is elastic and periodic and logs every collision.
    pub transport: Option<TransportReport>,
    /// Potential energy, n(y) and the barometric fit (physics.md §15); `null`
    /// without a field or without snapshots after the equilibration time.
    pub gravity: Option<GravityReport>,
    /// The thermostat's target against the measured temperature (physics.md
    /// §16); `null` without a thermostat.
    pub thermostat: Option<ThermostatReport>,
    /// How the discs grew: start and final η, how growth ended, the last Z and
    /// the rescales (physics.md §17); `null` unless the run compressed.
    pub compression: Option<CompressionReport>,
    /// The vibrating floor and the mean powers it puts in and the collisions
    /// dissipate (physics.md §18); `null` without a floor.
    pub floor: Option<FloorReport>,
    /// The quantities absent above that a reader would look for, each with the
    /// reason it could not be computed.
    pub not_computed: Vec<NotComputed>,
}

/// One species of the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeciesInfo {
    /// Number of discs.
    pub count: usize,
    /// Radius (length).
    pub radius: f64,
    /// Mass (mass).
    pub mass: f64,
}

/// The part of the log analysed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WindowReport {
    /// First simulated time in the log (time).
    pub t_start: f64,
    /// Last simulated time in the log (time).
    pub t_end: f64,
    /// Data before this time are ignored (time).
    pub equilibrate: f64,
    /// Minimum spacing of the snapshots used for the velocity distribution (time);
    /// `null`: every snapshot.
    pub every: Option<f64>,
    /// Whether `every` is the default rather than asked for: [`DECORRELATION_COLLISIONS`]
    /// collision times from the log's collision rate, or more when that would keep
    /// more than `max_velocities` velocities.
    pub every_default: bool,
    /// The default spacing of an inelastic run, whose collision rate changes: the
    /// snapshots used are at least this many pair collisions per disc apart,
    /// counted between them (`every` then only applies the memory bound); `null`
    /// otherwise.
    pub every_collisions: Option<f64>,
    /// Whether the default `every` was widened to keep at most `max_velocities`
    /// velocities in memory.
    pub every_from_budget: bool,
    /// The most velocities (discs × snapshots) the default spacing keeps.
    pub max_velocities: usize,
    /// The smallest spacing of the snapshots used, in pair collisions per disc
    /// counted between them (2 ΔN_pair/N, from the `/thermo` running counts or
    /// the logged collisions); `null` with fewer than two. Below
    /// about 4, the velocities of consecutive snapshots are correlated and the
    /// Maxwell–Boltzmann tests reject too often.
    pub spacing_collisions: Option<f64>,
    /// Snapshots in the log.
    pub snapshots_seen: usize,
    /// Times of the snapshots used for the velocity distribution.
    pub snapshot_times: Vec<f64>,
}

impl Report {
    /// The JSON object `carom analyze --json` prints: the report's fields with
    /// `file` (the log as named) and `log_complete` (false for a log cut short).
    pub fn to_json(&self, file: &str, complete: bool) -> serde_json::Value {
        let mut v = serde_json::to_value(self).expect("a Report serialises");
        if let Some(o) = v.as_object_mut() {
            o.insert("file".into(), serde_json::Value::String(file.to_owned()));
            o.insert("log_complete".into(), serde_json::Value::Bool(complete));
        }
        v
    }
}

/// One quantity the report lacks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NotComputed {
    /// The report's field (e.g. `structure_factor`).
    pub quantity: &'static str,
    /// Why it is absent, in words.
    pub why: String,
}
