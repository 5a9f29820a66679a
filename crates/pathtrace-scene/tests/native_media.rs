//! The native format's participating media: `[media.NAME]` tables (extinction and albedo or
//! absorption and scattering, `scale`, `phase`), objects' `interior`/`exterior`, the camera's
//! `medium` and the `null` material; what they build, round trips through TOML and JSON, located
//! errors; and the Mitsuba importer's `homogeneous`, `isotropic`, `hg`, `null` and `volpath`.

use pathtrace::math::Rgb;
use pathtrace::medium::{MediumId, PhaseFunction};
use pathtrace_scene::mitsuba;
use pathtrace_scene::native::model::MaterialKind;
use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
use std::path::{Path, PathBuf};

const SCENE: &str = r#"[camera]
look_from = [0, 0, -4]
look_at = [0, 0, 0]
medium = "haze"

[materials.boundary]
type = "null"

[materials.glass]
type = "dielectric"
ior = 1.5

[materials.light]
type = "emissive"
radiance = 5

[media.haze]
sigma_t = 0.05
albedo = 0.9

[media.jelly]
sigma_a = [0.1, 0.5, 0.9]
sigma_s = [2, 1, 0.5]
scale = 2
phase = { type = "hg", g = 0.4 }

[media.smoke]
sigma_t = [1, 2, 3]

[[objects]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "glass"
interior = "jelly"
exterior = "haze"

[[objects]]
type = "box"
min = [-3, -3, -3]
max = [3, 3, 3]
material = "boundary"
interior = "smoke"

[[objects]]
type = "quad"
q = [-1, 4, -1]
u = [2, 0, 0]
v = [0, 0, 2]
material = "light"
"#;

fn load(text: &str) -> Result<pathtrace_scene::LoadedScene, String> {
    load_str(text, Format::Toml, Path::new("s.toml")).map_err(|e| e.to_string())
}

fn close(a: Rgb, b: [f32; 3]) -> bool {
    a.to_array().iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6)
}

#[test]
fn media_tables_build_the_media_they_describe() {
    let scene = load(SCENE).unwrap().scene;
    assert!(scene.is_volumetric());
    // Media are numbered in name order: haze, jelly, smoke.
    let [haze, jelly, smoke] = [0, 1, 2].map(|i| scene.media()[i]);
    assert!(close(haze.sigma_t(), [0.05; 3]) && close(haze.sigma_s, [0.045; 3]));
    assert_eq!(haze.phase, PhaseFunction::Isotropic);
    // σa and σs, both scaled by 2.
    assert!(close(jelly.sigma_a, [0.2, 1.0, 1.8]) && close(jelly.sigma_s, [4.0, 2.0, 1.0]));
    assert_eq!(jelly.phase, PhaseFunction::HenyeyGreenstein { g: 0.4 });
    // Mitsuba's default albedo, 0.75.
    assert!(close(smoke.sigma_s, [0.75, 1.5, 2.25]));
    assert_eq!(scene.camera_medium(), 0);
    // The glass sphere separates jelly (inside) from haze (outside); the box bounds the smoke.
    let bounds: Vec<_> = (0..scene.materials().len() as u32).filter_map(|m| scene.boundary(m)).collect();
    assert!(bounds.iter().any(|b| (b.interior, b.exterior) == (1, 0)), "{bounds:?}");
    assert!(bounds.iter().any(|b| (b.interior, b.exterior) == (2, MediumId::NONE)), "{bounds:?}");
}

#[test]
fn scenes_without_media_are_not_volumetric() {
    let plain = "[camera]\nlook_from = [0, 0, -4]\nlook_at = [0, 0, 0]\n[materials.light]\ntype = \"emissive\"\n\
                 radiance = 1\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"light\"\n";
    assert!(!load(plain).unwrap().scene.is_volumetric());
}

#[test]
fn media_round_trip_through_toml_and_json() {
    let file = parse_str(SCENE, Format::Toml, Path::new("s.toml")).unwrap();
    assert_eq!(file.materials["boundary"].kind, MaterialKind::Null);
    for format in [Format::Toml, Format::Json] {
        let text = to_string(&file, format).unwrap();
        assert_eq!(parse_str(&text, format, Path::new("s")).unwrap(), file, "{text}");
    }
}

#[test]
fn media_mistakes_are_located() {
    // (text replaced, replacement, what the error must say, the line it must point at)
    let cases = [
        ("sigma_t = 0.05", "sigma_t = -0.05", "`sigma_t` must be finite and ≥ 0", 18),
        ("albedo = 0.9", "albedo = 1.5", "`albedo` must be in [0, 1]", 19),
        ("scale = 2", "scale = -2", "`scale` must be a finite number ≥ 0", 24),
        ("sigma_t = [1, 2, 3]", "sigma_t = [1, 2, 3]\nsigma_s = 1", "not both", 29),
        ("g = 0.4", "g = 1.2", "strictly between −1 and 1", 25),
        ("interior = \"jelly\"", "interior = \"jello\"", "unknown medium `jello` (media: haze, jelly, smoke)", 35),
        ("medium = \"haze\"", "medium = \"fog\"", "unknown medium `fog`", 4),
        ("type = \"hg\"", "type = \"rayleigh\"", "unknown variant `rayleigh`", 25),
        ("sigma_t = 0.05", "sigma_t = 0.05\ndensity = 2", "unknown field `density`", 19),
        (
            "type = \"null\"",
            "type = \"null\"\nalbedo = 1",
            "not a parameter of a null material (it takes no parameters)",
            6,
        ),
    ];
    for (from, to, says, line) in cases {
        let text = SCENE.replace(from, to);
        assert_ne!(text, SCENE, "{from}");
        let err = load(&text).expect_err(to);
        assert!(err.contains(says), "{to}: {err}");
        assert!(err.contains(&format!("s.toml:{line}:")), "{to}: expected line {line}: {err}");
    }
}

