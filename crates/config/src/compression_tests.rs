//! Compression (physics.md §17) in the configuration: the run mode `compression`
//! and the placement `{"compressed": {...}}` validated with the field named,
//! passed to the engine (the target as a scale of the radii), full collision
//! records by default, left out of the stored configuration when absent, and the
//! example.

use super::tests::err_of;
use super::*;
use carom_engine::Placement;
use carom_log::CollisionDetail;

fn spec(text: &str) -> carom_log::RunSpec {
    Config::from_json_str(text).unwrap().to_run_spec().unwrap()
}

#[test]
fn compression_is_refused_out_of_range_or_with_dynamics_it_does_not_support() {
    for (text, field, says) in [
        (
            r#"{"compression": {"rate": 0, "target_packing_fraction": 0.7}}"#,
            "compression.rate",
            "value 0",
        ),
        (
            r#"{"compression": {"rate": 0.1, "target_packing_fraction": 0.95}}"#,
            "compression.target_packing_fraction",
            "0.95",
        ),
        (
            r#"{"box": {"packing_fraction": 0.5}, "compression": {"rate": 0.1, "target_packing_fraction": 0.4}}"#,
            "compression.target_packing_fraction",
            "below",
        ),
        (
            r#"{"compression": {"rate": 0.1, "target_packing_fraction": 0.7, "max_reduced_pressure": 1}}"#,
            "compression.max_reduced_pressure",
            "value 1",
        ),
        (
            r#"{"compression": {"rate": 0.1, "target_packing_fraction": 0.7}, "collision": {"model": "normal", "coefficient": 0.9}}"#,
            "compression",
            "inelastic",
        ),
        (
            r#"{"compression": {"rate": 0.1}}"#,
            "compression",
            "target_packing_fraction",
        ),
        (
            r#"{"placement": {"compressed": {"rate": -1}}}"#,
            "placement.compressed.rate",
            "value -1",
        ),
    ] {
        let e = err_of(text, &[]);
        let msg = e.to_string();
        assert!(msg.contains(field) && msg.contains(says), "{text}: {msg}");
    }
}

#[test]
fn compression_reaches_the_engine_with_full_collision_records() {
    let s = spec(
        r#"{"species": [{"count": 100, "radius": 0.5, "mass": 1}],
            "box": {"packing_fraction": 0.3}, "placement": "random", "temperature": 2,
            "compression": {"rate": 0.05, "target_packing_fraction": 0.48}}"#,
    );
    let g = s.params.growth;
    assert_eq!(g.rate, 0.05);
    assert!(
        (g.target_scale - 1.6f64.sqrt()).abs() < 1e-12,
        "{}",
        g.target_scale
    );
    assert_eq!(
        (g.kt, g.rescale_interval, g.max_reduced_pressure),
        (2.0, 1.0, 1e3)
    );
    assert_eq!(s.log.collision_detail, CollisionDetail::Full);
    assert!(
        s.config_json.contains("target_packing_fraction"),
        "{}",
        s.config_json
    );
    let plain = spec("{}");
    assert_eq!(plain.params.growth.rate, 0.0);
    assert!(!plain.config_json.contains("target_packing_fraction"));
}

#[test]
fn compressed_placement_starts_at_the_lower_of_its_start_and_the_box() {
    let s = spec(r#"{"box": {"packing_fraction": 0.7}, "placement": {"compressed": {}}}"#);
    assert_eq!(
        s.system.placement,
        Placement::Compressed {
            rate: 0.01,
            start: 0.3
        }
    );
    let s =
        spec(r#"{"box": {"packing_fraction": 0.2}, "placement": {"compressed": {"rate": 0.5}}}"#);
    let Placement::Compressed { rate, start } = s.system.placement else {
        panic!("not compressed");
    };
    assert_eq!(rate, 0.5);
    assert!((start - 0.2).abs() < 1e-12, "{start}");
}

#[test]
fn the_compression_example_is_valid() {
    let path = super::tests::data_dir().join("compression-crystal.json");
    let s = load_config(Some(&path), &[]).unwrap();
    assert_eq!(s.params.growth.rate, 0.002);
}
