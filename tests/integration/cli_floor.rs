//! A vibrated granular bed from the command line (physics.md §18): `carom run`
//! on the example, then `carom analyze` reports the floor (A, f, Γ = Aω²/g) and
//! the powers in and out over its window, equal within a few per cent in the
//! steady state, and takes out the input-free energy budget and Haff's law.

use crate::cli_common::{carom, json_of, ok, scratch};

#[test]
fn a_shaken_bed_is_analysed_with_its_floor_power() {
    let dir = scratch("bed");
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/data/vibrated-bed.json");
    ok(&carom(
        &dir,
        &[
            "run",
            example,
            "-o",
            "bed.mcap",
            "-q",
            "--set",
            "stop.duration=200",
            "--set",
            "log.checkpoint_interval=20",
        ],
    ));
    let r = json_of(&carom(
        &dir,
        &["analyze", "bed.mcap", "--json", "--no-structure", "-q"],
    ));
    let f = &r["floor"];
    assert_eq!(f["amplitude"], 0.5);
    assert!((f["frequency"].as_f64().unwrap() - 0.45).abs() < 1e-12);
    let omega = 2.0 * std::f64::consts::PI * 0.45;
    assert!((f["shaking_parameter"].as_f64().unwrap() - 0.5 * omega * omega).abs() < 1e-12);
    // The window starts at the first checkpoint after the analysis window's start.
    let start = r["window"]["equilibrate"].as_f64().unwrap();
    let w = f["window"].as_array().unwrap();
    assert!(w[0].as_f64().unwrap() >= start && w[0].as_f64().unwrap() < start + 20.0 + 1e-9);
    assert_eq!(w[1].as_f64().unwrap(), 200.0);
    let (p_in, p_out) = (
        f["power_in"].as_f64().unwrap(),
        f["power_out"].as_f64().unwrap(),
    );
    assert!(
        p_in > 0.0 && (p_in / p_out - 1.0).abs() < 0.05,
        "in {p_in}, out {p_out}"
    );
    assert!(
        r["inelastic"]["energy"].is_null() && r["inelastic"]["haff"].is_null(),
        "{}",
        r["inelastic"]
    );
    let text = ok(&carom(
        &dir,
        &["analyze", "bed.mcap", "--no-structure", "-q"],
    ));
    assert!(
        text.contains("vibrating floor (physics.md §18)")
            && text.contains("A = 0.500000, f = 0.450000, Γ = Aω²/g"),
        "{text}"
    );
}
