//! A sweep's directory: `plan.json` (the plan with its base configuration inlined
//! and its ranges expanded, so the directory stands alone), `points.json` (the
//! points in order: the index of a Slurm array task is a position in it), and one
//! directory per point with its `config.json`, its log `run.mcap`, the output of
//! its last attempt `carom.log`, and `failed.txt` while its last attempt failed.

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

use super::error::io;
use super::{Plan, SweepError};

/// A sweep's directory and its plan.
#[derive(Debug, Clone)]
pub struct SweepDir {
    /// The directory.
    pub dir: PathBuf,
    /// The plan it holds.
    pub plan: Plan,
}

impl SweepDir {
    /// Lay out `plan` in `dir` (created if missing). A directory that already holds
    /// a sweep is accepted only if its points are the same (same names and
    /// configurations): re-running a sweep continues it, and another plan needs
    /// another directory.
    pub fn create(dir: &Path, plan: Plan) -> Result<SweepDir, SweepError> {
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let stored = dir.join("plan.json");
        if stored.exists() {
            let old = Plan::load(&stored)?;
            // Point by point, one configuration at a time.
            let same = old.points.len() == plan.points.len()
                && (0..plan.points.len()).all(|i| {
                    old.points[i].name == plan.points[i].name && old.config(i) == plan.config(i)
                });
            if !same {
                return Err(SweepError::Directory {
                    dir: dir.to_path_buf(),
                    problem: "holds a sweep of another plan (its plan.json expands to other \
                              points or configurations); give another --out, or remove it"
                        .into(),
                });
            }
        } else {
            write(&stored, &plan_text(&plan))?;
        }
        write(&dir.join("points.json"), &points_text(&plan))?;
        Ok(SweepDir {
            dir: dir.to_path_buf(),
            plan,
        })
    }

    /// Make point `i`'s directory and write its `config.json` (again, if it is
    /// there: the plan's configuration is the one that runs).
    pub fn prepare_point(&self, i: usize) -> Result<(), SweepError> {
        std::fs::create_dir_all(self.point_dir(i)).map_err(io(self.point_dir(i)))?;
        let text = serde_json::to_string_pretty(&self.plan.config(i)).expect("JSON") + "\n";
        write(&self.config_path(i), &text)
    }

    /// The sweep laid out in `dir` by [`SweepDir::create`].
    pub fn open(dir: &Path) -> Result<SweepDir, SweepError> {
        let stored = dir.join("plan.json");
        if !stored.exists() {
            return Err(SweepError::Directory {
                dir: dir.to_path_buf(),
                problem: "holds no sweep (no plan.json; `carom sweep PLAN --out DIR` makes one)"
                    .into(),
            });
        }
        Ok(SweepDir {
            dir: dir.to_path_buf(),
            plan: Plan::load(&stored)?,
        })
    }

    /// Point `i`'s directory.
    pub fn point_dir(&self, i: usize) -> PathBuf {
        self.dir.join(&self.plan.points[i].name)
    }
    /// Point `i`'s configuration file.
    pub fn config_path(&self, i: usize) -> PathBuf {
        self.point_dir(i).join("config.json")
    }
    /// Point `i`'s log.
    pub fn log_path(&self, i: usize) -> PathBuf {
        self.point_dir(i).join("run.mcap")
    }
    /// What point `i`'s last attempt printed.
    pub fn output_path(&self, i: usize) -> PathBuf {
        self.point_dir(i).join("carom.log")
    }
    /// Present while point `i`'s last attempt failed: its exit status and last words.
    pub fn failure_path(&self, i: usize) -> PathBuf {
        self.point_dir(i).join("failed.txt")
    }
}

/// The plan as stored: base inlined, ranges expanded, axes in their order.
fn plan_text(plan: &Plan) -> String {
    let mut s = String::from("{\n");
    if let Some(d) = &plan.description {
        s += &format!("  \"description\": {},\n", Value::from(d.clone()));
    }
    s += "  \"base\": ";
    let base = serde_json::to_string_pretty(&plan.base).expect("JSON");
    s += &base.replace('\n', "\n  ");
    s += ",\n  \"vary\": {";
    for (k, a) in plan.axes.iter().enumerate() {
        s += if k == 0 { "\n    " } else { ",\n    " };
        s += &format!(
            "{}: {}",
            Value::from(a.path.clone()),
            Value::from(a.values.clone())
        );
    }
    s += if plan.axes.is_empty() {
        "},\n"
    } else {
        "\n  },\n"
    };
    s += &format!(
        "  \"replicas\": {},\n  \"seed\": {}\n}}\n",
        plan.replicas, plan.first_seed
    );
    s
}

/// `points.json`: one object per point, `{"index", "name", "seed", "values"}`,
/// written one point at a time.
fn points_text(plan: &Plan) -> String {
    let mut s = String::from("[");
    for (i, p) in plan.points.iter().enumerate() {
        let values: serde_json::Map<String, Value> = plan
            .axes
            .iter()
            .zip(&p.values)
            .map(|(a, v)| (a.path.clone(), v.clone()))
            .collect();
        s += if i == 0 { "\n  " } else { ",\n  " };
        s += &json!({"index": i, "name": p.name, "seed": p.seed, "values": values}).to_string();
    }
    s += "\n]\n";
    s
}

/// Write `text` to `path` through a temporary file renamed over it, so that a
/// crash leaves the old file or the new one.
fn write(path: &Path, text: &str) -> Result<(), SweepError> {
    let tmp = path.with_extension("json.tmp");
    std::fs::write(&tmp, text).map_err(io(&tmp))?;
    std::fs::rename(&tmp, path).map_err(io(path))
}
