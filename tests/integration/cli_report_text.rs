//! What `carom analyze` says, read as a person reads it: every line of the text
//! report fits a terminal of 100 columns; no quantity is printed as a number it
//! cannot be (NaN, an error of NaN, a division by zero tests); a quantity that
//! cannot be computed is named with the reason, in the text and in the JSON;
//! the collision rate says where its collisions were counted; S(k)'s first peak
//! is the neighbour shell, not the small-k rise of a clustering gas.

use std::path::Path;

use crate::cli_common::{carom, json_of, ok, scratch};

fn data(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// Run `args` into `log`, then the text report of it.
fn report(dir: &Path, log: &str, args: &[&str]) -> String {
    let mut run = vec!["run", "--out", log, "-q"];
    run.extend(args);
    ok(&carom(dir, &run));
    ok(&carom(dir, &["analyze", log, "-q"]))
}

fn assert_readable(name: &str, text: &str) {
    for line in text.lines() {
        assert!(
            line.chars().count() <= 100,
            "{name}: a line of {} columns:\n{line}",
            line.chars().count()
        );
        for bad in ["NaN", "inf", "α/0", "0.00e0"] {
            assert!(!line.contains(bad), "{name}: '{bad}' printed:\n{line}");
        }
    }
}

#[test]
fn every_line_fits_a_terminal_and_no_number_is_made_up() {
    let dir = scratch("width");
    let two = data("two-discs.json");
    let granular = data("granular-cooling.json");
    let atmosphere = data("atmosphere.json");
    let cases: [(&str, Vec<&str>); 5] = [
        (
            "fluid",
            vec!["--set", "species.0.count=500", "--set", "stop.duration=20"],
        ),
        ("two", vec![two.as_str()]),
        (
            "granular",
            vec![
                granular.as_str(),
                "--set",
                "species.0.count=2000",
                "--set",
                "stop.duration=40",
            ],
        ),
        (
            "atmosphere",
            vec![atmosphere.as_str(), "--set", "stop.duration=100"],
        ),
        (
            "quiet",
            vec![
                "--set",
                "species.0.count=500",
                "--set",
                "stop.duration=20",
                "--set",
                "log.collisions=false",
            ],
        ),
    ];
    for (name, args) in cases {
        let log = format!("{name}.mcap");
        let text = report(&dir, &log, &args);
        assert_readable(name, &text);
        assert!(text.lines().count() > 15, "{name}: {text}");
    }
}

#[test]
fn two_discs_get_no_bond_order_and_no_contact_error_and_say_why() {
    let dir = scratch("two");
    let text = report(&dir, "two.mcap", &[&data("two-discs.json")]);
    // The velocity tests: none made, and said so rather than "α/0".
    assert!(text.contains("not tested"), "{text}");
    assert!(!text.contains("bond order ψ6"), "{text}");
    let j = json_of(&carom(&dir, &["analyze", "two.mcap", "--json", "-q"]));
    assert!(j["bond_order"].is_null() && j["orientational_correlation"].is_null());
    let missing: Vec<&str> = j["not_computed"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n["quantity"].as_str().unwrap())
        .collect();
    for q in [
        "bond_order",
        "orientational_correlation",
        "structure_factor",
        "transport",
    ] {
        assert!(missing.contains(&q), "{q} not explained: {missing:?}");
        assert!(text.contains(q), "{q} not in the text:\n{text}");
    }
    // g(σ⁺) from the pooled g, but most time blocks hold no pair near contact:
    // no error, and the reason in its place (not "± NaN").
    let c = &j["pair_correlation"]["pairs"][0]["contact"];
    assert!(c["value"].as_f64().unwrap() > 0.0, "{c}");
    assert!(c["std_error"].is_null(), "{c}");
    assert!(
        c["no_error"].as_str().unwrap().contains("time blocks"),
        "{c}"
    );
    assert!(text.contains("error not computed"), "{text}");
}

#[test]
fn the_collision_rate_says_where_it_counted() {
    let dir = scratch("counted");
    let base = ["--set", "species.0.count=400", "--set", "stop.duration=10"];
    let mut quiet = base.to_vec();
    quiet.extend(["--set", "log.collisions=false"]);
    let logged = report(&dir, "logged.mcap", &base);
    let unlogged = report(&dir, "unlogged.mcap", &quiet);
    assert!(
        logged.contains("pair and 0 wall collisions in the log"),
        "{logged}"
    );
    assert!(
        !unlogged.contains("wall collisions in the log"),
        "{unlogged}"
    );
    assert!(
        unlogged.contains("running collision counts of /thermo"),
        "{unlogged}"
    );
    let j = json_of(&carom(&dir, &["analyze", "unlogged.mcap", "--json", "-q"]));
    assert_eq!(j["collision_rate"]["counted_from"], "thermo");
    assert!(j["collision_rate"]["per_disc"].as_f64().unwrap() > 0.0);
    let missing = j["not_computed"].to_string();
    assert!(missing.contains("did not log them"), "{missing}");
}

#[test]
fn the_first_peak_of_a_clustering_gas_is_its_neighbour_shell() {
    let dir = scratch("peak");
    ok(&carom(
        &dir,
        &[
            "run",
            &data("granular-cooling.json"),
            "--out",
            "g.mcap",
            "-q",
            "--set",
            "species.0.count=4000",
            "--set",
            "stop.duration=60",
        ],
    ));
    let j = json_of(&carom(&dir, &["analyze", "g.mcap", "--json", "-q"]));
    let f = &j["structure_factor"];
    let peak = f["peak_k"].as_f64().unwrap();
    // σ = 1: the shell of neighbours is near 2π; below π S(k) is the clusters.
    assert!(peak >= std::f64::consts::PI, "first peak at k = {peak}");
    // The same rule gives the dynamics' k* (a snapshot's S(k), not the mean).
    let k_star = j["dynamics"]["k_star"].as_f64().unwrap();
    assert!(
        (k_star - peak).abs() < 1.0,
        "k* = {k_star}, S(k) peak {peak}"
    );
    // And the gas does cluster: S at the smallest k is above the peak's height.
    let s0 = f["s"][0].as_f64().unwrap();
    assert!(f["peak_s"].as_f64().unwrap() > 0.0 && s0.is_finite());
}
