//! Instancing in the scene formats: native `[shape_groups.NAME]` + `[[instances]]` (TOML and
//! JSON) and Mitsuba's `<shape type="shapegroup">` + `<shape type="instance">`; located errors.

use pathtrace::math::{Ray, Vec3};
use pathtrace::scene::PrimRef;
use pathtrace::Scene;
use pathtrace_scene::native::{load_str, Format};

/// A lamp, and a group (a unit sphere and a quad below it) placed three times along x, the
/// last one with its material replaced (that `material` is on line 40).
const SCENE: &str = r#"[camera]
look_from = [0, 2, -8]
look_at = [0, 0, 0]

[materials.white]
type = "lambertian"
albedo = 0.5

[materials.red]
type = "lambertian"
albedo = [0.8, 0.1, 0.1]

[materials.lamp]
type = "emissive"
radiance = 4

[[objects]]
type = "quad"
q = [-5, 6, -5]
u = [10, 0, 0]
v = [0, 0, 10]
material = "lamp"

[shape_groups.ball]
objects = [
  { type = "sphere", center = [0, 0, 0], radius = 1, material = "white" },
  { type = "quad", q = [-1, -2, -1], u = [2, 0, 0], v = [0, 0, 2], material = "white" },
]

[[instances]]
group = "ball"
transform = [{ translate = [-3, 0, 0] }]

[[instances]]
group = "ball"
transform = [{ scale = 0.5 }, { translate = [0, 0, 0] }]

[[instances]]
group = "ball"
material = "red"
transform = [{ translate = [3, 0, 0] }]
"#;

/// The hit of a ray straight down from height 5 at `x`: (t, instance).
fn down(scene: &Scene, x: f32) -> Option<(f32, u32)> {
    let ray = Ray::new(Vec3::new(x, 5.0, 0.0), -Vec3::Y);
    let hit = scene.intersect(&ray, f32::INFINITY)?;
    match hit.prim {
        PrimRef::Instance { instance, .. } => Some((hit.hit.t, instance)),
        _ => None,
    }
}

fn check(scene: &Scene) {
    assert_eq!(scene.instance_count(), 3);
    // One copy of the group's two primitives is stored, plus the lamp.
    assert_eq!(scene.primitive_count(), 1);
    let (t, i) = down(scene, -3.0).unwrap();
    assert!((t - 4.0).abs() < 1e-4 && i == 0, "{t} {i}");
    let (t, i) = down(scene, 0.0).unwrap();
    assert!((t - 4.5).abs() < 1e-4 && i == 1, "{t} {i}");
    // Beside the half-size sphere, the quad below it (at y = -1).
    let ray = Ray::new(Vec3::new(0.4, 5.0, 0.45), -Vec3::Y);
    let t = scene.intersect(&ray, f32::INFINITY).unwrap().hit.t;
    assert!((t - 6.0).abs() < 1e-4, "{t}");
    // The red instance's sphere has the red material.
    let ray = Ray::new(Vec3::new(3.0, 5.0, 0.0), -Vec3::Y);
    let hit = scene.intersect(&ray, f32::INFINITY).unwrap();
    let it = scene.interaction(&ray, &hit);
    assert!(format!("{:?}", it.material).contains("0.8"), "{:?}", it.material);
    assert!(down(scene, 5.0).is_none());
}

#[test]
fn native_instances_load_in_toml_and_json() {
    let loaded = load_str(SCENE, Format::Toml, "s.toml".as_ref()).unwrap();
    check(&loaded.scene);
    let model: pathtrace_scene::native::SceneFile = toml::from_str(SCENE).unwrap();
    let json = serde_json::to_string_pretty(&model).unwrap();
    assert!(json.contains("\"shape_groups\"") && json.contains("\"instances\""));
    let loaded = load_str(&json, Format::Json, "s.json".as_ref()).unwrap();
    check(&loaded.scene);
}

