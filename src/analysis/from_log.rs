//! From a log file to a [`Report`]: the time span and collision counts come from a
//! finished log's index (or, for a log cut short, a scan), the run from
//! [`describe`], and then every message is read in one streaming pass into the
//! [`Analyzer`]. Only the first snapshot of a log whose configuration cannot be
//! read is needed before the analysis can start; the messages read up to it are
//! kept and fed after it, so the pass stays one.
//!
//! Collisions give the virial and wall impulse bin by bin; a log without them, or
//! with only every k-th, gets them from the differences of consecutive `/thermo`
//! records' running totals instead.

use std::path::Path;

use carom_core::DVec2;
use carom_io::{
    scan_indexed, scan_observed, LogEnd, LogMessage, LogReader, ReadError, ReadProgress,
};
use carom_io::{Snapshot, KIND_PAIR};
use thiserror::Error;

use super::description::describe;
use super::stats::StatsError;
use super::{AnalysisOptions, Analyzer, Report};

/// Why a log could not be analysed.
#[derive(Debug, Error)]
pub enum AnalysisError {
    /// The log could not be read.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// A statistic could not be computed.
    #[error("analysis: {0}")]
    Stats(#[from] StatsError),
    /// The log holds nothing to analyse, or an option does not fit it.
    #[error("{0}")]
    Unusable(String),
}

/// Who hears how reading a log goes (a progress display).
pub trait ReadObserver {
    /// A pass over the file begins, named by what it does ("scanning", "reading").
    fn pass(&mut self, what: &'static str);
    /// How far the current pass has got.
    fn progress(&mut self, p: ReadProgress);
    /// A warning about the log, for people.
    fn warn(&mut self, line: &str);
}

/// Analyse the log `path` with `opts`, telling `observer` how reading goes.
/// Returns the report and whether the log is complete (not cut short).
pub fn analyze_log(
    path: &Path,
    opts: AnalysisOptions,
    observer: &mut dyn ReadObserver,
) -> Result<(Report, bool), AnalysisError> {
    let info = match scan_indexed(path)? {
        Some(info) => info,
        None => {
            observer.pass("scanning");
            scan_observed(path, &mut |p| observer.progress(p))?
        }
    };
    if let Some(w) = info.end.warning() {
        observer.warn(&format!("warning: {w}"));
    }
    let complete = info.end == LogEnd::Complete;
    let mut reader = LogReader::open(path)?;
    observer.pass("reading");
    let mut shown = 0;
    // Messages read before the analysis could start (only when the run is learnt
    // from the first snapshot).
    let mut early: Vec<LogMessage> = Vec::new();
    let mut first_snapshot = || -> Result<Option<Snapshot>, ReadError> {
        while let Some(m) = reader.next_message()? {
            let s = match &m {
                LogMessage::Snapshot(s) => Some(s.clone()),
                _ => None,
            };
            early.push(m);
            if s.is_some() {
                return Ok(s);
            }
        }
        Ok(None)
    };
    let mut warnings = Vec::new();
    let run = describe(
        &path.display().to_string(),
        &info,
        &mut first_snapshot,
        &mut |w: &str| warnings.push(w.to_owned()),
    )?;
    for w in &warnings {
        observer.warn(w);
    }
    let t_end = run.t_end;
    if let Some(t) = opts.equilibrate {
        if !(t.is_finite() && t >= 0.0) {
            return Err(AnalysisError::Unusable(format!(
                "--equilibrate {t}: must be a finite time ≥ 0"
            )));
        }
        if t >= t_end {
            return Err(AnalysisError::Unusable(format!(
                "--equilibrate {t}: must be before the end of the log at t = {t_end}"
            )));
        }
    }
    if let Some(dt) = opts.every {
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(AnalysisError::Unusable(format!(
                "--every {dt}: must be a finite time ≥ 0"
            )));
        }
    }
    let mut feed = Feed {
        totals_from_thermo: run.totals_from_thermo,
        analyzer: Analyzer::new(run, opts)?,
        previous_thermo: None,
        vx: Vec::new(),
        vy: Vec::new(),
    };
    for m in early {
        feed.message(m)?;
    }
    loop {
        if let Some(p) = reader.progress_since(&mut shown) {
            observer.progress(p);
        }
        // A truncated tail ends the stream (the scan already warned).
        let Some(m) = reader.next_message()? else {
            break;
        };
        feed.message(m)?;
    }
    Ok((feed.analyzer.finish()?, complete))
}

/// An [`Analyzer`] fed message by message.
struct Feed {
    analyzer: Analyzer,
    totals_from_thermo: bool,
    /// (time, virial sum, wall impulse, pair collisions) of the last `/thermo`.
    previous_thermo: Option<(f64, f64, f64, u64)>,
    vx: Vec<f64>,
    vy: Vec<f64>,
}

impl Feed {
    fn message(&mut self, m: LogMessage) -> Result<(), StatsError> {
        let a = &mut self.analyzer;
        match m {
            LogMessage::Collisions(b) => {
                for k in 0..b.time.len() {
                    if b.kind[k] == KIND_PAIR {
                        a.pair(b.time[k], b.virial[k], b.energy_lost[k]);
                    } else {
                        a.wall(b.time[k], b.virial[k], b.energy_lost[k]);
                    }
                }
            }
            LogMessage::Snapshot(s) => {
                self.vx.clear();
                self.vy.clear();
                self.vx.extend(s.velocities.iter().map(|v: &DVec2| v.x));
                self.vy.extend(s.velocities.iter().map(|v: &DVec2| v.y));
                a.snapshot(s.time, &s.species, &self.vx, &self.vy)?;
                self.vx.clear();
                self.vy.clear();
                self.vx.extend(s.positions.iter().map(|p: &DVec2| p.x));
                self.vy.extend(s.positions.iter().map(|p: &DVec2| p.y));
                a.positions(s.time, &s.species, &self.vx, &self.vy)?;
            }
            LogMessage::Thermo(t) => {
                a.thermo(t.time, t.kinetic_energy, Some(t.energy_lost));
                if self.totals_from_thermo {
                    if let Some((t0, v0, w0, p0)) = self.previous_thermo {
                        if t.pair_collisions >= p0 {
                            a.increment(
                                t0,
                                t.time,
                                t.virial_sum - v0,
                                t.wall_impulse - w0,
                                t.pair_collisions - p0,
                            );
                        }
                    }
                    self.previous_thermo =
                        Some((t.time, t.virial_sum, t.wall_impulse, t.pair_collisions));
                }
            }
            LogMessage::Checkpoint(_) => {}
        }
        Ok(())
    }
}
