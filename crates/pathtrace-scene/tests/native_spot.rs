//! The native format's `[[lights]] type = "spot"` and `[render] light_selection`: defaults,
//! round trips through TOML and JSON, what they build, and located errors.

use pathtrace::light::{Light, LightSelection, LightSet, SpotLight};
use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
use std::path::Path;

const SCENE: &str = r#"[render]
light_selection = "uniform"

[camera]
look_from = [0, 1, -4]
look_at = [0, 0, 0]

[materials.floor]
type = "diffuse"
albedo = 0.5

[[objects]]
type = "quad"
q = [-2, 0, -2]
u = [0, 0, 4]
v = [4, 0, 0]
material = "floor"

[[lights]]
type = "spot"
intensity = [10, 8, 6]
cutoff_angle = 30
transform = [{ look_at = { from = [0, 2, 0], to = [0, 0, 0], up = [0, 0, 1] } }]

[[lights]]
type = "spot"
intensity = 2
cutoff_angle = 40
beam_width = 10
"#;

fn load(text: &str) -> Result<pathtrace_scene::LoadedScene, String> {
    load_str(text, Format::Toml, Path::new("s.toml")).map_err(|e| e.to_string())
}

/// The set's spot lights.
fn spots(lights: &LightSet) -> Vec<&SpotLight> {
    lights
        .lights()
        .iter()
        .filter_map(|l| match l {
            Light::Spot(s) => Some(s),
            _ => None,
        })
        .collect()
}

#[test]
fn spot_lights_and_light_selection_build() {
    let loaded = load(SCENE).unwrap();
    assert_eq!(loaded.defaults.light_selection, Some(LightSelection::Uniform));
    let lights = &loaded.scene.lights;
    assert_eq!(lights.selection(), LightSelection::Uniform);
    assert_eq!(spots(lights).len(), 2);
    assert!(lights.has_delta());
    let spot = spots(lights)[0];
    assert_eq!(spot.position(), pathtrace::math::Vec3::new(0.0, 2.0, 0.0));
    // Pointing down; default beam width 3/4 · 30 = 22.5°: full at 20°, half-way down the ramp
    // at 26.25°, nothing at 31°.
    let at = |deg: f32| spot.falloff(pathtrace::math::Vec3::new(deg.to_radians().sin(), -deg.to_radians().cos(), 0.0));
    assert_eq!(at(20.0), 1.0);
    assert!((at(26.25) - 0.5).abs() < 1e-4);
    assert_eq!(at(31.0), 0.0);
    // Uniform selection: the two spots are equally likely.
    assert!((lights.index_pmf(0) - 0.5).abs() < 1e-6 && (lights.index_pmf(1) - 0.5).abs() < 1e-6);
    let power = load(&SCENE.replace("light_selection = \"uniform\"", "light_selection = \"power\"")).unwrap();
    assert!(power.scene.lights.index_pmf(0) > 0.8, "the brighter, wider spot dominates by power");
}

#[test]
fn spots_round_trip_through_toml_and_json() {
    let file = parse_str(SCENE, Format::Toml, Path::new("s.toml")).unwrap();
    for format in [Format::Toml, Format::Json] {
        let text = to_string(&file, format).unwrap();
        assert_eq!(parse_str(&text, format, Path::new("s")).unwrap(), file, "{text}");
    }
}

#[test]
fn spot_mistakes_are_located() {
    // (text replaced, replacement, lines the error may point at, what it must say)
    let cases = [
        ("beam_width = 10", "beam_width = 50", 25..=29, "beam_width ≤ cutoff_angle"),
        ("intensity = 2", "intensity = -2", 25..=29, "intensity ≥ 0"),
        ("cutoff_angle = 30", "cutoff_angle = 0", 19..=23, "0 < beam_width"),
        ("cutoff_angle = 40", "cutoff_angle = 40\nposition = [0, 1, 0]", 19..=30, "unknown field"),
        ("light_selection = \"uniform\"", "light_selection = \"random\"", 2..=2, "power or uniform"),
    ];
    for (from, to, lines, what) in cases {
        let e = load(&SCENE.replace(from, to)).unwrap_err();
        let line: usize = e.split(':').nth(1).and_then(|l| l.parse().ok()).unwrap_or(0);
        assert!(e.starts_with("s.toml:") && lines.contains(&line) && e.contains(what), "{to}: {e}");
    }
}
