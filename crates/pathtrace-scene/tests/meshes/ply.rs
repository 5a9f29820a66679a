//! PLY features, encodings and errors.

use crate::common::{s, write_ply, El, Enc, TempDir, Val};
use pathtrace::math::{Vec2, Vec3};
use pathtrace::shape::TriangleMesh;
use pathtrace_scene::mesh::{load_mesh, parse_mesh, MeshLoadError};
use std::path::Path;

const ENCODINGS: [Enc; 3] = [Enc::Ascii, Enc::Le, Enc::Be];

fn load(bytes: &[u8]) -> Result<TriangleMesh, MeshLoadError> {
    let dir = TempDir::new();
    let mut parts = load_mesh(&dir.write("part.ply", bytes))?;
    assert_eq!(parts.len(), 1);
    let (name, mesh) = parts.pop().unwrap();
    assert_eq!(name, "part", "a PLY part is named by the file stem");
    mesh.validate().unwrap();
    Ok(mesh)
}

/// A quad and a triangle with normals, uvs and every kind of extra data around them.
fn rich(enc: Enc) -> Vec<u8> {
    let material = El {
        name: "material",
        props: &["float shininess", "list ushort uint ids"],
        records: vec![vec![Val::S(2.0), Val::L(vec![1.0, 2.0])], vec![Val::S(3.0), Val::L(vec![])]],
    };
    let vertex_props = [
        "float x",
        "float y",
        "double z",
        "uchar red",
        "float nx",
        "float ny",
        "float nz",
        "list uchar short junk",
        "double u",
        "float v",
        "char c",
    ];
    let corners = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let vertex = El {
        name: "vertex",
        props: &vertex_props,
        records: corners
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let mut r = s(&[p[0], p[1], p[2], 200.0, 0.0, 0.0, 2.0]);
                r.push(Val::L(vec![-3.0; i]));
                r.extend(s(&[p[0] * 0.5, p[1] * 0.25, -4.0]));
                r
            })
            .collect(),
    };
    let edge = El { name: "edge", props: &["int a", "int b"], records: vec![s(&[0.0, 1.0])] };
    let face = El {
        name: "face",
        props: &["ushort flags", "list uchar int vertex_indices", "list uint float weights"],
        records: vec![
            vec![Val::S(7.0), Val::L(vec![0.0, 1.0, 2.0, 3.0]), Val::L(vec![0.5])],
            vec![Val::S(8.0), Val::L(vec![0.0, 2.0, 3.0]), Val::L(vec![])],
        ],
    };
    write_ply(enc, &[material, vertex, edge, face])
}

#[test]
fn every_encoding_gives_the_same_mesh() {
    let expected = TriangleMesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        indices: vec![[0, 1, 2], [0, 2, 3], [0, 2, 3]],
        normals: Some(vec![Vec3::Z; 4]),
        uvs: Some(vec![Vec2::ZERO, Vec2::new(0.5, 0.0), Vec2::new(0.5, 0.25), Vec2::new(0.0, 0.25)]),
        tangents: None,
    };
    for enc in ENCODINGS {
        assert_eq!(load(&rich(enc)).unwrap(), expected, "{enc:?}");
    }
}

fn simple(enc: Enc, vertex_props: &[&str], face_prop: &str, uv: [f64; 2]) -> Vec<u8> {
    let records = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .map(|p| s(&[p[0], p[1], p[2], uv[0], uv[1]])[..vertex_props.len()].to_vec())
        .collect();
    let vertex = El { name: "vertex", props: vertex_props, records };
    let face = El { name: "face", props: &[face_prop], records: vec![vec![Val::L(vec![0.0, 1.0, 2.0])]] };
    write_ply(enc, &[vertex, face])
}

#[test]
fn uv_names_index_types_and_sized_type_names() {
    for enc in ENCODINGS {
        for [u, v] in [["u", "v"], ["s", "t"], ["texture_u", "texture_v"], ["texture_s", "texture_t"]] {
            let props = ["float x", "float y", "float z", &format!("float {u}"), &format!("float {v}")];
            let m = load(&simple(enc, &props, "list uchar int vertex_indices", [0.25, 0.5])).unwrap();
            assert_eq!(m.uvs, Some(vec![Vec2::new(0.25, 0.5); 3]), "{enc:?} {u} {v}");
        }
        for list in
            ["list uchar uint vertex_index", "list ushort ushort vertex_indices", "list int uchar vertex_indices"]
        {
            let m = load(&simple(enc, &["float x", "float y", "float z"], list, [0.0; 2])).unwrap();
            assert_eq!(m.indices, vec![[0, 1, 2]], "{enc:?} {list}");
        }
        let sized = ["float32 x", "float64 y", "int16 z", "uint8 s"];
        let m = load(&simple(enc, &sized, "list uint8 int32 vertex_indices", [3.0, 0.0])).unwrap();
        assert_eq!(m.positions, vec![Vec3::ZERO, Vec3::X, Vec3::Y]);
        assert_eq!(m.uvs, None, "a lone s is not a texture coordinate");
    }
}

