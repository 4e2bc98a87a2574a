//! Unit tests of the configuration front end, validator and resolution.

use super::error::init_field_to_config;
use super::*;
use carom_core::Restitution;
use carom_engine::{EngineParams, Placement, Velocities};
use carom_log::{CollisionDetail, LogOptions, RunSpec, Stop};
use std::collections::BTreeSet;
use std::path::Path;

pub(super) fn data_dir() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data")
}

pub(super) fn err_of(text: &str, sets: &[&str]) -> ConfigError {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    match Config::from_json_with_sets(text, "test", &sets).and_then(|c| c.to_run_spec()) {
        Ok(_) => panic!("expected an error for {text} {sets:?}"),
        Err(e) => e,
    }
}

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
fn default_is_fluid_of_ten_thousand_at_half_packing() {
    let spec = load_config(None, &[]).unwrap();
    assert_eq!(spec.system.species.len(), 1);
    assert_eq!(spec.system.species[0].count, 10_000);
    let s = &spec.system.species[0];
    let eta = s.count as f64 * s.disc_area() / spec.system.sim_box.area();
    assert!((eta - 0.5).abs() < 1e-12, "η = {eta}");
    assert!((spec.system.sim_box.size.x - spec.system.sim_box.size.y).abs() < 1e-9);
    assert_eq!(spec.stop, Stop::Time(DEFAULT_DURATION));
    assert_eq!(spec.params, EngineParams::default());
    assert_eq!(spec.log, LogOptions::default());
    assert_eq!(spec.system.placement, Placement::Lattice);
    assert_eq!(spec.system.velocities, Velocities::MaxwellBoltzmann);
}

#[test]
fn canonical_json_round_trips_to_the_same_run() {
    for text in [
        "{}",
        r#"{"box": {"size": [20, 10], "boundary": {"x": "periodic", "y": "walls"}}}"#,
        r#"{"collision": {"model": "normal", "coefficient": 0.8, "tc": 1e-6}, "stop": {"collisions": 1e6}}"#,
    ] {
        let a = Config::from_json_str(text).unwrap().to_run_spec().unwrap();
        let b = Config::from_json_str(&a.config_json)
            .unwrap()
            .to_run_spec()
            .unwrap();
        assert_eq!(a, b, "{text}");
    }
}

