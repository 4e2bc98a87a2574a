//! `carom analyze` shows the transport report (physics.md §14): in the JSON as
//! `transport`, in the text as its lines, and with `--plot` as the figures
//! `vacf_exact`, `msd_exact`, `helfand_viscosity` and `helfand_conductivity`; a
//! walled run gets `transport: null` and none of those figures.

use crate::cli_common::*;

use std::path::Path;

use serde_json::Value;

/// `v` as a finite number.
fn finite(v: &Value) -> f64 {
    let x = v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"));
    assert!(x.is_finite(), "{v}");
    x
}

const FIGURES: [&str; 4] = [
    "vacf_exact",
    "msd_exact",
    "helfand_viscosity",
    "helfand_conductivity",
];

/// 200 discs at η = 0.3 for 50 time units: ω ≈ 2.4 pair collisions per disc per
/// unit time (the Enskog rate with χ ≈ 1.77), so about 120 per disc, elastic and
/// periodic with every collision logged: the replay must match every snapshot.
#[test]
fn an_elastic_periodic_run_shows_its_transport_in_json_text_and_figures() {
    let dir = scratch("transport");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            "--out",
            "t.mcap",
            "--set",
            "species.0.count=200",
            "--set",
            "box.packing_fraction=0.3",
            "--set",
            "stop.duration=50",
            "--set",
            "seed=3",
        ],
    ));
    let r = json_of(&carom(
        &dir,
        &["analyze", "t.mcap", "--quiet", "--json", "--plot", "figs"],
    ));
    let t = &r["transport"];
    assert_eq!(t["n"], 200, "{t}");
    assert!(
        finite(&t["viscosity"]["value_helfand"]["value"]) > 0.0,
        "{t}"
    );
    assert!(
        finite(&t["species"][0]["diffusion_msd"]["value"]) > 0.0,
        "{t}"
    );
    assert!(
        finite(&t["species"][0]["diffusion_msd"]["std_error"]) > 0.0,
        "{t}"
    );
    assert!(t["snapshots_checked"].as_u64().unwrap() > 0, "{t}");
    assert_eq!(t["snapshots_mismatched"], 0, "{t}");
    assert!(finite(&t["thermal_conductivity"]["value_green_kubo"]["value"]) > 0.0);
    for name in FIGURES {
        let png = std::fs::read(dir.join(format!("figs/{name}.png"))).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{name}");
        let svg = std::fs::read_to_string(dir.join(format!("figs/{name}.svg"))).unwrap();
        assert!(
            svg.contains("<svg") && svg.contains("lag τ/τ₀ (τ₀ = σ√(m/kT)"),
            "{name}"
        );
    }
    let svg = std::fs::read_to_string(dir.join("figs/helfand_viscosity.svg")).unwrap();
    for label in [
        "Einstein–Helfand",
        "Green–Kubo",
        "Enskog η_E",
        "(mass/time)",
    ] {
        assert!(svg.contains(label), "{label}");
    }
    let svg = std::fs::read_to_string(dir.join("figs/vacf_exact.svg")).unwrap();
    assert!(svg.contains("mode coupling"));

    // Without the structure: no g(r), ψ6, g6 or S(k), the same transport (the
    // same events in the same order).
    let quick = json_of(&carom(
        &dir,
        &["analyze", "t.mcap", "--quiet", "--json", "--no-structure"],
    ));
    for key in [
        "pair_correlation",
        "bond_order",
        "orientational_correlation",
        "structure_factor",
    ] {
        assert!(!r[key].is_null() && quick[key].is_null(), "{key}");
    }
    assert_eq!(quick["transport"], r["transport"]);

    let text = ok(&carom(&dir, &["analyze", "t.mcap", "--quiet"]));
    let n = t["snapshots_checked"].as_u64().unwrap();
    for line in [
        "transport (exact collision replay".to_string(),
        "  N                 200 discs".to_string(),
        format!("velocities matched all {n} snapshots"),
        "  η Green–Kubo      ".to_string(),
        "  λ Green–Kubo      ".to_string(),
        "grow like ln τ".to_string(),
    ] {
        assert!(text.contains(&line), "{line} missing from\n{text}");
    }
    // One quantity per line, ≤ 100 columns, in both sections.
    let section = text
        .split("dynamics (snapshot MSD")
        .nth(1)
        .expect("dynamics");
    for line in section.lines() {
        assert!(line.chars().count() <= 100, "too long: {line}");
    }
    // The window in t_c, beside the documented one; each unreliable value says
    // why on the next line, and the JSON says the same.
    let w = &t["window_collision_times"];
    assert!(text.contains(&format!(
        "= [{:.1}, {:.1}] t_c  (documented [10, 100] t_c)",
        finite(&w[0]),
        finite(&w[1])
    )));
    for (name, rel) in [
        ("  D    ", &t["species"][0]["diffusion_reliability"]),
        ("  η    ", &t["viscosity"]["reliability"]),
        ("  λ    ", &t["thermal_conductivity"]["reliability"]),
    ] {
        let transport = text
            .split("transport (exact collision replay")
            .nth(1)
            .unwrap();
        let line = transport.lines().find(|l| l.starts_with(name)).expect(name);
        let reliable = rel["reliable"].as_bool().unwrap();
        assert_eq!(line.ends_with("UNRELIABLE"), !reliable, "{line} {rel}");
        assert_eq!(line.ends_with("  reliable"), reliable, "{line} {rel}");
        assert_eq!(rel["why"].as_array().unwrap().is_empty(), reliable, "{rel}");
    }
}

