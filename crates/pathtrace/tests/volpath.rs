//! Volumetric path tracing end to end (integrator/media.rs in the one estimator): closed forms
//! that a wrong free-flight weight, transmittance, phase weight, MIS weight or medium
//! bookkeeping would break.
//!
//! - Furnace: an albedo-1 medium (any σt, chromatic, any phase function) inside a null-bounded
//!   or glass-bounded sphere under a uniform sky scatters without loss, so every pixel shows
//!   exactly the sky's radiance.
//! - Slab: an absorbing slab between an orthographic camera and the sky shows L·exp(−σt·d);
//!   a floor lit by a directional light through the slab and seen through it shows
//!   (ρ/π)·E·exp(−2σt·d) (the shadow ray's transmittance through null boundaries).
//! - Random media: no NaN, and an albedo < 1 medium never makes the sky brighter.

// Channels index several arrays at once (mean, variance, expectation).
#![allow(clippy::needless_range_loop)]

use pathtrace::integrator::Strategy;
use pathtrace::light::{DirectionalLight, EnvironmentLight, PointLight};
use pathtrace::material::{Dielectric, Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec3};
use pathtrace::medium::{HomogeneousMedium, MediumId, PhaseFunction};
use pathtrace::shape::{Quad, Shape, Sphere};
use pathtrace::{render, CameraDesc, Lens, RenderSettings, SceneBuilder};
use std::sync::Arc;

const SKY: Rgb = Rgb { r: 0.8, g: 0.5, b: 1.2 };

fn settings(size: u32, spp: u32, strategy: Strategy) -> RenderSettings {
    let mut s = RenderSettings { width: size, height: size, spp, seed: 11, ..Default::default() };
    s.path.strategy = strategy;
    s.path.max_depth = -1;
    s
}

/// A sphere of radius 1 at the origin filled with `medium`, bounded by `boundary`, under the
/// sky; the camera looks at it from outside (or sits inside it, `inside`).
fn sphere_of(medium: HomogeneousMedium, boundary: Material, inside: bool) -> pathtrace::Scene {
    let mut b = SceneBuilder::new();
    let m = b.medium(medium).unwrap();
    let wall = b.material(boundary);
    let wall = b.bounded_material(wall, Some(m), None).unwrap();
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap()), wall, &Transform::IDENTITY).unwrap();
    b.environment(EnvironmentLight::constant(SKY)).unwrap();
    let (from, fov) = if inside { (Vec3::new(0.1, -0.2, 0.3), 90.0) } else { (Vec3::new(0.0, 0.0, 3.5), 35.0) };
    b.camera(CameraDesc {
        look_from: from,
        look_at: Vec3::new(0.0, 0.1, 0.0),
        up: Vec3::Y,
        vfov_degrees: fov,
        focal_length: 1.0,
        lens: Lens::Pinhole,
    });
    if inside {
        b.camera_medium(Some(m)).unwrap();
    }
    b.build().unwrap()
}

fn check_furnace(scene: pathtrace::Scene, strategy: Strategy, what: &str) {
    let out = render(Arc::new(scene), settings(16, 512, strategy)).unwrap();
    assert_eq!(out.progress.dropped_samples, 0, "{what}: non-finite samples");
    let est = out.film.region_estimate(0, 0, 16, 16);
    let expected = SKY.to_array().map(f64::from);
    let z = est.max_z_score_against(expected);
    assert!(z < 4.5, "{what} ({strategy}): mean {:?}, the sky is {expected:?} (z = {z:.2})", est.mean);
    for c in 0..3 {
        assert!(
            est.variance_of_mean[c].sqrt() < 0.01 * expected[c],
            "{what}: too noisy to judge ({:?} ± {:?})",
            est.mean,
            est.variance_of_mean.map(f64::sqrt)
        );
    }
}

#[test]
fn albedo_one_media_in_null_spheres_show_exactly_the_sky() {
    let phases = [
        PhaseFunction::Isotropic,
        PhaseFunction::HenyeyGreenstein { g: 0.7 },
        PhaseFunction::HenyeyGreenstein { g: -0.4 },
    ];
    for phase in phases {
        // Chromatic extinction: the channels' optical depths across the sphere are 1.2, 4 and 10.
        let medium = HomogeneousMedium::from_extinction(Rgb::new(0.6, 2.0, 5.0), Rgb::splat(1.0), 1.0, phase);
        for strategy in [Strategy::Mis, Strategy::Bsdf] {
            check_furnace(sphere_of(medium, Material::Null, false), strategy, &format!("{phase:?}, outside"));
        }
        check_furnace(sphere_of(medium, Material::Null, true), Strategy::Mis, &format!("{phase:?}, camera inside"));
    }
}

