//! Mitsuba 0.6 scene files: every 0.6 form the importer upgrades (tests/data/v06/scene.xml:
//! camelCase names, `<lookAt>`, `<srgb>` in decimal and `#rrggbb`, `<spectrum>` as one value, as
//! wavelength:value pairs and as an .spd file, `<blackbody>`, `uoffset`/`uscale`, `bdpt`,
//! `ldrfilm`) renders as the same scene upgraded by hand to Mitsuba 3 (tests/data/v06/scene_v3.xml)
//! renders in pathtrace, and as Mitsuba 3.9.1 renders scene_v3.xml, block by block (8 × 8-pixel
//! blocks of a 64 × 64 image) and in its mean colour within 1%; each form also has a parser test,
//! and malformed 0.6 values give located errors.
//!
//! Reference (tests/data/v06/scene_blocks.rs): Mitsuba 3.9.1 `llvm_ad_rgb`, 16 renders × 1024 spp
//! of scene_v3.xml, made by the command in that file's first line.

mod blocks;

use pathtrace_scene::mitsuba::{convert_str, load_mitsuba, load_str};
use pathtrace_scene::native::model::{MaterialKind, SceneFile};
use std::path::{Path, PathBuf};

include!("data/v06/scene_blocks.rs");

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/v06").join(name)
}

/// The three substitutions of scene.xml, each named once with its place: bdpt, ldrfilm and the
/// black body.
fn load_v06() -> pathtrace_scene::LoadedScene {
    let (loaded, warnings) = load_mitsuba(&data("scene.xml"), &[]).unwrap();
    let expected = ["integrator `bdpt`", "film `ldrfilm`", "<blackbody> (4500 K)"];
    assert_eq!(warnings.len(), expected.len(), "{warnings:#?}");
    for (w, e) in warnings.iter().zip(expected) {
        assert!(w.contains(e) && w.contains("scene.xml:"), "{w} should name {e} and its place");
    }
    loaded
}

