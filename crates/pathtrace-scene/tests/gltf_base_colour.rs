//! glTF's base colour = baseColorFactor × baseColorTexture and opacity = baseColorFactor's alpha
//! × the texture's alpha (glTF 2.0 §3.9.2), as a bitmap texture's `factor`:
//! tests/data/maps/basecolor.gltf (a Lambertian floor under a 4 × 4 sRGB RGBA texture, factor
//! [0.9, 0.6, 0.3, 0.7], alphaMode BLEND, lit by a standing panel), written by
//! benches/peers/make_gltf_texture_assets.py with its Mitsuba 3 twin basecolor.xml (a `mask` of
//! the pre-multiplied alpha around a `diffuse` of the pre-multiplied, sRGB-decoded colours, both
//! PFM bitmaps; rendered with `volpath`, which passes shadow rays through the mask as ours does,
//! and unlimited depth, as tests/gltf_maps.rs does for cut-outs). It loads without a warning and
//! agrees block by block with Mitsuba 3.9.1 `scalar_rgb` (16 × 1024 spp; the command heads the
//! block file), and so does our import of the twin. Dropping either factor, as the import did
//! before, fails the same test. Converted to TOML or JSON, the factors survive.

mod blocks;

use pathtrace_scene::gltf::{build_model, convert_file, load_gltf};
use pathtrace_scene::mitsuba::load_mitsuba;
use pathtrace_scene::native::model::{Colour, MaterialKind, SceneFile, TextureDef, Triple};
use std::path::{Path, PathBuf};

include!("data/maps/basecolor_blocks.rs");

const SPP: u32 = 256;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/maps").join(name)
}

/// The floor's albedo and opacity bitmap factors.
fn factors(file: &mut SceneFile) -> (&mut Triple, &mut Triple) {
    let floor = file.materials.get_mut("gltf-0").expect("the floor");
    let MaterialKind::Lambertian { albedo: Colour::Texture(TextureDef::Bitmap { factor: albedo, alpha: false, .. }) } =
        &mut floor.kind
    else {
        panic!("the floor is not a textured lambertian")
    };
    let Some(Colour::Texture(TextureDef::Bitmap { factor: alpha, alpha: true, raw: true, .. })) =
        floor.opacity.as_mut().map(|o| &mut o.texture)
    else {
        panic!("an alpha texture")
    };
    (albedo, alpha)
}

#[test]
fn base_colour_factor_times_texture_matches_its_mitsuba_twin_block_by_block() {
    let path = data("basecolor.gltf");
    let (mut file, warnings) = convert_file(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert_eq!(file.materials["gltf-0"].opacity.as_ref().unwrap().cutoff, None, "BLEND");
    let (albedo, alpha) = factors(&mut file);
    assert_eq!(albedo.vec3().to_array(), [0.9, 0.6, 0.3]);
    assert_eq!(alpha.vec3().to_array(), [0.7; 3]);
    let (mut loaded, _) = load_gltf(&path, &[]).unwrap();
    loaded.defaults.max_depth = -1;
    blocks::assert_scene_agrees("basecolor.gltf", loaded, SPP, &GLTF_BASECOLOR_MEAN, &GLTF_BASECOLOR_SE);
    let (twin, warnings) = load_mitsuba(&data("basecolor.xml"), &[("integrator", "path")]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    blocks::assert_scene_agrees("basecolor.xml", twin, SPP, &GLTF_BASECOLOR_MEAN, &GLTF_BASECOLOR_SE);
}

/// The import before the factor existed (the texture alone, the texture's alpha alone) is far
/// from Mitsuba's render: the block test above could fail.
#[test]
fn dropping_either_factor_fails_the_block_test() {
    let path = data("basecolor.gltf");
    for (what, drop_colour) in [("colour", true), ("alpha", false)] {
        let (mut file, _) = convert_file(&path, &[]).unwrap();
        let (albedo, alpha) = factors(&mut file);
        *(if drop_colour { albedo } else { alpha }) = Triple::ONE;
        let mut loaded = build_model(&file, &path).unwrap();
        loaded.defaults.max_depth = -1;
        let scene = format!("basecolor.gltf without the {what} factor");
        let o = blocks::render_blocks(&scene, loaded, SPP, &GLTF_BASECOLOR_MEAN, &GLTF_BASECOLOR_SE);
        assert!(o.worst > 10.0 && o.beyond > 10, "{scene}: worst |z| {:.2}, {} beyond", o.worst, o.beyond);
    }
}

/// `pathtrace convert`'s path: the converted model written as TOML or JSON carries both factors
/// and reads back equal, and the TOML renders exactly as the glTF.
#[test]
fn converted_factors_round_trip_through_toml_and_json() {
    use pathtrace::{render, RenderSettings};
    use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
    use std::sync::Arc;
    let path = data("basecolor.gltf");
    let (file, _) = convert_file(&path, &[]).unwrap();
    let beside = data("converted.toml");
    for format in [Format::Toml, Format::Json] {
        let text = to_string(&file, format).unwrap();
        let compact: String = text.chars().filter(|c| !c.is_whitespace()).collect();
        for f in ["factor=[0.9,0.6,0.3]", "factor=0.7"] {
            let f = if format == Format::Json { f.replace("factor=", "\"factor\":") } else { f.to_string() };
            assert!(compact.contains(&f), "{f} not in {text}");
        }
        assert_eq!(parse_str(&text, format, &beside).unwrap(), file, "{text}");
    }
    let text = to_string(&file, Format::Toml).unwrap();
    let s = RenderSettings { width: blocks::SIZE, height: blocks::SIZE, spp: 4, seed: 3, ..Default::default() };
    let ours = render(Arc::new(load_str(&text, Format::Toml, &beside).unwrap().scene), s.clone()).unwrap();
    let (direct, _) = load_gltf(&path, &[]).unwrap();
    assert!(render(Arc::new(direct.scene), s).unwrap().film.image().pixels == ours.film.image().pixels);
}
