//! glTF `TANGENT` attributes (glTF 2.0 §3.7.2.1: xyz the tangent, w = ±1 the bitangent's sign,
//! bitangent = w · normal × tangent) as the normal map's tangent frame. Variants of
//! tests/data/maps/normal_map.gltf (a floor whose texture coordinates give ∂p/∂u along +x) with
//! a second buffer of tangents, rendered at a fixed seed on one thread:
//!
//! - tangents equal to the texture coordinates' (+x, w = +1) give the same image to the bit
//!   (the frame's first axis is the normalised projection of either vector; for this axis-aligned
//!   floor both are exactly (1, 0, 0), and w = +1 multiplies the texel's y by 1);
//! - w = −1 gives the image of w = +1 with the normal texture's green channel inverted
//!   (g → 255 − g: the same texel y up to the rounding of its decoding), and not the image of
//!   w = +1 with the original texture;
//! - malformed accessors (wrong type, count, component type, a w that is not ±1) are errors
//!   naming the accessor, never a panic.

mod common;

use pathtrace::{render, RenderSettings};
use pathtrace_scene::gltf::load_gltf;
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/maps").join(name)
}

/// A copy of normal_map.gltf in `dir` named `name`, whose primitive reads `tangents` (one per
/// vertex, written as they are: any count, any values) from a second buffer, as an accessor of
/// `ty` (a glTF type name) and `component` type; `normal_image` the normal texture's file in `dir`.
fn with_tangents(
    dir: &common::TempDir,
    name: &str,
    tangents: &[f32],
    ty: &str,
    component: u32,
    normal_image: &str,
) -> PathBuf {
    for f in ["normal_map.bin", "normal.png"] {
        std::fs::copy(data(f), dir.path().join(f)).unwrap();
    }
    let bytes: Vec<u8> = tangents.iter().flat_map(|x| x.to_le_bytes()).collect();
    let bin = format!("{name}.bin");
    dir.write(&bin, &bytes);
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(data("normal_map.gltf")).unwrap()).unwrap();
    let components = match ty {
        "VEC3" => 3,
        "VEC4" => 4,
        _ => 1,
    };
    v["buffers"].as_array_mut().unwrap().push(serde_json::json!({ "uri": bin, "byteLength": bytes.len() }));
    v["bufferViews"].as_array_mut().unwrap().push(serde_json::json!({
        "buffer": 1, "byteOffset": 0, "byteLength": bytes.len() }));
    v["accessors"].as_array_mut().unwrap().push(serde_json::json!({
        "bufferView": 4, "componentType": component, "count": tangents.len() / components, "type": ty }));
    v["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = 4.into();
    v["images"][0]["uri"] = normal_image.into();
    let path = dir.path().join(name);
    std::fs::write(&path, serde_json::to_vec_pretty(&v).unwrap()).unwrap();
    path
}

/// The same tangent, with bitangent sign `w`, at each of the floor's four vertices.
fn four(t: [f32; 4]) -> Vec<f32> {
    t.repeat(4)
}

const F32: u32 = 5126;

/// The image of a glTF scene: 32 × 32, 16 samples per pixel, seed 3, one thread.
fn image(path: &Path) -> Vec<f32> {
    let (loaded, warnings) = load_gltf(path, &[]).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(warnings.is_empty(), "{warnings:#?}");
    let mut s = RenderSettings { width: 32, height: 32, spp: 16, seed: 3, threads: 1, ..Default::default() };
    s.path.max_depth = 4;
    let out = render(Arc::new(loaded.scene), s).unwrap();
    out.film.image().pixels.iter().flat_map(|p| p.to_array()).collect()
}

fn differing_bits(a: &[f32], b: &[f32]) -> usize {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).filter(|(x, y)| x.to_bits() != y.to_bits()).count()
}

fn mean_abs_difference(a: &[f32], b: &[f32]) -> f64 {
    a.iter().zip(b).map(|(x, y)| f64::from((x - y).abs())).sum::<f64>() / a.len() as f64
}

fn mean(a: &[f32]) -> f64 {
    a.iter().map(|&x| f64::from(x)).sum::<f64>() / a.len() as f64
}

#[test]
fn tangents_equal_to_the_texture_coordinates_change_no_bit() {
    let dir = common::TempDir::new();
    let plain = image(&data("normal_map.gltf"));
    let along_u = image(&with_tangents(&dir, "along_u.gltf", &four([1.0, 0.0, 0.0, 1.0]), "VEC4", F32, "normal.png"));
    assert_eq!(differing_bits(&plain, &along_u), 0);
    // The attribute is read: tangents along +z turn the map's bumps by 90° about the normal.
    let along_z = image(&with_tangents(&dir, "along_z.gltf", &four([0.0, 0.0, 1.0, 1.0]), "VEC4", F32, "normal.png"));
    let moved = mean_abs_difference(&plain, &along_z);
    assert!(moved > 0.02 * mean(&plain), "turned tangents moved the image by {moved} (mean {})", mean(&plain));
}

