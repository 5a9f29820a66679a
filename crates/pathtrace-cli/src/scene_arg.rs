//! Turning the SCENE argument into a scene: a path ending in .toml or .json is a scene file,
//! anything else a built-in scene name.

use crate::CliError;
use pathtrace_scene::native::{self, Format};
use pathtrace_scene::{builtin, LoadedScene};
use std::path::Path;

/// True if the argument names a scene file rather than a built-in scene.
fn is_file(arg: &str) -> bool {
    Format::from_path(Path::new(arg)).is_some()
}

/// Loads a scene file or a built-in scene; errors are one line (with file:line:col for files)
/// and exit code 2.
pub fn load(arg: &str) -> Result<LoadedScene, CliError> {
    if is_file(arg) {
        return native::load_file(Path::new(arg)).map_err(|e| CliError::usage(e.to_string()));
    }
    match builtin::load(arg) {
        Some(Ok(loaded)) => Ok(loaded),
        Some(Err(e)) => Err(CliError::usage(format!("built-in scene '{arg}' failed to build: {e}"))),
        None => Err(CliError::usage(format!(
            "unknown scene '{arg}': give a .toml or .json scene file, or a built-in scene ({})",
            builtin::NAMES.join(", ")
        ))),
    }
}

/// The name for default outputs: a file's stem, or the built-in scene's name.
pub fn stem(arg: &str) -> String {
    if is_file(arg) {
        if let Some(s) = Path::new(arg).file_stem().and_then(|s| s.to_str()) {
            return s.to_string();
        }
    }
    arg.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_are_named_after_the_file_stem() {
        assert_eq!(stem("scenes/cornell-box.toml"), "cornell-box");
        assert_eq!(stem("a/b.JSON"), "b");
        assert_eq!(stem("cornell-box"), "cornell-box");
    }
}
