//! `pathtrace convert IN OUT`: any scene file → the native format (by OUT's extension).

use crate::args::ConvertArgs;
use crate::{scene_arg, CliError};
use pathtrace_scene::native::model::{Colour, GroupDef, LightDef, ObjectDef, ShapeDef};
use pathtrace_scene::native::{self, Format};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub fn run(a: ConvertArgs) -> Result<ExitCode, CliError> {
    let format = Format::from_path(&a.output)
        .ok_or_else(|| CliError::usage(format!("'{}': the output must end in .toml or .json", a.output.display())))?;
    let mut file = scene_arg::read_model(&a.input, &a.defines)?;
    // Mesh, texture and environment-map paths are relative to the scene's folder: keep them
    // working from the output's.
    if let (Some(from), Some(to)) = (folder(&a.input), folder(&a.output)) {
        if from != to {
            rebase(&mut file.objects, &mut file.groups, &from);
            for m in file.materials.values_mut() {
                for c in m.textures_mut() {
                    if let Some(filename) = match c {
                        Colour::Texture(t) => t.filename_mut(),
                        Colour::Constant(_) => None,
                    } {
                        rebase_path(filename, &from);
                    }
                }
            }
            for l in &mut file.lights {
                if let LightDef::Envmap { filename, .. } = l {
                    rebase_path(filename, &from);
                }
            }
        }
    }
    let text = native::to_string(&file, format).map_err(|e| CliError::runtime(format!("cannot serialise: {e}")))?;
    std::fs::write(&a.output, text)
        .map_err(|e| CliError::runtime(format!("cannot write '{}': {e}", a.output.display())))?;
    Ok(ExitCode::SUCCESS)
}

/// The canonical folder of a file path.
fn folder(p: &Path) -> Option<PathBuf> {
    let d = p.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    d.canonicalize().ok()
}

/// Makes a relative path absolute against `dir`.
fn rebase_path(file: &mut String, dir: &Path) {
    if Path::new(file.as_str()).is_relative() {
        *file = dir.join(file.as_str()).to_string_lossy().into_owned();
    }
}

/// Makes relative mesh paths absolute against `dir`.
fn rebase(objects: &mut [ObjectDef], groups: &mut [GroupDef], dir: &Path) {
    for o in objects {
        if let ShapeDef::Mesh { file, .. } = &mut o.shape {
            rebase_path(file, dir);
        }
    }
    for g in groups {
        rebase(&mut g.objects, &mut g.groups, dir);
    }
}
