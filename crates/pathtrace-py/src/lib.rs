//! The native core of the Python package `pathtrace` (`pathtrace._core`): scenes, renders and
//! films as Python objects over the engine's `Scene`, `RenderSession` and `Film`, with numpy
//! arrays out. The pure-Python layer (`python/pathtrace/__init__.py`) holds the public API, its
//! docstrings and the bits that are simplest in Python (a dict as JSON, warnings).

mod error;
mod film;
mod job;
mod options;
mod progress;
mod render;
mod scene;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<error::SceneError>())?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<film::Film>()?;
    m.add_class::<progress::Progress>()?;
    m.add_class::<job::RenderJob>()?;
    m.add_function(wrap_pyfunction!(scene::load_file, m)?)?;
    m.add_function(wrap_pyfunction!(scene::load_json, m)?)?;
    m.add_function(wrap_pyfunction!(scene::builtin, m)?)?;
    m.add_function(wrap_pyfunction!(scene::builtin_names, m)?)?;
    m.add_function(wrap_pyfunction!(scene::_rebuild_scene, m)?)?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::start, m)?)?;
    m.add_function(wrap_pyfunction!(render::render_key, m)?)?;
    Ok(())
}