#[test]
fn a_negative_bitangent_sign_inverts_the_normal_maps_green_channel() {
    let dir = common::TempDir::new();
    let mut img = image::open(data("normal.png")).unwrap().to_rgb8();
    img.pixels_mut().for_each(|p| p.0[1] = 255 - p.0[1]);
    img.save(dir.path().join("green_inverted.png")).unwrap();
    let x = [1.0, 0.0, 0.0];
    let mirrored =
        image(&with_tangents(&dir, "w_neg.gltf", &four([x[0], x[1], x[2], -1.0]), "VEC4", F32, "normal.png"));
    let inverted =
        image(&with_tangents(&dir, "green.gltf", &four([x[0], x[1], x[2], 1.0]), "VEC4", F32, "green_inverted.png"));
    let plain = image(&with_tangents(&dir, "w_pos.gltf", &four([x[0], x[1], x[2], 1.0]), "VEC4", F32, "normal.png"));
    let m = mean(&plain);
    // Same paths, same texel normals up to the rounding of 2(255 − g)/255 − 1 against
    // −(2g/255 − 1): every value within 1e-4 of the image mean.
    let worst = mirrored.iter().zip(&inverted).map(|(a, b)| f64::from((a - b).abs())).fold(0.0, f64::max);
    assert!(worst < 1e-4 * m, "largest difference {worst} (image mean {m})");
    // And the sign matters: w = −1 is not the original frame.
    let moved = mean_abs_difference(&mirrored, &plain);
    assert!(moved > 0.02 * m, "w = -1 moved the image by {moved} (mean {m})");
}

/// A malformed variant: its file name, tangents, accessor type and component type, and what its
/// error must say.
type Case<'a> = (&'a str, Vec<f32>, &'a str, u32, &'a [&'a str]);

#[test]
fn malformed_tangent_accessors_are_located_errors() {
    let dir = common::TempDir::new();
    let err = |path: PathBuf| load_gltf(&path, &[]).map(|_| ()).expect_err("an error").to_string();
    let cases: [Case; 5] = [
        ("vec3.gltf", [1.0, 0.0, 0.0].repeat(4), "VEC3", F32, &["TANGENT", "accessors[4]", "Vec3"]),
        ("count.gltf", [1.0, 0.0, 0.0, 1.0].repeat(3), "VEC4", F32, &["TANGENT", "3 elements", "POSITION has 4"]),
        ("w.gltf", four([1.0, 0.0, 0.0, 0.5]), "VEC4", F32, &["TANGENT element 0", "1 or -1"]),
        ("nan.gltf", four([f32::NAN, 0.0, 0.0, 1.0]), "VEC4", F32, &["TANGENT element 0", "finite"]),
        ("u16.gltf", four([1.0, 0.0, 0.0, 1.0]), "VEC4", 5123, &["TANGENT", "accessors[4]", "U16"]),
    ];
    for (name, tangents, ty, component, expected) in cases {
        let e = err(with_tangents(&dir, name, &tangents, ty, component, "normal.png"));
        assert!(e.contains(name) && e.contains("meshes[0].primitives[0]"), "{name}: {e}");
        for x in expected {
            assert!(e.contains(x), "{name}: `{x}` missing from: {e}");
        }
    }
    // An accessor longer than its buffer: named, not read past the end.
    let path = with_tangents(&dir, "short.gltf", &four([1.0, 0.0, 0.0, 1.0]), "VEC4", F32, "normal.png");
    let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    v["accessors"][4]["count"] = 5.into();
    std::fs::write(&path, serde_json::to_vec(&v).unwrap()).unwrap();
    let e = err(path);
    assert!(e.contains("TANGENT (accessors[4])") && e.contains("do not fit"), "{e}");
}

/// glTF 2.0 §3.7.2.1: without NORMAL (flat normals) the tangents are ignored: the image is that
/// of the same file without them.
#[test]
fn tangents_without_normals_are_ignored() {
    let dir = common::TempDir::new();
    let drop_normals = |path: &Path| {
        let mut v: serde_json::Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
        v["meshes"][0]["primitives"][0]["attributes"].as_object_mut().unwrap().remove("NORMAL");
        std::fs::write(path, serde_json::to_vec(&v).unwrap()).unwrap();
    };
    let with = with_tangents(&dir, "turned.gltf", &four([0.0, 0.0, 1.0, -1.0]), "VEC4", F32, "normal.png");
    drop_normals(&with);
    let without = dir.path().join("plain.gltf");
    std::fs::copy(data("normal_map.gltf"), &without).unwrap();
    drop_normals(&without);
    assert_eq!(differing_bits(&image(&with), &image(&without)), 0);
}
