//! Environment maps: the sampler against its own pdf, the pdf against the image, a furnace, and
//! MIS against either strategy alone. The HDR images are made here (a sky gradient plus a small
//! bright sun), so no image file is needed.
//!
//! - Chi-square: directions from `EnvMap::sample` follow `EnvMap::pdf`, which integrates to 1.
//! - Importance: the pdf is proportional to luminance (up to the piecewise-constant
//!   approximation), so luminance/pdf varies little over samples, while under uniform sampling
//!   the sun makes it vary enormously; and both estimate the same ∫ L dω.
//! - Furnace: a convex Lambertian sphere of albedo a under a map that is L everywhere shows a·L.
//! - MIS: a glossy sphere under the sun-and-sky map, relative MSE against a high-spp reference.
//! - MIS compensation: the density of the luminance above the map's mean passes the same
//!   chi-square test, is zero where the map is dim, lowers the variance of an MIS estimate of
//!   irradiance without moving its mean, and renders agree with an estimator that keeps the
//!   complete density.

use pathtrace::integrator::Strategy;
use pathtrace::light::{EnvMap, EnvSampling, EnvironmentLight, Light, LightSet};
use pathtrace::material::{Glossy, Lambertian, Material};
use pathtrace::math::{Rgb, Transform, Vec2, Vec3};
use pathtrace::metrics::relative_mse;
use pathtrace::shape::{Shape, Sphere};
use pathtrace::{render, CameraDesc, RenderSettings, Scene, SceneBuilder};
use pathtrace_testkit::{chi_square_p_value, TestRng};
use std::sync::Arc;

/// A sky fading from blue at the zenith to dark at the nadir, plus a Gaussian sun of standard
/// deviation `sun_radius` texels at (`sun_x`, `sun_y`) whose peak is `sun_peak` times white.
fn sun_and_sky(w: u32, h: u32, (sun_x, sun_y): (f32, f32), sun_radius: f32, sun_peak: f32) -> Vec<Rgb> {
    let mut pixels = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let up = 1.0 - y as f32 / (h - 1) as f32;
            let sky = Rgb::new(0.2 + 0.3 * up, 0.3 + 0.4 * up, 0.5 + 0.7 * up) * up.max(0.05);
            let d2 = (x as f32 - sun_x).powi(2) + (y as f32 - sun_y).powi(2);
            let sun = Rgb::new(1.0, 0.9, 0.7) * sun_peak * (-0.5 * d2 / (sun_radius * sun_radius)).exp();
            pixels.push(sky + sun);
        }
    }
    pixels
}

/// 64 × 32 texels, a sun of σ = 1.5 texels about 1000 times brighter than the sky.
fn sky_map(to_world: Transform) -> EnvMap {
    EnvMap::new(64, 32, sun_and_sky(64, 32, (20.0, 9.0), 1.5, 800.0), 1.0, to_world).unwrap()
}

fn v2(u: [f64; 2]) -> Vec2 {
    Vec2::new(u[0] as f32, u[1] as f32)
}

/// ∫ f dω over the sphere by the midpoint rule on `n × 2n` cells equal in cos θ and φ (about
/// +z, unrelated to the map's axes). The adaptive quadrature of the testkit spends its budget on
/// the jumps of a piecewise-constant pdf, so a plain fine grid is used instead.
fn midpoint_over_sphere(f: impl Fn(Vec3) -> f64, n: usize) -> f64 {
    let (nz, nphi) = (n, 2 * n);
    let cell = 4.0 * std::f64::consts::PI / (nz * nphi) as f64;
    let mut total = 0.0;
    for i in 0..nz {
        let z = -1.0 + 2.0 * (i as f64 + 0.5) / nz as f64;
        let r = (1.0 - z * z).sqrt();
        for j in 0..nphi {
            let phi = std::f64::consts::TAU * (j as f64 + 0.5) / nphi as f64;
            total += f(Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, z as f32));
        }
    }
    total * cell
}

/// The local direction of lat-long coordinates (u, v), written out from Mitsuba's convention
/// independently of the engine: d = (sin θ sin φ, cos θ, −sin θ cos φ), φ = 2πu, θ = πv.
fn lat_long(u: f64, v: f64) -> Vec3 {
    let (st, ct) = (std::f64::consts::PI * v).sin_cos();
    let (sp, cp) = (std::f64::consts::TAU * u).sin_cos();
    Vec3::new((st * sp) as f32, ct as f32, (-st * cp) as f32)
}