#[test]
fn albedo_one_medium_in_a_glass_sphere_shows_exactly_the_sky() {
    let medium = HomogeneousMedium::from_extinction(
        Rgb::new(1.0, 3.0, 0.5),
        Rgb::splat(1.0),
        1.0,
        PhaseFunction::HenyeyGreenstein { g: 0.5 },
    );
    let glass = Material::Dielectric(Dielectric { ior: 1.5, tint: Rgb::splat(1.0) });
    check_furnace(sphere_of(medium, glass, false), Strategy::Mis, "glass sphere");
}

/// A null-bounded slab z ∈ [0, d] filling the view, between an orthographic camera above and
/// (optionally) a Lambertian floor below, under the sky or a directional light.
fn slab_scene(sigma_t: Rgb, albedo: Rgb, d: f32, floor: Option<f32>) -> pathtrace::Scene {
    let mut b = SceneBuilder::new();
    let m = b.medium(HomogeneousMedium::from_extinction(sigma_t, albedo, 1.0, PhaseFunction::Isotropic)).unwrap();
    let null = b.material(Material::Null);
    let null = b.bounded_material(null, Some(m), None).unwrap();
    b.add_box(Vec3::new(-50.0, -50.0, 0.0), Vec3::new(50.0, 50.0, d), null, &Transform::IDENTITY).unwrap();
    match floor {
        Some(rho) => {
            let grey = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(rho) }));
            let quad = Quad::new(Vec3::new(-40.0, -40.0, -1.0), Vec3::new(80.0, 0.0, 0.0), Vec3::new(0.0, 80.0, 0.0));
            b.shape(Shape::Quad(quad.unwrap()), grey, &Transform::IDENTITY).unwrap();
            b.directional_light(DirectionalLight::new(Vec3::new(0.0, 0.0, -1.0), SKY).unwrap());
        }
        None => b.environment(EnvironmentLight::constant(SKY)).unwrap(),
    }
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 0.0, d + 2.0),
        look_at: Vec3::new(0.0, 0.0, 0.0),
        up: Vec3::Y,
        vfov_degrees: 40.0,
        focal_length: 1.0,
        lens: Lens::Orthographic { height: 2.0 },
    });
    b.build().unwrap()
}

#[test]
fn an_absorbing_slab_transmits_exp_minus_sigma_t_d() {
    let sigma_t = Rgb::new(0.3, 1.0, 2.0);
    let d = 0.8;
    let out = render(Arc::new(slab_scene(sigma_t, Rgb::BLACK, d, None)), settings(8, 4096, Strategy::Mis)).unwrap();
    let est = out.film.region_estimate(0, 0, 8, 8);
    let expected: [f64; 3] = std::array::from_fn(|c| {
        f64::from(SKY.to_array()[c]) * (-f64::from(sigma_t.to_array()[c]) * f64::from(d)).exp()
    });
    for c in 0..3 {
        let rel = est.mean[c] / expected[c] - 1.0;
        assert!(rel.abs() < 0.02, "channel {c}: {} vs L·exp(−σt·d) = {}", est.mean[c], expected[c]);
    }
    assert!(est.max_z_score_against(expected) < 4.5, "{:?} vs {expected:?}", est.mean);
}

#[test]
fn shadow_rays_through_a_null_bounded_slab_carry_its_transmittance() {
    let sigma_t = Rgb::new(0.2, 0.7, 1.5);
    let (d, rho) = (0.5, 0.6);
    let scene = slab_scene(sigma_t, Rgb::BLACK, d, Some(rho));
    let out = render(Arc::new(scene), settings(8, 1024, Strategy::Mis)).unwrap();
    let est = out.film.region_estimate(0, 0, 8, 8);
    // Light straight down through the slab onto the floor, then straight up through it again.
    let expected: [f64; 3] = std::array::from_fn(|c| {
        let tr = (-f64::from(sigma_t.to_array()[c]) * f64::from(d)).exp();
        f64::from(rho) / std::f64::consts::PI * f64::from(SKY.to_array()[c]) * tr * tr
    });
    for c in 0..3 {
        let rel = est.mean[c] / expected[c] - 1.0;
        assert!(rel.abs() < 0.01, "channel {c}: {} vs (ρ/π)·E·exp(−2σt·d) = {}", est.mean[c], expected[c]);
    }
}

