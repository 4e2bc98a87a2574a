//! Temperature: kT = 2K/f with f = 2N − (number of periodic axes) (physics.md §5),
//! averaged over the snapshots used for the velocity distribution, with the
//! series of kT against time from every thermo record and snapshot.

use carom_core::observables::{degrees_of_freedom, temperature};

use super::samples::Samples;
use super::series::{subsample, MAX_SERIES};
use super::thermo_report::TemperatureReport;

/// kT averaged over the snapshots used (`None` without any).
pub(super) fn snapshot_kt(a: &Samples) -> Option<f64> {
    let used = a.snapshots_used.len();
    (used > 0).then(|| temperature(a.mb_kinetic / used as f64, a.dof()))
}

/// The temperature report; `kt_used` from [`snapshot_kt`].
pub(super) fn report(a: &Samples, kt_used: Option<f64>) -> TemperatureReport {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::RunDescription;
    use crate::AnalysisOptions;
    use crate::Analyzer;
    use carom_core::{Boundary, SimBox, Species};

    fn analyzer(run: RunDescription, equilibrate: f64) -> Analyzer {
        let opts = AnalysisOptions {
            equilibrate: Some(equilibrate),
            every: Some(1.0),
            ..Default::default()
        };
        Analyzer::new(run, opts).unwrap()
    }

    /// Three discs of mass 2 in a periodic box, f = 2·3 − 2 = 4. K = Σ ½·2·v²:
    /// 1.25 + 1 + 2.5 = 4.75 and 5 + 1 + 2 = 8; kT = 2·(4.75 + 8)/2/4 = 3.1875.
    #[test]
    fn the_snapshot_temperature_is_twice_the_mean_kinetic_energy_per_degree_of_freedom() {
        let run = RunDescription {
            species: vec![Species::new(3, 0.4, 2.0)],
            ..RunDescription::for_tests()
        };
        let mut a = analyzer(run, 0.0);
        assert_eq!(snapshot_kt(&a.samples), None);
        let s = [0, 0, 0];
        a.snapshot(1.0, &s, &[1.0, -1.0, 0.5], &[0.5, 0.0, -1.5])
            .unwrap();
        a.snapshot(3.0, &s, &[2.0, 0.0, -1.0], &[1.0, -1.0, 1.0])
            .unwrap();
        let kt = snapshot_kt(&a.samples).unwrap();
        assert!((kt - 3.1875).abs() < 1e-15, "{kt}");
    }

    /// A channel (x periodic, walls on y) of 3 discs: f = 2·3 − 1 = 5, so
    /// K = 5, 2.5, 10 at t = 0, 4, 10 are kT = 2, 1, 4. Without snapshots kT is
    /// the series at the start of the window, t = 2: halfway from 2 to 1, 1.5.
    #[test]
    fn the_report_takes_the_snapshots_temperature_or_the_series_at_the_window_start() {
        let run = RunDescription {
            species: vec![Species::new(3, 0.4, 2.0)],
            sim_box: SimBox {
                boundary: [Boundary::Periodic, Boundary::Walls { restitution: 1.0 }],
                ..SimBox::periodic(10.0, 8.0)
            },
            ..RunDescription::for_tests()
        };
        let mut a = analyzer(run, 2.0);
        let r = report(&a.samples, None);
        assert!(r.kt.is_nan() && r.kt_initial.is_none() && r.kt_final.is_none());
        for (t, k) in [(0.0, 5.0), (4.0, 2.5), (10.0, 10.0)] {
            a.thermo(t, k, None);
        }
        let r = report(&a.samples, None);
        assert_eq!(
            (r.kt, r.kt_initial, r.kt_final),
            (1.5, Some(2.0), Some(4.0))
        );
        assert_eq!((r.dof, r.conserved_momentum_components), (5, 1));
        assert_eq!(r.series, [[0.0, 2.0], [4.0, 1.0], [10.0, 4.0]]);
        assert_eq!(report(&a.samples, Some(0.7)).kt, 0.7);
    }
}
