//! End-to-end tests of the `carom` binary: run, analyze, info, resume, bad
//! configurations and Ctrl-C (issue 4).

use crate::cli_common::*;

use std::path::Path;
use std::process::{Command, Output, Stdio};

use serde_json::{json, Value};

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[test]
fn run_then_analyze_at_eta_0_3_matches_the_equation_of_state() {
    let dir = scratch("eos");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            "--out",
            "eos.mcap",
            "--set",
            "species.0.count=1024",
            "--set",
            "box.packing_fraction=0.3",
            "--set",
            "stop.duration=220",
            "--set",
            "seed=11",
            "--set",
            "log.snapshot_interval=2",
        ],
    ));
    let r = json_of(&carom(
        &dir,
        &[
            "analyze",
            "eos.mcap",
            "--json",
            "--equilibrate",
            "20",
            "--every",
            "4",
        ],
    ));
    assert_eq!(r["n"], 1024);
    assert_eq!(r["log_complete"], true);
    // Temperature with f = 2N − 2 (NVE from velocities scaled to kT = 1).
    assert_eq!(r["temperature"]["dof"], 2046);
    assert!((f(&r["temperature"]["kt"]) - 1.0).abs() < 1e-9);
    // Maxwell–Boltzmann passes: p-values not tiny.
    let mb = &r["maxwell_boltzmann"][0];
    assert_eq!(mb["passed"], true, "{mb}");
    assert!(f(&mb["chi_square"]["p_value"]) > 1e-3);
    assert!(f(&mb["ks"]["p_value"]) > 1e-3);
    assert_eq!(mb["snapshots"], 51);
    // Z at η = 0.3 within 3 standard errors of physics.md §7's 2.0633 ± 0.0020.
    let z = f(&r["pressure"]["z"]);
    let se = f(&r["pressure"]["z_std_error"]);
    assert!(se > 0.0 && se < 0.02, "se = {se}");
    let tol = 3.0 * (se * se + 0.0020f64 * 0.0020).sqrt();
    assert!((z - 2.0633).abs() < tol, "Z = {z} ± {se}");
    // The Enskog consistency check closes.
    let e = &r["enskog"];
    assert!(
        f(&e["difference"]).abs() < 4.0 * f(&e["difference_std_error"]),
        "{e}"
    );
    assert!(r["inelastic"].is_null());

    // The text report says the same.
    let text = ok(&carom(
        &dir,
        &["analyze", "eos.mcap", "--equilibrate", "20"],
    ));
    assert!(text.contains("Z = βPA/N"), "{text}");
    assert!(text.contains("consistent with Maxwell–Boltzmann"), "{text}");
}

#[test]
fn equal_speeds_analysed_from_the_first_snapshot_fail_maxwell_boltzmann() {
    let dir = scratch("equal");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            "--out",
            "eq.mcap",
            "--set",
            "species.0.count=1000",
            "--set",
            "box.packing_fraction=0.3",
            "--set",
            "velocities=equal-speed",
            "--set",
            "stop.duration=5",
        ],
    ));
    let r = json_of(&carom(
        &dir,
        &[
            "analyze",
            "eq.mcap",
            "--json",
            "--equilibrate",
            "0",
            "--every",
            "1e9",
        ],
    ));
    let mb = &r["maxwell_boltzmann"][0];
    assert_eq!(mb["snapshots"], 1, "{mb}");
    assert_eq!(r["window"]["snapshot_times"][0], 0.0);
    assert_eq!(mb["passed"], false);
    assert!(f(&mb["ks"]["p_value"]) < 1e-10);
    assert!(f(&mb["chi_square"]["p_value"]) < 1e-10);
}

