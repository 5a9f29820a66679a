//! Scenes bundled with the binary, so `pathtrace render cornell-box` works anywhere. Each is a
//! native scene file from the repository's scenes/ folder, embedded at compile time.

use crate::native::{load_str, Format, SceneError};
use crate::LoadedScene;
use std::path::Path;

/// Names of the built-in scenes.
pub const NAMES: [&str; 1] = ["cornell-box"];

/// The embedded files: (name, file name shown in errors, text).
const FILES: [(&str, &str, &str); 1] =
    [("cornell-box", "cornell-box.toml", include_str!("../../../../scenes/cornell-box.toml"))];

/// The text of a built-in scene file, by name (`cornell` is accepted for `cornell-box`).
pub fn source(name: &str) -> Option<(&'static str, &'static str)> {
    let name = if name == "cornell" { "cornell-box" } else { name };
    FILES.iter().find(|f| f.0 == name).map(|f| (f.1, f.2))
}

/// Builds a bundled scene by name; `None` if there is no such scene.
pub fn load(name: &str) -> Option<Result<LoadedScene, SceneError>> {
    let (file, text) = source(name)?;
    Some(load_str(text, Format::Toml, Path::new(file)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_built_in_scene_builds() {
        for name in NAMES {
            let loaded = load(name).unwrap().unwrap();
            assert!(loaded.scene.primitive_count() > 0, "{name}");
        }
        assert!(load("no-such-scene").is_none());
    }
}
