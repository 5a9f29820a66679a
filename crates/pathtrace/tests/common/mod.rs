//! Scenes shared by several integration tests.

use pathtrace::light::Emission;
use pathtrace::material::{Dielectric, Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::shape::{Quad, Shape, Sphere};
use pathtrace::{CameraDesc, Scene, SceneBuilder};
use std::sync::Arc;

/// A glass sphere on a diffuse floor under a square lamp of side `lamp_side` and the given
/// radiance, 4 units up: refraction, caustics and uneven noise in a few lines.
pub fn glass_sphere_under_lamp(lamp_side: f32, radiance: f32) -> Arc<Scene> {
    let mut b = SceneBuilder::new();
    let white = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(0.7) }));
    let glass = b.material(Material::Dielectric(Dielectric { ior: 1.5, tint: Rgb::WHITE }));
    let light = b.emissive(Emission { radiance: Rgb::splat(radiance), two_sided: false });
    let floor = Quad::new(Vec3::new(-5.0, 0.0, -5.0), Vec3::new(0.0, 0.0, 10.0), Vec3::new(10.0, 0.0, 0.0)).unwrap();
    b.shape(Shape::Quad(floor), white, &Transform::IDENTITY).unwrap();
    b.shape(Shape::Sphere(Sphere::new(Vec3::new(0.0, 1.0, 0.0), 1.0).unwrap()), glass, &Transform::IDENTITY).unwrap();
    let h = lamp_side / 2.0;
    let lamp =
        Quad::new(Vec3::new(-h, 4.0, -h), Vec3::new(lamp_side, 0.0, 0.0), Vec3::new(0.0, 0.0, lamp_side)).unwrap();
    b.shape(Shape::Quad(lamp), light, &Transform::IDENTITY).unwrap();
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 2.0, -6.0),
        look_at: Vec3::new(0.0, 1.0, 0.0),
        ..Default::default()
    });
    Arc::new(b.build().unwrap())
}
