//! The observables of plain arrays (`carom.pair_correlation`, `psi6`,
//! `structure_factor`, `msd`, …): carom-analysis's `frames` module and its ψ6
//! estimators, wrapped, not re-implemented, so the arrays of any code give the
//! numbers `carom analyze` gives a log (physics.md §10–§13, the same
//! accumulators, bit for bit). The Python side (`python/carom/observables.py`)
//! names and checks the arguments and turns frames of any shape into the stacks
//! passed here: x, y (and vx, vy) as frames × N float64, one species index per
//! disc, per-species radius and mass, the box (L_x, L_y) with which axes are
//! periodic, and the window [t0, t1]. The sections come back as the JSON of the
//! report (`serde_json`, exact for every f64), ψ6 per disc as interleaved
//! (Re, Im) pairs, which numpy views as complex128 without a copy.

use carom_analysis::frames::{self, Frame, System, Window};
use carom_analysis::{delaunay_neighbours, local_psi6, local_psi6_equal, local_psi6_nearest};
use carom_core::{Boundary, SimBox, Species};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The box (L_x, L_y) with each axis periodic or walled (the walls' restitution
/// plays no part in a snapshot's structure).
fn sim_box(size: (f64, f64), periodic: (bool, bool)) -> SimBox {
    let axis = |p: bool| {
        if p {
            Boundary::Periodic
        } else {
            Boundary::Walls { restitution: 1.0 }
        }
    };
    SimBox {
        size: carom_core::DVec2::new(size.0, size.1),
        boundary: [axis(periodic.0), axis(periodic.1)],
    }
}

/// The box and species of the frames: species s has `radius[s]`, `mass[s]` and
/// as many discs as `species` (one index per disc) names it.
fn system(
    size: (f64, f64),
    periodic: (bool, bool),
    radius: &[f64],
    mass: &[f64],
    species: &[u16],
) -> PyResult<System> {
    if radius.len() != mass.len() {
        return Err(PyValueError::new_err(format!(
            "radius and mass: {} and {} species",
            radius.len(),
            mass.len()
        )));
    }
    let mut count = vec![0usize; radius.len()];
    for &s in species {
        let c = count.get_mut(s as usize).ok_or_else(|| {
            PyValueError::new_err(format!(
                "species: index {s}, but radius gives {} species",
                radius.len()
            ))
        })?;
        *c += 1;
    }
    Ok(System {
        sim_box: sim_box(size, periodic),
        species: (0..radius.len())
            .map(|s| Species::new(count[s], radius[s], mass[s]))
            .collect(),
    })
}

/// One [`Frame`] per row of `x`, `y` (and `v` = (vx, vy)) at `times`.
fn stack(
    times: &[f64],
    species: &[u16],
    x: &PyReadonlyArray2<'_, f64>,
    y: &PyReadonlyArray2<'_, f64>,
    v: Option<(&PyReadonlyArray2<'_, f64>, &PyReadonlyArray2<'_, f64>)>,
) -> PyResult<Vec<Frame>> {
    let (x, y) = (x.as_array(), y.as_array());
    let v = v.map(|(vx, vy)| (vx.as_array(), vy.as_array()));
    let rows = [
        Some(x.nrows()),
        Some(y.nrows()),
        v.map(|v| v.0.nrows()),
        v.map(|v| v.1.nrows()),
    ];
    if rows.iter().flatten().any(|&r| r != times.len()) {
        return Err(PyValueError::new_err(format!(
            "times: {} frames, but the arrays have {rows:?} rows",
            times.len()
        )));
    }
    Ok(times
        .iter()
        .enumerate()
        .map(|(f, &time)| Frame {
            time,
            species: species.to_vec(),
            x: x.row(f).to_vec(),
            y: y.row(f).to_vec(),
            velocities: v.map(|(vx, vy)| [vx.row(f).to_vec(), vy.row(f).to_vec()]),
        })
        .collect())
}

fn invalid(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// The structure sections (g_ab(r) with contact values, ψ6 with |Ψ6| and χ6,
/// g6(r), S(k); physics.md §10–§11) of the frames (positions in the box) in the
/// window, as the JSON of `carom analyze --json`'s sections.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn structure_json(
    py: Python<'_>,
    box_size: (f64, f64),
    periodic: (bool, bool),
    radius: Vec<f64>,
    mass: Vec<f64>,
    species: Vec<u16>,
    times: Vec<f64>,
    x: PyReadonlyArray2<'_, f64>,
    y: PyReadonlyArray2<'_, f64>,
    window: (f64, f64),
) -> PyResult<String> {
    let system = system(box_size, periodic, &radius, &mass, &species)?;
    let frames = stack(&times, &species, &x, &y, None)?;
    let window = Window {
        start: window.0,
        end: window.1,
    };
    let report = py
        .detach(|| frames::structure(&system, window, &frames))
        .map_err(invalid)?;
    serde_json::to_string(&report).map_err(invalid)
}

/// The dynamics section (MSD, α₂, D per species, the snapshot VACF, F_s(k*, τ)
/// and τ_α; physics.md §13) of frames of unwrapped positions and velocities in
/// time order, as JSON; `None` without two frames in the window.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn dynamics_json(
    py: Python<'_>,
    box_size: (f64, f64),
    periodic: (bool, bool),
    radius: Vec<f64>,
    mass: Vec<f64>,
    species: Vec<u16>,
    times: Vec<f64>,
    x: PyReadonlyArray2<'_, f64>,
    y: PyReadonlyArray2<'_, f64>,
    vx: PyReadonlyArray2<'_, f64>,
    vy: PyReadonlyArray2<'_, f64>,
    window: (f64, f64),
    snapshot_interval: Option<f64>,
    collision_rate: Option<f64>,
) -> PyResult<Option<String>> {
    let system = system(box_size, periodic, &radius, &mass, &species)?;
    let frames = stack(&times, &species, &x, &y, Some((&vx, &vy)))?;
    let window = Window {
        start: window.0,
        end: window.1,
    };
    let rate = collision_rate.unwrap_or(f64::NAN);
    let report = py
        .detach(|| frames::dynamics(&system, window, snapshot_interval, rate, &frames))
        .map_err(invalid)?;
    report
        .map(|r| serde_json::to_string(&r).map_err(invalid))
        .transpose()
}

