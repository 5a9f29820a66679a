//! glTF textures beyond the base colour: tests/data/maps/emissive.gltf (emissiveTexture ×
//! emissiveFactor × KHR_materials_emissive_strength on a standing panel that lights a floor) and
//! metal_rough.gltf (a metal floor whose roughness is the metallicRoughnessTexture's green channel
//! × roughnessFactor), written by benches/peers/make_gltf_texture_assets.py with their Mitsuba 3
//! twins (the same data as an `area` emitter of a bitmap radiance, and a `roughconductor` with a
//! bitmap α). Each agrees block by block with Mitsuba 3.9.1 `llvm_ad_rgb` (16 × 1024 spp; the
//! commands head the block files). emissive.glb (image in a buffer view) and emissive_data.gltf
//! (buffer and image as base64 `data:` URIs) render exactly as emissive.gltf. Broken embedded
//! images, bad base64 and damaged files give located errors, never a panic.

mod blocks;
mod common;

use pathtrace::{render, RenderSettings};
use pathtrace_scene::gltf::{convert_file, load_gltf};
use pathtrace_scene::native::model::{Colour, MaterialKind, TextureDef};
use std::path::{Path, PathBuf};
use std::sync::Arc;

include!("data/maps/emissive_blocks.rs");
include!("data/maps/metal_rough_blocks.rs");

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/maps").join(name)
}

/// The emission texture's filename of the panel (materials[1]).
fn emission_image(path: &Path) -> String {
    let (file, warnings) = convert_file(path, &[]).unwrap();
    assert!(warnings.is_empty(), "{}: {warnings:#?}", path.display());
    let e = file.materials["gltf-1"].emission.as_ref().expect("an emitting panel");
    match &e.texture {
        Some(Colour::Texture(TextureDef::Bitmap { filename, raw: false, alpha: false, .. })) => filename.clone(),
        other => panic!("{other:?}"),
    }
}

#[test]
fn emissive_texture_matches_its_mitsuba_twin_block_by_block() {
    assert_eq!(emission_image(&data("emissive.gltf")), "emissive.png");
    let (mut loaded, _) = load_gltf(&data("emissive.gltf"), &[]).unwrap();
    loaded.defaults.max_depth = 4;
    blocks::assert_scene_agrees("emissive.gltf", loaded, 1024, &GLTF_EMISSIVE_MEAN, &GLTF_EMISSIVE_SE);
}

/// A dielectric (metallicFactor 0) with the same texture becomes a rough plastic whose α is
/// the texture, as the metal's (the plastic model's approximation is the only warning), and it
/// loads.
#[test]
fn metallic_roughness_texture_drives_the_rough_plastic_approximation() {
    let dir = common::TempDir::new();
    for f in ["metal_rough.bin", "metal_rough.png"] {
        std::fs::copy(data(f), dir.path().join(f)).unwrap();
    }
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(data("metal_rough.gltf")).unwrap()).unwrap();
    v["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 0.0.into();
    let path = dir.path().join("plastic_rough.gltf");
    std::fs::write(&path, serde_json::to_vec_pretty(&v).unwrap()).unwrap();
    let (file, warnings) = convert_file(&path, &[]).unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:#?}");
    assert!(warnings[0].contains("materials[0]") && warnings[0].contains("rough_plastic"), "{warnings:#?}");
    let m = &file.materials["gltf-0"];
    assert!(matches!(m.kind, MaterialKind::RoughPlastic { .. }), "{m:?}");
    assert!(
        matches!(m.roughness, Some(Colour::Texture(TextureDef::Channel { channel: 1, squared: true, .. }))),
        "{m:?}"
    );
    let (loaded, _) = load_gltf(&path, &[]).unwrap();
    assert!(loaded.scene.is_material_textured(0));
}

/// The image of a render of `path` at `spp` (seed fixed).
fn pixels(path: &Path, spp: u32) -> Vec<[f32; 3]> {
    let (loaded, _) = load_gltf(path, &[]).unwrap_or_else(|e| panic!("{e}"));
    let size = blocks::SIZE;
    let s = RenderSettings { width: size, height: size, spp, seed: 3, ..Default::default() };
    let out = render(Arc::new(loaded.scene), s).unwrap();
    out.film.image().pixels.iter().map(|c| c.to_array()).collect()
}

#[test]
fn embedded_images_and_data_uris_render_as_the_image_file() {
    assert_eq!(emission_image(&data("emissive.glb")), "emissive.glb#images[0]");
    assert_eq!(emission_image(&data("emissive_data.gltf")), "emissive_data.gltf#images[0]");
    let reference = pixels(&data("emissive.gltf"), 8);
    assert!(reference.iter().any(|p| p[0] > 1.0), "the panel is seen");
    for name in ["emissive.glb", "emissive_data.gltf"] {
        assert!(pixels(&data(name), 8) == reference, "{name} renders differently from emissive.gltf");
    }
}