#[test]
fn set_overrides_nested_fields_and_parses_values() {
    let sets: Vec<String> = [
        "species.0.count=500",
        "log.snapshot_interval=0.5",
        "collision.model=normal",
        "collision.coefficient=0.9",
        "placement=random",
        "box.packing_fraction=0.2",
        "log.thermo_interval=null",
        "species.1.count=20",
        "species.1.radius=0.7",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let c = Config::from_json_with_sets("{}", "test", &sets).unwrap();
    assert_eq!(c.species.len(), 2);
    assert_eq!(c.species[0].count, 500);
    assert_eq!(c.species[1].count, 20);
    assert_eq!(c.species[1].radius, 0.7);
    assert_eq!(c.species[1].mass, 1.0);
    assert_eq!(c.log.snapshot_interval, Some(0.5));
    assert_eq!(c.log.thermo_interval, None);
    assert_eq!(c.placement, PlacementConfig::Random);
    let spec = c.to_run_spec().unwrap();
    assert_eq!(spec.params.restitution, Restitution::Normal(0.9));
    // Explicit box size via --set on a config that had none.
    let c = Config::from_json_with_sets("{}", "t", &["box.size=[30,15]".to_owned()]).unwrap();
    assert_eq!(c.sim_box.size, Some([30.0, 15.0]));
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

/// Discs that all start at rest never collide: a collision stop is refused
/// (it would run forever, writing snapshots), a time stop is not.
#[test]
fn a_collision_stop_without_kinetic_energy_is_refused() {
    let at_rest = r#"{"species": [{"count": 2}], "box": {"size": [10, 10]},
        "placement": {"explicit": [[2, 2], [6, 6]]},
        "velocities": {"explicit": [[0, 0], [0, 0]]}"#;
    let e = err_of(
        &format!(r#"{at_rest}, "stop": {{"collisions": 10}}}}"#),
        &[],
    );
    assert_eq!(e.field(), Some("stop.collisions"), "{e}");
    assert!(e.to_string().contains("no disc ever moves"), "{e}");
    assert!(e.to_string().contains("allowed: stop.duration"), "{e}");
    let timed = format!(r#"{at_rest}, "stop": {{"duration": 10}}}}"#);
    assert!(Config::from_json_with_sets(&timed, "test", &[])
        .and_then(|c| c.to_run_spec())
        .is_ok());
    // One moving disc is enough to collide with a wall or another disc.
    let moving = at_rest.replace("[[0, 0], [0, 0]]", "[[0, 0], [0.5, 0]]");
    assert!(Config::from_json_with_sets(
        &format!(r#"{moving}, "stop": {{"collisions": 10}}}}"#),
        "test",
        &[]
    )
    .and_then(|c| c.to_run_spec())
    .is_ok());
}

#[test]
fn log_intervals_give_at_most_a_billion_records_per_run() {
    let ok = |text: &str| Config::from_json_str(text).unwrap().to_run_spec().unwrap();
    // 10⁹ snapshots over the run: allowed; one interval's width less: refused.
    ok(r#"{"stop": {"duration": 1000}, "log": {"snapshot_interval": 1e-6}}"#);
    let e = err_of(
        r#"{"stop": {"duration": 1000}, "log": {"snapshot_interval": 0.99e-6}}"#,
        &[],
    );
    assert_eq!(e.field(), Some("log.snapshot_interval"), "{e}");
    assert!(e.to_string().contains("1.0e9 records"), "{e}");
    // The default duration (50) counts too.
    let e = err_of(r#"{"log": {"thermo_interval": 1e-8}}"#, &[]);
    assert_eq!(e.field(), Some("log.thermo_interval"), "{e}");
    // The watchdog's bound goes with either stop, and alone (default duration).
    ok(r#"{"stop": {"collisions": 10, "max_time_without_collision": 5}}"#);
    ok(r#"{"stop": {"duration": 10, "max_time_without_collision": 5}}"#);
    ok(r#"{"stop": {"max_time_without_collision": 5}}"#);
    // A run stopped by its collision count has no known length: not checked.
    ok(r#"{"stop": {"collisions": 10}, "log": {"thermo_interval": 1e-17}}"#);
}

/// The collision record: compact by default, full when asked for or when only
/// every k-th collision is logged (compact records need every collision).
#[test]
fn collision_detail_defaults_to_compact_and_full_with_a_stride() {
    let detail = |text: &str| {
        let c: Config = serde_json::from_str(text).unwrap();
        c.validate().unwrap();
        c.log.options().collision_record()
    };
    assert_eq!(detail("{}"), CollisionDetail::Compact);
    assert_eq!(
        detail(r#"{"log": {"collision_detail": "full"}}"#),
        CollisionDetail::Full
    );
    assert_eq!(
        detail(r#"{"log": {"collision_every": 3}}"#),
        CollisionDetail::Full
    );
    assert_eq!(
        detail(r#"{"log": {"collision_every": 3, "collision_detail": "full"}}"#),
        CollisionDetail::Full
    );
    let e = err_of(
        r#"{"log": {"collision_every": 2, "collision_detail": "compact"}}"#,
        &[],
    );
    let text = e.to_string();
    assert!(text.contains("collision_every"), "{text}");
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

fn example_paths() -> Vec<std::path::PathBuf> {
    let mut v: Vec<_> = std::fs::read_dir(data_dir())
        .expect("data/ exists")
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.extension().is_some_and(|e| e == "json")
                && !p.to_string_lossy().ends_with(".schema.json")
        })
        .collect();
    v.sort();
    v
}

#[test]
fn every_example_config_parses_and_builds() {
    let paths = example_paths();
    let names: BTreeSet<String> = paths
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    for required in [
        "dilute-gas.json",
        "dense-fluid.json",
        "binary-mixture.json",
        "granular-cooling.json",
        "channel.json",
    ] {
        assert!(names.contains(required), "data/{required} missing");
    }
    for p in &paths {
        let spec = load_config(Some(p), &[]).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        let state = spec
            .system
            .build()
            .unwrap_or_else(|e| panic!("{}: {}", p.display(), ConfigError::from_init(e)));
        assert_eq!(
            state.positions.len(),
            spec.system.species.iter().map(|s| s.count).sum::<usize>()
        );
    }
}

#[test]
fn examples_are_what_their_names_say() {
    let get = |name: &str| load_config(Some(&data_dir().join(name)), &[]).unwrap();
    let eta = |s: &RunSpec| {
        s.system
            .species
            .iter()
            .map(|sp| sp.count as f64 * sp.disc_area())
            .sum::<f64>()
            / s.system.sim_box.area()
    };
    assert!((eta(&get("dense-fluid.json")) - 0.68).abs() < 1e-9);
    assert!(eta(&get("dilute-gas.json")) < 0.1);
    assert!(get("binary-mixture.json").system.species.len() >= 2);
    let glass = get("glass-mixture.json");
    assert!(glass.system.species.len() >= 2 && eta(&glass) > 0.75);
    assert_eq!(glass.system.placement, Placement::Relaxed);
    assert!(matches!(
        get("granular-cooling.json").params.restitution,
        Restitution::Normal(e) if e < 1.0
    ));
    let ch = get("channel.json").system.sim_box.boundary;
    assert!(ch[0].is_periodic() && !ch[1].is_periodic());
}

#[test]
fn the_scene_is_off_by_default_and_on_with_its_interval() {
    let spec = |text: &str| Config::from_json_str(text).unwrap().to_run_spec().unwrap();
    assert_eq!(spec("{}").log.scene_interval, None);
    assert_eq!(
        spec(r#"{"log": {"scene_interval": 0.25}}"#)
            .log
            .scene_interval,
        Some(0.25)
    );
    assert_eq!(
        spec(r#"{"log": {"scene_interval": null}}"#)
            .log
            .scene_interval,
        None
    );
}
