//! Renders depend only on (scene, settings, seed): the number of threads changes nothing, not
//! even the last bit.

mod common;

use pathtrace::integrator::Strategy;
use pathtrace::sampling::SamplerKind;
use pathtrace::{render, AdaptiveSettings, RenderSettings, Scene};
use std::sync::Arc;

fn scene() -> Arc<Scene> {
    common::glass_sphere_under_lamp(2.0, 10.0)
}

#[test]
fn one_and_two_threads_give_bit_identical_films() {
    for (strategy, sampler) in [
        (Strategy::Mis, SamplerKind::Independent),
        (Strategy::Mixture, SamplerKind::Stratified),
        (Strategy::Bsdf, SamplerKind::Sobol),
    ] {
        let mut s =
            RenderSettings { width: 40, height: 30, spp: 19, seed: 5, sampler, tile_size: 7, ..Default::default() };
        s.path.strategy = strategy;
        let one = render(scene(), RenderSettings { threads: 1, ..s.clone() }).unwrap().film;
        let two = render(scene(), RenderSettings { threads: 2, ..s.clone() }).unwrap().film;
        assert_eq!(one, two, "{strategy}/{sampler}");
        // And a different seed does change the image.
        let other = render(scene(), RenderSettings { threads: 2, seed: 6, ..s }).unwrap().film;
        assert_ne!(one, other);
    }
}

#[test]
fn adaptive_renders_are_bit_identical_for_one_and_two_threads() {
    for sampler in [SamplerKind::Independent, SamplerKind::Sobol] {
        let s = RenderSettings {
            width: 40,
            height: 30,
            spp: 24,
            seed: 5,
            sampler,
            tile_size: 7,
            adaptive: Some(AdaptiveSettings { min_spp: 4, ..Default::default() }),
            ..Default::default()
        };
        let one = render(scene(), RenderSettings { threads: 1, ..s.clone() }).unwrap().film;
        let two = render(scene(), RenderSettings { threads: 2, ..s.clone() }).unwrap().film;
        assert_eq!(one, two, "{sampler}");
        // Adaptation happened: pixels hold different counts, 24 on average.
        let (lo, hi) = one.spp_range();
        assert!(lo >= 4 && hi > 24, "{lo}..{hi}");
        assert_eq!(one.total_samples() + one.dropped_samples, 40 * 30 * 24);
    }
}
