//! Every example configuration in data/ does what data/README.md's table says,
//! with its shipped seed: each is run (shortened with `--set` where the claim
//! survives) and its claim checked from `carom analyze --json`. The full-length
//! runs of the slow examples are #[ignore]d: `cargo test --release --test examples
//! -- --ignored`.

mod cli_common;
use cli_common::*;
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

#[test]
fn equilibrium_examples_are_maxwell_boltzmann() {
    for name in ["dilute-gas", "binary-mixture", "channel"] {
        let r = example(name, &["stop.duration=20"], &[]);
        maxwell_boltzmann_passes(&r);
    }
}
