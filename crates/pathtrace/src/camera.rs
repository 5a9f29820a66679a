//! The cameras: a look-from / look-at / up basis and a grid of pixel rays ("Ray Tracing in One
//! Weekend" §11): w = (from − at)/‖from − at‖, u = (up × w)/‖up × w‖, v = w × u; image x runs
//! along +u, image y along −v, starting at the upper-left pixel.
//!
//! - Pinhole: the viewport is 2·tan(vfov/2)·focal high and aspect × that wide, at `focal` along −w.
//! - Thin lens (Mitsuba 3's `thinlens`, pbrt-v4 §5.2.3): the pinhole ray through the pixel picks
//!   the point it meets on the plane of focus, `focus_distance` along −w; the ray then starts at a
//!   point of the lens disk of radius `aperture_radius` (concentric map, as Mitsuba) and aims at
//!   that point, so everything on the plane of focus is sharp and the rest is blurred.
//! - Orthographic (Mitsuba 3's `orthographic`): parallel rays along −w from a `height` × aspect
//!   rectangle centred on look-from.

use crate::math::{normalize_robust, Ray, Vec2, Vec3};
use crate::wide::simd::{F32s, Vec3s};
use crate::wide::warp as lanes;

/// The projection of a camera.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Lens {
    /// Every ray starts at look-from (infinite depth of field).
    #[default]
    Pinhole,
    /// A lens disk of `aperture_radius` focused on the plane `focus_distance` in front of it.
    ThinLens { aperture_radius: f32, focus_distance: f32 },
    /// Parallel rays from a viewport `height` high (scene units), as wide as the image's aspect.
    Orthographic { height: f32 },
}

impl Lens {
    /// Whether the rays need a 2D lens sample (the thin lens's aperture point).
    pub fn needs_aperture_sample(&self) -> bool {
        matches!(self, Lens::ThinLens { .. })
    }
}

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
    /// Pinhole, thin lens or orthographic.
    pub lens: Lens,
}

impl Default for CameraDesc {
    fn default() -> Self {
        Self {
            look_from: Vec3::ZERO,
            look_at: -Vec3::Z,
            up: Vec3::Y,
            vfov_degrees: 40.0,
            focal_length: 1.0,
            lens: Lens::Pinhole,
        }
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
    #[error("thin-lens aperture radius {0} must be zero or positive")]
    Aperture(f32),
    #[error("thin-lens focus distance {0} must be positive")]
    FocusDistance(f32),
    #[error("orthographic view height {0} must be positive")]
    ViewHeight(f32),
}

/// What the camera does with a pixel's viewport point.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Projection {
    Pinhole,
    /// `lens_u`, `lens_v`: the lens disk's axes scaled by the aperture radius; `focus_scale`:
    /// focus distance / focal length (how far past the viewport the plane of focus lies).
    ThinLens {
        lens_u: Vec3,
        lens_v: Vec3,
        focus_scale: f32,
    },
    /// Rays along `dir` from the viewport point itself.
    Orthographic {
        dir: Vec3,
    },
}

/// A camera set up for one image resolution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    origin: Vec3,
    pixel00: Vec3,
    du: Vec3,
    dv: Vec3,
    projection: Projection,
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
            && desc.focal_length.is_finite()
            && match desc.lens {
                Lens::Pinhole => true,
                Lens::ThinLens { aperture_radius, focus_distance } => {
                    aperture_radius.is_finite() && focus_distance.is_finite()
                }
                Lens::Orthographic { height } => height.is_finite(),
            };
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
        let (viewport_h, centre, projection) = match desc.lens {
            Lens::Pinhole => (Self::pinhole_height(desc), desc.look_from - desc.focal_length * w, Projection::Pinhole),
            Lens::ThinLens { aperture_radius, focus_distance } => {
                if aperture_radius < 0.0 {
                    return Err(CameraError::Aperture(aperture_radius));
                }
                if focus_distance <= 0.0 {
                    return Err(CameraError::FocusDistance(focus_distance));
                }
                let projection = Projection::ThinLens {
                    lens_u: u * aperture_radius,
                    lens_v: v * aperture_radius,
                    focus_scale: focus_distance / desc.focal_length,
                };
                (Self::pinhole_height(desc), desc.look_from - desc.focal_length * w, projection)
            }
            Lens::Orthographic { height } => {
                if height <= 0.0 {
                    return Err(CameraError::ViewHeight(height));
                }
                (height, desc.look_from, Projection::Orthographic { dir: -w })
            }
        };
        let viewport_w = viewport_h * (width as f32 / height as f32);
        let viewport_u = viewport_w * u;
        let viewport_v = -viewport_h * v;
        let du = viewport_u / width as f32;
        let dv = viewport_v / height as f32;
        let upper_left = centre - viewport_u / 2.0 - viewport_v / 2.0;
        Ok(Self { origin: desc.look_from, pixel00: upper_left + 0.5 * (du + dv), du, dv, projection, width, height })
    }

    fn pinhole_height(desc: &CameraDesc) -> f32 {
        2.0 * (desc.vfov_degrees.to_radians() / 2.0).tan() * desc.focal_length
    }

    /// Whether [`Camera::generate_ray`] uses its `aperture` sample.
    #[inline(always)]
    pub fn needs_aperture_sample(&self) -> bool {
        matches!(self.projection, Projection::ThinLens { .. })
    }

    /// The ray through pixel `(x, y)` offset by `jitter ∈ [0,1)²` within the pixel
    /// (`(0.5, 0.5)` is the pixel centre); `aperture ∈ [0,1)²` picks the point on a thin lens
    /// (other cameras ignore it). The direction is unit length. The one-lane instance of
    /// [`Camera::generate_rays`].
    #[inline(always)]
    pub fn generate_ray(&self, x: u32, y: u32, jitter: Vec2, aperture: Vec2) -> Ray {
        let one = |v: f32| F32s([v]);
        let (origin, dir) = self.generate_rays(
            [one(x as f32), one(y as f32)],
            [one(jitter.x), one(jitter.y)],
            [one(aperture.x), one(aperture.y)],
        );
        Ray::new(origin.lane(0), dir.lane(0))
    }

    /// [`Camera::generate_ray`] for `N` lanes at once: lane `i` is the ray through pixel
    /// `(pixel[0][i], pixel[1][i])` (whole numbers), offset by its `jitter` and through its
    /// `aperture` point; returns the origins and unit directions. Why lanes: lane by lane, each
    /// camera sample waited on its own square root and division (a tenth of the teapot's render).
    #[inline(always)]
    pub(crate) fn generate_rays<const N: usize>(
        &self,
        pixel: [F32s<N>; 2],
        jitter: [F32s<N>; 2],
        aperture: [F32s<N>; 2],
    ) -> (Vec3s<N>, Vec3s<N>) {
        // The same operations, in the same order, as glam's Vec3 arithmetic on one ray.
        let a = pixel[0] + jitter[0] - 0.5;
        let b = pixel[1] + jitter[1] - 0.5;
        let target = along(self.pixel00, a, self.du, b, self.dv);
        let origin = Vec3s::splat(self.origin);
        match self.projection {
            Projection::Pinhole => (origin, target.sub(&origin).normalize()),
            Projection::ThinLens { lens_u, lens_v, focus_scale } => {
                let focus = origin.add(&target.sub(&origin).scale(F32s::splat(focus_scale)));
                let (dx, dy) = lanes::square_to_uniform_disk(aperture[0], aperture[1]);
                let lens = along(self.origin, dx, lens_u, dy, lens_v);
                (lens, focus.sub(&lens).normalize())
            }
            Projection::Orthographic { dir } => (target, Vec3s::splat(dir)),
        }
    }
}