#[test]
fn zero_normals_drop_normals_for_the_mesh() {
    let props = ["float x", "float y", "float z", "float nx", "float ny", "float nz"];
    let vertex = El {
        name: "vertex",
        props: &props,
        records: vec![
            s(&[0.0, 0.0, 0.0, 0.0, 0.0, 3.0]),
            s(&[1.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
            s(&[0.0, 1.0, 0.0, 0.0, 0.0, 1.0]),
        ],
    };
    let face = El {
        name: "face",
        props: &["list uchar int vertex_indices"],
        records: vec![vec![Val::L(vec![0.0, 1.0, 2.0])]],
    };
    for enc in ENCODINGS {
        let m = load(&write_ply(enc, &[vertex.clone(), face.clone()])).unwrap();
        assert_eq!(m.normals, None);
    }
}

fn ply_error(bytes: &[u8]) -> MeshLoadError {
    parse_mesh(bytes, Path::new("bad.ply")).expect_err("the file should be rejected")
}

const HEADER: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
                      element face 1\nproperty list uchar int vertex_indices\nend_header\n";

#[test]
fn header_and_ascii_errors_name_the_line() {
    let body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    assert!(parse_mesh(format!("{HEADER}{body}").as_bytes(), Path::new("ok.ply")).is_ok());
    let cases = [
        ("plx\n".to_string(), 1, "not a PLY file"),
        (HEADER.replace("ascii", "binary_middle_endian"), 2, "unknown PLY format"),
        (HEADER.replace("format ascii 1.0\n", ""), 8, "no \"format\" line"),
        (HEADER.replace("end_header\n", ""), 8, "no \"end_header\""),
        (HEADER.replace("float y", "float7 y"), 5, "unknown property type \"float7\""),
        (HEADER.replace("vertex 3", "vertex three"), 3, "malformed element count"),
        (HEADER.replace("element vertex 3", "elephant"), 3, "unknown header keyword"),
        (HEADER.replace("property float z\n", ""), 3, "needs x, y and z"),
        (HEADER.replace("vertex_indices", "corners"), 7, "needs a vertex_indices list"),
        (HEADER.replace("uchar int vertex", "uchar float vertex"), 8, "list of an integer type"),
        (HEADER.replace("element face 1\nproperty list uchar int vertex_indices\n", ""), 7, "no face element"),
        (format!("{HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"), 13, "face 0 of 1: vertex index 3 is out of range"),
        (format!("{HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"), 13, "vertex index -1 is out of range"),
        (format!("{HEADER}0 0 0\n1 0 0\n0 1 0\n2 0 1\n"), 13, "at least 3 vertices"),
        (format!("{HEADER}0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n"), 12, "vertex 2 has a NaN"),
        (format!("{HEADER}0 0 0\n1 0 0\n0 1e40 0\n3 0 1 2\n"), 12, "NaN or infinite"),
        (format!("{HEADER}0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"), 11, "vertex 1 of 3: malformed number \"x\""),
        (format!("{HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n"), 13, "malformed integer \"1.5\""),
        (format!("{HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1"), 13, "the file ends in the middle"),
        (HEADER.replace("vertex 3", "vertex 4000000000"), 10, "the header declares 4000000000 vertices"),
        (HEADER.replace("vertex 3", "vertex 1099511627776"), 3, "too many vertices for 32-bit indices"),
        (HEADER.replace("face 1", "face 0") + "0 0 0\n1 0 0\n0 1 0\n", 9, "no faces"),
    ];
    for (text, line, message) in cases {
        let e = ply_error(text.as_bytes());
        assert_eq!(e.line(), Some(line), "{e}");
        assert!(e.message().contains(message), "{e} should say {message:?}");
        assert!(e.to_string().starts_with(&format!("bad.ply:{line}: ")), "{e}");
    }
}

#[test]
fn binary_errors_name_the_byte_offset() {
    for enc in [Enc::Le, Enc::Be] {
        let good = rich(enc);
        let header_len = good.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
        let truncated = ply_error(&good[..good.len() - 3]);
        assert!(truncated.message().contains("ends in the middle"), "{truncated}");
        let offset = truncated.offset().unwrap();
        assert!(offset as usize >= header_len && (offset as usize) < good.len(), "{truncated}");
        assert!(truncated.to_string().ends_with(&format!("(byte offset {offset})")), "{truncated}");
        // Counts beyond what the file can hold fail before allocating.
        let huge = String::from_utf8_lossy(&good[..header_len]).replace("vertex 4", "vertex 4000000000");
        let mut bytes = huge.into_bytes();
        bytes.extend_from_slice(&good[header_len..]);
        let e = ply_error(&bytes);
        assert!(e.message().contains("declares 4000000000 vertices"), "{e}");
        let too_many = String::from_utf8_lossy(&good[..header_len]).replace("vertex 4", "vertex 1099511627776");
        assert!(ply_error(too_many.as_bytes()).message().contains("32-bit"));
    }
    let mut bad_index = simple(Enc::Le, &["float x", "float y", "float z"], "list uchar int vertex_indices", [0.0; 2]);
    let n = bad_index.len();
    bad_index[n - 4..].copy_from_slice(&7i32.to_le_bytes());
    let e = ply_error(&bad_index);
    assert_eq!(e.offset(), Some(n as u64 - 4), "{e}");
    assert!(e.message().contains("vertex index 7 is out of range: the file has 3 vertices"), "{e}");
}