#[test]
fn bad_configurations_fail_cleanly_naming_the_field() {
    let dir = scratch("bad");
    let cases: &[(&str, &[&str], &str)] = &[
        // (config text, --set arguments, field the message must name)
        (
            r#"{"species": [{"count": "many"}]}"#,
            &[],
            "species.0.count",
        ),
        (
            r#"{"species": [{"count": 10, "radius": true}]}"#,
            &[],
            "species.0.radius",
        ),
        (
            r#"{"species": [{"count": 10, "mass": -1}]}"#,
            &[],
            "species.0.mass",
        ),
        (
            r#"{"box": {"packing_fraction": "dense"}}"#,
            &[],
            "box.packing_fraction",
        ),
        (
            r#"{"box": {"packing_fraction": 0.95}}"#,
            &[],
            "box.packing_fraction",
        ),
        (r#"{"box": {"size": [10]}}"#, &[], "box.size"),
        (r#"{"box": {"boundary": "sticky"}}"#, &[], "box.boundary"),
        (
            r#"{"box": {"boundary": "walls", "wall_restitution": 2}}"#,
            &[],
            "box.wall_restitution",
        ),
        (r#"{"temperature": "hot"}"#, &[], "temperature"),
        (r#"{"temperature": -1}"#, &[], "temperature"),
        (r#"{"seed": 1.5}"#, &[], "seed"),
        (r#"{"placement": "hexagonal"}"#, &[], "placement"),
        (r#"{"velocities": 3}"#, &[], "velocities"),
        (
            r#"{"collision": {"model": "sticky"}}"#,
            &[],
            "collision.model",
        ),
        (
            r#"{"collision": {"model": "normal", "coefficient": 1.5}}"#,
            &[],
            "collision.coefficient",
        ),
        (r#"{"collision": {"tc": "short"}}"#, &[], "collision.tc"),
        (r#"{"stop": {"duration": 0}}"#, &[], "stop.duration"),
        (r#"{"stop": {"collisions": -5}}"#, &[], "stop.collisions"),
        (
            r#"{"log": {"compression": "gzip"}}"#,
            &[],
            "log.compression",
        ),
        (
            r#"{"log": {"snapshot_interval": -1}}"#,
            &[],
            "log.snapshot_interval",
        ),
        (r#"{"log": {"collisions": "all"}}"#, &[], "log.collisions"),
        (
            r#"{"species": [{"count": 10, "charge": 1}]}"#,
            &[],
            "species.0.charge",
        ),
        (r#"{"temprature": 1}"#, &[], "temprature"),
        (
            r#"{"species": [{"count": 2}], "box": {"size": [10, 10]},
               "placement": {"explicit": [[2, 2], [2.5, 2]]}}"#,
            &[],
            "placement.explicit",
        ),
        (
            r#"{"species": [{"count": 200}], "box": {"packing_fraction": 0.85},
               "placement": "random"}"#,
            &[],
            "placement",
        ),
        ("{}", &["--set", "species.0.count=many"], "species.0.count"),
        ("{}", &["--set", "log.nonsense=1"], "log.nonsense"),
        ("{}", &["--set", "species.3.count=1"], "species.3"),
        ("{ not json", &[], "line 1"),
    ];
    for (k, (text, sets, field)) in cases.iter().enumerate() {
        let cfg = dir.join(format!("bad{k}.json"));
        std::fs::write(&cfg, text).unwrap();
        let mut args = vec!["run", "--quiet", cfg.to_str().unwrap(), "--out", "x.mcap"];
        args.extend_from_slice(sets);
        let out = carom(&dir, &args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{text} {sets:?}: {stderr}");
        assert!(stderr.contains(field), "{text} {sets:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(!dir.join("x.mcap").exists(), "{text}: a log was written");
    }
    // A missing configuration file.
    let out = carom(&dir, &["run", "no-such.json"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no-such.json"));
}

#[test]
fn info_describes_a_complete_log_and_run_refuses_to_overwrite_it() {
    let dir = scratch("info");
    let two = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/two-discs.json");
    ok(&carom(&dir, &["run", "--quiet", two.to_str().unwrap()]));
    assert!(dir.join("two-discs.mcap").exists());
    let mut i = json_of(&carom(&dir, &["info", "two-discs.mcap", "--json"]));
    assert_eq!(i["complete"], true);
    // From the index; --verify reads every message and finds the same.
    assert_eq!(i["verified"], false);
    let mut v = json_of(&carom(
        &dir,
        &["info", "--verify", "two-discs.mcap", "--json"],
    ));
    assert_eq!(v["verified"], true);
    for x in [&mut i, &mut v] {
        x.as_object_mut().unwrap().remove("verified");
    }
    assert_eq!(i, v);
    assert_eq!(i["run"]["n_discs"], 2);
    assert_eq!(i["summary"]["stop_reason"], "collisions");
    assert_eq!(
        i["summary"]["pair_collisions"].as_u64().unwrap()
            + i["summary"]["wall_collisions"].as_u64().unwrap(),
        10
    );
    assert_eq!(i["channels"]["/collisions"]["defined"], true);
    assert_eq!(i["run"]["config"]["species"][0]["count"], 2);
    let out = carom(&dir, &["info", "two-discs.mcap"]);
    let text = ok(&out);
    assert!(
        text.contains("complete") && text.contains("/snapshot"),
        "{text}"
    );
    // A read shorter than the progress interval shows no progress; --quiet none
    // at all, and changes nothing else.
    assert_eq!(String::from_utf8_lossy(&out.stderr), "");
    assert_eq!(ok(&carom(&dir, &["info", "-q", "two-discs.mcap"])), text);
    // Running again into the same file needs --force.
    let out = carom(&dir, &["run", "--quiet", two.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--force"));
    ok(&carom(
        &dir,
        &["run", "--quiet", "--force", two.to_str().unwrap()],
    ));
    // Not a log.
    std::fs::write(dir.join("junk.mcap"), b"definitely not mcap").unwrap();
    let out = carom(&dir, &["info", "junk.mcap"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(!String::from_utf8_lossy(&out.stderr).contains("panicked"));
    let out = carom(&dir, &["analyze", "junk.mcap"]);
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn granular_cooling_reports_the_energy_budget_and_plots() {
    let dir = scratch("granular");
    let cfg = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/granular-cooling.json");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            cfg.to_str().unwrap(),
            "--out",
            "g.mcap",
            "--set",
            "species.0.count=900",
            "--set",
            "box.packing_fraction=0.1",
            "--set",
            "stop.duration=30",
            "--set",
            "log.snapshot_interval=5",
        ],
    ));
    let r = json_of(&carom(
        &dir,
        &["analyze", "g.mcap", "--json", "--plot", "figs"],
    ));
    assert_eq!(r["elastic"], false);
    let e = &r["inelastic"]["energy"];
    assert!(f(&e["final"]) < 0.6 * f(&e["initial"]), "{e}");
    assert!(f(&e["relative_residual"]).abs() < 1e-9, "{e}");
    let h = &r["inelastic"]["haff"];
    assert!((f(&h["ratio"]) - 1.0).abs() < 0.15, "{h}");
    assert!(r["temperature"]["series"].as_array().unwrap().len() > 100);
    for name in [
        "speed_species0",
        "components_species0",
        "temperature",
        "pressure",
    ] {
        let png = std::fs::read(dir.join(format!("figs/{name}.png"))).unwrap();
        assert_eq!(&png[..4], b"\x89PNG", "{name}");
        let svg = std::fs::read_to_string(dir.join(format!("figs/{name}.svg"))).unwrap();
        assert!(svg.contains("<svg"), "{name}");
    }
    // Axes in the run's units; the cooling curve with Haff's law in the legend.
    let svg = std::fs::read_to_string(dir.join("figs/temperature.svg")).unwrap();
    for label in ["kT (energy)", "(time)", "Haff", "measured kT"] {
        assert!(svg.contains(label), "{label}");
    }
    let svg = std::fs::read_to_string(dir.join("figs/speed_species0.svg")).unwrap();
    assert!(svg.contains("(length/time)"));
    let a2 = &r["inelastic"]["sonine"];
    assert!(f(&a2["std_error"]) > 0.0 && f(&a2["theory"]) < 0.0, "{a2}");
    assert_eq!(
        r["maxwell_boltzmann"][0]["scaled_to_snapshot_temperature"],
        true
    );
}

/// A dense fluid (η = 0.68) analysed from its lattice start is reported as
/// drifting, in the text and in the JSON, not as a converged Z.
#[test]
fn a_dense_fluid_analysed_from_its_start_is_reported_drifting() {
    let dir = scratch("drift");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            "--out",
            "d.mcap",
            "--set",
            "species.0.count=1000",
            "--set",
            "box.packing_fraction=0.68",
            "--set",
            "stop.duration=8",
        ],
    ));
    let args = ["analyze", "d.mcap", "--equilibrate", "0", "--quiet"];
    let out = carom(&dir, &args);
    ok(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("DRIFTING") && text.contains("drift      "),
        "{text}"
    );
    assert!(text.contains("--equilibrate"), "{text}");
    let r = json_of(&carom(&dir, &[&args[..], &["--json"]].concat()));
    let d = &r["pressure"]["drift"];
    assert_eq!(d["drifting"], true, "{d}");
    assert!(f(&d["second_half"]) > f(&d["first_half"]), "{d}");
    assert!(f(&d["difference_std_errors"]) > 3.0, "{d}");
}

#[test]
fn channel_pressure_comes_from_the_walls() {
    let dir = scratch("channel");
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
            "species.0.count=400",
            "--set",
            "stop.duration=40",
        ],
    ));
    let r = json_of(&carom(&dir, &["analyze", "c.mcap", "--json"]));
    assert_eq!(r["periodic"], serde_json::json!([true, false]));
    assert_eq!(r["temperature"]["dof"], 799);
    let p = &r["pressure"];
    assert!(p["estimator"].as_str().unwrap().contains("wall"));
    // Reachable area L_x (L_y − 2a) with a = 0.5.
    let size = &r["box_size"];
    let area = f(&size[0]) * (f(&size[1]) - 1.0);
    assert!((f(&p["area"]) - area).abs() < 1e-9 * area);
    // A dense-ish channel is well above ideal: Z between 1.5 and 4 at η = 0.4.
    assert!(f(&p["z"]) > 1.5 && f(&p["z"]) < 4.0, "{p}");
    assert!(r["enskog"].is_null());
}

/// The last `/thermo` record's Z of the log `path`.
fn final_thermo_z(path: &Path) -> f64 {
    use carom_log::{LogMessage, LogReader};
    let mut r = LogReader::open(path).unwrap();
    let last = r.thermo().filter_map(|m| match m.unwrap() {
        LogMessage::Thermo(t) => Some(t),
        _ => None,
    });
    last.last().expect("a /thermo record").z.expect("a Z")
}

/// A walled mixture: `/thermo` and `analyze` compute Z with one definition (each
/// species its own reachable area). With `--equilibrate 0` both average the wall
/// impulse over the whole run, `/thermo` at once and `analyze` as the mean of its
/// 1024 equal time bins at each bin's kT; the run is elastic, so kT is the same in
/// every bin up to rounding and the two differ only by rounding. (They differed by
/// 0.6 % when `/thermo` used the largest radius and `analyze` the mean one.)
#[test]
fn a_walled_mixture_has_one_z_in_thermo_and_analyze() {
    let dir = scratch("walled-mixture");
    let sets = [
        "species.0.count=300",
        "species.0.radius=0.5",
        "species.0.mass=1",
        "species.1.count=200",
        "species.1.radius=0.7",
        "species.1.mass=2",
        "box.packing_fraction=0.35",
        "box.boundary=walls",
        "placement=random",
        "seed=5",
        "stop.duration=100",
    ];
    let mut args = vec!["run", "--quiet", "--out", "m.mcap"];
    for s in &sets {
        args.extend(["--set", s]);
    }
    ok(&carom(&dir, &args));
    let thermo_z = final_thermo_z(&dir.join("m.mcap"));
    let r = json_of(&carom(
        &dir,
        &[
            "analyze",
            "m.mcap",
            "--json",
            "--quiet",
            "--equilibrate",
            "0",
        ],
    ));
    let z = f(&r["pressure"]["z"]);
    assert!(
        (z - thermo_z).abs() < 1e-12 * thermo_z,
        "analyze Z = {z}, /thermo Z = {thermo_z}"
    );
    assert!(z > 2.0 && z < 2.8, "{z}");
}

#[test]
fn ctrl_c_finishes_the_log_and_resume_continues_it() {
    let dir = scratch("ctrlc");
    let child = Command::new(BIN)
        .args([
            "run",
            "--out",
            "long.mcap",
            "--set",
            "species.0.count=2000",
            "--set",
            "stop.duration=1e6",
            // (The signal is under test, not the projection against a small disk.)
            "--ignore-disk-estimate",
        ])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("interrupted"), "{stderr}");
    let i = json_of(&carom(&dir, &["info", "long.mcap", "--json"]));
    assert_eq!(i["complete"], true);
    assert_eq!(i["summary"]["stop_reason"], "interrupted");
    let t_stop = f(&i["summary"]["sim_time"]);
    assert!(t_stop > 0.0);
    // Resume with a nearby stop time, into a new file.
    let until = format!("{}", t_stop + 1.0);
    let resume = [
        "resume",
        "long.mcap",
        "--out",
        "more.mcap",
        "--until",
        &until,
        "--quiet",
    ];
    ok(&carom(&dir, &resume));
    let j = json_of(&carom(&dir, &["info", "more.mcap", "--json"]));
    assert_eq!(j["summary"]["stop_reason"], "time");
    assert!((f(&j["summary"]["sim_time"]) - (t_stop + 1.0)).abs() < 1e-9);
    assert_eq!(j["run"]["resumed_from"], "long.mcap");
    // A stop before the log's end is a usage error (exit 2) naming the option.
    let out = carom(&dir, &["resume", "long.mcap", "--until", "0", "--quiet"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("stop.time"));
    // Resuming into an existing other file needs --force, as `run` does; the file
    // is left as it was.
    let before = std::fs::read(dir.join("more.mcap")).unwrap();
    let out = carom(&dir, &resume);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--force"));
    let out = carom(
        &dir,
        &[
            "run",
            "--resume",
            "long.mcap",
            "--out",
            "more.mcap",
            "--quiet",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(std::fs::read(dir.join("more.mcap")).unwrap(), before);
    ok(&carom(&dir, &[&resume[..], &["--force"]].concat()));
    // --dry-run only prints a new run's configuration: with --resume it is a usage
    // error, not a run.
    let out = carom(
        &dir,
        &["run", "--resume", "more.mcap", "--dry-run", "--quiet"],
    );
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn a_run_in_units_of_picoseconds_is_analysed_like_one_in_reduced_units() {
    // The same run with lengths and times scaled by 2⁻⁴⁰ (≈ 10⁻¹², as for discs
    // of a few Å in seconds): scaling by a power of two is exact, so the trajectory
    // is the same number for number, and so must the analysis be. (MCAP's whole
    // nanoseconds cannot resolve these times; the analysis reads times from the
    // messages.)
    let dir = scratch("picoseconds");
    let s = 2f64.powi(-40);
    let run = |out: &str, scale: f64| {
        let set = |k: &str, v: f64| ["--set".to_string(), format!("{k}={v:e}")];
        let mut args: Vec<String> = [
            "run",
            "--quiet",
            "--out",
            out,
            "--set",
            "species.0.count=400",
        ]
        .iter()
        .map(|x| x.to_string())
        .collect();
        for (k, v) in [
            ("species.0.radius", 0.5),
            ("stop.duration", 20.0),
            ("log.snapshot_interval", 1.0),
            ("log.thermo_interval", 0.5),
            ("log.checkpoint_interval", 10.0),
        ] {
            args.extend(set(k, v * scale));
        }
        let args: Vec<&str> = args.iter().map(|x| x.as_str()).collect();
        ok(&carom(&dir, &args));
        json_of(&carom(&dir, &["analyze", out, "--json"]))
    };
    let reduced = run("reduced.mcap", 1.0);
    let pico = run("pico.mcap", s);
    assert_eq!(
        pico["window"]["snapshot_times"].as_array().unwrap().len(),
        reduced["window"]["snapshot_times"]
            .as_array()
            .unwrap()
            .len()
    );
    assert_eq!(f(&pico["window"]["t_end"]), 20.0 * s);
    assert_eq!(f(&pico["pressure"]["z"]), f(&reduced["pressure"]["z"]));
    assert_eq!(
        f(&pico["collision_rate"]["per_disc"]) * s,
        f(&reduced["collision_rate"]["per_disc"])
    );
    // Too few histogram bins leave the χ² test nothing: a usage error.
    let out = carom(&dir, &["analyze", "pico.mcap", "--bins", "3"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--bins"));
    // `info` shows the channels' spans in the run's own time.
    let i = json_of(&carom(&dir, &["info", "pico.mcap", "--json"]));
    assert_eq!(
        f(&i["channels"]["/snapshot"]["time_span"][1]),
        20.0 * s,
        "{i}"
    );
}

#[test]
fn a_species_with_too_few_speeds_is_reported_untested_not_fatal() {
    // One heavy disc among 400: three snapshots give it three speeds, too few for
    // a χ² test. The rest of the analysis must still come out.
    let dir = scratch("fewspeeds");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            "--out",
            "m.mcap",
            "--set",
            "species.0.count=400",
            "--set",
            r#"species.1={"count": 1, "radius": 0.5, "mass": 2}"#,
            "--set",
            "stop.duration=3",
        ],
    ));
    let r = json_of(&carom(&dir, &["analyze", "m.mcap", "--json"]));
    assert_eq!(r["maxwell_boltzmann"].as_array().unwrap().len(), 1, "{r}");
    assert_eq!(r["maxwell_boltzmann"][0]["species"], 0);
    let u = &r["maxwell_boltzmann_untested"];
    assert_eq!(u.as_array().unwrap().len(), 1, "{r}");
    assert_eq!(u[0]["species"], 1);
    assert!(f(&r["pressure"]["z"]) > 3.0, "{r}");
    let out = carom(&dir, &["analyze", "m.mcap"]);
    let text = ok(&out);
    assert!(
        text.contains("Maxwell–Boltzmann, species 1\n  not tested"),
        "{text}"
    );
    assert!(
        !String::from_utf8_lossy(&out.stderr).contains("reading m.mcap"),
        "a short read shows no progress"
    );
    assert_eq!(ok(&carom(&dir, &["analyze", "--quiet", "m.mcap"])), text);
}

/// Start `carom ARGS` in `dir`, send it `signal` (a `kill` signal name) after
/// `wait_ms`, and collect what it printed and how it ended.
fn signalled(dir: &Path, args: &[&str], signal: &str, wait_ms: u64) -> Output {
    let child = Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(wait_ms));
    let status = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    child.wait_with_output().unwrap()
}

#[test]
fn ctrl_c_while_placing_the_discs_stops_at_once_and_writes_nothing() {
    // Relaxed placement of 40 000 discs beyond jamming minimizes for tens of
    // seconds before it gives up: the progress is shown, and Ctrl-C ends it with
    // the interrupt's exit code and no log.
    let dir = scratch("ctrlc-placing");
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/glass-mixture.json");
    let run = [
        "run",
        config.to_str().unwrap(),
        "--out",
        "dense.mcap",
        "--set",
        "box.packing_fraction=0.85",
        "--set",
        "species.0.count=20000",
        "--set",
        "species.1.count=20000",
    ];
    // Placed at the example's own density: the end of placement is reported.
    let out = Command::new(BIN)
        .args(
            [
                &run[..2],
                &["--out", "placed.mcap", "--set", "stop.duration=0.01"],
            ]
            .concat(),
        )
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("placed 4000 discs (relaxed placement) in "),
        "{stderr}"
    );
    let start = std::time::Instant::now();
    let out = signalled(&dir, &run, "INT", 1500);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    assert!(
        start.elapsed().as_secs() < 10,
        "took {:?} to stop",
        start.elapsed()
    );
    assert!(
        stderr.contains("placing 40000 discs (relaxed placement): step 0 of at most"),
        "{stderr}"
    );
    assert!(
        stderr.contains("interrupted while placing the discs")
            && stderr.contains("no log was written"),
        "{stderr}"
    );
    assert!(!dir.join("dense.mcap").exists());
}

#[test]
fn sigterm_and_sighup_stop_cleanly_also_when_resuming_in_place() {
    // A batch scheduler sends SIGTERM at the end of a job's time; a closed terminal
    // sends SIGHUP. Both must leave a finished log, like Ctrl-C.
    let dir = scratch("sigterm");
    let run = [
        "run",
        "--out",
        "job.mcap",
        "--set",
        "species.0.count=2000",
        "--set",
        "stop.duration=1e6",
        // (The signals are under test, not the projection against a small disk.)
        "--ignore-disk-estimate",
    ];
    let out = signalled(&dir, &run, "TERM", 1500);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    let i = json_of(&carom(&dir, &["info", "job.mcap", "--json"]));
    assert_eq!(i["complete"], true);
    assert_eq!(i["summary"]["stop_reason"], "interrupted");
    let t_first = f(&i["summary"]["sim_time"]);
    // Continued in place (through a temporary file) and hung up: the file is
    // finished (further on, unless the signal came before the first event), and
    // the temporary file is gone.
    let out = signalled(
        &dir,
        &["resume", "job.mcap", "--ignore-disk-estimate"],
        "HUP",
        2500,
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    let j = json_of(&carom(&dir, &["info", "job.mcap", "--json"]));
    assert_eq!(j["complete"], true);
    assert_eq!(j["summary"]["stop_reason"], "interrupted");
    assert!(f(&j["summary"]["sim_time"]) >= t_first, "{j}");
    assert!(!dir.join("job.mcap.resume-tmp").exists());
}

#[test]
fn pressure_from_thermo_totals_when_collisions_are_not_logged() {
    let dir = scratch("nocoll");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            "--out",
            "n.mcap",
            "--set",
            "species.0.count=1024",
            "--set",
            "box.packing_fraction=0.3",
            "--set",
            "stop.duration=150",
            "--set",
            "log.collisions=false",
        ],
    ));
    let i = json_of(&carom(&dir, &["info", "n.mcap", "--json"]));
    assert_eq!(i["logged_collisions"], 0);
    let r = json_of(&carom(&dir, &["analyze", "n.mcap", "--json"]));
    assert_eq!(r["collision_rate"]["logged_pair_collisions"], 0);
    let z = f(&r["pressure"]["z"]);
    let se = f(&r["pressure"]["z_std_error"]);
    assert!(se > 0.0 && se < 0.02, "se = {se}");
    let tol = 3.0 * (se * se + 0.0020f64 * 0.0020).sqrt();
    assert!((z - 2.0633).abs() < tol, "Z = {z} ± {se}");
    // ω from the thermo pair counts; the Enskog check still closes.
    assert!(f(&r["collision_rate"]["per_disc"]) > 2.0);
    // (Z − 1) − (√π/4)ωτ0 = 0 within 4 of its blocked SE (the NVE offset, ≈ 10⁻⁴, is
    // far below it).
    let e = &r["enskog"];
    assert!(
        f(&e["difference"]).abs() < 4.0 * f(&e["difference_std_error"]),
        "{e}"
    );
}

/// Logging every 5000th collision saves disk but must not cost the pressure its
/// precision: the sums over every collision are in the /thermo records, so the
/// same run logged sparsely and fully gives the same Z and ω (before, the sparse
/// log's 1-in-5000 sample gave an estimate: Z = 3.68 ± 0.26 against 4.1085 at
/// η = 0.5 for a 1-in-20000 log).
#[test]
fn a_sparse_collision_log_gives_the_pressure_of_the_full_one() {
    let dir = scratch("sparse");
    let mut report = Vec::new();
    for (file, every) in [("full.mcap", "1"), ("sparse.mcap", "5000")] {
        ok(&carom(
            &dir,
            &[
                "run",
                "--quiet",
                "--out",
                file,
                "--set",
                "species.0.count=400",
                "--set",
                "stop.duration=40",
                "--set",
                &format!("log.collision_every={every}"),
            ],
        ));
        report.push(json_of(&carom(&dir, &["analyze", file, "--json"])));
    }
    let [full, sparse] = [&report[0], &report[1]];
    let logged = |r: &Value| {
        r["collision_rate"]["logged_pair_collisions"]
            .as_u64()
            .unwrap()
    };
    assert!(
        logged(sparse) * 1000 < logged(full),
        "{} vs {}",
        logged(sparse),
        logged(full)
    );
    for (section, key) in [("pressure", "z"), ("collision_rate", "per_disc")] {
        let (a, b) = (f(&full[section][key]), f(&sparse[section][key]));
        assert!(
            (a - b).abs() <= 1e-9 * a.abs(),
            "{section}.{key}: full log {a}, sparse log {b}"
        );
    }
    assert!(f(&sparse["pressure"]["z_std_error"]) < 0.05, "{sparse}");
}

#[test]
fn a_truncated_log_is_analysed_up_to_the_cut_with_a_warning() {
    let dir = scratch("cut");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            "--out",
            "full.mcap",
            "--set",
            "species.0.count=400",
            "--set",
            "box.packing_fraction=0.3",
            "--set",
            "stop.duration=40",
            "--set",
            "log.compression=none",
        ],
    ));
    let bytes = std::fs::read(dir.join("full.mcap")).unwrap();
    std::fs::write(dir.join("cut.mcap"), &bytes[..bytes.len() * 6 / 10]).unwrap();
    let i = json_of(&carom(&dir, &["info", "cut.mcap", "--json"]));
    assert_eq!(i["complete"], false);
    assert_eq!(
        i["verified"], true,
        "a cut log has no index: every message is read"
    );
    assert!(i["summary"].is_null());
    // Damage inside a finished log: its index still reads, but reading every
    // message (info --verify, analyze) finds it.
    let mut damaged = bytes.clone();
    damaged[bytes.len() / 2] ^= 0x10;
    std::fs::write(dir.join("damaged.mcap"), &damaged).unwrap();
    let i = json_of(&carom(&dir, &["info", "damaged.mcap", "--json"]));
    assert_eq!(
        (&i["complete"], &i["verified"]),
        (&json!(true), &json!(false))
    );
    for args in [
        &["info", "--verify", "damaged.mcap"][..],
        &["analyze", "damaged.mcap"],
    ] {
        let out = carom(&dir, args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(
            stderr.contains("damaged.mcap is corrupted"),
            "{args:?}: {stderr}"
        );
    }
    let out = carom(&dir, &["analyze", "cut.mcap", "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(stderr.contains("truncated"), "{stderr}");
    let r = json_of(&out);
    assert_eq!(r["log_complete"], false);
    let t_end = f(&r["window"]["t_end"]);
    assert!(t_end > 5.0 && t_end < 40.0, "{t_end}");
    assert!(f(&r["pressure"]["z"]) > 1.8 && f(&r["pressure"]["z"]) < 2.4);
}

#[test]
fn analyze_spaces_snapshots_five_collisions_apart_unless_told_and_warns_when_closer() {
    let dir = scratch("spacing");
    ok(&carom(
        &dir,
        &[
            "run",
            "--quiet",
            "--out",
            "dense.mcap",
            "--set",
            "species.0.count=400",
            "--set",
            "stop.duration=10",
            "--set",
            "log.snapshot_interval=0.02",
        ],
    ));
    let text = ok(&carom(&dir, &["analyze", "dense.mcap"]));
    let flat = text.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        flat.contains("apart: 5 pair collisions per disc (--every to change)"),
        "{text}"
    );
    assert!(!text.contains("warning"), "{text}");
    let r = json_of(&carom(&dir, &["analyze", "dense.mcap", "--json"]));
    let w = &r["window"];
    assert_eq!(w["every_default"], true);
    let omega = f(&r["collision_rate"]["per_disc"]);
    // The rate from the thermo records (whole log) and the one measured over the
    // window agree to a few per cent.
    assert!((f(&w["every"]) * omega / 5.0 - 1.0).abs() < 0.05, "{w}");
    assert!(f(&w["spacing_collisions"]) >= 4.5, "{w}");
    // Every snapshot, 0.02 apart (about 0.14 collisions per disc): a warning.
    let text = ok(&carom(&dir, &["analyze", "dense.mcap", "--every", "0"]));
    assert!(
        text.contains("warning: the snapshots used are only") && text.contains("reject too often"),
        "{text}"
    );
    let r = json_of(&carom(
        &dir,
        &["analyze", "dense.mcap", "--json", "--every", "0"],
    ));
    assert_eq!(r["window"]["every_default"], false);
    assert!(
        f(&r["window"]["spacing_collisions"]) < 0.5,
        "{}",
        r["window"]
    );
}

/// A log that cannot be written to the end (here: a file size limit, as a full disk
/// would do) stops the run with the operating system's reason, not the MCAP
/// library's generic one, and says that the log is readable and how to continue
/// it; `resume` then finishes the run into another file.
#[cfg(unix)]
#[test]
fn a_log_cut_by_a_write_error_names_the_cause_and_resumes() {
    let dir = scratch("write-error");
    // RLIMIT_FSIZE of 20000 blocks (10 or 20 MB, as the shell counts them); SIGXFSZ
    // ignored, so that a write past the limit fails with EFBIG instead of killing
    // the process.
    let script = format!(
        "trap '' XFSZ; ulimit -f 20000; exec '{BIN}' run --out cut.mcap --quiet \
         --set species.0.count=4000 --set stop.duration=40"
    );
    let out = sh(&dir, &script);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("File too large"), "{stderr}");
    assert!(!stderr.contains("compression stream"), "{stderr}");
    assert!(stderr.contains("carom resume cut.mcap"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let size = std::fs::metadata(dir.join("cut.mcap")).unwrap().len();
    assert!(size <= 20_000 * 1024, "{size} bytes");
    let i = json_of(&carom(&dir, &["info", "cut.mcap", "--json"]));
    assert_eq!(i["complete"], false);
    let resume = ["resume", "cut.mcap", "--out", "whole.mcap", "--quiet"];
    ok(&carom(&dir, &resume));
    let j = json_of(&carom(&dir, &["info", "whole.mcap", "--json"]));
    assert_eq!(j["complete"], true);
    assert_eq!(j["summary"]["stop_reason"], "time");
    assert_eq!(f(&j["summary"]["sim_time"]), 40.0);
}

/// A single disc cannot be given a temperature (zero total momentum leaves it at
/// rest): the configuration is refused naming `temperature`. Placed at rest
/// explicitly, it runs, and `analyze` reports its velocities as untested (no
/// thermal motion) instead of failing.
#[test]
fn a_disc_at_rest_is_refused_a_temperature_and_analysed_without_error() {
    let dir = scratch("at-rest");
    let out = carom(
        &dir,
        &[
            "run",
            "--set",
            "species.0.count=1",
            "--out",
            "one.mcap",
            "-q",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("temperature") && stderr.contains("single disc"),
        "{stderr}"
    );
    let config = json!({
        "species": [{"count": 1, "radius": 0.5, "mass": 1.0}],
        "box": {"size": [4.0, 4.0]},
        "placement": {"explicit": [[1.0, 2.0]]},
        "velocities": {"explicit": [[0.0, 0.0]]},
        "stop": {"duration": 5.0},
        "log": {"snapshot_interval": 0.5}
    });
    std::fs::write(dir.join("rest.json"), config.to_string()).unwrap();
    ok(&carom(&dir, &["run", "rest.json", "-q"]));
    let a = json_of(&carom(&dir, &["analyze", "rest.mcap", "--json", "-q"]));
    assert_eq!(f(&a["temperature"]["kt"]), 0.0);
    assert_eq!(a["maxwell_boltzmann"], json!([]));
    let untested = &a["maxwell_boltzmann_untested"][0];
    assert_eq!(untested["species"], 0);
    assert!(
        untested["reason"]
            .as_str()
            .unwrap()
            .contains("no thermal motion"),
        "{untested}"
    );
}

/// A directory given as a log is named as such (Linux opens it like a file and
/// then fails to read it with "Invalid argument").
#[test]
fn a_directory_given_as_a_log_is_named_as_one() {
    let dir = scratch("directory");
    std::fs::create_dir_all(dir.join("logs")).unwrap();
    for args in [
        &["analyze", "logs"][..],
        &["info", "logs"],
        &["resume", "logs", "--out", "x.mcap"],
    ] {
        let out = carom(&dir, args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(
            stderr.contains("logs: a directory, not a log file"),
            "{args:?}: {stderr}"
        );
    }
}

/// A negative time option is refused by the option's own check, naming it, rather
/// than taken for an unknown flag by the argument parser.
#[test]
fn negative_times_are_refused_naming_the_option() {
    let dir = scratch("negative");
    ok(&carom(
        &dir,
        &[
            "run",
            "--set",
            "species.0.count=200",
            "--set",
            "stop.duration=2",
            "--out",
            "small.mcap",
            "-q",
        ],
    ));
    for (args, named) in [
        (
            &["analyze", "small.mcap", "--every", "-1"][..],
            "--every -1",
        ),
        (&["resume", "small.mcap", "--until", "-3"], "stop time -3"),
    ] {
        let out = carom(&dir, args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(named), "{args:?}: {stderr}");
        assert!(!stderr.contains("unexpected argument"), "{stderr}");
    }
}

/// Issue 33, item 1: a run far larger than the machine's memory (4·10⁹ discs need
/// about 2 TB) is refused at once with the numbers and the field, with exit status
/// 2, before anything of the size of N is allocated; `--dry-run` checks it too,
/// and `CAROM_IGNORE_MEMORY_CHECK=1` skips the check.
#[test]
fn a_run_larger_than_the_memory_is_refused_before_placing() {
    let dir = scratch("memory-check");
    let mut child = Command::new(BIN)
        .args(["run", "--set", "species.0.count=4e9", "--out", "huge.mcap"])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Before the check this placed discs for minutes with memory climbing: give
    // it a generous 30 s, then stop it and fail.
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed().as_secs() >= 30 {
            child.kill().unwrap();
            child.wait().unwrap();
            panic!("a run of 4e9 discs was still going after 30 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    for needed in [
        "species.0.count",
        "4000000000 discs need about 2240.0 GB",
        "available",
    ] {
        assert!(stderr.contains(needed), "{needed:?} not in: {stderr}");
    }
    assert!(stderr.contains("CAROM_IGNORE_MEMORY_CHECK=1"), "{stderr}");
    assert!(!dir.join("huge.mcap").exists());
    let dry = carom(&dir, &["run", "--set", "species.0.count=4e9", "--dry-run"]);
    assert_eq!(dry.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&dry.stderr).contains("species.0.count"));
    let ignored = Command::new(BIN)
        .args(["run", "--set", "species.0.count=4e9", "--dry-run"])
        .env("CAROM_IGNORE_MEMORY_CHECK", "1")
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(ok(&ignored).contains("4000000000"));
}
