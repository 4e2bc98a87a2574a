//! Thermostatted runs (physics.md §16): the temperature a thermostat should hold
//! against the one measured. Andersen holds kT at its target with every velocity
//! component free (momentum is not conserved): kT = 2K/(2N), against the target.
//! Driving holds an inelastic gas at the granular temperature T = K/N where the
//! injection m ξ² (1 − 1/N) per disc balances the collisional loss (16.6):
//!     T^{3/2} = 2 m ξ² (1 − 1/N) / [(1 − e²)(1 + 3a2/16) c],   ω = c √T,
//! with c from Enskog and Henderson's g(σ) (7.2, 7.6), or from the measured ω, and
//! a2 van Noije & Ernst's value for the driven gas (16.7). A thermostat voids the
//! energy budget and Haff's law (no input assumed) and the replayed transport
//! (blind to its velocity changes): the analyzer leaves those sections out.

use carom_core::observables::packing_fraction;
use carom_core::rates::henderson_contact_value;
use carom_core::{Restitution, Species};
use carom_log::Thermostat;
use serde::Serialize;

use super::description::RunDescription;
use super::thermo_report::TemperatureReport;

/// What a thermostat should hold and what the run measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThermostatReport {
    /// `andersen` or `driven`.
    pub kind: &'static str,
    /// Andersen: the target kT (energy).
    pub target_kt: Option<f64>,
    /// Andersen: redraws per disc and unit time ν (1/time).
    pub rate: Option<f64>,
    /// Driven: ξ² (length²/time³).
    pub xi2: Option<f64>,
    /// Driven: time between kicks (time).
    pub interval: Option<f64>,
    /// kT = 2K/(2N) over the snapshots used (energy): every velocity component is
    /// free under Andersen.
    pub kt_all_components: f64,
    /// Andersen: `kt_all_components` / target − 1.
    pub relative_difference: Option<f64>,
    /// Driven: the granular temperature T = K/N over the snapshots used (energy).
    pub granular_temperature: Option<f64>,
    /// Driven, one species, normal restitution: the steady T of (16.6) with
    /// Enskog's rate and Henderson's g(σ) (energy).
    pub predicted_temperature: Option<f64>,
    /// Driven, normal restitution: the steady T of (16.6) with the measured rate
    /// per √T, c = ω/√T (energy).
    pub predicted_temperature_from_rate: Option<f64>,
    /// Driven, normal restitution: a2 of the driven gas (16.7).
    pub a2_theory: Option<f64>,
}

/// van Noije & Ernst's Sonine coefficient of the white-noise driven gas in 2D
/// (physics.md (16.7)): a2 = 16 (1 − e)(1 − 2e²) / (185 − 153 e + 30 e² (1 − e)).
pub fn driven_a2(e: f64) -> f64 {
    16.0 * (1.0 - e) * (1.0 - 2.0 * e * e) / (185.0 - 153.0 * e + 30.0 * e * e * (1.0 - e))
}

/// The steady granular temperature T = K/N (energy) of `n` discs of mass `mass`
/// driven with ξ² = `xi2` and colliding with normal restitution `e` at the pair
/// collision rate per disc ω = `c` √T (physics.md (16.6)).
pub fn driven_steady_temperature(xi2: f64, mass: f64, n: usize, e: f64, c: f64) -> f64 {
    let injection = mass * xi2 * (1.0 - 1.0 / n as f64);
    let loss = (1.0 - e * e) * (1.0 + 3.0 * driven_a2(e) / 16.0) * c / 2.0;
    (injection / loss).powf(2.0 / 3.0)
}

/// Enskog's c = ω/√T = 2 σ n g(σ) √(π/m) (physics.md (7.2)) of one species of
/// diameter 2a and mass m at number density `density`, with Henderson's g(σ) at
/// packing fraction `eta` (7.6).
pub fn enskog_rate_coefficient(species: &Species, density: f64, eta: f64) -> f64 {
    let sigma = 2.0 * species.radius;
    2.0 * sigma
        * density
        * henderson_contact_value(eta)
        * (std::f64::consts::PI / species.mass).sqrt()
}

