//! The cooling granular gas (data/granular-cooling.json, e = 0.9) from the
//! command line: `carom analyze`'s advice fits a gas that never becomes
//! stationary, its snapshots are spaced by the collisions counted between them,
//! ω is given at the start and the end of the window, Haff's law is predicted
//! from Enskog's ω_E with a verdict, and a log with a snapshot schedule still
//! gets its Sonine coefficient past `--equilibrate`.

use crate::cli_common::{carom, json_of, ok, scratch};

const EXAMPLE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data/granular-cooling.json");

/// The example shortened to t = 50 with a snapshot every 0.6 (the issue's
/// 168-snapshot log at half length).
fn cooling_log(dir: &std::path::Path, extra: &[&str]) {
    let mut args = vec![
        "run",
        EXAMPLE,
        "-o",
        "g.mcap",
        "-q",
        "--force",
        "--set",
        "stop.duration=50",
    ];
    for s in extra {
        args.extend(["--set", s]);
    }
    ok(&carom(dir, &args));
}

#[test]
fn a_cooling_gas_gets_advice_and_spacing_that_fit_it() {
    let dir = scratch("cooling");
    cooling_log(&dir, &["log.snapshot_interval=0.6"]);
    let text = ok(&carom(&dir, &["analyze", "g.mcap", "--no-structure", "-q"]));
    assert!(!text.contains("equilibrate longer"), "{text}");
    assert!(!text.contains("run longer"), "{text}");
    assert!(!text.contains("\n  ω  "), "a single mean ω: {text}");
    for want in [
        "ω at the start",
        "ω at the end",
        "cooling rate from Enskog's ω_E",
        "second Sonine order",
        "self-consistency",
    ] {
        assert!(text.contains(want), "no {want:?}: {text}");
    }
    let verdict = text
        .lines()
        .skip_while(|l| !l.starts_with("cooling rate from Enskog"))
        .find(|l| l.trim_start().starts_with("verdict"))
        .expect("a verdict");
    assert!(verdict.contains("cools"), "{verdict}");
    for line in text.lines() {
        assert!(line.chars().count() <= 100, "{line}");
    }

    let r = json_of(&carom(
        &dir,
        &["analyze", "g.mcap", "--json", "--no-structure", "-q"],
    ));
    let w = &r["window"];
    assert_eq!(w["every_collisions"], 5.0);
    let used = w["snapshot_times"].as_array().unwrap().len();
    // Every used pair ≥ 5 collisions per disc apart, counted: no warning.
    let spacing = w["spacing_collisions"].as_f64().unwrap();
    assert!(spacing >= 5.0, "{w}");
    assert!(!text.contains("warning: the snapshots used"), "{text}");
    // As many as the collisions in the window allow: C/(5 + δ) + 1 with C the
    // collisions per disc in the window and δ ≤ the most between two snapshots
    // (ω at the start × 0.6).
    let c = &r["collision_rate"];
    let window = c["window"].as_array().unwrap();
    let span = window[1].as_f64().unwrap() - window[0].as_f64().unwrap();
    let collisions = c["per_disc"].as_f64().unwrap() * span;
    let delta = c["start"]["per_disc"].as_f64().unwrap() * 0.6 * 1.2;
    let allowed = (collisions / (5.0 + delta)).floor() as usize + 1;
    assert!(used >= allowed, "{used} used, {collisions} collisions: {w}");
    // The old rule, 5/ω with ω the whole log's mean, spaced them in time: its
    // snapshots at the end of the window were fewer than 4 collisions apart.
    let end = &c["end"];
    let n = r["n"].as_f64().unwrap();
    let log_rate = 2.0 * c["logged_pair_collisions"].as_f64().unwrap() / (n * 50.0);
    let old_last_gap = end["per_disc"].as_f64().unwrap() * 5.0 / log_rate;
    assert!(old_last_gap < 4.0, "{old_last_gap}");
    // ω falls as √T between the window's ends.
    let (a, b) = (&c["start"], &c["end"]);
    let ratio = a["per_disc"].as_f64().unwrap() / b["per_disc"].as_f64().unwrap();
    let sqrt_t = (a["kt"].as_f64().unwrap() / b["kt"].as_f64().unwrap()).sqrt();
    assert!(ratio > 1.5 && (ratio / sqrt_t - 1.0).abs() < 0.15, "{c}");
    // The Enskog check is in the JSON with its verdict.
    let h = &r["inelastic"]["haff"]["enskog"];
    assert!(
        h["agrees"].is_boolean() && h["ratio"].as_f64().unwrap() > 0.0,
        "{h}"
    );
    let s = &r["inelastic"]["sonine"];
    assert!(s["theory_second_order"].as_f64().unwrap() < s["theory"].as_f64().unwrap());
}

/// Log-spaced snapshots in one block over the whole run: the block's only start
/// is t = 0, so a rule that took block starts only used none past
/// `--equilibrate 5` and dropped the Sonine coefficient silently.
#[test]
fn a_snapshot_schedule_past_equilibrate_still_gives_the_sonine_coefficient() {
    let dir = scratch("cooling-schedule");
    cooling_log(
        &dir,
        &[
            "stop.duration=40",
            "log.snapshot_interval=40",
            "log.snapshot_schedule.points=30",
            "log.snapshot_schedule.first=0.05",
        ],
    );
    let r = json_of(&carom(
        &dir,
        &[
            "analyze",
            "g.mcap",
            "--json",
            "--no-structure",
            "-q",
            "--equilibrate",
            "5",
        ],
    ));
    let used = r["window"]["snapshot_times"].as_array().unwrap().len();
    assert!(used >= 2, "{}", r["window"]);
    let s = &r["inelastic"]["sonine"];
    assert!(s["snapshots"].as_u64().unwrap() >= 2, "{s}");
    assert!(s["a2"].as_f64().unwrap().abs() < 0.2, "{s}");
    // Past the end of the snapshots: no Sonine coefficient, and the report says why.
    let r = json_of(&carom(
        &dir,
        &[
            "analyze",
            "g.mcap",
            "--json",
            "--no-structure",
            "-q",
            "--equilibrate",
            "39.9",
        ],
    ));
    assert!(r["inelastic"]["sonine"].is_null());
    let why = r["not_computed"]
        .as_array()
        .unwrap()
        .iter()
        .find(|n| n["quantity"] == "inelastic.sonine")
        .expect("inelastic.sonine listed");
    assert!(why["why"].as_str().unwrap().contains("used"), "{why}");
}
