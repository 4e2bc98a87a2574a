//! Foxglove can plot `/thermo` of every kind of log: each JSON schema carom writes
//! follows the rules of Foxglove's JSON Schema reader (every property typed, an
//! enum of strings typed "string"), and every record decodes against it. Checked
//! by `tests/node/jsonschema.mjs` on a plain run and on runs with gravity, each
//! thermostat, compression and the vibrating floor (a property without a type made
//! Foxglove drop the whole channel). Skips without node and tests/node's modules;
//! fails instead when `CI` is set.

use std::path::Path;
use std::process::Command;

use crate::cli_common::{carom, node_with, ok, scratch};

/// What the node checker says of `log`: (schemas, messages on `/thermo`).
fn foxglove_check(dir: &Path, log: &str) -> Option<(u64, u64)> {
    let node = node_with("@mcap/core")?;
    let out = Command::new("node")
        .arg(node.join("jsonschema.mjs"))
        .arg(dir.join(log))
        .output()
        .expect("node runs");
    assert!(
        out.status.success(),
        "Foxglove's JSON Schema rules reject {log}:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    Some((
        v["schemas"].as_u64().unwrap(),
        v["per_topic"]["/thermo"].as_u64().unwrap_or(0),
    ))
}

#[test]
fn every_kind_of_log_has_a_thermo_channel_foxglove_decodes() {
    let dir = scratch("kinds");
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("data");
    let example = |name: &str| data.join(name).to_string_lossy().into_owned();
    // (log, configuration or none for the default, overrides that keep it short)
    let kinds: [(&str, Option<String>, &[&str]); 6] = [
        ("plain", None, &["species.0.count=200", "stop.duration=5"]),
        (
            "gravity",
            Some(example("atmosphere.json")),
            &["stop.duration=10"],
        ),
        (
            "andersen",
            Some(example("thermostatted-fluid.json")),
            &["stop.duration=5"],
        ),
        (
            "driven",
            Some(example("driven-granular.json")),
            &["stop.duration=5"],
        ),
        (
            "compression",
            Some(example("compression-crystal.json")),
            &[
                "species.0.count=200",
                "compression.rate=0.05",
                "stop.duration=20",
            ],
        ),
        (
            "floor",
            Some(example("vibrated-bed.json")),
            &["stop.duration=10"],
        ),
    ];
    for (name, config, sets) in kinds {
        let log = format!("{name}.mcap");
        let mut args = vec!["run".to_string()];
        args.extend(config);
        args.extend(["--out".into(), log.clone(), "-q".into()]);
        for s in sets {
            args.extend(["--set".to_string(), s.to_string()]);
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        ok(&carom(&dir, &args));
        let Some((schemas, thermo)) = foxglove_check(&dir, &log) else {
            return;
        };
        assert!(schemas >= 1, "{name}: no JSON schema checked");
        assert!(thermo >= 5, "{name}: only {thermo} /thermo records decoded");
    }
}
