//! The `neighbours` field: its names are the engine's, it reaches the engine,
//! `"auto"` is left out of the stored configuration (so old runs' configurations
//! are unchanged), `"lists"` is refused with gravity, compression or a vibrating
//! floor naming the field and what is allowed, and an unknown name lists the
//! allowed ones.

use super::tests::err_of;
use super::*;
use carom_engine::Neighbours;

fn spec(text: &str) -> carom_log::RunSpec {
    Config::from_json_str(text).unwrap().to_run_spec().unwrap()
}

#[test]
fn the_names_are_the_engines() {
    for n in [
        NeighboursConfig::Auto,
        NeighboursConfig::Cells,
        NeighboursConfig::Lists,
    ] {
        let name = serde_json::to_value(n).unwrap();
        assert_eq!(name, n.neighbours().name(), "{n:?}");
        assert_eq!(
            Neighbours::from_name(n.neighbours().name()),
            Some(n.neighbours())
        );
    }
}

#[test]
fn each_setting_reaches_the_engine() {
    for (name, engine) in [
        ("auto", Neighbours::Auto),
        ("cells", Neighbours::Cells),
        ("lists", Neighbours::Lists),
    ] {
        let s = spec(&format!(r#"{{"neighbours": "{name}"}}"#));
        assert_eq!(s.params.neighbours, engine, "{name}");
        // `--set neighbours=…` works like any field.
        let c = Config::from_json_with_sets("{}", "test", &[format!("neighbours={name}")]);
        assert_eq!(c.unwrap().to_run_spec().unwrap().params.neighbours, engine);
    }
    assert_eq!(spec("{}").params.neighbours, Neighbours::Auto);
}

#[test]
fn auto_is_left_out_of_the_stored_configuration() {
    for text in ["{}", r#"{"neighbours": "auto"}"#] {
        let s = spec(text);
        assert!(!s.config_json.contains("neighbours"), "{}", s.config_json);
        assert_eq!(s.config_json, spec("{}").config_json);
    }
    for name in ["cells", "lists"] {
        let s = spec(&format!(r#"{{"neighbours": "{name}"}}"#));
        let stored = format!("\"neighbours\": \"{name}\"");
        assert!(s.config_json.contains(&stored), "{}", s.config_json);
        // The stored configuration gives the same run.
        assert_eq!(spec(&s.config_json), s, "{name}");
    }
}

#[test]
fn lists_are_refused_without_straight_flights() {
    let walls = r#""box": {"boundary": {"x": "periodic", "y": "walls"}, "size": [20, 40]}, "species": [{"count": 50}]"#;
    for (text, says) in [
        (
            format!(r#"{{"neighbours": "lists", "gravity": 1, {walls}}}"#),
            "with gravity",
        ),
        (
            r#"{"neighbours": "lists", "compression": {"rate": 0.1, "target_packing_fraction": 0.7}}"#
                .to_owned(),
            "with compression",
        ),
        (
            format!(
                r#"{{"neighbours": "lists", {walls}, "vibrating_floor": {{"amplitude": 0.5, "frequency": 2}}}}"#
            ),
            "with a vibrating floor",
        ),
    ] {
        let e = err_of(&text, &[]);
        assert_eq!(e.field(), Some("neighbours"), "{text}: {e}");
        let msg = e.to_string();
        assert!(
            msg.contains(says) && msg.contains(r#"allowed: "auto" or "cells""#),
            "{text}: {msg}"
        );
        // The same settings are accepted on cells and by auto.
        for other in ["auto", "cells"] {
            let text = text.replace("\"lists\"", &format!("\"{other}\""));
            Config::from_json_str(&text).unwrap().to_run_spec().unwrap();
        }
    }
}

#[test]
fn an_unknown_name_lists_the_allowed_ones() {
    for (text, sets) in [
        (r#"{"neighbours": "grid"}"#, vec![]),
        ("{}", vec!["neighbours=verlet"]),
    ] {
        let e = err_of(text, &sets);
        assert_eq!(e.field(), Some("neighbours"), "{text} {sets:?}: {e}");
        let msg = e.to_string();
        assert!(
            msg.contains("allowed: one of `auto`, `cells`, `lists`"),
            "{text} {sets:?}: {msg}"
        );
    }
    // A value of the wrong type names the field too (serde's words for it).
    let e = err_of(r#"{"neighbours": 1}"#, &[]);
    assert_eq!(e.field(), Some("neighbours"), "{e}");
}
