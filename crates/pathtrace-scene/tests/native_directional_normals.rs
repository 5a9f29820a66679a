//! The native format's directional light and mesh `normals` field: an analytic directional-light
//! image, the documented examples, round trips, located errors, and the four normal choices on a
//! bent two-triangle mesh.

mod common;

use pathtrace::math::{Ray, Vec3};
use pathtrace::{render, RenderSettings};
use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
use std::sync::Arc;

const FLOOR: &str = r#"
[render]
width = 8
height = 8
max_depth = 2
[camera]
look_from = [0, 5, 0]
look_at = [0, 0, 0]
up = [0, 0, 1]
vfov = 20
[materials.grey]
type = "lambertian"
albedo = 0.5
[[objects]]
type = "quad"
q = [-10, 0, -10]
u = [0, 0, 20]
v = [20, 0, 0]
material = "grey"
"#;

/// A Lambertian floor of albedo ρ under a directional light of irradiance E at angle θ from the
/// normal has radiance ρ/π·E·cos θ everywhere (one bounce); the light is a delta, so every
/// sample gives exactly that value.
#[test]
fn lambertian_floor_under_a_directional_light_has_the_closed_form_radiance() {
    let cases = [
        "direction = [0, -1, -1]",
        // The transform's local +z turned to (0, −1, −1)/√2: a rotation of 135° about x.
        "transform = [{ rotate_x = 135 }]",
    ];
    for light in cases {
        let text = format!("{FLOOR}[[lights]]\ntype = \"directional\"\nirradiance = [2, 1, 0.5]\n{light}\n");
        let loaded = load_str(&text, Format::Toml, "d.toml".as_ref()).unwrap();
        let d = loaded.defaults;
        let mut s = RenderSettings { width: d.width, height: d.height, spp: 4, ..Default::default() };
        s.path.max_depth = d.max_depth;
        let out = render(Arc::new(loaded.scene), s).unwrap();
        let mean = out.film.region_estimate(0, 0, d.width, d.height).mean;
        let cos = std::f64::consts::FRAC_1_SQRT_2;
        for (k, e) in [2.0, 1.0, 0.5].into_iter().enumerate() {
            let expected = 0.5 / std::f64::consts::PI * e * cos;
            assert!((mean[k] - expected).abs() < 1e-5 * expected.max(1.0), "{light}: {mean:?} vs {expected}");
        }
    }
}

#[test]
fn directional_light_errors_are_located() {
    let both = format!("{FLOOR}[[lights]]\ntype = \"directional\"\nirradiance = 1\ndirection = [0, -1, 0]\ntransform = [{{ rotate_x = 90 }}]\n");
    let e = load_str(&both, Format::Toml, "d.toml".as_ref()).unwrap_err().to_string();
    assert!(e.contains("d.toml:") && e.contains("not both"), "{e}");
    let zero = format!("{FLOOR}[[lights]]\ntype = \"directional\"\nirradiance = 1\ndirection = [0, 0, 0]\n");
    let e = load_str(&zero, Format::Toml, "d.toml".as_ref()).unwrap_err().to_string();
    assert!(e.contains("d.toml:") && e.contains("non-zero direction"), "{e}");
}

/// The TOML examples in the `//!` docs of the directional light and of vertex normals.
#[test]
fn documented_examples_parse_and_round_trip() {
    let light = include_str!("../../pathtrace/src/light/directional.rs");
    let normals = include_str!("../../pathtrace/src/shape/vertex_normals.rs");
    let example = |src: &str| -> String {
        let lines: Vec<&str> =
            src.lines().take_while(|l| l.starts_with("//!")).map(|l| l.trim_start_matches("//!")).collect();
        let start = lines.iter().position(|l| l.trim() == "```toml").unwrap() + 1;
        let end = start + lines[start..].iter().position(|l| l.trim() == "```").unwrap();
        lines[start..end].iter().map(|l| l.strip_prefix(' ').unwrap_or(l)).collect::<Vec<_>>().join("\n")
    };
    let text = format!("{FLOOR}{}\n{}\n", example(light), example(normals));
    let file = parse_str(&text, Format::Toml, "x.toml".as_ref()).unwrap();
    let json = to_string(&file, Format::Json).unwrap();
    assert_eq!(parse_str(&json, Format::Json, "x.json".as_ref()).unwrap(), file);
    let toml = to_string(&file, Format::Toml).unwrap();
    assert_eq!(parse_str(&toml, Format::Toml, "x.toml".as_ref()).unwrap(), file);
    let bad =
        format!("{FLOOR}[[objects]]\ntype = \"mesh\"\nfile = \"m.obj\"\nnormals = \"wobbly\"\nmaterial = \"grey\"\n");
    let e = parse_str(&bad, Format::Toml, "x.toml".as_ref()).unwrap_err().to_string();
    assert!(e.contains("x.toml:") && e.contains("wobbly"), "{e}");
}

/// Two triangles folded 90° along the z axis (a floor facing +y for x < 0 and a wall facing −x
/// at x = 0, y > 0), without normals in the file, lifted by 1 above the scene's floor: the
/// shading normal next to the fold is smooth (the fold's normal is (−1, 1, 0)/√2, both corner
/// angles there being 45°) for `smooth` and `computed`, and the face's for `face` and `file`.
#[test]
fn mesh_normal_choices() {
    let dir = common::TempDir::new();
    // Vertices 1 and 2 lie on the fold (the z axis); 0 is on the floor, 3 up the wall.
    let obj = "v -1 0 0\nv 0 0 -1\nv 0 0 1\nv 0 1 0\nf 1 3 2\nf 2 3 4\n";
    std::fs::write(dir.path().join("fold.obj"), obj).unwrap();
    let with_normals = "v -1 0 0\nv 0 0 -1\nv 0 0 1\nv 0 1 0\nvn 0 1 0\nf 1//1 3//1 2//1\nf 2//1 3//1 4//1\n";
    std::fs::write(dir.path().join("fold_n.obj"), with_normals).unwrap();
    let normal_at = |file: &str, choice: &str| -> Vec3 {
        let text = format!(
            "{FLOOR}[[objects]]\ntype = \"mesh\"\nfile = \"{file}\"\nnormals = \"{choice}\"\nmaterial = \"grey\"\n\
             transform = [{{ translate = [0, 1, 0] }}]\n\
             [[lights]]\ntype = \"directional\"\nirradiance = 1\n"
        );
        let scene_path = dir.path().join("s.toml");
        let scene = load_str(&text, Format::Toml, &scene_path).unwrap().scene;
        // Straight down onto the floor triangle, just left of the fold.
        let ray = Ray::new(Vec3::new(-0.01, 3.0, 0.0), Vec3::NEG_Y);
        let hit = scene.intersect(&ray, f32::INFINITY).unwrap();
        scene.interaction(&ray, &hit).surface.n_shading
    };
    let tilted = Vec3::new(-1.0, 1.0, 0.0).normalize();
    let close = |a: Vec3, b: Vec3| (a - b).length() < 0.03;
    for choice in ["smooth", "computed"] {
        let n = normal_at("fold.obj", choice);
        assert!(close(n, tilted), "{choice}: {n:?}");
    }
    for choice in ["face", "file"] {
        assert!(close(normal_at("fold.obj", choice), Vec3::Y), "{choice}");
    }
    // With normals in the file (all +y): `smooth` and `file` keep them, `computed` replaces them.
    assert!(close(normal_at("fold_n.obj", "smooth"), Vec3::Y));
    assert!(close(normal_at("fold_n.obj", "file"), Vec3::Y));
    assert!(close(normal_at("fold_n.obj", "computed"), tilted));
}
