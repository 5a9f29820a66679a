//! Feature buffers (albedo, normal, depth) accumulated with the image, against scenes whose
//! answers are known in closed form: a textured Lambertian square filling the frame, a unit
//! sphere seen head-on, a mirror that shows a coloured wall behind the camera, and paths that
//! escape to the environment.

use pathtrace::film::{FeatureBuffers, PixelFilter};
use pathtrace::light::EnvironmentLight;
use pathtrace::material::{Lambertian, Material, Mirror};
use pathtrace::math::{Rgb, Transform, Vec2, Vec3};
use pathtrace::shape::{Quad, Shape, Sphere};
use pathtrace::texture::{Checkerboard, ColourSlot, Texture, UvTransform};
use pathtrace::wide::Kernel;
use pathtrace::{render, CameraDesc, RenderSettings, Scene, SceneBuilder};
use std::sync::Arc;

const SIZE: u32 = 32;

/// The camera at (0, 0, 1) looking down -z with a 90° fov: the square [-1, 1]² in z = 0 fills
/// the frame exactly.
fn camera() -> CameraDesc {
    CameraDesc {
        look_from: Vec3::new(0.0, 0.0, 1.0),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        vfov_degrees: 90.0,
        focal_length: 1.0,
        ..Default::default()
    }
}

fn unit_square() -> Shape {
    Shape::Quad(Quad::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)).unwrap())
}

fn features(scene: Scene, spp: u32, kernel: Kernel) -> FeatureBuffers {
    let mut s =
        RenderSettings { width: SIZE, height: SIZE, spp, seed: 5, kernel, features: true, ..Default::default() };
    // The pixel itself only, so every sample of a pixel lands in the pixel's own footprint.
    s.filter = PixelFilter::with_radius("box", 0.5).unwrap();
    let out = render(Arc::new(scene), s).unwrap();
    let f = out.features.expect("features were asked for");
    assert_eq!(out.film.total_samples(), f.pixels().iter().map(|p| p.count as u64).sum::<u64>());
    f
}

/// Where the ray through pixel `(x, y)`'s centre meets the plane z = 0.
fn plane_point(x: u32, y: u32) -> Vec2 {
    let s = 2.0 / SIZE as f32;
    Vec2::new(-1.0 + (x as f32 + 0.5) * s, 1.0 - (y as f32 + 0.5) * s)
}

/// The least and greatest distance from the camera to the plane z = 0 over pixel `(x, y)`
/// (reached at its corners: the distance has no extremum inside a pixel off the axis, and the
/// centre pixels' range includes the axis value 1 from both sides).
fn plane_distance_range(x: u32, y: u32) -> (f32, f32) {
    let s = 2.0 / SIZE as f32;
    let (x0, y0) = (-1.0 + x as f32 * s, 1.0 - y as f32 * s);
    let corners = [(x0, y0), (x0 + s, y0), (x0, y0 - s), (x0 + s, y0 - s)];
    let d = corners.map(|(u, v): (f32, f32)| (1.0 + u * u + v * v).sqrt());
    let lo = d.iter().fold(f32::MAX, |a, &b| a.min(b));
    let lo = if x0 <= 0.0 && x0 + s >= 0.0 && y0 >= 0.0 && y0 - s <= 0.0 { 1.0 } else { lo };
    (lo, d.iter().fold(0.0, |a, &b| a.max(b)))
}

fn assert_depth_in(what: &str, got: Rgb, (lo, hi): (f32, f32)) {
    assert!(got.r == got.g && got.g == got.b, "{what}: {got:?} differs between channels");
    assert!(got.r >= lo - 1e-5 && got.r <= hi + 1e-5, "{what}: {} outside the pixel's range [{lo}, {hi}]", got.r);
}

fn assert_close(what: &str, got: Rgb, want: Rgb, tol: f32) {
    let d = (got.r - want.r).abs().max((got.g - want.g).abs()).max((got.b - want.b).abs());
    assert!(d <= tol, "{what}: {got:?}, expected {want:?}");
}

