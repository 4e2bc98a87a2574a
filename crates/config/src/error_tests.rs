//! Unit tests of the configuration errors: type, range, unknown-field, `--set`,
//! syntax and build errors each name the offending field (as a config path) and say
//! what is allowed.

use super::error::init_field_to_config;
use super::tests::err_of;
use super::*;

fn field_of(text: &str, sets: &[&str]) -> String {
    let e = err_of(text, sets);
    e.field()
        .unwrap_or_else(|| panic!("no field in {e}"))
        .to_owned()
}

#[test]
fn type_errors_say_what_is_allowed_in_words() {
    for (text, sets, allowed) in [
        (r#"{"temperature": "warm"}"#, vec![], "allowed: a number"),
        ("{}", vec!["temperature=abc"], "allowed: a number"),
        (r#"{"seed": -1}"#, vec![], "allowed: a non-negative integer"),
        (
            r#"{"log": {"collisions": 3}}"#,
            vec![],
            "allowed: true or false",
        ),
    ] {
        let msg = err_of(text, &sets).to_string();
        assert!(msg.contains(allowed), "{text} {sets:?}: {msg}");
        assert!(!msg.contains("f64") && !msg.contains("u64"), "{msg}");
    }
}

#[test]
fn set_errors_name_the_key() {
    assert!(matches!(err_of("{}", &["nokey"]), ConfigError::Set { .. }));
    assert!(matches!(
        err_of("{}", &["species.5.count=1"]),
        ConfigError::Set { .. }
    ));
    assert!(matches!(
        err_of("{}", &["species.x.count=1"]),
        ConfigError::Set { .. }
    ));
    assert!(matches!(
        err_of("{}", &["temperature.x=1"]),
        ConfigError::Set { .. }
    ));
    assert_eq!(field_of("{}", &["bogus=1"]), "bogus");
    assert_eq!(field_of("{}", &["log.bogus=1"]), "log.bogus");
    assert_eq!(field_of("{}", &["species.0.colour=1"]), "species.0.colour");
    assert_eq!(field_of("{}", &["temperature=hot"]), "temperature");
}

#[test]
fn wrong_types_name_the_field() {
    let cases = [
        (r#"{"species": [{"count": "many"}]}"#, "species.0.count"),
        (
            r#"{"species": [{"count": 10, "radius": "big"}]}"#,
            "species.0.radius",
        ),
        (r#"{"species": [{"count": 1.5}]}"#, "species.0.count"),
        (r#"{"species": [{"count": -3}]}"#, "species.0.count"),
        (r#"{"species": {"count": 3}}"#, "species"),
        (r#"{"species": [{"radius": 0.5}]}"#, "species.0"),
        (r#"{"temperature": "warm"}"#, "temperature"),
        (r#"{"seed": -1}"#, "seed"),
        (r#"{"box": {"size": [1, 2, 3]}}"#, "box.size"),
        (r#"{"box": {"boundary": "sticky"}}"#, "box.boundary"),
        (r#"{"box": {"boundary": {"x": "walls"}}}"#, "box.boundary"),
        (
            r#"{"box": {"boundary": {"x": "walls", "y": "hole"}}}"#,
            "box.boundary.y",
        ),
        (r#"{"placement": "hexagonal"}"#, "placement"),
        (
            r#"{"placement": {"explicit": [[1, "a"]]}}"#,
            "placement.explicit.0.1",
        ),
        (r#"{"velocities": "fast"}"#, "velocities"),
        (r#"{"collision": {"model": "plastic"}}"#, "collision.model"),
        (r#"{"stop": {"duration": "long"}}"#, "stop.duration"),
        (r#"{"log": {"collisions": "yes"}}"#, "log.collisions"),
        (r#"{"log": {"compression": "gzip"}}"#, "log.compression"),
        (r#"{"neighbours": "grid"}"#, "neighbours"),
    ];
    for (text, field) in cases {
        assert_eq!(field_of(text, &[]), field, "{text}");
    }
    let e = err_of(r#"{"box": {"size": [1, 2, 3]}}"#, &[]).to_string();
    assert!(e.contains("exactly 2 numbers"), "{e}");
}

#[test]
fn unknown_fields_are_named() {
    let cases = [
        (r#"{"speices": []}"#, "speices"),
        (r#"{"box": {"eta": 0.3}}"#, "box.eta"),
        (
            r#"{"species": [{"count": 1, "charge": 2}]}"#,
            "species.0.charge",
        ),
        (
            r#"{"collision": {"model": "normal", "e": 0.9}}"#,
            "collision.e",
        ),
        (r#"{"stop": {"time": 3}}"#, "stop.time"),
        (r#"{"log": {"snapshots": 3}}"#, "log.snapshots"),
        (
            r#"{"box": {"boundary": {"x": "walls", "y": "walls", "z": "walls"}}}"#,
            "box.boundary.z",
        ),
    ];
    for (text, field) in cases {
        let e = err_of(text, &[]);
        assert_eq!(e.field(), Some(field), "{text}: {e}");
        assert!(e.to_string().contains("unknown field"), "{e}");
    }
    // The message lists what is allowed.
    let e = err_of(r#"{"log": {"snapshots": 3}}"#, &[]).to_string();
    assert!(e.contains("snapshot_interval"), "{e}");
}

#[test]
fn out_of_range_values_are_named() {
    let cases = [
        (r#"{"species": []}"#, "species"),
        (r#"{"species": [{"count": 0}]}"#, "species"),
        (
            r#"{"species": [{"count": 5, "radius": 0}]}"#,
            "species.0.radius",
        ),
        (
            r#"{"species": [{"count": 5}, {"count": 5, "mass": -1}]}"#,
            "species.1.mass",
        ),
        (r#"{"temperature": 1, "temperature": 2}"#, "temperature"),
        (
            r#"{"species": [{"count": 5, "radius": 0.5, "radius": 1}]}"#,
            "species.0.radius",
        ),
        // Boxes derived from η and the aspect: the setting that spoils them is
        // named, not the box.size nobody wrote.
        (r#"{"species": [{"count": 5, "radius": 1e200}]}"#, "species"),
        (
            r#"{"box": {"packing_fraction": 1e-320}}"#,
            "box.packing_fraction",
        ),
        (
            r#"{"species": [{"count": 4}], "box": {"aspect": 100}}"#,
            "box.aspect",
        ),
        (
            r#"{"box": {"packing_fraction": 0.95}}"#,
            "box.packing_fraction",
        ),
        (
            r#"{"box": {"packing_fraction": 0}}"#,
            "box.packing_fraction",
        ),
        (r#"{"box": {"aspect": 0}}"#, "box.aspect"),
        (
            r#"{"box": {"size": [10, 10], "packing_fraction": 0.3}}"#,
            "box.packing_fraction",
        ),
        (r#"{"box": {"size": [0.5, 10]}}"#, "box.size.0"),
        (
            r#"{"box": {"wall_restitution": 0.5}}"#,
            "box.wall_restitution",
        ),
        (
            r#"{"box": {"boundary": "walls", "wall_restitution": 1.5}}"#,
            "box.wall_restitution",
        ),
        (r#"{"temperature": 0}"#, "temperature"),
        (r#"{"temperature": -1}"#, "temperature"),
        (
            r#"{"collision": {"model": "normal"}}"#,
            "collision.coefficient",
        ),
        (
            r#"{"collision": {"model": "normal", "coefficient": 1.2}}"#,
            "collision.coefficient",
        ),
        (
            r#"{"collision": {"coefficient": 0.9}}"#,
            "collision.coefficient",
        ),
        (r#"{"collision": {"tc": -1}}"#, "collision.tc"),
        (
            r#"{"collision": {"max_events_without_time_advance": 0}}"#,
            "collision.max_events_without_time_advance",
        ),
        (r#"{"stop": {"duration": 1, "collisions": 5}}"#, "stop"),
        (r#"{"stop": {"duration": -1}}"#, "stop.duration"),
        (r#"{"stop": {"collisions": 0}}"#, "stop.collisions"),
        (
            r#"{"stop": {"collisions": 9, "max_time_without_collision": 0}}"#,
            "stop.max_time_without_collision",
        ),
        (
            r#"{"stop": {"max_time_without_collision": -3}}"#,
            "stop.max_time_without_collision",
        ),
        (
            r#"{"species": [{"count": 1}], "stop": {"collisions": 10}}"#,
            "stop.collisions",
        ),
        (r#"{"log": {"collision_every": 0}}"#, "log.collision_every"),
        (
            r#"{"log": {"collision_every": 2, "collision_detail": "compact"}}"#,
            "log.collision_detail",
        ),
        (
            r#"{"log": {"collision_detail": "short"}}"#,
            "log.collision_detail",
        ),
        (
            r#"{"log": {"snapshot_interval": 0}}"#,
            "log.snapshot_interval",
        ),
        (r#"{"log": {"flush_seconds": 0}}"#, "log.flush_seconds"),
        (r#"{"log": {"scene_interval": -1}}"#, "log.scene_interval"),
        (
            r#"{"stop": {"duration": 1e3}, "log": {"scene_interval": 1e-7}}"#,
            "log.scene_interval",
        ),
        (
            r#"{"log": {"thermo_interval": 1e-17}}"#,
            "log.thermo_interval",
        ),
        (
            r#"{"stop": {"duration": 1e3}, "log": {"checkpoint_interval": 1e-7}}"#,
            "log.checkpoint_interval",
        ),
        (
            r#"{"species": [{"count": 2}], "placement": {"explicit": [[1, 1]]}}"#,
            "placement.explicit",
        ),
        (
            r#"{"species": [{"count": 1}], "velocities": {"explicit": []}}"#,
            "velocities.explicit",
        ),
        ("[1, 2]", "(top level)"),
    ];
    for (text, field) in cases {
        let e = err_of(text, &[]);
        assert_eq!(e.field(), Some(field), "{text}: {e}");
        assert!(e.to_string().contains("allowed"), "{e}");
    }
}

#[test]
fn syntax_errors_give_line_and_column() {
    let e = err_of("{\n  \"seed\": 1,\n  oops\n}", &[]);
    match e {
        ConfigError::Syntax { line, .. } => assert_eq!(line, 3),
        other => panic!("{other}"),
    }
}

#[test]
fn build_errors_map_to_config_fields() {
    // Overlapping explicit discs.
    let text = r#"{"species": [{"count": 2}], "box": {"size": [10, 10]},
            "placement": {"explicit": [[1, 1], [1.5, 1]]}}"#;
    let spec = Config::from_json_str(text).unwrap().to_run_spec().unwrap();
    let e = ConfigError::from_init(spec.system.build().unwrap_err());
    assert_eq!(e.field(), Some("placement.explicit"));
    assert!(e.to_string().contains("overlap"), "{e}");
    // A disc outside a walled box.
    let text = r#"{"species": [{"count": 2}], "box": {"size": [10, 10], "boundary": "walls"},
            "placement": {"explicit": [[1, 1], [0.2, 5]]}}"#;
    let spec = Config::from_json_str(text).unwrap().to_run_spec().unwrap();
    let e = ConfigError::from_init(spec.system.build().unwrap_err());
    assert_eq!(e.field(), Some("placement.explicit.1"), "{e}");
    // Random placement that cannot fit.
    let spec = Config::from_json_with_sets(
        "{}",
        "t",
        &[
            "placement=random".to_owned(),
            "box.packing_fraction=0.85".to_owned(),
            "species.0.count=200".to_owned(),
        ],
    )
    .unwrap()
    .to_run_spec()
    .unwrap();
    let e = ConfigError::from_init(spec.system.build().unwrap_err());
    assert_eq!(e.field(), Some("placement"), "{e}");
    // A lattice that does not fit is the packing fraction's fault, or the
    // box size's when the configuration gives that.
    let too_dense = |sets: &[&str]| {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let spec = Config::from_json_with_sets("{}", "t", &sets)
            .unwrap()
            .to_run_spec()
            .unwrap();
        ConfigError::from_init_in(spec.system.build().unwrap_err(), &spec.config_json)
    };
    let e = too_dense(&["species.0.count=7", "box.packing_fraction=0.72"]);
    assert_eq!(e.field(), Some("box.packing_fraction"), "{e}");
    let e = too_dense(&["species.0.count=1020", "box.size=[30, 30]"]);
    assert_eq!(e.field(), Some("box.size"), "{e}");
    assert_eq!(
        init_field_to_config("species[1].radius"),
        "species.1.radius"
    );
    assert_eq!(
        init_field_to_config("velocities[4]"),
        "velocities.explicit.4"
    );
}
