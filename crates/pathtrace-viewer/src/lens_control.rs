//! Depth-of-field controls on a [`CameraDesc`]: opening and closing the aperture, moving the
//! plane of focus, and focusing on the surface under the cursor (its depth along the view
//! direction). Pure functions, unit-tested below; the window code maps keys and clicks to them.

use pathtrace::math::{Ray, Vec2};
use pathtrace::{Camera, CameraDesc, Lens, Scene};

/// The aperture a pinhole opens to, as a fraction of the look-at distance.
const FIRST_APERTURE: f32 = 0.01;
/// Closing below this fraction of the look-at distance gives the pinhole back.
const SMALLEST_APERTURE: f32 = 0.001;

fn look_distance(c: &CameraDesc) -> f32 {
    (c.look_at - c.look_from).length()
}

/// Scales the aperture radius by `factor` (> 1 opens it). A pinhole opens to a small lens
/// focused on the look-at point; a lens closed below a tiny radius becomes a pinhole again.
/// Orthographic cameras have no aperture and are unchanged.
pub fn aperture(c: &CameraDesc, factor: f32) -> CameraDesc {
    let d = look_distance(c);
    let lens = match c.lens {
        Lens::Pinhole if factor > 1.0 => {
            Lens::ThinLens { aperture_radius: FIRST_APERTURE * d, focus_distance: d.max(f32::MIN_POSITIVE) }
        }
        Lens::ThinLens { aperture_radius, focus_distance } => {
            let r = aperture_radius * factor;
            if r < SMALLEST_APERTURE * d {
                Lens::Pinhole
            } else {
                Lens::ThinLens { aperture_radius: r, focus_distance }
            }
        }
        other => other,
    };
    CameraDesc { lens, ..*c }
}

/// Scales the focus distance by `factor` (thin lens only).
pub fn focus(c: &CameraDesc, factor: f32) -> CameraDesc {
    match c.lens {
        Lens::ThinLens { aperture_radius, focus_distance } => {
            CameraDesc { lens: Lens::ThinLens { aperture_radius, focus_distance: focus_distance * factor }, ..*c }
        }
        _ => *c,
    }
}

/// Focuses at `distance` along the view direction, opening a pinhole's aperture so the focus
/// shows. Orthographic cameras are unchanged.
pub fn focus_at(c: &CameraDesc, distance: f32) -> CameraDesc {
    if !(distance > 0.0 && distance.is_finite()) {
        return *c;
    }
    let opened = if c.lens == Lens::Pinhole { aperture(c, 2.0) } else { *c };
    match opened.lens {
        Lens::ThinLens { aperture_radius, .. } => {
            CameraDesc { lens: Lens::ThinLens { aperture_radius, focus_distance: distance }, ..opened }
        }
        _ => *c,
    }
}

/// The depth (distance along the view direction, what `focus_distance` measures) of the surface
/// seen at image point (`x`, `y`) (pixels, may be fractional) of a `width` × `height` render, or
/// `None` where the ray through it leaves the scene.
pub fn depth_under(scene: &Scene, c: &CameraDesc, width: u32, height: u32, x: f32, y: f32) -> Option<f32> {
    if !(x >= 0.0 && y >= 0.0 && x < width as f32 && y < height as f32) {
        return None;
    }
    // The lens centre's ray, which is the pinhole's.
    let camera = Camera::new(c, width, height).ok()?;
    let (px, py) = (x.floor(), y.floor());
    let ray: Ray = camera.generate_ray(px as u32, py as u32, Vec2::new(x - px, y - py), Vec2::splat(0.5));
    let hit = scene.intersect(&ray, f32::INFINITY)?;
    let forward = (c.look_at - c.look_from).try_normalize()?;
    Some(hit.hit.t * ray.dir.dot(forward))
}

#[cfg(test)]
mod tests {
    use super::*;
    use pathtrace::light::Emission;
    use pathtrace::material::{Lambertian, Material};
    use pathtrace::math::{Rgb, Transform, Vec3};
    use pathtrace::shape::{Shape, Sphere};
    use pathtrace::SceneBuilder;

    fn camera() -> CameraDesc {
        CameraDesc { look_from: Vec3::new(0.0, 0.0, -10.0), look_at: Vec3::ZERO, ..Default::default() }
    }

    /// `lens` is a thin lens of this radius and focus distance (to f32 rounding).
    fn thin(lens: Lens, radius: f32, focus: f32) {
        let Lens::ThinLens { aperture_radius, focus_distance } = lens else { panic!("{lens:?}") };
        let close = |a: f32, b: f32| (a - b).abs() <= 1e-6 * b;
        assert!(close(aperture_radius, radius) && close(focus_distance, focus), "{lens:?}");
    }

    #[test]
    fn the_aperture_opens_from_a_pinhole_and_closes_back_to_one() {
        let opened = aperture(&camera(), 2.0);
        thin(opened.lens, 0.1, 10.0);
        let wider = aperture(&opened, 2.0);
        thin(wider.lens, 0.2, 10.0);
        assert_eq!(aperture(&camera(), 0.5).lens, Lens::Pinhole, "closing a pinhole keeps it");
        let mut c = opened;
        for _ in 0..4 {
            c = aperture(&c, 0.5);
        }
        assert_eq!(c.lens, Lens::Pinhole, "0.1 / 16 is below 0.001 · 10");
        let ortho = CameraDesc { lens: Lens::Orthographic { height: 2.0 }, ..camera() };
        assert_eq!(aperture(&ortho, 2.0), ortho);
        assert_eq!(focus(&ortho, 2.0), ortho);
    }

    #[test]
    fn focus_moves_the_plane_of_focus() {
        let c = aperture(&camera(), 2.0);
        thin(focus(&c, 1.5).lens, 0.1, 15.0);
        thin(focus_at(&c, 4.0).lens, 0.1, 4.0);
        thin(focus_at(&camera(), 4.0).lens, 0.1, 4.0);
        assert_eq!(focus_at(&c, f32::NAN), c);
    }

    #[test]
    fn the_depth_under_the_cursor_is_measured_along_the_view() {
        // A unit sphere 3 units right of the view axis; its nearest point to the camera plane
        // seen from the left of the image (+x is the image's left, as u = up × w).
        let mut b = SceneBuilder::new();
        let m = b.material_with_emission(
            Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }),
            Emission { radiance: Rgb::splat(1.0), two_sided: true },
        );
        let sphere = Sphere::new(Vec3::new(3.0, 0.0, 0.0), 1.0).unwrap();
        b.shape(Shape::Sphere(sphere), m, &Transform::IDENTITY).unwrap();
        b.camera(camera());
        let scene = b.build().unwrap();
        let (w, h) = (101, 101);
        // The pixel whose centre ray points at the sphere's centre.
        let half = (20f32).to_radians().tan();
        let x = 50.5 - (3.0 / 10.0) / half * 50.5;
        let d = depth_under(&scene, &camera(), w, h, x, 50.5).expect("the sphere is under the cursor");
        // The ray meets the sphere 1 unit before its centre: the depth is (√109 − 1)·cos α.
        let cos_a = 10.0 / 109f32.sqrt();
        assert!((d - (109f32.sqrt() - 1.0) * cos_a).abs() < 1e-2, "{d}");
        assert_eq!(depth_under(&scene, &camera(), w, h, 2.0, 2.0), None, "the sky has no depth");
        assert_eq!(depth_under(&scene, &camera(), w, h, -1.0, 2.0), None);
    }
}
