//! glTF's metallic channel per texel as a `blend` (Mitsuba 3's `blendbsdf`):
//! tests/data/maps/metallic.gltf (a floor whose metallicRoughnessTexture's blue channel × 0.9
//! mixes a Lambertian base and a rough metal texel by texel, lit by a constant panel) and its
//! Mitsuba 3 twin metallic.xml (a `blendbsdf` whose weight is a bitmap of the same texels),
//! written by benches/peers/make_gltf_texture_assets.py. Both agree block by block with
//! Mitsuba 3.9.1 `llvm_ad_rgb` (16 × 1024 spp; the command heads the block file). Bad blend
//! parameters in the native format and in Mitsuba files are located errors, never a panic.

mod blocks;

use pathtrace::{render, RenderSettings};
use pathtrace_scene::gltf::{convert_file, load_gltf};
use pathtrace_scene::native::model::{Colour, MaterialKind, TextureDef};
use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
use std::path::{Path, PathBuf};
use std::sync::Arc;

include!("data/maps/metallic_blocks.rs");

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/maps").join(name)
}

#[test]
fn metallic_texture_becomes_a_blend_that_matches_the_mitsuba_twin() {
    let (file, warnings) = convert_file(&data("metallic.gltf"), &[]).unwrap();
    // The metal model's approximation, nothing else (specularFactor 0: the dielectric is exact).
    assert_eq!(warnings.len(), 1, "{warnings:#?}");
    assert!(warnings[0].contains("materials[0]") && warnings[0].contains("rough_conductor"), "{warnings:#?}");
    let MaterialKind::Blend { weight, bsdfs } = &file.materials["gltf-0"].kind else {
        panic!("{:?}", file.materials["gltf-0"]);
    };
    let Colour::Texture(TextureDef::Channel { filename, channel: 2, factor, squared: false, nearest: true, .. }) =
        weight
    else {
        panic!("{weight:?}");
    };
    assert_eq!((filename.as_str(), factor.get()), ("metallic.png", 0.9));
    assert_eq!(bsdfs, &["gltf-0-dielectric".to_string(), "gltf-0-metal".to_string()]);
    assert!(matches!(file.materials["gltf-0-dielectric"].kind, MaterialKind::Lambertian { .. }));
    assert!(matches!(file.materials["gltf-0-metal"].kind, MaterialKind::RoughConductor { .. }));
    assert!(matches!(
        file.materials["gltf-0-metal"].roughness,
        Some(Colour::Texture(TextureDef::Channel { channel: 1, squared: true, .. }))
    ));
    let (mut loaded, _) = load_gltf(&data("metallic.gltf"), &[]).unwrap();
    loaded.defaults.max_depth = 4;
    blocks::assert_scene_agrees("metallic.gltf", loaded, 1024, &GLTF_METALLIC_MEAN, &GLTF_METALLIC_SE);
    // Our import of the twin (Mitsuba's blendbsdf with a bitmap weight) against the same reference.
    blocks::assert_agrees(&data("metallic.xml"), 1024, &GLTF_METALLIC_MEAN, &GLTF_METALLIC_SE);
}

