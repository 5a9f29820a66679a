//! The film sums samples exactly (fixed-point integers, `film/accumulator.rs`), so a render split
//! into sample ranges — rendered with any thread count and lane width, merged in any order — is
//! bit for bit the render of the whole range at once, feature buffers included. This is what lets
//! a render be spread over machines (docs/distributed.md).

use pathtrace::film::{engine_build, render_key, Film, PixelFilter, RangedFilm};
use pathtrace::sampling::SamplerKind;
use pathtrace::wide::Kernel;
use pathtrace::{render, RenderSettings, SampleRange, Scene};
use pathtrace_scene::native::load_file;
use std::path::PathBuf;
use std::sync::Arc;

fn repo_scene(rel: &str) -> Arc<Scene> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").join(rel);
    Arc::new(load_file(&path).unwrap_or_else(|e| panic!("{rel}: {e}")).scene)
}

const SPP: u32 = 12;

fn settings(sampler: SamplerKind, threads: usize, kernel: Kernel, range: Option<SampleRange>) -> RenderSettings {
    settings_with(PixelFilter::Pixel, sampler, threads, kernel, range)
}

fn settings_with(
    filter: PixelFilter,
    sampler: SamplerKind,
    threads: usize,
    kernel: Kernel,
    range: Option<SampleRange>,
) -> RenderSettings {
    let mut s = RenderSettings {
        filter,
        width: 24,
        height: 20,
        spp: SPP,
        seed: 3,
        sampler,
        kernel,
        threads,
        tile_size: 8,
        sample_range: range,
        features: true,
        ..Default::default()
    };
    s.path.max_depth = 8;
    s
}

fn render_range(scene: &Arc<Scene>, s: RenderSettings) -> RangedFilm {
    let range = s.samples();
    let key = render_key(1, &s);
    let out = render(Arc::clone(scene), s).unwrap();
    assert_eq!(out.progress.spp_done, range.len());
    RangedFilm::new(out.film, key, engine_build(), SPP, range).with_features(out.features)
}

/// A small deterministic generator for splits and merge orders (the test must not vary).
struct Lcg(u64);

impl Lcg {
    fn below(&mut self, n: u32) -> u32 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((self.0 >> 33) % u64::from(n)) as u32
    }
}

/// `parts` random cut points of `0..SPP`.
fn random_split(rng: &mut Lcg, parts: u32) -> Vec<SampleRange> {
    let mut cuts: Vec<u32> = (0..parts - 1).map(|_| 1 + rng.below(SPP - 1)).collect();
    cuts.extend([0, SPP]);
    cuts.sort();
    cuts.dedup();
    cuts.windows(2).map(|w| SampleRange::new(w[0], w[1])).collect()
}

/// Whether AVX-512 runs here (then `Kernel::Wide` runs groups of 32 lanes and `Wide8` the AVX2
/// kernel's 16). Builds with debug assertions, as this test's, compile only the portable 8-lane
/// loop (`render/tile.rs`).
fn has_avx512() -> bool {
    if cfg!(debug_assertions) {
        return false;
    }
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512vl")
            && std::arch::is_x86_feature_detected!("avx512dq")
            && std::arch::is_x86_feature_detected!("avx512bw")
    }
    #[cfg(not(target_arch = "x86_64"))]
    false
}

fn assert_same_film(a: &Film, b: &Film, what: &str) {
    let differing = a.pixels().iter().zip(b.pixels()).filter(|(p, q)| p != q).count();
    assert_eq!(differing, 0, "{what}: {differing} pixels differ");
    assert_eq!(a, b, "{what}");
}

#[test]
fn split_renders_merged_in_any_order_equal_the_whole_render() {
    if !has_avx512() {
        eprintln!("note: no AVX-512 here (or a build with debug assertions): Wide and Wide8 are the same loop");
    }
    let scenes = [
        "scenes/cornell-box.toml",
        "scenes/gallery/08-sky-point-thin-glass.toml",
        "scenes/gallery/07-cornell-glass.toml",
    ];
    let mut rng = Lcg(2026);
    for (k, rel) in scenes.iter().enumerate() {
        let scene = repo_scene(rel);
        for sampler in [SamplerKind::Independent, SamplerKind::Stratified, SamplerKind::Sobol] {
            let whole = render_range(&scene, settings(sampler, 1, Kernel::Wide, None));
            assert!(whole.film.total_samples() > 0);
            // Several random splits, each part with its own thread count and lane width, merged
            // in a random order.
            for trial in 0..3 {
                let count = 2 + rng.below(4);
                let parts = random_split(&mut rng, count);
                let mut films: Vec<RangedFilm> = parts
                    .iter()
                    .enumerate()
                    .map(|(i, &r)| {
                        let threads = 1 + (i + trial + k) % 2;
                        let kernel = [Kernel::Wide8, Kernel::Wide, Kernel::Scalar][(i + trial) % 3];
                        render_range(&scene, settings(sampler, threads, kernel, Some(r)))
                    })
                    .collect();
                let mut merged = films.swap_remove(rng.below(films.len() as u32) as usize);
                while !films.is_empty() {
                    let next = films.swap_remove(rng.below(films.len() as u32) as usize);
                    merged.merge(&next).unwrap();
                }
                assert!(merged.is_complete(), "{rel} {sampler:?} {parts:?}");
                assert_same_film(&merged.film, &whole.film, &format!("{rel} {sampler:?} split {parts:?}"));
                assert_eq!(merged.film.image().pixels, whole.film.image().pixels);
                let (m, w) = (merged.features.as_ref().unwrap(), whole.features.as_ref().unwrap());
                let differing = m.pixels().iter().zip(w.pixels()).filter(|(p, q)| p != q).count();
                assert_eq!(differing, 0, "{rel} {sampler:?} split {parts:?}: feature pixels differ");
                assert_eq!(m.albedo().pixels, w.albedo().pixels);
            }
        }
    }
}

