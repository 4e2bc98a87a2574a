//! The run driver: builds the engine, asks it for observations at exact times, hands
//! every event to the MCAP log writer, and ends the log cleanly.
//!
//! Two entry points, both blocking until the run ends:
//!
//! * [`run`] — a fresh run from a [`RunSpec`] into a new log file;
//! * [`resume`] — continue a log (complete, or cut short by a crash) from its last
//!   checkpoint.
//!
//! ```no_run
//! use carom::run::{run, Control, Progress};
//! use std::sync::atomic::AtomicBool;
//! # fn spec() -> carom::io::RunSpec { unimplemented!() }
//! let stop = AtomicBool::new(false); // set it from a Ctrl-C handler
//! let mut show = |p: &Progress| eprintln!("t = {:.3}, {} collisions", p.sim_time, p.collisions);
//! let summary = run(&spec(), "out.mcap".as_ref(), Control::new(&stop, &mut show)).unwrap();
//! println!("{} collisions/s", summary.collisions_per_second);
//! ```
//!
//! ## What a run writes, in order
//! 1. `carom.run` metadata (config, version, seed, start time, stop, log options);
//! 2. at the start time: a `/snapshot`, a `/thermo` record and a `/checkpoint`
//!    (each when enabled; the initial checkpoint always), then at start + k·interval
//!    for k = 1, 2, … the same (exact times, through `Engine::schedule`);
//! 3. `/collisions` batches in between (every collision, or every k-th);
//! 4. at the end: a final `/thermo` record and `/checkpoint`, and `carom.summary`.
//!
//! A stop at time `t_end` is delivered after every observation scheduled at
//! exactly `t_end`, so a snapshot due at `t_end` is in the log.
//!
//! ## How resume continues a log
//! [`resume`] reads the input's last complete checkpoint and writes a **new** file
//! that holds, first, the input's messages up to and including that checkpoint,
//! copied byte for byte, then the continuation. Because the engine restarts
//! bit-identically and the driver's counters (collision ordinal, message sequence
//! numbers) are stored in the checkpoint, the new file has exactly the messages the
//! uninterrupted run would have written: one file covers the whole run. Messages of
//! the input after its last checkpoint (up to the crash) are dropped; the
//! continuation writes them again, identically. When the output path equals the
//! input path the new file is written beside it and renamed over the input only once
//! it is finished, so a crash during the resume leaves the input intact.

use carom_core::observables::degrees_of_freedom;
use carom_core::{Boundary, DVec2};
use carom_events::{Engine, EngineError, Event, InitError, PlacementProgress, State, SystemSpec};
use carom_io::checkpoint_codec::LogCheckpoint;
use carom_io::config::MAX_RECORDS;
use carom_io::log_reader::{last_checkpoint_observed, LogReader, ReadError, ReadProgress};
use carom_io::log_writer::{LogWriter, WriteError, WriterOptions, WriterPosition, CH_THERMO};
use carom_io::run_metadata::{now_rfc3339, RunMetadata, StopReason, SummaryMetadata};
use carom_io::schema::{Thermo, LOG_FORMAT_VERSION};
use carom_io::{LogOptions, RunSpec, Stop};
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};
use thiserror::Error;

/// A run that could not be carried out. Each variant says what and where.
#[derive(Debug, Error)]
pub enum RunError {
    /// The initial state could not be built.
    #[error("initial state: {0}")]
    Init(#[from] InitError),
    /// An option is out of range.
    #[error("{field}: {problem} (allowed: {allowed})")]
    Invalid {
        /// The option, as a dotted path (e.g. `log.snapshot_interval`).
        field: &'static str,
        /// What is wrong.
        problem: String,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The engine failed mid-run; the log was finished (with `stop_reason = error`
    /// in its summary) and is readable up to the failure.
    #[error("engine failed at simulated time {time}: {source}; the log {log} is finished and readable up to there")]
    Engine {
        /// The engine's error.
        source: EngineError,
        /// Simulated time of the failure.
        time: f64,
        /// The log file.
        log: PathBuf,
    },
    /// The checkpoint to resume from was rejected by the engine.
    #[error("cannot resume from the last checkpoint of {file}: {source}")]
    BadCheckpoint {
        /// The input log.
        file: PathBuf,
        /// The engine's reason.
        source: EngineError,
    },
    /// Writing the log failed.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// Writing the log failed during the run (a full disk, a file system gone):
    /// the log is not finished, but readable up to its last flush, and `resume`
    /// continues it from its last complete checkpoint.
    #[error(
        "{source}\nthe run stopped at simulated time {}; {log} is readable up to its last \
         flush, and `carom resume {log}` continues it from its last complete checkpoint \
         once the cause is removed (a full disk: free space, or resume with --out on \
         another disk)",
        // Seven digits are plenty to say where; the log has the exact times.
        *.time as f32
    )]
    LogCut {
        /// The writer's error.
        source: WriteError,
        /// Simulated time when the run stopped (time).
        time: f64,
        /// The log file.
        log: PathBuf,
    },
    /// Reading the log to resume failed.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// The stop flag was raised while the discs were being placed, before the log
    /// was created: nothing was written.
    #[error("interrupted while placing the discs (relaxed placement, after {steps} minimization steps); no log was written")]
    InterruptedPlacing {
        /// Minimization steps taken.
        steps: usize,
    },
    /// The disk that is to hold the resumed log has too little room for even the
    /// copy of the input up to its last checkpoint (nothing was written).
    #[error(
        "cannot resume into {out}: its disk has {} free, and the copy of {input} up to its \
         last checkpoint needs about {}; free some space, or resume with --out on another \
         disk",
        indicatif::DecimalBytes(*.free),
        indicatif::DecimalBytes(*.need)
    )]
    NoRoom {
        /// The log being resumed.
        input: PathBuf,
        /// The file the resumed log was to be written to.
        out: PathBuf,
        /// Bytes the copy needs (taken as the input's size).
        need: u64,
        /// Bytes free on the output's disk.
        free: u64,
    },
    /// Renaming the finished resumed log over the input failed.
    #[error("cannot move the resumed log {from} over {to}: {source}")]
    Rename {
        /// The finished temporary file.
        from: PathBuf,
        /// The input log.
        to: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
}

