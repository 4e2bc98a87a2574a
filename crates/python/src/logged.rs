//! `sim.run(..., log="run.mcap")`: a run that writes the command's log, by
//! carom-run itself (`carom_run::run` for a simulation at its start,
//! `carom_run::resume` to continue the log it last wrote), so the log is
//! analysed, resumed and exported by the command like any other. Afterwards the
//! simulation goes on from the log's final checkpoint, the engine's complete
//! state, as `carom resume` does: bit for bit the trajectory of one unbroken run.
//!
//! Ctrl-C: the run's progress callback (every [`LOOK`]) takes the GIL to look at
//! the signals; a signal raises the run's stop flag, the run finishes its log
//! (`stop_reason = interrupted`, resumable), and `KeyboardInterrupt` follows.
//!
//! Live: the simulation's server is the run's `Control::observer`, as for
//! `carom run --live`.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use carom_engine::Engine;
use carom_live::Live;
use carom_log::{last_checkpoint, RunSpec, Stop};
use carom_run::{Control, Observer, Progress, ResumeOptions, RunError};
use pyo3::exceptions::{PyFileExistsError, PyValueError};
use pyo3::prelude::*;

use crate::errors;

/// Wall time between two looks at the signals during a logged run.
const LOOK: Duration = Duration::from_millis(50);

/// Where a logged run starts.
pub enum Start<'a> {
    /// A fresh run of `spec` (the simulation is at its start).
    Fresh(&'a RunSpec),
    /// The continuation of the log the simulation last wrote.
    Resume,
}

fn run_error(e: RunError, config_json: &str) -> PyErr {
    match e {
        RunError::Init(init) => {
            errors::config(carom_config::ConfigError::from_init_in(init, config_json))
        }
        e @ RunError::Invalid { .. } => PyValueError::new_err(e.to_string()),
        e => errors::engine(e),
    }
}

/// Where a run of a simulation now at (`time`, `collisions`), whose last logged
/// run wrote `last` (if any), logging to `path`, starts; or why it cannot.
pub fn start<'a>(
    spec: &'a RunSpec,
    last: Option<&Path>,
    fresh: bool,
    path: &Path,
) -> PyResult<Start<'a>> {
    if last.is_some_and(|l| carom_run::same_file(l, path)) {
        return Ok(Start::Resume);
    }
    if !fresh {
        return Err(PyValueError::new_err(format!(
            "log = {}: a log holds a run from its start, and this simulation has run \
             without one (or into another log); log from a new Simulation",
            path.display()
        )));
    }
    if path.exists() {
        return Err(PyFileExistsError::new_err(format!(
            "{} exists; remove it or choose another log",
            path.display()
        )));
    }
    Ok(Start::Fresh(spec))
}

/// Run to `stop` writing `path`, served to `live` if given; returns the engine at
/// the log's final checkpoint, with the `KeyboardInterrupt` to raise if a signal
/// stopped the run (the log is finished either way).
pub fn run(
    py: Python<'_>,
    start: Start<'_>,
    stop: Stop,
    path: &Path,
    config_json: &str,
    live: Option<&mut Live>,
) -> PyResult<(Engine, Option<PyErr>)> {
    let flag = AtomicBool::new(false);
    let mut signal: Option<PyErr> = None;
    let out: PathBuf = path.to_path_buf();
    let result = py.detach(|| {
        let mut look = |_: &Progress| {
            if signal.is_none() {
                if let Err(e) = Python::attach(|py| py.check_signals()) {
                    signal = Some(e);
                    flag.store(true, Ordering::SeqCst);
                }
            }
        };
        let control = Control {
            progress_interval: LOOK,
            observer: live.map(|l| l as &mut dyn Observer),
            ..Control::new(&flag, &mut look)
        };
        match start {
            Start::Fresh(spec) => {
                let spec = RunSpec {
                    stop,
                    ..spec.clone()
                };
                carom_run::run(&spec, &out, control)
            }
            Start::Resume => {
                carom_run::resume(&out, &out, &ResumeOptions { stop: Some(stop) }, control)
            }
        }
    });
    result.map_err(|e| run_error(e, config_json))?;
    let (cp, _, _) = py.detach(|| last_checkpoint(&out)).map_err(errors::read)?;
    let engine = Engine::from_checkpoint(cp.engine).map_err(errors::engine)?;
    Ok((engine, signal))
}
