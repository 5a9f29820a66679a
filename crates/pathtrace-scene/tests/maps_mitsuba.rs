//! Normal and bump maps against Mitsuba 3: tests/data/maps/normal_bump.xml (a `normalmap`
//! diffuse floor and a `bumpmap` rough plastic wall, under a square lamp and a directional
//! light; depth 3) loads without a warning and agrees with Mitsuba block by block (8 × 8-pixel
//! blocks of a 64 × 64 image) and in its mean colour within 1%.
//!
//! Reference (tests/data/maps/normal_bump_blocks.rs): Mitsuba 3.9.1 `llvm_ad_rgb`, 16 renders ×
//! 1024 spp, from `DRJIT_LIBLLVM_PATH=…/libLLVM-19.so .venv-peers/bin/python
//! benches/peers/block_means.py normal_bump.xml --scenes crates/pathtrace-scene/tests/data/maps
//! --spp 1024 --runs 16 --name NORMAL_BUMP --variant llvm_ad_rgb`; the images come from
//! benches/peers/make_map_assets.py. The same pattern covers textured area emitters
//! (emitter_texture.xml, emissive.xml) and a rough plastic with an α texture (plastic_alpha.xml
//! against its constant-α twin); each block file's first line is its command.

mod blocks;

use pathtrace_scene::mitsuba::load_mitsuba;
use std::path::Path;

include!("data/maps/normal_bump_blocks.rs");
include!("data/maps/mask_blocks.rs");
include!("data/maps/roughness_blocks.rs");
include!("data/maps/emitter_texture_blocks.rs");
include!("data/maps/emissive_blocks.rs");
include!("data/maps/plastic_alpha_blocks.rs");

fn data(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/maps").join(name)
}