/// The dilute gas (data/dilute-gas.json, φ = 0.05, t_c ≈ 4) run for 100 time
/// units: the window is a few t_c, far short of [10, 100] t_c, and the running
/// D(τ) still climbs over it (the VACF has not decayed at τ ≈ t_c): D is flagged
/// for both reasons, η and λ at least for the window, in the JSON and the text.
#[test]
fn a_short_window_in_a_dilute_gas_is_flagged_unreliable() {
    let dir = scratch("dilute-flags");
    let cfg = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/dilute-gas.json");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            cfg.to_str().unwrap(),
            "--out",
            "d.mcap",
            "--set",
            "stop.duration=100",
        ],
    ));
    let r = json_of(&carom(
        &dir,
        &["analyze", "d.mcap", "--quiet", "--json", "--no-structure"],
    ));
    let t = &r["transport"];
    assert!(
        finite(&t["window_collision_times"][1]) < 10.0,
        "{}",
        t["window"]
    );
    let d = &t["species"][0]["diffusion_reliability"];
    assert_eq!(d["reliable"], false, "{d}");
    let why: Vec<&str> = d["why"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|w| w.as_str())
        .collect();
    assert!(
        why.iter()
            .any(|w| w.contains("shorter than the documented")),
        "{d}"
    );
    assert!(why.iter().any(|w| w.contains("not levelled off")), "{d}");
    for q in ["viscosity", "thermal_conductivity"] {
        assert_eq!(t[q]["reliability"]["reliable"], false, "{q}");
    }
    assert_eq!(
        t["species"][0]["tail_amplitude_reliability"]["reliable"],
        false
    );
    let text = ok(&carom(
        &dir,
        &["analyze", "d.mcap", "--quiet", "--no-structure"],
    ));
    assert!(
        text.contains("why: running value has not levelled off"),
        "{text}"
    );
    assert!(text.matches("UNRELIABLE").count() >= 4, "{text}");
}

/// A channel (walls in y) has no transport report and none of its figures.
#[test]
fn a_walled_run_has_no_transport() {
    let dir = scratch("walled");
    let cfg = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/channel.json");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            cfg.to_str().unwrap(),
            "--out",
            "c.mcap",
            "--set",
            "species.0.count=100",
            "--set",
            "stop.duration=10",
        ],
    ));
    let r = json_of(&carom(
        &dir,
        &["analyze", "c.mcap", "--quiet", "--json", "--plot", "figs"],
    ));
    assert_eq!(r["periodic"], serde_json::json!([true, false]));
    assert!(r["transport"].is_null(), "{}", r["transport"]);
    for name in FIGURES {
        assert!(!dir.join(format!("figs/{name}.png")).exists(), "{name}");
    }
    let text = ok(&carom(&dir, &["analyze", "c.mcap", "--quiet"]));
    // No transport section; the list of what was not computed says why.
    assert!(
        !text.contains("transport (exact collision replay"),
        "{text}"
    );
    assert!(text.contains("needs a periodic box"), "{text}");
}
