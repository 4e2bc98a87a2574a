//! The shipped schema (data/config.schema.json) is the one generated from the
//! types, and it keeps what editors rely on: unknown fields refused everywhere.

use super::tests::data_dir;
use super::*;
use serde_json::Value;

const REGENERATE: &str =
    "cargo run -p carom-config --example write_schema > data/config.schema.json";

#[test]
fn shipped_schema_is_the_generated_one() {
    let shipped = std::fs::read_to_string(data_dir().join("config.schema.json")).unwrap();
    let generated = config_schema_json();
    if shipped != generated {
        let line = shipped
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .map_or("the end".to_owned(), |i| format!("line {}", i + 1));
        panic!(
            "data/config.schema.json differs from the schema generated from \
             crates/config/src/model.rs (first at {line}); regenerate it with\n    {REGENERATE}"
        );
    }
}

/// Every object schema that lists properties forbids others, as the reader
/// (`deny_unknown_fields`) does; `$defs` are reached through the whole tree.
#[test]
fn every_object_refuses_unknown_fields() {
    fn walk(v: &Value, at: &str, objects: &mut usize) {
        match v {
            Value::Object(m) => {
                if m.get("properties").is_some_and(Value::is_object) {
                    *objects += 1;
                    assert_eq!(
                        m.get("additionalProperties"),
                        Some(&Value::Bool(false)),
                        "schema object at {at} must set additionalProperties: false"
                    );
                }
                for (k, x) in m {
                    walk(x, &format!("{at}/{k}"), objects);
                }
            }
            Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    walk(x, &format!("{at}/{i}"), objects);
                }
            }
            _ => {}
        }
    }
    let schema = serde_json::to_value(config_schema()).unwrap();
    let mut objects = 0;
    walk(&schema, "#", &mut objects);
    // Config, box, species, collision, stop, log, snapshot_schedule, compression,
    // floor, compressed placement, the two placement and one velocity objects,
    // the per-axis boundary and the two thermostats.
    assert!(objects >= 15, "only {objects} object schemas");
}

/// The alias `"center-of-mass"` is in the schema (schemars lists only the
/// primary spelling; `model` adds it) and the reader takes both.
#[test]
fn schema_lists_both_spellings_of_centre_of_mass() {
    let schema = serde_json::to_value(config_schema()).unwrap();
    let model = &schema["$defs"]["CollisionModel"]["oneOf"];
    let spellings: Vec<&Value> = model
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|v| v.get("enum"))
        .flat_map(|e| e.as_array().unwrap())
        .collect();
    assert_eq!(spellings, ["centre-of-mass", "center-of-mass"]);
    for s in spellings {
        let v = serde_json::json!({"collision": {"model": s}});
        let c: Config = serde_json::from_value(v).unwrap();
        assert_eq!(c.collision.model, CollisionModel::CentreOfMass);
    }
}

/// The schema lets every optional field be `null` (schemars' `Option`), and so
/// does the reader: `null` is the field left out.
#[test]
fn null_is_an_absent_optional_field() {
    let nulls = serde_json::json!({
        "$schema": null, "description": null, "thermostat": null,
        "compression": null, "vibrating_floor": null,
        "box": {"packing_fraction": null, "aspect": null, "size": null, "wall_restitution": null},
        "collision": {"coefficient": null},
        "stop": {"duration": null, "max_time_without_collision": null},
        "log": {"collision_detail": null, "snapshot_schedule": null, "scene_interval": null},
    });
    let c: Config = serde_json::from_value(nulls).unwrap();
    assert_eq!(c, Config::default());
    let v = serde_json::json!({"placement": {"compressed": {"start_packing_fraction": null}}});
    let c: Config = serde_json::from_value(v).unwrap();
    let PlacementConfig::Compressed(p) = c.placement else {
        panic!("{:?}", c.placement)
    };
    assert_eq!(p.start_packing_fraction, None);
}
