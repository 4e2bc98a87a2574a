//! Which `/snapshot` messages of a log become pictures or exported frames
//! (`carom render`, `carom render --movie`, `carom export`), read one at a time so
//! that memory stays one snapshot whatever the log's length.
//!
//! A frame range keeps the snapshots with `from ≤ t ≤ to`, thinned so that kept
//! frames are at least `every` apart in simulated time (the first in range is
//! always kept; a tolerance of 10⁻⁹ relative absorbs the rounding of times such as
//! 0.1 × k). [`nearest_snapshot`] picks the one snapshot closest to a time instead.

use std::path::Path;

use carom_log::{LogMessage, LogReader, ReadError, ReadProgress, Snapshot};
use thiserror::Error;

/// Why frames could not be made.
#[derive(Debug, Error)]
pub enum FrameError {
    /// The log could not be read.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// The log holds no snapshot at all.
    #[error("{file} holds no snapshots (its run was logged with log.snapshot_interval = null); render and export draw the /snapshot messages")]
    NoSnapshots {
        /// The log.
        file: String,
    },
    /// A command-line value does not fit the log (the message names the flag).
    #[error("{0}")]
    Unusable(String),
    /// Writing the output failed.
    #[error("cannot write {file}: {reason}")]
    Write {
        /// The output file.
        file: String,
        /// Why, in words (the operating system's reason for an I/O error).
        reason: String,
    },
}

/// Which snapshots to keep: a time range and a thinning interval.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FrameRange {
    /// Earliest time kept (`--from`); `None`: from the start.
    pub from: Option<f64>,
    /// Latest time kept (`--to`); `None`: to the end.
    pub to: Option<f64>,
    /// Least simulated time between kept frames (`--every`); `None`: every snapshot.
    pub every: Option<f64>,
}

impl FrameRange {
    /// Check the values, naming the flag of a wrong one.
    pub fn check(&self) -> Result<(), FrameError> {
        for (flag, v) in [("--from", self.from), ("--to", self.to)] {
            if let Some(t) = v {
                if !(t.is_finite() && t >= 0.0) {
                    return Err(FrameError::Unusable(format!(
                        "{flag} {t}: must be a finite time ≥ 0"
                    )));
                }
            }
        }
        if let (Some(a), Some(b)) = (self.from, self.to) {
            if b < a {
                return Err(FrameError::Unusable(format!(
                    "--to {b}: must not be before --from {a}"
                )));
            }
        }
        if let Some(dt) = self.every {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(FrameError::Unusable(format!(
                    "--every {dt}: must be a finite time > 0"
                )));
            }
        }
        Ok(())
    }

    /// The range as given on the command line ("--from 2 --to 5").
    fn describe(&self) -> String {
        let flags = [
            ("--from", self.from),
            ("--to", self.to),
            ("--every", self.every),
        ];
        let given: Vec<String> = flags
            .iter()
            .filter_map(|(f, v)| v.map(|t| format!("{f} {t}")))
            .collect();
        given.join(" ")
    }
}

/// What a pass over the frames found.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FrameCount {
    /// Frames handed out.
    pub frames: u64,
    /// Snapshots in the log read so far (kept or not).
    pub snapshots: u64,
    /// Discs in the last frame.
    pub discs: u64,
}

/// Time tolerance of `--every`, relative.
const EVERY_TOLERANCE: f64 = 1e-9;

/// The next snapshot of `reader`, if any; `None` at the end of the log, or when
/// the log has no `/snapshot` channel at all.
fn next_snapshot(reader: &mut LogReader) -> Result<Option<Snapshot>, ReadError> {
    match reader.snapshots().next() {
        None => Ok(None),
        Some(Ok(LogMessage::Snapshot(s))) => Ok(Some(s)),
        Some(Ok(_)) => unreachable!("the /snapshot iterator yields snapshots only"),
        Some(Err(ReadError::MissingChannel {
            topic: "/snapshot", ..
        })) => Ok(None),
        Some(Err(e)) => Err(e),
    }
}