#[test]
fn a_textured_diffuse_square_shows_its_reflectance_normal_and_distance_in_every_pixel() {
    let (c0, c1) = (Rgb::new(0.8, 0.2, 0.5), Rgb::new(0.2, 0.6, 0.1));
    // 8×8 checks over the square: 4×4 pixels each, so no pixel straddles two checks.
    let board = Checkerboard { color0: c0, color1: c1, to_uv: UvTransform::scale(Vec2::splat(4.0)) };
    let mut b = SceneBuilder::new();
    let m = b.material(Material::Lambertian(Lambertian { albedo: board.mean() }));
    let t = b.texture(Texture::Checkerboard(board));
    b.bind_texture(m, ColourSlot::Base, t).unwrap();
    b.shape(unit_square(), m, &Transform::IDENTITY).unwrap();
    b.environment(EnvironmentLight::constant(Rgb::WHITE)).unwrap();
    b.camera(camera());
    let f = features(b.build().unwrap(), 16, Kernel::default());
    let (albedo, normal, depth) = (f.albedo(), f.normal(), f.depth());
    let mut seen = [0; 2];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let p = plane_point(x, y);
            let want = board.eval(Vec2::new((p.x + 1.0) / 2.0, (p.y + 1.0) / 2.0));
            seen[usize::from(want == c1)] += 1;
            assert_close(&format!("albedo ({x},{y})"), albedo.get(x, y), want, 1e-5);
            assert_close(&format!("normal ({x},{y})"), normal.get(x, y), Rgb::new(0.0, 0.0, 1.0), 1e-6);
            assert_depth_in(&format!("depth ({x},{y})"), depth.get(x, y), plane_distance_range(x, y));
        }
    }
    assert_eq!(seen, [512, 512]);
}

/// The sphere scene's sky: brighter than 1 in blue, so its albedo shows the clamp.
const SKY: Rgb = Rgb::new(0.3, 0.6, 2.5);

fn sphere_scene() -> Scene {
    let mut b = SceneBuilder::new();
    let m = b.material(Material::Lambertian(Lambertian { albedo: Rgb::new(0.2, 0.4, 0.6) }));
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap()), m, &Transform::IDENTITY).unwrap();
    b.environment(EnvironmentLight::constant(SKY)).unwrap();
    b.camera(CameraDesc { look_from: Vec3::new(0.0, 0.0, 5.0), vfov_degrees: 30.0, ..camera() });
    b.build().unwrap()
}

#[test]
fn sphere_normals_are_unit_and_face_the_camera_and_depth_is_the_hit_distance() {
    let f = features(sphere_scene(), 8, Kernel::default());
    let (albedo, normal, depth) = (f.albedo(), f.normal(), f.depth());
    let eye = Vec3::new(0.0, 0.0, 5.0);
    // The corner rays pass the sphere: they see the sky, whose albedo is its radiance clamped
    // to [0, 1]; no normal, no depth.
    assert_eq!(albedo.get(0, 0), Rgb::new(0.3, 0.6, 1.0));
    for img in [&normal, &depth] {
        assert_eq!(img.get(0, 0), Rgb::BLACK);
    }
    let cam = pathtrace::Camera::new(&sphere_scene().camera, SIZE, SIZE).unwrap();
    let mut inside = 0;
    for y in 0..SIZE {
        for x in 0..SIZE {
            // Pixels whose four corners all hit the sphere are covered by it entirely.
            let corner_hits = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
                .iter()
                .filter_map(|&(u, v)| {
                    let ray = cam.generate_ray(x, y, Vec2::new(u, v), Vec2::splat(0.5));
                    let b = ray.origin.dot(ray.dir);
                    let disc = b * b - (ray.origin.length_squared() - 1.0);
                    (disc > 0.0).then(|| -b - disc.sqrt())
                })
                .collect::<Vec<f32>>();
            if corner_hits.len() < 4 {
                continue;
            }
            inside += 1;
            let n = normal.get(x, y);
            let n = Vec3::new(n.r, n.g, n.b);
            // The mean of unit normals over a small patch is unit length to second order.
            assert!((n.length() - 1.0).abs() < 1e-2, "({x},{y}): |n| = {}", n.length());
            // It faces the camera: the sphere point it names is seen from the eye.
            assert!(n.dot(eye - n) > 0.0, "({x},{y}): normal {n} faces away from the camera");
            // Depth lies between the pixel corners' hit distances (the distance varies
            // monotonically across so small a patch).
            let d = depth.get(x, y).r;
            let (lo, hi) = corner_hits.iter().fold((f32::MAX, 0.0f32), |(l, h), &t| (l.min(t), h.max(t)));
            assert!(d >= lo - 1e-4 && d <= hi + 1e-4, "({x},{y}): depth {d} outside [{lo}, {hi}]");
            assert_close(&format!("albedo ({x},{y})"), albedo.get(x, y), Rgb::new(0.2, 0.4, 0.6), 1e-5);
        }
    }
    assert!(inside > 100, "the sphere should cover many pixels, saw {inside}");
}

