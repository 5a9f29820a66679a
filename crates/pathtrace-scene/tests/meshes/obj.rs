//! OBJ features and errors.

use crate::common::TempDir;
use pathtrace::math::{Vec2, Vec3};
use pathtrace::shape::TriangleMesh;
use pathtrace_scene::mesh::{load_mesh, MeshLoadError};

fn load(text: &str) -> Result<Vec<(String, TriangleMesh)>, MeshLoadError> {
    let dir = TempDir::new();
    load_mesh(&dir.write("test.obj", text))
}

fn one(text: &str) -> TriangleMesh {
    let mut parts = load(text).unwrap();
    assert_eq!(parts.len(), 1);
    let (name, mesh) = parts.pop().unwrap();
    assert_eq!(name, "default");
    mesh.validate().unwrap();
    mesh
}

fn error(text: &str) -> MeshLoadError {
    load(text).expect_err("the file should be rejected")
}

const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

#[test]
fn polygons_are_fan_triangulated() {
    let m = one(&format!("{QUAD}f 1 2 3 4\n"));
    assert_eq!(m.positions, vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y]);
    assert_eq!(m.indices, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!((m.normals, m.uvs), (None, None));
    let pentagon = one(&format!("{QUAD}v 0.5 2 0\nf 1 2 3 5 4\n"));
    assert_eq!(pentagon.indices, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
}

#[test]
fn every_corner_form_is_read() {
    let attrs = "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 2\n";
    let full = one(&format!("{QUAD}{attrs}f 1/1/1 2/2/1 3/3/1\n"));
    assert_eq!(full.normals, Some(vec![Vec3::Z; 3]), "normals are normalised");
    assert_eq!(full.uvs, Some(vec![Vec2::ZERO, Vec2::X, Vec2::ONE]));
    let uv_only = one(&format!("{QUAD}{attrs}f 1/1 2/2 3/3\n"));
    assert_eq!((uv_only.normals, uv_only.uvs), (None, full.uvs.clone()));
    let normal_only = one(&format!("{QUAD}{attrs}f 1//1 2//1 3//1\n"));
    assert_eq!((normal_only.normals, normal_only.uvs), (full.normals.clone(), None));
    let vt_one_number = one(&format!("{QUAD}vt 0.5\nf 1/1 2/1 3/1\n"));
    assert_eq!(vt_one_number.uvs, Some(vec![Vec2::new(0.5, 0.0); 3]));
}

#[test]
fn negative_indices_count_back_from_the_last_vertex() {
    let absolute = one(&format!("{QUAD}vn 0 0 1\nf 1//1 2//1 3//1 4//1\n"));
    let relative = one(&format!("{QUAD}vn 0 0 1\nf -4//-1 -3//-1 -2//-1 -1//-1\n"));
    assert_eq!(absolute, relative);
}

#[test]
fn usemtl_groups_become_parts_holding_only_their_vertices() {
    let text = format!(
        "{QUAD}v 2 0 0\nv 2 1 0\nf 1 2 3\nusemtl red\nf 2 5 6\no other\ng group\nusemtl blue\nf 1 3 4\n\
         usemtl red\nf 2 6 3\n"
    );
    let parts = load(&text).unwrap();
    let names: Vec<&str> = parts.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["default", "red", "blue"]);
    let red = &parts[1].1;
    assert_eq!(
        red.positions,
        vec![Vec3::X, Vec3::new(2.0, 0.0, 0.0), Vec3::new(2.0, 1.0, 0.0), Vec3::new(1.0, 1.0, 0.0)]
    );
    assert_eq!(red.indices, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(parts[2].1.positions.len(), 3);
    for (_, m) in &parts {
        m.validate().unwrap();
    }
}

#[test]
fn vertices_are_shared_per_distinct_triple() {
    let shared = one(&format!("{QUAD}f 1 2 3\nf 1 3 4\n"));
    assert_eq!(shared.positions.len(), 4);
    // The same position with two different normals is two vertices.
    let split = one(&format!("{QUAD}vn 0 0 1\nvn 0 1 0\nf 1//1 2//1 3//1\nf 1//2 3//2 4//2\n"));
    assert_eq!(split.positions.len(), 6);
    assert_eq!(split.indices, vec![[0, 1, 2], [3, 4, 5]]);
}

#[test]
fn mixed_corners_drop_normals_and_uvs_for_the_part() {
    let m = one(&format!("{QUAD}vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf 1 3 4\n"));
    assert_eq!((m.normals, m.uvs), (None, None));
    // Dropped attributes no longer split vertices.
    assert_eq!(m.positions.len(), 4);
    // Only the part with the mixed corners loses them.
    let parts = load(&format!("{QUAD}vn 0 0 1\nf 1//1 2//1 3//1\nusemtl b\nf 1//1 3 4//1\n")).unwrap();
    assert!(parts[0].1.normals.is_some());
    assert!(parts[1].1.normals.is_none());
}

#[test]
fn zero_normals_drop_normals_for_the_part() {
    let m = one(&format!("{QUAD}vn 0 0 0\nvn 0 0 1\nf 1//1 2//2 3//2\n"));
    assert_eq!(m.normals, None);
}

#[test]
fn comments_blank_lines_crlf_continuations_and_ignored_statements() {
    let text = "# a comment\r\nmtllib x.mtl\r\no thing\r\n\r\nv 0 0 0 # trailing comment\r\nv 1 0 \\\r\n 0\r\n\
                v 0 1 0 1.0\r\ns off\r\nvp 0.5\r\nl 1 2\r\nf 1 \\\n2 3\r\n";
    let m = one(text);
    assert_eq!(m.positions, vec![Vec3::ZERO, Vec3::X, Vec3::Y]);
    assert_eq!(m.indices, vec![[0, 1, 2]]);
}

#[test]
fn errors_name_file_and_line() {
    let cases = [
        (format!("{QUAD}f 1 2 9\n"), 5, "vertex index 9 is out of range: 4 defined so far"),
        (format!("{QUAD}f 1 2 -5\n"), 5, "vertex index -5 is out of range"),
        (format!("{QUAD}f 0 1 2\n"), 5, "index 0 is invalid"),
        (format!("{QUAD}f 1/1 2/1 3/1\n"), 5, "texture coordinate index 1 is out of range: 0 defined"),
        (format!("{QUAD}f 1//1 2//1 3//1\n"), 5, "normal index 1 is out of range"),
        (format!("{QUAD}f 1 2\n"), 5, "at least 3 vertices"),
        (format!("{QUAD}f 1/2/3/4 2 3\n"), 5, "malformed face corner \"1/2/3/4\""),
        (format!("{QUAD}f 1// 2 3\n"), 5, "malformed face corner"),
        (format!("{QUAD}f 1/ 2 3\n"), 5, "malformed face corner"),
        (format!("{QUAD}f a 2 3\n"), 5, "malformed vertex index \"a\""),
        ("v 0 0\n".to_string(), 1, "a vertex position needs 3 numbers, found 2"),
        ("\nv 0 0 1..5\n".to_string(), 2, "malformed number \"1..5\""),
        ("v 0 nan 0\n".to_string(), 1, "the number \"nan\" is not finite"),
        ("v 0 0 inf\n".to_string(), 1, "not finite"),
        ("v 0 0 1e39\n".to_string(), 1, "not finite"),
        ("vn 0 0 NaN\n".to_string(), 1, "not finite"),
        ("vt 0 infinity\n".to_string(), 1, "not finite"),
        (QUAD.to_string(), 5, "the file holds no faces"),
    ];
    for (text, line, message) in cases {
        let e = error(&text);
        assert_eq!(e.line(), Some(line), "{e}");
        assert!(e.message().contains(message), "{e} should say {message:?}");
        let shown = e.to_string();
        assert!(shown.contains(&format!("test.obj:{line}: ")), "{shown}");
        assert!(!shown.contains('\n'));
    }
}

#[test]
fn extensions_are_case_insensitive_and_unknown_ones_rejected() {
    let dir = TempDir::new();
    let text = format!("{QUAD}f 1 2 3\n");
    assert!(load_mesh(&dir.write("upper.OBJ", &text)).is_ok());
    let e = load_mesh(&dir.write("mesh.stl", &text)).unwrap_err();
    assert!(e.to_string().contains("unsupported mesh format"), "{e}");
    let e = load_mesh(&dir.path().join("missing.obj")).unwrap_err();
    assert!(e.to_string().starts_with(&dir.path().join("missing.obj").display().to_string()), "{e}");
    assert!(e.message().contains("cannot read"), "{e}");
}

#[test]
fn errors_are_std_errors() {
    fn takes(_: &dyn std::error::Error) {}
    takes(&error("f 1 2 3\n"));
}

/// A byte-order mark used to swallow the first line (shifting every index after it), and classic
/// Mac line endings made the file one line: every encoding of the lines reads the same mesh.
#[test]
fn byte_order_marks_and_every_line_ending_read_the_same_mesh() {
    let plain = one(&format!("{QUAD}f 1 2 3 4\n"));
    let lf = format!("{QUAD}f 1 2 3 4\n");
    for text in [
        format!("\u{feff}{lf}"),
        lf.replace('\n', "\r\n"),
        lf.replace('\n', "\r"),
        format!("\u{feff}{}", lf.replace('\n', "\r")),
    ] {
        assert_eq!(one(&text), plain, "{text:?}");
    }
    let located = error("\u{feff}v 0 0 0\r\rv 1 x 0\r").to_string();
    assert!(located.contains(":3:"), "{located}");
}
