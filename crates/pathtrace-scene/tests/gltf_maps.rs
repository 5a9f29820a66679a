//! glTF normal textures: tests/data/maps/normal_map.gltf (+ normal_map.bin, normal.png), written
//! by benches/peers/make_gltf_assets.py with its Mitsuba 3 twin normal_map.xml (the same floor and
//! texture coordinates in an OBJ, `normalmap` around `diffuse` without terminator shadowing, the
//! same camera and directional light). The glTF loads without a warning and agrees block by
//! block with Mitsuba's render of the twin (reference: Mitsuba 3.9.1 `llvm_ad_rgb`, 16 × 1024
//! spp, `block_means.py normal_map.xml --scenes crates/pathtrace-scene/tests/data/maps --spp 1024
//! --runs 16 --name GLTF_NORMAL_MAP --variant llvm_ad_rgb`); so does our import of the twin.
//! Broken normal textures give located errors or warnings, never a panic.

mod blocks;
mod common;

use pathtrace_scene::gltf::{convert_file, load_gltf};
use pathtrace_scene::native::model::NormalDef;
use std::path::{Path, PathBuf};

include!("data/maps/normal_map_blocks.rs");
include!("data/maps/cutout_blocks.rs");

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/maps").join(name)
}

#[test]
fn gltf_normal_map_matches_its_mitsuba_twin_block_by_block() {
    let (file, warnings) = convert_file(&data("normal_map.gltf"), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let normal = file.materials["gltf-0"].normal.as_ref().expect("a normal map");
    assert!(!normal.shadowing && matches!(normal.map, NormalDef::Map { strength, .. } if strength.get() == 1.0));
    let (mut loaded, _) = load_gltf(&data("normal_map.gltf"), &[]).unwrap();
    loaded.defaults.max_depth = 4;
    blocks::assert_scene_agrees("normal_map.gltf", loaded, 1024, &GLTF_NORMAL_MAP_MEAN, &GLTF_NORMAL_MAP_SE);
    blocks::assert_agrees(&data("normal_map.xml"), 1024, &GLTF_NORMAL_MAP_MEAN, &GLTF_NORMAL_MAP_SE);
}

/// alphaMode BLEND: a card cut out by its base colour texture's alpha (tests/data/maps/cutout.gltf)
/// agrees with the Mitsuba twin (a `mask` of the same cut-out, rendered with `volpath`;
/// reference `block_means.py cutout.xml … --name GLTF_CUTOUT --variant llvm_ad_rgb`), and so does
/// our import of the twin. alphaMode MASK (cutoff 0.5) gives hard edges where the bilinear
/// opacity ramps over a texel: its blocks along the edges differ from Mitsuba's (measured up to
/// 0.003 in a block of 0.39, z ≈ 70), its image mean agrees within 1%.
#[test]
fn gltf_alpha_modes_match_the_mitsuba_twin() {
    use pathtrace_scene::native::model::{Colour, TextureDef};
    let (file, warnings) = convert_file(&data("cutout.gltf"), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let o = file.materials["gltf-1"].opacity.as_ref().expect("an opacity");
    assert!(matches!(&o.texture, Colour::Texture(TextureDef::Bitmap { alpha: true, .. })));
    assert_eq!(o.cutoff, None);
    let (mut loaded, _) = load_gltf(&data("cutout.gltf"), &[]).unwrap();
    loaded.defaults.max_depth = -1;
    blocks::assert_scene_agrees("cutout.gltf", loaded, 1024, &GLTF_CUTOUT_MEAN, &GLTF_CUTOUT_SE);
    // MASK: the image mean.
    let dir = common::TempDir::new();
    let path = edited_copy(&dir, "cutout.gltf", &["cutout.bin", "cutout.png"], &|v| {
        v["materials"][1]["alphaMode"] = "MASK".into();
    });
    let (mut loaded, _) = load_gltf(&path, &[]).unwrap();
    loaded.defaults.max_depth = -1;
    let o = blocks::render_blocks("cutout.gltf (MASK)", loaded, 256, &GLTF_CUTOUT_MEAN, &GLTF_CUTOUT_SE);
    for k in 0..3 {
        let theirs = GLTF_CUTOUT_MEAN.iter().map(|b| b[k]).sum::<f64>() / 64.0;
        assert!((o.mean[k] - theirs).abs() < 0.01 * theirs, "channel {k}: {:?} vs {theirs}", o.mean);
    }
    let (twin, warnings) =
        pathtrace_scene::mitsuba::load_mitsuba(&data("cutout.xml"), &[("integrator", "path")]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    blocks::assert_scene_agrees("cutout.xml", twin, 1024, &GLTF_CUTOUT_MEAN, &GLTF_CUTOUT_SE);
}

/// The glTF `name` with its JSON changed by `edit`, in a scratch folder with the files it reads.
fn edited_copy(dir: &common::TempDir, name: &str, files: &[&str], edit: &dyn Fn(&mut serde_json::Value)) -> PathBuf {
    for f in files {
        std::fs::copy(data(f), dir.path().join(f)).unwrap();
    }
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(data(name)).unwrap()).unwrap();
    edit(&mut v);
    let path = dir.path().join(name);
    std::fs::write(&path, serde_json::to_vec_pretty(&v).unwrap()).unwrap();
    path
}

/// normal_map.gltf with its JSON changed by `edit`.
fn edited(dir: &common::TempDir, edit: impl Fn(&mut serde_json::Value)) -> PathBuf {
    edited_copy(dir, "normal_map.gltf", &["normal_map.bin", "normal.png"], &edit)
}

#[test]
fn broken_normal_textures_are_located_errors_or_warnings() {
    let dir = common::TempDir::new();
    // A texture index out of range: the file is not valid glTF.
    let path = edited(&dir, |v| v["materials"][0]["normalTexture"]["index"] = 7.into());
    let e = load_gltf(&path, &[]).map(|_| ()).expect_err("an error").to_string();
    assert!(e.contains("normal_map.gltf") && e.contains("not a valid glTF"), "{e}");
    // A missing image: the build names the material and the file.
    let path = edited(&dir, |v| v["images"][0]["uri"] = "gone.png".into());
    let e = load_gltf(&path, &[]).map(|_| ()).expect_err("an error").to_string();
    assert!(e.contains("gone.png") && e.contains("gltf-0"), "{e}");
    // A second texture coordinate set: a warning (TANGENT attributes: tests/gltf_tangents.rs).
    let path = edited(&dir, |v| {
        v["materials"][0]["normalTexture"]["texCoord"] = 1.into();
    });
    let (file, warnings) = convert_file(&path, &[]).unwrap();
    assert!(file.materials["gltf-0"].normal.is_none());
    assert!(warnings.iter().any(|w| w.contains("materials[0]") && w.contains("TEXCOORD_0")), "{warnings:#?}");
    // A strength (glTF's `scale`) carries over; a non-finite one cannot be written in JSON.
    let path = edited(&dir, |v| v["materials"][0]["normalTexture"]["scale"] = 0.5.into());
    let (file, _) = convert_file(&path, &[]).unwrap();
    let normal = file.materials["gltf-0"].normal.as_ref().unwrap();
    assert!(matches!(normal.map, NormalDef::Map { strength, .. } if strength.get() == 0.5));
}

#[test]
fn alpha_modes_convert_and_bad_alpha_images_are_located_errors() {
    let dir = common::TempDir::new();
    let write =
        |edit: &dyn Fn(&mut serde_json::Value)| edited_copy(&dir, "cutout.gltf", &["cutout.bin", "cutout.png"], edit);
    // BLEND without a texture: the factor's alpha, no cutoff.
    let path = write(&|v| {
        v["materials"][0]["alphaMode"] = "BLEND".into();
        v["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.25.into();
    });
    let (file, warnings) = convert_file(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let o = file.materials["gltf-0"].opacity.as_ref().unwrap();
    assert_eq!(o.cutoff, None);
    assert!(matches!(&o.texture, pathtrace_scene::native::model::Colour::Constant(t) if t.vec3().x == 0.25));
    // An alpha image that is not a PNG or JPEG: a located error, not a panic.
    std::fs::write(dir.path().join("cutout.exr"), b"not an image").unwrap();
    let path = write(&|v| v["images"][0]["uri"] = "cutout.exr".into());
    let e = load_gltf(&path, &[]).map(|_| ()).expect_err("an error").to_string();
    assert!(e.contains("cutout.exr") && e.contains("gltf-1"), "{e}");
    // An emissive cut-out keeps its emission and drops the mask, with a warning.
    let path = write(&|v| v["materials"][1]["emissiveFactor"] = serde_json::json!([1.0, 1.0, 1.0]));
    let (file, warnings) = convert_file(&path, &[]).unwrap();
    assert!(file.materials["gltf-1"].opacity.is_none());
    assert!(warnings.iter().any(|w| w.contains("cannot be cut out")), "{warnings:#?}");
}

/// An orthographic glTF camera becomes the native orthographic camera: height 2·ymag, aspect
/// xmag/ymag; a non-positive ymag falls back to a perspective view with a warning (or is refused
/// by the file's validation), never a panic.
#[test]
fn orthographic_cameras_convert() {
    use pathtrace_scene::native::model::ProjectionName;
    let dir = common::TempDir::new();
    let ortho = |xmag: f64, ymag: f64| {
        let edit = move |v: &mut serde_json::Value| {
            v["cameras"][0] = serde_json::json!({ "type": "orthographic",
                "orthographic": { "xmag": xmag, "ymag": ymag, "znear": 0.01, "zfar": 100.0 } });
        };
        edited_copy(&dir, "normal_map.gltf", &["normal_map.bin", "normal.png"], &edit)
    };
    let (file, warnings) = convert_file(&ortho(2.0, 1.5), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let c = &file.camera;
    assert_eq!(c.projection, Some(ProjectionName::Orthographic));
    assert_eq!(c.height.map(|h| h.get()), Some(3.0));
    assert!((c.aspect.unwrap().get() - 4.0 / 3.0).abs() < 1e-6);
    assert!(load_gltf(&ortho(2.0, 1.5), &[]).is_ok());
    match convert_file(&ortho(2.0, -1.0), &[]) {
        Ok((file, warnings)) => {
            assert!(warnings.iter().any(|w| w.contains("ymag")), "{warnings:#?}");
            assert_eq!(file.camera.projection, None);
        }
        Err(e) => assert!(e.to_string().contains("normal_map.gltf"), "{e}"),
    }
}
