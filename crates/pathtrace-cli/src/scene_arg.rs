//! Turning the SCENE argument into a scene.

use crate::CliError;
use pathtrace_scene::{builtin, LoadedScene};

/// Loads a built-in scene by name.
pub fn load(name: &str) -> Result<LoadedScene, CliError> {
    match builtin::load(name) {
        Some(Ok(loaded)) => Ok(loaded),
        Some(Err(e)) => Err(CliError::usage(format!("built-in scene '{name}' failed to build: {e}"))),
        None => Err(CliError::usage(format!(
            "unknown scene '{name}': built-in scenes are {} (scene files are not supported yet)",
            builtin::NAMES.join(", ")
        ))),
    }
}
