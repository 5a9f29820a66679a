//! `pathtrace view`: a live OpenGL window on a render in progress.
//!
//! A thin consumer of the engine's [`pathtrace::RenderSession`]: the session's worker threads
//! render, the window thread uploads each new snapshot as a float texture and tone maps it in a
//! fragment shader (the same exposure, curve and sRGB transfer as `pathtrace render`'s PNGs).
//! Camera moves and setting changes restart accumulation at once. See docs/viewer.md.

pub mod accumulation;
mod app;
pub mod camera_control;
mod config;
pub mod controls;
mod gl_picture;
pub mod lens_control;
pub mod overlay;
pub mod view_mode;

pub use config::ViewerConfig;

use eframe::egui;

/// Why the viewer could not run.
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    /// No window could be opened (no display, or no OpenGL 3.3 context).
    #[error("cannot open a window ({0}); render without one with `pathtrace render`")]
    NoDisplay(String),
    /// The render could not start.
    #[error("{0}")]
    Render(String),
}

/// True if a display server is named in the environment (X11 or Wayland).
pub fn display_available() -> bool {
    let set = |v: &str| std::env::var_os(v).is_some_and(|s| !s.is_empty());
    set("DISPLAY") || set("WAYLAND_DISPLAY")
}

/// Opens the window and runs until it is closed (or the render is done, with
/// `exit_when_done`).
pub fn run(config: ViewerConfig) -> Result<(), ViewerError> {
    if !display_available() {
        return Err(ViewerError::NoDisplay("no display: neither DISPLAY nor WAYLAND_DISPLAY is set".into()));
    }
    let (w, h) = (config.settings.width as f32, config.settings.height as f32);
    // Room for the picture at one pixel per screen pixel (when the scale factor is 1), plus the
    // status bar; never wider than a typical screen at first.
    let inner = egui::vec2(w.clamp(640.0, 1600.0), (h + 52.0).min(1000.0));
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title(format!("pathtrace view — {}", config.name))
            .with_inner_size(inner),
        renderer: eframe::Renderer::Glow,
        ..Default::default()
    };
    // A window system that cannot be reached may panic deep in winit; report it as one line
    // instead of a panic message (the payload becomes the error text).
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let mut failure = None;
        let slot = &mut failure;
        let outcome = eframe::run_native(
            "pathtrace view",
            options,
            Box::new(move |cc| match app::ViewerApp::new(cc, config) {
                Ok(app) => Ok(Box::new(app) as Box<dyn eframe::App>),
                Err(e) => {
                    let text = e.to_string();
                    *slot = Some(e);
                    Err(text.into())
                }
            }),
        );
        (outcome, failure)
    }));
    std::panic::set_hook(previous_hook);
    match result {
        Ok((_, Some(e))) => Err(e),
        Ok((Ok(()), None)) => Ok(()),
        Ok((Err(e), None)) => Err(ViewerError::NoDisplay(one_line(&e.to_string()))),
        Err(payload) => {
            let text = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "the window system failed".into());
            Err(ViewerError::NoDisplay(one_line(&text)))
        }
    }
}

/// Folds a multi-line message onto one line.
fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}
