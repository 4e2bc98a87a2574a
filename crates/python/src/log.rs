//! `carom.open_log(path)`: a carom log (MCAP) read with carom-log's reader into
//! numpy arrays. Its run metadata as a dict of JSON texts (the run facts among
//! them), its snapshots one at a time (the arrays of `arrays.rs`), its `/thermo`
//! records as JSON, and its collisions as columns, with the velocities of compact
//! records replayed exactly from the snapshots and checkpoints before them (the
//! reader's replay; docs/log-format.md, compact collisions).

use std::fs::File;
use std::io::BufReader;
use std::path::PathBuf;

use carom_log::{scan, scan_indexed, CollisionBatch, LogMessage, LogReader, Snapshot};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

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

/// The float64 columns of a collision batch, in the order of [`F64_NAMES`]
/// (the impulse apart: a full record does not store a pair's).
fn f64_columns(b: &CollisionBatch) -> [&[f64]; 15] {
    [
        &b.time,
        &b.nx,
        &b.ny,
        &b.vix_before,
        &b.viy_before,
        &b.vjx_before,
        &b.vjy_before,
        &b.vix_after,
        &b.viy_after,
        &b.vjx_after,
        &b.vjy_after,
        &b.energy_lost,
        &b.virial,
        &b.impulse_x,
        &b.impulse_y,
    ]
}

/// The index of `impulse_x` in [`f64_columns`].
const IMPULSE: usize = 13;

/// The names of [`f64_columns`] in the dict (those of `CollisionBatch`).
const F64_NAMES: [&str; 15] = [
    "time",
    "nx",
    "ny",
    "vix_before",
    "viy_before",
    "vjx_before",
    "vjy_before",
    "vix_after",
    "viy_after",
    "vjx_after",
    "vjy_after",
    "energy_lost",
    "virial",
    "impulse_x",
    "impulse_y",
];

/// The collisions with t0 ≤ time ≤ t1, as columns.
#[derive(Default)]
struct Columns {
    ordinal: Vec<u64>,
    kind: Vec<u8>,
    i: Vec<u32>,
    j: Vec<u32>,
    f64s: [Vec<f64>; 15],
}

impl Columns {
    /// Append the records of `b` with t0 ≤ time ≤ t1 (a run of the batch, whose
    /// times are in order), column by column.
    fn take(&mut self, b: &CollisionBatch, t0: f64, t1: f64) {
        let lo = b.time.partition_point(|&t| t < t0);
        let hi = b.time.partition_point(|&t| t <= t1).max(lo);
        let ordinal = |k: usize| b.first_ordinal.wrapping_add(k as u64 * b.stride);
        self.ordinal.extend((lo..hi).map(ordinal));
        self.kind.extend_from_slice(&b.kind[lo..hi]);
        self.i.extend_from_slice(&b.i[lo..hi]);
        self.j.extend_from_slice(&b.j[lo..hi]);
        let stored = b.impulse_x.len() == b.len();
        for (k, (out, col)) in self.f64s.iter_mut().zip(f64_columns(b)).enumerate() {
            if k < IMPULSE || stored {
                out.extend_from_slice(&col[lo..hi]);
            } else {
                // Not stored: carom-log's rule for a full record's impulse.
                out.extend((lo..hi).map(|r| b.get(r).impulse[k - IMPULSE]));
            }
        }
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

    /// The collisions with t0 ≤ time ≤ t1 as a dict of numpy columns: `ordinal`,
    /// `kind` (0 pair, 1 wall), `time`, `i`, `j`, `nx`, `ny`, the velocities
    /// before and after (`vix_before` … `vjy_after`), `energy_lost`, `virial`,
    /// `impulse_x`, `impulse_y`.
    #[pyo3(signature = (t0=f64::NEG_INFINITY, t1=f64::INFINITY))]
    fn collision_columns<'py>(
        &self,
        py: Python<'py>,
        t0: f64,
        t1: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mut reader = open(&self.path)?;
        let c = py
            .detach(|| {
                let mut c = Columns::default();
                // Whole batches, replayed if compact (snapshots and checkpoints
                // read on the way feed the replay).
                while let Some(m) = reader.next_message().map_err(|e| e.to_string())? {
                    if let LogMessage::Collisions(b) = m {
                        if b.time.first().is_some_and(|&t| t > t1) {
                            break;
                        }
                        c.take(&b, t0, t1);
                    }
                }
                Ok::<_, String>(c)
            })
            .map_err(errors::read)?;
        let d = PyDict::new(py);
        d.set_item("ordinal", c.ordinal.into_pyarray(py))?;
        d.set_item("kind", c.kind.into_pyarray(py))?;
        d.set_item("i", c.i.into_pyarray(py))?;
        d.set_item("j", c.j.into_pyarray(py))?;
        for (name, v) in F64_NAMES.into_iter().zip(c.f64s) {
            d.set_item(name, v.into_pyarray(py))?;
        }
        Ok(d)
    }
}