#[test]
fn normal_and_bump_maps_match_mitsuba_block_by_block() {
    let path = data("normal_bump.xml");
    let (loaded, warnings) = load_mitsuba(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let perturbed =
        (0..loaded.scene.materials().len() as u32).filter(|&m| loaded.scene.normal_perturbation(m).is_some()).count();
    assert_eq!(perturbed, 2);
    blocks::assert_agrees(&path, 1024, &NORMAL_BUMP_MEAN, &NORMAL_BUMP_SE);
}

/// Opacity masks (a textured cut-out and a constant 0.4, each around a two-sided diffuse) cast
/// shadows with holes under an area light and a directional light; the reference is Mitsuba's
/// `volpath`, whose shadow rays pass masks as ours do (see the scene's comment).
#[test]
fn opacity_masks_match_mitsuba_block_by_block() {
    let path = data("mask.xml");
    let (loaded, warnings) = load_mitsuba(&path, &[("integrator", "path")]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert!(loaded.scene.has_cutouts());
    blocks::assert_scene_agrees("mask.xml", loaded, 1024, &MASK_MEAN, &MASK_SE);
}

/// A rough aluminium floor whose GGX α is a texture (α from 0 to 1 in ridges) reflecting a wall
/// and a lamp: Mitsuba's textured `alpha` (reference `block_means.py roughness.xml … --name
/// ROUGHNESS --variant llvm_ad_rgb`).
#[test]
fn textured_roughness_matches_mitsuba_block_by_block() {
    let path = data("roughness.xml");
    let (loaded, warnings) = load_mitsuba(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert!(loaded.scene.is_material_textured(0), "the floor's α is textured");
    blocks::assert_agrees(&path, 1024, &ROUGHNESS_MEAN, &ROUGHNESS_SE);
}

/// A GGX rough plastic floor whose α is a texture (four strips, α 0.05 to 0.7, nearest) under a
/// lamp: plastic_alpha.xml read by us; Mitsuba's `roughplastic` takes no α texture, so the
/// reference is its twin plastic_alpha_twin.xml, the floor cut into four constant-α rectangles
/// (`block_means.py plastic_alpha_twin.xml … --name PLASTIC_ALPHA --variant llvm_ad_rgb`). The
/// twin, read by us with constant α, must agree too.
#[test]
fn textured_rough_plastic_matches_its_mitsuba_twin_block_by_block() {
    let path = data("plastic_alpha.xml");
    let (loaded, warnings) = load_mitsuba(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert!(loaded.scene.is_material_textured(0), "the floor's α is textured");
    blocks::assert_agrees(&path, 1024, &PLASTIC_ALPHA_MEAN, &PLASTIC_ALPHA_SE);
    blocks::assert_agrees(&data("plastic_alpha_twin.xml"), 1024, &PLASTIC_ALPHA_MEAN, &PLASTIC_ALPHA_SE);
}

/// Area emitters whose radiance is a `bitmap`: a rectangle lamp (emitter_texture.xml, an sRGB
/// PNG looked up at the rectangle's uv; reference `block_means.py emitter_texture.xml … --name
/// EMITTER_TEXTURE --variant llvm_ad_rgb`) and an OBJ panel (emissive.xml, a PFM at the mesh's
/// uv; the glTF twins' reference GLTF_EMISSIVE, which Mitsuba rendered from this very file).
#[test]
fn textured_area_emitters_match_mitsuba_block_by_block() {
    for (name, mean, se) in [
        ("emitter_texture.xml", &EMITTER_TEXTURE_MEAN, &EMITTER_TEXTURE_SE),
        ("emissive.xml", &GLTF_EMISSIVE_MEAN, &GLTF_EMISSIVE_SE),
    ] {
        let path = data(name);
        let (file, warnings) = pathtrace_scene::mitsuba::convert_file(&path, &[]).unwrap();
        assert!(warnings.is_empty(), "{name}: {warnings:#?}");
        let textured = file.materials.values().filter_map(|m| m.emission.as_ref()).filter(|e| e.texture.is_some());
        assert_eq!(textured.count(), 1, "{name}: one textured emitter");
        blocks::assert_agrees(&path, 1024, mean, se);
    }
}

#[test]
fn textured_area_emitter_errors_are_located() {
    let at = data("t.xml");
    let err = |xml: &str| pathtrace_scene::mitsuba::load_str(xml, &at, &[]).map(|_| ()).unwrap_err().to_string();
    let lamp = |shape: &str, file: &str| {
        format!(
            r#"<scene version="3.0.0">
    <shape type="{shape}"><emitter type="area"><texture name="radiance" type="bitmap">
        <string name="filename" value="{file}"/></texture></emitter></shape>
</scene>"#
        )
    };
    let e = err(&lamp("rectangle", "missing.png"));
    assert!(e.contains("t.xml:3:") && e.contains("missing.png"), "{e}");
    let e = err(&lamp("sphere", "emissive.png"));
    assert!(e.contains("t.xml:2:") && e.contains("meshes and rectangles only"), "{e}");
}

/// A floor shape with `bsdf` around a light, in a Mitsuba scene read from the maps folder.
fn scene_with(bsdf: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <shape type="rectangle">{bsdf}</shape>
    <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>
        <integer name="height" value="8"/></film></sensor>
    <emitter type="directional"><vector name="direction" value="0, 0, -1"/></emitter>
</scene>"#
    )
}

#[test]
fn malformed_wrappers_are_located_and_explained() {
    let at = data("t.xml");
    let err = |bsdf: &str| {
        pathtrace_scene::mitsuba::load_str(&scene_with(bsdf), &at, &[]).map(|_| ()).unwrap_err().to_string()
    };
    let e = err(r#"<bsdf type="normalmap"><texture name="normalmap" type="bitmap">
        <string name="filename" value="normal.png"/></texture></bsdf>"#);
    assert!(e.contains("needs a nested <bsdf>") && e.contains("t.xml:2:"), "{e}");
    let e = err(r#"<bsdf type="normalmap"><bsdf type="diffuse"/></bsdf>"#);
    assert!(e.contains("needs a `normalmap` texture"), "{e}");
    let e = err(r#"<bsdf type="bumpmap"><bsdf type="diffuse"/></bsdf>"#);
    assert!(e.contains("needs a nested <texture>"), "{e}");
    let e = err(r#"<bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="missing.png"/>
        </texture><bsdf type="diffuse"/></bsdf>"#);
    assert!(e.contains("missing.png"), "{e}");
    let e = err(r#"<bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="height.png"/>
        </texture><bsdf type="normalmap"><rgb name="normalmap" value="0.5, 0.5, 1"/><bsdf type="diffuse"/></bsdf></bsdf>"#);
    assert!(e.contains("only one"), "{e}");
    let e = err(r#"<bsdf type="mask"><float name="opacity" value="0.5"/></bsdf>"#);
    assert!(e.contains("`mask` BSDF needs a nested <bsdf>"), "{e}");
    let e = err(r#"<bsdf type="mask"><float name="opacity" value="oops"/><bsdf type="diffuse"/></bsdf>"#);
    assert!(e.contains("t.xml:2:"), "{e}");
    // A normal map that is not `raw` is read raw, with a warning; a constant one is accepted.
    let (_, warnings) = pathtrace_scene::mitsuba::load_str(
        &scene_with(
            r#"<bsdf type="twosided"><bsdf type="normalmap"><texture name="normalmap" type="bitmap">
            <string name="filename" value="normal.png"/></texture><bsdf type="diffuse"/></bsdf></bsdf>"#,
        ),
        &at,
        &[],
    )
    .unwrap();
    assert!(warnings.iter().any(|w| w.contains("read raw")), "{warnings:?}");
}
