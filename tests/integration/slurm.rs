//! `carom sweep --slurm` on a real Slurm: a 2 × 2 sweep submitted as a 4-task job
//! array with `--wait`, every point finished by its task, the results collected,
//! and a second submission finding nothing left to run. The cluster is the
//! single-node one `.ci/slurm-start` starts on this machine; where no Slurm
//! answers (`sinfo` shows no idle node) the test says it skipped.

use std::process::Command;

use crate::cli_common::{carom, json_of, ok, scratch};

/// Whether a Slurm controller answers with an idle node.
fn slurm_up() -> bool {
    Command::new("sinfo")
        .args(["-h", "-o", "%T"])
        .output()
        .map(|o| {
            o.status.success()
                && String::from_utf8_lossy(&o.stdout)
                    .lines()
                    .any(|l| l == "idle")
        })
        .unwrap_or(false)
}

#[test]
fn a_job_array_runs_every_point_and_collects() {
    if !slurm_up() {
        // CI starts a cluster (.ci/run) and says so: there a missing one is a failure.
        assert!(
            std::env::var_os("CAROM_SLURM").is_none(),
            "CAROM_SLURM is set but no Slurm node is idle"
        );
        eprintln!("skipped: no Slurm cluster answers here (start one with .ci/slurm-start)");
        return;
    }
    let dir = scratch("array");
    std::fs::write(
        dir.join("plan.json"),
        r#"{"base": {"species": [{"count": 100}], "stop": {"duration": 10},
                     "log": {"snapshot_interval": 0.5}},
            "vary": {"box.packing_fraction": [0.2, 0.4]}, "replicas": 2}"#,
    )
    .unwrap();
    let out = carom(
        &dir,
        &[
            "sweep",
            "plan.json",
            "--out",
            "out",
            "--slurm",
            "--wait",
            "--time",
            "10",
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    let stdout = ok(&out);
    assert!(
        stderr.contains("submitted job array") && stderr.contains("4 of 4 points"),
        "{stderr}"
    );
    assert!(stdout.contains("done: 4"), "{stdout}");
    let script = std::fs::read_to_string(dir.join("out/slurm/sweep.sbatch")).unwrap();
    assert!(
        script.contains("#SBATCH --array=0-3") && script.contains("#SBATCH --time=10"),
        "{script}"
    );
    // Each task's own output says its point finished.
    let outputs: Vec<String> = std::fs::read_dir(dir.join("out/slurm"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "out"))
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect();
    assert_eq!(outputs.len(), 4, "{outputs:?}");
    assert!(outputs.iter().all(|o| o.contains("): Done")), "{outputs:?}");

    let c = json_of(&carom(
        &dir,
        &["collect", "out", "--json", "--no-structure", "-q"],
    ));
    let points = c["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    for p in points {
        assert_eq!(p["runs"].as_array().unwrap().len(), 2, "{p}");
        assert!(p["results"]["Z"]["value"].as_f64().unwrap() > 1.0);
    }
    // Submitting again finds every point finished: no new array.
    let again = carom(&dir, &["sweep", "plan.json", "--out", "out", "--slurm"]);
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(
        again.status.success() && stderr.contains("finished or running"),
        "{stderr}"
    );
}
