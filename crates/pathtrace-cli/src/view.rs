//! `pathtrace view`: loads the scene exactly as `pathtrace render` does (same overrides), then
//! hands it to the live viewer (crate pathtrace-viewer, the default `viewer` feature).

use crate::args::ViewArgs;
use crate::CliError;
use std::process::ExitCode;

#[cfg(feature = "viewer")]
pub fn run(a: ViewArgs) -> Result<ExitCode, CliError> {
    use crate::render::settings_from;
    use crate::scene_arg;
    use pathtrace_scene::image_io::read_image;
    use pathtrace_viewer::{ViewerConfig, ViewerError};
    use std::path::{Path, PathBuf};
    use std::sync::Arc;

    let tone = crate::args::tone_settings(a.exposure, a.tonemap)?;
    // Fail before loading a large scene when there is nowhere to show it.
    if !pathtrace_viewer::display_available() {
        return Err(CliError::usage(ViewerError::NoDisplay("no display".into()).to_string()));
    }
    let mut loaded = scene_arg::load_with(&a.scene, &a.defines)?;
    if let Some(mode) = a.quality.light_selection {
        loaded.scene.lights.set_selection(mode);
    }
    let mut settings = settings_from(&a.quality, a.spp, None, &loaded.defaults);
    if settings.spp == 0 {
        // --spp 0: render until the window closes, as an open-ended (time-limited) session whose
        // limit, about 136 years, no window outlives.
        settings.time_limit = Some(std::time::Duration::from_secs(u64::from(u32::MAX)));
    }
    let reference = match &a.reference {
        Some(path) => {
            let img = read_image(path).map_err(|e| CliError::usage(e.to_string()))?;
            if (img.width, img.height) != (settings.width, settings.height) {
                return Err(CliError::usage(format!(
                    "reference {} is {}×{}, the render {}×{}: give --size to match",
                    path.display(),
                    img.width,
                    img.height,
                    settings.width,
                    settings.height
                )));
            }
            Some(img)
        }
        None => None,
    };
    let stem = scene_arg::stem(&a.scene);
    // Saved cameras go next to the scene file, so its relative mesh paths keep working.
    let folder = if scene_arg::is_scene_file(&a.scene) {
        Path::new(&a.scene).parent().map(Path::to_path_buf).unwrap_or_default()
    } else {
        PathBuf::new()
    };
    let scene_model = scene_arg::model(&a.scene, &a.defines).map(|m| (m, folder.join(format!("{stem}-view.toml"))));
    let config = ViewerConfig {
        name: stem.clone(),
        camera: loaded.scene.camera,
        scene: Arc::new(loaded.scene),
        settings,
        tone,
        reference,
        scene_model,
        image_stem: PathBuf::from(&stem),
        screenshot: a.screenshot,
        screenshot_at_spp: a.screenshot_at_spp,
        screenshot_window: a.screenshot_window,
        exit_when_done: a.exit_when_done,
    };
    match pathtrace_viewer::run(config) {
        Ok(()) => Ok(ExitCode::SUCCESS),
        Err(e @ ViewerError::NoDisplay(_)) => Err(CliError::usage(e.to_string())),
        Err(e) => Err(CliError::runtime(e.to_string())),
    }
}

#[cfg(not(feature = "viewer"))]
pub fn run(_: ViewArgs) -> Result<ExitCode, CliError> {
    Err(CliError::usage("this pathtrace was built without the viewer (cargo feature `viewer`); use `pathtrace render`"))
}
