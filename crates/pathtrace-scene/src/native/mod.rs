//! The native scene format: one serde model ([`SceneFile`]) written as TOML or JSON, built into
//! a renderable scene through the engine's `SceneBuilder`. The reference is docs/scene-format.md.
//!
//! ```
//! use pathtrace_scene::native::{load_str, Format};
//! let scene = r#"
//! [camera]
//! look_from = [0, 1, -5]
//! look_at = [0, 1, 0]
//!
//! [materials.light]
//! type = "emissive"
//! radiance = 5
//!
//! [[objects]]
//! type = "sphere"
//! center = [0, 1, 0]
//! radius = 1
//! material = "light"
//! "#;
//! let loaded = load_str(scene, Format::Toml, "example.toml".as_ref()).unwrap();
//! assert_eq!(loaded.defaults.spp, 64);
//! ```

mod build;
mod error;
mod locate;
mod material;
mod medium;
pub mod model;
mod object;
mod optics;
mod parse;
mod texture;
pub(crate) mod transform;
mod values;

pub use build::build;
pub use error::{line_column, SceneError};
pub use locate::{ItemPath, Key, Locate};
pub use model::SceneFile;
pub use parse::{parse_str, to_string, Format, Source};

use crate::LoadedScene;
use std::path::Path;

/// Reads a scene file (`.toml` or `.json`) into the model, keeping its text for error locations.
pub fn read_file(path: &Path) -> Result<(Source, SceneFile), SceneError> {
    let format = Format::from_path(path)
        .ok_or_else(|| SceneError::whole_file(path, "a scene file must end in .toml or .json"))?;
    let text = std::fs::read_to_string(path).map_err(|e| SceneError::whole_file(path, format!("cannot read: {e}")))?;
    let source = Source { path: path.to_path_buf(), text, format };
    let file = source.parse()?;
    Ok((source, file))
}

/// Loads and builds a scene file; mesh paths resolve against its folder.
pub fn load_file(path: &Path) -> Result<LoadedScene, SceneError> {
    let (source, file) = read_file(path)?;
    build(&file, &source)
}

/// Parses and builds scene text; `path` names it in errors and anchors relative mesh paths.
pub fn load_str(text: &str, format: Format, path: &Path) -> Result<LoadedScene, SceneError> {
    let source = Source { path: path.to_path_buf(), text: text.to_string(), format };
    build(&source.parse()?, &source)
}
