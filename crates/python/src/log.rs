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

/// The collisions with t0 ≤ time ≤ t1, as columns (the names of
/// `CollisionBatch`, with `ordinal`).
#[derive(Default)]
struct Columns {
    ordinal: Vec<u64>,
    batch: CollisionBatch,
}

impl Columns {
    fn take(&mut self, b: &CollisionBatch, t0: f64, t1: f64) {
        for r in b.iter().filter(|r| r.time >= t0 && r.time <= t1) {
            self.ordinal.push(r.ordinal);
            self.batch.push(&r);
            // The one field `push` leaves out: zero in a full record of a pair.
            self.batch.impulse_x.push(r.impulse.x);
            self.batch.impulse_y.push(r.impulse.y);
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
        let b = c.batch;
        let d = PyDict::new(py);
        d.set_item("ordinal", c.ordinal.into_pyarray(py))?;
        d.set_item("kind", b.kind.into_pyarray(py))?;
        d.set_item("time", b.time.into_pyarray(py))?;
        d.set_item("i", b.i.into_pyarray(py))?;
        d.set_item("j", b.j.into_pyarray(py))?;
        let f64s = [
            ("nx", b.nx),
            ("ny", b.ny),
            ("vix_before", b.vix_before),
            ("viy_before", b.viy_before),
            ("vjx_before", b.vjx_before),
            ("vjy_before", b.vjy_before),
            ("vix_after", b.vix_after),
            ("viy_after", b.viy_after),
            ("vjx_after", b.vjx_after),
            ("vjy_after", b.vjy_after),
            ("energy_lost", b.energy_lost),
            ("virial", b.virial),
            ("impulse_x", b.impulse_x),
            ("impulse_y", b.impulse_y),
        ];
        for (name, v) in f64s {
            d.set_item(name, v.into_pyarray(py))?;
        }
        Ok(d)
    }
}
