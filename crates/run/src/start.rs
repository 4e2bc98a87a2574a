//! A fresh run: check the options, place the discs (reporting relaxed or
//! compressed placement's progress and heeding the stop flag, before any log
//! exists), build the engine, refuse a stop it could never reach in reasonable
//! work (`watchdog`, `bounds`), write the run's metadata and hand over to the
//! [`Driver`].

use std::ops::ControlFlow;
use std::path::Path;
use std::sync::atomic::Ordering;
use std::time::Instant;

use carom_engine::{Engine, PlacementProgress, State, SystemSpec};
use carom_log::{
    check_log_options, now_rfc3339, LogWriter, RunFacts, RunMetadata, RunSpec, WriterOptions,
    WriterPosition, LOG_FORMAT_VERSION,
};

use super::bounds::check_scheduled;
use super::driver::Driver;
use super::replace::Output;
use super::watchdog::check_reachable;
use super::{Control, RunError, RunSummary};

/// Start a fresh run of `spec`, logging to `out` (created, or replaced once the
/// run has started: see `replace.rs`). Blocks until the run stops (stop
/// criterion, `control.stop`, or an engine failure, after which the log is still
/// finished). The log holds what `driver/mod.rs` describes.
///
/// ```no_run
/// use carom_run::{run, Control, Progress};
/// use std::sync::atomic::AtomicBool;
/// # fn spec() -> carom_log::RunSpec { unimplemented!() }
/// let stop = AtomicBool::new(false); // set it from a Ctrl-C handler
/// let mut show = |p: &Progress| eprintln!("t = {:.3}, {} collisions", p.sim_time, p.collisions);
/// let summary = run(&spec(), "out.mcap".as_ref(), Control::new(&stop, &mut show)).unwrap();
/// println!("{} collisions/s", summary.collisions_per_second);
/// ```
pub fn run(spec: &RunSpec, out: &Path, mut control: Control<'_>) -> Result<RunSummary, RunError> {
    // Before placement, which can take a minute: a fresh state starts at time 0.
    check_log_options(&spec.log, &spec.stop, 0.0, "stop.time")?;
    // Locked before placement, so that a second writer is refused at once; an
    // older log is replaced only once the new one has started (replace.rs).
    let output = Output::lock(out)?;
    let (engine, meta) = match start(spec, out, &mut control) {
        Ok(started) => started,
        Err(e) => return Err(output.abandon(e)),
    };
    let writer = LogWriter::create(
        output.writing(),
        WriterOptions {
            collision_normals: WriterOptions::needs_normals(spec.params.restitution),
            ..WriterOptions::from_log_options(&spec.log)
        },
        &meta.to_map(),
        WriterPosition::default(),
    );
    let writer = match writer {
        Ok(w) => w,
        Err(e) => return output.finish(Err(e.into())),
    };
    let mut d = Driver::new(engine, writer, spec.log.clone(), spec.stop, control);
    d.run_start_time = d.engine.now();
    d.max_quiet = spec.max_time_without_collision;
    d.replace_at_start = output.replace_at_start();
    let summary = d.schedule_initial().and_then(|()| d.run_loop(out));
    output.finish(summary)
}

/// Place the discs and build the engine and the run's metadata: all that can
/// fail before the log is written.
fn start(
    spec: &RunSpec,
    out: &Path,
    control: &mut Control<'_>,
) -> Result<(Engine, RunMetadata), RunError> {
    let state = place(&spec.system, control)?;
    debug_assert_eq!(state.time, 0.0);
    let n = state.len();
    let facts = RunFacts::new(&state.species, &state.sim_box, &spec.params, &spec.log)
        .with_thermostat(spec.thermostat);
    let engine = Engine::new(state, spec.params)
        .and_then(|mut e| {
            e.set_thermostat(spec.thermostat, spec.system.seed)?;
            Ok(e)
        })
        .map_err(|source| RunError::Engine {
            source,
            time: 0.0,
            log: out.to_path_buf(),
        })?;
    check_reachable(&engine, spec.stop, &spec.log)?;
    let stop_field = match spec.stop {
        carom_log::Stop::Time(_) => "stop.duration",
        carom_log::Stop::Collisions(_) => "stop.collisions",
    };
    check_scheduled(&engine, spec.stop, stop_field)?;
    let meta = RunMetadata {
        log_format: LOG_FORMAT_VERSION.into(),
        carom_version: env!("CARGO_PKG_VERSION").into(),
        config: spec.config_json.clone(),
        seed: spec.system.seed,
        start_time: now_rfc3339(),
        n_discs: n as u64,
        stop: spec.stop,
        max_time_without_collision: spec.max_time_without_collision,
        log: spec.log.clone(),
        resumed_from: None,
        resumed_at: None,
        run_facts: Some(facts),
    };
    Ok((engine, meta))
}

/// Build the initial state of `system`, reporting relaxed or compressed
/// placement's progress to
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
