//! `pathtrace.SceneError`: a `ValueError` carrying the file, line and column the CLI prints.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

pyo3::create_exception!(
    pathtrace,
    SceneError,
    PyValueError,
    "A scene that cannot be loaded. `str(e)` is the CLI's `FILE:LINE:COL: message`; `.path`, `.line`, `.column` \
     and `.message` hold the parts."
);

/// The Python exception for a scene error, with its location as attributes.
pub fn scene_error(py: Python<'_>, e: &pathtrace_scene::native::SceneError) -> PyErr {
    let err = SceneError::new_err(e.to_string());
    let value = err.value(py);
    let located = (|| -> PyResult<()> {
        value.setattr("path", e.path.to_string_lossy().into_owned())?;
        value.setattr("line", e.line)?;
        value.setattr("column", e.column)?;
        value.setattr("message", e.message.clone())
    })();
    // Setting attributes on a fresh exception instance cannot fail short of memory exhaustion;
    // if it did, that error says more than a SceneError without its location.
    match located {
        Ok(()) => err,
        Err(attr_error) => attr_error,
    }
}
