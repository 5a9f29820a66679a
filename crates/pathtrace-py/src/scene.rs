//! `pathtrace.Scene` and its loaders: scene files of every format the CLI reads, native JSON
//! text (what `load_dict` sends), and the built-in scenes.

use crate::error::scene_error;
use pathtrace_scene::film_file::{scene_source_key, SceneSource};
use pathtrace_scene::native::{self, Format};
use pathtrace_scene::{builtin as builtins, LoadedScene, RenderDefaults};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What a scene was built from: enough to build it again elsewhere (pickling) and to key the
/// films rendered from it.
#[derive(Clone, Debug)]
enum Source {
    /// A file path (the other process must see the same file) and its defines.
    File(PathBuf, Vec<(String, String)>),
    /// Native JSON text and its name.
    Json(String, String),
    Builtin(String),
}

/// A pickled scene's source: (kind, path/text/name, name, defines), the arguments of
/// `_rebuild_scene`.
type SourceArgs = (String, String, String, Vec<(String, String)>);

/// A built scene (geometry, BVH, lights, camera) and the render settings its file suggests.
/// Immutable and shareable: many renders may use one scene at once.
#[pyclass(frozen, module = "pathtrace")]
pub struct Scene {
    pub scene: Arc<pathtrace::Scene>,
    pub defaults: RenderDefaults,
    name: String,
    source: Source,
    /// `scene_source_key` of the source, the scene half of the key films record.
    pub source_key: u64,
}

impl Scene {
    fn new(loaded: LoadedScene, name: String, source: Source, source_key: u64) -> Self {
        Self { scene: Arc::new(loaded.scene), defaults: loaded.defaults, name, source, source_key }
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

    /// A hex digest of what the scene was built from (file bytes and defines, JSON text or
    /// built-in name): films record it, and refuse to merge with films of another scene.
    #[getter]
    fn source_key(&self) -> String {
        format!("{:016x}", self.source_key)
    }

    /// Pickling rebuilds the scene from its source in the receiving process (a file scene needs
    /// the same file there, as a render farm's shared file system gives).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, SourceArgs)> {
        let rebuild = py.import("pathtrace._core")?.getattr("_rebuild_scene")?;
        let args: SourceArgs = match &self.source {
            Source::File(path, defines) => ("file".into(), path.display().to_string(), String::new(), defines.clone()),
            Source::Json(text, name) => ("json".into(), text.clone(), name.clone(), Vec::new()),
            Source::Builtin(name) => ("builtin".into(), name.clone(), String::new(), Vec::new()),
        };
        Ok((rebuild, args))
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
    // The loader read the file a moment ago; reading it again for the key is cheap by comparison.
    let bytes =
        std::fs::read(&path).map_err(|e| PyValueError::new_err(format!("{}: cannot read: {e}", path.display())))?;
    let key = scene_source_key(&SceneSource::File { bytes: &bytes, defines: &defines });
    let name = path.display().to_string();
    Ok((Scene::new(loaded, name, Source::File(path, defines), key), warnings))
}

/// Builds a scene from native-format JSON text; `name` stands for the file in errors, and
/// relative mesh paths resolve against the current directory.
#[pyfunction]
pub fn load_json(py: Python<'_>, text: String, name: String) -> PyResult<Scene> {
    let loaded = py.detach(|| native::load_str(&text, Format::Json, Path::new(&name)));
    let loaded = loaded.map_err(|e| scene_error(py, &e))?;
    let key = scene_source_key(&SceneSource::Text(&text));
    Ok(Scene::new(loaded, name.clone(), Source::Json(text, name), key))
}

/// A built-in scene by name.
#[pyfunction]
pub fn builtin(py: Python<'_>, name: String) -> PyResult<Scene> {
    match builtins::load(&name) {
        Some(Ok(loaded)) => {
            let key = scene_source_key(&SceneSource::Builtin(&name));
            Ok(Scene::new(loaded, name.clone(), Source::Builtin(name), key))
        }
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

/// Rebuilds a pickled scene (see `Scene.__reduce__`).
#[pyfunction]
pub fn _rebuild_scene(
    py: Python<'_>,
    kind: String,
    first: String,
    second: String,
    defines: Vec<(String, String)>,
) -> PyResult<Scene> {
    match kind.as_str() {
        "file" => load_file(py, PathBuf::from(first), defines).map(|(scene, _warnings)| scene),
        "json" => load_json(py, first, second),
        "builtin" => builtin(py, first),
        _ => Err(PyValueError::new_err(format!("not a pickled pathtrace scene (source kind '{kind}')"))),
    }
}
