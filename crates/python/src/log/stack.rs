//! `Log.snapshot_stack(t0, t1)`: the snapshots with t0 ≤ time ≤ t1 stacked into
//! 2-D numpy arrays (frames × N), after a memory check. A first pass counts the
//! frames without decoding them (each snapshot's time read from its message);
//! the stack needs frames × N × [`BYTES_PER_DISC`] bytes, which must not exceed
//! `max_bytes` (by default half the memory available to the process, carom-run's
//! [`memory_available`]: the other half is left for what the caller computes
//! from the arrays). Only then is anything large allocated and the second pass
//! decodes the frames into it. N is fixed for a run (no disc is added or
//! removed), but a frame with other discs than the first (N or species) is
//! refused rather than stacked wrongly.

use std::path::Path;

use carom_log::{LogMessage, LogReader, CH_SNAPSHOT};
use carom_run::{memory_available, IGNORE_MEMORY_CHECK};
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::IntoPyArray;
use pyo3::exceptions::{PyMemoryError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors;

/// Bytes per disc and frame of a stack: x, y, vx, vy, radius (float64) and the
/// two images (int32).
pub const BYTES_PER_DISC: u64 = 5 * 8 + 2 * 4;
/// Bytes per frame besides the discs: time and box (float64).
const BYTES_PER_FRAME: u64 = 3 * 8;

/// The stack's arrays while they are filled (frames × N, row-major).
#[derive(Default)]
struct Stack {
    /// N, the discs of every frame.
    n: usize,
    time: Vec<f64>,
    box_size: Vec<f64>,
    x: Vec<f64>,
    y: Vec<f64>,
    vx: Vec<f64>,
    vy: Vec<f64>,
    radius: Vec<f64>,
    image: Vec<i32>,
    species: Vec<u16>,
    mass: Vec<f64>,
}

/// Times of the snapshots with t0 ≤ time ≤ t1 (the first pass: messages are
/// not decoded).
fn frame_times(path: &Path, t0: f64, t1: f64) -> Result<Vec<f64>, carom_log::ReadError> {
    let mut reader = LogReader::open(path)?;
    let mut times = Vec::new();
    while let Some(m) = reader.next_raw()? {
        if m.channel != CH_SNAPSHOT {
            continue;
        }
        let t = m.simulated_times().0;
        if t > t1 {
            break;
        }
        if t >= t0 {
            times.push(t);
        }
    }
    Ok(times)
}

/// The largest stack allowed and where the number comes from; `None`: no check
/// (memory unknown, or `CAROM_IGNORE_MEMORY_CHECK=1` without a `max_bytes`).
fn limit(max_bytes: Option<u64>) -> Option<(u64, String)> {
    if let Some(b) = max_bytes {
        return Some((b, "max_bytes".into()));
    }
    if std::env::var(IGNORE_MEMORY_CHECK).is_ok_and(|v| v == "1") {
        return None;
    }
    let (available, source) = memory_available()?;
    Some((
        available / 2,
        format!("half of the memory available, {source}"),
    ))
}

/// Refuse a stack of `frames` × `n` discs larger than the limit.
fn check(frames: &[f64], n: u64, t: (f64, f64), max_bytes: Option<u64>) -> PyResult<()> {
    let Some((allowed, source)) = limit(max_bytes) else {
        return Ok(());
    };
    let per_frame = n * BYTES_PER_DISC + BYTES_PER_FRAME;
    let needed = frames.len() as u64 * per_frame;
    if needed <= allowed {
        return Ok(());
    }
    let fit = allowed / per_frame;
    let gb = |b: u64| b as f64 / 1e9;
    let span = format!(
        "t = {} to {}",
        frames.first().copied().unwrap_or(f64::NAN),
        frames.last().copied().unwrap_or(f64::NAN)
    );
    Err(PyMemoryError::new_err(format!(
        "snapshot_stack(t0={}, t1={}): {} frames ({span}) of {n} discs need {:.2} GB \
         ({BYTES_PER_DISC} bytes per disc and frame), more than the {:.2} GB allowed \
         ({source}); narrow t0 and t1 to at most {fit} frames, read the frames one at a \
         time with snapshots(t0, t1), or raise max_bytes",
        t.0,
        t.1,
        frames.len(),
        gb(needed),
        gb(allowed),
    )))
}

impl Stack {
    fn with_capacity(frames: usize, n: usize) -> Self {
        let per_disc = || Vec::with_capacity(frames * n);
        Stack {
            n,
            time: Vec::with_capacity(frames),
            box_size: Vec::with_capacity(2 * frames),
            x: per_disc(),
            y: per_disc(),
            vx: per_disc(),
            vy: per_disc(),
            radius: per_disc(),
            image: Vec::with_capacity(2 * frames * n),
            ..Stack::default()
        }
    }

    /// Append snapshot `s`; a frame of other discs than the run's N, or of
    /// other species than the first frame, is an error.
    fn push(&mut self, s: &carom_log::Snapshot) -> Result<(), String> {
        if s.len() != self.n || (!self.time.is_empty() && s.species != self.species) {
            return Err(format!(
                "the snapshot at time {} has {} discs where the run has {} (or other \
                 species than the first frame): frames of different discs cannot be \
                 stacked; read them one at a time with snapshots(t0, t1)",
                s.time,
                s.len(),
                self.n
            ));
        }
        if self.time.is_empty() {
            self.species.clone_from(&s.species);
            self.mass = (0..s.len()).map(|k| s.mass(k)).collect();
        }
        self.time.push(s.time);
        self.box_size.extend([s.box_size.x, s.box_size.y]);
        self.x.extend(s.positions.iter().map(|p| p.x));
        self.y.extend(s.positions.iter().map(|p| p.y));
        self.vx.extend(s.velocities.iter().map(|v| v.x));
        self.vy.extend(s.velocities.iter().map(|v| v.y));
        let radius = |k: usize| s.species_radius[usize::from(s.species[k])];
        self.radius.extend((0..s.len()).map(radius));
        if s.images.len() == s.len() {
            self.image.extend(s.images.iter().flatten());
        } else {
            // Logs before format 2.1 hold no images.
            self.image.extend(std::iter::repeat_n(0, 2 * s.len()));
        }
        Ok(())
    }

    fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let (f, n) = (self.time.len(), self.n);
        let shape = |v: Vec<f64>| Array2::from_shape_vec((f, n), v);
        let bad = |e: numpy::ndarray::ShapeError| PyValueError::new_err(e.to_string());
        let d = PyDict::new(py);
        d.set_item("time", Array1::from(self.time).into_pyarray(py))?;
        let boxes = Array2::from_shape_vec((f, 2), self.box_size).map_err(bad)?;
        d.set_item("box", boxes.into_pyarray(py))?;
        for (name, v) in [
            ("x", self.x),
            ("y", self.y),
            ("vx", self.vx),
            ("vy", self.vy),
            ("radius", self.radius),
        ] {
            d.set_item(name, shape(v).map_err(bad)?.into_pyarray(py))?;
        }
        let image = Array3::from_shape_vec((f, n, 2), self.image).map_err(bad)?;
        d.set_item("image", image.into_pyarray(py))?;
        let species: Vec<i32> = self.species.iter().map(|&s| i32::from(s)).collect();
        d.set_item("species", species.into_pyarray(py))?;
        d.set_item("mass", self.mass.into_pyarray(py))?;
        Ok(d)
    }
}

/// The stacked snapshots of the log at `path` (see the module's documentation).
pub fn snapshot_stack<'py>(
    py: Python<'py>,
    path: &Path,
    t0: f64,
    t1: f64,
    max_bytes: Option<u64>,
) -> PyResult<Bound<'py, PyDict>> {
    let frames = py
        .detach(|| frame_times(path, t0, t1))
        .map_err(errors::read)?;
    let n = LogReader::open(path).map_err(errors::read)?.run().n_discs;
    check(&frames, n, (t0, t1), max_bytes)?;
    let stack = py.detach(|| {
        let mut stack = Stack::with_capacity(frames.len(), n as usize);
        let mut reader = LogReader::open(path).map_err(errors::read)?;
        for m in reader.snapshots() {
            let LogMessage::Snapshot(s) = m.map_err(errors::read)? else {
                continue;
            };
            if s.time > t1 {
                break;
            }
            if s.time >= t0 {
                stack.push(&s).map_err(PyValueError::new_err)?;
            }
        }
        Ok::<_, PyErr>(stack)
    })?;
    stack.into_dict(py)
}
