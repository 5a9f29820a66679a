//! Block-by-block z-tests of a Mitsuba XML scene rendered by us against Mitsuba 3's block means
//! and standard errors (made by benches/peers/block_means.py): each 8 × 8-pixel block's mean per
//! channel, z = (ours − theirs) / √(σ²ours + σ²theirs).

#![allow(dead_code)]

use pathtrace::{render, RenderSettings};
use pathtrace_scene::mitsuba::{build_model, convert_file};
use pathtrace_scene::native::model::{MeshNormals, ShapeDef};
use pathtrace_scene::LoadedScene;
use std::path::Path;
use std::sync::Arc;

pub const SIZE: u32 = 64;
pub const BLOCK: u32 = 8;
/// A block-channel whose |z| exceeds this counts as disagreeing; 192 block-channels per scene
/// expect 0.09 such by chance.
pub const Z_LIMIT: f64 = 3.5;

/// How a render compared with the reference blocks.
pub struct Outcome {
    /// The largest |z| of any block-channel.
    pub worst: f64,
    /// Block-channels with |z| above [`Z_LIMIT`].
    pub beyond: usize,
    /// Our image mean.
    pub mean: [f64; 3],
}

pub fn block_test(path: &Path, normals: MeshNormals, spp: u32, mean: &[[f64; 3]], se: &[[f64; 3]]) -> Outcome {
    let scene = path.display();
    let (mut file, warnings) = convert_file(path, &[]).unwrap_or_else(|e| panic!("{scene}: {e}"));
    assert!(warnings.is_empty(), "{scene}: {warnings:#?}");
    // Mitsuba rendered the scene resized to SIZE × SIZE: the camera is built for that film (the
    // scenes used here give the fov of the smaller axis, or are square already).
    (file.render.width, file.render.height) = (Some(SIZE), Some(SIZE));
    for o in &mut file.objects {
        if let ShapeDef::Mesh { normals: n, .. } = &mut o.shape {
            *n = normals;
        }
    }
    let loaded = build_model(&file, path).unwrap_or_else(|e| panic!("{scene}: {e}"));
    let o = render_blocks(&scene.to_string(), loaded, spp, mean, se);
    eprintln!("  (normals {normals:?})");
    o
}

/// Renders an already loaded scene (its film must be SIZE × SIZE) and compares its blocks.
pub fn render_blocks(scene: &str, loaded: LoadedScene, spp: u32, mean: &[[f64; 3]], se: &[[f64; 3]]) -> Outcome {
    let d = loaded.defaults;
    let mut s = RenderSettings { width: SIZE, height: SIZE, spp, seed: 7, ..Default::default() };
    s.filter = d.filter.unwrap_or_default();
    s.path.max_depth = d.max_depth;
    let out = render(Arc::new(loaded.scene), s).unwrap();
    assert_eq!(out.progress.dropped_samples, 0, "{scene}: NaN samples");
    let n = SIZE / BLOCK;
    let (mut worst, mut beyond) = (0.0f64, 0);
    for by in 0..n {
        for bx in 0..n {
            let i = (by * n + bx) as usize;
            let est = out.film.region_estimate(bx * BLOCK, by * BLOCK, (bx + 1) * BLOCK, (by + 1) * BLOCK);
            for k in 0..3 {
                let var = est.variance_of_mean[k] + se[i][k] * se[i][k];
                if var == 0.0 {
                    // A block of constant colour (the sky alone): equal up to Mitsuba's storage of
                    // RGB constants (llvm_ad_rgb returns a sky of 0.4 as 0.3999961).
                    let tolerance = 2e-5 * mean[i][k].abs();
                    assert!(
                        (est.mean[k] - mean[i][k]).abs() <= tolerance,
                        "{scene} block {i} channel {k}: {} vs {}",
                        est.mean[k],
                        mean[i][k]
                    );
                    continue;
                }
                let z = (est.mean[k] - mean[i][k]) / var.sqrt();
                worst = worst.max(z.abs());
                beyond += usize::from(z.abs() > Z_LIMIT);
            }
        }
    }
    let whole = out.film.region_estimate(0, 0, SIZE, SIZE).mean;
    eprintln!("{scene}: worst |z| {worst:.2}, {beyond} block-channels beyond {Z_LIMIT}, mean {whole:.5?}");
    Outcome { worst, beyond, mean: whole }
}

pub fn assert_agrees(path: &Path, spp: u32, mean: &[[f64; 3]], se: &[[f64; 3]]) {
    let o = block_test(path, MeshNormals::Smooth, spp, mean, se);
    check(&path.display().to_string(), &o, mean);
}

/// [`render_blocks`] with the agreement asserted; returns the outcome.
pub fn assert_scene_agrees(scene: &str, loaded: LoadedScene, spp: u32, mean: &[[f64; 3]], se: &[[f64; 3]]) -> Outcome {
    let o = render_blocks(scene, loaded, spp, mean, se);
    check(scene, &o, mean);
    o
}

/// At most one block-channel beyond [`Z_LIMIT`], none beyond 4.5, and the image mean within 1%.
fn check(scene: &str, o: &Outcome, mean: &[[f64; 3]]) {
    assert!(o.beyond <= 1 && o.worst < 4.5, "{scene}: worst |z| {:.2}, {} beyond {Z_LIMIT}", o.worst, o.beyond);
    let theirs: [f64; 3] = std::array::from_fn(|k| mean.iter().map(|b| b[k]).sum::<f64>() / mean.len() as f64);
    for k in 0..3 {
        assert!(
            (o.mean[k] - theirs[k]).abs() <= 0.01 * theirs[k] + 1e-4,
            "{scene} channel {k}: {:?} vs {theirs:?}",
            o.mean
        );
    }
}
