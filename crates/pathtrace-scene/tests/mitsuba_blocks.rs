//! Acceptance for meshes without stored normals: the public scenes whose PLY or OBJ files have
//! no normals (the bunny, the teapot, and cbox-classic, whose non-planar red wall then shades
//! smoothly in a scene small enough for the brute-force intersector) agree with Mitsuba 3 block
//! by block, which needs Mitsuba's smooth vertex normals (angle-weighted, computed after the
//! transform). The same renders with flat shading (the `file` choice, pathtrace's reading before
//! smooth normals) disagree, which shows the test can see the difference.
//!
//! References (tests/data/mitsuba_blocks.rs): Mitsuba 3.9.1 `scalar_rgb`, each scene as written
//! but with a 64 × 64 film, 16 renders × 1024 spp with seeds 0–15; per 8 × 8-pixel block the mean
//! and its standard error from the spread of the 16 renders, made by
//! `.venv-peers/bin/python benches/peers/block_means.py SCENE --spp 1024 --runs 16 --name NAME`.
//! Skipped with a note when ../shared/scenes is absent.

mod blocks;

use blocks::{assert_agrees, block_test};
use pathtrace::integrator::PathSettings;
use pathtrace::wide::WideScene;
use pathtrace_scene::mitsuba::{build_model, convert_file};
use pathtrace_scene::native::model::MeshNormals;
use std::path::{Path, PathBuf};

include!("data/mitsuba_blocks.rs");

fn shared(scene: &str) -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    if !dir.is_dir() {
        eprintln!("skipped: {} is absent", dir.display());
        return None;
    }
    Some(dir.join(scene))
}

fn assert_agrees_shared(scene: &str, spp: u32, mean: &[[f64; 3]], se: &[[f64; 3]]) {
    if let Some(path) = shared(scene) {
        assert_agrees(&path, spp, mean, se);
    }
}

#[test]
fn bunny_agrees_with_mitsuba_block_by_block() {
    assert_agrees_shared("bunny/docs/scenes/shape_ply_bunny.xml", 512, &BUNNY_MEAN, &BUNNY_SE);
}

#[test]
fn flat_shaded_bunny_is_seen_to_disagree() {
    let Some(path) = shared("bunny/docs/scenes/shape_ply_bunny.xml") else { return };
    let o = block_test(&path, MeshNormals::File, 2048, &BUNNY_MEAN, &BUNNY_SE);
    assert!(o.beyond >= 2, "flat shading should be told apart: worst |z| {:.2}, {} beyond", o.worst, o.beyond);
}

#[test]
fn teapot_agrees_with_mitsuba_block_by_block() {
    assert_agrees_shared("teapot-simple/simple.xml", 512, &TEAPOT_MEAN, &TEAPOT_SE);
}

const CBOX_CLASSIC: &str = "cbox-classic/docs/scenes/integrator_depth_inf.xml";

#[test]
fn cbox_classic_agrees_with_mitsuba_block_by_block() {
    assert_agrees_shared(CBOX_CLASSIC, 512, &CBOX_CLASSIC_MEAN, &CBOX_CLASSIC_SE);
}

/// The test above exercises the brute-force intersector's smooth normals only if the scene
/// takes it (38 triangles, the red wall's two not coplanar).
#[test]
fn cbox_classic_takes_the_brute_force_intersector() {
    let Some(path) = shared(CBOX_CLASSIC) else { return };
    let (file, _) = convert_file(&path, &[]).unwrap();
    let loaded = build_model(&file, &path).unwrap();
    assert!(WideScene::new(&loaded.scene, &PathSettings::default()).brute_force());
}
