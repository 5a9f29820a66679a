//! The native model: TOML → JSON → TOML round trips, defaults, and the scene-graph semantics
//! (object transform first, then each enclosing group's, innermost first).

use pathtrace::integrator::Strategy;
use pathtrace::math::{Ray, Vec3};
use pathtrace::sampling::SamplerKind;
use pathtrace_scene::native::{load_str, parse_str, to_string, Format};

const CORNELL: &str = include_str!("../../../scenes/cornell-box.toml");
const FEATURES: &str = include_str!("data/features.toml");

#[test]
fn toml_to_json_to_toml_gives_the_same_scene_file() {
    for (name, text) in [("cornell-box.toml", CORNELL), ("features.toml", FEATURES)] {
        let original = parse_str(text, Format::Toml, name.as_ref()).unwrap();
        let json = to_string(&original, Format::Json).unwrap();
        let from_json = parse_str(&json, Format::Json, "x.json".as_ref()).unwrap();
        assert_eq!(original, from_json, "{name}: TOML → JSON changed the scene");
        let toml = to_string(&from_json, Format::Toml).unwrap();
        let back = parse_str(&toml, Format::Toml, "x.toml".as_ref()).unwrap();
        assert_eq!(original, back, "{name}: JSON → TOML changed the scene:\n{toml}");
    }
}

#[test]
fn render_settings_and_aspect_follow_the_documented_rules() {
    let loaded = load_str(FEATURES, Format::Toml, "features.toml".as_ref()).unwrap();
    let d = loaded.defaults;
    // width 64 given, height not: height = round(64 / aspect 2) = 32.
    assert_eq!((d.width, d.height, d.spp, d.max_depth), (64, 32, 4, 6));
    assert_eq!((d.strategy, d.sampler, d.seed), (Some(Strategy::Bsdf), Some(SamplerKind::Stratified), Some(42)));
    let minimal = "[camera]\nlook_from = [0, 0, 5]\nlook_at = [0, 0, 0]\naspect = 0.5\n[render]\nheight = 100\n\
                   [materials.l]\ntype = \"emissive\"\nradiance = 1\n\
                   [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"l\"\n";
    let d = load_str(minimal, Format::Toml, "m.toml".as_ref()).unwrap().defaults;
    assert_eq!((d.width, d.height, d.spp, d.max_depth), (50, 100, 64, -1));
    assert_eq!((d.strategy, d.sampler, d.seed), (None, None, None));
}

#[test]
fn group_transforms_apply_after_object_transforms_innermost_first() {
    // A unit sphere at the origin, scaled by 2, inside a group translating by +10 x, inside a group
    // rotating 90° about y. Object first: radius 2; then +10 x; then (10, 0, 0) → (0, 0, -10).
    let text = r#"{
      "camera": {"look_from": [0, 0, 0], "look_at": [0, 0, 1]},
      "materials": {"l": {"type": "emissive", "radiance": 1}},
      "groups": [{"transform": [{"rotate_y": 90}],
                  "groups": [{"transform": [{"translate": [10, 0, 0]}],
                              "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "l",
                                           "transform": [{"scale": 2}]}]}]}]
    }"#;
    let scene = load_str(text, Format::Json, "g.json".as_ref()).unwrap().scene;
    let hit = |origin: Vec3, dir: Vec3| scene.intersect(&Ray::new(origin, dir), f32::INFINITY).map(|h| h.hit.t);
    let t = hit(Vec3::ZERO, -Vec3::Z).expect("the sphere should be at z = -10");
    assert!((t - 8.0).abs() < 1e-3, "t = {t}");
    assert!(hit(Vec3::ZERO, Vec3::X).is_none());
}

#[test]
fn the_documentation_example_loads_and_converts() {
    let doc = include_str!("../../../docs/scene-format.md");
    let start = doc.find("```toml\n").expect("a toml example") + "```toml\n".len();
    let example = &doc[start..start + doc[start..].find("```").unwrap()];
    let loaded = load_str(example, Format::Toml, "example.toml".as_ref()).unwrap();
    assert_eq!((loaded.defaults.width, loaded.defaults.height, loaded.defaults.spp), (640, 480, 128));
    let file = parse_str(example, Format::Toml, "example.toml".as_ref()).unwrap();
    let json = to_string(&file, Format::Json).unwrap();
    assert_eq!(parse_str(&json, Format::Json, "example.json".as_ref()).unwrap(), file);
}

/// Loads every `.toml` scene in `scenes/NAME` of the repository; returns how many there were.
fn load_every_scene_in(name: &str) -> usize {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes").join(name);
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            pathtrace_scene::native::load_file(&path).unwrap_or_else(|e| panic!("{e}"));
            count += 1;
        }
    }
    count
}

#[test]
fn every_gallery_scene_loads() {
    let count = load_every_scene_in("gallery");
    assert!(count >= 7, "found only {count} gallery scenes");
}

#[test]
fn the_convergence_study_scenes_load() {
    assert!(load_every_scene_in("converge") >= 1, "found no scene in scenes/converge");
}
