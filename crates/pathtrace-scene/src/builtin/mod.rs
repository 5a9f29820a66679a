//! Scenes bundled with the binary, so `pathtrace render cornell-box` works anywhere.

mod cornell_box;

use crate::LoadedScene;
use pathtrace::scene::BuildError;

/// Names of the built-in scenes.
pub const NAMES: [&str; 1] = ["cornell-box"];

/// Builds a bundled scene by name; `None` if there is no such scene.
pub fn load(name: &str) -> Option<Result<LoadedScene, BuildError>> {
    match name {
        "cornell-box" | "cornell" => Some(cornell_box::build()),
        _ => None,
    }
}