/// A progress report, handed to the caller's callback about every
/// [`Control::progress_interval`] of wall time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Current simulated time (time).
    pub sim_time: f64,
    /// Collisions (pair + wall) since the start of the run, including before a resume.
    pub collisions: u64,
    /// Collisions of this process per wall-clock second so far.
    pub collisions_per_second: f64,
    /// Wall-clock seconds since this process started the run.
    pub wall_seconds: f64,
    /// Fraction of the run done (0–1), from the stop criterion.
    pub fraction: f64,
    /// The stop criterion.
    pub stop: Stop,
    /// Bytes of the log file on disk so far (what has reached the file; the
    /// writer's buffers and the chunk being filled are not counted yet).
    pub log_bytes: u64,
}

impl Progress {
    /// The size (bytes) the log would reach at the stop if it kept growing at the
    /// rate it has so far, once that rate says something: from 1 % of the run, or
    /// from 64 MB written (the first snapshot and checkpoint, written at the start,
    /// would otherwise weigh too much). A log of a cooling gas grows more slowly
    /// later, so this is an upper estimate there.
    pub fn projected_log_bytes(&self) -> Option<f64> {
        let sure = self.fraction >= 0.01 || self.log_bytes >= 64 << 20;
        (sure && self.fraction > 0.0).then(|| self.log_bytes as f64 / self.fraction)
    }
}

/// How the caller steers a run: a stop flag (for Ctrl-C) and a progress callback.
pub struct Control<'a> {
    /// When this becomes `true` the run stops at the next event and finishes its log
    /// (final checkpoint and summary, `stop_reason = interrupted`).
    pub stop: Option<&'a AtomicBool>,
    /// Called about every `progress_interval` of wall time, and once at the end.
    pub progress: Option<&'a mut dyn FnMut(&Progress)>,
    /// Called about every `progress_interval` of wall time while relaxed placement
    /// minimizes (before the run starts and its log exists), and once when it ends.
    pub placing: Option<&'a mut dyn FnMut(&PlacementProgress)>,
    /// Called while [`resume`] reads its input, before the run goes on: in each
    /// [`ResumePass`] with the input reader's progress, about once per MiB read and
    /// at the end of the pass (the whole log is read once and most of it copied,
    /// about a minute each for a log of 10⁶ discs).
    pub reading: Option<&'a mut dyn FnMut(ResumePass, ReadProgress)>,
    /// How many bytes the disk of the log file given as argument still has free for
    /// this user, asked with every progress report (also without a callback). `None`
    /// asks the file system ([`free_space_for`]); a
    /// caller with a quota of its own, or a test, answers here. When the room left
    /// falls to what finishing the log needs (see [`disk_low`]) the run stops
    /// with [`StopReason::DiskFull`] and a finished log, instead of dying later with
    /// a write error and a log cut at its last flush.
    pub free_space: Option<&'a mut FreeSpace<'a>>,
    /// Wall time between progress calls, and between looks at the room left on
    /// the log's disk.
    pub progress_interval: Duration,
}

/// Whether a log must stop now to be finished: its disk has `free` bytes, finishing
/// it would write up to `finish` bytes ([`LogWriter::finish_bound`]), and it grew by
/// `growth` bytes since the last look, a [`Control::progress_interval`] ago. Twice
/// that growth is kept in hand, as the next look comes one interval later and the
/// writer may have fallen behind by as much.
pub fn disk_low(free: u64, finish: u64, growth: u64) -> bool {
    free <= finish.saturating_add(growth.saturating_mul(2))
}

