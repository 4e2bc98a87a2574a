//! `carom.open_log(path)`: a carom log (MCAP) read with carom-log's reader into
//! numpy arrays. Its run metadata as a dict of JSON texts (the run facts among
//! them), its snapshots one at a time (the arrays of `arrays.rs`), its `/thermo`
//! records as JSON, its collisions as records of `carom.COLLISION_DTYPE`
//! (`collisions.rs`), with the velocities of compact records replayed exactly from
//! the snapshots and checkpoints before them (the reader's replay;
//! docs/log-format.md, compact collisions), and its snapshots stacked into 2-D
//! arrays after a memory check (`stack.rs`).

use std::fs::File;
use std::io::BufReader;
use std::path::PathBuf;

use carom_log::{scan, scan_indexed, LogMessage, LogReader, Snapshot};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

mod collisions;
mod stack;

use crate::arrays::Arrays;
use crate::errors;

/// A carom log opened for reading.
#[pyclass(module = "carom._carom")]
pub struct Log {
    path: PathBuf,
}

fn open(path: &std::path::Path) -> PyResult<LogReader<BufReader<File>>> {
    LogReader::open(path).map_err(errors::read)
}

/// A snapshot as the dict of `arrays.rs`.
fn snapshot_dict<'py>(py: Python<'py>, s: &Snapshot) -> PyResult<Bound<'py, PyDict>> {
    Arrays {
        time: s.time,
        box_size: s.box_size,
        species_radius: &s.species_radius,
        species_mass: &s.species_mass,
        species: &s.species,
        positions: &s.positions,
        velocities: &s.velocities,
        images: &s.images,
    }
    .to_dict(py)
}

/// The snapshots of a log with t0 ≤ time ≤ t1, one at a time (bound to the
/// thread that made it: the reader's decompressor is not shared between threads).
#[pyclass(module = "carom._carom", unsendable)]
pub struct Snapshots {
    reader: LogReader<BufReader<File>>,
    t0: f64,
    t1: f64,
}

#[pymethods]
impl Snapshots {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__<'py>(&mut self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        // A fresh view of the channel each time: it goes on where the last stopped.
        while let Some(m) = self.reader.snapshots().next() {
            let LogMessage::Snapshot(s) = m.map_err(errors::read)? else {
                continue;
            };
            if s.time > self.t1 {
                return Ok(None);
            }
            if s.time >= self.t0 {
                return snapshot_dict(py, &s).map(Some);
            }
        }
        Ok(None)
    }
}

impl Log {
    /// The number of collisions the log's index says it holds, when t0 and t1
    /// take them all (t0 ≤ 0, t1 = ∞) and the log is complete; else `None`.
    fn whole_log_collisions(&self, py: Python<'_>, t0: f64, t1: f64) -> PyResult<Option<usize>> {
        if t0 > 0.0 || t1 < f64::INFINITY {
            return Ok(None);
        }
        let info = py
            .detach(|| scan_indexed(&self.path))
            .map_err(errors::read)?;
        Ok(info
            .and_then(|i| i.summary)
            .and_then(|s| usize::try_from(s.logged_collisions).ok()))
    }
}

#[pymethods]
impl Log {
    #[new]
    fn new(path: PathBuf) -> PyResult<Self> {
        open(&path)?;
        Ok(Log { path })
    }

    /// The run's metadata (`carom.run`): each key's text, JSON for the structured
    /// ones (`config`, `stop`, `log_options`, `run_facts`).
    fn run_metadata(&self) -> PyResult<std::collections::BTreeMap<String, String>> {
        Ok(open(&self.path)?.run_map().clone())
    }

    /// The run's summary (`carom.summary`), absent from a log cut short: from
    /// the file's index, or a scan of the whole file where it has none.
    fn summary_metadata(
        &self,
        py: Python<'_>,
    ) -> PyResult<Option<std::collections::BTreeMap<String, String>>> {
        let info = py
            .detach(|| match scan_indexed(&self.path)? {
                Some(info) => Ok(info),
                None => scan(&self.path),
            })
            .map_err(errors::read)?;
        Ok(info.summary.map(|s| s.to_map()))
    }

    /// The snapshots with t0 ≤ time ≤ t1, one dict of arrays at a time.
    #[pyo3(signature = (t0=f64::NEG_INFINITY, t1=f64::INFINITY))]
    fn snapshots(&self, t0: f64, t1: f64) -> PyResult<Snapshots> {
        Ok(Snapshots {
            reader: open(&self.path)?,
            t0,
            t1,
        })
    }

    /// Every `/thermo` record as its JSON text, in order.
    fn thermo_json(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        let mut reader = open(&self.path)?;
        py.detach(|| {
            let mut out = Vec::new();
            for m in reader.thermo() {
                if let LogMessage::Thermo(t) = m.map_err(|e| e.to_string())? {
                    out.push(serde_json::to_string(&t).map_err(|e| e.to_string())?);
                }
            }
            Ok::<_, String>(out)
        })
        .map_err(errors::read)
    }

    /// The collisions with t0 ≤ time ≤ t1 as a uint64 array of one row per
    /// record, its words laid out as `carom.COLLISION_DTYPE` (`collisions.rs`),
    /// for Python to view as that dtype. Read with the GIL released. For the
    /// whole of a complete log the array is allocated by numpy first (the count
    /// is the summary's), which backs large arrays with huge pages: a quarter of
    /// the time went to the kernel mapping 4 KiB pages of a growing `Vec`.
    #[pyo3(signature = (t0=f64::NEG_INFINITY, t1=f64::INFINITY))]
    fn collision_records<'py>(
        &self,
        py: Python<'py>,
        t0: f64,
        t1: f64,
    ) -> PyResult<Bound<'py, PyArray2<u64>>> {
        if let Some(n) = self.whole_log_collisions(py, t0, t1)? {
            let records = PyArray2::<u64>::zeros(py, [n, collisions::WORDS], false);
            let mut rw = records.readwrite();
            let out = rw.as_slice_mut()?;
            let mut reader = open(&self.path)?;
            let filled = py
                .detach(|| collisions::fill_collision_words(&mut reader, t0, t1, out))
                .map_err(errors::read)?;
            if filled {
                drop(rw);
                return Ok(records);
            }
        }
        let mut reader = open(&self.path)?;
        let words = py
            .detach(|| collisions::collision_words(&mut reader, t0, t1))
            .map_err(errors::read)?;
        let rows = words.len() / collisions::WORDS;
        let records = Array2::from_shape_vec((rows, collisions::WORDS), words)
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(records.into_pyarray(py))
    }

    /// The snapshots with t0 ≤ time ≤ t1 stacked (frames × N), after the memory
    /// check of `stack.rs` against `max_bytes` (default: half the memory
    /// available).
    #[pyo3(signature = (t0=f64::NEG_INFINITY, t1=f64::INFINITY, max_bytes=None))]
    fn snapshot_stack<'py>(
        &self,
        py: Python<'py>,
        t0: f64,
        t1: f64,
        max_bytes: Option<u64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        stack::snapshot_stack(py, &self.path, t0, t1, max_bytes)
    }
}
