//! Light selection, by power and uniform: the selection probabilities sum to 1 and follow their
//! definitions; the directions the `light`/`mixture` strategies draw follow
//! `LightSet::pdf_direction` under both (chi-square); both render the same image within
//! confidence intervals. And emissive meshes: one light per triangle, picked by power (so by
//! area within a mesh) and sampled uniformly by area on the triangle; uniform selection picks
//! the whole mesh as one emitter (Mitsuba's rule), its triangles by area.

use pathtrace::light::{
    AreaLight, Emission, EnvironmentLight, Light, LightSelection, LightSet, LightShape, PointLight, SpotLight,
};
use pathtrace::material::{Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec2, Vec3};
use pathtrace::shape::{Quad, Shape, Sphere, TriangleMesh};
use pathtrace::{render, CameraDesc, RenderSettings, SceneBuilder};
use pathtrace_testkit::{integrate_over_sphere, ChiSquareTest, TestRng};
use std::sync::Arc;

fn lamp(l: f32) -> Emission {
    Emission { radiance: Rgb::splat(l), two_sided: false }
}

/// A quad, a sphere, a dark quad (zero power), a point, a spot and a constant environment.
fn mixed_set() -> LightSet {
    let quad = Quad::new(Vec3::new(-0.5, 1.0, -0.8), Vec3::new(1.5, 0.2, 0.0), Vec3::new(0.0, 0.3, 1.2)).unwrap();
    let dark = Quad::new(Vec3::new(2.0, 0.0, 0.0), Vec3::X, Vec3::Z).unwrap();
    let sphere = Sphere::new(Vec3::new(-1.5, 0.5, 1.0), 0.4).unwrap();
    let area = vec![
        AreaLight::new(LightShape::Quad(quad), Emission { radiance: Rgb::splat(2.0), two_sided: true }),
        AreaLight::new(LightShape::Sphere(sphere), lamp(7.0)),
        AreaLight::new(LightShape::Quad(dark), lamp(0.0)),
    ];
    let point = PointLight { position: Vec3::new(0.0, 3.0, 0.0), intensity: Rgb::splat(5.0) };
    let spot = SpotLight::new(&Transform::translate(Vec3::Y), Rgb::splat(9.0), 30.0, 20.0).unwrap();
    let env = EnvironmentLight::constant(Rgb::new(0.1, 0.2, 0.3));
    let lights =
        area.into_iter().map(Light::Area).chain([Light::Point(point), Light::Spot(spot), Light::Environment(env)]);
    LightSet::new(lights.collect(), 2.0)
}

#[test]
fn selection_probabilities_sum_to_one_in_both_modes() {
    let mut set = mixed_set();
    assert_eq!(set.count(), 6);
    for mode in [LightSelection::Power, LightSelection::Uniform] {
        set.set_selection(mode);
        let sum: f64 = (0..set.count()).map(|i| set.index_pmf(i) as f64).sum();
        assert!((sum - 1.0).abs() < 1e-6, "{mode}: pmfs sum to {sum}");
        assert_eq!(set.index_pmf(2), 0.0, "{mode}: a light without power is never picked");
    }
    // Uniform: the five lights with power, 1/5 each.
    set.set_selection(LightSelection::Uniform);
    for i in [0, 1, 3, 4, 5] {
        assert!((set.index_pmf(i) - 0.2).abs() < 1e-6, "light {i}: {}", set.index_pmf(i));
    }
    // Power: the quad (two-sided, L·A·π·2) against the sphere (L·4πr²·π).
    set.set_selection(LightSelection::Power);
    let pi = std::f32::consts::PI;
    let quad_area = Vec3::new(1.5, 0.2, 0.0).cross(Vec3::new(0.0, 0.3, 1.2)).length();
    let ratio = set.index_pmf(0) / set.index_pmf(1);
    let expected = (2.0 * quad_area * pi * 2.0) / (7.0 * 4.0 * pi * 0.16 * pi);
    assert!((ratio / expected - 1.0).abs() < 1e-4, "{ratio} vs {expected}");
}

#[test]
fn continuous_directions_follow_pdf_direction_in_both_modes() {
    let mut set = mixed_set();
    let p = Vec3::new(0.3, 0.1, -2.0);
    for mode in [LightSelection::Power, LightSelection::Uniform] {
        set.set_selection(mode);
        let pdf = |w: Vec3| set.pdf_direction(p, w) as f64;
        let integral = integrate_over_sphere(pdf, 96, 192);
        assert!((integral - 1.0).abs() < 5e-3, "{mode}: pdf integrates to {integral}");
        let mut rng = TestRng::new(9);
        let test = ChiSquareTest { theta_bins: 20, phi_bins: 40, samples: 400_000, ..Default::default() };
        let outcome = test
            .run(|u| set.sample_continuous(p, rng.next_f32(), Vec2::new(u[0] as f32, u[1] as f32)).map(|s| s.wi), pdf);
        assert!(outcome.passed, "{mode}: chi-square rejected\n{}", outcome.summary());
    }
}

