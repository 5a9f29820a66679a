//! Every kind of bad scene file gives one message `FILE:LINE:COL: what is wrong`, pointing at
//! the offending line, in TOML and in JSON.

use pathtrace_scene::native::{load_str, Format};

/// A valid scene to break in one place: camera on lines 1–3, materials from line 5, the quad
/// from line 13 and the sphere from line 20 (its radius on line 23).
const GOOD: &str = r#"[camera]
look_from = [0, 1, -5]
look_at = [0, 1, 0]

[materials.white]
type = "lambertian"
albedo = 0.5

[materials.lamp]
type = "emissive"
radiance = [4, 4, 4]

[[objects]]
type = "quad"
q = [-1, 0, -1]
u = [2, 0, 0]
v = [0, 0, 2]
material = "white"

[[objects]]
type = "sphere"
center = [0, 2, 0]
radius = 0.5
material = "lamp"
"#;

fn error(text: &str, format: Format) -> String {
    let name = if format == Format::Toml { "s.toml" } else { "s.json" };
    match load_str(text, format, name.as_ref()) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn toml_error(replace: &str, with: &str) -> String {
    assert!(GOOD.contains(replace), "{replace}");
    error(&GOOD.replacen(replace, with, 1), Format::Toml)
}

fn expect(msg: &str, location: &str, words: &[&str]) {
    assert!(msg.starts_with(location), "expected {location}…, got: {msg}");
    for w in words {
        assert!(msg.contains(w), "expected '{w}' in: {msg}");
    }
    assert!(!msg.contains('\n'), "not one line: {msg}");
}

#[test]
fn the_good_scene_loads() {
    let loaded = load_str(GOOD, Format::Toml, "s.toml".as_ref()).unwrap();
    assert_eq!(loaded.scene.primitive_count(), 2);
}

#[test]
fn syntax_errors_point_at_the_line() {
    expect(&toml_error("radius = 0.5", "radius = = 0.5"), "s.toml:23:10:", &["radius = = 0.5"]);
    expect(&error("{\"camera\": {\n  \"look_from\": [0, 1,, 0]}}", Format::Json), "s.json:2:", &["look_from"]);
    expect(&error("{\"camera\": {", Format::Json), "s.json:1:", &["EOF"]);
}

#[test]
fn schema_errors_point_at_the_value() {
    expect(&toml_error("radius = 0.5", "radus = 0.5"), "s.toml:", &["radus"]);
    expect(&toml_error("radius = 0.5", "radius = \"big\""), "s.toml:23:10:", &["radius = \"big\""]);
    expect(&toml_error("radius = 0.5", "radius = nan"), "s.toml:23:10:", &["NaN", "finite"]);
    expect(&toml_error("albedo = 0.5", "albedo = [0.5, inf, 0.5]"), "s.toml:7:", &["finite"]);
    expect(&toml_error("type = \"quad\"", "type = \"quadd\""), "s.toml:14:8:", &["quadd"]);
    expect(&toml_error("look_at = [0, 1, 0]", "look_at = [0, 1]"), "s.toml:3:", &["length"]);
    expect(&toml_error("[camera]", "[render]\nwidth = -4\n[camera]"), "s.toml:2:9:", &["width"]);
    expect(&toml_error("[camera]", "[render]\nstrategy = \"fast\"\n[camera]"), "s.toml:2:12:", &["fast", "mis"]);
    expect(&toml_error("[camera]", "[render]\nrr_depth = 0\n[camera]"), "s.toml:2:", &["rr_depth", "at least 1"]);
}

#[test]
fn build_errors_point_at_their_object() {
    expect(&toml_error("material = \"white\"", "material = \"whte\""), "s.toml:18:12:", &["whte", "lamp, white"]);
    expect(&toml_error("v = [0, 0, 2]", "v = [4, 0, 0]"), "s.toml:13:", &["degenerate quad"]);
    expect(&toml_error("radius = 0.5", "radius = -0.5"), "s.toml:20:", &["degenerate sphere"]);
    expect(&toml_error("albedo = 0.5", "albedo = 1.5"), "s.toml:5:", &["white", "[0, 1]"]);
    expect(
        &toml_error("type = \"sphere\"", "transform = [{scale = 0}]\ntype = \"sphere\""),
        "s.toml:21:",
        &["non-zero"],
    );
    expect(&toml_error("look_at = [0, 1, 0]", "look_at = [0, 1, -5]"), "s.toml:1:1:", &["camera"]);
    expect(
        &toml_error(
            "type = \"quad\"\nq = [-1, 0, -1]\nu = [2, 0, 0]\nv = [0, 0, 2]",
            "type = \"mesh\"\nfile = \"no/such.obj\"",
        ),
        "s.toml:15:8:",
        &["no/such.obj"],
    );
}

#[test]
fn empty_and_unlit_scenes_are_errors() {
    expect(
        &error("[camera]\nlook_from = [0, 0, 1]\nlook_at = [0, 0, 0]\n", Format::Toml),
        "s.toml:1:1:",
        &["no objects"],
    );
    let unlit = GOOD.replace("material = \"lamp\"", "material = \"white\"");
    expect(&error(&unlit, Format::Toml), "s.toml:5:", &["no lights"]);
    expect(&error("", Format::Json), "s.json:1:1:", &["EOF"]);
}

#[test]
fn json_build_errors_point_at_their_object() {
    let json = r#"{
  "camera": {"look_from": [0, 1, -5], "look_at": [0, 1, 0]},
  "materials": {"lamp": {"type": "emissive", "radiance": 4}},
  "objects": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "lamp"},
    {"type": "sphere", "center": [0, 0, 0], "radius": 1,
     "material": "glass"}
  ]
}"#;
    expect(&error(json, Format::Json), "s.json:7:18:", &["glass", "\"material\": \"glass\""]);
    let bad_type = json.replace("\"radius\": 1,\n", "\"radius\": true,\n");
    expect(&error(&bad_type, Format::Json), "s.json:6:", &["boolean"]);
}
