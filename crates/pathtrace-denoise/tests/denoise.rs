//! Denoising with Intel Open Image Denoise on real scenes: at 4 spp, the denoised image's relative
//! MSE against a high-spp reference must be at most a tenth of the noisy image's.
//!
//! Needs the library (docs/denoising.md says how to install it; .ci/run does so). Without it these
//! tests fail in CI (CI=true) and are skipped with a note elsewhere.

use pathtrace::film::Image;
use pathtrace::metrics::relative_mse;
use pathtrace::{render, RenderSettings, Scene};
use pathtrace_denoise::Denoiser;
use pathtrace_scene::mitsuba::load_mitsuba;
use std::path::Path;
use std::sync::Arc;

fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true" || v == "1")
}

/// The denoiser, or `None` (with a note) outside CI when the library is absent.
fn denoiser() -> Option<Denoiser> {
    match Denoiser::new() {
        Ok(d) => Some(d),
        Err(e) => {
            assert!(!in_ci(), "CI=true but the denoiser is unavailable (.ci/run should install it): {e}");
            eprintln!("note: skipped, {e}");
            None
        }
    }
}

/// The image, albedo and normal of `spp` samples per pixel.
fn render_with_features(scene: &Arc<Scene>, size: (u32, u32), spp: u32, seed: u64) -> (Image, Image, Image) {
    let s = RenderSettings { width: size.0, height: size.1, spp, seed, features: true, ..Default::default() };
    let out = render(Arc::clone(scene), s).unwrap();
    let f = out.features.unwrap();
    (out.film.image(), f.albedo(), f.normal())
}

/// Denoises a 4-spp render and compares both it and the noisy one with a `reference_spp` render.
fn assert_tenfold_gain(name: &str, scene: Scene, size: (u32, u32), reference_spp: u32) {
    let Some(denoiser) = denoiser() else { return };
    let scene = Arc::new(scene);
    let (noisy, albedo, normal) = render_with_features(&scene, size, 4, 1);
    let denoised = denoiser.denoise(&noisy, &albedo, &normal).unwrap();
    let s = RenderSettings { width: size.0, height: size.1, spp: reference_spp, seed: 2, ..Default::default() };
    let reference = render(scene, s).unwrap().film.image();
    let before = relative_mse(&noisy, &reference).unwrap();
    let after = relative_mse(&denoised, &reference).unwrap();
    eprintln!("{name}: relative MSE noisy {before:.5}, denoised {after:.5} ({:.1}x lower)", before / after);
    assert!(after <= before / 10.0, "{name}: denoised {after:.5} vs noisy {before:.5}: less than tenfold");
}

#[test]
fn denoising_the_cornell_box_at_4_spp_cuts_the_relative_mse_tenfold() {
    let loaded = pathtrace_scene::builtin::load("cornell-box").unwrap().unwrap();
    assert_tenfold_gain("cornell-box", loaded.scene, (128, 128), 2048);
}

#[test]
fn denoising_the_bunny_at_4_spp_cuts_the_relative_mse_tenfold() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes/bunny/docs/scenes/shape_ply_bunny.xml");
    if !path.is_file() {
        eprintln!("note: {} is absent; skipped", path.display());
        return;
    }
    let (loaded, _) = load_mitsuba(&path, &[]).unwrap();
    assert_tenfold_gain("bunny", loaded.scene, (128, 96), 512);
}

#[test]
fn mismatched_buffers_are_an_error() {
    let Some(denoiser) = denoiser() else { return };
    let img = Image::new(8, 8);
    let small = Image::new(4, 8);
    let e = denoiser.denoise(&img, &small, &img).unwrap_err();
    assert!(e.to_string().contains("albedo image is 4x8"), "{e}");
}
