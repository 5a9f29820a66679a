//! The built-in Cornell box: every unbiased strategy converges to the same image, and that
//! image matches an independent renderer.
//!
//! The reference is Mitsuba 3.9.1 (`scalar_rgb`, path integrator, max depth 8, box filter,
//! 128², 4096 spp) rendering the identical scene built by `benches/peers/cornell_mitsuba.py`;
//! numbers and command in `benches/peers/README.md`. Its own standard error is ≈ 4e-5 for the
//! whole image and ≤ 1.3e-4 for the regions.

use pathtrace::film::{Film, RegionEstimate};
use pathtrace::integrator::Strategy;
use pathtrace::sampling::SamplerKind;
use pathtrace::{render, RenderSettings};
use std::sync::Arc;

const SIZE: u32 = 128;

/// (name, x0, y0, x1, y1) at 128², half-open, row 0 at the top.
const REGIONS: [(&str, u32, u32, u32, u32); 5] = [
    ("whole image", 0, 0, 128, 128),
    ("left (green) wall", 8, 38, 20, 77),
    ("right (red) wall", 108, 38, 120, 77),
    ("floor", 46, 113, 60, 124),
    ("back wall", 45, 32, 83, 51),
];

/// Mitsuba's means for the regions above.
const MITSUBA: [[f64; 3]; 5] = [
    [0.1716, 0.1539, 0.1402],
    [0.0323, 0.1130, 0.0361],
    [0.1796, 0.0135, 0.0128],
    [0.1473, 0.1527, 0.1423],
    [0.2280, 0.2112, 0.1992],
];
const MITSUBA_STD_ERROR: f64 = 1.3e-4;

fn render_box(strategy: Strategy, sampler: SamplerKind, spp: u32, seed: u64) -> Film {
    let loaded = pathtrace_scene::builtin::load("cornell-box").unwrap().unwrap();
    let mut s = RenderSettings { width: SIZE, height: SIZE, spp, seed, sampler, ..Default::default() };
    s.path.strategy = strategy;
    s.path.max_depth = 8;
    let out = render(Arc::new(loaded.scene), s).unwrap();
    assert_eq!(out.progress.dropped_samples, 0, "{strategy}: NaN samples");
    out.film
}

fn regions(film: &Film) -> Vec<RegionEstimate> {
    REGIONS.iter().map(|&(_, x0, y0, x1, y1)| film.region_estimate(x0, y0, x1, y1)).collect()
}

#[test]
fn unbiased_strategies_agree_within_confidence_intervals() {
    let mis = regions(&render_box(Strategy::Mis, SamplerKind::Independent, 128, 1));
    for (strategy, sampler) in [
        (Strategy::Bsdf, SamplerKind::Independent),
        (Strategy::Mixture, SamplerKind::Independent),
        (Strategy::Mis, SamplerKind::Stratified),
    ] {
        let other = regions(&render_box(strategy, sampler, 128, 2));
        for (i, (a, b)) in mis.iter().zip(&other).enumerate() {
            let z = a.max_z_score(b);
            // 5 regions × 3 channels × 3 comparisons: |z| < 4.5 keeps false alarms below 1e-3.
            assert!(z < 4.5, "{} ({strategy}/{sampler}): mis {:?} vs {:?}, z = {z:.2}", REGIONS[i].0, a.mean, b.mean);
        }
    }
}

#[test]
fn the_image_matches_an_independent_renderer() {
    let ours = regions(&render_box(Strategy::Mis, SamplerKind::Independent, 512, 3));
    for (i, (est, reference)) in ours.iter().zip(MITSUBA).enumerate() {
        for (k, &want) in reference.iter().enumerate() {
            let sd = (est.variance_of_mean[k] + MITSUBA_STD_ERROR * MITSUBA_STD_ERROR).sqrt();
            // The reference is rounded to 4 decimals: allow half a unit of that as well.
            let z = ((est.mean[k] - want).abs() - 5e-5).max(0.0) / sd;
            assert!(
                z < 4.5,
                "{} channel {k}: ours {:.5} vs Mitsuba {:.4} (z = {z:.2})",
                REGIONS[i].0,
                est.mean[k],
                want
            );
        }
    }
}

#[test]
fn the_light_is_seen_at_its_radiance() {
    let film = render_box(Strategy::Mis, SamplerKind::Independent, 4, 4);
    let light = film.region_estimate(55, 17, 73, 20);
    for k in 0..3 {
        assert!((light.mean[k] - 15.0).abs() < 1e-4, "{:?}", light.mean);
    }
}
