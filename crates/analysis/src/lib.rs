//! Analysis of carom runs: what `carom analyze` measures, checked against
//! theory with statistics independent of the engine (physics.md §5–§18).
//!
//! [`analyze_log`] reads a log in one streaming pass (an older log's facts
//! derived once by the caller's [`OldLogFacts`], [`analyze_log_with`]) into an
//! [`Analyzer`], which the tests also feed straight from the engine;
//! [`Analyzer::finish_with`] (with the run's [`RunDynamics`]) assembles the
//! [`Report`], one section per observable (temperature, Maxwell–Boltzmann, Z,
//! collision rate, inelastic checks, g_ab(r), ψ6, g6(r), S(k), MSD/D/F_s,
//! transport, gravity, thermostat, compression, floor). [`frames`] gives the
//! structure and dynamics sections of plain arrays (another code's snapshots, a
//! GSD file) with the same accumulators; [`stats`] the statistics.

#![deny(missing_docs)]

mod analyzer;
mod atmosphere;
mod bond_correlation;
mod bond_order;
mod cell_list;
mod collision_rate;
mod compression;
mod contact;
mod description;
mod dynamics;
mod dynamics_report;
mod eos_reference;
mod error;
mod floor;
pub mod frames;
mod from_log;
mod haff_enskog;
mod hcs_sonine;
mod helfand;
mod hydrostatic;
mod increment_correlator;
mod inelastic;
mod inelastic_report;
mod log_facts;
mod msd;
mod neighbours;
mod not_computed;
mod nufft;
mod options;
mod origins;
mod pair_correlation;
mod pressure;
mod psi6_estimators;
mod quadrature;
mod report;
mod run_dynamics;
mod samples;
mod self_scattering;
mod series;
mod sixfold;
mod sonine;
pub mod stats;
mod structure;
mod structure_factor;
mod temperature;
#[cfg(test)]
mod test_lattice;
mod thermo_report;
mod thermostat;
mod transport;
mod transport_reliability;
mod transport_report;
mod transport_theory;
mod unwrap;
mod vacf_exact;
mod velocity;
mod velocity_report;

pub use analyzer::Analyzer;
pub use atmosphere::{BarometricFit, GravityReport};
pub use bond_correlation::{
    BondCorrelationReport, G6_BIN_WIDTH_SIGMA, G6_R_MAX_SIGMA, G6_SNAPSHOTS,
};
pub use bond_order::{
    global_psi6, local_psi6, BondOrderReport, OtherEstimatorsReport, MIN_BOND_ORDER_DISCS,
};
pub use compression::CompressionReport;
pub use contact::{
    ContactTheoremReport, ContactValue, PairCorrelationReport, PairReport, CONTACT_FIT_SIGMA,
};
pub use description::RunDescription;
pub use dynamics::SEGMENTS as DYNAMICS_SEGMENTS;
pub use dynamics_report::{DiffusionFit, DynamicsReport, SpeciesDynamics};
pub use eos_reference::{henderson_z, kolafa_rottner, li_2022, KOLAFA_ROTTNER};
pub use error::AnalysisError;
pub use floor::FloorReport;
pub use from_log::{analyze_log, analyze_log_with, ReadObserver};
pub use haff_enskog::ENSKOG_COOLING_TOLERANCE;
pub use inelastic_report::{EnergyBudget, HaffEnskog, HaffReport, InelasticReport, SonineReport};
pub use log_facts::{no_old_log_facts, OldLogFacts};
pub use msd::D_WINDOW_COLLISIONS;
pub use neighbours::{delaunay_neighbours, Neighbours, GHOST_SPACINGS};
pub use options::{AnalysisOptions, CORRELATED_SPACING, DECORRELATION_COLLISIONS, MAX_VELOCITIES};
pub use origins::{MAX_DISC_ORIGINS, ORIGINS_PER_LEVEL};
pub use pair_correlation::{BIN_WIDTH_SIGMA, BLOCKS as PAIR_CORRELATION_BLOCKS, R_MAX_SIGMA};
pub use psi6_estimators::{local_psi6_equal, local_psi6_nearest, six_neighbour_fraction};
pub use report::{NotComputed, Report, SpeciesInfo, WindowReport};
pub use run_dynamics::{FloorRun, RunDynamics};
pub use series::DRIFT_STD_ERRORS;
pub use structure::StructureReport;
pub use structure_factor::{
    StructureFactorReport, K_STAR_MIN_SIGMA, SK_K_MAX_SIGMA, SK_MAX_MODES, SK_SNAPSHOTS,
};
pub use thermo_report::{
    CollisionRateReport, DriftReport, EnskogReport, PressureReport, RateAt, TemperatureReport,
};
pub use thermostat::{
    driven_a2, driven_steady_temperature, enskog_rate_coefficient, ThermostatReport,
};
pub use transport::TRANSPORT_SEGMENTS;
pub use transport_reliability::{LEVELLING_SLOPE, TRANSPORT_WINDOW};
pub use transport_report::{
    EnskogTransport, Estimate, HelfandReport, Reliability, SpeciesTransport, TransportReport,
};
pub use unwrap::Unwrapper;
pub use velocity::{MAX_SNAPSHOT_CORRELATION, MB_FAMILY_ALPHA, MB_TESTS_PER_SPECIES};
pub use velocity_report::{ChiSquareReport, HistogramReport, KsReport, SpeciesMb, SpeciesUntested};
