//! glTF 2.0 import: tests/data/gltf/scene.gltf (+ scene.bin) and scene.glb, written by
//! benches/peers/make_gltf_assets.py together with their Mitsuba 3 twin scene.xml (the same
//! triangles, colours, camera and directional light; `KHR_materials_specular` specularFactor 0
//! makes glTF's BRDF Lambertian, Mitsuba's `diffuse`). Both glTF forms load without a warning and
//! agree block by block with Mitsuba's render of the twin (reference: 16 × 1024 spp from
//! `block_means.py scene.xml --scenes crates/pathtrace-scene/tests/data/gltf --spp 1024 --runs 16
//! --name GLTF`); so does our import of the twin. Broken files (malformed JSON, truncated
//! buffers, out-of-range accessors and indices, random byte damage) give errors naming the file
//! and the place, never a panic.

mod blocks;
mod common;

use pathtrace::light::Light;
use pathtrace_scene::gltf::{convert_file, load_gltf};
use pathtrace_scene::native::{parse_str, to_string, Format};
use std::path::{Path, PathBuf};

include!("data/gltf_blocks.rs");

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/gltf").join(name)
}

#[test]
fn gltf_and_glb_load_cleanly_with_the_hierarchy_camera_and_light() {
    for name in ["scene.gltf", "scene.glb"] {
        let (file, warnings) = convert_file(&data(name), &[]).unwrap();
        assert!(warnings.is_empty(), "{name}: {warnings:#?}");
        assert_eq!(file.objects.len(), 2, "{name}");
        assert_eq!(file.lights.len(), 1, "{name}");
        let (loaded, _) = load_gltf(&data(name), &[]).unwrap();
        assert_eq!(loaded.scene.lights.lights().iter().filter(|l| matches!(l, Light::Directional(_))).count(), 1);
        assert_eq!(loaded.scene.primitive_count(), 14, "{name}: 2 floor + 12 cube triangles");
    }
    let e = convert_file(&data("scene.gltf"), &[("camera", "nope")]).unwrap_err().to_string();
    assert!(e.contains("no camera named `nope`"), "{e}");
    assert!(convert_file(&data("scene.gltf"), &[("camera", "main")]).is_ok());
}

#[test]
fn gltf_matches_its_mitsuba_twin_block_by_block() {
    for name in ["scene.gltf", "scene.glb"] {
        let (mut loaded, _) = load_gltf(&data(name), &[]).unwrap();
        // The twin's integrator stops at depth 4; a glTF file has no render settings.
        loaded.defaults.max_depth = 4;
        let o = blocks::assert_scene_agrees(name, loaded, 1024, &GLTF_MEAN, &GLTF_SE);
        eprintln!("{name}: worst |z| {:.2}, {} beyond", o.worst, o.beyond);
    }
    // Our import of the XML twin, against the same reference.
    blocks::assert_agrees(&data("scene.xml"), 1024, &GLTF_MEAN, &GLTF_SE);
}

#[test]
fn converted_gltf_round_trips_through_the_native_format() {
    let (file, _) = convert_file(&data("scene.gltf"), &[]).unwrap();
    for format in [Format::Toml, Format::Json] {
        let text = to_string(&file, format).unwrap();
        let back = parse_str(&text, format, &data(if format == Format::Toml { "x.toml" } else { "x.json" })).unwrap();
        assert_eq!(back, file);
    }
}

/// Runs `f` on a copy of the scene folder in which `edit` has changed one file; the result must
/// be an error (never a panic) whose text contains every one of `expected`.
fn broken(file: &str, edit: impl FnOnce(Vec<u8>) -> Vec<u8>, expected: &[&str]) {
    let dir = common::TempDir::new();
    for f in ["scene.gltf", "scene.bin", "scene.glb"] {
        std::fs::copy(data(f), dir.path().join(f)).unwrap();
    }
    let bytes = std::fs::read(dir.path().join(file)).unwrap();
    std::fs::write(dir.path().join(file), edit(bytes)).unwrap();
    let scene = if file == "scene.glb" { "scene.glb" } else { "scene.gltf" };
    let e = load_gltf(&dir.path().join(scene), &[]).err().unwrap_or_else(|| panic!("{file}: no error")).to_string();
    assert!(e.contains(scene), "{e}");
    for x in expected {
        assert!(e.contains(x), "expected `{x}` in: {e}");
    }
}

fn edit_json(f: impl FnOnce(&mut serde_json::Value)) -> impl FnOnce(Vec<u8>) -> Vec<u8> {
    move |bytes| {
        let mut v: serde_json::Value = serde_json::from_slice(&bytes).unwrap();
        f(&mut v);
        serde_json::to_vec_pretty(&v).unwrap()
    }
}

#[test]
fn malformed_json_is_located_by_line_and_column() {
    broken("scene.gltf", |b| b[..b.len() / 2].to_vec(), &["scene.gltf:", "invalid glTF JSON"]);
    broken(
        "scene.gltf",
        |b| String::from_utf8(b).unwrap().replacen("\"nodes\"", "\"nodes\" 7", 1).into_bytes(),
        &["invalid glTF JSON"],
    );
    // Valid JSON but not glTF: a node's mesh index out of range (the crate's validation).
    broken("scene.gltf", edit_json(|v| v["nodes"][0]["mesh"] = 9.into()), &["not a valid glTF"]);
}