/// A floor lit by a bright lamp, a dim sphere lamp, a point light, a spot light and a sky.
fn lit_floor() -> SceneBuilder {
    let mut b = SceneBuilder::new();
    let floor = b.material(Material::Lambertian(Lambertian { albedo: Rgb::new(0.7, 0.6, 0.5) }));
    let bright = b.emissive(lamp(20.0));
    let dim = b.emissive(lamp(0.5));
    let quad = Quad::new(Vec3::new(-3.0, 0.0, -3.0), Vec3::new(0.0, 0.0, 6.0), Vec3::new(6.0, 0.0, 0.0)).unwrap();
    b.shape(Shape::Quad(quad), floor, &Transform::IDENTITY).unwrap();
    let lamp_quad = Quad::new(Vec3::new(-1.5, 2.0, -0.3), Vec3::new(0.6, 0.0, 0.0), Vec3::new(0.0, 0.0, 0.6)).unwrap();
    b.shape(Shape::Quad(lamp_quad), bright, &Transform::IDENTITY).unwrap();
    b.shape(Shape::Sphere(Sphere::new(Vec3::new(1.2, 0.6, 0.5), 0.3).unwrap()), dim, &Transform::IDENTITY).unwrap();
    b.point_light(PointLight { position: Vec3::new(0.5, 1.5, -1.0), intensity: Rgb::new(2.0, 1.0, 0.5) }).unwrap();
    let spot_at = Transform::rotate_x(90.0).then(&Transform::translate(Vec3::new(0.0, 2.5, 1.0)));
    b.spot_light(SpotLight::new(&spot_at, Rgb::new(1.0, 3.0, 6.0), 35.0, 15.0).unwrap());
    b.environment(EnvironmentLight::constant(Rgb::new(0.05, 0.08, 0.12))).unwrap();
    b.camera(CameraDesc {
        look_from: Vec3::new(0.0, 3.0, -4.0),
        look_at: Vec3::new(0.0, 0.0, 0.3),
        ..Default::default()
    });
    b
}

#[test]
fn power_and_uniform_selection_render_the_same_image() {
    let size = 32;
    let render_with = |mode: LightSelection| {
        let mut scene = lit_floor().build().unwrap();
        scene.lights.set_selection(mode);
        let mut s = RenderSettings { width: size, height: size, spp: 256, seed: 21, ..Default::default() };
        s.path.max_depth = 3;
        render(Arc::new(scene), s).unwrap().film
    };
    let power = render_with(LightSelection::Power);
    let uniform = render_with(LightSelection::Uniform);
    let whole = power.region_estimate(0, 0, size, size).max_z_score(&uniform.region_estimate(0, 0, size, size));
    assert!(whole < 4.0, "image means differ: z = {whole:.2}");
    // 8×8 blocks of 4×4 pixels, 3 channels: 192 comparisons, max |z| < 4.5 (p ≈ 1e-3 under H0).
    let mut worst = 0.0f64;
    for by in 0..8 {
        for bx in 0..8 {
            let (x0, y0) = (bx * 4, by * 4);
            let a = power.region_estimate(x0, y0, x0 + 4, y0 + 4);
            let b = uniform.region_estimate(x0, y0, x0 + 4, y0 + 4);
            worst = worst.max(a.max_z_score(&b));
        }
    }
    assert!(worst < 4.5, "a block differs: z = {worst:.2}");
    let (p, u) = (power.region_estimate(0, 0, size, size), uniform.region_estimate(0, 0, size, size));
    println!("power {:?} ± {:?}\nuniform {:?} ± {:?}", p.mean, p.variance_of_mean, u.mean, u.variance_of_mean);
    assert!(p.mean[0] > 0.05, "the scene is lit");
}