/// Chi-square test of `map.sample_with` against `map.pdf_with` under `how` (map of `w × h` texels, identity
/// `to_world`) on lat-long bins of 2 texel columns by 1 texel row, their u edges shifted by half
/// a texel so that they follow the cells of the sampling distribution; the expected count of a
/// bin integrates pdf · dω = pdf · 2π² sin θ du dv by the midpoint rule on 8 × 8 points per cell,
/// exact for a density constant per cell in (u, v). Returns the p-value.
fn lat_long_chi_square(map: &EnvMap, how: EnvSampling, w: usize, h: usize, samples: usize) -> f64 {
    let (bu, bv) = (w / 2, h - 1);
    let shift = 0.5 / w as f64;
    let bin_of = |d: Vec3| {
        let u = (d.x as f64).atan2(-d.z as f64) / std::f64::consts::TAU - shift;
        let v = (d.y as f64).clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
        let i = ((u - u.floor()) * bu as f64) as usize % bu;
        let j = ((v * bv as f64) as usize).min(bv - 1);
        j * bu + i
    };
    let mut observed = vec![0.0f64; bu * bv];
    let mut rng = TestRng::new(17);
    for _ in 0..samples {
        let (d, pdf) = map.sample_with(v2(rng.next_2d()), how);
        if pdf > 0.0 {
            observed[bin_of(d)] += 1.0;
        }
    }
    let sub = 16;
    let (du, dv) = (1.0 / (bu * sub) as f64, 1.0 / (bv * 8) as f64);
    let mut expected = vec![0.0f64; bu * bv];
    for j in 0..bv {
        for i in 0..bu {
            let mut p = 0.0;
            for a in 0..sub {
                for b in 0..8 {
                    let u = shift + (i * sub + a) as f64 * du + 0.5 * du;
                    let v = (j * 8 + b) as f64 * dv + 0.5 * dv;
                    let sin_theta = (std::f64::consts::PI * v).sin();
                    let jac = 2.0 * std::f64::consts::PI.powi(2) * sin_theta;
                    p += map.pdf_with(lat_long(u, v), how) as f64 * jac * du * dv;
                }
            }
            expected[j * bu + i] = p * samples as f64;
        }
    }
    let total: f64 = expected.iter().sum::<f64>() / samples as f64;
    assert!((total - 1.0).abs() < 1e-3, "the pdf integrates to {total} over the lat-long cells");
    // Pool bins expecting fewer than 5 samples into one.
    let (mut stat, mut dof, mut pool_o, mut pool_e) = (0.0, 0usize, 0.0, 0.0);
    for (o, e) in observed.iter().zip(&expected) {
        if *e < 5.0 {
            pool_o += o;
            pool_e += e;
        } else {
            stat += (o - e).powi(2) / e;
            dof += 1;
        }
    }
    if pool_e >= 5.0 {
        stat += (pool_o - pool_e).powi(2) / pool_e;
        dof += 1;
    }
    chi_square_p_value(stat, dof - 1)
}

#[test]
fn samples_follow_the_pdf_and_the_pdf_integrates_to_one() {
    let (w, h) = (64, 32);
    let map = sky_map(Transform::IDENTITY);
    let p = lat_long_chi_square(&map, EnvSampling::Complete, w, h, 1_000_000);
    assert!(p > 0.01, "chi-square rejected the sampler (p = {p})");
    // Rotated (and mirrored, as Mitsuba's matpreview is): integrates to 1 in world directions,
    // and every sample's own pdf is the pdf of its direction.
    let mirror = Transform::scale(Vec3::new(-1.0, 1.0, 1.0)).unwrap();
    let tilted = Transform::rotate_x(30.0).then(&Transform::rotate_y(-110.0)).then(&mirror);
    for (name, t) in [("identity", Transform::IDENTITY), ("rotated", tilted)] {
        let map = sky_map(t);
        let integral = midpoint_over_sphere(|d| map.pdf(d) as f64, 1024);
        assert!((integral - 1.0).abs() < 5e-3, "{name}: pdf integrates to {integral}");
        let mut rng = TestRng::new(3);
        for _ in 0..2000 {
            let (d, pdf) = map.sample(v2(rng.next_2d()));
            assert!((pdf - map.pdf(d)).abs() <= 2e-3 * pdf, "{name}: {pdf} vs {}", map.pdf(d));
        }
    }
}