/// `pathtrace convert`'s path: the converted model written as TOML and read back (next to the
/// glTF) renders exactly as the glTF; the references to embedded images and the channel
/// texture survive the trip.
#[test]
fn converted_texture_scenes_round_trip_through_toml() {
    use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
    for name in ["emissive.glb", "metal_rough.gltf"] {
        let (file, _) = convert_file(&data(name), &[]).unwrap();
        let text = to_string(&file, Format::Toml).unwrap();
        assert!(text.contains("emission_texture") || text.contains("type = \"channel\""), "{text}");
        let toml_path = data("converted.toml");
        let back = parse_str(&text, Format::Toml, &toml_path).unwrap();
        assert_eq!(back, file, "{name}");
        let loaded = load_str(&text, Format::Toml, &toml_path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let size = blocks::SIZE;
        let s = RenderSettings { width: size, height: size, spp: 4, seed: 3, ..Default::default() };
        let ours = render(Arc::new(loaded.scene), s.clone()).unwrap().film.image().pixels;
        let (direct, _) = load_gltf(&data(name), &[]).unwrap();
        assert!(render(Arc::new(direct.scene), s).unwrap().film.image().pixels == ours, "{name}");
    }
}

#[test]
fn metallic_roughness_texture_matches_its_mitsuba_twin_block_by_block() {
    let (file, warnings) = convert_file(&data("metal_rough.gltf"), &[]).unwrap();
    // The metallic channel (1 everywhere) makes a blend (tests/gltf_metallic.rs) of a metal, whose
    // model is approximated, and glTF's dielectric (specularFactor 1: approximated by
    // rough_plastic, which takes no roughness texture); nothing else is warned.
    assert!(warnings.iter().all(|w| w.contains("materials[0]")), "{warnings:#?}");
    assert!(warnings.iter().any(|w| w.contains("rough_conductor")), "{warnings:#?}");
    assert!(!warnings.iter().any(|w| w.contains("blue") || w.contains("metallic")), "{warnings:#?}");
    let Some(Colour::Texture(TextureDef::Channel {
        filename, channel: 1, factor, squared: true, nearest: true, ..
    })) = &file.materials["gltf-0-metal"].roughness
    else {
        panic!("{:?}", file.materials["gltf-0-metal"]);
    };
    assert_eq!((filename.as_str(), factor.get()), ("metal_rough.png", 0.9));
    let (mut loaded, _) = load_gltf(&data("metal_rough.gltf"), &[]).unwrap();
    loaded.defaults.max_depth = 4;
    blocks::assert_scene_agrees("metal_rough.gltf", loaded, 1024, &GLTF_METAL_ROUGH_MEAN, &GLTF_METAL_ROUGH_SE);
    // Our import of the twin (a bitmap α read from the PFM) against the same reference.
    blocks::assert_agrees(&data("metal_rough.xml"), 1024, &GLTF_METAL_ROUGH_MEAN, &GLTF_METAL_ROUGH_SE);
}

/// `name` with its JSON changed by `edit`, in a scratch folder with the files it reads.
fn edited(dir: &common::TempDir, name: &str, edit: &dyn Fn(&mut serde_json::Value)) -> PathBuf {
    for f in ["emissive.bin", "emissive.png"] {
        std::fs::copy(data(f), dir.path().join(f)).unwrap();
    }
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(data(name)).unwrap()).unwrap();
    edit(&mut v);
    let path = dir.path().join(name);
    std::fs::write(&path, serde_json::to_vec_pretty(&v).unwrap()).unwrap();
    path
}

/// The error of loading `path`, which must name the file and contain every one of `expected`.
fn load_error(path: &Path, expected: &[&str]) {
    let e = load_gltf(path, &[]).map(|_| ()).expect_err("an error").to_string();
    let name = path.file_name().unwrap().to_string_lossy();
    assert!(e.contains(name.as_ref()), "{e}");
    for x in expected {
        assert!(e.contains(x), "expected `{x}` in: {e}");
    }
}

#[test]
fn bad_embedded_images_and_data_uris_are_located_errors() {
    let dir = common::TempDir::new();
    // An image data: URI that is not base64.
    let path = edited(&dir, "emissive_data.gltf", &|v| v["images"][0]["uri"] = "data:image/png;base64,@@@@".into());
    load_error(&path, &["images[0]", "base64", "gltf-1"]);
    // A buffer data: URI that is not base64.
    let path = edited(&dir, "emissive_data.gltf", &|v| {
        v["buffers"][0]["uri"] = "data:application/octet-stream;base64,%%%".into()
    });
    load_error(&path, &["buffers[0]", "base64"]);
    // Valid base64 that is not a PNG: the decoder's error, located at the material.
    let path = edited(&dir, "emissive_data.gltf", &|v| v["images"][0]["uri"] = "data:image/png;base64,AAAA".into());
    load_error(&path, &["emissive_data.gltf#images[0]", "gltf-1", "cannot load texture"]);
    // An image in a buffer view that runs past the end of its buffer.
    let path = edited(&dir, "emissive.gltf", &|v| {
        v["bufferViews"]
            .as_array_mut()
            .unwrap()
            .push(serde_json::json!({"buffer": 0, "byteOffset": 100, "byteLength": 5000}));
        v["images"][0] = serde_json::json!({"bufferView": 6, "mimeType": "image/png"});
    });
    load_error(&path, &["images[0]", "runs past the end"]);
    // A buffer view holding geometry, not an image: a decode error.
    let path = edited(&dir, "emissive.gltf", &|v| {
        v["images"][0] = serde_json::json!({"bufferView": 0, "mimeType": "image/png"});
    });
    load_error(&path, &["gltf-1", "cannot load texture"]);
    // A format glTF does not allow.
    let path = edited(&dir, "emissive.gltf", &|v| {
        v["images"][0] = serde_json::json!({"bufferView": 0, "mimeType": "image/webp"});
    });
    match load_gltf(&path, &[]) {
        Ok(_) => panic!("image/webp accepted"),
        Err(e) => assert!(e.to_string().contains("emissive.gltf"), "{e}"),
    }
    // An image file that is missing.
    let path = edited(&dir, "emissive.gltf", &|v| v["images"][0]["uri"] = "gone.png".into());
    load_error(&path, &["gone.png", "gltf-1"]);
}

