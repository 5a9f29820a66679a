//! What `pathtrace view` hands the viewer: a built scene, settings and options. Scene loading
//! and command-line parsing stay in the CLI, shared with `pathtrace render`.

use pathtrace::film::{Image, ToneMapSettings};
use pathtrace::{CameraDesc, RenderSettings, Scene};
use pathtrace_scene::native::SceneFile;
use std::path::PathBuf;
use std::sync::Arc;

/// Everything the viewer needs to start.
pub struct ViewerConfig {
    /// Shown in the title bar and used to name saved files.
    pub name: String,
    pub scene: Arc<Scene>,
    /// The starting camera (the scene's own).
    pub camera: CameraDesc,
    /// Size, sample count (0 = until closed), seed, strategy, sampler, depth, threads.
    pub settings: RenderSettings,
    /// Starting exposure and tone curve.
    pub tone: ToneMapSettings,
    /// An image to measure the render against (same size), for PSNR, relative MSE and the
    /// difference view.
    pub reference: Option<Image>,
    /// The scene as a native model and where to write it when the camera is saved (None: the
    /// scene cannot be saved).
    pub scene_model: Option<(SceneFile, PathBuf)>,
    /// Where saved images go (without extension; `.png` and `.exr` are added).
    pub image_stem: PathBuf,
    /// Capture the picture area of the window to this PNG when the render is done.
    pub screenshot: Option<PathBuf>,
    /// Capture as soon as this many samples per pixel are on screen instead (mid-render).
    pub screenshot_at_spp: Option<u32>,
    /// Capture the whole window (status bar included) instead of the picture area.
    pub screenshot_window: bool,
    /// Close the window once the render is done (and the screenshot taken).
    pub exit_when_done: bool,
}