/// A mirror filling the frame, and behind the camera (at z = 3, beyond the camera at z = 1) a
/// coloured wall that only the mirror shows.
fn mirror_scene(reflectance: Rgb, wall: Rgb) -> Scene {
    let mut b = SceneBuilder::new();
    let mirror = b.material(Material::Mirror(Mirror { reflectance }));
    b.shape(unit_square(), mirror, &Transform::IDENTITY).unwrap();
    let w = b.material(Material::Lambertian(Lambertian { albedo: wall }));
    let quad = Quad::new(Vec3::new(-20.0, -20.0, 3.0), Vec3::new(40.0, 0.0, 0.0), Vec3::new(0.0, 40.0, 0.0)).unwrap();
    b.shape(Shape::Quad(quad), w, &Transform::IDENTITY).unwrap();
    b.environment(EnvironmentLight::constant(Rgb::WHITE)).unwrap();
    b.camera(camera());
    b.build().unwrap()
}

#[test]
fn through_a_mirror_the_buffers_show_the_mirrored_object() {
    let (r, wall) = (Rgb::new(0.9, 0.8, 0.7), Rgb::new(0.1, 0.5, 0.3));
    for kernel in [Kernel::default(), Kernel::Scalar] {
        let f = features(mirror_scene(r, wall), 4, kernel);
        let (albedo, normal, depth) = (f.albedo(), f.normal(), f.depth());
        for (x, y) in [(0, 0), (SIZE / 2, SIZE / 2), (3, 27)] {
            // The wall's albedo, tinted by the mirror it is seen in.
            assert_close("albedo", albedo.get(x, y), Rgb::new(r.r * wall.r, r.g * wall.g, r.b * wall.b), 1e-5);
            // The wall's normal, facing the mirror (down -z), not the mirror's own.
            assert_close("normal", normal.get(x, y), Rgb::new(0.0, 0.0, -1.0), 1e-6);
            // Depth is the camera ray's: the distance to the mirror.
            assert_depth_in("depth", depth.get(x, y), plane_distance_range(x, y));
        }
    }
}

#[test]
fn escaped_paths_record_the_environment_clamped_and_tinted_by_the_specular_chain() {
    // A mirror filling the frame with nothing in front of it: every path escapes after it.
    let r = Rgb::new(0.9, 0.8, 0.7);
    let mirror_to_sky = |sky: Option<Rgb>| {
        let mut b = SceneBuilder::new();
        let mirror = b.material(Material::Mirror(Mirror { reflectance: r }));
        b.shape(unit_square(), mirror, &Transform::IDENTITY).unwrap();
        if let Some(sky) = sky {
            b.environment(EnvironmentLight::constant(sky)).unwrap();
        }
        b.allow_no_lights(true);
        b.camera(camera());
        b.build().unwrap()
    };
    for kernel in [Kernel::default(), Kernel::Scalar] {
        let albedo = features(mirror_to_sky(Some(SKY)), 2, kernel).albedo();
        for (x, y) in [(0, 0), (SIZE / 2, SIZE / 2), (3, 27)] {
            assert_close("mirrored sky", albedo.get(x, y), Rgb::new(r.r * 0.3, r.g * 0.6, r.b * 1.0), 1e-6);
        }
        // Without an environment the escaped path keeps the mirror's own albedo, and a camera
        // ray that escapes records zero.
        let albedo = features(mirror_to_sky(None), 2, kernel).albedo();
        assert_close("mirror, no sky", albedo.get(5, 5), r, 1e-6);
        let mut b = SceneBuilder::new();
        let m = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }));
        b.shape(Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, -30.0), 0.1).unwrap()), m, &Transform::IDENTITY).unwrap();
        b.allow_no_lights(true);
        b.camera(camera());
        assert_eq!(features(b.build().unwrap(), 2, kernel).albedo().get(0, 0), Rgb::BLACK);
    }
}

#[test]
fn features_are_off_by_default_and_do_not_change_the_image() {
    let s = RenderSettings { width: 16, height: 16, spp: 4, seed: 2, ..Default::default() };
    let scene = Arc::new(sphere_scene());
    let plain = render(Arc::clone(&scene), s.clone()).unwrap();
    assert!(plain.features.is_none());
    let with = render(scene, RenderSettings { features: true, ..s }).unwrap();
    assert_eq!(plain.film.image(), with.film.image());
}

#[test]
fn lane_groups_and_one_lane_record_identical_buffers() {
    // The sums are exact integers, so the order the lanes finish their samples in changes no bit.
    for scene in [sphere_scene, || mirror_scene(Rgb::new(0.9, 0.8, 0.7), Rgb::new(0.1, 0.5, 0.3))] {
        assert_eq!(features(scene(), 6, Kernel::default()), features(scene(), 6, Kernel::Scalar));
    }
}
