//! Running one point: the `carom` command its state calls for (a fresh
//! `carom run`, or `carom resume` from the log's last checkpoint), run as a child
//! process in its own process group (a terminal's Ctrl-C reaches the sweep, which
//! passes it on once), and a failure recorded in `failed.txt`. A log in the
//! point's directory that is not the point's own readable run (a `mismatch` or
//! `unreadable`, see [`super::status`]) is never overwritten: it is renamed to
//! `run.set-aside-K.mcap` beside it first, and the sweep says so. The child's
//! output goes straight into the point's `carom.log` (`start_point`).

use std::fs::File;
use std::io::{Read, Seek, SeekFrom, Write};
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
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
        PointState::Pending | PointState::Mismatch { .. } | PointState::Unreadable { .. } => {
            Some(fresh())
        }
        PointState::Interrupted { resumable, .. } => Some(if resumable {
            vec!["resume".into(), s(&sweep.log_path(i))]
        } else {
            fresh()
        }),
        PointState::Failed { .. } => {
            // A failed run is tried again, from its checkpoint if it has one.
            let resumable = sweep.log_path(i).exists()
                && matches!(
                    log_state(&sweep.log_path(i), &sweep.plan.run_spec(i)),
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
    /// Its `carom.log`, where the child's output starts in it, and how far the
    /// progress has been read.
    output: PathBuf,
    start: u64,
    read: u64,
    /// The start of a line not yet complete.
    partial: Vec<u8>,
    /// Where a log that was not the point's was moved, and why.
    pub set_aside: Option<String>,
}

/// Move point `i`'s log aside to the first free `run.set-aside-K.mcap`; where it went.
fn set_aside(sweep: &SweepDir, i: usize) -> Result<PathBuf, SweepError> {
    let log = sweep.log_path(i);
    let to = (1..)
        .map(|k| sweep.point_dir(i).join(format!("run.set-aside-{k}.mcap")))
        .find(|p| !p.exists())
        .expect("a free name");
    std::fs::rename(&log, &to).map_err(io(&log))?;
    Ok(to)
}

/// The child writes its output (stdout and stderr) straight into the point's
/// `carom.log`, not into pipes to the sweep: a sweep that dies (killed, or its own
/// output closed as in `carom sweep … | head`) takes nothing of its points with it —
/// they run on to their end and finish their logs; a sweep started meanwhile finds
/// them `running` and skips them. The sweep follows a point's progress by reading
/// the plain progress lines `carom run` prints when not on a terminal
/// (`[   12.3 s]  45.2% t = …`) from that file.
///
/// Start point `i` with `exe` (the `carom` binary). `Err(state)` if it needs nothing.
pub(super) fn start_point(
    exe: &Path,
    sweep: &SweepDir,
    i: usize,
) -> Result<Result<Running, PointState>, SweepError> {
    let state = point_state(sweep, i);
    let Some(args) = point_command(sweep, i) else {
        return Ok(Err(state));
    };
    sweep.prepare_point(i)?;
    let set_aside = match &state {
        PointState::Mismatch { detail } | PointState::Unreadable { detail } => {
            let to = set_aside(sweep, i)?;
            let what = match state {
                PointState::Mismatch { .. } => "is not this point's run",
                _ => "cannot be read",
            };
            Some(format!(
                "the log there {what} ({detail}); moved it aside to {}",
                to.display()
            ))
        }
        _ => None,
    };
    let _ = std::fs::remove_file(sweep.failure_path(i));
    let out_path = sweep.output_path(i);
    let mut out = File::create(&out_path).map_err(io(&out_path))?;
    if let Some(note) = &set_aside {
        let _ = writeln!(out, "carom sweep: {note}");
    }
    let _ = writeln!(out, "$ carom {}", args.join(" "));
    let read = out.stream_position().unwrap_or(0);
    // Both streams append to the one file (the summary on stdout, progress and
    // warnings on stderr), in the order written.
    let append = || {
        File::options()
            .append(true)
            .open(&out_path)
            .map_err(io(&out_path))
    };
    let child = Command::new(exe)
        .args(&args)
        .stdin(Stdio::null())
        .stdout(append()?)
        .stderr(append()?)
        .process_group(0)
        .spawn()
        .map_err(io(exe))?;
    Ok(Ok(Running {
        child: Some(child),
        output: out_path,
        start: read,
        read,
        partial: Vec::new(),
        set_aside,
    }))
}

impl Running {
    /// The fraction done in the last progress line the child wrote since the
    /// last call, if any.
    pub(super) fn progress(&mut self) -> Option<f64> {
        let mut f = File::open(&self.output).ok()?;
        f.seek(SeekFrom::Start(self.read)).ok()?;
        let mut new = Vec::new();
        // At most 1 MiB at a time: progress lines are short and few.
        f.take(1 << 20).read_to_end(&mut new).ok()?;
        self.read += new.len() as u64;
        self.partial.extend_from_slice(&new);
        let end = self.partial.iter().rposition(|&b| b == b'\n')?;
        let lines: Vec<u8> = self.partial.drain(..=end).collect();
        String::from_utf8_lossy(&lines)
            .lines()
            .filter_map(progress_fraction)
            .next_back()
    }

    /// Record how the child ended (with `status`).
    pub(super) fn finish(self, sweep: &SweepDir, i: usize, status: ExitStatus) -> PointOutcome {
        match status.code() {
            Some(0) => PointOutcome::Done,
            Some(130) => PointOutcome::Interrupted,
            code => {
                let how = match code {
                    Some(c) => format!("exit status {c}"),
                    None => format!("killed ({status})"),
                };
                let words = last_words(&self.output, self.start);
                let text = format!("{how}: {words}");
                let _ = std::fs::write(sweep.failure_path(i), format!("{text}\n"));
                PointOutcome::Failed(text)
            }
        }
    }
}

/// The last three lines of `path` after byte `from` that are not progress lines,
/// joined by ` | `.
fn last_words(path: &Path, from: u64) -> String {
    let text = std::fs::read(path).unwrap_or_default();
    let text = String::from_utf8_lossy(&text[(from as usize).min(text.len())..]).into_owned();
    let last: Vec<&str> = text
        .lines()
        .filter(|l| progress_fraction(l).is_none() && !l.trim().is_empty())
        .collect();
    last[last.len().saturating_sub(3)..].join(" | ")
}

/// Run point `i` to its end with `exe`, in the foreground (a Slurm task).
pub fn run_point(exe: &Path, sweep: &SweepDir, i: usize) -> Result<PointOutcome, SweepError> {
    match start_point(exe, sweep, i)? {
        Err(state) => Ok(PointOutcome::Skipped(state)),
        Ok(mut r) => {
            if let Some(note) = &r.set_aside {
                let name = &sweep.plan.points[i].name;
                let _ = writeln!(std::io::stderr(), "point {i} ({name}): {note}");
            }
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