#[test]
fn compensated_samples_follow_their_pdf_which_leaves_out_the_sky_below_the_mean() {
    let (w, h) = (64, 32);
    let map = sky_map(Transform::IDENTITY);
    let p = lat_long_chi_square(&map, EnvSampling::Compensated, w, h, 1_000_000);
    assert!(p > 0.01, "chi-square rejected the compensated sampler (p = {p})");
    let tilted = Transform::rotate_x(30.0).then(&Transform::rotate_y(-110.0));
    let map = sky_map(tilted);
    let pdf = |d: Vec3| map.pdf_with(d, EnvSampling::Compensated);
    let integral = midpoint_over_sphere(|d| pdf(d) as f64, 1024);
    assert!((integral - 1.0).abs() < 5e-3, "the compensated pdf integrates to {integral}");
    let mut rng = TestRng::new(5);
    for _ in 0..2000 {
        let (d, p) = map.sample_with(v2(rng.next_2d()), EnvSampling::Compensated);
        assert!((p - pdf(d)).abs() <= 2e-3 * p, "{p} vs {}", pdf(d));
    }
    // The sun holds most of the light, so the whole sky is below the mean: the compensated
    // density is zero there (the complete one is not) and larger on the sun.
    let to_world = |u: f64, v: f64| tilted.vector(lat_long(u, v));
    let (sky, sun) = (to_world(0.8, 0.2), to_world((20.0 + 0.5) / w as f64, 9.0 / (h - 1) as f64));
    assert_eq!(pdf(sky), 0.0);
    assert!(map.pdf(sky) > 0.0);
    assert!(pdf(sun) > map.pdf(sun), "{} vs {}", pdf(sun), map.pdf(sun));
}

#[test]
fn a_map_with_nothing_above_its_mean_keeps_the_complete_density() {
    let map = EnvMap::new(8, 5, vec![Rgb::new(1.0, 2.0, 4.0); 40], 1.0, Transform::rotate_x(70.0)).unwrap();
    let mut rng = TestRng::new(9);
    for _ in 0..200 {
        let u = v2(rng.next_2d());
        let (complete, compensated) = (map.sample(u), map.sample_with(u, EnvSampling::Compensated));
        assert_eq!(complete.0.to_array(), compensated.0.to_array());
        assert_eq!(complete.1, compensated.1);
    }
}

/// Mean and variance of one-sample-per-technique MIS estimates (power heuristic) of the
/// irradiance ∫ L cos θ dω at the normal `n`: a light sample drawn with the map's density under
/// `how` and a cosine-weighted direction, each weighed against the other's density.
fn mis_irradiance(map: &EnvMap, how: EnvSampling, n: Vec3, samples: usize) -> (f64, f64) {
    let frame = pathtrace::math::Frame::from_normal(n);
    let power = |a: f32, b: f32| if a > 0.0 { a * a / (a * a + b * b) } else { 0.0 };
    let mut rng = TestRng::new(23);
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    for _ in 0..samples {
        let mut estimate = 0.0f32;
        let (d, p_light) = map.sample_with(v2(rng.next_2d()), how);
        let cos = d.dot(n);
        if p_light > 0.0 && cos > 0.0 {
            let w = power(p_light, cos / std::f32::consts::PI);
            estimate += map.radiance(d).luminance() * cos * w / p_light;
        }
        let d = frame.to_world(pathtrace::sampling::warp::square_to_cosine_hemisphere(v2(rng.next_2d())));
        let cos = d.dot(n);
        if cos > 0.0 {
            let p_bsdf = cos / std::f32::consts::PI;
            let w = power(p_bsdf, map.pdf_with(d, how));
            estimate += map.radiance(d).luminance() * cos * w / p_bsdf;
        }
        s += estimate as f64;
        s2 += (estimate as f64).powi(2);
    }
    let mean = s / samples as f64;
    (mean, (s2 / samples as f64 - mean * mean).max(0.0))
}

#[test]
fn compensation_lowers_the_variance_of_mis_and_keeps_its_mean() {
    // The sun is 52° from the zenith: the sky and the sun both light an upward normal.
    let map = sky_map(Transform::IDENTITY);
    let n = Vec3::Y;
    let exact = midpoint_over_sphere(|d| (map.radiance(d).luminance() * d.dot(n).max(0.0)) as f64, 1024);
    let samples = 400_000;
    let (complete, var_complete) = mis_irradiance(&map, EnvSampling::Complete, n, samples);
    let (compensated, var_compensated) = mis_irradiance(&map, EnvSampling::Compensated, n, samples);
    eprintln!("irradiance {exact:.4}: complete {complete:.4} (variance {var_complete:.4}), compensated {compensated:.4} (variance {var_compensated:.4})");
    for (name, mean, var) in [("complete", complete, var_complete), ("compensated", compensated, var_compensated)] {
        let se = (var / samples as f64).sqrt();
        assert!((mean - exact).abs() < 4.0 * se + 2e-3 * exact, "{name}: {mean} vs {exact} (se {se})");
    }
    assert!(var_compensated < 0.9 * var_complete, "compensated {var_compensated} vs complete {var_complete}");
}