#[test]
fn shape_groups_cannot_bound_media() {
    let text = format!(
        "{SCENE}\n[shape_groups.g]\n[[shape_groups.g.objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\n\
         material = \"boundary\"\ninterior = \"smoke\"\n[[instances]]\ngroup = \"g\"\n"
    );
    let err = load(&text).unwrap_err();
    assert!(err.contains("cannot bound media"), "{err}");
}

fn data(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(rel)
}

#[test]
fn mitsuba_media_convert_to_the_native_tables() {
    let (file, warnings) = mitsuba::convert_file(&data("media/fog_shafts.xml"), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    assert_eq!(file.camera.medium.as_deref(), Some("fog"));
    assert_eq!(file.render.max_depth, Some(12));
    let fog = &file.media["fog"];
    assert_eq!(fog.sigma_t.unwrap().rgb(), Rgb::new(0.25, 0.3, 0.4));
    assert!(matches!(fog.phase, Some(pathtrace_scene::native::model::PhaseDef::Hg { g: Some(g) }) if g.get() == 0.3));
    let bounded: Vec<_> = file.objects.iter().filter(|o| o.interior.is_some()).collect();
    assert_eq!(bounded.len(), 1);
    assert_eq!(file.materials[&bounded[0].material].kind, MaterialKind::Null);
    // The converted file renders the same scene: write it and read it back.
    let text = to_string(&file, Format::Toml).unwrap();
    assert!(text.contains("[media.fog]") && text.contains("interior = \"fog\""), "{text}");
    assert_eq!(parse_str(&text, Format::Toml, Path::new("fog.toml")).unwrap(), file);

    // A nested <medium name="interior"> with a density scale.
    let (loaded, warnings) = mitsuba::load_mitsuba(&data("media/jelly_sphere.xml"), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:#?}");
    let jelly = loaded.scene.media()[0];
    assert!(close(jelly.sigma_t(), [2.0, 3.0, 4.0]), "{jelly:?}");
    assert!(close(jelly.sigma_s, [1.9, 1.5, 1.2]), "{jelly:?}");
    assert_eq!(loaded.scene.camera_medium(), MediumId::NONE);
}

#[test]
fn mitsuba_media_mistakes_are_warned_or_located() {
    let scene = |medium: &str, shape_extra: &str| {
        format!(
            r#"<scene version="3.0.0">
    <sensor type="perspective"><transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform></sensor>
    {medium}
    <shape type="sphere"><bsdf type="null"/>{shape_extra}<emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
</scene>"#
        )
    };
    let load = |text: &str| mitsuba::load_str(text, Path::new("m.xml"), &[]).map_err(|e| e.to_string());
    // Heterogeneous media are not supported: a warning, and the shape bounds nothing.
    let grid = scene(r#"<medium type="heterogeneous" id="m"/>"#, r#"<ref name="interior" id="m"/>"#);
    let (loaded, warnings) = load(&grid).unwrap();
    assert!(warnings.iter().any(|w| w.contains("heterogeneous")), "{warnings:?}");
    assert!(loaded.scene.media().is_empty());
    // A negative extinction is an error at the medium.
    let negative = scene(
        r#"<medium type="homogeneous" id="m"><float name="sigma_t" value="-1"/></medium>"#,
        r#"<ref name="interior" id="m"/>"#,
    );
    let err = load(&negative).unwrap_err();
    assert!(err.contains("m.xml:3:") && err.contains("sigma_t"), "{err}");
    // `interior` must name a medium.
    let wrong = scene(r#"<bsdf type="diffuse" id="m"/>"#, r#"<ref name="interior" id="m"/>"#);
    let err = load(&wrong).unwrap_err();
    assert!(err.contains("must be a <medium>"), "{err}");
    let unknown = scene("", r#"<ref name="interior" id="nowhere"/>"#);
    assert!(load(&unknown).unwrap_err().contains("unknown ref id `nowhere`"));
}

#[test]
fn the_documented_media_example_builds() {
    let doc =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/scene-format.md")).unwrap();
    let section = doc.split("## `[media.NAME]`").nth(1).expect("the media section");
    let example = section.split("```toml\n").nth(1).and_then(|s| s.split("```").next()).expect("its example");
    let scene = load(example).unwrap_or_else(|e| panic!("{e}\n{example}")).scene;
    assert_eq!(scene.media().len(), 2);
    assert_eq!(scene.camera_medium(), 0);
    let bounds: Vec<_> = (0..scene.materials().len() as u32).filter_map(|m| scene.boundary(m)).collect();
    assert!(bounds.iter().any(|b| (b.interior, b.exterior) == (1, 0)), "{bounds:?}");
}
