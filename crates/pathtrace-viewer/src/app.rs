//! The window: turns input into [`Action`]s, keeps the [`Accumulation`] in step with the view
//! state, uploads a new snapshot when there is one, and draws the picture with [`GlPicture`].
//! No rendering happens here: samples come from the session's worker threads.

use crate::accumulation::{Accumulation, RenderKey};
use crate::config::ViewerConfig;
use crate::controls::{Action, ViewState};
use crate::gl_picture::{read_rgb8, GlPicture};
use crate::lens_control;
use crate::overlay::{progress_line, SHORTCUTS};
use crate::view_mode::{view_image, ViewMode, ViewSources};
use crate::ViewerError;
use eframe::egui::{self, Key, PointerButton};
use eframe::{egui_glow, glow};
use pathtrace::film::{Film, Image};
use pathtrace::metrics;
use pathtrace::{CameraDesc, RenderSettings};
use pathtrace_scene::image_io::write_image;
use pathtrace_scene::native::model::{Num, ProjectionName};
use pathtrace_scene::native::{self, Format};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// How often a running render's picture is refreshed: often enough to watch it converge, rare
/// enough that copying the film and drawing (software GL included) leave the workers alone.
const REFRESH: Duration = Duration::from_millis(100);
/// How often the noise estimate and reference metrics are recomputed (they copy the film).
const STATS_REFRESH: Duration = Duration::from_millis(500);
/// Orbit speed for mouse drags, radians per point.
const ORBIT_PER_POINT: f32 = 0.005;
/// Orbit step of the arrow keys, radians.
const ORBIT_KEY_STEP: f32 = 0.05;
/// Fly step: a fraction of the look-at distance per key press.
const FLY_STEP: f32 = 0.05;
/// Focus-distance factor per key press (K nearer, L farther).
const FOCUS_STEP: f32 = 1.1;
/// Scroll points per field-of-view zoom step.
const SCROLL_PER_STEP: f32 = 50.0;

/// What the texture currently shows; a different stamp means upload again.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Stamp {
    generation: u64,
    samples: u64,
    spp_done: u32,
    view: ViewMode,
    key: RenderKey,
}

/// A captured RGB8 picture (width, height, rows from the top), or why capturing failed.
type Captured = Result<(u32, u32, Vec<u8>), String>;

/// The screenshot (--screenshot): requested once the final image is on screen, captured inside
/// the paint callback straight from the framebuffer, written on the next update.
#[derive(Default)]
struct Capture {
    requested: bool,
    window_requested: bool,
    pixels: Option<Captured>,
}

/// Figures for the status bar, refreshed every [`STATS_REFRESH`].
#[derive(Default)]
struct Stats {
    at: Option<Instant>,
    noise: Option<f64>,
    psnr: Option<f64>,
    rel_mse: Option<f64>,
}

pub struct ViewerApp {
    config: ViewerConfig,
    acc: Accumulation,
    state: ViewState,
    home_camera: CameraDesc,
    picture: Arc<Mutex<GlPicture>>,
    uploaded: Option<Stamp>,
    uploaded_at: Option<Instant>,
    stats: Stats,
    /// The denoised snapshot shown instead of the live render (`O` toggles), and whether it is
    /// on the GPU yet.
    denoised: Option<(Image, bool)>,
    /// Loaded on first use: Open Image Denoise is optional.
    denoiser: Option<pathtrace_denoise::Denoiser>,
    capture: Arc<Mutex<Capture>>,
    screenshot_done: bool,
    help: bool,
    status_bar: bool,
    message: Option<(String, Instant)>,
}

impl ViewerApp {
    pub fn new(cc: &eframe::CreationContext<'_>, config: ViewerConfig) -> Result<Self, ViewerError> {
        let gl = cc.gl.as_ref().ok_or_else(|| ViewerError::NoDisplay("no OpenGL context".into()))?;
        let picture = GlPicture::new(gl).map_err(ViewerError::NoDisplay)?;
        let key = RenderKey::new(config.camera, &config.settings);
        // Feature buffers ride along with the render, for the feature views (and denoising).
        let settings = RenderSettings { features: true, ..config.settings.clone() };
        let acc = Accumulation::start(Arc::clone(&config.scene), settings, key)
            .map_err(|e| ViewerError::Render(e.to_string()))?;
        let state = ViewState { key, tone: config.tone, view: ViewMode::Render, zoom: 1.0, offset: (0.0, 0.0) };
        Ok(Self {
            home_camera: config.camera,
            config,
            acc,
            state,
            picture: Arc::new(Mutex::new(picture)),
            uploaded: None,
            uploaded_at: None,
            stats: Stats::default(),
            denoised: None,
            denoiser: None,
            capture: Arc::new(Mutex::new(Capture::default())),
            screenshot_done: false,
            help: false,
            status_bar: true,
            message: None,
        })
    }