#[test]
fn the_light_set_samples_the_map_with_its_own_density() {
    // One light: next-event estimation picks the map with probability 1 and its pdf.
    let env = EnvironmentLight::map(sky_map(Transform::rotate_z(20.0)));
    let set = LightSet::new(vec![Light::Environment(env)], 1.0);
    let p = Vec3::new(0.3, -0.2, 1.0);
    let mut rng = TestRng::new(8);
    for _ in 0..1000 {
        let s = set.sample(p, rng.next_f32(), v2(rng.next_2d())).unwrap();
        let env = set.environment().unwrap();
        assert!((s.pdf - set.pdf_direction(p, s.wi)).abs() <= 2e-3 * s.pdf);
        assert!((s.pdf - set.pdf_environment(s.wi)).abs() <= 2e-3 * s.pdf);
        // Looked up at the sampled image coordinates rather than at the direction mapped back
        // to the image: equal up to the rounding of that round trip (well under 0.1% even beside
        // the steep sun).
        let looked_up = env.radiance(s.wi);
        let error = (s.radiance - looked_up).to_array().into_iter().fold(0.0f32, |m, c| m.max(c.abs()));
        assert!(error <= 1e-3 * looked_up.max_component() + 1e-6, "{:?} vs {looked_up:?}", s.radiance);
        assert!(s.dist.is_infinite());
    }
}

/// Mean and coefficient of variation of luminance/pdf over `n` samples.
fn ratio_stats(n: usize, mut sample: impl FnMut(Vec2) -> (f32, f32)) -> (f64, f64) {
    let mut rng = TestRng::new(11);
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let (lum, pdf) = sample(v2(rng.next_2d()));
        let r = if pdf > 0.0 { (lum / pdf) as f64 } else { 0.0 };
        s += r;
        s2 += r * r;
    }
    let mean = s / n as f64;
    (mean, (s2 / n as f64 - mean * mean).max(0.0).sqrt() / mean)
}

#[test]
fn the_pdf_is_proportional_to_luminance() {
    let map = sky_map(Transform::rotate_y(45.0));
    let exact = midpoint_over_sphere(|w| map.radiance(w).luminance() as f64, 1024);
    let n = 200_000;
    let (importance, cv_importance) = ratio_stats(n, |u| {
        let (d, pdf) = map.sample(u);
        (map.radiance(d).luminance(), pdf)
    });
    let (uniform, cv_uniform) = ratio_stats(n, |u| {
        let d = pathtrace::sampling::warp::square_to_uniform_sphere(u);
        (map.radiance(d).luminance(), pathtrace::sampling::warp::uniform_sphere_pdf())
    });
    // Both estimate ∫ L dω (4 standard errors); the stored integral agrees with quadrature.
    for (name, est, cv) in [("importance", importance, cv_importance), ("uniform", uniform, cv_uniform)] {
        let se = cv * est / (n as f64).sqrt();
        assert!((est - exact).abs() < 4.0 * se + 1e-3 * exact, "{name}: {est} vs {exact} (se {se})");
    }
    assert!((map.luminance_integral() - exact).abs() < 0.02 * exact, "{} vs {exact}", map.luminance_integral());
    eprintln!("luminance/pdf coefficient of variation: importance {cv_importance:.3}, uniform {cv_uniform:.3}");
    // Proportional up to bilinear-vs-constant differences inside cells.
    assert!(cv_importance < 0.3, "luminance/pdf varies by {cv_importance} under importance sampling");
    assert!(cv_uniform > 3.0, "the test map is not peaked enough to tell ({cv_uniform})");
}

/// From −z, `vfov_degrees` wide: 10° sees only the sphere, 45° all of it and some sky.
fn camera(vfov_degrees: f32) -> CameraDesc {
    CameraDesc { look_from: Vec3::new(0.0, 0.0, -3.0), look_at: Vec3::ZERO, vfov_degrees, ..Default::default() }
}

fn sphere_scene(material: Material, env: EnvironmentLight, vfov_degrees: f32) -> Arc<Scene> {
    let mut b = SceneBuilder::new();
    let m = b.material(material);
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap()), m, &Transform::IDENTITY).unwrap();
    b.environment(env).unwrap();
    b.camera(camera(vfov_degrees));
    Arc::new(b.build().unwrap())
}

fn settings(strategy: Strategy, spp: u32, seed: u64) -> RenderSettings {
    let mut s = RenderSettings { width: 16, height: 16, spp, seed, ..Default::default() };
    s.path.strategy = strategy;
    s
}

