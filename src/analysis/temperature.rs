//! Temperature: kT = 2K/f with f = 2N − (number of periodic axes) (physics.md §5),
//! averaged over the snapshots used for the velocity distribution, with the
//! series of kT against time from every thermo record and snapshot.

use carom_core::observables::{degrees_of_freedom, temperature};

use super::analyzer::Analyzer;
use super::report::TemperatureReport;
use super::series::{subsample, MAX_SERIES};

/// kT averaged over the snapshots used (`None` without any).
pub(super) fn snapshot_kt(a: &Analyzer) -> Option<f64> {
    let used = a.snapshots_used.len();
    (used > 0).then(|| temperature(a.mb_kinetic / used as f64, a.dof()))
}

/// The temperature report; `kt_used` from [`snapshot_kt`].
pub(super) fn report(a: &Analyzer, kt_used: Option<f64>) -> TemperatureReport {
    let sim_box = &a.run.sim_box;
    TemperatureReport {
        kt: kt_used.or_else(|| a.kt_at(a.t_eq)).unwrap_or(f64::NAN),
        kt_initial: a.kt_series.first().map(|p| p.1),
        kt_final: a.kt_series.last().map(|p| p.1),
        dof: degrees_of_freedom(a.run.n(), sim_box),
        conserved_momentum_components: sim_box.conserved_momentum_components(),
        convention: "kT = 2K/f, f = 2N − (number of periodic axes) (physics.md §5)",
        series: subsample(&a.kt_series, MAX_SERIES),
    }
}
