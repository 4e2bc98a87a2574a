//! Logs of a compression (Lubachevsky–Stillinger, physics.md §17): how the growth
//! went, and the window at fixed size that the equilibrium analysis may use.
//!
//! While discs grow, every radius is a_i⁰ s(t), s(t) = 1 + γ t (17.1), and the
//! velocities are rescaled to the target kT at fixed instants: neither the pair
//! correlation at contact nor the equation of state nor the Maxwell–Boltzmann
//! tests mean anything there. Once growth ends the radii stay a_i⁰ s_end, with
//! η_end = s_end² η₀. The `/thermo` records carry s, η, the phase and Z (log format
//! 2.2); this module reads them in a pass of their own before the analysis, gives
//! the radii after growth and the start of the window (after growth ended), and
//! reports start and final η, how growth ended, the last Z and the rescales.

use std::path::Path;

use carom_core::observables::packing_fraction;
use carom_core::{SimBox, Species};
use carom_log::{Growth, GrowthEvent, GrowthPhase, LogMessage, LogReader};
use serde::Serialize;

use super::error::AnalysisError;

/// How the compression in a log went.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CompressionReport {
    /// η of the configured radii, where growth starts (scale 1).
    pub start_packing_fraction: f64,
    /// η at which growth was configured to stop.
    pub target_packing_fraction: f64,
    /// η at the end of growth, or at the last record while discs still grow.
    pub final_packing_fraction: f64,
    /// Radii at the end of growth / configured radii, s_end.
    pub final_radius_scale: f64,
    /// `target`, `jammed`, or `growing` (growth had not ended by the end of the log).
    pub ended: &'static str,
    /// Time of the first event after growth ended (time); `null` while growing.
    pub end_time: Option<f64>,
    /// Virial Z = βPA/N over the last interval between rescales before the end.
    pub last_z: f64,
    /// The jamming bound on Z (growth stops above it).
    pub max_reduced_pressure: f64,
    /// Velocity rescales logged (growth instants, the end included).
    pub rescales: u64,
    /// Relative growth rate γ (1/time) and time between rescales (time).
    pub rate: f64,
    /// Time between rescales (time).
    pub rescale_interval: f64,
}

/// What the log's `/thermo` records say about its growth.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Compression {
    /// The report's content (its `final_*` values at the end of growth).
    pub(super) report: CompressionReport,
}

impl Compression {
    /// Read the `/thermo` records of the log `path` of a run with `growth` from
    /// configured species `species` in `sim_box`. A log cut short is read up to
    /// its cut. Errors when the log holds no growth fields (written before log
    /// format 2.2, or without `/thermo` records).
    pub(super) fn read(
        path: &Path,
        growth: &Growth,
        species: &[Species],
        sim_box: &SimBox,
    ) -> Result<Compression, AnalysisError> {
        let eta0 = packing_fraction(species, sim_box);
        let mut reader = LogReader::open(path)?;
        let mut last: Option<carom_log::Thermo> = None;
        let mut end: Option<carom_log::Thermo> = None;
        let mut rescales = 0;
        for m in reader.thermo() {
            let Ok(LogMessage::Thermo(t)) = m else { break };
            if t.growth.is_none() {
                continue;
            }
            match t.growth_event {
                Some(GrowthEvent::Rescale) => rescales += 1,
                Some(GrowthEvent::End) => {
                    rescales += 1;
                    end = Some(t);
                }
                None => {}
            }
            last = Some(t);
        }
        let Some(last) = last else {
            return Err(AnalysisError::Unusable(format!(
                "{} is a compression run but its /thermo records carry no growth (log \
                 format before 2.2, or thermo records off): the radii after growth are \
                 unknown, so the analysis would use the wrong ones",
                path.display()
            )));
        };
        // The record that fixes the final radii: the end of growth, or (a log that
        // starts after it ended, e.g. a resumed one) any record past it.
        let fixed = end.or((last.growth != Some(GrowthPhase::Growing)).then_some(last));
        let at = fixed.unwrap_or(last);
        let ended = match at.growth {
            Some(GrowthPhase::Target) => "target",
            Some(GrowthPhase::Jammed) => "jammed",
            _ => "growing",
        };
        Ok(Compression {
            report: CompressionReport {
                start_packing_fraction: eta0,
                target_packing_fraction: eta0 * growth.target_scale * growth.target_scale,
                final_packing_fraction: at.packing_fraction.unwrap_or(f64::NAN),
                final_radius_scale: at.radius_scale.unwrap_or(f64::NAN),
                ended,
                end_time: end.map(|t| t.time),
                last_z: at.growth_z.unwrap_or(f64::NAN),
                max_reduced_pressure: growth.max_reduced_pressure,
                rescales,
                rate: growth.rate,
                rescale_interval: growth.rescale_interval,
            },
        })
    }

