//! One state of the discs as a dict of numpy arrays, the same for a simulation's
//! `state` and a log's snapshots: `x`, `y`, `vx`, `vy` (float64, length N),
//! `image` (int32, N × 2: the unwrapped position is r_i + n_i·L), `species`
//! (int32), `radius` and `mass` (float64, per disc), `time` and `box` (L_x, L_y).
//! Disc i is the user's disc i (the order of the configuration's species and of
//! `placement.explicit`, or of the arrays given to `Simulation.from_arrays`).
//!
//! Each column is written once, straight into a fresh numpy array ([`Columns`]):
//! at N = 10⁶ a state is 60 MB, and a copy through an intermediate state cost
//! more than the writing itself.

use carom_core::DVec2;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The arrays of one state, borrowed from a snapshot.
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
        let columns = Columns::zeros(py, n);
        columns.write(|w| {
            for i in 0..n {
                let image = self.images.get(i).copied().unwrap_or([0; 2]);
                w.disc(i, self.positions[i], self.velocities[i], image);
                w.species[i] = i32::from(self.species[i]);
            }
        })?;
        columns.into_dict(
            py,
            self.time,
            self.box_size,
            self.species_radius,
            self.species_mass,
        )
    }
}

/// The per-disc columns of one state, fresh numpy arrays of N discs.
pub struct Columns<'py> {
    x: Bound<'py, PyArray1<f64>>,
    y: Bound<'py, PyArray1<f64>>,
    vx: Bound<'py, PyArray1<f64>>,
    vy: Bound<'py, PyArray1<f64>>,
    image: Bound<'py, PyArray2<i32>>,
    species: Bound<'py, PyArray1<i32>>,
}

/// The columns open for writing (see [`Columns::write`]).
pub struct Writer<'a> {
    x: &'a mut [f64],
    y: &'a mut [f64],
    vx: &'a mut [f64],
    vy: &'a mut [f64],
    /// Images, row-major N × 2.
    image: &'a mut [i32],
    /// Species of each disc.
    pub species: &'a mut [i32],
}

impl Writer<'_> {
    /// Write disc `i`: its position, velocity and periodic image.
    #[inline]
    pub fn disc(&mut self, i: usize, position: DVec2, velocity: DVec2, image: [i32; 2]) {
        self.x[i] = position.x;
        self.y[i] = position.y;
        self.vx[i] = velocity.x;
        self.vy[i] = velocity.y;
        self.image[2 * i] = image[0];
        self.image[2 * i + 1] = image[1];
    }
}

impl<'py> Columns<'py> {
    /// Columns of `n` discs, zero (numpy's `zeros`: the pages are the kernel's
    /// zero pages until written).
    pub fn zeros(py: Python<'py>, n: usize) -> Self {
        let f = || PyArray1::<f64>::zeros(py, n, false);
        Columns {
            x: f(),
            y: f(),
            vx: f(),
            vy: f(),
            image: PyArray2::<i32>::zeros(py, (n, 2), false),
            species: PyArray1::<i32>::zeros(py, n, false),
        }
    }

    /// Open every column for writing and hand them to `fill`.
    pub fn write(&self, fill: impl FnOnce(&mut Writer<'_>)) -> PyResult<()> {
        let (mut x, mut y) = (self.x.readwrite(), self.y.readwrite());
        let (mut vx, mut vy) = (self.vx.readwrite(), self.vy.readwrite());
        let (mut image, mut species) = (self.image.readwrite(), self.species.readwrite());
        fill(&mut Writer {
            x: x.as_slice_mut()?,
            y: y.as_slice_mut()?,
            vx: vx.as_slice_mut()?,
            vy: vy.as_slice_mut()?,
            image: image.as_slice_mut()?,
            species: species.as_slice_mut()?,
        });
        Ok(())
    }

    /// The state's dict: the columns, `radius` and `mass` per disc from the
    /// species' (`species_radius[species[i]]`), `time` and `box`.
    pub fn into_dict(
        self,
        py: Python<'py>,
        time: f64,
        box_size: DVec2,
        species_radius: &[f64],
        species_mass: &[f64],
    ) -> PyResult<Bound<'py, PyDict>> {
        let per_disc = |table: &[f64]| -> PyResult<Bound<'py, PyArray1<f64>>> {
            let species = self.species.readonly();
            let column = species.as_slice()?.iter().map(|&s| table[s as usize]);
            Ok(PyArray1::from_iter(py, column))
        };
        let (radius, mass) = (per_disc(species_radius)?, per_disc(species_mass)?);
        let d = PyDict::new(py);
        d.set_item("time", time)?;
        d.set_item("box", (box_size.x, box_size.y))?;
        d.set_item("x", self.x)?;
        d.set_item("y", self.y)?;
        d.set_item("vx", self.vx)?;
        d.set_item("vy", self.vy)?;
        d.set_item("radius", radius)?;
        d.set_item("mass", mass)?;
        d.set_item("species", self.species)?;
        d.set_item("image", self.image)?;
        Ok(d)
    }
}