/// `base + a·u + b·v` per lane. A function, not a closure in `generate_rays`: the closure was
/// compiled out of line, without the caller's AVX-512 (1–2% of the render in a profile).
#[inline(always)]
fn along<const N: usize>(base: Vec3, a: F32s<N>, u: Vec3, b: F32s<N>, v: Vec3) -> Vec3s<N> {
    Vec3s { x: base.x + a * u.x + b * v.x, y: base.y + a * u.y + b * v.y, z: base.z + a * u.z + b * v.z }
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
            lens: Lens::Pinhole,
        }
    }

    #[test]
    fn centre_ray_looks_at_the_target_and_corners_span_the_fov() {
        let cam = Camera::new(&cornell(), 100, 100).unwrap();
        let centre = cam.generate_ray(50, 50, Vec2::ZERO, Vec2::ZERO);
        assert!((centre.dir - Vec3::Z).length() < 1e-4, "{:?}", centre.dir);
        // Top edge centre: elevation is vfov/2 = 20°.
        let top = cam.generate_ray(50, 0, Vec2::new(0.0, 0.0), Vec2::ZERO);
        assert!((top.dir.y.asin().to_degrees() - 20.0).abs() < 0.01, "{:?}", top.dir);
        // The camera's u axis is up × w = -x here, so the left of the image is +x.
        let left = cam.generate_ray(0, 50, Vec2::new(0.0, 0.0), Vec2::ZERO);
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

    /// A group of rays is, lane for lane and bit for bit, the rays generated one at a time, for
    /// every projection.
    #[test]
    fn lanes_of_rays_are_the_single_rays() {
        const N: usize = 16;
        let lenses = [
            Lens::Pinhole,
            Lens::ThinLens { aperture_radius: 20.0, focus_distance: 700.0 },
            Lens::Orthographic { height: 500.0 },
        ];
        for lens in lenses {
            let cam = Camera::new(&CameraDesc { lens, ..cornell() }, 97, 61).unwrap();
            let lane = |i: usize, k: u32| {
                ((i as u32).wrapping_mul(2_654_435_761).wrapping_add(k * 40_503) % 1000) as f32 / 1000.0
            };
            let pixel = [F32s::<N>::from_fn(|i| (i * 7 % 97) as f32), F32s::from_fn(|i| (i * 5 % 61) as f32)];
            let jitter = [F32s::from_fn(|i| lane(i, 1)), F32s::from_fn(|i| lane(i, 2))];
            let aperture = [F32s::from_fn(|i| lane(i, 3)), F32s::from_fn(|i| lane(i, 4))];
            let (origin, dir) = cam.generate_rays(pixel, jitter, aperture);
            for i in 0..N {
                let one = cam.generate_ray(
                    (i * 7 % 97) as u32,
                    (i * 5 % 61) as u32,
                    Vec2::new(jitter[0].0[i], jitter[1].0[i]),
                    Vec2::new(aperture[0].0[i], aperture[1].0[i]),
                );
                let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                assert_eq!(bits(origin.lane(i)), bits(one.origin), "{lens:?} lane {i}");
                assert_eq!(bits(dir.lane(i)), bits(one.dir), "{lens:?} lane {i}");
            }
        }
    }
}
