//! Directional lights against Mitsuba 3: tests/data/directional.xml (two `directional` emitters,
//! one by `direction` and one by a `to_world` lookat, over a diffuse floor, wall and sphere; path
//! tracing to depth 4) loads without a warning and agrees with Mitsuba block by block (8 × 8-pixel
//! blocks of a 64 × 64 image) and in its mean colour within 1%.
//!
//! Reference (tests/data/directional_blocks.rs): Mitsuba 3.9.1 `scalar_rgb`, 16 renders × 1024
//! spp, from `.venv-peers/bin/python benches/peers/block_means.py directional.xml --scenes
//! crates/pathtrace-scene/tests/data --spp 1024 --runs 16 --name DIRECTIONAL`.

mod blocks;

use pathtrace::light::Light;
use pathtrace_scene::mitsuba::load_mitsuba;
use std::path::Path;

include!("data/directional_blocks.rs");

#[test]
fn directional_lights_match_mitsuba_block_by_block() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/directional.xml");
    let (loaded, warnings) = load_mitsuba(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert_eq!(loaded.scene.lights.lights().iter().filter(|l| matches!(l, Light::Directional(_))).count(), 2);
    blocks::assert_agrees(&path, 1024, &DIRECTIONAL_MEAN, &DIRECTIONAL_SE);
}
