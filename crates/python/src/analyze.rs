//! `carom.analyze(path, …)`: carom-analysis on a log, the same report as
//! `carom analyze --json` (the `Report` serialised, with `file` and
//! `log_complete` added), as JSON text that the Python side turns into a dict.
//! An old log's missing run facts are derived from its configuration, as the
//! command does (carom-config's `derive_facts_for_old_log`).

use std::path::PathBuf;

use carom_analysis::{analyze_log_with, AnalysisOptions, ReadObserver};
use carom_config::derive_facts_for_old_log;
use carom_log::ReadProgress;
use pyo3::prelude::*;

use crate::errors;

/// Reading goes unshown; the warnings about a damaged log are kept.
#[derive(Default)]
struct Quiet {
    warnings: Vec<String>,
}

impl ReadObserver for Quiet {
    fn pass(&mut self, _what: &'static str) {}
    fn progress(&mut self, _p: ReadProgress) {}
    fn warn(&mut self, line: &str) {
        self.warnings.push(line.to_owned());
    }
}

/// Analyse the log `path` (the options of `carom analyze`: `equilibrate`,
/// `every`, `bins`, `structure`) and return the report as JSON text with the
/// warnings about the log.
#[pyfunction]
#[pyo3(signature = (path, equilibrate=None, every=None, bins=40, structure=true))]
pub fn analyze_json(
    py: Python<'_>,
    path: PathBuf,
    equilibrate: Option<f64>,
    every: Option<f64>,
    bins: usize,
    structure: bool,
) -> PyResult<(String, Vec<String>)> {
    if bins < 4 {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "bins = {bins}: at least 4 (the χ² test fits kT and needs a degree of freedom left)"
        )));
    }
    let opts = AnalysisOptions {
        equilibrate,
        every,
        speed_bins: bins,
        structure,
        ..AnalysisOptions::default()
    };
    let mut quiet = Quiet::default();
    let (report, complete) = py
        .detach(|| analyze_log_with(&path, opts, &derive_facts_for_old_log, &mut quiet))
        .map_err(errors::read)?;
    let v = report.to_json(&path.display().to_string(), complete);
    Ok((v.to_string(), quiet.warnings))
}
