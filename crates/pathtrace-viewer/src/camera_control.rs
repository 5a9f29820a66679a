//! Camera controller maths: orbit, pan, field-of-view zoom and fly moves on a [`CameraDesc`].
//! Pure functions (no window, no input handling), so every move is unit-tested.
//!
//! The basis follows the engine's camera: forward f = (at − from)/‖at − from‖,
//! right r = f × up (normalised), true up u = r × f.

use pathtrace::math::Vec3;
use pathtrace::CameraDesc;

/// Narrowest and widest vertical field of view the zoom allows, in degrees.
pub const FOV_LIMITS: (f32, f32) = (1.0, 150.0);

/// Closest the view direction may come to the up axis when orbiting, in radians (so the basis
/// never degenerates).
const POLE_MARGIN: f32 = 0.01;

/// The camera's orthonormal basis: (forward, right, true up), or `None` if degenerate.
pub fn basis(c: &CameraDesc) -> Option<(Vec3, Vec3, Vec3)> {
    let f = (c.look_at - c.look_from).try_normalize()?;
    let r = f.cross(c.up).try_normalize()?;
    Some((f, r, r.cross(f)))
}

/// Orbits the eye around the look-at point: `yaw` about the scene's up axis, `pitch` about the
/// camera's right axis (radians; positive pitch raises the eye). The distance to the look-at point
/// is kept, and the pitch is limited so the eye never crosses the pole.
pub fn orbit(c: &CameraDesc, yaw: f32, pitch: f32) -> CameraDesc {
    let Some(up) = c.up.try_normalize() else { return *c };
    let offset = c.look_from - c.look_at;
    let distance = offset.length();
    let Some(dir) = offset.try_normalize() else { return *c };
    // Spherical angles of the eye about the up axis: polar angle θ from `up`.
    let theta = dir.dot(up).clamp(-1.0, 1.0).acos();
    let new_theta = (theta - pitch).clamp(POLE_MARGIN, std::f32::consts::PI - POLE_MARGIN);
    let Some((_, right, _)) = basis(c) else { return *c };
    // Tilt within the plane of `up` and `dir` (about `right`; right × dir = −true up, so a
    // positive angle lowers the eye), then turn about `up` (Rodrigues).
    let tilted = rotate(dir, right, new_theta - theta);
    let turned = rotate(tilted, up, yaw);
    CameraDesc { look_from: c.look_at + turned * distance, ..*c }
}

/// Rotates `v` by `angle` radians about the unit `axis` (Rodrigues' rotation formula:
/// v cos a + (k × v) sin a + k (k·v)(1 − cos a)).
fn rotate(v: Vec3, axis: Vec3, angle: f32) -> Vec3 {
    let (s, co) = angle.sin_cos();
    v * co + axis.cross(v) * s + axis * axis.dot(v) * (1.0 - co)
}

/// Pans by a drag of (`dx`, `dy`) image pixels in an image `height` pixels tall: both the eye and
/// the look-at point move in the view plane so the point under the cursor at the look-at
/// distance follows it (one pixel there spans 2·d·tan(fov/2)/height).
pub fn pan(c: &CameraDesc, dx: f32, dy: f32, height: u32) -> CameraDesc {
    let Some((f, r, u)) = basis(c) else { return *c };
    let _ = f;
    let d = (c.look_at - c.look_from).length();
    let per_pixel = 2.0 * d * (c.vfov_degrees.to_radians() * 0.5).tan() / height.max(1) as f32;
    // Dragging right moves the scene right, so the camera moves left; likewise for up/down.
    let delta = r * (-dx * per_pixel) + u * (dy * per_pixel);
    CameraDesc { look_from: c.look_from + delta, look_at: c.look_at + delta, ..*c }
}

/// Zooms by changing the field of view: `steps` > 0 narrows it (zoom in) by 10% per step, within
/// [`FOV_LIMITS`]; the eye and look-at point do not move.
pub fn zoom(c: &CameraDesc, steps: f32) -> CameraDesc {
    let fov = (c.vfov_degrees * 0.9f32.powf(steps)).clamp(FOV_LIMITS.0, FOV_LIMITS.1);
    CameraDesc { vfov_degrees: fov, ..*c }
}

