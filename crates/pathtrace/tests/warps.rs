//! Every warp's pdf integrates to 1 over the sphere, and a chi-square test accepts the warp's
//! samples against its pdf. Light sampling is checked the same way: directions produced by
//! sampling a quad, disk or sphere light (or the environment) from a point must follow
//! `LightSet::pdf_direction`.

use pathtrace::light::{AreaLight, Emission, EnvironmentLight, Light, LightSet, LightShape, PointLight};
use pathtrace::math::{Rgb, Vec2, Vec3};
use pathtrace::sampling::warp;
use pathtrace::shape::{Disk, Quad, Sphere};
use pathtrace_testkit::{integrate_over_sphere, ChiSquareTest, TestRng};

fn v2(u: [f64; 2]) -> Vec2 {
    Vec2::new(u[0] as f32, u[1] as f32)
}

fn check(
    name: &str,
    test: &ChiSquareTest,
    sample: impl FnMut([f64; 2]) -> Option<Vec3>,
    pdf: impl Fn(Vec3) -> f64 + Copy,
) {
    let integral = integrate_over_sphere(pdf, 64, 128);
    assert!((integral - 1.0).abs() < 2e-3, "{name}: pdf integrates to {integral}");
    let outcome = test.run(sample, pdf);
    assert!(outcome.passed, "{name}: chi-square rejected the sampler\n{}", outcome.summary());
}

#[test]
fn uniform_sphere_and_hemisphere() {
    let t = ChiSquareTest::default();
    check("uniform sphere", &t, |u| Some(warp::square_to_uniform_sphere(v2(u))), |_| warp::uniform_sphere_pdf() as f64);
    check(
        "uniform hemisphere",
        &t,
        |u| Some(warp::square_to_uniform_hemisphere(v2(u))),
        |w| warp::uniform_hemisphere_pdf(w) as f64,
    );
}

#[test]
fn cosine_hemisphere() {
    check(
        "cosine hemisphere",
        &ChiSquareTest::default(),
        |u| Some(warp::square_to_cosine_hemisphere(v2(u))),
        |w| warp::cosine_hemisphere_pdf(w) as f64,
    );
}

#[test]
fn uniform_cone() {
    let cos_max = 0.7f32;
    check(
        "cone",
        &ChiSquareTest::default(),
        |u| Some(warp::square_to_uniform_cone(v2(u), cos_max)),
        move |w| warp::uniform_cone_pdf(w, cos_max) as f64,
    );
}

#[test]
fn power_cosine_lobes() {
    for (n, bins) in [(1.0f32, (10, 20)), (10.0, (20, 40)), (80.0, (40, 80))] {
        let t = ChiSquareTest { theta_bins: bins.0, phi_bins: bins.1, ..Default::default() };
        // The pdf in f64 so that its own rounding does not bias the expected counts.
        let pdf = move |w: Vec3| {
            if w.z <= 0.0 {
                0.0
            } else {
                (n as f64 + 1.0) / (2.0 * std::f64::consts::PI) * (w.z as f64).powf(n as f64)
            }
        };
        check(&format!("power cosine n={n}"), &t, |u| Some(warp::square_to_power_cosine(v2(u), n)), pdf);
    }
}

fn light_set(shape: LightShape) -> LightSet {
    LightSet::from_area(vec![AreaLight::new(shape, Emission { radiance: Rgb::splat(1.0), two_sided: true })])
}

#[test]
fn quad_light_directions_follow_r2_over_cos_a() {
    let quad = Quad::new(Vec3::new(-0.5, 1.0, -0.8), Vec3::new(1.5, 0.2, 0.0), Vec3::new(0.0, 0.3, 1.2)).unwrap();
    let lights = light_set(LightShape::Quad(quad));
    let p = Vec3::new(0.1, -0.3, 0.2);
    check(
        "quad light",
        &ChiSquareTest { theta_bins: 40, phi_bins: 80, ..Default::default() },
        |u| lights.sample(p, 0.5, v2(u)).map(|s| s.wi),
        |w| lights.pdf_direction(p, w) as f64,
    );
}

