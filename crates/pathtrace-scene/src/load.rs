//! Loading a scene file of any format the renderer reads, chosen by its extension: native
//! `.toml`/`.json`, Mitsuba 3 `.xml` (whose `<default>` parameters `defines` override), or glTF
//! 2.0 `.gltf`/`.glb` (`defines` may name the camera: `camera=NAME`). The
//! CLI and the Python module both load files through here, so they accept the same files and
//! report the same errors.

use crate::native::{self, Format, SceneError};
use crate::{gltf, mitsuba, LoadedScene};
use std::path::Path;

/// True for a `.xml` path (any case).
pub fn is_xml(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("xml"))
}

/// True if the path names a scene file the renderer reads (by its extension).
pub fn is_scene_file(path: &Path) -> bool {
    Format::from_path(path).is_some() || is_xml(path) || gltf::is_gltf(path)
}

/// Loads and builds a scene file. Import warnings (Mitsuba features substituted or ignored) go
/// to `warn` as soon as the file is converted, so they are seen even when the build then fails.
/// `defines` apply only to Mitsuba scenes; giving any for a native file is an error.
pub fn load_file(path: &Path, defines: &[(&str, &str)], warn: &mut dyn FnMut(&str)) -> Result<LoadedScene, SceneError> {
    if is_xml(path) {
        return mitsuba::load_mitsuba_reporting(path, defines, warn);
    }
    if gltf::is_gltf(path) {
        let (file, warnings) = gltf::convert_file(path, defines)?;
        warnings.iter().for_each(|w| warn(w));
        return gltf::build_model(&file, path);
    }
    if !defines.is_empty() {
        return Err(SceneError::whole_file(path, "defines (-D NAME=VALUE) apply only to Mitsuba .xml and glTF scenes"));
    }
    if Format::from_path(path).is_none() {
        return Err(SceneError::whole_file(path, "a scene file must end in .toml, .json, .xml, .gltf or .glb"));
    }
    native::load_file(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defines_for_a_native_file_are_an_error_naming_the_file() {
        let e = load_file(Path::new("scene.toml"), &[("spp", "4")], &mut |_| {}).unwrap_err();
        assert_eq!((e.path.as_path(), e.line, e.column), (Path::new("scene.toml"), 1, 1));
        assert!(e.message.contains("only to Mitsuba"), "{e}");
    }

    #[test]
    fn an_unknown_extension_is_an_error() {
        let e = load_file(Path::new("mesh.obj"), &[], &mut |_| {}).unwrap_err();
        assert!(e.message.contains(".toml, .json, .xml, .gltf or .glb"), "{e}");
        assert!(is_scene_file(Path::new("a/B.XML")) && is_scene_file(Path::new("b.json")));
        assert!(!is_scene_file(Path::new("cornell-box")));
    }
}
