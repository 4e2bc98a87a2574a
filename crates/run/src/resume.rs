//! Continuing a log from its last complete checkpoint.
//!
//! [`resume`] writes a **new** file that holds first the input's messages up to
//! and including that checkpoint, copied byte for byte, then the continuation.
//! The engine restarts bit-identically and the driver's counters (collision
//! ordinal, message sequence numbers) are in the checkpoint, so the new file has
//! exactly the messages the uninterrupted run would have written. Messages after
//! the last checkpoint (up to a crash) are dropped and written again, identically.
//! Resuming in place writes beside the input and renames over it once finished,
//! so a crash during the resume leaves the input intact; resuming over another,
//! older log replaces it once the copied prefix is on the disk (`replace.rs`).

use std::path::Path;

use carom_engine::{Engine, EngineError};
use carom_log::LogCheckpoint;
use carom_log::Stop;
use carom_log::Thermo;
use carom_log::{check_log_options, last_checkpoint_observed, LogReader, ReadProgress};
use carom_log::{LogWriter, WriterOptions, WriterPosition, CH_THERMO};

use super::bounds::check_scheduled;
use super::disk::{finish_reserve, free_bytes};
use super::driver::Driver;
use super::lock::lock_log;
use super::observation::Observation;
use super::replace::Output;
use super::watchdog::check_reachable;
use super::{Control, ResumeOptions, ResumePass, RunError, RunSummary};