#[test]
fn sphere_light_directions_follow_the_cone_and_area_pdfs() {
    let sphere = Sphere::new(Vec3::new(0.3, 2.0, -0.4), 0.9).unwrap();
    let lights = light_set(LightShape::Sphere(sphere));
    let outside = Vec3::new(0.0, 0.0, 0.0);
    check(
        "sphere light from outside",
        &ChiSquareTest { theta_bins: 40, phi_bins: 80, ..Default::default() },
        |u| lights.sample(outside, 0.5, v2(u)).map(|s| s.wi),
        |w| lights.pdf_direction(outside, w) as f64,
    );
    let inside = Vec3::new(0.5, 2.2, -0.2);
    check(
        "sphere light from inside",
        &ChiSquareTest::default(),
        |u| lights.sample(inside, 0.5, v2(u)).map(|s| s.wi),
        |w| lights.pdf_direction(inside, w) as f64,
    );
}

#[test]
fn disk_light_directions_follow_r2_over_cos_a() {
    // An ellipse (non-uniform axes), tilted, seen from below.
    let disk = Disk::new(Vec3::new(0.2, 1.2, -0.3), Vec3::new(0.9, 0.1, 0.0), Vec3::new(0.0, 0.2, 0.6)).unwrap();
    let lights = light_set(LightShape::Disk(disk));
    let p = Vec3::new(0.1, -0.3, 0.2);
    check(
        "disk light",
        &ChiSquareTest { theta_bins: 40, phi_bins: 80, ..Default::default() },
        |u| lights.sample(p, 0.5, v2(u)).map(|s| s.wi),
        |w| lights.pdf_direction(p, w) as f64,
    );
}

#[test]
fn environment_directions_are_uniform_and_mix_with_area_lights() {
    let env = EnvironmentLight::constant(Rgb::new(0.2, 0.5, 1.0));
    let only = LightSet::new(vec![Light::Environment(env.clone())], 1.0);
    let p = Vec3::new(0.3, 0.1, -2.0);
    check(
        "environment",
        &ChiSquareTest::default(),
        |u| only.sample(p, 0.5, v2(u)).map(|s| s.wi),
        |w| only.pdf_direction(p, w) as f64,
    );
    // A quad, a point light and the environment: directions for the light/mixture strategies skip
    // the point light and follow the summed density of the others.
    let quad = Quad::new(Vec3::new(-0.5, 1.0, -0.8), Vec3::new(1.5, 0.2, 0.0), Vec3::new(0.0, 0.3, 1.2)).unwrap();
    let area = AreaLight::new(LightShape::Quad(quad), Emission { radiance: Rgb::splat(1.0), two_sided: true });
    let point = PointLight { position: Vec3::new(0.0, 3.0, 0.0), intensity: Rgb::splat(5.0) };
    let mixed = LightSet::new(vec![Light::Area(area), Light::Point(point), Light::Environment(env)], 1.5);
    let mut rng = TestRng::new(5);
    check(
        "quad + environment (point light skipped)",
        &ChiSquareTest { theta_bins: 40, phi_bins: 80, ..Default::default() },
        |u| mixed.sample_continuous(p, rng.next_f32(), v2(u)).map(|s| s.wi),
        |w| mixed.pdf_direction(p, w) as f64,
    );
}

#[test]
fn selection_by_power_counts_every_kind_of_light() {
    // Powers: area L·A·π = 1·1·π; point 4π·I = 4π; environment π r²·4π·L = 4π² (r = 1, L = 1).
    let quad = Quad::new(Vec3::ZERO, Vec3::X, Vec3::Z).unwrap();
    let area = AreaLight::new(LightShape::Quad(quad), Emission { radiance: Rgb::WHITE, two_sided: false });
    let point = PointLight { position: Vec3::Y, intensity: Rgb::WHITE };
    let env = EnvironmentLight::constant(Rgb::WHITE);
    let set = LightSet::new(vec![Light::Area(area), Light::Point(point), Light::Environment(env)], 1.0);
    let pi = std::f32::consts::PI;
    let total = pi + 4.0 * pi + 4.0 * pi * pi;
    assert!((set.selection_pmf(0) - pi / total).abs() < 1e-6);
    assert!((set.pdf_environment(Vec3::Z) - 4.0 * pi * pi / total / (4.0 * pi)).abs() < 1e-6);
    // Next-event estimation reaches the point light as a delta sample of probability 4π/total.
    let mut found = false;
    for k in 0..100 {
        if let Some(s) = set.sample(Vec3::new(0.0, -1.0, 0.0), k as f32 / 100.0, Vec2::splat(0.5)) {
            if s.delta {
                found = true;
                assert!((s.pdf - 4.0 * pi / total).abs() < 1e-6);
                assert!((s.dist - 2.0).abs() < 1e-6);
                assert!((s.radiance.r - 0.25).abs() < 1e-6, "I/r² = 1/4");
            }
        }
    }
    assert!(found);
}
