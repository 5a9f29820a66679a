//! The pinhole camera: a look-from / look-at / up basis, a vertical field of view, and a grid of
//! pixel rays ("Ray Tracing in One Weekend" §11):
//! w = (from − at)/‖from − at‖, u = (up × w)/‖up × w‖, v = w × u; the viewport is
//! 2·tan(vfov/2)·focal high and aspect × that wide; image x runs along +u, image y along −v,
//! starting at the upper-left pixel.

use crate::math::{normalize_robust, Ray, Vec2, Vec3};

/// How the camera is placed (what scene files describe).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraDesc {
    pub look_from: Vec3,
    pub look_at: Vec3,
    pub up: Vec3,
    /// Vertical field of view in degrees, in (0, 180).
    pub vfov_degrees: f32,
    /// Distance to the viewport plane; it scales the viewport but not the image (pinhole).
    pub focal_length: f32,
}

impl Default for CameraDesc {
    fn default() -> Self {
        Self { look_from: Vec3::ZERO, look_at: -Vec3::Z, up: Vec3::Y, vfov_degrees: 40.0, focal_length: 1.0 }
    }
}

/// Why a camera cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CameraError {
    #[error("camera look_from and look_at are the same point")]
    ZeroViewDirection,
    #[error("camera look_from and look_at are too far apart: their distance overflows single precision (3.4e38)")]
    TooFarApart,
    #[error("camera up vector is zero or parallel to the viewing direction")]
    DegenerateUp,
    #[error("vertical field of view {0}° must be between 0 and 180 degrees")]
    FieldOfView(f32),
    #[error("focal length {0} must be positive")]
    FocalLength(f32),
    #[error("image size {0}×{1} must be at least 1×1")]
    ImageSize(u32, u32),
    #[error("camera parameters must be finite numbers")]
    NotFinite,
}

/// A camera set up for one image resolution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    origin: Vec3,
    pixel00: Vec3,
    du: Vec3,
    dv: Vec3,
    pub width: u32,
    pub height: u32,
}

impl Camera {
    pub fn new(desc: &CameraDesc, width: u32, height: u32) -> Result<Self, CameraError> {
        if width == 0 || height == 0 {
            return Err(CameraError::ImageSize(width, height));
        }
        let finite = desc.look_from.is_finite()
            && desc.look_at.is_finite()
            && desc.up.is_finite()
            && desc.vfov_degrees.is_finite()
            && desc.focal_length.is_finite();
        if !finite {
            return Err(CameraError::NotFinite);
        }
        if !(desc.vfov_degrees > 0.0 && desc.vfov_degrees < 180.0) {
            return Err(CameraError::FieldOfView(desc.vfov_degrees));
        }
        if desc.focal_length <= 0.0 {
            return Err(CameraError::FocalLength(desc.focal_length));
        }
        let offset = desc.look_from - desc.look_at;
        if !offset.is_finite() {
            return Err(CameraError::TooFarApart);
        }
        let w = normalize_robust(offset).ok_or(CameraError::ZeroViewDirection)?;
        let u = normalize_robust(desc.up.cross(w)).ok_or(CameraError::DegenerateUp)?;
        let v = w.cross(u);
        let viewport_h = 2.0 * (desc.vfov_degrees.to_radians() / 2.0).tan() * desc.focal_length;
        let viewport_w = viewport_h * (width as f32 / height as f32);
        let viewport_u = viewport_w * u;
        let viewport_v = -viewport_h * v;
        let du = viewport_u / width as f32;
        let dv = viewport_v / height as f32;
        let upper_left = desc.look_from - desc.focal_length * w - viewport_u / 2.0 - viewport_v / 2.0;
        Ok(Self { origin: desc.look_from, pixel00: upper_left + 0.5 * (du + dv), du, dv, width, height })
    }

    /// The ray through pixel `(x, y)` offset by `jitter ∈ [0,1)²` within the pixel
    /// (`(0.5, 0.5)` is the pixel centre). The direction is unit length.
    #[inline(always)]
    pub fn generate_ray(&self, x: u32, y: u32, jitter: Vec2) -> Ray {
        let target = self.pixel00 + (x as f32 + jitter.x - 0.5) * self.du + (y as f32 + jitter.y - 0.5) * self.dv;
        Ray::new(self.origin, (target - self.origin).normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cornell() -> CameraDesc {
        CameraDesc {
            look_from: Vec3::new(278.0, 278.0, -800.0),
            look_at: Vec3::new(278.0, 278.0, 0.0),
            up: Vec3::Y,
            vfov_degrees: 40.0,
            focal_length: 1.0,
        }
    }

    #[test]
    fn centre_ray_looks_at_the_target_and_corners_span_the_fov() {
        let cam = Camera::new(&cornell(), 100, 100).unwrap();
        let centre = cam.generate_ray(50, 50, Vec2::ZERO);
        assert!((centre.dir - Vec3::Z).length() < 1e-4, "{:?}", centre.dir);
        // Top edge centre: elevation is vfov/2 = 20°.
        let top = cam.generate_ray(50, 0, Vec2::new(0.0, 0.0));
        assert!((top.dir.y.asin().to_degrees() - 20.0).abs() < 0.01, "{:?}", top.dir);
        // The camera's u axis is up × w = -x here, so the left of the image is +x.
        let left = cam.generate_ray(0, 50, Vec2::new(0.0, 0.0));
        assert!(left.dir.x > 0.0);
    }

    #[test]
    fn bad_parameters_are_errors() {
        let mut d = cornell();
        d.look_at = d.look_from;
        assert_eq!(Camera::new(&d, 10, 10), Err(CameraError::ZeroViewDirection));
        let mut d = cornell();
        d.up = Vec3::Z;
        assert_eq!(Camera::new(&d, 10, 10), Err(CameraError::DegenerateUp));
        let mut d = cornell();
        d.vfov_degrees = 180.0;
        assert!(matches!(Camera::new(&d, 10, 10), Err(CameraError::FieldOfView(_))));
        assert!(matches!(Camera::new(&cornell(), 0, 10), Err(CameraError::ImageSize(0, 10))));
    }
}
