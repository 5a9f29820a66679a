//! The native format's `[camera] type = "thinlens"` and `"orthographic"`: what they build, the
//! focus-distance default, round trips through TOML and JSON, and located errors.

use pathtrace::Lens;
use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
use std::path::Path;

const SCENE: &str = r#"[camera]
type = "thinlens"
look_from = [0, 0, -4]
look_at = [0, 0, 0]
aperture_radius = 0.1
focus_distance = 3

[materials.light]
type = "diffuse"
albedo = 0
emission = 5

[[objects]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "light"
"#;

fn load(text: &str) -> Result<pathtrace_scene::LoadedScene, String> {
    load_str(text, Format::Toml, Path::new("s.toml")).map_err(|e| e.to_string())
}

#[test]
fn thin_lens_and_orthographic_cameras_build() {
    let lens = |text: &str| load(text).unwrap().scene.camera.lens;
    assert_eq!(lens(SCENE), Lens::ThinLens { aperture_radius: 0.1, focus_distance: 3.0 });
    // Without focus_distance the camera focuses on look_at.
    assert_eq!(
        lens(&SCENE.replace("focus_distance = 3\n", "")),
        Lens::ThinLens { aperture_radius: 0.1, focus_distance: 4.0 }
    );
    let ortho = SCENE
        .replace("type = \"thinlens\"", "type = \"orthographic\"")
        .replace("aperture_radius = 0.1\nfocus_distance = 3", "height = 2.5");
    assert_eq!(lens(&ortho), Lens::Orthographic { height: 2.5 });
    let pinhole = SCENE.replace("type = \"thinlens\"\n", "").replace("aperture_radius = 0.1\nfocus_distance = 3\n", "");
    assert_eq!(lens(&pinhole), Lens::Pinhole);
}

#[test]
fn cameras_round_trip_through_toml_and_json() {
    let file = parse_str(SCENE, Format::Toml, Path::new("s.toml")).unwrap();
    for format in [Format::Toml, Format::Json] {
        let text = to_string(&file, format).unwrap();
        assert_eq!(parse_str(&text, format, Path::new("s")).unwrap(), file, "{text}");
    }
}

#[test]
fn camera_mistakes_are_located() {
    // (text replaced, replacement, what the error must say)
    let cases = [
        ("aperture_radius = 0.1\n", "", "needs `aperture_radius`"),
        ("aperture_radius = 0.1", "aperture_radius = -1", "aperture radius -1 must be zero or positive"),
        ("focus_distance = 3", "focus_distance = 0", "focus distance 0 must be positive"),
        ("type = \"thinlens\"", "type = \"orthographic\"", "belongs to a `type = \"thinlens\"` camera"),
        ("type = \"thinlens\"", "type = \"fisheye\"", "unknown variant `fisheye`"),
        ("focus_distance = 3", "focus_distance = 3\nheight = 2", "belongs to a `type = \"orthographic\"` camera"),
    ];
    for (from, to, says) in cases {
        let text = SCENE.replace(from, to);
        assert_ne!(text, SCENE, "{from}");
        let err = load(&text).expect_err(to);
        assert!(err.contains("s.toml") && err.contains(says), "{to}: {err}");
    }
}
