//! Unit tests that the JSON Schema (data/config.schema.json) and the Rust
//! configuration agree: the same field paths, the same enumerated spellings.

use super::tests::data_dir;
use super::*;
use serde_json::Value;
use std::collections::BTreeSet;

/// Every object key path a JSON value contains (`*` for array elements).
fn value_paths(v: &Value, prefix: &str, out: &mut BTreeSet<String>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                let p = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                out.insert(p.clone());
                value_paths(x, &p, out);
            }
        }
        Value::Array(a) => {
            for x in a {
                value_paths(x, &format!("{prefix}.*"), out);
            }
        }
        _ => {}
    }
}

/// Every property path a JSON Schema declares, following `$ref`, `oneOf`,
/// `anyOf` and `items`. Also checks that every object schema with properties
/// forbids additional ones (as `deny_unknown_fields` does).
fn schema_paths(schema: &Value, root: &Value, prefix: &str, out: &mut BTreeSet<String>) {
    if let Some(r) = schema.get("$ref").and_then(Value::as_str) {
        let ptr = r.strip_prefix('#').expect("local $ref");
        let target = root.pointer(ptr).unwrap_or_else(|| panic!("bad $ref {r}"));
        return schema_paths(target, root, prefix, out);
    }
    for key in ["oneOf", "anyOf", "allOf"] {
        if let Some(list) = schema.get(key).and_then(Value::as_array) {
            for s in list {
                schema_paths(s, root, prefix, out);
            }
        }
    }
    if let Some(items) = schema.get("items") {
        schema_paths(items, root, &format!("{prefix}.*"), out);
    }
    if let Some(props) = schema.get("properties").and_then(Value::as_object) {
        assert_eq!(
            schema.get("additionalProperties"),
            Some(&Value::Bool(false)),
            "schema object at `{prefix}` must set additionalProperties: false"
        );
        for (k, s) in props {
            let p = if prefix.is_empty() {
                k.clone()
            } else {
                format!("{prefix}.{k}")
            };
            out.insert(p.clone());
            schema_paths(s, root, &p, out);
        }
    }
}

fn load_schema() -> Value {
    let text = std::fs::read_to_string(data_dir().join("config.schema.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// A configuration in which every optional field is present (as far as fields
/// can coexist in one value), serialised.
fn maximal_values() -> Vec<Value> {
    let mut c = Config {
        schema: Some("x".into()),
        description: Some("x".into()),
        sim_box: BoxConfig {
            packing_fraction: Some(0.5),
            aspect: Some(1.0),
            size: Some([1.0, 1.0]),
            wall_restitution: Some(1.0),
            ..BoxConfig::default()
        },
        stop: StopConfig {
            duration: Some(1.0),
            collisions: Some(1),
            max_time_without_collision: Some(1.0),
        },
        gravity: 1.0,
        vibrating_floor: Some(FloorConfig {
            amplitude: 0.5,
            frequency: 1.0,
        }),
        compression: Some(GrowthConfig {
            rate: 1.0,
            target_packing_fraction: 0.5,
            rescale_interval: 1.0,
            max_reduced_pressure: 1e3,
        }),
        ..Config::default()
    };
    c.collision.coefficient = Some(1.0);
    c.log.collision_detail = Some(CollisionDetailConfig::Full);
    c.log.snapshot_schedule = Some(SnapshotScheduleConfig {
        points: 1,
        first: 0.5,
    });
    let mut d = c.clone();
    c.thermostat = Some(ThermostatConfig::Andersen { kt: 1.0, rate: 1.0 });
    d.thermostat = Some(ThermostatConfig::Driven {
        xi2: 1.0,
        interval: 1.0,
    });
    c.placement = PlacementConfig::Explicit(vec![[0.0, 0.0]]);
    c.velocities = VelocitiesConfig::Explicit(vec![[0.0, 0.0]]);
    d.sim_box.boundary = BoundaryConfig::PerAxis {
        x: AxisBoundary::Periodic,
        y: AxisBoundary::Walls,
    };
    let mut e = d.clone();
    e.placement = PlacementConfig::Compressed(CompressedPlacementConfig {
        rate: 1.0,
        start_packing_fraction: Some(0.3),
    });
    vec![
        serde_json::to_value(c).unwrap(),
        serde_json::to_value(d).unwrap(),
        serde_json::to_value(e).unwrap(),
    ]
}

#[test]
fn schema_lists_exactly_the_fields_rust_accepts() {
    let schema = load_schema();
    let mut from_schema = BTreeSet::new();
    schema_paths(&schema, &schema, "", &mut from_schema);
    let mut from_rust = BTreeSet::new();
    for v in maximal_values() {
        value_paths(&v, "", &mut from_rust);
    }
    // Array elements that are numbers (positions, size) have no key paths.
    let missing: Vec<_> = from_rust.difference(&from_schema).collect();
    let extra: Vec<_> = from_schema.difference(&from_rust).collect();
    assert!(
        missing.is_empty(),
        "fields missing from the schema: {missing:?}"
    );
    assert!(extra.is_empty(), "schema fields Rust rejects: {extra:?}");
    // And Rust accepts each of them: the maximal values deserialise (only the
    // range checks would object).
    for v in maximal_values() {
        let _: Config = serde_json::from_value(v).unwrap();
    }
}

/// Every string the schema enumerates for a field is accepted by Rust there,
/// and a string it does not list is rejected.
#[test]
fn schema_enums_match_rust_spellings() {
    fn enums(schema: &Value, root: &Value, prefix: &str, out: &mut Vec<(String, String)>) {
        if let Some(r) = schema.get("$ref").and_then(Value::as_str) {
            let target = root.pointer(r.strip_prefix('#').unwrap()).unwrap();
            return enums(target, root, prefix, out);
        }
        if let Some(list) = schema.get("enum").and_then(Value::as_array) {
            for s in list.iter().filter_map(Value::as_str) {
                out.push((prefix.to_owned(), s.to_owned()));
            }
        }
        for key in ["oneOf", "anyOf"] {
            if let Some(list) = schema.get(key).and_then(Value::as_array) {
                for s in list {
                    enums(s, root, prefix, out);
                }
            }
        }
        if let Some(props) = schema.get("properties").and_then(Value::as_object) {
            for (k, s) in props {
                let p = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                enums(s, root, &p, out);
            }
        }
    }
    let schema = load_schema();
    let mut list = Vec::new();
    enums(&schema, &schema, "", &mut list);
    assert!(list.len() >= 12, "{list:?}");
    for (path, s) in &list {
        let with = |value: &str| {
            let mut v = serde_json::json!({});
            // Per-axis boundaries need both axes.
            if let Some(parent) = path.strip_suffix(".x").or(path.strip_suffix(".y")) {
                apply_set(&mut v, &format!("{parent}={{}}")).unwrap();
                for axis in ["x", "y"] {
                    apply_set(&mut v, &format!("{parent}.{axis}=periodic")).unwrap();
                }
            }
            apply_set(
                &mut v,
                &format!("{path}={}", Value::String(value.to_owned())),
            )
            .unwrap();
            serde_json::from_value::<Config>(v)
        };
        let r = with(s);
        assert!(
            r.is_ok(),
            "schema allows {path} = {s:?} but Rust says {r:?}"
        );
        let r = with(&format!("{s}-not"));
        assert!(r.is_err(), "{path} = {s}-not accepted");
    }
}