#[test]
fn a_diffuse_sphere_under_a_constant_map_shows_albedo_times_the_map() {
    let (albedo, sky) = (Rgb::new(0.8, 0.5, 0.2), Rgb::new(1.0, 2.0, 4.0));
    let map = EnvMap::new(8, 5, vec![sky; 40], 1.0, Transform::rotate_x(70.0)).unwrap();
    let scene = sphere_scene(Material::Lambertian(Lambertian { albedo }), EnvironmentLight::map(map), 10.0);
    let expected = (albedo * sky).to_array().map(|c| c as f64);
    for strategy in [Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Mis, Strategy::MisBalance] {
        let est = render(scene.clone(), settings(strategy, 128, 7)).unwrap().film.region_estimate(0, 0, 16, 16);
        let z = est.max_z_score_against(expected);
        assert!(z < 4.5, "{strategy}: {:?} vs {expected:?} (z = {z:.2})", est.mean);
        assert!(est.variance_of_mean[2].sqrt() < 0.01 * expected[2], "{strategy}: too noisy to judge");
    }
}

/// Relative MSE of a glossy sphere under the sun-and-sky map at `spp`, averaged over seeds,
/// against a reference rendered with MIS at `ref_spp`.
pub fn glossy_errors(spp: u32, ref_spp: u32, seeds: u64) -> Vec<(Strategy, f64)> {
    // 256 × 128 texels with a small sun (σ = 1 texel, ~1.4° wide), 20000 times the sky.
    let pixels = sun_and_sky(256, 128, (80.0, 40.0), 1.0, 20_000.0);
    let map = EnvMap::new(256, 128, pixels, 1.0, Transform::rotate_y(200.0)).unwrap();
    let glossy = Material::Glossy(Glossy { albedo: Rgb::splat(0.8), exponent: 20.0 });
    let scene = sphere_scene(glossy, EnvironmentLight::map(map), 45.0);
    let reference = render(scene.clone(), settings(Strategy::Mis, ref_spp, 1000)).unwrap().film.image();
    [Strategy::Bsdf, Strategy::Light, Strategy::Mis]
        .into_iter()
        .map(|s| {
            let total: f64 = (0..seeds)
                .map(|seed| {
                    let img = render(scene.clone(), settings(s, spp, seed)).unwrap().film.image();
                    relative_mse(&img, &reference).unwrap()
                })
                .sum();
            (s, total / seeds as f64)
        })
        .collect()
}

/// Renders under `mis` sample the map with the compensated density, under `mixture` with the
/// complete one: both converge to the same image (a diffuse and a glossy sphere, seen whole
/// against the sky, and the sky itself).
#[test]
fn compensated_mis_renders_agree_with_the_complete_density() {
    let pixels = sun_and_sky(128, 64, (40.0, 20.0), 2.0, 300.0);
    let map = EnvMap::new(128, 64, pixels, 1.0, Transform::rotate_y(130.0)).unwrap();
    let diffuse = Material::Lambertian(Lambertian { albedo: Rgb::new(0.8, 0.6, 0.4) });
    let glossy = Material::Glossy(Glossy { albedo: Rgb::splat(0.8), exponent: 8.0 });
    for (name, material) in [("diffuse", diffuse), ("glossy", glossy)] {
        let scene = sphere_scene(material, EnvironmentLight::map(map.clone()), 45.0);
        let est = |strategy: Strategy, spp: u32| {
            render(scene.clone(), settings(strategy, spp, 31)).unwrap().film.region_estimate(0, 0, 16, 16)
        };
        let (mis, mixture) = (est(Strategy::Mis, 512), est(Strategy::Mixture, 1024));
        let z = mis.max_z_score(&mixture);
        assert!(z < 4.5, "{name}: mis {:?} vs mixture {:?} (z = {z:.2})", mis.mean, mixture.mean);
        assert!(mis.variance_of_mean[0].sqrt() < 0.01 * mis.mean[0], "{name}: too noisy to judge");
    }
}

#[test]
fn mis_beats_either_strategy_alone_on_a_glossy_sphere_under_a_sun() {
    let errors = glossy_errors(4, 2048, 4);
    println!("relative MSE at 4 spp: {errors:?}");
    let get = |s: Strategy| errors.iter().find(|e| e.0 == s).unwrap().1;
    let mis = get(Strategy::Mis);
    assert!(mis < 0.5 * get(Strategy::Bsdf), "{errors:?}");
    assert!(mis < 0.5 * get(Strategy::Light), "{errors:?}");
}
