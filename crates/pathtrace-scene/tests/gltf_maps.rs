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

/// The glTF with its JSON changed by `edit`, in a scratch folder with the buffer and image.
fn edited(dir: &common::TempDir, edit: impl FnOnce(&mut serde_json::Value)) -> PathBuf {
    for f in ["normal_map.bin", "normal.png"] {
        std::fs::copy(data(f), dir.path().join(f)).unwrap();
    }
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(data("normal_map.gltf")).unwrap()).unwrap();
    edit(&mut v);
    let path = dir.path().join("normal_map.gltf");
    std::fs::write(&path, serde_json::to_vec_pretty(&v).unwrap()).unwrap();
    path
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
    // A second texture coordinate set, a TANGENT attribute, a texture transform: warnings.
    let path = edited(&dir, |v| {
        v["materials"][0]["normalTexture"]["texCoord"] = 1.into();
        v["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = 1.into();
    });
    let (file, warnings) = convert_file(&path, &[]).unwrap();
    assert!(file.materials["gltf-0"].normal.is_none());
    assert!(warnings.iter().any(|w| w.contains("materials[0]") && w.contains("TEXCOORD_0")), "{warnings:#?}");
    assert!(warnings.iter().any(|w| w.contains("TANGENT")), "{warnings:#?}");
    // A strength (glTF's `scale`) carries over; a non-finite one cannot be written in JSON.
    let path = edited(&dir, |v| v["materials"][0]["normalTexture"]["scale"] = 0.5.into());
    let (file, _) = convert_file(&path, &[]).unwrap();
    let normal = file.materials["gltf-0"].normal.as_ref().unwrap();
    assert!(matches!(normal.map, NormalDef::Map { strength, .. } if strength.get() == 0.5));
}
