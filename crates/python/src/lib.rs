//! `carom._carom`: the compiled half of carom's Python package (the other half,
//! `python/carom/__init__.py`, puts a Python face on it).
//!
//! Three things, each a file: a simulation in memory ([`Simulation`], built by
//! carom-config from the same JSON configuration as `carom run`, run by the
//! engine with the GIL released), a log read into numpy arrays ([`Log`], by
//! carom-log's reader, compact collision records replayed), and the analysis of
//! a log as the JSON of `carom analyze --json` ([`analyze_json`]). Arrays are
//! float64 with the discs in the user's order (physics.md's notation: positions
//! r_i, velocities v_i, images n_i with unwrapped r_i + n_i·L).
#![deny(missing_docs)]

mod analyze;
mod arrays;
mod errors;
mod from_arrays;
mod live;
mod log;
mod logged;
mod observables;
mod simulation;

use pyo3::prelude::*;

pub use analyze::analyze_json;
pub use log::Log;
pub use observables::{dynamics_json, local_psi6_pairs, structure_json};
pub use simulation::Simulation;

/// The module `carom._carom`.
#[pymodule]
fn _carom(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Simulation>()?;
    m.add_class::<Log>()?;
    m.add_function(wrap_pyfunction!(analyze_json, m)?)?;
    // The observables of plain arrays (observables.rs).
    m.add_function(wrap_pyfunction!(structure_json, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics_json, m)?)?;
    m.add_function(wrap_pyfunction!(local_psi6_pairs, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
