//! Haff's law from first principles (physics.md §8): the cooling rate predicted
//! from Enskog's collision frequency ω_E = 2σ n g(σ) √(π kT/m) (physics.md §7,
//! Henderson's g(σ) via `carom_core::rates`) and the measured a2, against the
//! measured kT(t). In the homogeneous cooling state dkT/dt = −ζ kT with
//! ζ = (1 − e²)(1 + 3a2/16) ω_E/2, so 1/√kT grows linearly in time with slope
//!     s = (1 − e²)(1 + 3a2/16) ω_E/(4 √kT)
//! (a constant, since ω_E ∝ √kT): the same law as T0/(1 + t/t0)². Unlike the
//! report's Haff check, nothing here is taken from the measured collisions, so
//! the two agree only if the gas collides as Enskog's theory says and stays
//! homogeneous (clusters cool more slowly).

use carom_core::observables::{has_walls, packing_fraction};
use carom_core::rates::henderson_contact_value;

use super::inelastic_report::HaffEnskog;
use super::samples::Samples;
use super::thermostat::enskog_rate_coefficient;

/// |measured/predicted slope − 1| accepted as agreement: Enskog's rate neglects
/// the velocity correlations that build up in a cooling gas, a few per cent at
/// η ≈ 0.25 (docs/validation.md, 'granular cooling').
pub const ENSKOG_COOLING_TOLERANCE: f64 = 0.05;

/// The prediction over the window [t_eq, t_end] with the measured `a2`; `None`
/// for a mixture, a box with walls, or fewer than three kT records in the window.
pub(super) fn haff_enskog(a: &Samples, e: f64, a2: f64) -> Option<HaffEnskog> {
    let run = &a.run;
    let mut present = run.species.iter().filter(|s| s.count > 0);
    let (Some(species), None) = (present.next(), present.next()) else {
        return None;
    };
    if has_walls(&run.sim_box) || !a2.is_finite() {
        return None;
    }
    let points: Vec<(f64, f64)> = a
        .kt_series
        .iter()
        .filter(|p| p.0 >= a.t_eq && p.0 <= run.t_end && p.1 > 0.0)
        .map(|&(t, kt)| (t, 1.0 / kt.sqrt()))
        .collect();
    if points.len() < 3 {
        return None;
    }
    let eta = packing_fraction(&run.species, &run.sim_box);
    let density = run.n() as f64 / run.sim_box.area();
    // ω_E/√kT.
    let omega_unit = enskog_rate_coefficient(species, density, eta);
    let slope_predicted = (1.0 - e * e) * (1.0 + 3.0 * a2 / 16.0) * omega_unit / 4.0;
    let slope_measured = least_squares_slope(&points);
    let kt0 = a.kt_at(a.t_eq)?;
    let (t1, y1) = points[points.len() - 1];
    let y_end = 1.0 / kt0.sqrt() + slope_predicted * (t1 - a.t_eq);
    let ratio = slope_measured / slope_predicted;
    Some(HaffEnskog {
        window: [a.t_eq, t1],
        g_contact: henderson_contact_value(eta),
        a2,
        omega_start: omega_unit * kt0.sqrt(),
        slope_predicted,
        slope_measured,
        ratio,
        kt_end_predicted: 1.0 / (y_end * y_end),
        kt_end_measured: 1.0 / (y1 * y1),
        agrees: (ratio - 1.0).abs() <= ENSKOG_COOLING_TOLERANCE,
    })
}

/// The least-squares slope of y against t.
fn least_squares_slope(p: &[(f64, f64)]) -> f64 {
    let n = p.len() as f64;
    let (mt, my) = p
        .iter()
        .fold((0.0, 0.0), |(a, b), (t, y)| (a + t / n, b + y / n));
    let (sty, stt) = p.iter().fold((0.0, 0.0), |(a, b), (t, y)| {
        (a + (t - mt) * (y - my), b + (t - mt) * (t - mt))
    });
    sty / stt
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::RunDescription;
    use crate::AnalysisOptions;
    use crate::Analyzer;
    use carom_core::{Restitution, SimBox, Species};

    /// A gas that follows Haff's law exactly with Enskog's rate: 1/√kT = 1/√kT0 +
    /// s t at the predicted s, so the ratio is 1 and kT at the end is predicted to
    /// rounding. By hand: 4 discs of σ = 1, m = 2 in a 10 × 10 box, η = π/100,
    /// n = 4/100; ω_E/√kT = 2σ n g √(π/m) with Henderson's g.
    #[test]
    fn an_exact_haff_gas_gives_ratio_one() {
        let run = RunDescription {
            species: vec![Species::new(4, 0.5, 2.0)],
            sim_box: SimBox::periodic(10.0, 10.0),
            restitution: Restitution::Normal(0.8),
            ..RunDescription::for_tests()
        };
        let opts = AnalysisOptions {
            equilibrate: Some(2.0),
            ..Default::default()
        };
        let mut a = Analyzer::new(run, opts).unwrap();
        let eta = std::f64::consts::PI / 100.0;
        let g = (1.0 - 7.0 * eta / 16.0) / (1.0 - eta).powi(2);
        let omega_unit = 2.0 * 1.0 * 0.04 * g * (std::f64::consts::PI / 2.0).sqrt();
        let a2 = -0.02;
        let s = (1.0 - 0.64) * (1.0 + 3.0 * a2 / 16.0) * omega_unit / 4.0;
        let f = a.samples.dof() as f64 / 2.0;
        for k in 0..=10 {
            let t = k as f64;
            let kt = (1.0 / (1.0 + s * t)).powi(2);
            a.thermo(t, kt * f, None);
        }
        let h = haff_enskog(&a.samples, 0.8, a2).unwrap();
        assert!((h.slope_predicted - s).abs() < 1e-14 * s, "{h:?}");
        assert!((h.ratio - 1.0).abs() < 1e-12 && h.agrees, "{h:?}");
        assert!((h.kt_end_predicted / h.kt_end_measured - 1.0).abs() < 1e-12);
        assert!((h.g_contact - g).abs() < 1e-15);
        assert_eq!(h.window, [2.0, 10.0]);
        // Cooling 10 % slower than predicted is a disagreement.
        let mut b = Analyzer::new(a.samples.run.clone(), opts).unwrap();
        for k in 0..=10 {
            let t = k as f64;
            b.thermo(t, (1.0 / (1.0 + 0.9 * s * t)).powi(2) * f, None);
        }
        let h = haff_enskog(&b.samples, 0.8, a2).unwrap();
        assert!((h.ratio - 0.9).abs() < 1e-12 && !h.agrees, "{h:?}");
    }
}
