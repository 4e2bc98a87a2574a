//! Unit tests of the `thermostat` section: parsing both kinds, the errors that
//! name the field, full collision records with a thermostat, and the examples.

use super::tests::{data_dir, err_of};
use super::*;
use carom_engine::Thermostat;
use carom_log::CollisionDetail;

fn spec(text: &str) -> carom_log::RunSpec {
    Config::from_json_str(text).unwrap().to_run_spec().unwrap()
}

#[test]
fn both_kinds_parse_into_the_engines_thermostat() {
    assert_eq!(spec("{}").thermostat, None);
    let a = spec(r#"{"thermostat": {"kind": "andersen", "kT": 2, "rate": 0.5}}"#);
    assert_eq!(
        a.thermostat,
        Some(Thermostat::Andersen { kt: 2.0, rate: 0.5 })
    );
    let d = spec(r#"{"thermostat": {"kind": "driven", "xi2": 0.1, "interval": 0.01}}"#);
    assert_eq!(
        d.thermostat,
        Some(Thermostat::Driven {
            xi2: 0.1,
            interval: 0.01
        })
    );
    // The thermostat travels with the stored configuration.
    assert!(a.config_json.contains("\"andersen\"") && a.config_json.contains("\"kT\""));
    // Velocities change between collisions: full records, never compact ones.
    assert_eq!(a.log.collision_record(), CollisionDetail::Full);
    assert_eq!(spec("{}").log.collision_record(), CollisionDetail::Compact);
}

#[test]
fn bad_thermostats_name_the_field_and_what_is_allowed() {
    for (text, field, says) in [
        (
            r#"{"thermostat": {"kind": "andersen", "kT": 0, "rate": 1}}"#,
            "thermostat.kT",
            "> 0",
        ),
        (
            r#"{"thermostat": {"kind": "andersen", "kT": 1, "rate": -2}}"#,
            "thermostat.rate",
            "> 0",
        ),
        (
            r#"{"thermostat": {"kind": "driven", "xi2": 0, "interval": 1}}"#,
            "thermostat.xi2",
            "> 0",
        ),
        (
            r#"{"thermostat": {"kind": "driven", "xi2": 1, "interval": 0}}"#,
            "thermostat.interval",
            "> 0",
        ),
        (
            r#"{"thermostat": {"kind": "andersen", "kT": 1, "rate": 1},
                "log": {"collision_detail": "compact"}}"#,
            "log.collision_detail",
            "\"full\"",
        ),
    ] {
        let e = err_of(text, &[]);
        let msg = e.to_string();
        assert_eq!(e.field(), Some(field), "{msg}");
        assert!(msg.contains(says) && msg.contains("allowed"), "{msg}");
    }
    // Missing, misspelt and unknown fields are serde's errors, naming them.
    for (text, word) in [
        (r#"{"thermostat": {"kind": "andersen", "kT": 1}}"#, "rate"),
        (
            r#"{"thermostat": {"kind": "nose-hoover", "kT": 1}}"#,
            "nose-hoover",
        ),
        (
            r#"{"thermostat": {"kind": "driven", "xi2": 1, "interval": 1, "kT": 1}}"#,
            "kT",
        ),
    ] {
        let msg = err_of(text, &[]).to_string();
        assert!(msg.contains("thermostat") && msg.contains(word), "{msg}");
    }
}

#[test]
fn the_thermostat_examples_are_what_their_names_say() {
    let get = |name: &str| load_config(Some(&data_dir().join(name)), &[]).unwrap();
    assert!(matches!(
        get("thermostatted-fluid.json").thermostat,
        Some(Thermostat::Andersen { kt, .. }) if kt == 2.0
    ));
    let driven = get("driven-granular.json");
    assert!(matches!(driven.thermostat, Some(Thermostat::Driven { .. })));
    assert!(!driven.params.restitution.is_elastic());
}
