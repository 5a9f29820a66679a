//! Triangle meshes from files: Wavefront OBJ, Stanford PLY and Mitsuba `.serialized`.
//!
//! [`load_mesh`] reads a file and picks the parser by extension; [`parse_mesh`] does the same
//! for bytes already in memory. Both return named parts: one per OBJ material (`usemtl`), or one
//! for a PLY file, named after the file stem. Every error names the file and the line (text) or
//! byte offset (binary PLY data) of the problem.

mod error;
mod normals;
mod obj;
mod ply;
mod serialized;

pub use error::MeshLoadError;
pub(crate) use normals::normalised as normalised_normals;

use pathtrace::shape::TriangleMesh;
use std::path::Path;

/// Loads an `.obj`, `.ply` or `.serialized` file (extension case-insensitive) as named mesh parts.
pub fn load_mesh(path: &Path) -> Result<Vec<(String, TriangleMesh)>, MeshLoadError> {
    let bytes = std::fs::read(path)
        .map_err(|e| MeshLoadError::File { file: path.to_path_buf(), message: format!("cannot read the file: {e}") })?;
    parse_mesh(&bytes, path)
}

/// Parses mesh file content; `path` picks the format by its extension and names the file in
/// errors (and the part, for PLY).
pub fn parse_mesh(bytes: &[u8], path: &Path) -> Result<Vec<(String, TriangleMesh)>, MeshLoadError> {
    let extension = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("obj") => obj::parse(bytes).map_err(|f| f.into_error(path)),
        Some("ply") => {
            let mesh = ply::parse(bytes).map_err(|f| f.into_error(path))?;
            let name = path.file_stem().map_or_else(|| "mesh".to_string(), |s| s.to_string_lossy().into_owned());
            Ok(vec![(name, mesh)])
        }
        Some("serialized") => serialized::parse(bytes).map_err(|f| f.into_error(path)),
        Some("gltf" | "glb") => crate::gltf::mesh_parts(bytes, path)
            .map_err(|message| MeshLoadError::File { file: path.to_path_buf(), message }),
        _ => Err(MeshLoadError::File {
            file: path.to_path_buf(),
            message: "unsupported mesh format: expected a .obj, .ply, .serialized, .gltf or .glb file".to_string(),
        }),
    }
}