#[test]
fn v06_scene_renders_like_its_hand_upgrade() {
    // The same scene read from both files renders the same (the colours differ only by the
    // 6-digit rounding of scene_v3.xml and its 10 nm black-body samples).
    let (upgraded, warnings) = load_mitsuba(&data("scene_v3.xml"), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let ours = blocks::render_blocks("v06/scene.xml", load_v06(), 256, &V06_MEAN, &V06_SE).mean;
    let theirs = blocks::render_blocks("v06/scene_v3.xml", upgraded, 256, &V06_MEAN, &V06_SE).mean;
    for k in 0..3 {
        assert!((ours[k] / theirs[k] - 1.0).abs() < 2e-4, "{ours:?} vs {theirs:?}");
    }
}

/// Against Mitsuba 3.9.1's render of the hand-upgraded file: block by block and in the mean.
/// (This needed Mitsuba's one-sided `diffuse`, its black default BSDF on emitting shapes and its
/// rough-plastic transmittance; before them the image was 1.3% brighter.)
#[test]
fn v06_scene_agrees_with_mitsuba_block_by_block() {
    blocks::assert_scene_agrees("v06/scene.xml", load_v06(), 1024, &V06_MEAN, &V06_SE);
}

/// A 0.6 scene around `body` (a camera and a light, so it builds).
fn v06(body: &str) -> String {
    format!(
        r#"<scene version="0.6.0">
    <sensor type="perspective"><transform name="toWorld"><lookAt origin="0,0,-4" target="0,0,0" up="0,1,0"/></transform></sensor>
    <shape type="sphere"><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
{body}
</scene>"#
    )
}

fn convert(body: &str) -> (SceneFile, Vec<String>) {
    convert_str(&v06(body), &data("inline.xml"), &[]).unwrap_or_else(|e| panic!("{e}"))
}

/// The one material made for the scene's second shape (a rectangle with the BSDF under test).
/// The scattering model of a rectangle's `body` BSDF (one-sided or not: every opaque Mitsuba
/// BSDF outside `twosided` is, which `tests/mitsuba.rs` checks) and the import's warnings.
fn material(body: &str) -> (MaterialKind, Vec<String>) {
    let (file, warnings) = convert(&format!(r#"<shape type="rectangle">{body}</shape>"#));
    let name = &file.objects[1].material;
    (file.materials[name].kind.sides().0.clone(), warnings)
}

fn albedo(kind: &MaterialKind) -> String {
    match kind {
        MaterialKind::Lambertian { albedo } => format!("{albedo:?}"),
        MaterialKind::OneSided(inner) => albedo(inner),
        other => panic!("not lambertian: {other:?}"),
    }
}

#[test]
fn srgb_values_are_decoded_to_linear() {
    let (decimal, w) = material(r#"<bsdf type="diffuse"><srgb name="reflectance" value="0.5, 0.5, 0.5"/></bsdf>"#);
    assert!(w.is_empty(), "{w:?}");
    assert!(albedo(&decimal).contains("0.21404"), "{decimal:?}");
    let (hex, _) = material(r##"<bsdf type="diffuse"><srgb name="diffuseReflectance" value="#ff0000"/></bsdf>"##);
    assert!(albedo(&hex).contains("1.0") && albedo(&hex).contains("0.0"), "{hex:?}");
    // `intent` (0.6 only) is accepted and has no effect.
    let (with_intent, _) =
        material(r#"<bsdf type="diffuse"><srgb name="reflectance" intent="reflectance" value="0.5"/></bsdf>"#);
    assert_eq!(albedo(&with_intent), albedo(&decimal));
}

#[test]
fn spectra_in_every_form_load() {
    let one = material(r#"<bsdf type="diffuse"><spectrum name="reflectance" value="0.25"/></bsdf>"#).0;
    assert!(albedo(&one).contains("0.25"), "{one:?}");
    let list = material(
        r#"<bsdf type="diffuse"><spectrum name="reflectance" value="400:0.1, 500:0.3, 600:0.6, 700:0.9"/></bsdf>"#,
    )
    .0;
    // Mitsuba 3.9.1 scalar_rgb reads this list as (0.726577, 0.424956, 0.17397).
    assert!(albedo(&list).contains("0.7265"), "{list:?}");
    let file = material(r#"<bsdf type="diffuse"><spectrum name="reflectance" filename="tint.spd"/></bsdf>"#).0;
    assert!(matches!(file.sides().0, MaterialKind::Lambertian { .. }));
}

#[test]
fn black_bodies_become_rgb_with_a_warning() {
    let (file, w) = convert(
        r#"<emitter type="point"><point name="position" x="0" y="2" z="0"/>
            <blackbody name="intensity" temperature="6500K" scale="1e-4"/></emitter>"#,
    );
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("inline.xml:5:") && w[0].contains("6500 K"), "{w:?}");
    let text = format!("{:?}", file.lights);
    assert!(text.contains("Point"), "{text}");
}

#[test]
fn plugins_mitsuba_3_lacks_are_substituted_with_warnings() {
    let (kind, w) = material(r#"<bsdf type="phong"><float name="exponent" value="98"/></bsdf>"#);
    assert!(matches!(kind, MaterialKind::RoughPlastic { .. }), "{kind:?}");
    assert!(w[0].contains("phong") && w[0].contains("0.1414"), "{w:?}");

    let (kind, w) = material(
        r#"<bsdf type="coating"><float name="intIOR" value="1.6"/>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.4, 0.6"/></bsdf></bsdf>"#,
    );
    match &kind {
        MaterialKind::Plastic { albedo, .. } => assert!(format!("{albedo:?}").contains("0.4"), "{albedo:?}"),
        other => panic!("{other:?}"),
    }
    assert!(w[0].contains("`coating` over `diffuse`"), "{w:?}");

    let (kind, w) = material(
        r#"<bsdf type="roughcoating"><bsdf type="conductor"><string name="material" value="Au"/></bsdf></bsdf>"#,
    );
    assert!(matches!(kind, MaterialKind::Conductor { .. }), "{kind:?}");
    assert!(w[0].contains("using the BSDF it coats"), "{w:?}");

    let (kind, w) = material(r#"<bsdf type="roughdiffuse"><float name="alpha" value="0.3"/></bsdf>"#);
    assert!(matches!(kind.sides().0, MaterialKind::Lambertian { .. }) && w[0].contains("roughdiffuse"), "{w:?}");

    for (integrator, named) in [
        (r#"<integrator type="pssmlt"><integer name="maxDepth" value="3"/></integrator>"#, "pssmlt"),
        (
            r#"<integrator type="adaptive"><integrator type="path"><integer name="maxDepth" value="3"/></integrator></integrator>"#,
            "adaptive",
        ),
        (r#"<integrator type="volpath_simple"><integer name="maxDepth" value="3"/></integrator>"#, "volpath_simple"),
    ] {
        let (file, w) = convert(integrator);
        assert_eq!(file.render.max_depth, Some(3), "{integrator}");
        assert!(w.len() == 1 && w[0].contains(named), "{w:?}");
    }
}

#[test]
fn a_06_bumpmap_takes_its_scale_from_the_scale_texture() {
    let (file, w) = convert(
        r#"<shape type="rectangle"><bsdf type="bumpmap">
            <texture type="scale"><float name="scale" value="2.5"/>
                <texture type="checkerboard"/></texture>
            <bsdf type="diffuse"/></bsdf></shape>"#,
    );
    assert!(w.is_empty(), "{w:?}");
    let m = &file.materials[&file.objects[1].material];
    let normal = format!("{:?}", m.normal);
    assert!(normal.contains("Bump") && normal.contains("2.5"), "{normal}");
}

/// The error for a 0.6 body, as `FILE:LINE:COL: message`.
fn error(body: &str) -> String {
    let text = v06(body);
    match load_str(&text, &data("inline.xml"), &[]) {
        Ok(_) => panic!("accepted: {body}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn malformed_06_values_give_located_errors() {
    let bsdf = |colour: &str| format!(r#"<shape type="rectangle"><bsdf type="diffuse">{colour}</bsdf></shape>"#);
    for (body, expect) in [
        (bsdf(r##"<srgb name="reflectance" value="#12345"/>"##), "inline.xml:4:78: `#12345` is not a #rrggbb"),
        (bsdf(r##"<srgb name="reflectance" value="#12345g"/>"##), "inline.xml:4:78: `#12345g`"),
        (bsdf(r#"<srgb name="reflectance" value="0.1, 0.2"/>"#), "inline.xml:4:78: `0.1, 0.2` has 2 numbers"),
        (
            bsdf(r#"<spectrum name="reflectance" value="400:0.1, 500"/>"#),
            "inline.xml:4:82: `500` is not wavelength:value",
        ),
        (bsdf(r#"<spectrum name="reflectance" value="500:0.1, 400:0.3"/>"#), "wavelengths must increase"),
        (
            bsdf(r#"<spectrum name="reflectance" filename="missing.spd"/>"#),
            "inline.xml:4:85: spectrum file `missing.spd` not found",
        ),
        (
            bsdf(r#"<blackbody name="reflectance" temperature="hot"/>"#),
            "inline.xml:4:89: <blackbody> temperature `hot`",
        ),
        (
            r#"<shape type="rectangle"><bsdf type="lambert"/></shape>"#.to_string(),
            "inline.xml:4:37: unknown bsdf type `lambert`",
        ),
        (r#"<luminaire type="point"/>"#.to_string(), "inline.xml:4:1: unknown element <luminaire> (Mitsuba 0.3"),
        (r#"<integrator type="adaptive"/>"#.to_string(), "inline.xml:4:1: integrator `adaptive` needs a nested"),
    ] {
        let e = error(&body);
        assert!(e.contains(expect), "{body}\n  gave: {e}\n  expected: {expect}");
    }
}