    fn say(&mut self, text: impl Into<String>) {
        self.message = Some((text.into(), Instant::now()));
    }

    /// Applies `action`, restarting accumulation when it changed the estimate.
    fn act(&mut self, action: Action) {
        let next = self.state.apply(action, self.config.settings.height);
        match self.acc.set_key(next.key) {
            Ok(_) => self.state = next,
            Err(e) => {
                self.state = ViewState { key: *self.acc.key(), ..next };
                self.say(format!("cannot use that view: {e}"));
            }
        }
    }

    fn handle_input(&mut self, ctx: &egui::Context, picture: &egui::Response) {
        let mut actions = Vec::new();
        let has_reference = self.config.reference.is_some();
        ctx.input(|i| {
            let pressed = |k: Key| i.key_pressed(k);
            for (key, action) in [
                (Key::ArrowLeft, Action::Orbit(-ORBIT_KEY_STEP, 0.0)),
                (Key::ArrowRight, Action::Orbit(ORBIT_KEY_STEP, 0.0)),
                (Key::ArrowUp, Action::Orbit(0.0, ORBIT_KEY_STEP)),
                (Key::ArrowDown, Action::Orbit(0.0, -ORBIT_KEY_STEP)),
                (Key::W, Action::Fly(0.0, 0.0, FLY_STEP)),
                (Key::S, Action::Fly(0.0, 0.0, -FLY_STEP)),
                (Key::A, Action::Fly(-FLY_STEP, 0.0, 0.0)),
                (Key::D, Action::Fly(FLY_STEP, 0.0, 0.0)),
                (Key::Q, Action::Fly(0.0, -FLY_STEP, 0.0)),
                (Key::E, Action::Fly(0.0, FLY_STEP, 0.0)),
                (Key::R, Action::ResetCamera(self.home_camera)),
                (Key::O, Action::Aperture(std::f32::consts::SQRT_2)),
                (Key::I, Action::Aperture(std::f32::consts::FRAC_1_SQRT_2)),
                (Key::K, Action::Focus(1.0 / FOCUS_STEP)),
                (Key::L, Action::Focus(FOCUS_STEP)),
                (Key::M, Action::NextStrategy),
                (Key::N, Action::NextSampler),
                (Key::OpenBracket, Action::Depth(-1)),
                (Key::CloseBracket, Action::Depth(1)),
                (Key::Minus, Action::Exposure(-0.5)),
                (Key::Equals, Action::Exposure(0.5)),
                (Key::Plus, Action::Exposure(0.5)),
                (Key::T, Action::ToggleToneMap),
                (Key::V, Action::NextView { has_reference }),
                (Key::Num1, Action::PictureReset),
            ] {
                // Ctrl+S (save) is handled below; no Ctrl shortcut moves the camera.
                if pressed(key) && !i.modifiers.command {
                    actions.push(action);
                }
            }
            let scroll = i.raw_scroll_delta.y;
            if scroll != 0.0 && picture.hovered() {
                if i.modifiers.command {
                    actions.push(Action::PictureZoom(2f32.powf(scroll / SCROLL_PER_STEP)));
                } else {
                    actions.push(Action::Fov(scroll / SCROLL_PER_STEP));
                }
            }
        });
        // Mouse drags on the picture.
        let ppp = ctx.pixels_per_point();
        let d = picture.drag_delta();
        if d != egui::Vec2::ZERO {
            if picture.dragged_by(PointerButton::Primary) {
                actions.push(Action::Orbit(-d.x * ORBIT_PER_POINT, d.y * ORBIT_PER_POINT));
            } else if picture.dragged_by(PointerButton::Secondary) {
                // Points → image pixels at the current magnification.
                let k = ppp / self.state.zoom;
                actions.push(Action::Pan(d.x * k, d.y * k));
            } else if picture.dragged_by(PointerButton::Middle) {
                actions.push(Action::PicturePan(d.x * ppp, d.y * ppp));
            }
        }
        // Double-click: focus on the surface under the cursor.
        if picture.double_clicked() {
            if let Some(pos) = picture.interact_pointer_pos() {
                let rect = self.picture_rect(picture.rect, ppp);
                let s = &self.config.settings;
                let x = (pos.x - rect.min.x) / rect.width() * s.width as f32;
                let y = (pos.y - rect.min.y) / rect.height() * s.height as f32;
                let camera = &self.state.key.camera;
                match lens_control::depth_under(&self.config.scene, camera, s.width, s.height, x, y) {
                    Some(d) => actions.push(Action::FocusAt(d)),
                    None => self.say("nothing under the cursor to focus on".to_string()),
                }
            }
        }
        for a in actions {
            self.act(a);
        }
        let (save_image, save_camera, pause, help, quit, bar, diff, denoise) = ctx.input(|i| {
            (
                i.modifiers.command && i.key_pressed(Key::S),
                !i.modifiers.command && i.key_pressed(Key::C),
                i.key_pressed(Key::Space),
                i.key_pressed(Key::F1) || i.key_pressed(Key::Questionmark),
                i.key_pressed(Key::Escape),
                i.key_pressed(Key::H),
                i.key_pressed(Key::G),
                i.key_pressed(Key::X),
            )
        });
        if denoise {
            self.toggle_denoised();
        }
        if diff && has_reference {
            self.state.view =
                if self.state.view == ViewMode::Difference { ViewMode::Render } else { ViewMode::Difference };
        }
        if save_image {
            self.save_image();
        }
        if save_camera {
            self.save_camera();
        }
        if pause {
            if let Err(e) = self.acc.toggle_pause() {
                self.say(format!("cannot resume: {e}"));
            }
        }
        if help {
            self.help = !self.help;
        }
        if bar {
            self.status_bar = !self.status_bar;
        }
        if quit {
            if self.help {
                self.help = false;
            } else {
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
    }

    /// Shows the current snapshot denoised (Open Image Denoise with the albedo and normal
    /// buffers), or goes back to the live render.
    fn toggle_denoised(&mut self) {
        if self.denoised.take().is_some() {
            self.uploaded = None;
            return;
        }
        let Some(features) = self.acc.features() else { return };
        if self.denoiser.is_none() {
            match pathtrace_denoise::Denoiser::new() {
                Ok(d) => self.denoiser = Some(d),
                Err(e) => return self.say(format!("cannot denoise: {e}")),
            }
        }
        let Some(denoiser) = &self.denoiser else { return };
        let start = Instant::now();
        match denoiser.denoise(&self.acc.image(), &features.albedo(), &features.normal()) {
            Ok(image) => {
                let spp = self.acc.progress().spp_done;
                self.denoised = Some((image, false));
                self.say(format!(
                    "denoised the {spp}-spp snapshot in {:.2} s (O: back to the live render)",
                    start.elapsed().as_secs_f64()
                ));
            }
            Err(e) => self.say(format!("cannot denoise: {e}")),
        }
    }

    fn saved_path(&self, ext: &str) -> PathBuf {
        let mut name = self.config.image_stem.clone().into_os_string();
        name.push(format!("-view.{ext}"));
        PathBuf::from(name)
    }

    fn save_image(&mut self) {
        let image = self.acc.image();
        let mut written = Vec::new();
        for ext in ["png", "exr"] {
            let path = self.saved_path(ext);
            match write_image(&path, &image, &self.state.tone) {
                Ok(()) => written.push(path.display().to_string()),
                Err(e) => return self.say(format!("cannot save {}: {e}", path.display())),
            }
        }
        self.say(format!("saved {}", written.join(" and ")));
    }

    fn save_camera(&mut self) {
        let Some((model, path)) = &self.config.scene_model else {
            return self.say("this scene cannot be saved as a native scene file");
        };
        let mut model = model.clone();
        let c = self.state.key.camera;
        // Through the f32's shortest decimal form, so the file says 315.98416, not 315.9841613769531.
        let num = |x: f32| x.to_string().parse::<f64>().ok().and_then(Num::new).unwrap_or_else(|| x.into());
        let num3 = |v: pathtrace::math::Vec3| [num(v.x), num(v.y), num(v.z)];
        model.camera.look_from = num3(c.look_from);
        model.camera.look_at = num3(c.look_at);
        model.camera.up = Some(num3(c.up));
        model.camera.vfov = Some(num(c.vfov_degrees));
        // The lens, as the viewer's aperture and focus controls left it.
        let (projection, aperture, focus, height) = match c.lens {
            pathtrace::Lens::Pinhole => (ProjectionName::Perspective, None, None, None),
            pathtrace::Lens::ThinLens { aperture_radius, focus_distance } => {
                (ProjectionName::Thinlens, Some(num(aperture_radius)), Some(num(focus_distance)), None)
            }
            pathtrace::Lens::Orthographic { height } => (ProjectionName::Orthographic, None, None, Some(num(height))),
        };
        model.camera.projection = (projection != ProjectionName::Perspective).then_some(projection);
        (model.camera.aperture_radius, model.camera.focus_distance, model.camera.height) = (aperture, focus, height);
        model.render.max_depth = Some(self.state.key.max_depth);
        let result = native::to_string(&model, Format::Toml)
            .map_err(|e| e.to_string())
            .and_then(|text| std::fs::write(path, text).map_err(|e| e.to_string()));
        match result {
            Ok(()) => self.say(format!("saved the camera in {}", path.display())),
            Err(e) => self.say(format!("cannot save {}: {e}", path.display())),
        }
    }

    /// Uploads a new picture if the render or the view changed (at most every [`REFRESH`] while
    /// samples keep coming). Returns whether the texture now shows the final image.
    fn refresh_picture(&mut self, gl: Option<&Arc<glow::Context>>) -> bool {
        let p = self.acc.progress();
        let stamp = Stamp {
            generation: self.acc.generation(),
            samples: p.samples,
            spp_done: p.spp_done,
            view: self.state.view,
            key: self.state.key,
        };
        let final_image = self.acc.is_done();
        let Some(gl) = gl else { return false };
        if let Some((image, uploaded)) = &mut self.denoised {
            if !*uploaded {
                let rgb: Vec<f32> = image.pixels.iter().flat_map(|p| [p.r, p.g, p.b]).collect();
                if let Ok(mut pic) = self.picture.lock() {
                    pic.upload(gl, image.width, image.height, &rgb);
                }
                *uploaded = true;
            }
            return final_image;
        }
        if self.uploaded == Some(stamp) {
            return final_image;
        }
        let only_more_samples = self.uploaded.is_some_and(|u| {
            Stamp { samples: u.samples, spp_done: u.spp_done, ..u }
                == Stamp { samples: stamp.samples, spp_done: stamp.spp_done, ..stamp }
        });
        let too_soon = self.uploaded_at.is_some_and(|t| t.elapsed() < REFRESH);
        if only_more_samples && too_soon && !final_image {
            return false;
        }
        let image = self.acc.image();
        let needs_film = self.state.view == ViewMode::StdError;
        let film: Option<Film> = needs_film.then(|| self.acc.film());
        let features = self.state.view.needs_aovs().then(|| self.acc.features()).flatten();
        let src = ViewSources {
            image: &image,
            film: film.as_ref(),
            features: features.as_ref(),
            reference: self.config.reference.as_ref(),
        };
        let shown = view_image(self.state.view, &src).unwrap_or_else(|| image.clone());
        let rgb: Vec<f32> = shown.pixels.iter().flat_map(|p| [p.r, p.g, p.b]).collect();
        if let Ok(mut pic) = self.picture.lock() {
            pic.upload(gl, shown.width, shown.height, &rgb);
        }
        self.uploaded = Some(stamp);
        self.uploaded_at = Some(Instant::now());
        self.update_stats(&image, final_image);
        final_image
    }

    fn update_stats(&mut self, image: &Image, force: bool) {
        if !force && self.stats.at.is_some_and(|t| t.elapsed() < STATS_REFRESH) {
            return;
        }
        self.stats.at = Some(Instant::now());
        self.stats.noise = self.acc.film().relative_error_estimate();
        if let Some(r) = &self.config.reference {
            self.stats.psnr = metrics::psnr_8bit(image, r).ok();
            self.stats.rel_mse = metrics::relative_mse(image, r).ok();
        }
    }

    /// The picture's rectangle in points: centred in `area`, moved by the picture offset, one
    /// image pixel per `zoom` physical pixels, corners on physical pixels.
    fn picture_rect(&self, area: egui::Rect, ppp: f32) -> egui::Rect {
        let s = &self.config.settings;
        let size_px = egui::vec2(s.width as f32, s.height as f32) * self.state.zoom;
        let centre_px = area.center().to_vec2() * ppp + egui::vec2(self.state.offset.0, self.state.offset.1);
        let min_px = (centre_px - size_px * 0.5).round();
        egui::Rect::from_min_size(egui::pos2(min_px.x, min_px.y) / ppp, size_px / ppp)
    }

    fn status_text(&self) -> String {
        let p = self.acc.progress();
        let mut line = progress_line(&p, self.acc.is_paused(), self.stats.noise);
        if let (Some(psnr), Some(rel)) = (self.stats.psnr, self.stats.rel_mse) {
            line.push_str(&format!(" · PSNR {psnr:.2} dB · rel. MSE {rel:.3e}"));
        }
        let k = &self.state.key;
        let depth = if k.max_depth < 0 { "∞".to_string() } else { k.max_depth.to_string() };
        let second = format!(
            "{} · {} · depth {depth} · fov {:.1}° · exposure {:+.1} · {} · view: {} · ×{} · F1 help",
            k.strategy,
            k.sampler,
            k.camera.vfov_degrees,
            self.state.tone.exposure,
            self.state.tone.tone_map,
            self.state.view.name(),
            self.state.zoom,
        );
        format!("{line}\n{second}")
    }

    /// Drives the screenshot: once the wanted image is on screen, asks for a capture (of the
    /// picture from the paint callback, or of the whole window from egui) and writes it.
    fn take_screenshot(&mut self, ctx: &egui::Context, shown_spp: Option<u32>, final_image: bool) {
        let Some(path) = self.config.screenshot.clone() else { return };
        let ready = match self.config.screenshot_at_spp {
            Some(n) => final_image || shown_spp.is_some_and(|s| s >= n),
            None => final_image,
        };
        if self.screenshot_done || !ready {
            return;
        }
        let captured = if self.config.screenshot_window {
            self.window_capture(ctx)
        } else {
            self.capture.lock().ok().and_then(|mut c| {
                if c.pixels.is_none() {
                    c.requested = true;
                }
                c.pixels.take()
            })
        };
        match captured {
            None => ctx.request_repaint(),
            Some(Ok((w, h, rgb))) => {
                self.screenshot_done = true;
                match write_png(&path, w, h, rgb) {
                    Ok(()) => eprintln!("wrote {} ({w}×{h} from the window's framebuffer)", path.display()),
                    Err(e) => eprintln!("error: cannot write {}: {e}", path.display()),
                }
            }
            Some(Err(e)) => {
                self.screenshot_done = true;
                eprintln!("error: screenshot failed: {e}");
            }
        }
    }

    /// Whole-window capture through egui: request once, then wait for the reply event.
    fn window_capture(&mut self, ctx: &egui::Context) -> Option<Captured> {
        let reply = ctx.input(|i| {
            i.raw.events.iter().find_map(|e| match e {
                egui::Event::Screenshot { image, .. } => Some(Arc::clone(image)),
                _ => None,
            })
        });
        if let Some(image) = reply {
            let [w, h] = image.size;
            let rgb = image.pixels.iter().flat_map(|c| [c.r(), c.g(), c.b()]).collect();
            return Some(Ok((w as u32, h as u32, rgb)));
        }
        let mut cap = self.capture.lock().ok()?;
        if !cap.window_requested {
            cap.window_requested = true;
            ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(egui::UserData::default()));
        }
        None
    }
}

fn write_png(path: &Path, w: u32, h: u32, rgb: Vec<u8>) -> Result<(), String> {
    let img = image::RgbImage::from_raw(w, h, rgb).ok_or("pixel buffer has the wrong size")?;
    img.save_with_format(path, image::ImageFormat::Png).map_err(|e| e.to_string())
}

impl eframe::App for ViewerApp {
    fn update(&mut self, ctx: &egui::Context, frame: &mut eframe::Frame) {
        if self.status_bar {
            egui::TopBottomPanel::bottom("status").show(ctx, |ui| {
                ui.label(egui::RichText::new(self.status_text()).monospace().small());
                if let Some((m, at)) = &self.message {
                    if at.elapsed() < Duration::from_secs(5) {
                        ui.label(egui::RichText::new(m).small());
                    }
                }
            });
        }
        let panel = egui::CentralPanel::default().frame(egui::Frame::NONE.fill(egui::Color32::from_gray(24)));
        let response = panel.show(ctx, |ui| ui.allocate_response(ui.available_size(), egui::Sense::click_and_drag()));
        let area = response.inner;
        self.handle_input(ctx, &area);
        let final_image = self.refresh_picture(frame.gl());
        let shown_spp = self.uploaded.map(|u| u.spp_done);

        let ppp = ctx.pixels_per_point();
        let rect = self.picture_rect(area.rect, ppp);
        let picture = Arc::clone(&self.picture);
        let capture = Arc::clone(&self.capture);
        let scale = if self.state.view.is_radiance() { self.state.tone.exposure_scale() } else { 1.0 };
        let curve = if self.state.view.is_radiance() { self.state.tone.tone_map } else { Default::default() };
        let (w, h) = (self.config.settings.width, self.config.settings.height);
        let callback = egui_glow::CallbackFn::new(move |info, painter| {
            let gl = painter.gl();
            if let Ok(pic) = picture.lock() {
                pic.draw(gl, scale, curve);
            }
            let Ok(mut cap) = capture.lock() else { return };
            if cap.requested {
                cap.requested = false;
                let vp = info.viewport_in_pixels();
                let clip = info.clip_rect_in_pixels();
                // The clip rectangle is the picture panel; the picture must lie wholly inside it.
                let clipped = vp.left_px < clip.left_px
                    || vp.from_bottom_px < clip.from_bottom_px
                    || vp.left_px + vp.width_px > clip.left_px + clip.width_px
                    || vp.from_bottom_px + vp.height_px > clip.from_bottom_px + clip.height_px;
                cap.pixels = Some(if (vp.width_px, vp.height_px) != (w as i32, h as i32) || clipped {
                    Err(format!(
                        "the picture is {}×{} physical pixels on screen (clipped: {}), not {w}×{h}: enlarge the \
                         window or reset the zoom",
                        vp.width_px, vp.height_px, clipped
                    ))
                } else {
                    Ok((w, h, read_rgb8(gl, vp.left_px, vp.from_bottom_px, w, h)))
                });
            }
        });
        ctx.layer_painter(egui::LayerId::background())
            .with_clip_rect(area.rect)
            .add(egui::PaintCallback { rect, callback: Arc::new(callback) });

        if self.help {
            egui::Window::new("Shortcuts").collapsible(false).resizable(false).show(ctx, |ui| {
                egui::Grid::new("keys").striped(true).show(ui, |ui| {
                    for (keys, what) in SHORTCUTS {
                        ui.monospace(keys);
                        ui.label(what);
                        ui.end_row();
                    }
                });
            });
        }

        self.take_screenshot(ctx, shown_spp, final_image);
        let screenshot_pending = self.config.screenshot.is_some() && !self.screenshot_done;
        if self.config.exit_when_done && final_image && !screenshot_pending {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }
        if !final_image || screenshot_pending {
            ctx.request_repaint_after(REFRESH);
        }
    }

    fn on_exit(&mut self, gl: Option<&glow::Context>) {
        // One summary line, like `pathtrace render`'s, for the accumulation on screen at the end.
        let p = self.acc.progress();
        eprintln!(
            "view {}: {} spp in {:.1} s, {}samples/s",
            self.config.name,
            p.spp_done,
            p.elapsed.as_secs_f64(),
            crate::overlay::si(p.samples_per_second)
        );
        if let (Some(gl), Ok(pic)) = (gl, self.picture.lock()) {
            pic.destroy(gl);
        }
    }
}