/// Continue the log `input` from its last complete checkpoint into `out` (which may
/// equal `input`); see this module's documentation for the layout of the result.
/// `input` may be truncated (a killed run) or complete (then give a later
/// `opts.stop` to extend it).
pub fn resume(
    input: &Path,
    out: &Path,
    opts: &ResumeOptions,
    mut control: Control<'_>,
) -> Result<RunSummary, RunError> {
    // The input must not be written meanwhile, nor its result renamed over one
    // that is.
    // One that cannot be opened is reported by the reader, with its reason.
    let _input_lock = match lock_log(input, false) {
        Err(RunError::Lock { .. }) => None,
        lock => Some(lock?),
    };
    let mut reading = |pass: ResumePass, p: ReadProgress| {
        if let Some(show) = control.reading.as_mut() {
            show(pass, p);
        }
    };
    let (cp, prefix, mut meta) =
        last_checkpoint_observed(input, &mut |p| reading(ResumePass::FindingCheckpoint, p))?;
    let LogCheckpoint { driver, engine } = cp;
    let stop = opts.stop.unwrap_or(meta.stop);
    check_log_options(&meta.log, &stop, engine.now, "stop.time")?;
    let done = engine.stats.pair_collisions + engine.stats.wall_collisions;
    if let Stop::Collisions(n) = stop {
        if n < done {
            return Err(RunError::Invalid {
                field: "stop.collisions",
                problem: format!(
                    "stop at {n} collisions is below the {done} collisions of the last \
                     checkpoint"
                ),
                allowed: format!("a count ≥ {done}"),
            });
        }
    }
    let watchdog_pending = engine
        .scheduled
        .iter()
        .any(|s| Observation::decode(s.2) == Some(Observation::Watchdog));
    let pending_stops: Vec<f64> = engine
        .scheduled
        .iter()
        .filter(|s| Observation::decode(s.2).is_some_and(Observation::is_stop))
        .map(|s| s.0)
        .collect();
    if let Some(problem) = non_finite(&engine) {
        return Err(RunError::BadCheckpoint {
            file: input.to_path_buf(),
            source: EngineError::BadCheckpoint(problem),
        });
    }
    let next_ordinal = done;
    let resumed_at = engine.now;
    let collision_normals = WriterOptions::needs_normals(engine.params.restitution);
    let engine = Engine::from_checkpoint(engine).map_err(|source| RunError::BadCheckpoint {
        file: input.to_path_buf(),
        source,
    })?;
    // The same refusals as a fresh run's, before anything is written.
    let stop_field = match opts.stop {
        Some(Stop::Time(_)) => "--until",
        Some(Stop::Collisions(_)) => "--collisions",
        None => "the log's stop",
    };
    check_reachable(&engine, stop, &meta.log)?;
    check_scheduled(&engine, stop, stop_field)?;
    meta.resumed_from = Some(input.display().to_string());
    meta.resumed_at = Some(resumed_at);
    meta.stop = stop;
    let in_place = same_file(input, out);
    // In place: NAME.resume-tmp, renamed over the input once finished. Over
    // another, older log: NAME.run-tmp, renamed over it once the copy, which ends
    // in a checkpoint, is on the disk (replace.rs); a fresh file: in place.
    let output = if in_place {
        None
    } else {
        Some(Output::lock(out)?)
    };
    let target = match &output {
        Some(o) => o.writing().to_path_buf(),
        None => {
            let mut name = out.file_name().unwrap_or_default().to_os_string();
            name.push(".resume-tmp");
            out.with_file_name(name)
        }
    };
    // A failed resume in place leaves no temporary file to fill the disk: the
    // input is intact and is what to resume again.
    let mut temp = TempFile(in_place.then(|| target.clone()));
    let writer = LogWriter::create(
        &target,
        WriterOptions {
            collision_normals,
            ..WriterOptions::from_log_options(&meta.log)
        },
        &meta.to_map(),
        WriterPosition {
            next_ordinal,
            logged_collisions: driver.logged_collisions,
            next_sequence: driver.next_sequence,
        },
    );
    let mut writer = match writer {
        Ok(w) => w,
        Err(e) => {
            return Err(match output {
                Some(o) => o.abandon(e.into()),
                None => e.into(),
            })
        }
    };
    // The copy takes about as much room as the input up to its last checkpoint,
    // most of the file, and finishing the log after it its reserve: refuse at once
    // when that is not free, rather than fail part way (a log stopped because its
    // disk was full, resumed in place, would).
    let size = std::fs::metadata(input).map_or(0, |m| m.len());
    let reserve = finish_reserve(writer.finish_bound(size), 0, engine.len() as u64);
    let need = size.saturating_add(reserve);
    if let Some(free) = free_bytes(&mut control.free_space, &target)
        .ok()
        .filter(|&free| free < need)
    {
        // Nothing is left behind: the temporary file of a resume in place goes
        // with `temp`, the new file or temporary file with `output`.
        drop(writer);
        let e = RunError::NoRoom {
            input: input.to_path_buf(),
            out: out.to_path_buf(),
            need,
            free,
        };
        return Err(match output {
            Some(o) => o.abandon(e),
            None => e,
        });
    }
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
    if let Some(r) = output.as_ref().and_then(|o| o.replace_at_start()) {
        d.replace(r)?;
    }
    d.run_start_time = driver.run_start_time;
    d.last_checkpoint_at = Some((resumed_at, d.collisions));
    d.last_thermo_at = last_thermo_at;
    d.earlier_speed = carom_log::scan_indexed(input)
        .ok()
        .flatten()
        .and_then(|i| i.summary)
        .map(|s| s.collisions_per_second);
    if let Stop::Time(t) = stop {
        if !pending_stops.contains(&t) {
            d.schedule(t, Observation::Stop)?;
        }
    }
    d.max_quiet = meta.max_time_without_collision;
    if !watchdog_pending {
        // A checkpoint of a time-stopped run, or of a carom without the watchdog.
        d.schedule_watchdog()?;
    }
    // A resume in place that cannot write its log loses its continuation (the
    // temporary file goes with `temp`); the input is as it was.
    let log_path = if in_place { &target } else { out };
    let summary = d.run_loop(log_path).map_err(|e| match e {
        RunError::LogCut { source, time, .. } if in_place => RunError::ResumeCut {
            source,
            time,
            log: out.to_path_buf(),
        },
        e => e,
    })?;
    if in_place {
        // Finished: kept even if the rename fails (the error names it).
        temp.0 = None;
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
fn non_finite(cp: &carom_engine::Checkpoint) -> Option<String> {
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

/// Whether paths `a` and `b` name the same existing file (or are equal).
pub fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

/// The temporary file of a resume in place, removed when dropped unless it was
/// renamed over the input (then `None`).
struct TempFile(Option<std::path::PathBuf>);

impl Drop for TempFile {
    fn drop(&mut self) {
        if let Some(path) = &self.0 {
            let _ = std::fs::remove_file(path);
        }
    }
}
