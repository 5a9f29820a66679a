//! Thin-lens and orthographic sensors against Mitsuba 3: tests/data/thinlens_box.xml (a box with
//! spheres at three depths through a wide `thinlens` aperture focused on the nearest one) and
//! tests/data/orthographic_box.xml (the box through an `orthographic` sensor whose view size
//! comes from its `to_world` scale) load without a warning and agree with Mitsuba block by block
//! (8 × 8-pixel blocks of a 64 × 64 image) and in their mean colour within 1%. The thin-lens
//! scene rendered through a pinhole is told apart, so the blur is what agrees.
//!
//! References (tests/data/*_box_blocks.rs): Mitsuba 3.9.1 `scalar_rgb`, 16 renders × 1024 spp,
//! from `.venv-peers/bin/python benches/peers/block_means.py thinlens_box.xml --scenes
//! crates/pathtrace-scene/tests/data --spp 1024 --runs 16 --name THINLENS_BOX` (and
//! `orthographic_box.xml … --name ORTHOGRAPHIC_BOX`).

mod blocks;

use pathtrace::Lens;
use pathtrace_scene::mitsuba::load_mitsuba;
use std::path::{Path, PathBuf};

include!("data/thinlens_box_blocks.rs");
include!("data/orthographic_box_blocks.rs");

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

#[test]
fn thin_lens_matches_mitsuba_block_by_block() {
    let path = data("thinlens_box.xml");
    let (loaded, warnings) = load_mitsuba(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert_eq!(loaded.scene.camera.lens, Lens::ThinLens { aperture_radius: 0.6, focus_distance: 2.8 });
    blocks::assert_agrees(&path, 1024, &THINLENS_BOX_MEAN, &THINLENS_BOX_SE);
}

#[test]
fn the_same_view_through_a_pinhole_is_told_apart() {
    let path = data("thinlens_box.xml");
    let (mut loaded, _) = load_mitsuba(&path, &[]).unwrap();
    loaded.scene.camera.lens = Lens::Pinhole;
    let o = blocks::render_blocks("thinlens_box.xml as a pinhole", loaded, 1024, &THINLENS_BOX_MEAN, &THINLENS_BOX_SE);
    assert!(o.beyond >= 3, "a pinhole should be told apart: worst |z| {:.2}, {} beyond", o.worst, o.beyond);
}

#[test]
fn orthographic_matches_mitsuba_block_by_block() {
    let path = data("orthographic_box.xml");
    let (loaded, warnings) = load_mitsuba(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let Lens::Orthographic { height } = loaded.scene.camera.lens else { panic!("{:?}", loaded.scene.camera.lens) };
    // Mitsuba's view is 2 camera units high (square film), scaled by 1.3.
    assert!((height - 2.6).abs() < 1e-5, "{height}");
    blocks::assert_agrees(&path, 1024, &ORTHOGRAPHIC_BOX_MEAN, &ORTHOGRAPHIC_BOX_SE);
}