/// The thermostat report of the run `run` with `thermostat` and pair rule
/// `restitution`, from its temperature report and its measured collision rate
/// per disc `omega` (1/time).
pub(super) fn report(
    thermostat: &Thermostat,
    restitution: Restitution,
    run: &RunDescription,
    temperature: &TemperatureReport,
    omega: f64,
) -> ThermostatReport {
    let n = run.n();
    // K = kT f / 2 over the snapshots used.
    let k = temperature.kt * temperature.dof as f64 / 2.0;
    let kt_all = k / n as f64;
    let mut out = ThermostatReport {
        kind: thermostat.kind(),
        target_kt: None,
        rate: None,
        xi2: None,
        interval: None,
        kt_all_components: kt_all,
        relative_difference: None,
        granular_temperature: None,
        predicted_temperature: None,
        predicted_temperature_from_rate: None,
        a2_theory: None,
    };
    match *thermostat {
        Thermostat::Andersen { kt, rate } => {
            out.target_kt = Some(kt);
            out.rate = Some(rate);
            out.relative_difference = Some(kt_all / kt - 1.0);
        }
        Thermostat::Driven { xi2, interval } => {
            out.xi2 = Some(xi2);
            out.interval = Some(interval);
            let t = k / n as f64;
            out.granular_temperature = Some(t);
            if let (Restitution::Normal(e), [s]) = (restitution, &run.species[..]) {
                out.a2_theory = Some(driven_a2(e));
                let area = run.sim_box.size.x * run.sim_box.size.y;
                let eta = packing_fraction(&run.species, &run.sim_box);
                let c = enskog_rate_coefficient(s, n as f64 / area, eta);
                out.predicted_temperature = Some(driven_steady_temperature(xi2, s.mass, n, e, c));
                let measured = omega / t.sqrt();
                out.predicted_temperature_from_rate = (measured.is_finite() && measured > 0.0)
                    .then(|| driven_steady_temperature(xi2, s.mass, n, e, measured));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (16.7) at e = 0.9: 16 · 0.1 · (1 − 1.62) / (185 − 137.7 + 2.43) =
    /// −0.992 / 49.73 = −0.019948; 0 at e = 1 and at e = 1/√2.
    #[test]
    fn the_driven_a2_is_van_noije_and_ernsts() {
        assert!((driven_a2(0.9) + 0.992 / 49.73).abs() < 1e-12);
        assert_eq!(driven_a2(1.0), 0.0);
        assert!(driven_a2(0.5f64.sqrt()).abs() < 1e-15);
    }

    /// Hand-worked: ξ² = 0.17, m = 1, N = 2000, e = 0.9, c = 1.7866: injection
    /// 0.17 · 0.9995 = 0.169915, loss coefficient 0.19 · (1 − 0.0037403) · 1.7866/2
    /// = 0.169089, T = (1.004886)^(2/3) = 1.003252. Four times ξ² gives 4^(2/3)
    /// times T.
    #[test]
    fn the_steady_temperature_balances_injection_and_loss() {
        let t = driven_steady_temperature(0.17, 1.0, 2000, 0.9, 1.7866);
        let a2 = driven_a2(0.9);
        let loss = 0.19 * (1.0 + 3.0 * a2 / 16.0) * 1.7866 / 2.0;
        assert!((t - (0.169915 / loss).powf(2.0 / 3.0)).abs() < 1e-12);
        assert!((t - 1.00325).abs() < 1e-4, "{t}");
        let t4 = driven_steady_temperature(0.68, 1.0, 2000, 0.9, 1.7866);
        assert!((t4 / t - 4f64.powf(2.0 / 3.0)).abs() < 1e-12);
    }

    /// Enskog at η = 0.25, σ = 1, m = 1: n = 4η/π = 0.31831, Henderson g(σ) =
    /// (1 − 7/64)/0.5625 = 1.583333, c = 2 · 0.31831 · 1.583333 · √π = 1.78660.
    #[test]
    fn the_enskog_coefficient_is_two_sigma_n_g_root_pi() {
        let n = 4.0 * 0.25 / std::f64::consts::PI;
        let c = enskog_rate_coefficient(&Species::reference(1), n, 0.25);
        assert!((c - 1.78660).abs() < 1e-5, "{c}");
    }
}
