//! Every example configuration in data/ does what data/README.md's table says,
//! with its shipped seed: each is run (shortened with `--set` where the claim
//! survives) and its claim checked from `carom analyze --json`. The full-length
//! runs of the slow examples are #[ignore]d: `cargo test --release --test integration examples::
//! -- --ignored`.

use crate::cli_common::*;
use serde_json::Value;

/// `carom run data/<name>.json` with `sets`, then `carom analyze --json` with
/// `analyze` arguments.
fn example(name: &str, sets: &[&str], analyze: &[&str]) -> Value {
    let dir = scratch(&format!("example-{name}"));
    let config = format!("{}/data/{name}.json", env!("CARGO_MANIFEST_DIR"));
    let mut args = vec!["run", config.as_str(), "--quiet", "--out", "x.mcap"];
    for s in sets {
        args.extend(["--set", s]);
    }
    ok(&carom(&dir, &args));
    let mut a = vec!["analyze", "x.mcap", "--quiet", "--json"];
    a.extend(analyze);
    json_of(&carom(&dir, &a))
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// Every species' Maxwell–Boltzmann verdict passed.
fn maxwell_boltzmann_passes(r: &Value) {
    let mb = r["maxwell_boltzmann"].as_array().expect("velocity tests");
    assert!(!mb.is_empty());
    for s in mb {
        assert_eq!(s["passed"], true, "{s}");
    }
}

#[test]
fn thermostatted_fluid_is_maxwell_boltzmann_at_the_thermostat_temperature() {
    let r = example("thermostatted-fluid", &[], &[]);
    maxwell_boltzmann_passes(&r);
    let t = &r["thermostat"];
    assert_eq!(t["target_kt"], 2.0);
    assert!(f(&t["relative_difference"]).abs() < 0.01, "{t}");
}

#[test]
fn atmosphere_fit_agrees_with_the_hydrostatic_profile_not_the_ideal_law() {
    let r = example("atmosphere", &[], &[]);
    let b = &r["gravity"]["barometric"][0];
    assert!(b["not_applicable"].is_null(), "{b}");
    assert!(f(&b["deviation_hydrostatic_se"]).abs() < 3.0, "{b}");
    // The ideal law is the wrong model at this density, and the fit shows it.
    assert!(f(&b["deviation_se"]) < -3.0, "{b}");
}

#[test]
fn vibrated_bed_balances_power_and_compares_no_equilibrium_law() {
    let r = example("vibrated-bed", &[], &[]);
    let b = &r["gravity"]["barometric"][0];
    assert!(b["not_applicable"].is_string(), "{b}");
    assert!(
        b["deviation_se"].is_null() && b["beta_hydrostatic"].is_null(),
        "{b}"
    );
    assert!(
        r["inelastic"]["sonine"]["theory"].is_null(),
        "{}",
        r["inelastic"]
    );
    let fl = &r["floor"];
    let (pin, pout) = (f(&fl["power_in"]), f(&fl["power_out"]));
    assert!((pin / pout - 1.0).abs() < 0.05, "{fl}");
}

/// Shortened: the drift check sees Ψ6 still rising right after growth.
#[test]
fn compression_crystal_drift_check_sees_the_rise_after_growth() {
    let r = example(
        "compression-crystal",
        &["stop.duration=330", "log.snapshot_interval=2"],
        &["--equilibrate", "276"],
    );
    let d = &r["bond_order"]["drift"];
    assert!(!d.is_null(), "{}", r["bond_order"]);
    assert!(f(&d["difference_std_errors"]) > 3.0, "{d}");
}

#[test]
#[ignore = "a 600-time-unit compression, about a minute"]
fn compression_crystal_reaches_its_plateau() {
    let r = example("compression-crystal", &[], &["--equilibrate", "350"]);
    let b = &r["bond_order"];
    println!(
        "compression-crystal: |Psi6| = {} ± {}, drift {}",
        b["global"], b["global_std_error"], b["drift"]
    );
    assert!(f(&b["global"]) > 0.6, "{b}");
    assert_eq!(b["drift"]["drifting"], false, "{b}");
}

#[test]
fn dense_fluid_reports_its_drift() {
    let r = example("dense-fluid", &["species.0.count=2000"], &[]);
    let p = &r["pressure"];
    assert!(!p["drift"].is_null(), "{p}");
    // Not yet at the reference: the run is too short to reach Z ≈ 9.83.
    assert!(f(&p["z"]) < 9.83, "{p}");
}

/// The contact theorem's Z agrees with the virial Z within 3 standard errors.
fn contact_theorem_holds(r: &Value) {
    let ct = &r["pair_correlation"]["contact_theorem"];
    assert!(f(&ct["difference_std_errors"]).abs() < 3.0, "{ct}");
}

#[test]
fn equilibrium_examples_are_maxwell_boltzmann() {
    for name in ["dilute-gas", "binary-mixture", "channel"] {
        let r = example(name, &["stop.duration=20"], &[]);
        maxwell_boltzmann_passes(&r);
        if name != "channel" {
            contact_theorem_holds(&r);
        }
        if name == "dilute-gas" {
            let e = &r["enskog"];
            assert!(
                f(&e["difference"]).abs() < 3.0 * f(&e["difference_std_error"]),
                "{e}"
            );
            // A few mean free times only: the transport window is flagged.
            let v = &r["transport"]["viscosity"]["reliability"];
            assert_eq!(v["reliable"], false, "{v}");
            assert!(v["why"][0]
                .as_str()
                .unwrap()
                .contains("shorter than the documented"));
        }
    }
}

#[test]
fn glass_mixture_is_a_dense_disordered_fluid() {
    let r = example("glass-mixture", &["stop.duration=10"], &[]);
    assert!((f(&r["packing_fraction"]) - 0.78).abs() < 1e-9);
    maxwell_boltzmann_passes(&r);
    contact_theorem_holds(&r);
    // No crystal: the global bond order of a disordered mixture is small.
    assert!(f(&r["bond_order"]["global"]) < 0.1, "{}", r["bond_order"]);
}

#[test]
fn granular_cooling_closes_its_energy_budget_and_is_maxwellian_when_scaled() {
    let r = example(
        "granular-cooling",
        &["species.0.count=2000", "stop.duration=40"],
        &[],
    );
    let e = &r["inelastic"]["energy"];
    assert!(f(&e["relative_residual"]).abs() < 1e-12, "{e}");
    maxwell_boltzmann_passes(&r);
    assert_eq!(
        r["maxwell_boltzmann"][0]["scaled_to_snapshot_temperature"],
        true
    );
}

#[test]
fn driven_granular_settles_at_the_energy_balance_temperature() {
    let r = example("driven-granular", &["stop.duration=40"], &[]);
    let t = &r["thermostat"];
    let (tg, predicted) = (
        f(&t["granular_temperature"]),
        f(&t["predicted_temperature"]),
    );
    assert!((tg / predicted - 1.0).abs() < 0.03, "{t}");
    maxwell_boltzmann_passes(&r);
}

#[test]
fn two_discs_collide_ten_times_and_the_report_says_what_two_cannot_give() {
    let r = example("two-discs", &[], &[]);
    let c = &r["collision_rate"];
    assert_eq!(
        c["logged_pair_collisions"].as_u64().unwrap()
            + c["logged_wall_collisions"].as_u64().unwrap(),
        10,
        "{c}"
    );
    let missing = r["not_computed"].to_string();
    assert!(
        missing.contains("bond_order") && missing.contains("structure_factor"),
        "{missing}"
    );
}
