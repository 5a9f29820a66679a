//! The native format's pixel filter, `[[lights]]` (point, constant), `disk` shape and
//! `thindielectric` material: parsed with their defaults, round-tripped through TOML and JSON,
//! built into the engine's types, and rejected with a location when wrong.

use pathtrace::film::PixelFilter;
use pathtrace::light::Light;
use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
use std::path::Path;

const SCENE: &str = r#"[render]
filter = { type = "gaussian", stddev = 0.3 }

[camera]
look_from = [0, 0, -4]
look_at = [0, 0, 0]

[materials.pane]
type = "thindielectric"
ior = 1.4

[materials.lamp]
type = "emissive"
radiance = 3

[[objects]]
type = "disk"
center = [0, 0, 0]
normal = [0, 0, -1]
radius = 1
material = "pane"

[[objects]]
type = "disk"
center = [0, 3, 0]
normal = [0, -1, 0]
radius = 0.5
material = "lamp"

[[lights]]
type = "constant"
radiance = [0.1, 0.2, 0.3]

[[lights]]
type = "point"
position = [1, 2, 3]
intensity = 5
"#;

fn load(text: &str) -> Result<pathtrace_scene::LoadedScene, String> {
    load_str(text, Format::Toml, Path::new("s.toml")).map_err(|e| e.to_string())
}

#[test]
fn filters_lights_disks_and_thin_glass_build() {
    let loaded = load(SCENE).unwrap();
    let Some(PixelFilter::Gaussian(g)) = &loaded.defaults.filter else { panic!("{:?}", loaded.defaults.filter) };
    assert_eq!(g.stddev(), 0.3);
    let lights = &loaded.scene.lights;
    assert_eq!(lights.area_lights().count(), 1, "the emissive disk is an area light");
    assert_eq!(lights.lights().iter().filter(|l| matches!(l, Light::Point(_))).count(), 1);
    assert_eq!(lights.environment().and_then(|e| e.constant_radiance()).map(|r| r.b), Some(0.3));
    for (text, expected) in [
        (r#"filter = { type = "box" }"#, PixelFilter::Pixel),
        (r#"filter = { type = "box", radius = 1 }"#, PixelFilter::Box { radius: 1.0 }),
        (r#"filter = { type = "tent" }"#, PixelFilter::Tent { radius: 1.0 }),
    ] {
        let scene = SCENE.replace(r#"filter = { type = "gaussian", stddev = 0.3 }"#, text);
        assert_eq!(load(&scene).unwrap().defaults.filter, Some(expected));
    }
}

#[test]
fn the_new_items_round_trip_through_toml_and_json() {
    let file = parse_str(SCENE, Format::Toml, Path::new("s.toml")).unwrap();
    for format in [Format::Toml, Format::Json] {
        let text = to_string(&file, format).unwrap();
        assert_eq!(parse_str(&text, format, Path::new("s")).unwrap(), file, "{text}");
    }
}

#[test]
fn mistakes_are_located() {
    // (text replaced, replacement, lines the error may point at, what it must say)
    let cases = [
        (
            r#"filter = { type = "gaussian", stddev = 0.3 }"#,
            r#"filter = { type = "tent", stddev = 1 }"#,
            2..=2,
            "stddev",
        ),
        (
            r#"filter = { type = "gaussian", stddev = 0.3 }"#,
            r#"filter = { type = "box", radius = -1 }"#,
            2..=2,
            "radius",
        ),
        (
            r#"filter = { type = "gaussian", stddev = 0.3 }"#,
            r#"filter = { type = "tent", radius = 1e9 }"#,
            2..=2,
            "at most 40000",
        ),
        (
            r#"filter = { type = "gaussian", stddev = 0.3 }"#,
            r#"filter = { type = "mitchell" }"#,
            2..=2,
            "unknown variant",
        ),
        ("radius = 0.5", "radius = 0", 22..=27, "degenerate disk"),
        ("intensity = 5", "intensity = -5", 34..=37, "point light"),
        ("type = \"point\"", "type = \"spotlight\"", 34..=37, "unknown variant"),
        ("ior = 1.4", "ior = -1", 8..=10, "index of refraction must be a positive number"),
    ];
    for (from, to, lines, what) in cases {
        let e = load(&SCENE.replace(from, to)).unwrap_err();
        let line: usize = e.split(':').nth(1).and_then(|l| l.parse().ok()).unwrap_or(0);
        assert!(e.starts_with("s.toml:") && lines.contains(&line) && e.contains(what), "{to}: {e}");
    }
}