fn error(text: &str) -> String {
    match load_str(text, Format::Toml, "s.toml".as_ref()) {
        Ok(_) => panic!("expected an error"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn instancing_errors_name_file_line_and_column() {
    let e =
        error(&SCENE.replacen("group = \"ball\"\ntransform = [{ scale", "group = \"bal\"\ntransform = [{ scale", 1));
    assert!(e.starts_with("s.toml:35:9:") && e.contains("unknown shape group `bal` (shape groups: ball)"), "{e}");
    let e = error(&SCENE.replacen("material = \"red\"", "material = \"lamp\"", 1));
    assert!(e.starts_with("s.toml:40:12:") && e.contains("instanced shapes cannot be lights"), "{e}");
    let e = error(&SCENE.replacen("radius = 1, material = \"white\"", "radius = 1, material = \"lamp\"", 1));
    assert!(e.starts_with("s.toml:26:") && e.contains("objects of a shape group cannot be lights"), "{e}");
    let e = error(&SCENE.replacen("material = \"red\"", "material = \"blue\"", 1));
    assert!(e.starts_with("s.toml:40:12:") && e.contains("unknown material `blue`"), "{e}");
    let e = error(&SCENE.replacen(
        "{ type = \"sphere\"",
        "{ type = \"plane\", point = [0, 0, 0], normal = [0, 1, 0], material = \"white\" },\n  { type = \"sphere\"",
        1,
    ));
    assert!(e.starts_with("s.toml:26:") && e.contains("plane"), "{e}");
    let e = error(&SCENE.replacen("group = \"ball\"\nmaterial", "grup = \"ball\"\nmaterial", 1));
    assert!(e.starts_with("s.toml:39:1:") && e.contains("unknown field `grup`"), "{e}");
}

const XML: &str = r#"<scene version="3.0.0">
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 2, -8" target="0, 0, 0" up="0, 1, 0"/></transform>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="90"/><scale value="5"/><translate y="6"/></transform>
        <emitter type="area"><rgb name="radiance" value="4"/></emitter>
    </shape>
    <shape type="shapegroup" id="ball">
        <shape type="sphere"><float name="radius" value="1"/></shape>
        <shape type="rectangle">
            <transform name="to_world"><rotate x="1" angle="90"/><translate y="-2"/></transform>
        </shape>
    </shape>
    <shape type="instance">
        <ref id="ball"/>
        <transform name="to_world"><translate x="-3"/></transform>
    </shape>
    <shape type="instance">
        <ref id="ball"/>
        <transform name="to_world"><scale value="0.5"/></transform>
    </shape>
</scene>
"#;

#[test]
fn mitsuba_shapegroups_and_instances_are_imported() {
    let (loaded, warnings) = pathtrace_scene::mitsuba::load_str(XML, "s.xml".as_ref(), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let scene = &loaded.scene;
    assert_eq!(scene.instance_count(), 2);
    let (t, i) = down(scene, -3.0).unwrap();
    assert!((t - 4.0).abs() < 1e-4 && i == 0, "{t} {i}");
    let (t, i) = down(scene, 0.0).unwrap();
    assert!((t - 4.5).abs() < 1e-4 && i == 1, "{t} {i}");
    // An emitter inside a group is an error at that shape.
    let bad = XML.replacen(
        "<shape type=\"sphere\"><float name=\"radius\" value=\"1\"/></shape>",
        "<shape type=\"sphere\"><emitter type=\"area\"/></shape>",
        1,
    );
    let e = pathtrace_scene::mitsuba::load_str(&bad, "s.xml".as_ref(), &[]).err().unwrap().to_string();
    assert!(e.starts_with("s.xml:10:") && e.contains("cannot be lights"), "{e}");
    // An instance must name a shape group.
    let bad = XML.replacen(
        "<ref id=\"ball\"/>\n        <transform name=\"to_world\"><translate",
        "<ref id=\"nope\"/>\n        <transform name=\"to_world\"><translate",
        1,
    );
    let e = pathtrace_scene::mitsuba::load_str(&bad, "s.xml".as_ref(), &[]).err().unwrap().to_string();
    assert!(e.starts_with("s.xml:16:") && e.contains("unknown ref id `nope`"), "{e}");
}
