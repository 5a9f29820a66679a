//! Objects' `flip_normals` (Mitsuba's `flip_normals`): a one-sided light turned inward lights
//! what it encloses, as the sky domes of Bitterli's scenes do; every shape that takes it is
//! turned over (sphere, quad, disk, triangle, plane, mesh with its vertex normals); the field
//! round-trips, is read from Mitsuba files, and a box, which cannot take it, gives a located
//! error. tests/data/flip_normals.xml (an inward sphere emitter around a flipped one-sided floor
//! and a ball) agrees with Mitsuba 3.9.1 block by block; read without the flips it does not.
//!
//! Reference (tests/data/flip_normals_blocks.rs): Mitsuba 3.9.1 `scalar_rgb`, 16 renders × 1024
//! spp, from `.venv-peers/bin/python benches/peers/block_means.py flip_normals.xml --scenes
//! crates/pathtrace-scene/tests/data --spp 1024 --runs 16 --name FLIP_NORMALS`.

mod blocks;
mod common;

use pathtrace::film::Image;
use pathtrace::integrator::PathSettings;
use pathtrace::wide::Kernel;
use pathtrace::{render, RenderSettings};
use pathtrace_scene::mitsuba::{convert_str, load_mitsuba};
use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
use std::path::Path;
use std::sync::Arc;

include!("data/flip_normals_blocks.rs");

#[test]
fn flipped_dome_and_floor_match_mitsuba_block_by_block() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/flip_normals.xml");
    let (loaded, warnings) = load_mitsuba(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    blocks::assert_scene_agrees("flip_normals.xml", loaded, 256, &FLIP_NORMALS_MEAN, &FLIP_NORMALS_SE);

    // The test sees the flips: read without them (the importer's old behaviour) the dome lights
    // nothing inside it, and the image is black where Mitsuba's mean is (0.59, 0.65, 0.84).
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("name=\"flip_normals\" value=\"true\"", "name=\"flip_normals\" value=\"false\"");
    let dir = common::TempDir::new();
    let (unflipped, _) = load_mitsuba(&dir.write("unflipped.xml", text), &[]).unwrap();
    let s = RenderSettings { width: 16, height: 16, spp: 4, ..Default::default() };
    let mean = render(Arc::new(unflipped.scene), s).unwrap().film.image().mean().to_array();
    assert_eq!(mean, [0.0; 3]);
}

