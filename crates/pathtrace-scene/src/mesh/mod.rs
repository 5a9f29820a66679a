//! Triangle meshes from files (OBJ and PLY).
//!
//! Placeholder: the real loaders are written on another branch and replace this module when it
//! is merged. Until then every call fails with a clear message.

use pathtrace::shape::TriangleMesh;
use std::fmt;
use std::path::Path;

/// Why a mesh file cannot be loaded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MeshLoadError {
    /// Mesh loading is not built into this version.
    Unavailable,
}

impl MeshLoadError {
    /// What is wrong, as one line.
    pub fn message(&self) -> String {
        match self {
            MeshLoadError::Unavailable => "mesh loading not available yet".to_string(),
        }
    }
}

impl fmt::Display for MeshLoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message())
    }
}

impl std::error::Error for MeshLoadError {}

/// Loads the meshes of an OBJ or PLY file, each with its group or material name.
pub fn load_mesh(_path: &Path) -> Result<Vec<(String, TriangleMesh)>, MeshLoadError> {
    Err(MeshLoadError::Unavailable)
}
