//! One-sided diffuse surfaces against Mitsuba 3: tests/data/backfaces.xml (cards showing their
//! backs to the camera, one plain `diffuse` and one `twosided`, a card facing the camera, a floor,
//! an area light behind the cards; path tracing to depth 4) agrees with Mitsuba block by block
//! (8 × 8-pixel blocks of a 64 × 64 image) and in its mean colour within 1%; the same scene with
//! every surface shaded on both faces (pathtrace's reading before) is seen to disagree. Also
//! tests/data/smooth_edges/scene.xml: one-sided surfaces whose smooth normals face the viewer
//! where the true surface does not (shaded, as Mitsuba's shading-frame rule).
//!
//! Reference (tests/data/backfaces_blocks.rs): Mitsuba 3.9.1 `llvm_ad_rgb`, 16 renders × 1024
//! spp, made by the command in that file's first line.

mod blocks;

use pathtrace_scene::mitsuba::{build_model, convert_file, load_mitsuba};
use pathtrace_scene::native::model::MaterialKind;
use std::path::Path;

include!("data/backfaces_blocks.rs");
include!("data/smooth_edges/blocks.rs");

fn path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/backfaces.xml")
}

#[test]
fn diffuse_back_faces_match_mitsuba_block_by_block() {
    let (loaded, warnings) = load_mitsuba(&path(), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    blocks::assert_scene_agrees("backfaces.xml", loaded, 1024, &BACKFACES_MEAN, &BACKFACES_SE);
}

#[test]
fn two_sided_diffuse_is_seen_to_disagree() {
    let (mut file, _) = convert_file(&path(), &[]).unwrap();
    let mut unwrapped = 0;
    for m in file.materials.values_mut() {
        if let MaterialKind::OneSided(inner) = &m.kind {
            m.kind = (**inner).clone();
            unwrapped += 1;
        }
    }
    // The floor and the plain card are one-sided; the twosided card and the light are not.
    assert_eq!(unwrapped, 2);
    let loaded = build_model(&file, &path()).unwrap();
    let o = blocks::render_blocks("backfaces.xml (two-sided)", loaded, 1024, &BACKFACES_MEAN, &BACKFACES_SE);
    assert!(o.beyond >= 2, "two-sided shading should be told apart: worst |z| {:.2}, {} beyond", o.worst, o.beyond);
}

/// One-sided diffuse with smooth normals where the true surface faces away from the viewer but
/// the shading normal faces it (tests/data/smooth_edges/scene.xml: a card with bent vertex
/// normals seen from just below, and a low-poly smooth sphere, whose silhouettes show the
/// reverse): Mitsuba shades by the cosine in the shading frame, and so do we. Judging by the
/// true normal instead (black where it faces away) fails this test (see docs/scene-format.md).
#[test]
fn one_sided_smooth_normals_follow_the_shading_frame_as_mitsuba() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/smooth_edges/scene.xml");
    let (file, warnings) = convert_file(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let one_sided = file.materials.values().filter(|m| matches!(m.kind, MaterialKind::OneSided(_))).count();
    assert_eq!(one_sided, 4, "the two cards, the sphere and the floor");
    blocks::assert_agrees(&path, 1024, &SMOOTH_EDGES_MEAN, &SMOOTH_EDGES_SE);
}
