//! The user's commands and what each does to the view state. Input events become [`Action`]s in
//! the window code; applying them here is pure, so the mapping to restarts is unit-tested.

use crate::accumulation::RenderKey;
use crate::camera_control;
use crate::lens_control;
use crate::view_mode::ViewMode;
use pathtrace::film::{ToneMap, ToneMapSettings};
use pathtrace::integrator::Strategy;
use pathtrace::sampling::SamplerKind;
use pathtrace::CameraDesc;

/// Everything the user can change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewState {
    pub key: RenderKey,
    pub tone: ToneMapSettings,
    pub view: ViewMode,
    /// Picture magnification: physical pixels per image pixel.
    pub zoom: f32,
    /// Picture offset from centred, in physical pixels.
    pub offset: (f32, f32),
}

/// One user command.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// Orbit by (yaw, pitch) radians.
    Orbit(f32, f32),
    /// Pan the camera by a drag of (dx, dy) image pixels.
    Pan(f32, f32),
    /// Change the field of view by zoom steps (positive narrows).
    Fov(f32),
    /// Fly (right, up, forward) by a fraction of the look-at distance.
    Fly(f32, f32, f32),
    /// Back to the scene's camera.
    ResetCamera(CameraDesc),
    /// Scale the aperture radius (> 1 opens; a pinhole opens to a thin lens).
    Aperture(f32),
    /// Scale the focus distance (thin lens).
    Focus(f32),
    /// Focus at this distance along the view direction (the depth under the cursor).
    FocusAt(f32),
    NextStrategy,
    NextSampler,
    /// Change the maximum depth by ±1 (−1 = unlimited sits below 1).
    Depth(i32),
    /// Change exposure by this many stops.
    Exposure(f32),
    ToggleToneMap,
    NextView {
        has_reference: bool,
    },
    /// Magnify the picture by this factor (nearest-pixel), about its centre.
    PictureZoom(f32),
    /// Move the picture by (dx, dy) physical pixels.
    PicturePan(f32, f32),
    /// One image pixel per screen pixel, centred.
    PictureReset,
}

const STRATEGIES: [Strategy; 5] =
    [Strategy::Mis, Strategy::MisBalance, Strategy::Bsdf, Strategy::Mixture, Strategy::Light];
const SAMPLERS: [SamplerKind; 3] = [SamplerKind::Independent, SamplerKind::Stratified, SamplerKind::Sobol];
/// Largest and smallest picture magnification.
pub const PICTURE_ZOOM_LIMITS: (f32, f32) = (0.125, 64.0);

fn next_in<T: PartialEq + Copy>(list: &[T], current: T) -> T {
    let i = list.iter().position(|&x| x == current).map_or(0, |i| i + 1);
    list[i % list.len()]
}

/// The depth after a ±1 step: ... 2, 1, unlimited (−1) at the bottom wrapping to and from 1.
fn step_depth(depth: i32, delta: i32) -> i32 {
    match (depth, delta.signum()) {
        (-1, 1) => 1,
        (-1, _) => -1,
        (1, -1) => -1,
        (d, s) => (d + s).max(1),
    }
}

