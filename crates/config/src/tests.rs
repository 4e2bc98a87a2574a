//! Unit tests of the configuration front end, validator and resolution: defaults,
//! round trips, `--set` overrides, run-level checks, the example configs and the
//! scene. Errors that name the offending field are in `error_tests.rs`. The helpers
//! here are shared with the other test modules of the crate.

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