/// The bytes free for this user on the disk that holds (or will hold) the file
/// `path` (`fs4::statvfs` of its directory). A file system that reports a total
/// size of zero (some FUSE mounts do not report sizes at all) gives an error of
/// kind `Unsupported` rather than "0 bytes free", which would stop every run.
pub fn free_space_for(path: &Path) -> std::io::Result<u64> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let stats = fs4::statvfs(dir)?;
    if stats.total_space() == 0 {
        return Err(std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            "the file system reports no size",
        ));
    }
    Ok(stats.available_space())
}

/// A caller's answer to "how many bytes are free for the log at this path"
/// ([`Control::free_space`]).
pub type FreeSpace<'a> = dyn FnMut(&Path) -> std::io::Result<u64> + 'a;

/// The bytes free for the file `path` on its disk: the caller's answer `ask`
/// ([`Control::free_space`]) or, without one, the file system's
/// ([`free_space_for`]).
fn free_bytes(ask: &mut Option<&mut FreeSpace<'_>>, path: &Path) -> std::io::Result<u64> {
    match ask {
        Some(ask) => ask(path),
        None => free_space_for(path),
    }
}

/// What [`resume`] is doing with its input before the run goes on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ResumePass {
    /// Reading the whole log to find its last complete checkpoint.
    FindingCheckpoint,
    /// Copying the messages up to that checkpoint into the output.
    Copying,
}

impl ResumePass {
    /// One word for people, to stand before the file's name ("searching
    /// run.mcap", "copying run.mcap").
    pub fn as_str(self) -> &'static str {
        match self {
            ResumePass::FindingCheckpoint => "searching",
            ResumePass::Copying => "copying",
        }
    }
}

impl Default for Control<'_> {
    fn default() -> Self {
        Control {
            stop: None,
            progress: None,
            placing: None,
            reading: None,
            free_space: None,
            progress_interval: Duration::from_millis(200),
        }
    }
}

impl<'a> Control<'a> {
    /// A stop flag and a progress callback, with reports every 200 ms.
    pub fn new(stop: &'a AtomicBool, progress: &'a mut dyn FnMut(&Progress)) -> Self {
        Control {
            stop: Some(stop),
            progress: Some(progress),
            placing: None,
            reading: None,
            free_space: None,
            progress_interval: Duration::from_millis(200),
        }
    }
}

impl std::fmt::Debug for Control<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Control")
            .field("stop", &self.stop)
            .field("progress", &self.progress.is_some())
            .field("placing", &self.placing.is_some())
            .field("free_space", &self.free_space.is_some())
            .field("reading", &self.reading.is_some())
            .field("progress_interval", &self.progress_interval)
            .finish()
    }
}

/// What a finished run did.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSummary {
    /// The log file.
    pub log: PathBuf,
    /// Why it ended.
    pub stop_reason: StopReason,
    /// Simulated time at the end (time).
    pub sim_time: f64,
    /// Pair collisions over the whole run.
    pub pair_collisions: u64,
    /// Wall collisions over the whole run.
    pub wall_collisions: u64,
    /// Collisions written to `/collisions` over the whole run.
    pub logged_collisions: u64,
    /// Collisions processed by this process (excludes the part before a resume).
    pub collisions_this_process: u64,
    /// Wall-clock seconds of this process's part.
    pub wall_seconds: f64,
    /// `collisions_this_process / wall_seconds`.
    pub collisions_per_second: f64,
    /// Kinetic energy at the end (energy).
    pub kinetic_energy: f64,
    /// Energy dissipated over the whole run (energy).
    pub energy_lost: f64,
    /// Size of the log file (bytes).
    pub file_bytes: u64,
}

/// Options of [`resume`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ResumeOptions {
    /// A new stop criterion (e.g. to extend a finished run); `None` keeps the input's.
    pub stop: Option<Stop>,
}

// Tags of scheduled observations: kind in the top byte, index k below.
const TAG_SHIFT: u32 = 56;
const TAG_SNAPSHOT: u64 = 1;
const TAG_THERMO: u64 = 2;
const TAG_CHECKPOINT: u64 = 3;
const TAG_STOP: u64 = 4;
/// Index of the second (final) phase of a stop.
const STOP_FINAL: u64 = 1;

fn tag(kind: u64, k: u64) -> u64 {
    kind << TAG_SHIFT | (k & ((1 << TAG_SHIFT) - 1))
}

fn check_interval(field: &'static str, v: Option<f64>) -> Result<(), RunError> {
    match v {
        Some(x) if !(x.is_finite() && x > 0.0) => Err(RunError::Invalid {
            field,
            problem: format!("interval {x} is not a positive finite number"),
            allowed: "finite numbers > 0, or null for none",
        }),
        _ => Ok(()),
    }
}

