//! The thermostats against physics (physics.md §16), through the analysis of
//! `carom analyze` fed straight from the engine: Andersen at kT = 2 turns an
//! equal-speed start at kT = 1 into Maxwell–Boltzmann at kT = 2, and driving holds
//! an inelastic gas at the temperature the energy balance (16.6) predicts.

use crate::analysis_common::{analyse_state_with, fluid};
use carom_analysis::{
    driven_a2, driven_steady_temperature, enskog_rate_coefficient, AnalysisOptions, Report,
};
use carom_core::{Restitution, Species};
use carom_engine::{EngineParams, SystemSpec, Thermostat, ThermostatStats, Velocities};

/// Run `spec` with `params` and `thermostat` (seeded with the spec's seed) to
/// `t_end`, a snapshot every `dt`, and analyse it from `equilibrate` on.
fn run(
    spec: SystemSpec,
    params: EngineParams,
    thermostat: Thermostat,
    (t_end, dt, equilibrate): (f64, f64, f64),
) -> (Report, ThermostatStats) {
    let opts = AnalysisOptions {
        equilibrate: Some(equilibrate),
        every: Some(dt),
        ..Default::default()
    };
    let seed = spec.seed;
    let (report, engine) = analyse_state_with(
        spec.build().unwrap(),
        params,
        (t_end, dt),
        opts,
        None,
        |e| e.set_thermostat(Some(thermostat), seed).unwrap(),
    );
    (report, engine.thermostat_stats())
}

/// 1024 discs at η = 0.3, equal speeds at kT = 1, Andersen at kT = 2 and ν = 0.5
/// per disc (K relaxes as e^(−ν t): 10⁻⁴ of the way left at t = 20). Over
/// t ∈ [20, 120], snapshots every 2: the velocities pass the Maxwell–Boltzmann
/// tests (χ² and KS of the speeds, KS of each component) and kT = 2K/(2N) is 2
/// within 4 standard errors: one snapshot's kT has relative spread 1/√N = 3.1 %
/// (canonical), K's correlation time 1/ν = 2 leaves about 50/2.2 independent
/// snapshots, so SE ≈ 2 · 0.031/√23 = 0.013. Measured (seed 9, 2026-11-26):
/// kT = 2.0137 with f = 2N (+1.1 SE), χ² p = 0.87, KS p = 0.94, vx 0.077, vy 0.21.
#[test]
fn andersen_at_kt_2_gives_maxwell_boltzmann_at_kt_2() {
    let spec = fluid(1024, 0.3, 9, Velocities::EqualSpeed);
    let andersen = Thermostat::Andersen { kt: 2.0, rate: 0.5 };
    let (r, _) = run(spec, EngineParams::default(), andersen, (120.0, 2.0, 20.0));
    let mb = &r.maxwell_boltzmann[0];
    // kT = 2K/(2N): momentum is not conserved under Andersen.
    let kt = r.temperature.kt * r.temperature.dof as f64 / (2.0 * 1024.0);
    eprintln!(
        "Andersen: kT = {kt}, χ² p = {}, KS p = {}, vx p = {}, vy p = {}",
        mb.chi_square.p_value, mb.ks.p_value, mb.ks_vx.p_value, mb.ks_vy.p_value
    );
    assert!(mb.passed, "{:?} {:?}", mb.chi_square, mb.ks);
    assert!((kt - 2.0).abs() < 4.0 * 0.013, "kT = {kt}");
    // The MB tests' own temperature is that of the same snapshots.
    assert!((mb.kt - r.temperature.kt).abs() < 1e-9 * mb.kt);
}

/// A driven granular gas (e = 0.9, η = 0.25, 2000 discs) reaches the steady
/// granular temperature of the energy balance (16.6): injection m ξ² (1 − 1/N)
/// per disc against the loss (1 − e²)(1 + 3a2/16) ω T/2. With ω/√T measured in
/// the run the prediction tests the balance alone; with Enskog–Henderson's ω it
/// tests the kinetic theory too (Henderson's g(σ) is within 0.3 % at η = 0.25,
/// but velocity correlations of a driven gas raise the collision rate a little).
/// Driven from T = 1 with ξ² = 0.17 every 0.02 (1/28 of a mean free time);
/// T over t ∈ [20, 100].
///
/// First the kicks: the energy they put in over t = 100 is N ξ² (1 − 1/N) t on
/// average, its cross terms m v·Δv adding a relative standard error
/// √(2T/(N ξ² t)) = 0.77 % (within 4 of them). Then T against (16.6): molecular
/// chaos is assumed there, and noise-driven granular fluids build velocity
/// correlations (van Noije, Ernst, Brito & Orza 1997) that lower the energy lost
/// per collision, so T comes out a few per cent above; the test allows 4 % with
/// the measured rate and 5 % with Enskog–Henderson's.
/// Measured (seed 6, 2026-11-26): T = 1.0350 against 1.0117 (measured rate,
/// +2.3 %) and 1.0032 (Enskog–Henderson, +3.2 %).
#[test]
#[ignore = "about 20 s in release; run with --ignored"]
fn a_driven_granular_gas_holds_the_temperature_of_the_energy_balance() {
    let (n, eta, e, xi2) = (2000, 0.25, 0.9, 0.17);
    let spec = fluid(n, eta, 6, Velocities::MaxwellBoltzmann);
    let params = EngineParams {
        restitution: Restitution::Normal(e),
        tc: 1e-5,
        ..EngineParams::default()
    };
    let driven = Thermostat::Driven {
        xi2,
        interval: 0.02,
    };
    let area = spec.sim_box.area();
    let (r, kicks) = run(spec, params, driven, (100.0, 1.0, 20.0));
    let injected = kicks.energy_added / (n as f64 * 100.0);
    let expected = xi2 * (1.0 - 1.0 / n as f64);
    eprintln!("driven: injection {injected} per disc and unit time, expected {expected}");
    assert!(
        (injected / expected - 1.0).abs() < 4.0 * 0.0077,
        "{injected}"
    );
    let t = r.temperature.kt * r.temperature.dof as f64 / (2.0 * n as f64);
    let c_measured = r.collision_rate.per_disc / t.sqrt();
    let from_rate = driven_steady_temperature(xi2, 1.0, n, e, c_measured);
    let c_enskog = enskog_rate_coefficient(&Species::reference(n), n as f64 / area, eta);
    let from_enskog = driven_steady_temperature(xi2, 1.0, n, e, c_enskog);
    eprintln!(
        "driven: T = {t}; predicted {from_rate} (measured ω/√T = {c_measured}), \
         {from_enskog} (Enskog–Henderson c = {c_enskog}); a2 theory {}",
        driven_a2(e)
    );
    assert!((t / from_rate - 1.0).abs() < 0.04, "{t} vs {from_rate}");
    assert!((t / from_enskog - 1.0).abs() < 0.05, "{t} vs {from_enskog}");
}
