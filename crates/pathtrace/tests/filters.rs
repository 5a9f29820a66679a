//! Pixel filters sampled by importance: the sampled offsets follow the filter's density
//! (chi-square), that density integrates to 1, the gaussian's weights f/pdf restore its exact
//! shape, each axis is warped monotonically (so stratified samples stay stratified), and an
//! image of constant radiance keeps its value under every filter.

use pathtrace::film::{GaussianFilter, PixelFilter};
use pathtrace::light::Emission;
use pathtrace::material::Material;
use pathtrace::math::{Rgb, Transform, Vec2, Vec3};
use pathtrace::sampling::SamplerKind;
use pathtrace::shape::{Shape, Sphere};
use pathtrace::{render, CameraDesc, RenderSettings, SceneBuilder};
use pathtrace_testkit::{chi_square_p_value, TestRng};
use std::sync::Arc;

fn filters() -> Vec<PixelFilter> {
    vec![
        PixelFilter::Pixel,
        PixelFilter::Box { radius: 1.5 },
        PixelFilter::Tent { radius: 1.0 },
        PixelFilter::Tent { radius: 2.5 },
        PixelFilter::Gaussian(GaussianFilter::new(0.5).unwrap()),
        PixelFilter::Gaussian(GaussianFilter::new(0.8).unwrap()),
    ]
}

/// ∫ over the square [x0, x0 + h] × [y0, y0 + h] of `f`, by an 8 × 8 midpoint rule.
fn cell_integral(f: &dyn Fn(Vec2) -> f64, x0: f64, y0: f64, h: f64) -> f64 {
    let n = 8;
    let d = h / n as f64;
    let mut s = 0.0;
    for i in 0..n {
        for j in 0..n {
            s += f(Vec2::new((x0 + (i as f64 + 0.5) * d) as f32, (y0 + (j as f64 + 0.5) * d) as f32));
        }
    }
    s * d * d
}

#[test]
fn sampled_offsets_follow_the_pdf_and_the_pdf_integrates_to_one() {
    const BINS: usize = 24;
    const SAMPLES: usize = 200_000;
    for filter in filters() {
        let r = filter.radius() as f64;
        let h = 2.0 * r / BINS as f64;
        let pdf = |o: Vec2| filter.pdf(o);
        let expected: Vec<f64> = (0..BINS * BINS)
            .map(|k| cell_integral(&pdf, -r + (k % BINS) as f64 * h, -r + (k / BINS) as f64 * h, h))
            .collect();
        let total: f64 = expected.iter().sum();
        assert!((total - 1.0).abs() < 1e-3, "{filter:?}: pdf integrates to {total}");
        let mut counts = vec![0usize; BINS * BINS];
        let mut rng = TestRng::new(11);
        for _ in 0..SAMPLES {
            let s = filter.sample(Vec2::new(rng.next_f32(), rng.next_f32()));
            let o = s.jitter - Vec2::splat(0.5);
            let bx = (((o.x as f64 + r) / h) as usize).min(BINS - 1);
            let by = (((o.y as f64 + r) / h) as usize).min(BINS - 1);
            counts[by * BINS + bx] += 1;
        }
        // Pearson's statistic; cells expecting fewer than 5 samples are pooled into one.
        let (mut stat, mut dof, mut pool_e, mut pool_o) = (0.0, 0usize, 0.0, 0.0);
        for (e, &o) in expected.iter().zip(&counts) {
            let e = e * SAMPLES as f64;
            if e < 5.0 {
                pool_e += e;
                pool_o += o as f64;
                continue;
            }
            stat += (o as f64 - e).powi(2) / e;
            dof += 1;
        }
        if pool_e >= 5.0 {
            stat += (pool_o - pool_e).powi(2) / pool_e;
            dof += 1;
        } else {
            assert!(pool_o <= 5.0 + 5.0 * pool_e.max(1.0), "{filter:?}: {pool_o} samples where ≈{pool_e} expected");
        }
        let p = chi_square_p_value(stat, dof - 1);
        assert!(p > 1e-3, "{filter:?}: chi-square {stat:.1} on {} dof, p = {p:.2e}", dof - 1);
    }
}

#[test]
fn box_and_tent_samples_weigh_one_and_match_the_normalised_shape() {
    for filter in filters().into_iter().filter(|f| !matches!(f, PixelFilter::Gaussian(_))) {
        let mut rng = TestRng::new(3);
        for _ in 0..1000 {
            let s = filter.sample(Vec2::new(rng.next_f32(), rng.next_f32()));
            assert_eq!(s.weight, 1.0);
            let o = s.jitter - Vec2::splat(0.5);
            assert!((filter.pdf(o) - filter.eval_normalized(o)).abs() < 1e-12);
        }
    }
}

