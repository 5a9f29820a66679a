//! Analytic scene for the spot light: a spot at height h above a Lambertian plane (albedo a),
//! pointing straight down, with the pinhole camera at the spot's own position looking along its
//! axis. A camera ray leaving at angle θ from the axis is then exactly the spot's emission
//! direction towards the point it hits, at distance h/cos θ, so with direct lighting only the
//! pixel sees
//!
//!   L(θ) = (a/π) · I · f(θ) · cos θ / r² = (a/π) · I · f(θ) · cos³θ / h²,
//!
//! f being Mitsuba 3's falloff (1 inside the beam, linear in θ to 0 at the cutoff). Each pixel's
//! expected value is that closed form averaged over the pixel (box filter) by a 16×16 midpoint
//! rule through the camera's own ray generation; the render must match it within confidence
//! intervals inside the beam, in the falloff and (exactly 0) outside the cutoff.

use pathtrace::light::SpotLight;
use pathtrace::material::{Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec2, Vec3};
use pathtrace::shape::{Quad, Shape};
use pathtrace::{render, Camera, CameraDesc, RenderSettings, SceneBuilder};
use std::sync::Arc;

const H: f32 = 2.0;
const ALBEDO: f32 = 0.7;
const I: [f32; 3] = [30.0, 20.0, 10.0];
const CUTOFF: f32 = 30.0;
const BEAM: f32 = 12.0;
const SIZE: u32 = 48;

fn camera() -> CameraDesc {
    CameraDesc {
        look_from: Vec3::new(0.0, H, 0.0),
        look_at: Vec3::ZERO,
        up: Vec3::Z,
        vfov_degrees: 84.0,
        focal_length: 1.0,
        ..Default::default()
    }
}

/// Mitsuba's falloff as a function of θ (radians), written independently of the engine.
fn falloff(theta: f64) -> f64 {
    let (c, b) = ((CUTOFF as f64).to_radians(), (BEAM as f64).to_radians());
    if theta >= c {
        0.0
    } else if theta <= b {
        1.0
    } else {
        (c - theta) / (c - b)
    }
}

/// Expected pixel value per channel, over the pixel's footprint, and the pixel's class
/// (0 = all inside the beam, 1 = all in the ramp, 2 = all outside the cutoff, 3 = across the
/// beam's edge, 4 = across the cutoff).
fn expected(cam: &Camera, x: u32, y: u32) -> ([f64; 3], usize) {
    let n = 16;
    let mut sum = 0.0;
    let (mut lo, mut hi) = (f64::MAX, 0.0f64);
    for j in 0..n {
        for i in 0..n {
            let jitter = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
            let d = cam.generate_ray(x, y, jitter, pathtrace::math::Vec2::splat(0.5)).dir;
            let cos = (-d.y as f64).clamp(-1.0, 1.0);
            let theta = cos.acos();
            lo = lo.min(theta);
            hi = hi.max(theta);
            sum += falloff(theta) * cos.powi(3) / (H as f64 * H as f64);
        }
    }
    let mean = sum / (n * n) as f64 * ALBEDO as f64 / std::f64::consts::PI;
    let (c, b) = ((CUTOFF as f64).to_radians(), (BEAM as f64).to_radians());
    let class = if hi < b {
        0
    } else if lo > b && hi < c {
        1
    } else if lo > c {
        2
    } else if hi < c {
        3
    } else {
        4
    };
    (I.map(|i| i as f64 * mean), class)
}

#[test]
fn irradiance_under_a_spot_light_matches_the_closed_form() {
    let mut b = SceneBuilder::new();
    let floor = b.material(Material::Lambertian(Lambertian { albedo: Rgb::splat(ALBEDO) }));
    let quad = Quad::new(Vec3::new(-20.0, 0.0, -20.0), Vec3::new(0.0, 0.0, 40.0), Vec3::new(40.0, 0.0, 0.0)).unwrap();
    assert!(quad.normal().y > 0.0, "the floor faces the light");
    b.shape(Shape::Quad(quad), floor, &Transform::IDENTITY).unwrap();
    // Pointing down: local +z → world −y (rotate_x(90°) maps z to −y).
    let to_world = Transform::rotate_x(90.0).then(&Transform::translate(Vec3::new(0.0, H, 0.0)));
    let spot = SpotLight::new(&to_world, Rgb::from_array(I), CUTOFF, BEAM).unwrap();
    b.spot_light(spot);
    b.camera(camera());
    let mut s = RenderSettings { width: SIZE, height: SIZE, spp: 64, seed: 11, ..Default::default() };
    s.path.max_depth = 2;
    let out = render(Arc::new(b.build().unwrap()), s).unwrap();
    let cam = Camera::new(&camera(), SIZE, SIZE).unwrap();
    // With no area light or environment, the direction sampled at the last vertex could only
    // find emission that is not there: it is not traced (the closed form below still holds).
    let rays = out.progress.rays;
    assert_eq!(rays.extension_rays, 0, "{rays:?}");
    assert!(rays.shadow_rays > 0 && rays.camera_rays == (SIZE * SIZE * 64) as u64, "{rays:?}");

    let mut classes = [(0usize, [0.0f64; 3], [0.0f64; 3], [0.0f64; 3]); 5];
    let mut worst = (0.0f64, 0, 0);
    for y in 0..SIZE {
        for x in 0..SIZE {
            let (exp, class) = expected(&cam, x, y);
            let est = out.film.region_estimate(x, y, x + 1, y + 1);
            let c = &mut classes[class];
            c.0 += 1;
            for (k, e) in exp.iter().enumerate() {
                c.1[k] += est.mean[k];
                c.2[k] += est.variance_of_mean[k];
                c.3[k] += e;
            }
            if class == 2 {
                assert_eq!(est.mean, [0.0; 3], "pixel ({x}, {y}) lies outside the cutoff");
                continue;
            }
            // A pixel across the cutoff is lit on a sliver only, which 64 samples may miss
            // altogether (variance estimate 0): those are judged together, below.
            let z = if class == 4 { 0.0 } else { est.max_z_score_against(exp) };
            if z > worst.0 {
                worst = (z, x, y);
            }
        }
    }
    // About 1000 pixels tested: a per-pixel z above 5 has probability ≈ 1e-3 under the null hypothesis.
    assert!(worst.0 < 5.0, "pixel ({}, {}) off by z = {:.2}", worst.1, worst.2, worst.0);
    for (name, c) in ["beam", "falloff", "outside", "beam edge", "cutoff edge"].iter().zip(&classes) {
        assert!(c.0 >= 20, "{name}: only {} pixels; the scene no longer covers this region", c.0);
        for k in 0..3 {
            let (m, e) = (c.1[k] / c.0 as f64, c.3[k] / c.0 as f64);
            let se = c.2[k].sqrt() / c.0 as f64;
            println!("{name} ch{k}: {} px, render {m:.6} ± {se:.2e}, expected {e:.6}", c.0);
            assert!((m - e).abs() <= 4.0 * se + 1e-9 * e, "{name} ch{k}: {m} vs {e} (σ = {se:.2e})");
        }
    }
}