/// Flies: moves eye and look-at point together by (`right`, `up`, `forward`) in units of a
/// fraction of the look-at distance, so speed suits any scene scale.
pub fn fly(c: &CameraDesc, right: f32, up: f32, forward: f32, fraction: f32) -> CameraDesc {
    let Some((f, r, u)) = basis(c) else { return *c };
    let step = (c.look_at - c.look_from).length() * fraction;
    let delta = (r * right + u * up + f * forward) * step;
    CameraDesc { look_from: c.look_from + delta, look_at: c.look_at + delta, ..*c }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cornell() -> CameraDesc {
        CameraDesc {
            look_from: Vec3::new(278.0, 273.0, -800.0),
            look_at: Vec3::new(278.0, 273.0, 0.0),
            up: Vec3::Y,
            vfov_degrees: 40.0,
            focal_length: 1.0,
            lens: pathtrace::Lens::Pinhole,
        }
    }

    fn distance(c: &CameraDesc) -> f32 {
        (c.look_from - c.look_at).length()
    }

    #[test]
    fn orbit_keeps_the_look_at_point_and_its_distance() {
        let c = cornell();
        for (yaw, pitch) in [(0.3, 0.0), (0.0, 0.4), (-1.2, -0.7), (3.0, 2.0), (0.0, -5.0)] {
            let o = orbit(&c, yaw, pitch);
            assert_eq!(o.look_at, c.look_at);
            assert!((distance(&o) - distance(&c)).abs() < 1e-3 * distance(&c), "{yaw} {pitch}: {o:?}");
            assert!(basis(&o).is_some(), "orbit must never reach the pole");
        }
    }

    #[test]
    fn orbit_yaw_turns_about_up_and_pitch_raises_the_eye() {
        let c = cornell();
        let quarter = orbit(&c, std::f32::consts::FRAC_PI_2, 0.0);
        // A quarter turn about +y takes the eye from −z to −x or +x of the target, same height.
        assert!((quarter.look_from.y - c.look_from.y).abs() < 1e-2);
        assert!((quarter.look_from.x - c.look_at.x).abs() > 799.0, "{:?}", quarter.look_from);
        let raised = orbit(&c, 0.0, 0.3);
        assert!(raised.look_from.y > c.look_from.y + 100.0, "{:?}", raised.look_from);
        // Far past the pole is clamped just short of it.
        let top = orbit(&c, 0.0, 10.0);
        let dir = (top.look_from - top.look_at).normalize();
        assert!(dir.y > 0.99 && dir.y < 1.0, "{dir:?}");
    }

    #[test]
    fn pan_moves_both_points_by_the_same_offset_in_the_view_plane() {
        let c = cornell();
        let p = pan(&c, 10.0, -4.0, 256);
        let moved = p.look_from - c.look_from;
        assert!((p.look_at - c.look_at - moved).length() < 1e-3);
        assert!(moved.length() > 0.0);
        // In the view plane: no movement along the view direction.
        let (f, _, _) = basis(&c).unwrap();
        assert!(moved.dot(f).abs() < 1e-3);
        // One pixel at the look-at distance: 2·800·tan(20°)/256 ≈ 2.275 units.
        let one = pan(&c, 1.0, 0.0, 256);
        assert!(((one.look_from - c.look_from).length() - 2.2748).abs() < 1e-3);
    }

    #[test]
    fn zoom_changes_only_the_fov_within_limits() {
        let c = cornell();
        let z = zoom(&c, 1.0);
        assert!((z.vfov_degrees - 36.0).abs() < 1e-4);
        assert_eq!((z.look_from, z.look_at), (c.look_from, c.look_at));
        assert!(zoom(&c, -1.0).vfov_degrees > c.vfov_degrees);
        assert_eq!(zoom(&c, 1000.0).vfov_degrees, FOV_LIMITS.0);
        assert_eq!(zoom(&c, -1000.0).vfov_degrees, FOV_LIMITS.1);
    }

    #[test]
    fn fly_moves_both_points_along_the_camera_axes() {
        let c = cornell();
        let f = fly(&c, 0.0, 0.0, 1.0, 0.1);
        assert!((f.look_from - (c.look_from + Vec3::new(0.0, 0.0, 80.0))).length() < 1e-3);
        assert!((f.look_at - (c.look_at + Vec3::new(0.0, 0.0, 80.0))).length() < 1e-3);
        let side = fly(&c, 1.0, 0.0, 0.0, 0.1);
        assert!((side.look_from - c.look_from).dot(Vec3::Y).abs() < 1e-3);
        assert!((distance(&side) - distance(&c)).abs() < 1e-3);
    }

    #[test]
    fn degenerate_cameras_are_left_unchanged() {
        let c = CameraDesc { look_at: cornell().look_from, ..cornell() };
        assert_eq!(orbit(&c, 1.0, 1.0), c);
        assert_eq!(pan(&c, 1.0, 1.0, 10), c);
        assert_eq!(fly(&c, 1.0, 1.0, 1.0, 0.1), c);
    }
}
