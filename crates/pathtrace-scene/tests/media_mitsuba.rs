//! Participating media against Mitsuba 3's `volpath`: tests/data/media/fog_shafts.xml (the camera
//! inside null-bounded chromatic fog, sunlight through two slits drawing light shafts) and
//! tests/data/media/jelly_sphere.xml (a glass sphere filled with a scattering, red-leaning
//! medium on a floor under a sky and an area light) load without a warning and agree with
//! Mitsuba block by block (8 × 8-pixel blocks of a 64 × 64 image, |z| < 3.5 but for one
//! block-channel, none beyond 4.5) and in their mean colour within 1%, the fog also truncated at
//! depth 3 (Mitsuba's depth counting). Each scene without its medium is told apart, so the medium
//! is what agrees.
//!
//! References (tests/data/media/*_blocks.rs): Mitsuba 3.9.1 `llvm_ad_rgb`, 16 renders × 1024
//! spp, from `.venv-peers/bin/python benches/peers/block_means.py fog_shafts.xml --scenes
//! crates/pathtrace-scene/tests/data/media --spp 1024 --runs 16 --variant llvm_ad_rgb --name
//! FOG_SHAFTS` (and `jelly_sphere.xml … --name JELLY_SPHERE`; `fog_shafts.xml … -D max_depth=3
//! --name FOG_SHAFTS_DEPTH3`).

mod blocks;

use pathtrace_scene::mitsuba::{build_model, convert_file};
use std::path::{Path, PathBuf};

include!("data/media/fog_shafts_blocks.rs");
include!("data/media/jelly_sphere_blocks.rs");
include!("data/media/fog_shafts_depth3_blocks.rs");

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/media").join(name)
}

#[test]
fn fog_with_light_shafts_matches_mitsuba_block_by_block() {
    blocks::assert_agrees(&data("fog_shafts.xml"), 512, &FOG_SHAFTS_MEAN, &FOG_SHAFTS_SE);
}

/// At `max_depth` 3 a path has two vertices, medium or surface: depth must count medium
/// interactions as Mitsuba's `volpath` does (a medium vertex is one segment, a null crossing none)
/// for the truncated image to agree.
#[test]
fn fog_truncated_at_depth_3_matches_mitsuba_block_by_block() {
    let path = data("fog_shafts.xml");
    let (mut file, warnings) = convert_file(&path, &[("max_depth", "3")]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert_eq!(file.render.max_depth, Some(3));
    (file.render.width, file.render.height) = (Some(blocks::SIZE), Some(blocks::SIZE));
    let loaded = build_model(&file, &path).unwrap();
    blocks::assert_scene_agrees(
        "fog_shafts.xml at depth 3",
        loaded,
        512,
        &FOG_SHAFTS_DEPTH3_MEAN,
        &FOG_SHAFTS_DEPTH3_SE,
    );
}

#[test]
fn jelly_in_a_glass_sphere_matches_mitsuba_block_by_block() {
    blocks::assert_agrees(&data("jelly_sphere.xml"), 256, &JELLY_SPHERE_MEAN, &JELLY_SPHERE_SE);
}

#[test]
fn the_fog_without_its_medium_is_told_apart() {
    let path = data("fog_shafts.xml");
    let (mut file, _) = convert_file(&path, &[]).unwrap();
    for o in &mut file.objects {
        o.interior = None;
    }
    file.camera.medium = None;
    (file.render.width, file.render.height) = (Some(blocks::SIZE), Some(blocks::SIZE));
    let loaded = build_model(&file, &path).unwrap();
    let o = blocks::render_blocks("fog_shafts.xml without fog", loaded, 128, &FOG_SHAFTS_MEAN, &FOG_SHAFTS_SE);
    assert!(o.beyond >= 10, "no fog should be told apart: worst |z| {:.2}, {} beyond", o.worst, o.beyond);
}

#[test]
fn the_glass_sphere_without_jelly_is_told_apart() {
    let path = data("jelly_sphere.xml");
    let (mut file, _) = convert_file(&path, &[]).unwrap();
    for o in &mut file.objects {
        o.interior = None;
    }
    (file.render.width, file.render.height) = (Some(blocks::SIZE), Some(blocks::SIZE));
    let loaded = build_model(&file, &path).unwrap();
    let o = blocks::render_blocks("jelly_sphere.xml without jelly", loaded, 64, &JELLY_SPHERE_MEAN, &JELLY_SPHERE_SE);
    assert!(o.beyond >= 10, "an empty sphere should be told apart: worst |z| {:.2}, {} beyond", o.worst, o.beyond);
}
