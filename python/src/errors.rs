//! Rust errors as Python exceptions: one-line `ValueError`s, `OSError` for unreadable files.

use pyo3::PyErr;
use pyo3::exceptions::{PyOSError, PyValueError};

/// Any error as a `ValueError` with its one-line message.
pub(crate) fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A reader's error: unreadable files are `OSError`, everything else `ValueError`.
pub(crate) fn io_error(e: inrs::io::IoError) -> PyErr {
    match e {
        inrs::io::IoError::Read { .. } => PyOSError::new_err(e.to_string()),
        other => value_error(other),
    }
}