#[test]
fn truncated_buffers_and_out_of_range_accessors_and_indices_are_errors() {
    broken("scene.bin", |b| b[..100].to_vec(), &["buffers[0]", "truncated"]);
    broken("scene.glb", |b| b[..b.len() - 200].to_vec(), &["scene.glb"]);
    broken("scene.gltf", edit_json(|v| v["accessors"][0]["count"] = 1_000_000.into()), &["accessors[0]", "do not fit"]);
    broken("scene.gltf", edit_json(|v| v["accessors"][3]["count"] = u64::MAX.into()), &["scene.gltf"]);
    broken("scene.gltf", edit_json(|v| v["bufferViews"][0]["byteLength"] = 10_000.into()), &["runs past the end"]);
    broken("scene.gltf", edit_json(|v| v["accessors"][0]["componentType"] = 5121.into()), &["POSITION", "expected"]);
    // Index 0xffff in the floor's first triangle: out of range for its 4 vertices.
    broken(
        "scene.bin",
        |mut b| {
            let offset = 4 * 12 * 2; // floor positions + normals, then the u16 indices
            b[offset] = 0xff;
            b[offset + 1] = 0xff;
            b
        },
        &["meshes[0].primitives[0]", "index 65535 is out of range"],
    );
}

/// Every single-byte change and truncation of the GLB (a sample of them) gives a scene or an
/// error, never a panic.
#[test]
fn damaged_glb_never_panics() {
    let original = std::fs::read(data("scene.glb")).unwrap();
    let dir = common::TempDir::new();
    let path = dir.path().join("x.glb");
    let mut rng = 0x9e3779b97f4a7c15u64;
    let mut next = || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        rng
    };
    for i in 0..400 {
        let mut b = original.clone();
        if i % 4 == 0 {
            b.truncate((next() as usize) % b.len());
        } else {
            let at = (next() as usize) % b.len();
            b[at] = next() as u8;
        }
        std::fs::write(&path, &b).unwrap();
        let result = std::panic::catch_unwind(|| load_gltf(&path, &[]).map(|_| ()));
        match result {
            Ok(Ok(())) => {}
            Ok(Err(e)) => assert!(e.to_string().contains("x.glb"), "{e}"),
            Err(_) => panic!("mutation {i} panicked"),
        }
    }
}

/// A base colour texture stored as a file becomes an image texture with the sampler's wrap and
/// filter and `KHR_texture_transform`'s matrix; an embedded one is named inside the glTF file. A
/// non-white baseColorFactor is the texture's factor (glTF 2.0 §3.9.2), without a warning.
#[test]
fn base_colour_textures_and_their_transform_convert() {
    use pathtrace_scene::native::model::{Colour, MaterialKind, TextureDef};
    let dir = common::TempDir::new();
    std::fs::copy(data("scene.bin"), dir.path().join("scene.bin")).unwrap();
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(data("scene.gltf")).unwrap()).unwrap();
    v["images"] = serde_json::json!([{ "uri": "wood%20grain.png" }, { "uri": "data:image/png;base64,AAAA" }]);
    v["samplers"] = serde_json::json!([{ "wrapS": 33071, "magFilter": 9728 }]);
    v["textures"] = serde_json::json!([{ "source": 0, "sampler": 0 }, { "source": 1 }]);
    let transform =
        serde_json::json!({ "offset": [0.5, 0.25], "rotation": std::f32::consts::FRAC_PI_2, "scale": [2.0, 3.0] });
    v["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = serde_json::json!([1.0, 1.0, 1.0, 1.0]);
    v["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] =
        serde_json::json!({ "index": 0, "extensions": { "KHR_texture_transform": transform } });
    v["materials"][1]["pbrMetallicRoughness"]["baseColorTexture"] = serde_json::json!({ "index": 1 });
    v["extensionsUsed"].as_array_mut().unwrap().push("KHR_texture_transform".into());
    let path = dir.path().join("scene.gltf");
    std::fs::write(&path, serde_json::to_vec(&v).unwrap()).unwrap();
    let (file, warnings) = convert_file(&path, &[]).unwrap();
    // Material 1's colour factor is not white: it multiplies the texture, nothing is warned.
    assert!(warnings.is_empty(), "{warnings:#?}");
    let MaterialKind::Lambertian {
        albedo: Colour::Texture(TextureDef::Bitmap { filename, nearest, clamp, to_uv, factor, .. }),
    } = &file.materials["gltf-0"].kind
    else {
        panic!("{:?}", file.materials["gltf-0"]);
    };
    assert_eq!((filename.as_str(), *nearest, *clamp), ("wood grain.png", true, true));
    assert_eq!(*factor, pathtrace_scene::native::model::Triple::ONE);
    // M = T·R(90°)·S(2, 3): [[0, 3, 0.5], [−2, 0, 0.25]].
    let rows: Vec<Vec<f64>> = to_uv.iter().map(|r| r.iter().map(|x| x.get()).collect()).collect();
    let expected = [[0.0, 3.0, 0.5], [-2.0, 0.0, 0.25]];
    for (r, e) in rows.iter().zip(expected) {
        for (a, b) in r.iter().zip(e) {
            assert!((a - b).abs() < 1e-6, "{rows:?}");
        }
    }
    // The data: URI image is named inside the glTF; its bytes (not a PNG) fail at the build.
    let MaterialKind::Lambertian { albedo: Colour::Texture(TextureDef::Bitmap { filename, factor, .. }) } =
        &file.materials["gltf-1"].kind
    else {
        panic!("{:?}", file.materials["gltf-1"]);
    };
    assert_eq!(filename, "scene.gltf#images[1]");
    assert_eq!(factor.vec3().to_array(), [0.2, 0.4, 0.7]);
    let image = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/maps/emissive.png");
    std::fs::copy(image, dir.path().join("wood grain.png")).unwrap();
    let e = load_gltf(&path, &[]).map(|_| ()).expect_err("an error").to_string();
    assert!(e.contains("scene.gltf#images[1]") && e.contains("gltf-1"), "{e}");
}
