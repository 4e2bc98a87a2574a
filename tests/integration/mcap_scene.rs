//! The `/scene` channel: written every `log.scene_interval` when asked (never by
//! default), skipped by carom's readers, continued frame for frame by a resume,
//! and decoded by Foxglove's own decoders (`tests/node/scene.mjs`: `@mcap/core`,
//! `@foxglove/rosmsg`, `@foxglove/rosmsg2-serialization`) to discs at the
//! positions and sizes of `/snapshot`, and by Python's `mcap-ros2-support`. The
//! node part runs when node and `npm install --prefix tests/node` are there, the
//! Python part with `CAROM_PYTHON` (see `mcap_python.rs`); each is skipped with a
//! message otherwise, and fails instead when `CI` is set.

use crate::mcap_common::*;
use carom_log::{scan, LogOptions, LogReader, Stop, CH_SCENE, CH_SNAPSHOT, THERMO_JSON_SCHEMA};
use carom_run::{resume, run, Control, ResumeOptions};
use serde_json::Value;
use std::path::Path;
use std::process::Command;

fn log(scene: Option<f64>) -> LogOptions {
    LogOptions {
        snapshot_interval: Some(0.5),
        thermo_interval: Some(0.5),
        checkpoint_interval: Some(1.0),
        scene_interval: scene,
        ..LogOptions::default()
    }
}

/// The `/scene` messages as (sequence, log time, bytes).
fn scene_messages(path: &Path) -> Vec<(u32, u64, Vec<u8>)> {
    let mut r = LogReader::open(path).unwrap();
    let mut v = Vec::new();
    while let Some(m) = r.next_raw().unwrap() {
        if m.channel == CH_SCENE {
            v.push((m.sequence, m.log_time, m.data.to_vec()));
        }
    }
    v
}

