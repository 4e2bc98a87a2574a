//! Slurm: a sweep's unfinished points as one job array. The batch script
//! (`DIR/slurm/sweep.sbatch`) runs `carom sweep point DIR --index $SLURM_ARRAY_TASK_ID`
//! in each task, which runs or resumes that point exactly as the local pool
//! would; `sbatch --parsable` submits it (with `--wait` it blocks until the array
//! ends). Nothing is asked of Slurm afterwards: `carom sweep status` reads the
//! points' logs, which also works where accounting (`sacct`) is off. The `carom`
//! binary and the sweep directory must be on a file system the nodes share.

use std::path::{Path, PathBuf};
use std::process::Command;

use super::error::io;
use super::{SweepDir, SweepError};

/// The `#SBATCH` choices of `carom sweep --slurm`.
#[derive(Debug, Clone, Default)]
pub struct SlurmOptions {
    /// `--partition`.
    pub partition: Option<String>,
    /// `--time` (Slurm's forms, e.g. `2:00:00`).
    pub time: Option<String>,
    /// `--mem` (e.g. `2G`).
    pub mem: Option<String>,
    /// `--cpus-per-task`.
    pub cpus_per_task: Option<u32>,
    /// More `sbatch` arguments, passed as given.
    pub extra: Vec<String>,
    /// Block until the array ends (`sbatch --wait`).
    pub wait: bool,
}

/// `indices` in Slurm's array syntax, runs merged: `0-3,5,7-9`.
pub fn array_spec(indices: &[usize]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut k = 0;
    while k < indices.len() {
        let a = indices[k];
        let mut b = a;
        while k + 1 < indices.len() && indices[k + 1] == b + 1 {
            k += 1;
            b += 1;
        }
        parts.push(if a == b {
            a.to_string()
        } else {
            format!("{a}-{b}")
        });
        k += 1;
    }
    parts.join(",")
}

/// The batch script for the points `indices` of `sweep`, run with `exe`.
pub fn script(sweep: &SweepDir, exe: &Path, indices: &[usize], opts: &SlurmOptions) -> String {
    let dir = sweep.dir.display();
    let name = sweep
        .dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "sweep".into());
    let mut s = String::from("#!/bin/sh\n");
    s += &format!("#SBATCH --job-name=carom-{}\n", shell_safe(&name));
    s += &format!("#SBATCH --array={}\n", array_spec(indices));
    s += &format!("#SBATCH --output={dir}/slurm/%A_%a.out\n");
    s += "#SBATCH --ntasks=1\n";
    if let Some(p) = &opts.partition {
        s += &format!("#SBATCH --partition={p}\n");
    }
    if let Some(t) = &opts.time {
        s += &format!("#SBATCH --time={t}\n");
    }
    if let Some(m) = &opts.mem {
        s += &format!("#SBATCH --mem={m}\n");
    }
    if let Some(c) = opts.cpus_per_task {
        s += &format!("#SBATCH --cpus-per-task={c}\n");
    }
    s += "# Each task runs (or resumes) one point of the sweep; `carom sweep status`\n";
    s += "# reads how they went from the points' logs.\n";
    s += &format!(
        "exec {} sweep point {} --index \"$SLURM_ARRAY_TASK_ID\"\n",
        quote(&exe.display().to_string()),
        quote(&dir.to_string())
    );
    s
}

/// Write the script for `indices` and submit it; the job ID.
pub fn submit(
    sweep: &SweepDir,
    exe: &Path,
    indices: &[usize],
    opts: &SlurmOptions,
) -> Result<String, SweepError> {
    let dir = sweep.dir.join("slurm");
    std::fs::create_dir_all(&dir).map_err(io(&dir))?;
    let path: PathBuf = dir.join("sweep.sbatch");
    std::fs::write(&path, script(sweep, exe, indices, opts)).map_err(io(&path))?;
    let mut cmd = Command::new("sbatch");
    cmd.arg("--parsable");
    if opts.wait {
        cmd.arg("--wait");
    }
    cmd.args(&opts.extra).arg(&path);
    let out = cmd.output().map_err(|e| {
        SweepError::Slurm(format!(
            "cannot run sbatch ({e}); is Slurm installed and on PATH?"
        ))
    })?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    let job = stdout.trim().split(';').next().unwrap_or("").to_owned();
    if job.is_empty() {
        return Err(SweepError::Slurm(format!(
            "sbatch {} failed ({}): {}",
            path.display(),
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        )));
    }
    // With --wait, sbatch's status is the array's: non-zero if a task failed,
    // which the points' own states tell in detail.
    Ok(job)
}

/// `s` single-quoted for sh.
fn quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', "'\\''"))
}

/// `s` with anything but letters, digits, `-`, `_`, `.` and `=` replaced.
fn shell_safe(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.=".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn array_specs_merge_runs() {
        assert_eq!(array_spec(&[0, 1, 2, 3]), "0-3");
        assert_eq!(array_spec(&[0, 2, 3, 4, 7]), "0,2-4,7");
        assert_eq!(array_spec(&[5]), "5");
        assert_eq!(array_spec(&[]), "");
    }

    #[test]
    fn quoting_survives_quotes() {
        assert_eq!(quote("a b"), "'a b'");
        assert_eq!(quote("it's"), "'it'\\''s'");
    }
}
