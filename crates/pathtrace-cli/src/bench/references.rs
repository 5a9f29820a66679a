//! The stored references of the suite: benches/references/NAME.exr, rendered by the project
//! itself (`pathtrace bench --make-references`) at many samples per pixel, and a manifest
//! (references.json) saying how each was made, so the check knows the reference's own noise.

use super::scenes::{SuiteScene, REFERENCE_SEED};
use super::system::source_commit;
use crate::CliError;
use pathtrace::film::{Image, ToneMapSettings};
use pathtrace_scene::image_io::{read_linear_image, write_image};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

const MANIFEST: &str = "references.json";

/// How one reference was made.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ReferenceInfo {
    pub spp: u32,
    pub seed: u64,
    pub width: u32,
    pub height: u32,
    pub max_depth: i32,
    pub render_seconds: f64,
    pub commit: Option<String>,
}

/// The references folder of the source tree this binary was built from.
pub fn default_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../benches/references")
}

fn read_manifest(dir: &Path) -> BTreeMap<String, ReferenceInfo> {
    std::fs::read_to_string(dir.join(MANIFEST)).ok().and_then(|t| serde_json::from_str(&t).ok()).unwrap_or_default()
}

/// The reference image of a scene and its samples per pixel; `Err(note)` if there is none.
pub fn load(dir: &Path, scene: &SuiteScene) -> Result<(Image, ReferenceInfo), String> {
    let path = dir.join(format!("{}.exr", scene.name));
    let info = read_manifest(dir)
        .remove(scene.name)
        .ok_or_else(|| format!("no reference for {} in {}", scene.name, dir.join(MANIFEST).display()))?;
    let image = read_linear_image(&path).map_err(|e| format!("reference unreadable: {e}"))?;
    Ok((image, info))
}

/// Renders and writes the reference of each scene (with all threads unless told otherwise),
/// updating the manifest after each so an interrupted run keeps what it finished.
pub fn make(dir: &Path, scenes: &[&SuiteScene], spp_override: Option<u32>, threads: usize) -> Result<(), CliError> {
    std::fs::create_dir_all(dir).map_err(|e| CliError::runtime(format!("cannot create {}: {e}", dir.display())))?;
    for scene in scenes {
        let loaded = match scene.load()? {
            Ok(l) => l,
            Err(note) => {
                eprintln!("{}: {note}", scene.name);
                continue;
            }
        };
        let spp = spp_override.unwrap_or(scene.reference_spp);
        let settings = scene.settings(&loaded, spp, REFERENCE_SEED, threads);
        eprintln!("{}: rendering the reference, {}×{}, {spp} spp …", scene.name, settings.width, settings.height);
        let outcome = pathtrace::render(Arc::new(loaded.scene), settings.clone())
            .map_err(|e| CliError::runtime(e.to_string()))?;
        let path = dir.join(format!("{}.exr", scene.name));
        write_image(&path, &outcome.film.image(), &ToneMapSettings::default())
            .map_err(|e| CliError::runtime(e.to_string()))?;
        let seconds = outcome.progress.elapsed.as_secs_f64();
        eprintln!("{}: {:.1} s, wrote {}", scene.name, seconds, path.display());
        let mut manifest = read_manifest(dir);
        manifest.insert(
            scene.name.to_string(),
            ReferenceInfo {
                spp,
                seed: REFERENCE_SEED,
                width: settings.width,
                height: settings.height,
                max_depth: settings.path.max_depth,
                render_seconds: seconds,
                commit: source_commit(),
            },
        );
        let text = serde_json::to_string_pretty(&manifest).map_err(|e| CliError::runtime(e.to_string()))?;
        std::fs::write(dir.join(MANIFEST), text + "\n")
            .map_err(|e| CliError::runtime(format!("cannot write the manifest: {e}")))?;
    }
    Ok(())
}