#[test]
fn thread_count_and_lane_width_do_not_change_a_bit_but_the_seed_does() {
    let scene = repo_scene("scenes/cornell-box.toml");
    let base = render_range(&scene, settings(SamplerKind::Sobol, 1, Kernel::Wide8, None));
    for (threads, kernel) in [(2, Kernel::Wide8), (1, Kernel::Wide), (2, Kernel::Wide), (2, Kernel::Scalar)] {
        let other = render_range(&scene, settings(SamplerKind::Sobol, threads, kernel, None));
        assert_same_film(&other.film, &base.film, &format!("{threads} threads, {kernel:?}"));
        assert_eq!(other.features, base.features, "{threads} threads, {kernel:?}: feature buffers");
    }
    let base = base.film;
    // The comparison can fail: another seed gives other samples.
    let mut s = settings(SamplerKind::Sobol, 1, Kernel::Wide8, None);
    s.seed = 4;
    let reseeded = render(Arc::clone(&scene), s).unwrap().film;
    assert_ne!(reseeded, base);
}

#[test]
fn a_range_outside_the_render_is_refused() {
    let scene = repo_scene("scenes/cornell-box.toml");
    let s = settings(SamplerKind::Independent, 1, Kernel::Wide, Some(SampleRange::new(8, SPP + 1)));
    let err = render(Arc::clone(&scene), s).unwrap_err();
    assert!(err.to_string().contains("8..13"), "{err}");
    let mut s = settings(SamplerKind::Independent, 1, Kernel::Wide, Some(SampleRange::new(0, 4)));
    s.adaptive = Some(Default::default());
    assert!(render(scene, s).is_err());
}

/// A gaussian-filtered render splats each sample into its neighbours (film/splat.rs), across
/// tile borders: the splatted sums Σw and Σw·L are exact integers too, so thread counts, lane
/// widths, tiles (with their halos) and split renders merged in any order all give the same bits.
#[test]
fn splatted_renders_are_exact_across_threads_lanes_and_split_merges() {
    let gaussian = || PixelFilter::by_name("gaussian").unwrap();
    let scene = repo_scene("scenes/gallery/07-cornell-glass.toml");
    let sampler = SamplerKind::Sobol;
    let whole = render_range(&scene, settings_with(gaussian(), sampler, 1, Kernel::Wide8, None));
    assert!(whole.film.splat_pixels().is_some());
    for (threads, kernel) in [(2, Kernel::Wide8), (1, Kernel::Wide), (2, Kernel::Scalar)] {
        let other = render_range(&scene, settings_with(gaussian(), sampler, threads, kernel, None));
        assert_same_film(&other.film, &whole.film, &format!("gaussian, {threads} threads, {kernel:?}"));
    }
    let mut rng = Lcg(19);
    for trial in 0..2 {
        let parts = random_split(&mut rng, 3 + trial);
        let mut films: Vec<RangedFilm> = parts
            .iter()
            .enumerate()
            .map(|(i, &r)| {
                let kernel = [Kernel::Scalar, Kernel::Wide, Kernel::Wide8][(i + trial as usize) % 3];
                render_range(&scene, settings_with(gaussian(), sampler, 1 + i % 2, kernel, Some(r)))
            })
            .collect();
        let mut merged = films.swap_remove(rng.below(films.len() as u32) as usize);
        while !films.is_empty() {
            let next = films.swap_remove(rng.below(films.len() as u32) as usize);
            // Through the film file, as parts from other machines arrive.
            merged.merge(&RangedFilm::from_bytes(&next.to_bytes()).unwrap()).unwrap();
        }
        assert_same_film(&merged.film, &whole.film, &format!("gaussian split {parts:?}"));
        assert_eq!(merged.film.image().pixels, whole.film.image().pixels);
    }
    // A splatting part and a plain one do not merge.
    let plain = render_range(&scene, settings(sampler, 1, Kernel::Wide8, Some(SampleRange::new(0, 1))));
    let mut part =
        render_range(&scene, settings_with(gaussian(), sampler, 1, Kernel::Wide8, Some(SampleRange::new(1, 2))));
    part.key = plain.key;
    assert!(part.merge(&plain).is_err());
}
