//! Running one point: the `carom` command its state calls for (a fresh
//! `carom run`, or `carom resume` from the log's last checkpoint), run as a child
//! process in its own process group (a terminal's Ctrl-C reaches the sweep, which
//! passes it on once), its output kept in the point's `carom.log`, its progress
//! read from the plain progress lines `carom run` prints when not on a terminal
//! (`[   12.3 s]  45.2% t = …`), and a failure recorded in `failed.txt`.

use std::io::{BufRead, BufReader, Write};
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, Command, ExitStatus, Stdio};

use super::error::io;
use super::status::log_state;
use super::{point_state, PointState, SweepDir, SweepError};

/// How an attempt at a point ended.
#[derive(Debug, Clone, PartialEq)]
pub enum PointOutcome {
    /// It had nothing to do (finished, or being run by another process).
    Skipped(PointState),
    /// The run reached its stop.
    Done,
    /// It was interrupted (exit status 130); re-running the sweep resumes it.
    Interrupted,
    /// It failed: the exit status and the last lines it printed.
    Failed(String),
}

/// The `carom` arguments point `i` needs now, or `None` if it needs nothing.
pub fn point_command(sweep: &SweepDir, i: usize) -> Option<Vec<String>> {
    let state = point_state(sweep, i);
    let s = |p: &Path| p.display().to_string();
    let fresh = || {
        vec![
            "run".into(),
            s(&sweep.config_path(i)),
            "--out".into(),
            s(&sweep.log_path(i)),
            "--force".into(),
        ]
    };
    match state {
        PointState::Done { .. } | PointState::Running => None,
        PointState::Pending => Some(fresh()),
        PointState::Interrupted { resumable, .. } => Some(if resumable {
            vec!["resume".into(), s(&sweep.log_path(i))]
        } else {
            fresh()
        }),
        PointState::Failed { .. } => {
            // A failed run is tried again, from its checkpoint if it has one.
            let resumable = sweep.log_path(i).exists()
                && matches!(
                    log_state(&sweep.log_path(i)),
                    PointState::Interrupted {
                        resumable: true,
                        ..
                    }
                );
            Some(if resumable {
                vec!["resume".into(), s(&sweep.log_path(i))]
            } else {
                fresh()
            })
        }
    }
}

/// A point being run.
pub(super) struct Running {
    /// The child, until a waiter takes it.
    pub child: Option<Child>,
    reader: std::thread::JoinHandle<Vec<String>>,
}

/// Start point `i` with `exe` (the `carom` binary), calling `progress` with the
/// fraction done whenever the child reports it. `None` if it needs nothing.
pub(super) fn start_point(
    exe: &Path,
    sweep: &SweepDir,
    i: usize,
    progress: impl Fn(f64) + Send + 'static,
) -> Result<Result<Running, PointState>, SweepError> {
    let Some(args) = point_command(sweep, i) else {
        return Ok(Err(point_state(sweep, i)));
    };
    let _ = std::fs::remove_file(sweep.failure_path(i));
    let out_path = sweep.output_path(i);
    let mut out = std::fs::File::create(&out_path).map_err(io(&out_path))?;
    let _ = writeln!(out, "$ carom {}", args.join(" "));
    let mut child = Command::new(exe)
        .args(&args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .process_group(0)
        .spawn()
        .map_err(io(exe))?;
    let stdout = child.stdout.take().expect("piped");
    let stderr = child.stderr.take().expect("piped");
    // The run's summary goes to stdout, its progress and warnings to stderr: both
    // into carom.log, stdout by a thread of its own so neither pipe fills up.
    let mut out2 = out.try_clone().map_err(io(&out_path))?;
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            let _ = writeln!(out2, "{line}");
        }
    });
    let reader = std::thread::spawn(move || {
        let mut tail = Vec::new();
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            let _ = writeln!(out, "{line}");
            if let Some(f) = progress_fraction(&line) {
                progress(f);
            }
            tail.push(line);
            if tail.len() > 8 {
                tail.remove(0);
            }
        }
        tail
    });
    Ok(Ok(Running {
        child: Some(child),
        reader,
    }))
}

impl Running {
    /// Wait for the child and record how it ended.
    pub(super) fn finish(self, sweep: &SweepDir, i: usize, status: ExitStatus) -> PointOutcome {
        let tail = self.reader.join().unwrap_or_default();
        match status.code() {
            Some(0) => PointOutcome::Done,
            Some(130) => PointOutcome::Interrupted,
            code => {
                let how = match code {
                    Some(c) => format!("exit status {c}"),
                    None => format!("killed ({status})"),
                };
                let last: Vec<&String> = tail
                    .iter()
                    .filter(|l| progress_fraction(l).is_none())
                    .collect();
                let words = last
                    .iter()
                    .rev()
                    .take(3)
                    .rev()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join(" | ");
                let text = format!("{how}: {words}");
                let _ = std::fs::write(sweep.failure_path(i), format!("{text}\n"));
                PointOutcome::Failed(text)
            }
        }
    }
}

/// Run point `i` to its end with `exe`, in the foreground (a Slurm task).
pub fn run_point(exe: &Path, sweep: &SweepDir, i: usize) -> Result<PointOutcome, SweepError> {
    match start_point(exe, sweep, i, |_| {})? {
        Err(state) => Ok(PointOutcome::Skipped(state)),
        Ok(mut r) => {
            let mut child = r.child.take().expect("a started point has its child");
            let status = child.wait().map_err(io(exe))?;
            Ok(r.finish(sweep, i, status))
        }
    }
}

/// The fraction done in one of `carom run`'s plain progress lines
/// (`[   12.3 s]  45.2% t = …`).
fn progress_fraction(line: &str) -> Option<f64> {
    let rest = line.strip_prefix('[')?;
    let (_, after) = rest.split_once("s] ")?;
    let pct = after.trim_start().split_once('%')?.0;
    pct.trim().parse::<f64>().ok().map(|p| p / 100.0)
}

#[cfg(test)]
mod tests {
    use super::progress_fraction;

    #[test]
    fn progress_lines_give_their_fraction() {
        assert_eq!(
            progress_fraction("[   12.3 s]  45.2% t = 1.0 / t = 50, 10 collisions"),
            Some(0.452)
        );
        assert_eq!(progress_fraction("[    0.0 s] 100.0% t = 50"), Some(1.0));
        assert_eq!(progress_fraction("warning: something"), None);
        assert_eq!(progress_fraction("[    1.0 s] placed 10 discs"), None);
    }
}