#[test]
fn gaussian_weights_restore_the_filter_shape() {
    // E[w·g(X)] = ∫ f·g for any g: check g = 1 (total weight) and g = x² (the shape's variance).
    for stddev in [0.5f32, 0.8] {
        let g = GaussianFilter::new(stddev).unwrap();
        let filter = PixelFilter::Gaussian(g.clone());
        let r = g.radius() as f64;
        let n = 20_000;
        let exact_var: f64 = (0..n)
            .map(|i| {
                let x = -r + (i as f64 + 0.5) * 2.0 * r / n as f64;
                x * x * g.eval_normalized(x) * 2.0 * r / n as f64
            })
            .sum();
        let mut rng = TestRng::new(5);
        let m = 400_000;
        let (mut sw, mut sw2, mut swx2) = (0.0, 0.0, 0.0);
        for _ in 0..m {
            let s = filter.sample(Vec2::new(rng.next_f32(), rng.next_f32()));
            let x = (s.jitter.x - 0.5) as f64;
            let w = s.weight as f64;
            sw += w;
            sw2 += w * w;
            swx2 += w * x * x;
        }
        let mean_w = sw / m as f64;
        let sd_w = ((sw2 / m as f64 - mean_w * mean_w).max(0.0) / m as f64).sqrt();
        assert!((mean_w - 1.0).abs() < 5.0 * sd_w + 1e-6, "σ={stddev}: mean weight {mean_w} ± {sd_w}");
        assert!(sd_w * (m as f64).sqrt() < 0.05, "σ={stddev}: weights vary too much ({sd_w})");
        let var = swx2 / m as f64;
        assert!((var - exact_var).abs() < 0.01 * exact_var, "σ={stddev}: E[w x²] = {var}, exact {exact_var}");
    }
}

#[test]
fn each_axis_is_warped_monotonically_so_strata_stay_apart() {
    for filter in filters() {
        let n = 257;
        let at = |i: usize, other: f32| {
            let u = i as f32 / (n - 1) as f32 * 0.999_999;
            (filter.sample(Vec2::new(u, other)).jitter.x, filter.sample(Vec2::new(other, u)).jitter.y)
        };
        for other in [0.1f32, 0.77] {
            for i in 1..n {
                let (a, b) = (at(i - 1, other), at(i, other));
                assert!(b.0 >= a.0 && b.1 >= a.1, "{filter:?}: not monotone at {i}");
                // Separable: an axis does not depend on the other coordinate.
                assert_eq!(at(i, other).0, at(i, 0.5).0);
            }
        }
    }
}

#[test]
fn constant_radiance_renders_the_same_mean_with_every_filter() {
    // The camera sits inside a sphere that emits L towards it everywhere: every pixel is L.
    const L: f32 = 2.5;
    let mut b = SceneBuilder::new();
    let glow = b.material_with_emission(Material::Black, Emission { radiance: Rgb::splat(L), two_sided: true });
    b.shape(Shape::Sphere(Sphere::new(Vec3::ZERO, 10.0).unwrap()), glow, &Transform::IDENTITY).unwrap();
    b.camera(CameraDesc { look_from: Vec3::ZERO, look_at: Vec3::Z, ..Default::default() });
    let scene = Arc::new(b.build().unwrap());
    for filter in filters() {
        for sampler in [SamplerKind::Independent, SamplerKind::Sobol] {
            let s = RenderSettings {
                width: 16,
                height: 16,
                spp: 64,
                sampler,
                filter: filter.clone(),
                ..Default::default()
            };
            let est = render(scene.clone(), s).unwrap().film.region_estimate(0, 0, 16, 16);
            let z = est.max_z_score_against([L as f64; 3]);
            let exact = !matches!(filter, PixelFilter::Gaussian(_));
            if exact {
                assert!((est.mean[0] - L as f64).abs() < 1e-5, "{filter:?}: {:?}", est.mean);
            } else {
                assert!(z < 4.5, "{filter:?} {sampler:?}: mean {:?} (z = {z:.2})", est.mean);
                assert!((est.mean[0] / L as f64 - 1.0).abs() < 2e-3, "{filter:?}: {:?}", est.mean);
            }
        }
    }
}