/// With media but no `null` surface, shadow rays take the group occlusion walk and carry the
/// transmittance of the medium they start in (`path.rs::add_transmitted_light`): a camera inside
/// an absorbing medium that fills space sees a floor lit by a point light straight above, through
/// the medium on the way down and on the way up.
#[test]
fn shadow_rays_inside_a_medium_without_boundaries_carry_its_transmittance() {
    let sigma_t = Rgb::new(0.2, 0.5, 0.9);
    let (rho, light_height, camera_height) = (0.6f32, 1.5f32, 1.0f32);
    let mut b = SceneBuilder::new();
    let m = b.medium(HomogeneousMedium::from_extinction(sigma_t, Rgb::BLACK, 1.0, PhaseFunction::Isotropic)).unwrap();
    let grey = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(rho) }));
    let quad = Quad::new(Vec3::new(-40.0, -40.0, 0.0), Vec3::new(80.0, 0.0, 0.0), Vec3::new(0.0, 80.0, 0.0));
    b.shape(Shape::Quad(quad.unwrap()), grey, &Transform::IDENTITY).unwrap();
    b.point_light(PointLight { position: Vec3::new(0.0, 0.0, light_height), intensity: SKY }).unwrap();
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 0.0, camera_height),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        vfov_degrees: 40.0,
        focal_length: 1.0,
        // A view 0.01 across: every pixel sees the floor straight below the light.
        lens: Lens::Orthographic { height: 0.01 },
    });
    b.camera_medium(Some(m)).unwrap();
    let out = render(Arc::new(b.build().unwrap()), settings(8, 1024, Strategy::Mis)).unwrap();
    let est = out.film.region_estimate(0, 0, 8, 8);
    // (ρ/π)·I/h²·exp(−σt·h) from the light, times exp(−σt·c) on the way to the camera.
    let expected: [f64; 3] = std::array::from_fn(|c| {
        let s = f64::from(sigma_t.to_array()[c]);
        let (h, cam) = (f64::from(light_height), f64::from(camera_height));
        f64::from(rho) / std::f64::consts::PI * f64::from(SKY.to_array()[c]) / (h * h) * (-s * (h + cam)).exp()
    });
    for c in 0..3 {
        let rel = est.mean[c] / expected[c] - 1.0;
        assert!(rel.abs() < 0.02, "channel {c}: {} vs (ρ/π)·I/h²·exp(−σt·(h + c)) = {}", est.mean[c], expected[c]);
    }
}

/// A small deterministic generator for the random media below.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

#[test]
fn random_media_give_no_nan_and_never_brighten_the_sky() {
    let mut rng = Lcg(19);
    for k in 0..12 {
        // Some channels clear (σt = 0), some very dense; albedos below 1; any g.
        let sigma_t =
            Rgb::from_array(std::array::from_fn(|_| if rng.next() < 0.2 { 0.0 } else { 30.0 * rng.next().powi(2) }));
        let albedo = Rgb::from_array(std::array::from_fn(|_| 0.98 * rng.next()));
        let g = 1.9 * rng.next() - 0.95;
        let phase = if k % 3 == 0 { PhaseFunction::Isotropic } else { PhaseFunction::HenyeyGreenstein { g } };
        let medium = HomogeneousMedium::from_extinction(sigma_t, albedo, 0.5 + rng.next(), phase);
        let boundary = if k % 2 == 0 {
            Material::Null
        } else {
            Material::Dielectric(Dielectric { ior: 1.33, tint: Rgb::splat(1.0) })
        };
        // The camera goes inside null spheres only: inside glass the radiance is η² times the
        // sky's (radiance compression), which the bound below is not about.
        let inside = k % 4 == 2;
        let out = render(Arc::new(sphere_of(medium, boundary, inside)), settings(8, 64, Strategy::Mis)).unwrap();
        assert_eq!(out.progress.dropped_samples, 0, "medium {k}: {medium:?} gave non-finite samples");
        let est = out.film.region_estimate(0, 0, 8, 8);
        for c in 0..3 {
            let sky = f64::from(SKY.to_array()[c]);
            let bound = sky + 4.5 * est.variance_of_mean[c].sqrt();
            assert!(est.mean[c].is_finite() && est.mean[c] <= bound, "medium {k} ({medium:?}): {:?}", est.mean);
        }
    }
}

#[test]
fn media_and_unknown_ids_are_checked_when_added() {
    let mut b = SceneBuilder::new();
    let bad =
        HomogeneousMedium::from_extinction(Rgb::new(-1.0, 1.0, 1.0), Rgb::splat(0.5), 1.0, PhaseFunction::Isotropic);
    assert!(b.medium(bad).unwrap_err().to_string().contains("≥ 0"));
    let bad_g = HomogeneousMedium::from_extinction(
        Rgb::splat(1.0),
        Rgb::splat(0.5),
        1.0,
        PhaseFunction::HenyeyGreenstein { g: 1.0 },
    );
    assert!(b.medium(bad_g).is_err());
    let m = b.material(Material::Null);
    assert!(b.bounded_material(m, Some(MediumId(3)), None).is_err());
    assert!(b.camera_medium(Some(MediumId(0))).is_err());
}
