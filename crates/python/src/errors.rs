//! carom's errors as Python exceptions: a configuration that cannot run is a
//! `ValueError` whose message is the command's (it names the field, as
//! `species.0.radius: …`); a log that cannot be read is an `OSError`; a failure
//! of the engine during a run is a `RuntimeError`.

use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::PyErr;

/// A configuration error (carom-config's message, naming the field).
pub fn config(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A log that cannot be read.
pub fn read(e: impl std::fmt::Display) -> PyErr {
    PyOSError::new_err(e.to_string())
}

/// The engine failed during a run.
pub fn engine(e: impl std::fmt::Display) -> PyErr {
    PyRuntimeError::new_err(e.to_string())
}