/// ψ6 of every disc of one frame (positions in the box) by `estimator`:
/// "voronoi" (11.1), "delaunay" (11.7) or "nearest" over the `k` nearest
/// (11.8); (Re, Im) interleaved, 2N float64.
#[pyfunction]
pub fn local_psi6_pairs<'py>(
    py: Python<'py>,
    box_size: (f64, f64),
    periodic: (bool, bool),
    x: PyReadonlyArray1<'py, f64>,
    y: PyReadonlyArray1<'py, f64>,
    estimator: &str,
    k: usize,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let sb = sim_box(box_size, periodic);
    let (x, y) = (x.as_array().to_vec(), y.as_array().to_vec());
    if x.len() != y.len() {
        return Err(PyValueError::new_err(format!(
            "x and y: {} and {} discs",
            x.len(),
            y.len()
        )));
    }
    let psi = py.detach(|| match estimator {
        "voronoi" => Ok(local_psi6(&sb, &x, &y)),
        "delaunay" => Ok(local_psi6_equal(&delaunay_neighbours(&sb, &x, &y))),
        "nearest" => Ok(local_psi6_nearest(
            &sb,
            &x,
            &y,
            &delaunay_neighbours(&sb, &x, &y),
            k,
        )),
        other => Err(PyValueError::new_err(format!(
            "estimator = {other:?}: one of \"voronoi\", \"delaunay\", \"nearest\""
        ))),
    })?;
    Ok(psi.into_flattened().into_pyarray(py))
}