/// A fan of four triangles of very different areas, facing −y, at height 2.
fn fan() -> TriangleMesh {
    let positions = vec![
        Vec3::new(0.0, 2.0, 0.0),
        Vec3::new(0.1, 2.0, 0.0),
        Vec3::new(0.0, 2.0, 0.4),
        Vec3::new(-1.2, 2.0, 0.0),
        Vec3::new(0.0, 2.0, -0.7),
    ];
    // Winding so that each normal points down (towards the reference point below).
    let indices = vec![[0, 2, 1], [0, 3, 2], [0, 4, 3], [0, 1, 4]];
    TriangleMesh { positions, indices, normals: None, uvs: None, tangents: None }
}

#[test]
fn emissive_meshes_are_one_light_per_triangle_picked_by_area_and_sampled_by_area() {
    let mut b = SceneBuilder::new();
    let glow = b.emissive(lamp(3.0));
    assert_eq!(b.mesh(&fan(), glow, &Transform::IDENTITY).unwrap(), 0);
    let scene = b.build().unwrap();
    let lights = &scene.lights;
    assert_eq!(lights.area_lights().count(), 4, "one area light per triangle");
    // Power selection within one mesh is proportional to each triangle's area.
    let total: f32 = lights.area_lights().map(AreaLight::area).sum();
    for (i, l) in lights.area_lights().enumerate() {
        let expected = l.area() / total;
        assert!((lights.selection_pmf(i as u32) - expected).abs() < 1e-6, "triangle {i}");
    }
    // Directions from below: the summed per-triangle r²/(cos·A) densities, weighted by area,
    // equal one uniform-by-area density over the whole fan; chi-square against it.
    let p = Vec3::new(0.1, 0.3, -0.1);
    let pdf = |w: Vec3| lights.pdf_direction(p, w) as f64;
    let integral = integrate_over_sphere(pdf, 96, 192);
    assert!((integral - 1.0).abs() < 5e-3, "pdf integrates to {integral}");
    let mut rng = TestRng::new(3);
    let test =
        ChiSquareTest { theta_bins: 30, phi_bins: 60, samples: 400_000, integration_res: 16, ..Default::default() };
    let outcome = test
        .run(|u| lights.sample_continuous(p, rng.next_f32(), Vec2::new(u[0] as f32, u[1] as f32)).map(|s| s.wi), pdf);
    assert!(outcome.passed, "chi-square rejected\n{}", outcome.summary());
    // Area sampling of the whole mesh: the density towards any point of the fan is
    // r²/(cos θ · A_total), whichever triangle the point lies on.
    for target in [Vec3::new(0.02, 2.0, 0.05), Vec3::new(-0.3, 2.0, -0.1), Vec3::new(-0.1, 2.0, 0.1)] {
        let d = target - p;
        let expected = d.length_squared() / ((d.y / d.length()) * total);
        let got = lights.pdf_direction(p, d.normalize());
        assert!((got / expected - 1.0).abs() < 1e-3, "{target}: {got} vs {expected}");
    }
}

#[test]
fn uniform_selection_picks_an_emissive_mesh_as_one_emitter_and_its_triangles_by_area() {
    let mut b = SceneBuilder::new();
    let glow = b.emissive(lamp(3.0));
    let bright = b.emissive(lamp(50.0));
    b.mesh(&fan(), glow, &Transform::IDENTITY).unwrap();
    let lamp_quad = Quad::new(Vec3::new(2.0, 2.0, 0.0), Vec3::new(0.3, 0.0, 0.0), Vec3::new(0.0, 0.0, 0.3)).unwrap();
    b.shape(Shape::Quad(lamp_quad), bright, &Transform::IDENTITY).unwrap();
    b.point_light(PointLight { position: Vec3::new(0.0, 3.0, 0.0), intensity: Rgb::splat(5.0) }).unwrap();
    let mut scene = b.build().unwrap();
    scene.lights.set_selection(LightSelection::Uniform);
    let lights = &scene.lights;
    // Lights: the fan's four triangles, the quad, the point light. Three emitters: 1/3 each.
    assert_eq!(lights.count(), 6);
    let fan_area: f32 = lights.area_lights().take(4).map(AreaLight::area).sum();
    for (i, l) in lights.area_lights().take(4).enumerate() {
        let expected = l.area() / fan_area / 3.0;
        assert!((lights.index_pmf(i) - expected).abs() < 1e-6, "triangle {i}: {} vs {expected}", lights.index_pmf(i));
    }
    for i in [4, 5] {
        assert!((lights.index_pmf(i) - 1.0 / 3.0).abs() < 1e-6, "light {i}: {}", lights.index_pmf(i));
    }
    let sum: f64 = (0..lights.count()).map(|i| lights.index_pmf(i) as f64).sum();
    assert!((sum - 1.0).abs() < 1e-6, "pmfs sum to {sum}");
}