/// Read `path`, calling `frame` with each snapshot `range` keeps, in order, and
/// `progress` as the file is read. Errors when the log has no snapshot or none in
/// the range.
pub fn for_each_frame(
    path: &Path,
    range: FrameRange,
    progress: &mut dyn FnMut(ReadProgress),
    frame: &mut dyn FnMut(&Snapshot) -> Result<(), FrameError>,
) -> Result<FrameCount, FrameError> {
    range.check()?;
    let mut reader = LogReader::open(path)?;
    let mut count = FrameCount::default();
    let mut last_kept: Option<f64> = None;
    let mut span: Option<(f64, f64)> = None;
    let mut shown = 0;
    while let Some(s) = next_snapshot(&mut reader)? {
        if let Some(p) = reader.progress_since(&mut shown) {
            progress(p);
        }
        count.snapshots += 1;
        span = Some(span.map_or((s.time, s.time), |(a, _)| (a, s.time)));
        if range.to.is_some_and(|to| s.time > to) {
            break;
        }
        if range.from.is_some_and(|from| s.time < from) {
            continue;
        }
        if let (Some(dt), Some(t0)) = (range.every, last_kept) {
            if s.time - t0 < dt * (1.0 - EVERY_TOLERANCE) {
                continue;
            }
        }
        last_kept = Some(s.time);
        count.frames += 1;
        count.discs = s.positions.len() as u64;
        frame(&s)?;
    }
    progress(reader.progress());
    match span {
        None => Err(FrameError::NoSnapshots {
            file: path.display().to_string(),
        }),
        Some((a, b)) if count.frames == 0 => Err(FrameError::Unusable(format!(
            "{}: no snapshot in that range; the log's snapshots span t = {a} … {b}{}",
            range.describe(),
            if range.to.is_some() {
                " (or later)"
            } else {
                ""
            }
        ))),
        Some(_) => Ok(count),
    }
}

/// Remove `path` after a failed write, if it is a regular file (never a device
/// such as /dev/null given as the output).
pub fn remove_output(path: &Path) {
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.is_file()) {
        let _ = std::fs::remove_file(path);
    }
}

/// A time as read from a log, for people: whole (the shortest text that reads
/// back exactly), in scientific notation outside 10⁻⁴ … 10¹⁵ in magnitude.
pub fn time_text(t: f64) -> String {
    let a = t.abs();
    if a == 0.0 || !a.is_finite() || (1e-4..1e15).contains(&a) {
        format!("{t}")
    } else {
        format!("{t:e}")
    }
}

/// The snapshot of `path` nearest to `time` (the earlier of two equally near;
/// `None`: the last). A `time` outside the span of the log's snapshots is an
/// error naming `--time`.
pub fn nearest_snapshot(
    path: &Path,
    time: Option<f64>,
    progress: &mut dyn FnMut(ReadProgress),
) -> Result<Snapshot, FrameError> {
    if let Some(t) = time {
        if !(t.is_finite() && t >= 0.0) {
            return Err(FrameError::Unusable(format!(
                "--time {t}: must be a finite time ≥ 0"
            )));
        }
    }
    let mut reader = LogReader::open(path)?;
    let mut best: Option<Snapshot> = None;
    let mut first: Option<f64> = None;
    // Whether a snapshot at or after `time` was read.
    let mut reached = false;
    let mut shown = 0;
    while let Some(s) = next_snapshot(&mut reader)? {
        if let Some(p) = reader.progress_since(&mut shown) {
            progress(p);
        }
        first.get_or_insert(s.time);
        match (time, &best) {
            (Some(t), Some(b)) if s.time >= t => {
                // Snapshots come in time order: this one or the one before.
                reached = true;
                if (s.time - t) < (t - b.time) {
                    best = Some(s);
                }
                break;
            }
            (Some(t), None) if s.time > t => {
                return Err(FrameError::Unusable(format!(
                    "--time {t}: before the log's first snapshot at t = {}",
                    s.time
                )));
            }
            _ => best = Some(s),
        }
    }
    progress(reader.progress());
    let Some(best) = best else {
        return Err(FrameError::NoSnapshots {
            file: path.display().to_string(),
        });
    };
    if let Some(t) = time {
        if !reached && t > best.time {
            return Err(FrameError::Unusable(format!(
                "--time {t}: after the log's last snapshot at t = {} (its snapshots span t = {} … {})",
                best.time,
                first.unwrap_or(best.time),
                best.time
            )));
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrong_ranges_name_their_flag() {
        let bad = [
            (
                FrameRange {
                    from: Some(-1.0),
                    ..Default::default()
                },
                "--from",
            ),
            (
                FrameRange {
                    to: Some(f64::NAN),
                    ..Default::default()
                },
                "--to",
            ),
            (
                FrameRange {
                    from: Some(5.0),
                    to: Some(2.0),
                    ..Default::default()
                },
                "--to 2",
            ),
            (
                FrameRange {
                    every: Some(0.0),
                    ..Default::default()
                },
                "--every",
            ),
        ];
        for (r, flag) in bad {
            let e = r.check().unwrap_err().to_string();
            assert!(e.starts_with(flag), "{e}");
        }
        assert!(FrameRange::default().check().is_ok());
    }
}