/// The comparison sees the weight: the same file with metallicFactor 0.45 (half the metal per
/// texel) disagrees with the reference in many blocks.
#[test]
fn a_halved_metallic_factor_is_seen() {
    let dir = std::env::temp_dir().join(format!("pathtrace-metallic-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for f in ["metallic.bin", "metallic.png"] {
        std::fs::copy(data(f), dir.join(f)).unwrap();
    }
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(data("metallic.gltf")).unwrap()).unwrap();
    v["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 0.45.into();
    let path = dir.join("metallic.gltf");
    std::fs::write(&path, serde_json::to_vec(&v).unwrap()).unwrap();
    let (mut loaded, _) = load_gltf(&path, &[]).unwrap();
    loaded.defaults.max_depth = 4;
    let o = blocks::render_blocks("metallic.gltf (factor 0.45)", loaded, 256, &GLTF_METALLIC_MEAN, &GLTF_METALLIC_SE);
    assert!(o.beyond > 20, "worst |z| {:.2}, {} beyond", o.worst, o.beyond);
    std::fs::remove_dir_all(&dir).ok();
}

/// The converted model written as TOML (`type = "blend"`, `weight`, `bsdfs`) and read back
/// renders exactly as the glTF.
#[test]
fn the_blend_round_trips_through_toml() {
    let (file, _) = convert_file(&data("metallic.gltf"), &[]).unwrap();
    let text = to_string(&file, Format::Toml).unwrap();
    assert!(text.contains("type = \"blend\"") && text.contains("bsdfs = ["), "{text}");
    let toml_path = data("converted.toml");
    assert_eq!(parse_str(&text, Format::Toml, &toml_path).unwrap(), file);
    let loaded = load_str(&text, Format::Toml, &toml_path).unwrap();
    let s = RenderSettings { width: 32, height: 32, spp: 4, seed: 3, threads: 1, ..Default::default() };
    let ours = render(Arc::new(loaded.scene), s.clone()).unwrap().film.image().pixels;
    let (direct, _) = load_gltf(&data("metallic.gltf"), &[]).unwrap();
    assert!(render(Arc::new(direct.scene), s).unwrap().film.image().pixels == ours);
}

/// A small native scene with a blend `floor` of `base` and `metal`, its table edited by `edit`.
fn native_scene(blend: &str, extra: &str) -> String {
    format!(
        r#"
[camera]
look_from = [0, 1, -3]
look_at = [0, 0, 0]

[materials.base]
type = "lambertian"
albedo = 0.5

[materials.metal]
type = "rough_conductor"
alpha = 0.2

[materials.floor]
type = "blend"
{blend}
{extra}
[[objects]]
type = "quad"
q = [-1, 0, -1]
u = [2, 0, 0]
v = [0, 0, 2]
material = "floor"

[[lights]]
type = "point"
position = [0, 2, 0]
intensity = 1
"#
    )
}

#[test]
fn native_blends_load_and_bad_parameters_are_located_errors() {
    let path = data("blend.toml");
    let load = |text: &str| load_str(text, Format::Toml, &path).map(|_| ());
    load(&native_scene("weight = 0.3\nbsdfs = [\"base\", \"metal\"]", "")).unwrap();
    let cases: [(&str, &str, &[&str]); 9] = [
        ("weight = 1.5\nbsdfs = [\"base\", \"metal\"]", "", &["floor", "weight", "from 0 to 1"]),
        ("bsdfs = [\"base\", \"metal\"]", "", &["floor", "needs `weight`"]),
        ("weight = 0.3", "", &["floor", "needs `bsdfs`"]),
        ("weight = 0.3\nbsdfs = [\"base\"]", "", &["floor", "names two materials", "not 1"]),
        ("weight = 0.3\nbsdfs = [\"base\", \"gold\"]", "", &["floor", "model 1 `gold`", "not a material"]),
        (
            "weight = 0.3\nbsdfs = [\"glass\", \"metal\"]",
            "[materials.glass]\ntype = \"dielectric\"\n",
            &["floor", "model 0 `glass`", "cannot be blended"],
        ),
        (
            "weight = 0.3\nbsdfs = [\"base\", \"inner\"]",
            "[materials.inner]\ntype = \"blend\"\nweight = 0.5\nbsdfs = [\"base\", \"metal\"]\n",
            &["floor", "model 1 `inner`", "cannot be blended"],
        ),
        (
            "weight = 0.3\nbsdfs = [\"base\", \"back\"]",
            "[materials.back]\ntype = \"lambertian\"\nalbedo = 0.5\none_sided = true\n",
            &["floor", "`back`", "one_sided"],
        ),
        ("weight = 0.3\nbsdfs = [\"base\", \"metal\"]\nalbedo = 0.5", "", &["`albedo` is not a parameter of a blend"]),
    ];
    for (blend, extra, expected) in cases {
        let e = load(&native_scene(blend, extra)).expect_err(blend).to_string();
        assert!(e.contains("blend.toml"), "{blend}: {e}");
        for x in expected {
            assert!(e.contains(x), "{blend}: `{x}` missing from: {e}");
        }
    }
}

/// A Mitsuba scene of one rectangle under a point light, its BSDF `bsdf`.
fn mitsuba_scene(bsdf: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
    </sensor>
    <shape type="rectangle">{bsdf}</shape>
    <emitter type="point"><point name="position" value="0, 0, 2"/></emitter>
</scene>"#
    )
}

#[test]
fn mitsuba_blendbsdfs_convert_and_bad_ones_are_located_errors() {
    use pathtrace_scene::mitsuba::load_mitsuba;
    let dir = std::env::temp_dir().join(format!("pathtrace-blend-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("blend.xml");
    let diffuse = r#"<bsdf type="diffuse"/>"#;
    let metal = r#"<bsdf type="roughconductor"/>"#;
    std::fs::write(&path, mitsuba_scene(&format!(r#"<bsdf type="blendbsdf">{diffuse}{metal}</bsdf>"#))).unwrap();
    let (_, warnings) = load_mitsuba(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let cases = [
        (format!(r#"<bsdf type="blendbsdf">{diffuse}</bsdf>"#), "exactly two nested BSDFs, found 1"),
        (
            format!(r#"<bsdf type="blendbsdf"><float name="weight" value="2"/>{diffuse}{metal}</bsdf>"#),
            "blendbsdf weight 2 must be from 0 to 1",
        ),
        (format!(r#"<bsdf type="blendbsdf"><bsdf type="dielectric"/>{metal}</bsdf>"#), "cannot be blended"),
    ];
    for (bsdf, expected) in cases {
        std::fs::write(&path, mitsuba_scene(&bsdf)).unwrap();
        let e = load_mitsuba(&path, &[]).map(|_| ()).expect_err(expected).to_string();
        assert!(e.contains("blend.xml") && e.contains(expected), "{expected}: {e}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
