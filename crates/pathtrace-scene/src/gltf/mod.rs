//! glTF 2.0 import (`.gltf` with its `.bin` buffers, or `.glb`), through the `gltf` crate, into
//! the native model: mesh primitives become `mesh` objects referencing the glTF file's parts
//! (so `pathtrace convert scene.gltf scene.toml` writes a native file that still reads its
//! geometry from the glTF), materials follow the metallic-roughness model (see [`material`]),
//! the first camera (or the one `-D camera=NAME` names) and `KHR_lights_punctual` lights are
//! kept. Each substitution gives a warning; a bad file an error naming the file and the
//! location (JSON line and column for syntax, else the glTF item such as `accessors[3]`).
//!
//! ```sh
//! pathtrace render scene.gltf              # or scene.glb
//! pathtrace convert scene.gltf scene.toml
//! ```

mod document;
mod geometry;
pub(crate) mod images;
mod material;
mod scene;
mod texture;

use crate::native::model::Num;
use crate::native::{build, ItemPath, Locate, SceneError, SceneFile};
use crate::LoadedScene;
use pathtrace::shape::TriangleMesh;
use std::path::{Path, PathBuf};

/// The f32 as the shortest decimal that reads back as it (so converted files stay readable).
fn num(x: f32) -> Num {
    Num::new(x.to_string().parse().unwrap_or(0.0)).unwrap_or(Num::from(0.0))
}

/// True for a `.gltf` or `.glb` path (any case).
pub fn is_gltf(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

/// Parses the file's bytes; a JSON syntax error is located at its line and column.
fn open(bytes: &[u8], path: &Path) -> Result<document::Opened, SceneError> {
    if !bytes.starts_with(b"glTF") {
        if let Err(e) = serde_json::from_slice::<serde_json::Value>(bytes) {
            let text = String::from_utf8_lossy(bytes);
            return Err(SceneError::at_line(path, &text, e.line(), e.column(), format!("invalid glTF JSON: {e}")));
        }
    }
    document::open(bytes, path).map_err(|e| SceneError::whole_file(path, e))
}

/// Reads a glTF file into the native model, with warnings. `defines` may hold `camera=NAME`.
pub fn convert_file(path: &Path, defines: &[(&str, &str)]) -> Result<(SceneFile, Vec<String>), SceneError> {
    let bytes = std::fs::read(path).map_err(|e| SceneError::whole_file(path, format!("cannot read: {e}")))?;
    let opened = open(&bytes, path)?;
    let mut camera = None;
    for (k, v) in defines {
        match *k {
            "camera" => camera = Some(*v),
            other => {
                return Err(SceneError::whole_file(path, format!("unknown glTF option `{other}` (known: camera)")))
            }
        }
    }
    let name = path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    scene::convert(&opened, &name, camera).map_err(|e| SceneError::whole_file(path, e))
}

/// Builds a converted glTF scene (mesh parts are read from the glTF file next to `path`).
pub fn build_model(file: &SceneFile, path: &Path) -> Result<LoadedScene, SceneError> {
    build(file, &Located(path.to_path_buf()))
}

/// Loads and builds a glTF file; returns the scene and the warnings.
pub fn load_gltf(path: &Path, defines: &[(&str, &str)]) -> Result<(LoadedScene, Vec<String>), SceneError> {
    let (file, warnings) = convert_file(path, defines)?;
    Ok((build_model(&file, path)?, warnings))
}

/// The mesh parts of a glTF file (one per primitive, numbered through all meshes), for
/// [`crate::mesh::parse_mesh`].
pub(crate) fn mesh_parts(bytes: &[u8], path: &Path) -> Result<Vec<(String, TriangleMesh)>, String> {
    let opened = open(bytes, path).map_err(|e| e.message)?;
    geometry::parts(&opened)
}

/// Build errors of a glTF scene name the native item (the object, the light).
struct Located(PathBuf);

impl Locate for Located {
    fn path(&self) -> &Path {
        &self.0
    }

    fn error_at(&self, item: &ItemPath, message: impl Into<String>) -> SceneError {
        SceneError::whole_file(&self.0, format!("{item}: {}", message.into()))
    }
}