/// The camera at (0, 0, −5) looks at a grey ball (albedo 0.5, radius 1) inside a sphere of
/// radius 20 that emits (1, 2, 3) from one side and reflects nothing.
fn dome(flip: bool) -> String {
    format!(
        r#"
[render]
width = 16
height = 16
[camera]
look_from = [0, 0, -5]
look_at = [0, 0, 0]
vfov = 30
[materials.sky]
type = "emissive"
radiance = [1, 2, 3]
[materials.grey]
type = "lambertian"
albedo = 0.5
[[objects]]
type = "sphere"
center = [0, 0, 0]
radius = 20
material = "sky"
flip_normals = {flip}
[[objects]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "grey"
"#
    )
}

fn render_text(text: &str, spp: u32, kernel: Kernel) -> (Image, pathtrace::film::Film) {
    let loaded = load_str(text, Format::Toml, Path::new("flip.toml")).unwrap();
    let d = loaded.defaults;
    let s = RenderSettings { width: d.width, height: d.height, spp, kernel, ..Default::default() };
    let out = render(Arc::new(loaded.scene), s).unwrap();
    (out.film.image(), out.film)
}

/// Inside an inward one-sided emitter of radiance L, the emitter is seen as L and a convex
/// Lambertian ball of albedo ρ, which sees nothing but the emitter, has radiance ρ·L (light
/// sampling from inside the sphere and material sampling, weighted by MIS). Turned outward, the
/// same emitter lights nothing inside it.
#[test]
fn an_inward_emitting_sphere_lights_what_it_encloses() {
    let (image, film) = render_text(&dome(true), 64, Kernel::Auto);
    let radiance = [1.0, 2.0, 3.0];
    for (x, y) in [(0, 0), (15, 0), (0, 15), (15, 15)] {
        let seen = image.get(x, y).to_array();
        for (s, l) in seen.into_iter().zip(radiance) {
            assert!((s as f64 - l).abs() < 1e-5, "dome pixel ({x}, {y}): {seen:?}");
        }
    }
    let ball = film.region_estimate(6, 6, 10, 10);
    for (c, l) in radiance.into_iter().enumerate() {
        let expected = 0.5 * l;
        let z = (ball.mean[c] - expected) / ball.variance_of_mean[c].sqrt();
        assert!(z.abs() < 4.0 && (ball.mean[c] / expected - 1.0).abs() < 0.02, "ball: {ball:?}, z {z}");
    }

    let (outward, _) = render_text(&dome(false), 4, Kernel::Auto);
    assert_eq!(outward.mean().to_array(), [0.0; 3], "an outward one-sided emitter lights nothing inside it");
}

/// The inward sphere light is served by the lane-parallel light samples and by the one-lane
/// instance alike: the same film to the bit.
#[test]
fn the_inward_sphere_light_gives_the_same_film_in_lanes_and_in_one_lane() {
    let (_, wide) = render_text(&dome(true), 1, Kernel::Auto);
    let (_, one) = render_text(&dome(true), 1, Kernel::Scalar);
    assert!(wide.pixels() == one.pixels(), "lanes and one lane differ");
}

/// A one-sided emitter of each flat shape, facing away from the camera (+z, the camera at the
/// origin looking along +z), is black; turned over it faces the camera and is seen as its
/// radiance in the image centre.
#[test]
fn every_flat_shape_and_meshes_turn_over() {
    let dir = common::TempDir::new();
    // One triangle in the plane z = 5 wound so its face normal is +z, with vertex normals +z.
    dir.write("tri.obj", "v -9 -9 5\nv 9 -9 5\nv 0 9 5\nvn 0 0 1\nf 1//1 2//1 3//1\n");
    let toml = dir.path().join("flip.toml");
    let shapes = [
        "type = \"quad\"\nq = [-9, -9, 5]\nu = [18, 0, 0]\nv = [0, 18, 0]",
        "type = \"disk\"\ncenter = [0, 0, 5]\nnormal = [0, 0, 1]\nradius = 9",
        "type = \"triangle\"\na = [-9, -9, 5]\nb = [9, -9, 5]\nc = [0, 9, 5]",
        "type = \"mesh\"\nfile = \"tri.obj\"\nnormals = \"file\"",
        "type = \"mesh\"\nfile = \"tri.obj\"\nnormals = \"face\"",
    ];
    for shape in shapes {
        for flip in [false, true] {
            let text = format!(
                "[render]\nwidth = 4\nheight = 4\nmax_depth = 1\n[camera]\nlook_from = [0, 0, 0]\nlook_at = [0, 0, 1]\n\
                 vfov = 10\n[materials.light]\ntype = \"emissive\"\nradiance = 2\n[[objects]]\n{shape}\n\
                 material = \"light\"\nflip_normals = {flip}\n"
            );
            let loaded = load_str(&text, Format::Toml, &toml).unwrap();
            let s = RenderSettings { width: 4, height: 4, spp: 1, ..Default::default() };
            let mean = render(Arc::new(loaded.scene), s).unwrap().film.image().mean().to_array();
            let expected = if flip { 2.0 } else { 0.0 };
            assert!(mean.iter().all(|&m| (m - expected).abs() < 1e-5), "{shape}, flip {flip}: {mean:?}");
        }
    }
}

/// A plane's front turns over too: a one-sided grey plane lit from the camera's side by a point
/// light shows only when its normal faces the camera.
#[test]
fn a_one_sided_plane_turns_over() {
    for (flip, lit) in [(false, false), (true, true)] {
        let text = format!(
            "[render]\nwidth = 4\nheight = 4\nmax_depth = 2\n[camera]\nlook_from = [0, 0, 0]\nlook_at = [0, 0, 1]\n\
             vfov = 10\n[materials.grey]\ntype = \"lambertian\"\nalbedo = 0.5\none_sided = true\n[[objects]]\n\
             type = \"plane\"\npoint = [0, 0, 5]\nnormal = [0, 0, 1]\nmaterial = \"grey\"\nflip_normals = {flip}\n\
             [[lights]]\ntype = \"point\"\nposition = [0, 0, 1]\nintensity = 16\n"
        );
        let loaded = load_str(&text, Format::Toml, Path::new("plane.toml")).unwrap();
        let path = PathSettings { max_depth: 2, ..Default::default() };
        let s = RenderSettings { width: 4, height: 4, spp: 1, path, ..Default::default() };
        let mean = render(Arc::new(loaded.scene), s).unwrap().film.image().mean().to_array();
        assert_eq!(mean[0] > 0.0, lit, "flip {flip}: {mean:?}");
    }
}

#[test]
fn flip_normals_round_trips_and_a_box_refuses_it() {
    let file = parse_str(&dome(true), Format::Toml, Path::new("a.toml")).unwrap();
    assert!(file.objects[0].flip_normals && !file.objects[1].flip_normals);
    let text = to_string(&file, Format::Toml).unwrap();
    assert_eq!(text.matches("flip_normals = true").count(), 1, "{text}");
    assert_eq!(parse_str(&text, Format::Toml, Path::new("b.toml")).unwrap(), file);

    let boxed = dome(false).replace(
        "type = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"grey\"",
        "type = \"box\"\nmin = [-1, -1, -1]\nmax = [1, 1, 1]\nmaterial = \"grey\"\nflip_normals = true",
    );
    let Err(e) = load_str(&boxed, Format::Toml, Path::new("box.toml")) else { panic!("a flipped box is refused") };
    let e = e.to_string();
    assert!(e.starts_with("box.toml:") && e.contains("flip_normals") && e.contains("box"), "{e}");
}

/// Mitsuba's `flip_normals` is read on every shape (a 0.6 file's `flipNormals` upgraded to it);
/// a cube's is warned about.
#[test]
fn mitsuba_flip_normals_is_read_on_every_shape() {
    let xml = |shape: &str| {
        format!(
            r#"<scene version="3.0.0">
  <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>
  <emitter type="point"><point name="position" value="0, 0, 0"/></emitter>
  <shape type="{shape}"><boolean name="flip_normals" value="true"/></shape>
</scene>"#
        )
    };
    for shape in ["sphere", "rectangle", "disk"] {
        let (file, warnings) = convert_str(&xml(shape), Path::new("s.xml"), &[]).unwrap();
        assert!(warnings.is_empty(), "{shape}: {warnings:?}");
        assert!(file.objects[0].flip_normals, "{shape}");
    }
    let (file, warnings) = convert_str(&xml("cube"), Path::new("s.xml"), &[]).unwrap();
    assert!(!file.objects[0].flip_normals);
    assert!(warnings.len() == 1 && warnings[0].contains("flip_normals"), "{warnings:?}");

    let old = r#"<scene version="0.6.0">
  <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>
  <emitter type="point"><point name="position" x="0" y="0" z="0"/></emitter>
  <shape type="sphere"><boolean name="flipNormals" value="true"/></shape>
</scene>"#;
    let (file, warnings) = convert_str(old, Path::new("old.xml"), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert!(file.objects[0].flip_normals);
}