impl ViewState {
    /// The state after `action`; `height` is the image height in pixels (for panning).
    pub fn apply(&self, action: Action, height: u32) -> ViewState {
        let mut s = *self;
        let cam = &self.key.camera;
        match action {
            Action::Orbit(yaw, pitch) => s.key.camera = camera_control::orbit(cam, yaw, pitch),
            Action::Pan(dx, dy) => s.key.camera = camera_control::pan(cam, dx, dy, height),
            Action::Fov(steps) => s.key.camera = camera_control::zoom(cam, steps),
            Action::Fly(r, u, f) => s.key.camera = camera_control::fly(cam, r, u, f, 1.0),
            Action::ResetCamera(c) => s.key.camera = c,
            Action::Aperture(f) => s.key.camera = lens_control::aperture(cam, f),
            Action::Focus(f) => s.key.camera = lens_control::focus(cam, f),
            Action::FocusAt(d) => s.key.camera = lens_control::focus_at(cam, d),
            Action::NextStrategy => s.key.strategy = next_in(&STRATEGIES, self.key.strategy),
            Action::NextSampler => s.key.sampler = next_in(&SAMPLERS, self.key.sampler),
            Action::Depth(d) => s.key.max_depth = step_depth(self.key.max_depth, d),
            Action::Exposure(stops) => s.tone.exposure = (self.tone.exposure + stops).clamp(-20.0, 20.0),
            Action::ToggleToneMap => {
                s.tone.tone_map = if self.tone.tone_map == ToneMap::Clamp { ToneMap::Aces } else { ToneMap::Clamp }
            }
            Action::NextView { has_reference } => s.view = self.view.next(has_reference),
            Action::PictureZoom(f) => {
                let z = (self.zoom * f).clamp(PICTURE_ZOOM_LIMITS.0, PICTURE_ZOOM_LIMITS.1);
                let k = z / self.zoom;
                s.zoom = z;
                s.offset = (self.offset.0 * k, self.offset.1 * k);
            }
            Action::PicturePan(dx, dy) => s.offset = (self.offset.0 + dx, self.offset.1 + dy),
            Action::PictureReset => {
                s.zoom = 1.0;
                s.offset = (0.0, 0.0);
            }
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pathtrace::math::Vec3;
    use pathtrace::RenderSettings;

    fn state() -> ViewState {
        let camera = CameraDesc { look_from: Vec3::new(0.0, 0.0, 5.0), look_at: Vec3::ZERO, ..Default::default() };
        ViewState {
            key: RenderKey::new(camera, &RenderSettings::default()),
            tone: ToneMapSettings::default(),
            view: ViewMode::Render,
            zoom: 1.0,
            offset: (0.0, 0.0),
        }
    }

    #[test]
    fn estimate_changing_actions_change_the_render_key() {
        let s = state();
        for a in [
            Action::Orbit(0.1, 0.0),
            Action::Pan(3.0, 0.0),
            Action::Fov(1.0),
            Action::Fly(0.0, 0.0, 0.1),
            Action::NextStrategy,
            Action::NextSampler,
            Action::Depth(1),
        ] {
            assert_ne!(s.apply(a, 256).key, s.key, "{a:?} must restart accumulation");
        }
    }

    #[test]
    fn display_only_actions_keep_the_render_key() {
        let s = state();
        for a in [
            Action::Exposure(1.0),
            Action::ToggleToneMap,
            Action::NextView { has_reference: true },
            Action::PictureZoom(2.0),
            Action::PicturePan(5.0, 5.0),
            Action::PictureReset,
            Action::ResetCamera(s.key.camera),
        ] {
            let t = s.apply(a, 256);
            assert_eq!(t.key, s.key, "{a:?} must not restart accumulation");
        }
        assert_eq!(s.apply(Action::Exposure(1.5), 256).tone.exposure, 1.5);
        assert_eq!(s.apply(Action::ToggleToneMap, 256).tone.tone_map, ToneMap::Aces);
    }

    #[test]
    fn depth_steps_wrap_through_unlimited() {
        assert_eq!(step_depth(-1, 1), 1);
        assert_eq!(step_depth(1, -1), -1);
        assert_eq!(step_depth(-1, -1), -1);
        assert_eq!(step_depth(5, 1), 6);
        assert_eq!(step_depth(5, -1), 4);
    }

    #[test]
    fn cycling_strategy_and_sampler_visits_each_once() {
        let mut s = state();
        let mut strategies = vec![];
        let mut samplers = vec![];
        for _ in 0..STRATEGIES.len() {
            s = s.apply(Action::NextStrategy, 256);
            strategies.push(s.key.strategy);
        }
        for _ in 0..3 {
            s = s.apply(Action::NextSampler, 256);
            samplers.push(s.key.sampler);
        }
        strategies.sort_by_key(|x| x.to_string());
        strategies.dedup();
        samplers.sort_by_key(|x| x.to_string());
        samplers.dedup();
        assert_eq!((strategies.len(), samplers.len()), (5, 3));
    }

    #[test]
    fn picture_zoom_is_limited_and_scales_the_offset() {
        let s = ViewState { offset: (10.0, -4.0), ..state() };
        let z = s.apply(Action::PictureZoom(2.0), 256);
        assert_eq!((z.zoom, z.offset), (2.0, (20.0, -8.0)));
        assert_eq!(s.apply(Action::PictureZoom(1e9), 256).zoom, PICTURE_ZOOM_LIMITS.1);
        assert_eq!(s.apply(Action::PictureZoom(1e-9), 256).zoom, PICTURE_ZOOM_LIMITS.0);
    }
}
