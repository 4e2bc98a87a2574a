//! The observables on plain arrays (`carom_analysis::frames`) against
//! `carom analyze --json` of the same log: a small run is exported to GSD, the
//! GSD read back with `hoomd-gsd` (float32 positions centred on the box, as
//! HOOMD has them), and its frames after the report's `window.equilibrate` fed to
//! `frames::structure` over the report's window. Every snapshot of the log is a
//! frame and starts a block (no snapshot schedule), so both use the same
//! snapshots; the positions differ by float32 rounding only, so the contact
//! value, |Ψ6| and the S(k) peak agree to far below their standard errors.

use std::path::PathBuf;
use std::process::Command;

use carom_analysis::frames::{structure, Frame, System, Window};
use carom_core::{SimBox, Species};
use hoomd_gsd::file_layer::{GsdFile, Mode};

fn carom(dir: &PathBuf, args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_carom"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The frames of a GSD file written by `carom export`: time, species, and
/// positions moved back from HOOMD's centred box.
fn read_gsd(path: &PathBuf) -> Vec<Frame> {
    let f = GsdFile::open(path, Mode::Read).unwrap();
    (0..f.n_frames())
        .map(|k| {
            let time = f
                .iter_scalars::<f64>(k, "log/carom/time")
                .unwrap()
                .next()
                .unwrap();
            let b: Vec<f32> = f.iter_scalars(k, "configuration/box").unwrap().collect();
            let (lx, ly) = (f64::from(b[0]), f64::from(b[1]));
            let species = f
                .iter_scalars::<u32>(k, "particles/typeid")
                .unwrap()
                .map(|t| t as u16)
                .collect();
            let p: Vec<[f32; 3]> = f.iter_arrays(k, "particles/position").unwrap().collect();
            Frame {
                time,
                species,
                x: p.iter().map(|p| f64::from(p[0]) + lx / 2.0).collect(),
                y: p.iter().map(|p| f64::from(p[1]) + ly / 2.0).collect(),
                velocities: None,
            }
        })
        .collect()
}

#[test]
fn gsd_frames_give_the_structure_of_analyze() {
    let dir = std::env::temp_dir().join(format!("carom-arrays-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = [
        "run",
        "--set",
        "species.0.count=400",
        "--set",
        "stop.duration=10",
        "--out",
        "a.mcap",
        "--force",
        "-q",
    ];
    carom(&dir, &run);
    carom(
        &dir,
        &[
            "export", "a.mcap", "--format", "gsd", "-o", "a.gsd", "-q", "-f",
        ],
    );
    let r: serde_json::Value =
        serde_json::from_str(&carom(&dir, &["analyze", "a.mcap", "--json", "-q"])).unwrap();
    let frames = read_gsd(&dir.join("a.gsd"));
    let w = &r["window"];
    let window = Window {
        start: w["equilibrate"].as_f64().unwrap(),
        end: w["t_end"].as_f64().unwrap(),
    };
    let used = frames.iter().filter(|f| f.time >= window.start).count();
    assert_eq!(used, w["snapshot_times"].as_array().unwrap().len());
    assert!(used >= 5, "{used}");
    let species = r["species"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let f = |k: &str| s[k].as_f64().unwrap();
            Species::new(f("count") as usize, f("radius"), f("mass"))
        })
        .collect();
    assert_eq!(r["periodic"], serde_json::json!([true, true]));
    let size = |i: usize| r["box_size"][i].as_f64().unwrap();
    let system = System {
        sim_box: SimBox::periodic(size(0), size(1)),
        species,
    };
    let s = structure(&system, window, &frames).unwrap();
    let near = |a: f64, b: &serde_json::Value, tol: f64| {
        let b = b.as_f64().unwrap();
        assert!((a - b).abs() <= tol * b.abs(), "{a} against {b}");
    };
    let pc = s.pair_correlation.unwrap();
    let want = &r["pair_correlation"]["pairs"][0];
    let contact = pc.pairs[0].contact.as_ref().unwrap();
    near(contact.value, &want["contact"]["value"], 1e-3);
    assert_eq!(pc.pairs[0].g.len(), want["g"].as_array().unwrap().len());
    let bo = s.bond_order.unwrap();
    near(bo.global, &r["bond_order"]["global"], 1e-4);
    near(bo.local, &r["bond_order"]["local"], 1e-4);
    assert_eq!(
        bo.snapshots as u64,
        r["bond_order"]["snapshots"].as_u64().unwrap()
    );
    let sk = s.structure_factor.unwrap();
    near(sk.peak_s.unwrap(), &r["structure_factor"]["peak_s"], 1e-3);
    near(sk.peak_k.unwrap(), &r["structure_factor"]["peak_k"], 1e-12);
    let _ = std::fs::remove_dir_all(&dir);
}
