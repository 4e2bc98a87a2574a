//! Inelastic runs: the energy budget E(t_end) = E(t_start) − dissipated, and
//! Haff's law of homogeneous cooling T(t) = T0/(1 + t/t0)² with
//! 1/t0 = (1 − e²)(1 + 3a2/16) ω(T0)/4 (physics.md §8), ω(T0) from the measured
//! collision rate scaled as √T. The temperature against time is the temperature
//! report's series.

use carom_core::Restitution;

use super::analyzer::Analyzer;
use super::report::{EnergyBudget, HaffReport, InelasticReport};

pub(super) fn report(a: &Analyzer) -> InelasticReport {
    let first = a.energy_series.first().copied();
    let last = a.energy_series.last().copied();
    let (e0, e1) = (first.map(|e| e.1), last.map(|e| e.1));
    // Dissipated energy between the first and last record: exact when the
    // source reports running totals, else the sum over logged collisions.
    let lost = match (first, last) {
        (Some((_, _, Some(a))), Some((_, _, Some(b)))) => Some(b - a),
        _ => None,
    };
    let lost_source = if lost.is_some() {
        "running total of the thermo records"
    } else {
        "sum over logged collisions × stride"
    };
    let lost = lost.unwrap_or(a.lost_from_collisions);
    let budget = match (e0, e1) {
        (Some(e0), Some(e1)) => Some(EnergyBudget {
            initial: e0,
            final_: e1,
            dissipated: lost,
            dissipated_source: lost_source,
            residual: e0 - lost - e1,
            relative_residual: (e0 - lost - e1) / e0,
        }),
        _ => None,
    };
    let haff = match a.run.restitution {
        Restitution::Normal(e) if e < 1.0 => haff(a, e),
        _ => None,
    };
    InelasticReport {
        energy: budget,
        haff,
    }
}

/// Haff's law (physics.md §8) with the collision frequency measured over the
/// run: in homogeneous cooling ω ∝ √T, so c = ω/√T = (2 N_pair/N) / ∫ √kT dt.
fn haff(a: &Analyzer, e: f64) -> Option<HaffReport> {
    let s = &a.kt_series;
    if s.len() < 3 {
        return None;
    }
    let (t0, kt0) = s[0];
    let integral: f64 = s
        .windows(2)
        .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1.max(0.0).sqrt() + w[1].1.max(0.0).sqrt()))
        .sum();
    let logged = if a.run.totals_from_thermo {
        0.0
    } else {
        a.pair_total as f64 * a.run.collision_stride as f64
    };
    let pairs = logged + a.pairs_from_increments as f64;
    if integral <= 0.0 || pairs == 0.0 {
        return None;
    }
    let c = 2.0 * pairs / a.run.n() as f64 / integral;
    let a2 = 16.0 * (1.0 - e) * (1.0 - 2.0 * e * e) / (57.0 - 25.0 * e + 30.0 * e * e * (1.0 - e));
    let omega0 = c * kt0.sqrt();
    let inv_t0 = (1.0 - e * e) * (1.0 + 3.0 * a2 / 16.0) * omega0 / 4.0;
    let (t_last, kt_last) = s[s.len() - 1];
    let predicted = kt0 / (1.0 + (t_last - t0) * inv_t0).powi(2);
    Some(HaffReport {
        a2,
        collision_frequency_initial: omega0,
        t0: 1.0 / inv_t0,
        kt_final_predicted: predicted,
        kt_final_measured: kt_last,
        ratio: kt_last / predicted,
    })
}
