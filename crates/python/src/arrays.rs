//! One state of the discs as a dict of numpy arrays, the same for a simulation's
//! `state` and a log's snapshots: `x`, `y`, `vx`, `vy` (float64, length N),
//! `image` (int32, N × 2: the unwrapped position is r_i + n_i·L), `species`
//! (int32), `radius` and `mass` (float64, per disc), `time` and `box` (L_x, L_y).
//! Disc i is the user's disc i (the order of the configuration's species and of
//! `placement.explicit`).

use carom_core::DVec2;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The arrays of one state, borrowed from an engine's state or a snapshot.
pub struct Arrays<'a> {
    /// Simulated time (time).
    pub time: f64,
    /// Box size (L_x, L_y).
    pub box_size: DVec2,
    /// Radius of each species.
    pub species_radius: &'a [f64],
    /// Mass of each species.
    pub species_mass: &'a [f64],
    /// Species of each disc.
    pub species: &'a [u16],
    /// Positions, in the box.
    pub positions: &'a [DVec2],
    /// Velocities.
    pub velocities: &'a [DVec2],
    /// Periodic images (empty: all zero).
    pub images: &'a [[i32; 2]],
}

impl Arrays<'_> {
    /// The dict of numpy arrays.
    pub fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let n = self.positions.len();
        let column = |f: &dyn Fn(usize) -> f64| -> Bound<'py, PyArray1<f64>> {
            (0..n).map(f).collect::<Vec<f64>>().into_pyarray(py)
        };
        let d = PyDict::new(py);
        d.set_item("time", self.time)?;
        d.set_item("box", (self.box_size.x, self.box_size.y))?;
        d.set_item("x", column(&|i| self.positions[i].x))?;
        d.set_item("y", column(&|i| self.positions[i].y))?;
        d.set_item("vx", column(&|i| self.velocities[i].x))?;
        d.set_item("vy", column(&|i| self.velocities[i].y))?;
        let sp = |i: usize| self.species[i] as usize;
        d.set_item("radius", column(&|i| self.species_radius[sp(i)]))?;
        d.set_item("mass", column(&|i| self.species_mass[sp(i)]))?;
        let species: Vec<i32> = self.species.iter().map(|&s| i32::from(s)).collect();
        d.set_item("species", species.into_pyarray(py))?;
        let mut image = Array2::<i32>::zeros((n, 2));
        for (k, im) in self.images.iter().enumerate().take(n) {
            image[[k, 0]] = im[0];
            image[[k, 1]] = im[1];
        }
        d.set_item("image", image.into_pyarray(py))?;
        Ok(d)
    }
}