fn validate(log: &LogOptions, stop: &Stop, now: f64) -> Result<(), RunError> {
    for (field, v) in log.intervals() {
        check_interval(field, v)?;
    }
    if log.collision_every == 0 {
        return Err(RunError::Invalid {
            field: "log.collision_every",
            problem: "0 collisions between logged ones".into(),
            allowed: "integers ≥ 1",
        });
    }
    if log.flush_seconds.is_nan() || log.flush_seconds < 0.0 {
        return Err(RunError::Invalid {
            field: "log.flush_seconds",
            problem: format!("{} is not ≥ 0", log.flush_seconds),
            allowed: "numbers ≥ 0",
        });
    }
    if let Stop::Time(t) = *stop {
        if !t.is_finite() || t < now {
            return Err(RunError::Invalid {
                field: "stop.time",
                problem: format!("stop time {t} is not a finite time ≥ the current time {now}"),
                allowed: "finite times ≥ the start time",
            });
        }
        // A stop time mistyped by some orders of magnitude (`resume --until 1e12`)
        // would otherwise fill the disk with records, as a mistyped interval would
        // (the configuration checks those against stop.duration).
        let smallest = log
            .intervals()
            .into_iter()
            .filter_map(|(name, x)| Some((name, x?)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((name, x)) = smallest {
            let records = (t - now) / x;
            if records > MAX_RECORDS {
                return Err(RunError::Invalid {
                    field: "stop.time",
                    problem: format!(
                        "stop time {t} would write {records:.1e} records {x} apart \
                         ({name}) after the current time {now}, more than {MAX_RECORDS:.0e}; \
                         the latest stop time is {}",
                        now + MAX_RECORDS * x
                    ),
                    allowed: "stop times at most 10⁹ log intervals after the current time",
                });
            }
        }
    }
    Ok(())
}

/// Start a fresh run of `spec`, logging to `out` (created or truncated). Blocks
/// until the run stops (stop criterion, `control.stop`, or an engine failure, after
/// which the log is still finished). See the module documentation for what is
/// written.
pub fn run(spec: &RunSpec, out: &Path, mut control: Control<'_>) -> Result<RunSummary, RunError> {
    // Before placement, which can take a minute: a fresh state starts at time 0.
    validate(&spec.log, &spec.stop, 0.0)?;
    let state = place(&spec.system, &mut control)?;
    debug_assert_eq!(state.time, 0.0);
    let n = state.len();
    let engine = Engine::new(state, spec.params).map_err(|source| RunError::Engine {
        source,
        time: 0.0,
        log: out.to_path_buf(),
    })?;
    let meta = RunMetadata {
        log_format: LOG_FORMAT_VERSION.into(),
        carom_version: env!("CARGO_PKG_VERSION").into(),
        config: spec.config_json.clone(),
        seed: spec.system.seed,
        start_time: now_rfc3339(),
        n_discs: n as u64,
        stop: spec.stop,
        log: spec.log.clone(),
        resumed_from: None,
        resumed_at: None,
    };
    let writer = LogWriter::create(
        out,
        WriterOptions::from_log_options(&spec.log),
        &meta.to_map(),
        WriterPosition::default(),
    )?;
    let mut d = Driver::new(engine, writer, spec.log.clone(), spec.stop, control);
    d.run_start_time = d.engine.now();
    d.schedule_initial()?;
    d.run_loop(out)
}

/// Build the initial state of `system`, reporting relaxed placement's progress to
/// `control.placing` (every `control.progress_interval`, and once at the end) and
/// stopping it when `control.stop` is raised.
fn place(system: &SystemSpec, control: &mut Control<'_>) -> Result<State, RunError> {
    let mut last_report: Option<Instant> = None;
    let mut latest = None;
    let mut observe = |p: &PlacementProgress| {
        latest = Some(*p);
        if let Some(show) = control.placing.as_mut() {
            if last_report.is_none_or(|t| t.elapsed() >= control.progress_interval) {
                show(p);
                last_report = Some(Instant::now());
            }
        }
        match control.stop {
            Some(flag) if flag.load(Ordering::Relaxed) => ControlFlow::Break(()),
            _ => ControlFlow::Continue(()),
        }
    };
    let state = system.build_observed(&mut observe);
    if let (Some(show), Some(p)) = (control.placing.as_mut(), latest) {
        // Reported before each step: a placement that succeeded took one more, and
        // left nothing too close.
        let done = PlacementProgress {
            steps: p.steps + 1,
            close: 0,
            ..p
        };
        show(if matches!(state, Ok(Some(_))) {
            &done
        } else {
            &p
        });
    }
    match state? {
        Some(state) => Ok(state),
        None => Err(RunError::InterruptedPlacing {
            steps: latest.map_or(0, |p| p.steps),
        }),
    }
}

/// Continue the log `input` from its last complete checkpoint into `out` (which may
/// equal `input`); see the module documentation for the layout of the result.
/// `input` may be truncated (a killed run) or complete (then give a later
/// `opts.stop` to extend it).
pub fn resume(
    input: &Path,
    out: &Path,
    opts: &ResumeOptions,
    mut control: Control<'_>,
) -> Result<RunSummary, RunError> {
    let mut reading = |pass: ResumePass, p: ReadProgress| {
        if let Some(show) = control.reading.as_mut() {
            show(pass, p);
        }
    };
    let (cp, prefix, mut meta) =
        last_checkpoint_observed(input, &mut |p| reading(ResumePass::FindingCheckpoint, p))?;
    let LogCheckpoint { driver, engine } = cp;
    let stop = opts.stop.unwrap_or(meta.stop);
    validate(&meta.log, &stop, engine.now)?;
    let pending_stops: Vec<f64> = engine
        .scheduled
        .iter()
        .filter(|s| s.2 >> TAG_SHIFT == TAG_STOP)
        .map(|s| s.0)
        .collect();
    if let Some(problem) = non_finite(&engine) {
        return Err(RunError::BadCheckpoint {
            file: input.to_path_buf(),
            source: EngineError::BadCheckpoint(problem),
        });
    }
    let next_ordinal = engine.stats.pair_collisions + engine.stats.wall_collisions;
    let resumed_at = engine.now;
    let engine = Engine::from_checkpoint(engine).map_err(|source| RunError::BadCheckpoint {
        file: input.to_path_buf(),
        source,
    })?;
    meta.resumed_from = Some(input.display().to_string());
    meta.resumed_at = Some(resumed_at);
    meta.stop = stop;
    let in_place = same_file(input, out);
    let target = if in_place {
        let mut name = out.file_name().unwrap_or_default().to_os_string();
        name.push(".resume-tmp");
        out.with_file_name(name)
    } else {
        out.to_path_buf()
    };
    // The copy alone takes about as much room as the input up to its last
    // checkpoint, most of the file: refuse at once when the input's size is not
    // free, rather than fail part way (a log stopped because its disk was full,
    // resumed in place, would).
    let need = std::fs::metadata(input).map_or(0, |m| m.len());
    if let Some(free) = free_bytes(&mut control.free_space, &target)
        .ok()
        .filter(|&free| free < need)
    {
        return Err(RunError::NoRoom {
            input: input.to_path_buf(),
            out: out.to_path_buf(),
            need,
            free,
        });
    }
    let mut writer = LogWriter::create(
        &target,
        WriterOptions::from_log_options(&meta.log),
        &meta.to_map(),
        WriterPosition {
            next_ordinal,
            logged_collisions: driver.logged_collisions,
            next_sequence: driver.next_sequence,
        },
    )?;
    // Copy the input's messages up to and including the checkpoint.
    let mut reader = LogReader::open(input)?;
    let mut copied = 0u64;
    let mut last_thermo_at = None;
    let mut seen = 0;
    while copied < prefix {
        if let Some(p) = reader.progress_since(&mut seen) {
            reading(ResumePass::Copying, p);
        }
        let Some(m) = reader.next_raw()? else {
            break;
        };
        if m.channel == CH_THERMO {
            if let Ok(t) = Thermo::decode(m.data) {
                last_thermo_at = Some((t.time, t.collisions));
            }
        }
        writer.copy_message(m.channel, m.sequence, m.log_time, m.publish_time, m.data)?;
        copied += 1;
        writer.maybe_flush()?;
    }
    reading(ResumePass::Copying, reader.progress());
    drop(reader);
    writer.flush()?;
    let mut d = Driver::new(engine, writer, meta.log.clone(), stop, control);
    d.run_start_time = driver.run_start_time;
    d.last_checkpoint_at = Some((resumed_at, d.collisions));
    d.last_thermo_at = last_thermo_at;
    if let Stop::Time(t) = stop {
        if !pending_stops.contains(&t) {
            d.engine
                .schedule(t, tag(TAG_STOP, 0))
                .map_err(|source| RunError::Engine {
                    source,
                    time: resumed_at,
                    log: target.clone(),
                })?;
        }
    }
    let summary = d.run_loop(&target)?;
    if in_place {
        std::fs::rename(&target, out).map_err(|source| RunError::Rename {
            from: target.clone(),
            to: out.to_path_buf(),
            source,
        })?;
        return Ok(RunSummary {
            log: out.to_path_buf(),
            ..summary
        });
    }
    Ok(summary)
}

/// The first non-finite value among the checkpoint's times, positions and
/// velocities (which the engine assumes finite), if any.
fn non_finite(cp: &carom_events::Checkpoint) -> Option<String> {
    if !cp.now.is_finite() {
        return Some(format!("current time {} is not finite", cp.now));
    }
    if !cp.sim_box.size.is_finite() {
        return Some("box size is not finite".into());
    }
    let bad = |name: &str, k: usize| Some(format!("{name} of disc slot {k} is not finite"));
    for (k, p) in cp.positions.iter().enumerate() {
        if !p.is_finite() {
            return bad("position", k);
        }
    }
    for (k, v) in cp.velocities.iter().enumerate() {
        if !v.is_finite() {
            return bad("velocity", k);
        }
    }
    for (k, t) in cp.times.iter().enumerate() {
        if !t.is_finite() {
            return bad("update time", k);
        }
    }
    None
}

fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

struct Driver<'a> {
    engine: Engine,
    writer: LogWriter,
    log: LogOptions,
    stop: Stop,
    control: Control<'a>,
    run_start_time: f64,
    /// (time, collisions) of the last checkpoint written.
    last_checkpoint_at: Option<(f64, u64)>,
    /// (time, collisions) of the last thermo record written.
    last_thermo_at: Option<(f64, u64)>,
    collisions: u64,
    start_collisions: u64,
    started: Instant,
    last_progress: Instant,
    /// The state written by the last snapshot, kept to reuse its arrays.
    snapshot: Option<State>,
    /// The log's size (bytes) when the room on its disk was last looked at.
    bytes_at_disk_check: u64,
}

impl<'a> Driver<'a> {
    fn new(
        engine: Engine,
        writer: LogWriter,
        log: LogOptions,
        stop: Stop,
        control: Control<'a>,
    ) -> Self {
        let s = engine.stats();
        let collisions = s.pair_collisions + s.wall_collisions;
        Driver {
            engine,
            writer,
            log,
            stop,
            control,
            run_start_time: 0.0,
            last_checkpoint_at: None,
            last_thermo_at: None,
            collisions,
            start_collisions: collisions,
            started: Instant::now(),
            last_progress: Instant::now(),
            snapshot: None,
            bytes_at_disk_check: 0,
        }
    }

    fn engine_err(&self, source: EngineError) -> RunError {
        RunError::Engine {
            source,
            time: self.engine.now(),
            log: self.writer.path().to_path_buf(),
        }
    }

    /// Schedule the observations at the start time and the stop.
    fn schedule_initial(&mut self) -> Result<(), RunError> {
        let t0 = self.run_start_time;
        let mut tags = Vec::new();
        if self.log.snapshot_interval.is_some() {
            tags.push(tag(TAG_SNAPSHOT, 0));
        }
        if self.log.thermo_interval.is_some() {
            tags.push(tag(TAG_THERMO, 0));
        }
        tags.push(tag(TAG_CHECKPOINT, 0));
        for tg in tags {
            self.engine
                .schedule(t0, tg)
                .map_err(|e| self.engine_err(e))?;
        }
        if let Stop::Time(t) = self.stop {
            self.engine
                .schedule(t, tag(TAG_STOP, 0))
                .map_err(|e| self.engine_err(e))?;
        }
        Ok(())
    }

    fn schedule_next(&mut self, kind: u64, k: u64, interval: Option<f64>) -> Result<(), RunError> {
        if let Some(dt) = interval {
            let t = self.run_start_time + (k + 1) as f64 * dt;
            if t >= self.engine.now() {
                self.engine
                    .schedule(t, tag(kind, k + 1))
                    .map_err(|e| self.engine_err(e))?;
            }
        }
        Ok(())
    }

    fn thermo(&self) -> Thermo {
        let e = &self.engine;
        let n = e.len();
        let sim_box = e.sim_box();
        let k_energy = e.kinetic_energy();
        let f = degrees_of_freedom(n, sim_box).max(1) as f64;
        let kt = 2.0 * k_energy / f;
        let s = e.stats();
        let t_el = e.now() - self.run_start_time;
        let wall_impulse: f64 = s.wall_impulse.iter().flatten().sum();
        let nf = n.max(1) as f64;
        let (mut pressure, mut z, mut rate) = (None, None, None);
        if t_el > 0.0 {
            rate = Some(2.0 * s.pair_collisions as f64 / (nf * t_el));
            if kt > 0.0 {
                let walled = [0, 1].map(|k| matches!(sim_box.boundary[k], Boundary::Walls { .. }));
                if !walled[0] && !walled[1] {
                    let w = s.virial_sum / (2.0 * t_el);
                    pressure = Some((nf * kt + w) / sim_box.area());
                    z = Some(1.0 + w / (nf * kt));
                } else {
                    let a = e.species().iter().map(|sp| sp.radius).fold(0.0, f64::max);
                    let size: DVec2 = sim_box.size;
                    let acc = [0, 1].map(|k| {
                        if walled[k] {
                            size[k] - 2.0 * a
                        } else {
                            size[k]
                        }
                    });
                    let mut p_sum = 0.0;
                    let mut axes = 0.0;
                    for k in 0..2 {
                        if walled[k] {
                            let imp = s.wall_impulse[k][0] + s.wall_impulse[k][1];
                            p_sum += imp / (2.0 * t_el * acc[1 - k]);
                            axes += 1.0;
                        }
                    }
                    let p = p_sum / axes;
                    pressure = Some(p);
                    z = Some(p * acc[0] * acc[1] / (nf * kt));
                }
            }
        }
        Thermo {
            time: e.now(),
            kinetic_energy: k_energy,
            temperature: kt,
            collisions: s.pair_collisions + s.wall_collisions,
            pair_collisions: s.pair_collisions,
            wall_collisions: s.wall_collisions,
            energy_lost: s.energy_lost,
            virial_sum: s.virial_sum,
            wall_impulse,
            pressure: pressure.filter(|x| x.is_finite()),
            z: z.filter(|x| x.is_finite()),
            collision_rate: rate.filter(|x| x.is_finite()),
        }
    }

    fn write_snapshot(&mut self) -> Result<(), RunError> {
        let state = match &mut self.snapshot {
            Some(s) => {
                self.engine.state_into(s);
                s
            }
            none => none.insert(self.engine.state()),
        };
        self.writer.write_snapshot(state)?;
        Ok(())
    }

    fn write_thermo(&mut self) -> Result<(), RunError> {
        let th = self.thermo();
        self.writer.write_thermo(&th)?;
        self.last_thermo_at = Some((self.engine.now(), self.collisions));
        Ok(())
    }

    fn write_checkpoint(&mut self) -> Result<(), RunError> {
        let cp = self.engine.checkpoint();
        self.writer.write_checkpoint(cp, self.run_start_time)?;
        self.last_checkpoint_at = Some((self.engine.now(), self.collisions));
        Ok(())
    }

    fn progress(&mut self) {
        let wall = self.started.elapsed().as_secs_f64();
        let done = self.collisions - self.start_collisions;
        let fraction = match self.stop {
            Stop::Time(t) => {
                let span = t - self.run_start_time;
                if span > 0.0 {
                    ((self.engine.now() - self.run_start_time) / span).clamp(0.0, 1.0)
                } else {
                    1.0
                }
            }
            Stop::Collisions(c) => {
                if c > 0 {
                    (self.collisions as f64 / c as f64).min(1.0)
                } else {
                    1.0
                }
            }
        };
        let p = Progress {
            sim_time: self.engine.now(),
            collisions: self.collisions,
            collisions_per_second: if wall > 0.0 { done as f64 / wall } else { 0.0 },
            wall_seconds: wall,
            fraction,
            stop: self.stop,
            log_bytes: self.log_bytes(),
        };
        if let Some(cb) = self.control.progress.as_mut() {
            cb(&p);
        }
        self.last_progress = Instant::now();
    }

    /// The log file's size on disk (bytes; 0 if it cannot be read).
    fn log_bytes(&self) -> u64 {
        std::fs::metadata(self.writer.path()).map_or(0, |m| m.len())
    }

    /// Look at the room left on the log's disk: whether the run must stop now to
    /// finish its log ([`disk_low`]). A disk whose room cannot be told is never low.
    fn disk_low(&mut self) -> bool {
        let bytes = self.log_bytes();
        let growth = bytes.saturating_sub(self.bytes_at_disk_check);
        self.bytes_at_disk_check = bytes;
        let free = free_bytes(&mut self.control.free_space, self.writer.path());
        free.is_ok_and(|free| disk_low(free, self.writer.finish_bound(bytes), growth))
    }

    /// The event loop; ends the log whatever happens, except when writing it fails:
    /// that is reported as [`RunError::LogCut`].
    fn run_loop(mut self, log_path: &Path) -> Result<RunSummary, RunError> {
        self.run_events(log_path).map_err(|e| match e {
            RunError::Write(source) => RunError::LogCut {
                source,
                time: self.engine.now(),
                log: log_path.to_path_buf(),
            },
            e => e,
        })
    }

    /// The body of [`Driver::run_loop`].
    fn run_events(&mut self, log_path: &Path) -> Result<RunSummary, RunError> {
        let stop_flag = self.control.stop;
        let max_collisions = match self.stop {
            Stop::Collisions(c) => c,
            Stop::Time(_) => u64::MAX,
        };
        let stop_time = match self.stop {
            Stop::Time(t) => t,
            Stop::Collisions(_) => f64::INFINITY,
        };
        let mut reason = if self.collisions >= max_collisions {
            Some(StopReason::Collisions)
        } else {
            None
        };
        let mut failure = None;
        let mut tick: u32 = 0;
        self.bytes_at_disk_check = self.log_bytes();
        while reason.is_none() {
            if stop_flag.is_some_and(|f| f.load(Ordering::Relaxed)) {
                reason = Some(StopReason::Interrupted);
                break;
            }
            let ev = match self.engine.next_event() {
                Ok(Some(ev)) => ev,
                Ok(None) => {
                    reason = Some(StopReason::Exhausted);
                    break;
                }
                Err(e) => {
                    failure = Some(e);
                    reason = Some(StopReason::Error);
                    break;
                }
            };
            match ev {
                Event::Pair(c) => {
                    self.collisions += 1;
                    self.writer.observe_pair(&c)?;
                }
                Event::Wall(c) => {
                    self.collisions += 1;
                    self.writer.observe_wall(&c)?;
                }
                Event::Scheduled { time, tag: tg } => {
                    let k = tg & ((1 << TAG_SHIFT) - 1);
                    match tg >> TAG_SHIFT {
                        TAG_SNAPSHOT => {
                            let interval = self.log.snapshot_interval;
                            self.schedule_next(TAG_SNAPSHOT, k, interval)?;
                            self.write_snapshot()?;
                        }
                        TAG_THERMO => {
                            let interval = self.log.thermo_interval;
                            self.schedule_next(TAG_THERMO, k, interval)?;
                            self.write_thermo()?;
                        }
                        TAG_CHECKPOINT => {
                            let interval = self.log.checkpoint_interval;
                            self.schedule_next(TAG_CHECKPOINT, k, interval)?;
                            self.write_checkpoint()?;
                        }
                        TAG_STOP if time >= stop_time => {
                            if k == STOP_FINAL {
                                reason = Some(StopReason::Time);
                            } else {
                                // Let every observation due at this very time come first.
                                self.engine
                                    .schedule(time, tag(TAG_STOP, STOP_FINAL))
                                    .map_err(|e| self.engine_err(e))?;
                            }
                        }
                        _ => {}
                    }
                }
            }
            if self.collisions >= max_collisions {
                reason = Some(StopReason::Collisions);
            }
            tick = tick.wrapping_add(1);
            if tick.is_multiple_of(1024) {
                self.writer.maybe_flush()?;
                if self.last_progress.elapsed() >= self.control.progress_interval {
                    self.progress();
                    if reason.is_none() && self.disk_low() {
                        reason = Some(StopReason::DiskFull);
                    }
                }
            }
        }
        let reason = reason.unwrap_or(StopReason::Error);
        // Finish the log.
        if failure.is_none() {
            let now = self.engine.now();
            if self.log.thermo_interval.is_some()
                && self.last_thermo_at != Some((now, self.collisions))
            {
                self.write_thermo()?;
            }
            if self.last_checkpoint_at != Some((now, self.collisions)) {
                self.write_checkpoint()?;
            }
        }
        self.progress();
        let wall = self.started.elapsed().as_secs_f64();
        let s = *self.engine.stats();
        let this = self.collisions - self.start_collisions;
        let cps = if wall > 0.0 { this as f64 / wall } else { 0.0 };
        let kinetic_energy = self.engine.kinetic_energy();
        let logged = self.writer.stats().logged_collisions;
        let sm = SummaryMetadata {
            end_time: now_rfc3339(),
            stop_reason: reason,
            error: failure.as_ref().map(|e| e.to_string()),
            sim_time: self.engine.now(),
            pair_collisions: s.pair_collisions,
            wall_collisions: s.wall_collisions,
            logged_collisions: logged,
            kinetic_energy,
            energy_lost: s.energy_lost,
            virial_sum: s.virial_sum,
            wall_seconds: wall,
            collisions_per_second: cps,
        };
        let file_bytes = self.writer.finish(&sm.to_map())?;
        if let Some(source) = failure {
            return Err(RunError::Engine {
                source,
                time: self.engine.now(),
                log: log_path.to_path_buf(),
            });
        }
        Ok(RunSummary {
            log: log_path.to_path_buf(),
            stop_reason: reason,
            sim_time: self.engine.now(),
            pair_collisions: s.pair_collisions,
            wall_collisions: s.wall_collisions,
            logged_collisions: logged,
            collisions_this_process: this,
            wall_seconds: wall,
            collisions_per_second: cps,
            kinetic_energy,
            energy_lost: s.energy_lost,
            file_bytes,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::{disk_low, free_space_for};
    use std::path::Path;

    #[test]
    fn a_file_system_that_reports_no_size_is_not_taken_for_a_full_disk() {
        let here = free_space_for(Path::new("target/some.mcap")).expect("a real disk");
        assert!(here > 0);
        // procfs reports a total size of 0 blocks, as some FUSE mounts do.
        #[cfg(target_os = "linux")]
        {
            let e = free_space_for(Path::new("/proc/some.mcap")).unwrap_err();
            assert_eq!(e.kind(), std::io::ErrorKind::Unsupported);
        }
    }

    #[test]
    fn a_disk_is_low_when_its_room_no_longer_covers_finishing_and_two_more_intervals() {
        // 100 MB to finish, growing 10 MB per interval: stop at 120 MB free.
        let mb = 1_000_000;
        assert!(!disk_low(121 * mb, 100 * mb, 10 * mb));
        assert!(disk_low(120 * mb, 100 * mb, 10 * mb));
        assert!(disk_low(0, 0, 0));
        // No growth: only the finish is kept.
        assert!(!disk_low(100 * mb + 1, 100 * mb, 0));
        // Huge numbers saturate instead of wrapping round to "plenty of room".
        assert!(disk_low(u64::MAX - 1, u64::MAX / 2, u64::MAX / 2));
    }
}
