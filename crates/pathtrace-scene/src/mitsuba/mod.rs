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

mod cie_tables;
pub mod spectrum;
mod upgrade;

use crate::native::{build, ItemPath, Locate, SceneError, SceneFile};
use crate::LoadedScene;
use convert::Origins;
use parse::XmlSource;
use std::path::Path;

/// Parses and converts Mitsuba XML text into the native model; `path` names the file in errors
/// and anchors relative mesh paths. Returns the model and the warnings about substitutions.
pub fn convert_str(text: &str, path: &Path, defines: &[(&str, &str)]) -> Result<(SceneFile, Vec<String>), SceneError> {
    convert_located(text, path, defines).map(|(file, _, warnings)| (file, warnings))
}

/// A converted scene with what its build errors need: the XML text and where each item of the
/// model came from.
fn convert_located(
    text: &str,
    path: &Path,
    defines: &[(&str, &str)],
) -> Result<(SceneFile, XmlLocator, Vec<String>), SceneError> {
    let mut src = XmlSource::new(path.to_path_buf(), text.to_string());
    let mut warnings = Vec::new();
    let root = parse::parse(&mut src, defines, &mut warnings)?;
    let (file, origins) = convert::convert_located(&src, &root, &mut warnings)?;
    Ok((file, XmlLocator { src, origins }, warnings))
}

/// Reads a Mitsuba XML file into the native model, with warnings.
pub fn convert_file(path: &Path, defines: &[(&str, &str)]) -> Result<(SceneFile, Vec<String>), SceneError> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneError::whole_file(path, format!("cannot read: {e}")))?;
    convert_str(&text, path, defines)
}

/// Locates build errors of a converted scene at the XML element the item came from (the most
/// specific one recorded: an object's `filename` property, else its `<shape>`, else `<scene>`).
struct XmlLocator {
    src: XmlSource,
    origins: Origins,
}

impl Locate for XmlLocator {
    fn path(&self) -> &Path {
        &self.src.path
    }

    fn error_at(&self, item: &ItemPath, message: impl Into<String>) -> SceneError {
        // Longest recorded prefix of the item; the last recorded wins among equals.
        let best = self.origins.iter().filter(|(p, _)| item.starts_with(p)).fold(
            None,
            |best: Option<&(ItemPath, usize)>, o| match best {
                Some(b) if b.0 .0.len() > o.0 .0.len() => Some(b),
                _ => Some(o),
            },
        );
        self.src.error(best.map_or(0, |b| b.1), message)
    }
}

/// Builds a converted scene; `path` is the XML file (mesh paths are relative to its folder).
/// Without the XML text, build errors are reported at the file (use [`load_str`] or
/// [`load_mitsuba`] to have them located at their element).
pub fn build_model(file: &SceneFile, path: &Path) -> Result<LoadedScene, SceneError> {
    let locator = XmlLocator { src: XmlSource::new(path.to_path_buf(), String::new()), origins: Vec::new() };
    build_located(file, &locator)
}

fn build_located(file: &SceneFile, locator: &XmlLocator) -> Result<LoadedScene, SceneError> {
    build(file, locator).map_err(|mut e| {
        if e.message.starts_with("the scene has no lights") {
            e.message = "the scene has no supported lights (area emitters on shapes, point, spot, constant or envmap emitters): \
                         nothing would be visible"
                .into();
        } else if e.message.starts_with("the scene has no objects") {
            e.message = "the scene has no supported shapes".into();
        }
        e
    })
}

/// Loads and builds a Mitsuba XML scene text (see [`convert_str`]); build errors (a missing or
/// broken mesh, degenerate geometry, a bad value) point at the XML element they come from.
pub fn load_str(text: &str, path: &Path, defines: &[(&str, &str)]) -> Result<(LoadedScene, Vec<String>), SceneError> {
    let (file, locator, warnings) = convert_located(text, path, defines)?;
    Ok((build_located(&file, &locator)?, warnings))
}

/// [`load_mitsuba`] handing each warning to `warn` before the build, so a scene whose build
/// fails still shows what its import substituted.
pub fn load_mitsuba_reporting(
    path: &Path,
    defines: &[(&str, &str)],
    warn: &mut dyn FnMut(&str),
) -> Result<LoadedScene, SceneError> {
    let text = std::fs::read_to_string(path).map_err(|e| SceneError::whole_file(path, format!("cannot read: {e}")))?;
    let (file, locator, warnings) = convert_located(&text, path, defines)?;
    warnings.iter().for_each(|w| warn(w));
    build_located(&file, &locator)
}

/// Loads and builds a Mitsuba XML scene file, with `defines` overriding its `<default>`
/// parameters. Returns the scene and the warnings about substitutions.
pub fn load_mitsuba(path: &Path, defines: &[(&str, &str)]) -> Result<(LoadedScene, Vec<String>), SceneError> {
    let mut warnings = Vec::new();
    let loaded = load_mitsuba_reporting(path, defines, &mut |w| warnings.push(w.to_string()))?;
    Ok((loaded, warnings))
}
