//! Mitsuba 3 XML import: the file is parsed into an element tree ([`parse`]), converted into the
//! native [`SceneFile`] ([`convert`]), and built by the native builder, so `.xml` scenes render
//! exactly like the equivalent `.toml`. What the native model cannot express is substituted and
//! named in a warning; the supported subset is listed in docs/scene-format.md.
//!
//! ```
//! use pathtrace_scene::mitsuba::load_str;
//! let xml = r#"<scene version="3.0.0">
//!     <default name="spp" value="16"/>
//!     <sensor type="perspective">
//!         <float name="fov" value="40"/>
//!         <transform name="to_world"><lookat origin="0, 0, -5" target="0, 0, 0" up="0, 1, 0"/></transform>
//!         <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
//!         <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="64"/></film>
//!     </sensor>
//!     <shape type="sphere"><emitter type="area"><rgb name="radiance" value="1, 1, 1"/></emitter></shape>
//! </scene>"#;
//! let (loaded, warnings) = load_str(xml, "example.xml".as_ref(), &[("spp", "8")]).unwrap();
//! assert_eq!(loaded.defaults.spp, 8);
//! assert!(warnings.is_empty());
//! ```

pub mod convert;
pub mod parse;

use crate::native::{build, Format, SceneError, SceneFile, Source};
use crate::LoadedScene;
use parse::XmlSource;
use std::path::Path;

/// Parses and converts Mitsuba XML text into the native model; `path` names the file in errors
/// and anchors relative mesh paths. Returns the model and the warnings about substitutions.
pub fn convert_str(text: &str, path: &Path, defines: &[(&str, &str)]) -> Result<(SceneFile, Vec<String>), SceneError> {
    let mut src = XmlSource::new(path.to_path_buf(), text.to_string());
    let mut warnings = Vec::new();
    let root = parse::parse(&mut src, defines, &mut warnings)?;
    let file = convert::convert(&src, &root, &mut warnings)?;
    Ok((file, warnings))
}

/// Reads a Mitsuba XML file into the native model, with warnings.
pub fn convert_file(path: &Path, defines: &[(&str, &str)]) -> Result<(SceneFile, Vec<String>), SceneError> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneError::whole_file(path, format!("cannot read: {e}")))?;
    convert_str(&text, path, defines)
}

/// Builds a converted scene; `path` is the XML file (mesh paths are relative to its folder).
/// Build errors have no XML element to point at; they are reported at the file.
pub fn build_model(file: &SceneFile, path: &Path) -> Result<LoadedScene, SceneError> {
    let source = Source { path: path.to_path_buf(), text: String::new(), format: Format::Toml };
    build(file, &source).map_err(|mut e| {
        if e.message.starts_with("the scene has no lights") {
            e.message = "the scene has no supported lights (area emitters on shapes, point emitters): \
                         nothing would be visible"
                .into();
        } else if e.message.starts_with("the scene has no objects") {
            e.message = "the scene has no supported shapes".into();
        }
        e
    })
}

/// Loads and builds a Mitsuba XML scene text (see [`convert_str`]).
pub fn load_str(text: &str, path: &Path, defines: &[(&str, &str)]) -> Result<(LoadedScene, Vec<String>), SceneError> {
    let (file, warnings) = convert_str(text, path, defines)?;
    Ok((build_model(&file, path)?, warnings))
}

/// Loads and builds a Mitsuba XML scene file, with `defines` overriding its `<default>`
/// parameters. Returns the scene and the warnings about substitutions.
pub fn load_mitsuba(path: &Path, defines: &[(&str, &str)]) -> Result<(LoadedScene, Vec<String>), SceneError> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneError::whole_file(path, format!("cannot read: {e}")))?;
    load_str(&text, path, defines)
}