/// What `tests/node/scene.mjs` finds in `path`; `None` to skip when node or the
/// packages are missing (a failure under `CI`: `skip_or_fail`).
fn node_scene(path: &Path) -> Option<Value> {
    let dir = node_with("@foxglove/rosmsg2-serialization")?;
    let out = Command::new("node")
        .arg(dir.join("scene.mjs"))
        .arg(path)
        .output()
        .expect("node runs");
    assert!(
        out.status.success(),
        "Foxglove's decoders disagree with /snapshot in {}:\n{}",
        path.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    Some(serde_json::from_slice(&out.stdout).expect("scene.mjs prints JSON"))
}

#[test]
fn foxglove_decodes_scene_frames_that_match_the_snapshots() {
    // A walled mixture: two species (two colours, two diameters), walls in y.
    let system = system(300, 0.45, true, true, 34);
    let out = tmp("scene.mcap");
    run(
        &spec(system, Stop::Time(2.0), log(Some(0.25))),
        &out,
        Control::default(),
    )
    .unwrap();
    // Frames at 0, 0.25, …, 2 with sequence numbers 0, 1, …; carom's own
    // readers see only the other channels.
    let frames = scene_messages(&out);
    let seq: Vec<u32> = frames.iter().map(|f| f.0).collect();
    assert_eq!(seq, (0..9).collect::<Vec<_>>());
    let times: Vec<u64> = frames.iter().map(|f| f.1).collect();
    assert_eq!(times, (0..9).map(|k| k * 250_000_000).collect::<Vec<_>>());
    let info = scan(&out).unwrap();
    assert!(info.channels[CH_SCENE]);
    assert_eq!(info.messages[CH_SCENE], 9);
    assert_eq!(info.messages[CH_SNAPSHOT], 5);
    let mut r = LogReader::open(&out).unwrap();
    let mut messages = 0;
    while r.next_message().unwrap().is_some() {
        messages += 1;
    }
    let counted: u64 = (0..CH_SCENE).map(|k| info.messages[k]).sum();
    assert_eq!(messages, counted, "next_message skips /scene");
    let mut r = LogReader::open(&out).unwrap();
    assert_eq!(r.snapshots().count(), 5);

    // mcap-ros2-support, the Python decoder of ROS 2 messages, reads the frames too.
    if let Some(py) = python() {
        let script = "import sys; from mcap.reader import make_reader\n\
            from mcap_ros2.decoder import DecoderFactory\n\
            d = DecoderFactory(); out = []\n\
            for s, c, m in make_reader(open(sys.argv[1], 'rb')).iter_messages(topics=['/scene']):\n\
            \x20   e = d.decoder_for(c.message_encoding, s)(m.data).entities[0]\n\
            \x20   p = e.cylinders[-1].pose.position\n\
            \x20   out.append(f'{e.id} {len(e.cylinders)} {p.x!r} {e.lines[0].points[2].y!r}')\n\
            print('\\n'.join(out))";
        let o = Command::new(&py)
            .args(["-c", script, out.to_str().unwrap()])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = String::from_utf8(o.stdout).unwrap();
        let mut r = LogReader::open(&out).unwrap();
        let snap = match r.snapshots().next().unwrap().unwrap() {
            carom_log::LogMessage::Snapshot(s) => s,
            m => panic!("{m:?}"),
        };
        let first = text.lines().next().unwrap();
        let want = format!(
            "discs 300 {:?} {:?}",
            snap.positions[299].x, snap.box_size.y
        );
        assert_eq!(first, want);
        assert_eq!(text.lines().count(), 9);
    }

    if let Some(v) = node_scene(&out) {
        assert_eq!(
            v["schema"],
            serde_json::json!(["foxglove_msgs/msg/SceneUpdate", "ros2msg", "cdr"])
        );
        assert_eq!(v["frames"], 9, "{v}");
        assert_eq!(v["snapshots"], 5, "{v}");
        assert_eq!(v["checked"], 5, "every snapshot has its frame: {v}");
        assert_eq!(v["discs"], 5 * 300, "{v}");
        let colours = v["colours"].as_object().unwrap();
        assert_eq!(colours.len(), 2, "{v}");
        assert_ne!(colours["0"], colours["1"], "species differ in colour: {v}");
    }
}

#[test]
fn no_scene_unless_asked() {
    let out = tmp("no-scene.mcap");
    run(
        &spec(system(50, 0.3, false, false, 3), Stop::Time(1.0), log(None)),
        &out,
        Control::default(),
    )
    .unwrap();
    let info = scan(&out).unwrap();
    assert!(!info.channels[CH_SCENE], "the channel is not even defined");
    assert_eq!(info.messages[CH_SCENE], 0);
}

#[test]
fn a_resumed_run_continues_the_frames_of_the_uninterrupted_one() {
    let system = system(200, 0.5, false, true, 12);
    let short = tmp("scene-short.mcap");
    run(
        &spec(system.clone(), Stop::Time(1.0), log(Some(0.3))),
        &short,
        Control::default(),
    )
    .unwrap();
    let extended = tmp("scene-extended.mcap");
    let opts = ResumeOptions {
        stop: Some(Stop::Time(2.5)),
    };
    resume(&short, &extended, &opts, Control::default()).unwrap();
    let long = tmp("scene-long.mcap");
    run(
        &spec(system, Stop::Time(2.5), log(Some(0.3))),
        &long,
        Control::default(),
    )
    .unwrap();
    let (a, b) = (scene_messages(&extended), scene_messages(&long));
    // Frames at 0, 0.3, …, 2.4: the same bytes, times and sequence numbers.
    assert_eq!(b.len(), 9);
    assert!(a == b, "the resumed log's frames differ");
}

/// The panel ids in a Foxglove layout tree (a panel id, or a split of two trees).
fn panels(tree: &Value, out: &mut Vec<String>) {
    match tree {
        Value::String(id) => out.push(id.clone()),
        _ => {
            panels(&tree["first"], out);
            panels(&tree["second"], out);
        }
    }
}

#[test]
fn the_foxglove_layout_shows_the_scene_from_above_beside_thermo_plots() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/foxglove/layout.json");
    let layout: Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    let configs = layout["configById"].as_object().unwrap();
    let mut ids = vec![];
    panels(&layout["layout"], &mut ids);
    ids.sort();
    let mut configured: Vec<String> = configs.keys().cloned().collect();
    configured.sort();
    assert_eq!(ids, configured, "every panel in the tree has its config");
    let thermo: Value = serde_json::from_str(THERMO_JSON_SCHEMA).unwrap();
    let (mut views, mut plotted) = (0, 0);
    for (id, c) in configs {
        if id.starts_with("3D!") {
            views += 1;
            assert_eq!(c["followTf"], "box", "{id} follows the scene's frame");
            assert_eq!(c["topics"]["/scene"]["visible"], true, "{id}");
            assert_eq!(c["cameraState"]["phi"], 0.0, "{id} looks straight down");
        } else {
            assert!(id.starts_with("Plot!"), "{id}");
            for p in c["paths"].as_array().unwrap() {
                let path = p["value"].as_str().unwrap();
                let field = path.strip_prefix("/thermo.").expect("plots of /thermo");
                assert!(
                    thermo["properties"].get(field).is_some(),
                    "{path}: /thermo has no field {field}"
                );
                plotted += 1;
            }
        }
    }
    assert_eq!(views, 1);
    assert!(plotted >= 2);
}
