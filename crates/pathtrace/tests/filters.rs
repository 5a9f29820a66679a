//! Pixel filters: where a camera sample goes in its pixel (uniform over the pixel, or over the
//! square of a box narrower than it: chi-square), each axis warped monotonically (so stratified
//! samples stay stratified), and an image of constant radiance keeps its value under every
//! filter, splatting ones (film/splat.rs) included, border pixels too.

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
        PixelFilter::Box { radius: 0.25 },
        PixelFilter::Box { radius: 1.5 },
        PixelFilter::Tent { radius: 1.0 },
        PixelFilter::Tent { radius: 2.5 },
        PixelFilter::Gaussian(GaussianFilter::new(0.5).unwrap()),
        PixelFilter::Gaussian(GaussianFilter::new(0.8).unwrap()),
    ]
}

#[test]
fn camera_samples_are_uniform_over_the_pixel_or_the_narrow_box() {
    const BINS: usize = 16;
    const SAMPLES: usize = 100_000;
    for filter in filters() {
        // The square the samples must cover uniformly (from the pixel's corner).
        let half = if filter.splats() { 0.5 } else { filter.radius() as f64 };
        let (lo, h) = (0.5 - half, 2.0 * half / BINS as f64);
        let mut counts = vec![0usize; BINS * BINS];
        let mut rng = TestRng::new(11);
        for _ in 0..SAMPLES {
            let j = filter.sample(Vec2::new(rng.next_f32(), rng.next_f32()));
            let bx = ((j.x as f64 - lo) / h).floor();
            let by = ((j.y as f64 - lo) / h).floor();
            assert!((0.0..BINS as f64).contains(&bx) && (0.0..BINS as f64).contains(&by), "{filter:?}: {j:?}");
            counts[by as usize * BINS + bx as usize] += 1;
        }
        let e = SAMPLES as f64 / (BINS * BINS) as f64;
        let stat: f64 = counts.iter().map(|&o| (o as f64 - e).powi(2) / e).sum();
        let p = chi_square_p_value(stat, BINS * BINS - 1);
        assert!(p > 1e-3, "{filter:?}: chi-square {stat:.1}, p = {p:.2e}");
    }
}

#[test]
fn each_axis_is_warped_monotonically_so_strata_stay_apart() {
    for filter in filters() {
        let n = 257;
        let at = |i: usize, other: f32| {
            let u = i as f32 / (n - 1) as f32 * 0.999_999;
            (filter.sample(Vec2::new(u, other)).x, filter.sample(Vec2::new(other, u)).y)
        };
        for other in [0.1f32, 0.77] {
            for i in 1..n {
                let (a, b) = (at(i - 1, other), at(i, other));
                assert!(b.0 > a.0 && b.1 > a.1, "{filter:?}: not monotone at {i}");
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
            let film = render(scene.clone(), s).unwrap().film;
            assert_eq!(film.splat_pixels().is_some(), filter.splats(), "{filter:?}");
            // Every pixel, the border ones included: a ratio of weights is exact for a constant.
            for (i, p) in film.image().pixels.iter().enumerate() {
                assert!((p.r - L).abs() < 1e-5 && (p.b - L).abs() < 1e-5, "{filter:?} {sampler:?} pixel {i}: {p:?}");
            }
        }
    }
}
