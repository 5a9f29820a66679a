//! `pathtrace.Scene` and its loaders: scene files of every format the CLI reads, native JSON
//! text (what `load_dict` sends), and the built-in scenes.

use crate::error::scene_error;
use pathtrace_scene::native::{self, Format};
use pathtrace_scene::{builtin as builtins, LoadedScene, RenderDefaults};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A built scene (geometry, BVH, lights, camera) and the render settings its file suggests.
/// Immutable and shareable: many renders may use one scene at once.
#[pyclass(frozen, module = "pathtrace")]
pub struct Scene {
    pub scene: Arc<pathtrace::Scene>,
    pub defaults: RenderDefaults,
    name: String,
}

impl Scene {
    fn new(loaded: LoadedScene, name: String) -> Self {
        Self { scene: Arc::new(loaded.scene), defaults: loaded.defaults, name }
    }
}

#[pymethods]
impl Scene {
    /// Image width the scene suggests, in pixels.
    #[getter]
    fn width(&self) -> u32 {
        self.defaults.width
    }

    /// Image height the scene suggests, in pixels.
    #[getter]
    fn height(&self) -> u32 {
        self.defaults.height
    }

    /// Samples per pixel the scene suggests.
    #[getter]
    fn spp(&self) -> u32 {
        self.defaults.spp
    }

    /// Maximum path segments the scene suggests (-1: unlimited).
    #[getter]
    fn max_depth(&self) -> i32 {
        self.defaults.max_depth
    }

    /// Number of primitives (triangles, spheres, quads, …) in the scene.
    #[getter]
    fn primitive_count(&self) -> usize {
        self.scene.primitive_count()
    }

    fn __repr__(&self) -> String {
        let d = &self.defaults;
        format!("<pathtrace.Scene {} {}x{}, {} spp>", self.name, d.width, d.height, d.spp)
    }
}

/// Loads a scene file (`.toml`, `.json`, Mitsuba `.xml`); returns the scene and the import
/// warnings (the Python layer issues them with `warnings.warn`).
#[pyfunction]
#[pyo3(signature = (path, defines=Vec::new()))]
pub fn load_file(py: Python<'_>, path: PathBuf, defines: Vec<(String, String)>) -> PyResult<(Scene, Vec<String>)> {
    let pairs: Vec<(&str, &str)> = defines.iter().map(|(n, v)| (n.as_str(), v.as_str())).collect();
    let mut warnings = Vec::new();
    // Building a large scene (a BVH over millions of triangles) takes a while: let other Python
    // threads run meanwhile.
    let loaded = py.detach(|| pathtrace_scene::load_file(&path, &pairs, &mut |w: &str| warnings.push(w.to_string())));
    let loaded = loaded.map_err(|e| scene_error(py, &e))?;
    Ok((Scene::new(loaded, path.display().to_string()), warnings))
}

/// Builds a scene from native-format JSON text; `name` stands for the file in errors, and
/// relative mesh paths resolve against the current directory.
#[pyfunction]
pub fn load_json(py: Python<'_>, text: String, name: String) -> PyResult<Scene> {
    let loaded = py.detach(|| native::load_str(&text, Format::Json, Path::new(&name)));
    let loaded = loaded.map_err(|e| scene_error(py, &e))?;
    Ok(Scene::new(loaded, name))
}

/// A built-in scene by name.
#[pyfunction]
pub fn builtin(py: Python<'_>, name: String) -> PyResult<Scene> {
    match builtins::load(&name) {
        Some(Ok(loaded)) => Ok(Scene::new(loaded, name)),
        Some(Err(e)) => Err(scene_error(py, &e)),
        None => Err(PyValueError::new_err(format!(
            "unknown built-in scene '{name}': the built-in scenes are {}",
            builtins::NAMES.join(", ")
        ))),
    }
}

/// The names `builtin` accepts.
#[pyfunction]
pub fn builtin_names() -> Vec<&'static str> {
    builtins::NAMES.to_vec()
}
