//! Turning the SCENE argument into a scene: a path ending in .toml or .json is a scene file, one
//! ending in .xml a Mitsuba 3 scene, .gltf or .glb a glTF 2.0 scene, anything else a built-in
//! scene name.

use crate::CliError;
use pathtrace_scene::load::{self, is_xml};
use pathtrace_scene::native::{self, Format};
use pathtrace_scene::{builtin, LoadedScene};
use pathtrace_scene::{gltf, mitsuba};
use std::path::Path;

/// True if the argument names a scene file rather than a built-in scene.
pub fn is_file(arg: &str) -> bool {
    load::is_scene_file(Path::new(arg))
}

/// Prints each import warning to stderr as `warning: ...`.
pub fn print_warnings(warnings: &[String]) {
    for w in warnings {
        eprintln!("warning: {}", pathtrace_scene::elide::elide_long_runs(w));
    }
}

/// The defines as the importer takes them.
fn pairs(defines: &[(String, String)]) -> Vec<(&str, &str)> {
    defines.iter().map(|(n, v)| (n.as_str(), v.as_str())).collect()
}

/// Reads any scene file into the native model (Mitsuba XML is converted, printing warnings).
pub fn read_model(path: &Path, defines: &[(String, String)]) -> Result<native::SceneFile, CliError> {
    if is_xml(path) {
        let (file, warnings) =
            mitsuba::convert_file(path, &pairs(defines)).map_err(|e| CliError::usage(e.to_string()))?;
        print_warnings(&warnings);
        return Ok(file);
    }
    if gltf::is_gltf(path) {
        let (file, warnings) = gltf::convert_file(path, &pairs(defines)).map_err(|e| CliError::usage(e.to_string()))?;
        print_warnings(&warnings);
        return Ok(file);
    }
    if !defines.is_empty() {
        return Err(CliError::usage("-D/--define applies only to Mitsuba .xml and glTF scenes"));
    }
    native::read_file(path).map(|(_, f)| f).map_err(|e| CliError::usage(e.to_string()))
}

/// Loads a scene file or a built-in scene; errors are one line (with file:line:col for files)
/// and exit code 2.
pub fn load(arg: &str) -> Result<LoadedScene, CliError> {
    load_with(arg, &[])
}

/// [`load`] with Mitsuba parameter overrides (`-D NAME=VALUE`); import warnings go to stderr.
pub fn load_with(arg: &str, defines: &[(String, String)]) -> Result<LoadedScene, CliError> {
    if is_file(arg) || !defines.is_empty() {
        let mut warn = |w: &str| print_warnings(&[w.to_string()]);
        return load::load_file(Path::new(arg), &pairs(defines), &mut warn).map_err(|e| CliError::usage(e.to_string()));
    }
    match builtin::load(arg) {
        Some(Ok(loaded)) => Ok(loaded),
        Some(Err(e)) => Err(CliError::usage(format!("built-in scene '{arg}' failed to build: {e}"))),
        None => Err(CliError::usage(format!(
            "unknown scene '{arg}': give a .toml, .json, .xml, .gltf or .glb scene file, or a built-in scene ({})",
            builtin::NAMES.join(", ")
        ))),
    }
}

/// True if the argument names a scene file rather than a built-in scene.
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub fn is_scene_file(arg: &str) -> bool {
    is_file(arg)
}

/// The scene as a native model (for writing it back, e.g. with another camera), or `None` when
/// it cannot be read as one; import warnings were already printed by [`load_with`].
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub fn model(arg: &str, defines: &[(String, String)]) -> Option<native::SceneFile> {
    if is_file(arg) {
        if is_xml(Path::new(arg)) {
            return mitsuba::convert_file(Path::new(arg), &pairs(defines)).ok().map(|(f, _)| f);
        }
        if gltf::is_gltf(Path::new(arg)) {
            return gltf::convert_file(Path::new(arg), &pairs(defines)).ok().map(|(f, _)| f);
        }
        return native::read_file(Path::new(arg)).ok().map(|(_, f)| f);
    }
    let (file, text) = builtin::source(arg)?;
    native::parse_str(text, Format::Toml, Path::new(file)).ok()
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
