//! First-hit AOVs against a scene whose answers are known in closed form: a unit Lambertian
//! sphere seen head-on from distance 5 (depth 4 at the centre, normal +z, albedo its colour).

use pathtrace::integrator::first_hit_aovs;
use pathtrace::light::Emission;
use pathtrace::material::{Lambertian, Material, Mirror};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::shape::{Shape, Sphere};
use pathtrace::{CameraDesc, Scene, SceneBuilder};

const SIZE: u32 = 33;

fn sphere_scene(material: Material) -> Scene {
    let mut b = SceneBuilder::new();
    let m = b.material(material);
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap()), m, &Transform::IDENTITY).unwrap();
    // A light far behind the camera, only so the scene is valid; AOVs ignore lighting.
    let lamp = b.emissive(Emission { radiance: Rgb::splat(1.0), two_sided: true });
    b.shape(Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, 50.0), 0.5).unwrap()), lamp, &Transform::IDENTITY).unwrap();
    b.camera(camera());
    b.build().unwrap()
}

fn camera() -> CameraDesc {
    CameraDesc {
        look_from: Vec3::new(0.0, 0.0, 5.0),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        vfov_degrees: 30.0,
        focal_length: 1.0,
        ..Default::default()
    }
}

fn close(a: Rgb, b: Rgb, tol: f32) -> bool {
    (a.r - b.r).abs() <= tol && (a.g - b.g).abs() <= tol && (a.b - b.b).abs() <= tol
}

#[test]
fn centre_pixel_sees_the_sphere_head_on() {
    let colour = Rgb::new(0.2, 0.4, 0.6);
    let scene = sphere_scene(Material::Lambertian(Lambertian { albedo: colour }));
    let aovs = first_hit_aovs(&scene, &camera(), SIZE, SIZE).unwrap();
    let c = SIZE / 2;
    assert!(close(aovs.depth.get(c, c), Rgb::splat(4.0), 1e-4), "{:?}", aovs.depth.get(c, c));
    assert!(close(aovs.normal.get(c, c), Rgb::new(0.5, 0.5, 1.0), 1e-4), "{:?}", aovs.normal.get(c, c));
    // Cosine-weighted sampling makes every Lambertian sample weigh exactly the albedo.
    assert!(close(aovs.albedo.get(c, c), colour, 1e-6), "{:?}", aovs.albedo.get(c, c));
}

#[test]
fn missed_pixels_are_black_and_depth_follows_the_ray_sphere_distance() {
    let scene = sphere_scene(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }));
    let aovs = first_hit_aovs(&scene, &camera(), SIZE, SIZE).unwrap();
    // A corner ray passes the sphere (half-angle of the view ≈ 21° > asin(1/5) ≈ 11.5°).
    for img in [&aovs.albedo, &aovs.normal, &aovs.depth] {
        assert_eq!(img.get(0, 0), Rgb::BLACK);
    }
    // Every hit pixel: depth t solves |o + t·d| = 1 for the pixel-centre ray, and the normal
    // there is the unit hit point.
    let cam = pathtrace::Camera::new(&camera(), SIZE, SIZE).unwrap();
    let mut hits = 0;
    for y in 0..SIZE {
        for x in 0..SIZE {
            let ray = cam.generate_ray(x, y, pathtrace::math::Vec2::splat(0.5), pathtrace::math::Vec2::splat(0.5));
            let b = ray.origin.dot(ray.dir);
            let disc = b * b - (ray.origin.length_squared() - 1.0);
            let depth = aovs.depth.get(x, y).r;
            if disc <= 0.0 {
                assert_eq!(depth, 0.0, "({x},{y}) should miss");
                continue;
            }
            hits += 1;
            let t = -b - disc.sqrt();
            assert!((depth - t).abs() < 1e-3, "({x},{y}): depth {depth}, expected {t}");
            let p = ray.origin + t * ray.dir;
            let n = aovs.normal.get(x, y);
            let decoded = Vec3::new(n.r, n.g, n.b) * 2.0 - Vec3::ONE;
            assert!((decoded - p).length() < 1e-2, "({x},{y}): normal {decoded} vs {p}");
        }
    }
    assert!(hits > 50, "the sphere should cover many pixels, saw {hits}");
}

#[test]
fn mirror_albedo_is_its_reflectance() {
    let r = Rgb::new(0.9, 0.7, 0.5);
    let scene = sphere_scene(Material::Mirror(Mirror { reflectance: r }));
    let aovs = first_hit_aovs(&scene, &camera(), SIZE, SIZE).unwrap();
    let c = SIZE / 2;
    assert!(close(aovs.albedo.get(c, c), r, 1e-5), "{:?}", aovs.albedo.get(c, c));
}

#[test]
fn a_bad_camera_is_an_error_not_a_panic() {
    let scene = sphere_scene(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.5) }));
    let bad = CameraDesc { look_at: camera().look_from, ..camera() };
    assert!(first_hit_aovs(&scene, &bad, 8, 8).is_err());
}
