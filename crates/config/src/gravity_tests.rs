//! The `gravity` field: validated (finite ≥ 0, walls along y, full collision
//! records), passed to the engine, full records by default, and left out of the
//! stored configuration when 0 so that existing logs' configurations are unchanged.

use super::tests::err_of;
use super::*;
use carom_log::CollisionDetail;

fn spec(text: &str) -> carom_log::RunSpec {
    Config::from_json_str(text).unwrap().to_run_spec().unwrap()
}

#[test]
fn gravity_is_refused_when_negative_or_with_a_periodic_y_or_compact_records() {
    for (text, field, says) in [
        (
            r#"{"gravity": -1, "box": {"boundary": "walls"}}"#,
            "gravity",
            "value -1",
        ),
        (r#"{"gravity": 1}"#, "gravity", "periodic y"),
        (
            r#"{"gravity": 1, "box": {"boundary": {"x": "walls", "y": "periodic"}}}"#,
            "gravity",
            "periodic y",
        ),
        (
            r#"{"gravity": 1, "box": {"boundary": "walls"}, "log": {"collision_detail": "compact"}}"#,
            "log.collision_detail",
            "gravity",
        ),
        (r#"{"gravity": "down"}"#, "gravity", ""),
    ] {
        let e = err_of(text, &[]);
        let msg = e.to_string();
        assert!(msg.contains(field) && msg.contains(says), "{text}: {msg}");
    }
}

#[test]
fn gravity_reaches_the_engine_with_full_collision_records() {
    let s = spec(r#"{"gravity": 0.25, "box": {"boundary": {"x": "periodic", "y": "walls"}}}"#);
    assert_eq!(s.params.gravity, 0.25);
    assert_eq!(s.log.collision_detail, CollisionDetail::Full);
    assert!(
        s.config_json.contains("\"gravity\": 0.25"),
        "{}",
        s.config_json
    );
    let plain = spec("{}");
    assert_eq!(plain.params.gravity, 0.0);
    assert_eq!(plain.log.collision_detail, CollisionDetail::Compact);
    assert!(
        !plain.config_json.contains("gravity"),
        "{}",
        plain.config_json
    );
    // `--set gravity=…` works like any field.
    let c = Config::from_json_with_sets(
        r#"{"box": {"boundary": "walls"}}"#,
        "test",
        &["gravity=2".to_string()],
    )
    .unwrap();
    assert_eq!(c.to_run_spec().unwrap().params.gravity, 2.0);
}

#[test]
fn the_atmosphere_example_is_valid() {
    let path = super::tests::data_dir().join("atmosphere.json");
    let s = load_config(Some(&path), &[]).unwrap();
    assert_eq!(s.params.gravity, 0.05);
}
