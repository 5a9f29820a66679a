//! Splatting (film/splat.rs) against Mitsuba 3: veach-mis, whose film has Mitsuba's default
//! gaussian filter (σ = ½ px, radius 2 px), agrees block by block with Mitsuba 3.9.1
//! `llvm_ad_rgb`, **border blocks included** (Mitsuba normalises each pixel by the filter weights
//! it received inside the film, so a border pixel's expected value differs from an interior
//! estimate's; a render that got the border rule wrong would miss there). The same scene rendered
//! with the plain pixel box is seen to disagree, which shows the test can tell filters apart.
//!
//! Reference (tests/data/veach_mis_blocks.rs): 64 × 64 film, 16 renders × 512 spp with seeds
//! 0–15, per 8 × 8-pixel block the mean and its standard error, made by
//! `.venv-peers/bin/python benches/peers/block_means.py veach-mis/docs/scenes/integrator_direct_both.xml --size 64 --block 8 --spp 512 --runs 16 --variant llvm_ad_rgb --name VEACH_MIS`.
//! Skipped with a note when ../shared/scenes is absent.

mod blocks;

use blocks::{assert_agrees, render_blocks, BLOCK, SIZE, Z_LIMIT};
use pathtrace::film::PixelFilter;
use pathtrace_scene::mitsuba::{build_model, convert_file};
use std::path::{Path, PathBuf};

include!("data/veach_mis_blocks.rs");

const SCENE: &str = "veach-mis/docs/scenes/integrator_direct_both.xml";

fn shared(scene: &str) -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    if !dir.is_dir() {
        eprintln!("skipped: {} is absent", dir.display());
        return None;
    }
    Some(dir.join(scene))
}

/// The blocks along the image's edge (which hold its border pixels).
fn border_blocks() -> Vec<usize> {
    let n = (SIZE / BLOCK) as usize;
    (0..n * n).filter(|i| i / n == 0 || i / n == n - 1 || i % n == 0 || i % n == n - 1).collect()
}

#[test]
fn gaussian_filtered_veach_mis_agrees_with_mitsuba_block_by_block() {
    let Some(path) = shared(SCENE) else { return };
    assert_eq!(border_blocks().len(), 28);
    assert_agrees(&path, 1024, &VEACH_MIS_MEAN, &VEACH_MIS_SE);
}

#[test]
fn veach_mis_with_the_pixel_box_is_seen_to_disagree() {
    let Some(path) = shared(SCENE) else { return };
    let (mut file, _) = convert_file(&path, &[]).unwrap();
    (file.render.width, file.render.height) = (Some(SIZE), Some(SIZE));
    let mut loaded = build_model(&file, &path).unwrap();
    assert!(matches!(loaded.defaults.filter, Some(PixelFilter::Gaussian(_))), "{:?}", loaded.defaults.filter);
    loaded.defaults.filter = Some(PixelFilter::Pixel);
    let o = render_blocks("veach-mis with the pixel box", loaded, 1024, &VEACH_MIS_MEAN, &VEACH_MIS_SE);
    assert!(
        o.beyond >= 2,
        "the pixel box should be told apart: worst |z| {:.2}, {} beyond {Z_LIMIT}",
        o.worst,
        o.beyond
    );
}
