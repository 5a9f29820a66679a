//! Constant environment and point lights against closed forms.
//!
//! - A convex Lambertian sphere of albedo a under a constant environment L: every point sees the
//!   environment over its whole hemisphere (irradiance πL) and light it reflects escapes, so it
//!   shows exactly (a/π)·πL = a·L, for every strategy.
//! - A thin glass sheet in front of the environment: reflected and transmitted paths both escape
//!   to L, so the sheet shows R'·L + T'·L = L (energy conservation through specular vertices).
//! - A point light of intensity I at height h above a Lambertian plane: the plane shows
//!   (a/π)·I·cos θ/r². Only next-event estimation (the `mis` strategy) can see a point light;
//!   the other strategies render it black (documented in docs/scene-format.md).

use pathtrace::integrator::Strategy;
use pathtrace::light::{EnvironmentLight, PointLight};
use pathtrace::material::{Lambertian, Material, ThinDielectric};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::shape::{Quad, Shape, Sphere};
use pathtrace::{render, CameraDesc, RenderSettings, Scene, SceneBuilder};
use std::sync::Arc;

const ALL: [Strategy; 5] = [Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Mis, Strategy::MisBalance];

fn settings(strategy: Strategy, spp: u32) -> RenderSettings {
    let mut s = RenderSettings { width: 16, height: 16, spp, seed: 7, ..Default::default() };
    s.path.strategy = strategy;
    s
}

fn env_scene(material: Material, shape: Shape, env: Rgb) -> Arc<Scene> {
    let mut b = SceneBuilder::new();
    let m = b.material(material);
    b.shape(shape, m, &Transform::IDENTITY).unwrap();
    b.environment(EnvironmentLight::constant(env)).unwrap();
    // Close and narrow: every pixel sees the object.
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 0.0, -3.0),
        look_at: Vec3::ZERO,
        vfov_degrees: 10.0,
        ..Default::default()
    });
    Arc::new(b.build().unwrap())
}

#[test]
fn a_diffuse_sphere_under_a_constant_sky_shows_albedo_times_sky() {
    let (albedo, sky) = (Rgb::new(0.8, 0.5, 0.2), Rgb::new(1.0, 2.0, 4.0));
    let sphere = Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap());
    let scene = env_scene(Material::Lambertian(Lambertian { albedo }), sphere, sky);
    let expected = (albedo * sky).to_array().map(|c| c as f64);
    for strategy in ALL {
        let est = render(scene.clone(), settings(strategy, 128)).unwrap().film.region_estimate(0, 0, 16, 16);
        let z = est.max_z_score_against(expected);
        assert!(z < 4.5, "{strategy}: {:?} vs {expected:?} (z = {z:.2})", est.mean);
        assert!(est.variance_of_mean[2].sqrt() < 0.01 * expected[2], "{strategy}: too noisy to judge");
    }
}

#[test]
fn a_thin_glass_sheet_under_a_constant_sky_conserves_energy() {
    let sky = Rgb::splat(1.5);
    let sheet = Quad::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)).unwrap();
    let glass = Material::ThinDielectric(ThinDielectric { ior: 1.5, tint: Rgb::WHITE });
    let scene = env_scene(glass, Shape::Quad(sheet), sky);
    for strategy in ALL {
        let est = render(scene.clone(), settings(strategy, 16)).unwrap().film.region_estimate(0, 0, 16, 16);
        for c in est.mean {
            assert!((c - 1.5).abs() < 1e-5, "{strategy}: {:?}", est.mean);
        }
    }
}

#[test]
fn a_point_light_over_a_lambertian_plane_follows_the_inverse_square_law() {
    let (albedo, intensity, h) = (0.6f32, Rgb::new(10.0, 20.0, 40.0), 2.0f32);
    let mut b = SceneBuilder::new();
    let floor = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(albedo) }));
    let plane = Quad::new(Vec3::new(-50.0, 0.0, -50.0), Vec3::new(0.0, 0.0, 100.0), Vec3::new(100.0, 0.0, 0.0));
    b.shape(Shape::Quad(plane.unwrap()), floor, &Transform::IDENTITY).unwrap();
    let light = Vec3::new(0.0, h, 0.0);
    b.point_light(PointLight { position: light, intensity }).unwrap();
    // From beside the light, a narrow view of the floor point at horizontal distance h:
    // cos θ = 1/√2 and r² = 2h² there.
    let target = Vec3::new(h, 0.0, 0.0);
    b.camera(CameraDesc {
        look_from: light + Vec3::new(0.0, 0.0, 0.01),
        look_at: target,
        vfov_degrees: 1.0,
        ..Default::default()
    });
    let scene = Arc::new(b.build().unwrap());
    let cos = std::f32::consts::FRAC_1_SQRT_2;
    let expected = (intensity * (albedo / std::f32::consts::PI * cos / (2.0 * h * h))).to_array();
    for strategy in ALL {
        let est = render(scene.clone(), settings(strategy, 4)).unwrap().film.region_estimate(0, 0, 16, 16);
        for (c, e) in est.mean.iter().zip(expected) {
            if strategy.is_mis() {
                assert!((c / e as f64 - 1.0).abs() < 3e-3, "{strategy}: {:?} vs {expected:?}", est.mean);
            } else {
                assert_eq!(*c, 0.0, "{strategy} cannot see a point light");
            }
        }
    }
}