    /// The radii after growth: the configured ones times s_end, as the engine
    /// computes them (`Engine::state`); `None` while discs still grow.
    pub(super) fn final_species(&self, species: &[Species]) -> Option<Vec<Species>> {
        let r = &self.report;
        (r.ended != "growing").then(|| {
            species
                .iter()
                .map(|sp| Species {
                    radius: sp.radius * r.final_radius_scale,
                    ..*sp
                })
                .collect()
        })
    }

    /// The start of the analysis window: `equilibrate` when given (refused
    /// before the end of growth), else the end of growth plus a tenth of the time
    /// after it, as the plain default takes a tenth of the log. Errors while discs
    /// grow to the end of the log.
    pub(super) fn window_start(
        &self,
        equilibrate: Option<f64>,
        t_start: f64,
        t_end: f64,
    ) -> Result<f64, AnalysisError> {
        let r = &self.report;
        if r.ended == "growing" {
            return Err(AnalysisError::Unusable(format!(
                "the discs grow until the end of the log (η = {} → {} at t = {t_end}, \
                 last Z = {}): the equation of state, g(r) and the Maxwell–Boltzmann \
                 tests need discs of fixed size; run on until growth ends (η target {}) \
                 and analyse the time after it",
                r.start_packing_fraction,
                r.final_packing_fraction,
                r.last_z,
                r.target_packing_fraction
            )));
        }
        // A log that starts after growth ended has no end record: all of it is at
        // fixed size.
        let grown = r.end_time.unwrap_or(t_start).max(t_start);
        match equilibrate {
            Some(t) if t < grown => Err(AnalysisError::Unusable(format!(
                "--equilibrate {t}: the discs grow until t = {grown} ({} at η = {}); the \
                 equation of state, g(r) and the Maxwell–Boltzmann tests need discs of \
                 fixed size (allowed: --equilibrate ≥ {grown}, or leave it out to start \
                 after growth)",
                r.ended, r.final_packing_fraction
            ))),
            Some(t) => Ok(t),
            None if grown >= t_end => Err(AnalysisError::Unusable(format!(
                "growth ends at t = {grown}, the end of the log: no time at fixed size to \
                 analyse; run on after growth ends"
            ))),
            None => Ok(grown + 0.1 * (t_end - grown)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ended(how: &'static str, end_time: Option<f64>) -> Compression {
        Compression {
            report: CompressionReport {
                start_packing_fraction: 0.3,
                target_packing_fraction: 0.6,
                final_packing_fraction: 0.6,
                final_radius_scale: 2f64.sqrt(),
                ended: how,
                end_time,
                last_z: 8.0,
                max_reduced_pressure: 1e3,
                rescales: 41,
                rate: 0.01,
                rescale_interval: 1.0,
            },
        }
    }

    #[test]
    fn the_window_starts_after_growth_and_refuses_to_start_during_it() {
        let c = ended("target", Some(41.5));
        // Default: the end of growth plus a tenth of the rest, 41.5 + 0.1·58.5.
        assert_eq!(c.window_start(None, 0.0, 100.0).unwrap(), 41.5 + 5.85);
        assert_eq!(c.window_start(Some(50.0), 0.0, 100.0).unwrap(), 50.0);
        assert_eq!(c.window_start(Some(41.5), 0.0, 100.0).unwrap(), 41.5);
        let e = c
            .window_start(Some(41.0), 0.0, 100.0)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("--equilibrate 41") && e.contains("grow until t = 41.5"),
            "{e}"
        );
        let e = c.window_start(None, 0.0, 41.5).unwrap_err().to_string();
        assert!(e.contains("no time at fixed size"), "{e}");
        // A resumed log that starts after growth ended: all of it.
        let c = ended("jammed", None);
        assert_eq!(c.window_start(None, 60.0, 100.0).unwrap(), 64.0);
        let e = ended("growing", None)
            .window_start(None, 0.0, 30.0)
            .unwrap_err();
        assert!(
            e.to_string().contains("grow until the end of the log"),
            "{e}"
        );
    }

    #[test]
    fn the_radii_after_growth_are_the_configured_ones_times_the_final_scale() {
        let sp = [Species::new(3, 0.5, 1.0), Species::new(2, 0.7, 2.0)];
        let f = ended("target", Some(1.0)).final_species(&sp).unwrap();
        assert_eq!(f[0].radius, 0.5 * 2f64.sqrt());
        assert_eq!(f[1].radius, 0.7 * 2f64.sqrt());
        assert_eq!((f[1].count, f[1].mass), (2, 2.0));
        assert!(ended("growing", None).final_species(&sp).is_none());
    }
}
