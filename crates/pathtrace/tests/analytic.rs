//! Analytic scene: a small spherical light (radius r, radiance Le) at the centre of a large
//! Lambertian sphere (radius R, albedo a). With direct lighting only (max depth 2), every wall
//! point faces the light head-on and receives irradiance π·Le·(r/R)² (a sphere source subtends a
//! cone of sin²α = (r/R)²), so its outgoing radiance is (a/π)·π·Le·(r/R)² = a·Le·(r/R)².

use pathtrace::integrator::Strategy;
use pathtrace::light::Emission;
use pathtrace::material::{Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::shape::{Shape, Sphere};
use pathtrace::{render, CameraDesc, RenderSettings, SceneBuilder};
use std::sync::Arc;

const R_LIGHT: f32 = 2.0;
const R_ROOM: f32 = 10.0;
const LE: f32 = 40.0;
const ALBEDO: f32 = 0.8;

fn render_direct(strategy: Strategy) -> pathtrace::film::RegionEstimate {
    let mut b = SceneBuilder::new();
    let light = b.emissive(Emission { radiance: Rgb::splat(LE), two_sided: false });
    let wall = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(ALBEDO) }));
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, R_LIGHT).unwrap()), light, &Transform::IDENTITY).unwrap();
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, R_ROOM).unwrap()), wall, &Transform::IDENTITY).unwrap();
    // Camera beside the light, looking away from it: every pixel sees the wall.
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 0.0, 5.0),
        look_at: Vec3::new(0.0, 0.0, 10.0),
        up: Vec3::Y,
        vfov_degrees: 30.0,
        focal_length: 1.0,
        ..Default::default()
    });
    let mut s = RenderSettings { width: 32, height: 32, spp: 256, seed: 3, ..Default::default() };
    s.path.strategy = strategy;
    s.path.max_depth = 2;
    let out = render(Arc::new(b.build().unwrap()), s).unwrap();
    out.film.region_estimate(0, 0, 32, 32)
}

#[test]
fn direct_lighting_from_a_sphere_light_matches_the_closed_form() {
    let expected = (ALBEDO * LE * (R_LIGHT / R_ROOM).powi(2)) as f64;
    // The light strategy is exact here too: with max depth 2 there is no indirect light to lose.
    for strategy in [Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Mis, Strategy::MisBalance] {
        let est = render_direct(strategy);
        let z = est.max_z_score_against([expected; 3]);
        assert!(z < 4.5, "{strategy}: {:?} vs {expected} (z = {z:.2})", est.mean);
        assert!(est.variance_of_mean[0].sqrt() < 0.02 * expected, "{strategy}: too noisy to judge");
    }
}