/// Single-byte changes and truncations of emissive.glb (a sample of them) give a scene or a
/// located error, never a panic.
#[test]
fn damaged_glb_with_an_embedded_image_never_panics() {
    let original = std::fs::read(data("emissive.glb")).unwrap();
    let dir = common::TempDir::new();
    let path = dir.path().join("x.glb");
    let mut rng = 0x2545f4914f6cdd1du64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        rng
    };
    // Damage in the image's bytes (the file's last ~111 bytes) half of the time.
    let image_start = original.len() - 120;
    for i in 0..300 {
        let mut b = original.clone();
        if i % 5 == 0 {
            b.truncate((next() as usize) % b.len());
        } else {
            let at = if i % 2 == 0 { image_start + (next() as usize) % 120 } else { (next() as usize) % b.len() };
            b[at] = next() as u8;
        }
        std::fs::write(&path, &b).unwrap();
        match std::panic::catch_unwind(|| load_gltf(&path, &[]).map(|_| ())) {
            Ok(Ok(())) => {}
            Ok(Err(e)) => assert!(e.to_string().contains("x.glb"), "{e}"),
            Err(_) => panic!("mutation {i} panicked"),
        }
    }
}

/// A texture transform on the normal texture is read (it was ignored before); a malformed one
/// drops the map with a warning; an emission texture on a sphere is a build error.
#[test]
fn normal_texture_transforms_and_misplaced_emission_textures() {
    let dir = common::TempDir::new();
    for f in ["normal_map.bin", "normal.png"] {
        std::fs::copy(data(f), dir.path().join(f)).unwrap();
    }
    let write = |t: serde_json::Value| {
        let mut v: serde_json::Value =
            serde_json::from_slice(&std::fs::read(data("normal_map.gltf")).unwrap()).unwrap();
        v["materials"][0]["normalTexture"]["extensions"] = serde_json::json!({ "KHR_texture_transform": t });
        let path = dir.path().join("normal_map.gltf");
        std::fs::write(&path, serde_json::to_vec(&v).unwrap()).unwrap();
        path
    };
    let path = write(serde_json::json!({ "offset": [0.5, 0.25], "scale": [2.0, 3.0] }));
    let (file, warnings) = convert_file(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let n = file.materials["gltf-0"].normal.as_ref().unwrap();
    let pathtrace_scene::native::model::NormalDef::Map {
        texture: Colour::Texture(TextureDef::Bitmap { to_uv, .. }),
        ..
    } = &n.map
    else {
        panic!("{n:?}")
    };
    let rows: Vec<Vec<f64>> = to_uv.iter().map(|r| r.iter().map(|x| x.get()).collect()).collect();
    assert_eq!(rows, [[2.0, 0.0, 0.5], [0.0, 3.0, 0.25]]);
    for bad in [serde_json::json!({ "scale": [1.0] }), serde_json::json!({ "texCoord": 1 })] {
        let (file, warnings) = convert_file(&write(bad.clone()), &[]).unwrap();
        assert!(file.materials["gltf-0"].normal.is_none(), "{bad}");
        assert!(warnings.iter().any(|w| w.contains("materials[0]") && w.contains("normal texture")), "{warnings:#?}");
    }
    // Native: an emission texture on a sphere cannot be sampled with its uv.
    let toml = r#"
        [camera]
        look_from = [0, 0, 5]
        look_at = [0, 0, 0]
        [materials.lamp]
        type = "emissive"
        radiance = 1
        emission_texture = { type = "bitmap", filename = "normal.png" }
        [[objects]]
        type = "sphere"
        center = [0, 0, 0]
        radius = 1
        material = "lamp"
    "#;
    let path = dir.write("lamp.toml", toml);
    let e = pathtrace_scene::load_file(&path, &[], &mut |_| {}).map(|_| ()).expect_err("an error").to_string();
    assert!(e.contains("lamp.toml") && e.contains("meshes and quads only"), "{e}");
}
