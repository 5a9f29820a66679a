//! Mitsuba 3 XML import: parameters, references, transforms, fov axes, errors with locations,
//! the Cornell box rendered from XML against the built-in one, and the public test scenes.

use pathtrace::film::{Film, RegionEstimate};
use pathtrace::light::{Light, LightSelection};
use pathtrace::math::Vec3;
use pathtrace::sampling::SamplerKind;
use pathtrace::{render, RenderSettings, Scene};
use pathtrace_scene::mitsuba::{convert_str, load_mitsuba, load_str};
use pathtrace_scene::native::model::{
    Colour, FilterName, LightDef, MaterialKind, MetalDef, SamplerName, ShapeDef, TransformStep, Triple,
};
use pathtrace_scene::native::{Format, SceneFile};
use std::path::{Path, PathBuf};
use std::sync::Arc;

const SENSOR: &str = r#"<sensor type="perspective">
    <float name="fov" value="40"/>
    <string name="fov_axis" value="y"/>
    <transform name="to_world"><lookat origin="0, 0, -5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="32"/></film>
</sensor>"#;

fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{SENSOR}\n{body}\n</scene>")
}

fn conv(xml: &str, defines: &[(&str, &str)]) -> (SceneFile, Vec<String>) {
    convert_str(xml, Path::new("t.xml"), defines).unwrap()
}

fn err(xml: &str) -> String {
    convert_str(xml, Path::new("t.xml"), &[]).unwrap_err().to_string()
}

const LIGHT: &str =
    r#"<shape type="sphere" id="lamp"><emitter type="area"><rgb name="radiance" value="1, 2, 3"/></emitter></shape>"#;

#[test]
fn defaults_and_overrides_substitute_into_attributes() {
    let xml = format!(
        r#"<scene version="3.0.0"><default name="spp" value="16"/><default name="d" value="5"/>
        {}
        <integrator type="path"><integer name="max_depth" value="$d"/></integrator>{LIGHT}</scene>"#,
        SENSOR.replace(
            "<film",
            "<sampler type=\"independent\"><integer name=\"sample_count\" value=\"$spp\"/></sampler><film"
        )
    );
    let (f, w) = conv(&xml, &[]);
    assert_eq!((f.render.spp, f.render.max_depth), (Some(16), Some(5)));
    assert!(w.is_empty(), "{w:?}");
    let (f, w) = conv(&xml, &[("spp", "3"), ("nothing", "1")]);
    assert_eq!(f.render.spp, Some(3));
    assert!(w.iter().any(|w| w.contains("nothing")), "{w:?}");
}

/// Two `<default>`s of one name: the first in document order wins (Mitsuba 3 keeps a parameter
/// it already has), here one in the scene file before the include that sets it again; a define
/// still beats both.
#[test]
fn the_first_default_of_a_name_wins() {
    let dir = std::env::temp_dir().join(format!("pathtrace-mitsuba-defaults-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("inc")).unwrap();
    let main = dir.join("main.xml");
    std::fs::write(
        &main,
        format!(
            r#"<scene version="3.0.0"><default name="d" value="64"/><include filename="inc/part.xml"/>{SENSOR}{LIGHT}</scene>"#
        ),
    )
    .unwrap();
    std::fs::write(
        dir.join("inc/part.xml"),
        r#"<scene version="3.0.0"><default name="d" value="-1"/>
        <integrator type="path"><integer name="max_depth" value="$d"/></integrator></scene>"#,
    )
    .unwrap();
    let text = std::fs::read_to_string(&main).unwrap();
    let (f, w) = convert_str(&text, &main, &[]).unwrap();
    assert!(w.is_empty(), "{w:?}");
    assert_eq!(f.render.max_depth, Some(64));
    let (f, _) = convert_str(&text, &main, &[("d", "3")]).unwrap();
    assert_eq!(f.render.max_depth, Some(3));
    std::fs::remove_dir_all(&dir).ok();
}

/// A sensor's sampler, film and reconstruction filter may be top-level elements it names with
/// `<ref id>` (mitsuba-data's sampler scenes do this), read as if written in place.
#[test]
fn a_sensor_reads_its_sampler_film_and_filter_through_refs() {
    let xml = format!(
        r#"<scene version="3.0.0">
        <sampler type="stratified" id="s"><integer name="sample_count" value="25"/></sampler>
        <rfilter type="box" id="r"/>
        <film type="hdrfilm" id="f"><integer name="width" value="40"/><integer name="height" value="30"/><ref id="r"/></film>
        <sensor type="perspective"><float name="fov" value="40"/><ref id="s"/><ref id="f"/></sensor>{LIGHT}</scene>"#
    );
    let (f, w) = conv(&xml, &[]);
    assert!(w.is_empty(), "{w:?}");
    assert_eq!((f.render.spp, f.render.width, f.render.height), (Some(25), Some(40), Some(30)));
    assert_eq!(f.render.sampler, Some(SamplerName(SamplerKind::Stratified)));
    assert_eq!(f.render.filter.map(|f| f.kind), Some(FilterName::Box));
    // A top-level sampler nobody names is still reported, as before.
    let (_, w) = conv(&scene(&format!(r#"<sampler type="independent"/>{LIGHT}"#)), &[]);
    assert!(w.iter().any(|w| w.contains("<sampler> is not supported")), "{w:?}");
}

/// Mitsuba 3's samplers map to ours of the same kind: `multijitter` to our jittered grid
/// (stratified), `ldsampler` to our padded Sobol' (0, 2)-sequence; the others are named in a
/// warning with the sampler used instead (not the independent one, which they all beat).
#[test]
fn mitsuba_samplers_map_to_ours_of_the_same_kind() {
    for (kind, ours, warned) in [
        ("independent", None, false),
        ("stratified", Some(SamplerKind::Stratified), false),
        ("multijitter", Some(SamplerKind::Stratified), false),
        ("ldsampler", Some(SamplerKind::Sobol), false),
        ("sobol", Some(SamplerKind::Sobol), false),
        ("halton", Some(SamplerKind::Sobol), true),
        ("orthogonal", Some(SamplerKind::Stratified), true),
    ] {
        let xml = format!(
            r#"<scene version="3.0.0"><sensor type="perspective"><float name="fov" value="40"/>
            <sampler type="{kind}"><integer name="sample_count" value="16"/></sampler></sensor>{LIGHT}</scene>"#
        );
        let (f, w) = conv(&xml, &[]);
        assert_eq!(f.render.sampler.map(|s| s.0), ours, "{kind}");
        assert_eq!(f.render.spp, Some(16), "{kind}");
        assert_eq!(
            w.iter().any(|w| w.contains(&format!("sampler `{kind}` is not supported"))),
            warned,
            "{kind}: {w:?}"
        );
    }
}

/// A path tracer's `rr_depth` is where Russian roulette starts (mitsuba-data's scenes pass it
/// through a `<default>`); Mitsuba requires it to be positive, and its `volpath` tests it one
/// vertex later than `path` does.
#[test]
fn the_path_tracers_rr_depth_is_read() {
    let integrator = |body: &str| scene(&format!(r#"<integrator type="path">{body}</integrator>{LIGHT}"#));
    let (f, w) = conv(&integrator(r#"<integer name="rr_depth" value="12"/>"#), &[]);
    assert!(w.is_empty(), "{w:?}");
    assert_eq!(f.render.rr_depth, Some(12));
    let (f, _) = conv(&integrator(""), &[]);
    assert_eq!(f.render.rr_depth, None, "unset: the engine's default (5, Mitsuba's too)");
    // `volpath` and `volpathmis` roulette one vertex later than `path` for the same value.
    for ty in ["volpath", "volpathmis"] {
        let xml = |body: &str| scene(&format!(r#"<integrator type="{ty}">{body}</integrator>{LIGHT}"#));
        assert_eq!(conv(&xml(r#"<integer name="rr_depth" value="12"/>"#), &[]).0.render.rr_depth, Some(13), "{ty}");
        assert_eq!(conv(&xml(""), &[]).0.render.rr_depth, Some(6), "{ty}");
    }
    let text = integrator(r#"<integer name="rr_depth" value="0"/>"#);
    let err = convert_str(&text, Path::new("rr.xml"), &[]).unwrap_err().to_string();
    assert!(err.contains("rr_depth") && err.contains("from 1"), "{err}");
}

#[test]
fn refs_share_a_material_and_twosided_unwraps() {
    let xml = scene(&format!(
        r#"<bsdf type="twosided" id="red"><bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.1, 0.1"/></bsdf></bsdf>
        <shape type="rectangle"><ref id="red"/></shape>
        <shape type="cube"><ref id="red"/></shape>
        <shape type="sphere"/>{LIGHT}"#
    ));
    let (f, w) = conv(&xml, &[]);
    assert!(w.is_empty(), "{w:?}");
    assert_eq!(f.objects[0].material, "red");
    assert_eq!(f.objects[1].material, "red");
    let red = &f.materials["red"];
    assert!(matches!(red.kind, MaterialKind::Lambertian { albedo: Colour::Constant(Triple::Each(_)) }));
    // No BSDF: Mitsuba's default diffuse 0.5, one-sided as every Mitsuba `diffuse` outside
    // `twosided`.
    let default = &f.materials[&f.objects[2].material];
    assert_eq!(default.kind, MaterialKind::OneSided(Box::new(MaterialKind::Lambertian { albedo: Colour::grey(0.5) })));
    let lamp = &f.materials[&f.objects[3].material];
    assert!(lamp.emission.is_some());
    assert!(matches!(f.objects[0].shape, ShapeDef::Quad { .. }));
    assert!(matches!(f.objects[1].shape, ShapeDef::Box { .. }));
}

#[test]
fn transforms_keep_document_order() {
    let xml = scene(&format!(
        r#"<shape type="sphere"><transform name="to_world">
            <scale value="2"/><rotate y="1" angle="90"/><translate x="1" y="2" z="3"/>
            <rotate value="1, 1, 0" angle="30"/><matrix value="1 0 0 1  0 1 0 0  0 0 1 0  0 0 0 1"/>
        </transform></shape>{LIGHT}"#
    ));
    let (f, _) = conv(&xml, &[]);
    let t = &f.objects[0].transform;
    assert!(matches!(t[0], TransformStep::Scale(Triple::Splat(_))));
    assert!(matches!(t[1], TransformStep::RotateY(_)));
    assert!(matches!(t[2], TransformStep::Translate(_)));
    assert!(matches!(t[3], TransformStep::Matrix(_)));
    assert!(matches!(t[4], TransformStep::Matrix(_)));
}

#[test]
fn fov_axis_becomes_a_vertical_fov() {
    // 64×32 film: aspect 2.
    let vfov = |axis: &str| {
        let xml = scene(LIGHT).replace("value=\"y\"", &format!("value=\"{axis}\""));
        conv(&xml, &[]).0.camera.vfov.unwrap().get()
    };
    let from_x = 2.0 * ((20f64).to_radians().tan() / 2.0).atan().to_degrees();
    let diag = 2.0 * ((20f64).to_radians().tan() / 5f64.sqrt()).atan().to_degrees();
    assert!((vfov("y") - 40.0).abs() < 1e-6);
    assert!((vfov("smaller") - 40.0).abs() < 1e-6);
    assert!((vfov("x") - from_x).abs() < 1e-6);
    assert!((vfov("larger") - from_x).abs() < 1e-6);
    assert!((vfov("diagonal") - diag).abs() < 1e-6);
}

#[test]
fn unsupported_plugins_warn_and_fall_back() {
    let xml = scene(&format!(
        r#"<emitter type="projector"/><shape type="cylinder"/>
        <emitter type="spot"><texture type="bitmap" name="texture"/></emitter>
        <shape type="sphere"><bsdf type="principled"/></shape>{LIGHT}"#
    ));
    let (f, w) = conv(&xml, &[]);
    assert!(w.iter().any(|w| w.contains("projector")), "{w:?}");
    assert!(w.iter().any(|w| w.contains("spot light's projected `texture`")), "{w:?}");
    assert!(w.iter().any(|w| w.contains("cylinder")), "{w:?}");
    assert!(w.iter().any(|w| w.contains("principled") && w.starts_with("t.xml:")), "{w:?}");
    assert_eq!(f.objects.len(), 2);
}

#[test]
fn disk_thindielectric_constant_point_and_filters_map_without_warnings() {
    let xml = scene(&format!(
        r#"<emitter type="constant"><rgb name="radiance" value="0.5"/></emitter>
        <emitter type="point"><point name="position" value="0, 3, 0"/><rgb name="intensity" value="10"/></emitter>
        <shape type="disk"><transform name="to_world"><scale value="2"/></transform>
            <bsdf type="thindielectric"><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/></bsdf></shape>
        {LIGHT}"#
    ));
    let (f, w) = conv(&xml, &[]);
    assert!(w.is_empty(), "{w:?}");
    assert!(matches!(f.objects[0].shape, ShapeDef::Disk { .. }));
    let glass = &f.materials[&f.objects[0].material];
    assert!(matches!(glass.kind, MaterialKind::ThinDielectric { ior, .. } if ior.get() == 1.5));
    assert!(matches!(f.lights[0], LightDef::Constant { .. }) && matches!(f.lights[1], LightDef::Point { .. }));
    // No <rfilter>: Mitsuba's default, a gaussian of stddev 0.5.
    assert_eq!(f.render.filter.map(|r| r.kind), Some(FilterName::Gaussian));
    for (rfilter, kind) in [
        (r#"<rfilter type="box"/>"#, FilterName::Box),
        (r#"<rfilter type="tent"><float name="radius" value="1.5"/></rfilter>"#, FilterName::Tent),
        (r#"<rfilter type="gaussian"><float name="stddev" value="0.3"/></rfilter>"#, FilterName::Gaussian),
    ] {
        let with = xml.replace(
            r#"<integer name="height" value="32"/>"#,
            &format!(r#"<integer name="height" value="32"/>{rfilter}"#),
        );
        let (f, w) = conv(&with, &[]);
        assert!(w.is_empty(), "{w:?}");
        assert_eq!(f.render.filter.map(|r| r.kind), Some(kind));
    }
    let (loaded, _) = load_str(&xml, Path::new("t.xml"), &[]).unwrap();
    assert_eq!(loaded.scene.lights.lights().iter().filter(|l| matches!(l, Light::Point(_))).count(), 1);
    assert!(loaded.scene.lights.environment().is_some());
}

#[test]
fn emitters_are_picked_uniformly_like_mitsuba() {
    // Mitsuba picks emitters in proportion to `sampling_weight` (1 unless given): the import
    // selects lights uniformly, a sphere light and a point light equally often however bright.
    let two = r#"<emitter type="point"><point name="position" value="0, 3, 0"/><rgb name="intensity" value="1000"/></emitter>
        <shape type="sphere"><float name="radius" value="0.1"/><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>"#;
    let (f, w) = conv(&scene(two), &[]);
    assert!(w.is_empty(), "{w:?}");
    assert_eq!(f.render.light_selection.map(|s| s.0), Some(LightSelection::Uniform));
    let (loaded, _) = load_str(&scene(two), Path::new("t.xml"), &[]).unwrap();
    let lights = &loaded.scene.lights;
    assert_eq!(lights.selection(), LightSelection::Uniform);
    assert!((0..lights.count()).all(|i| (lights.index_pmf(i) - 0.5).abs() < 1e-6));
    // A weight of 1 is the default; any other is warned about, at the property.
    let weighted =
        two.replace("value=\"1000\"/>", "value=\"1000\"/><float name=\"sampling_weight\" value=\"WEIGHT\"/>");
    let (_, w) = conv(&scene(&weighted.replace("WEIGHT", "1")), &[]);
    assert!(w.is_empty(), "{w:?}");
    let (_, w) = conv(&scene(&weighted.replace("WEIGHT", "4")), &[]);
    assert!(w.len() == 1 && w[0].contains("sampling_weight") && w[0].starts_with("t.xml:"), "{w:?}");
}

#[test]
fn spectra_are_converted_like_mitsuba() {
    // Mitsuba 3.9.1 scalar_rgb loads these as reflectance (0.726577, 0.424956, 0.17397) and
    // radiance (0.849361, 0.405349, 0.15115) (benches/peers/cie_tables.py --check shows the
    // integrals; the loaded values were read with mi.traverse).
    let spec = r#"<spectrum name="NAME" value="400:0.1, 500:0.3, 600:0.6, 700:0.9"/>"#;
    let xml = scene(&format!(
        r#"<shape type="sphere"><bsdf type="diffuse">{}</bsdf><emitter type="area">{}</emitter></shape>"#,
        spec.replace("NAME", "reflectance"),
        spec.replace("NAME", "radiance")
    ));
    let (f, w) = conv(&xml, &[]);
    assert!(w.is_empty(), "{w:?}");
    let m = f.materials.values().next().unwrap();
    let MaterialKind::Lambertian { albedo: Colour::Constant(albedo) } = m.kind.sides().0 else { panic!("{m:?}") };
    let close = |t: Triple, e: [f32; 3]| {
        let v = t.vec3();
        (v - Vec3::from(e)).abs().max_element() < 1e-4
    };
    assert!(close(*albedo, [0.726577, 0.424956, 0.17397]), "{albedo:?}");
    assert!(close(m.emission.as_ref().unwrap().radiance, [0.849361, 0.405349, 0.15115]), "{m:?}");
}

#[test]
fn errors_found_while_building_point_at_the_xml_element() {
    let tmp = std::env::temp_dir().join(format!("pathtrace-xml-build-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    // A mesh file that exists but is broken: reported at its `filename` property.
    std::fs::write(tmp.join("bad.obj"), "v 0 0 0\nv 1 0 0\nf 1 2 9\n").unwrap();
    let xml = scene(&format!("{LIGHT}\n<shape type=\"obj\">\n  <string name=\"filename\" value=\"bad.obj\"/></shape>"));
    let e = load_str(&xml, &tmp.join("s.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("s.xml:10:") && e.contains("bad.obj"), "{e}");
    // A degenerate transform (zero scale) on a sphere: at its <scale> step or its <shape>.
    let xml = scene(&format!(
        "{LIGHT}\n<shape type=\"disk\"><transform name=\"to_world\">\n<scale value=\"0\"/></transform></shape>"
    ));
    let e = load_str(&xml, &tmp.join("s.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("s.xml:9:") || e.contains("s.xml:10:"), "{e}");
    assert!(!e.contains(":1:1:"), "{e}");
    // A negative point intensity: at its <emitter>.
    let xml = scene(&format!("{LIGHT}\n<emitter type=\"point\"><rgb name=\"intensity\" value=\"-1\"/></emitter>"));
    let e = load_str(&xml, &tmp.join("s.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("s.xml:9:") && e.contains("point light"), "{e}");
    // A bad filter parameter: at its <rfilter>.
    let xml = scene(LIGHT).replace(
        r#"<integer name="height" value="32"/>"#,
        "<integer name=\"height\" value=\"32\"/>\n<rfilter type=\"gaussian\"><float name=\"stddev\" value=\"1e9\"/></rfilter>",
    );
    let e = load_str(&xml, &tmp.join("s.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("s.xml:7:") && e.contains("stddev"), "{e}");
    let _ = std::fs::remove_dir_all(&tmp);
}

#[test]
fn errors_carry_file_line_and_column() {
    assert!(err("<scene><shape").starts_with("t.xml:1:"), "{}", err("<scene><shape"));
    let bad_number = scene("<shape type=\"sphere\">\n<float name=\"radius\" value=\"abc\"/></shape>");
    let e = err(&bad_number);
    assert!(e.contains("`abc` is not a number"), "{e}");
    assert!(e.starts_with("t.xml:9:29:"), "{e}");
    let e = err(&scene("<shape type=\"sphere\">\n  <ref id=\"nope\"/></shape>"));
    assert!(e.starts_with("t.xml:9:") && e.contains("unknown ref id `nope`"), "{e}");
    let e = err(&scene("<shape type=\"obj\"><string name=\"filename\" value=\"missing.obj\"/></shape>"));
    assert!(e.contains("not found") && e.starts_with("t.xml:8:"), "{e}");
    let e = load_mitsuba(Path::new("/nonexistent/x.xml"), &[]).unwrap_err().to_string();
    assert!(e.starts_with("/nonexistent/x.xml:1:1: cannot read"), "{e}");
    assert!(err("<scene version=\"3\"></scene>").contains("no <sensor>"));
    let e = err(&scene("<shape type=\"sphere\"><bsdf type=\"dielectric\"><string name=\"int_ior\" value=\"unobtainium\"/></bsdf></shape>"));
    assert!(e.contains("unknown IOR"), "{e}");
}

#[test]
fn arbitrary_input_never_panics() {
    let base = scene(LIGHT);
    for cut in (0..base.len()).step_by(7) {
        if base.is_char_boundary(cut) {
            let _ = convert_str(&base[..cut], Path::new("t.xml"), &[]);
        }
    }
    // Single-character mutations of a full scene (the Cornell box in XML).
    let full = cornell_xml();
    for (i, _) in full.char_indices().step_by(5) {
        for c in ["<", "\"", "$", "0", "-", ""] {
            let end = full[i..].chars().next().map_or(i, |ch| i + ch.len_utf8());
            let mutated = format!("{}{c}{}", &full[..i], &full[end..]);
            let _ = convert_str(&mutated, Path::new("t.xml"), &[]);
        }
    }
    for junk in ["", "<", "<scene/>", "<scene><default/></scene>", "<scene><sensor/></scene>"] {
        let _ = convert_str(junk, Path::new("t.xml"), &[("a", "$a")]);
    }
}

#[test]
fn converted_scenes_serialise_as_native_files() {
    let (f, _) = conv(&scene(LIGHT), &[]);
    for format in [Format::Toml, Format::Json] {
        let text = pathtrace_scene::native::to_string(&f, format).unwrap();
        let back = pathtrace_scene::native::parse_str(&text, format, Path::new("x")).unwrap();
        assert_eq!(back, f);
    }
}

// ---------------------------------------------------------------- the Cornell box in XML

/// pathtrace's built-in Cornell box written as Mitsuba XML (as benches/peers/cornell_mitsuba.py
/// builds it): walls as rectangles, boxes as cubes.
fn cornell_xml() -> String {
    type Quad = ([f32; 3], [f32; 3], [f32; 3], &'static str);
    let quads: [Quad; 6] = [
        ([555.0, 0.0, 0.0], [0.0, 555.0, 0.0], [0.0, 0.0, 555.0], "green"),
        ([0.0, 0.0, 0.0], [0.0, 555.0, 0.0], [0.0, 0.0, 555.0], "red"),
        ([0.0, 0.0, 0.0], [555.0, 0.0, 0.0], [0.0, 0.0, 555.0], "white"),
        ([555.0, 555.0, 555.0], [-555.0, 0.0, 0.0], [0.0, 0.0, -555.0], "white"),
        ([0.0, 0.0, 555.0], [555.0, 0.0, 0.0], [0.0, 555.0, 0.0], "white"),
        ([343.0, 554.0, 332.0], [-130.0, 0.0, 0.0], [0.0, 0.0, -105.0], "light"),
    ];
    let mut s = String::from(
        r#"<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="8"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="278, 278, -800" target="278, 278, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="64"/><rfilter type="box"/></film>
  </sensor>
  <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.65, 0.05, 0.05"/></bsdf>
  <bsdf type="twosided" id="white"><bsdf type="diffuse"><rgb name="reflectance" value="0.73, 0.73, 0.73"/></bsdf></bsdf>
  <!-- The green wall faces out of the box: twosided, or Mitsuba would show its black back. -->
  <bsdf type="twosided" id="green"><bsdf type="diffuse"><rgb name="reflectance" value="0.12, 0.45, 0.15"/></bsdf></bsdf>
  <bsdf type="diffuse" id="black"><rgb name="reflectance" value="0, 0, 0"/></bsdf>
"#,
    );
    for (q, u, v, m) in quads {
        let (q, u, v) = (Vec3::from(q), Vec3::from(u), Vec3::from(v));
        let (a, b, n, c) = (u / 2.0, v / 2.0, u.cross(v).normalize(), q + (u + v) / 2.0);
        let rows = format!(
            "{} {} {} {}  {} {} {} {}  {} {} {} {}  0 0 0 1",
            a.x, b.x, n.x, c.x, a.y, b.y, n.y, c.y, a.z, b.z, n.z, c.z
        );
        let inner = if m == "light" {
            r#"<ref id="black"/><emitter type="area"><rgb name="radiance" value="15, 15, 15"/></emitter>"#.to_string()
        } else {
            format!(r#"<ref id="{m}"/>"#)
        };
        s += &format!(
            "  <shape type=\"rectangle\"><transform name=\"to_world\"><matrix value=\"{rows}\"/></transform>{inner}</shape>\n"
        );
    }
    for (size, angle, offset) in
        [([165.0, 330.0, 165.0], 15.0, [265.0, 0.0, 295.0]), ([165.0; 3], -18.0, [130.0, 0.0, 65.0])]
    {
        let [x, y, z]: [f32; 3] = size;
        s += &format!(
            "  <shape type=\"cube\"><transform name=\"to_world\"><scale x=\"{}\" y=\"{}\" z=\"{}\"/><translate value=\"{} {} {}\"/>\
             <rotate y=\"1\" angle=\"{angle}\"/><translate x=\"{}\" y=\"{}\" z=\"{}\"/></transform><ref id=\"white\"/></shape>\n",
            x / 2.0, y / 2.0, z / 2.0, x / 2.0, y / 2.0, z / 2.0, offset[0], offset[1], offset[2]
        );
    }
    s + "</scene>\n"
}

fn film(scene: Scene, seed: u64) -> Film {
    let mut s = RenderSettings { width: 64, height: 64, spp: 64, seed, ..Default::default() };
    s.path.max_depth = 8;
    render(Arc::new(scene), s).unwrap().film
}

#[test]
fn the_cornell_box_in_xml_renders_like_the_builtin_one() {
    let (loaded, warnings) = load_str(&cornell_xml(), Path::new("cornell.xml"), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!((loaded.defaults.width, loaded.defaults.height, loaded.defaults.max_depth), (64, 64, 8));
    let builtin = pathtrace_scene::builtin::load("cornell-box").unwrap().unwrap();
    let (a, b) = (film(loaded.scene, 1), film(builtin.scene, 2));
    // Whole image, left (green) wall, right (red) wall, floor, back wall, light.
    let regions =
        [(0, 0, 64, 64), (4, 19, 10, 38), (54, 19, 60, 38), (23, 56, 30, 62), (22, 16, 42, 25), (28, 9, 36, 10)];
    for (x0, y0, x1, y1) in regions {
        let (ra, rb): (RegionEstimate, RegionEstimate) =
            (a.region_estimate(x0, y0, x1, y1), b.region_estimate(x0, y0, x1, y1));
        let z = ra.max_z_score(&rb);
        assert!(z < 4.5, "region {:?}: xml {:?} vs builtin {:?}, z = {z:.2}", (x0, y0, x1, y1), ra.mean, rb.mean);
    }
    // The orientation: the green wall is on the left.
    let left = a.region_estimate(4, 19, 10, 38).mean;
    assert!(left[1] > left[0], "left wall should be green: {left:?}");
}

// ---------------------------------------------------------------- public scenes

fn shared_scenes() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    dir.is_dir().then_some(dir)
}

#[test]
fn public_scenes_load() {
    let Some(dir) = shared_scenes() else {
        eprintln!("skipped: ../shared/scenes is absent");
        return;
    };
    // (scene, uses only supported plugins); the clean ones are also rendered against Mitsuba in
    // mitsuba_means.rs.
    let scenes = [
        ("cbox/cbox.xml", true),
        ("cornell-box-bitterli/scene_v3.xml", true),
        ("teapot-simple/simple.xml", true),
        ("cbox-classic/docs/scenes/integrator_depth_inf.xml", true),
        ("veach-mis/docs/scenes/integrator_direct_both.xml", true),
        ("veach-mis-bitterli/scene_v3.xml", false),
        ("matpreview/docs/scenes/bsdf_diffuse_plain.xml", true),
        ("matpreview/docs/scenes/bsdf_plastic_shiny.xml", true),
        ("matpreview/docs/scenes/bsdf_roughconductor_copper.xml", true),
        ("matpreview/docs/scenes/bsdf_dielectric_glass.xml", true),
        ("bunny/docs/scenes/shape_ply_bunny.xml", true),
    ];
    for (s, supported) in scenes {
        let path = dir.join(s);
        match load_mitsuba(&path, &[]) {
            Ok((loaded, w)) if w.is_empty() => {
                assert!(supported, "{s}: loads silently although it uses unsupported plugins");
                eprintln!("{s}: loads without warnings ({} primitives)", loaded.scene.primitive_count())
            }
            Ok((_, w)) => {
                assert!(!supported, "{s}: warnings:\n  {}", w.join("\n  "));
                // Every warning names where and what was substituted.
                assert!(w.iter().all(|w| w.contains(".xml:")), "{w:?}");
                // Every BSDF these scenes use is supported.
                assert!(!w.iter().any(|w| w.contains("bsdf `") || w.contains("conductor:")), "{s}: {w:?}");
                eprintln!("{s}: loads with {} warning(s):\n  {}", w.len(), w.join("\n  "))
            }
            Err(e) => panic!("{s}: {e}"),
        }
    }
}

#[test]
fn reference_cycles_are_errors() {
    let e =
        err(&scene(r#"<bsdf type="twosided" id="a"><ref id="a"/></bsdf><shape type="sphere"><ref id="a"/></shape>"#));
    assert!(e.contains("nested too deeply"), "{e}");
}

#[test]
fn deep_nesting_is_an_error() {
    let deep = format!("<scene>{}{}</scene>", "<a>".repeat(10_000), "</a>".repeat(10_000));
    let e = err(&deep);
    assert!(e.starts_with("t.xml:1:"), "{e}");
}

#[test]
fn includes_splice_their_elements_and_locate_their_errors() {
    let dir = std::env::temp_dir().join(format!("pathtrace-mitsuba-include-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("inc")).unwrap();
    std::fs::write(
        dir.join("inc/part.xml"),
        format!("<scene version=\"3.0.0\">\n{LIGHT}\n<shape type=\"cylinder\"/></scene>"),
    )
    .unwrap();
    let main = dir.join("main.xml");
    std::fs::write(&main, scene(r#"<include filename="inc/part.xml"/>"#)).unwrap();
    let (loaded, w) = load_mitsuba(&main, &[]).unwrap();
    assert!(loaded.scene.primitive_count() >= 1);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("part.xml:3:1: shape `cylinder`"), "{w:?}");
    std::fs::write(
        dir.join("inc/part.xml"),
        "<scene version=\"3.0.0\">\n  <shape type=\"sphere\"><ref id=\"no\"/></shape></scene>",
    )
    .unwrap();
    let e = load_mitsuba(&main, &[]).unwrap_err().to_string();
    assert!(e.contains("part.xml:2:") && e.contains("unknown ref id `no`"), "{e}");
    std::fs::write(dir.join("inc/part.xml"), "<scene><include filename=\"inc/part.xml\"/></scene>").unwrap();
    let e = load_mitsuba(&main, &[]).unwrap_err().to_string();
    assert!(e.contains("include cycle"), "{e}");
    std::fs::write(&main, scene(r#"<include filename="inc/missing.xml"/>"#)).unwrap();
    let e = load_mitsuba(&main, &[]).unwrap_err().to_string();
    assert!(e.contains("main.xml:8:") && e.contains("cannot read included file"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn serialized_meshes_load_and_bad_ones_are_errors() {
    let Some(dir) = shared_scenes() else {
        eprintln!("skipped: ../shared/scenes is absent");
        return;
    };
    let path = dir.join("matpreview/common/meshes/matpreview.serialized");
    let parts = pathtrace_scene::mesh::load_mesh(&path).unwrap();
    assert!(parts.len() >= 3, "{} parts", parts.len());
    assert!(parts.iter().all(|(_, m)| !m.indices.is_empty()));
    // Truncated and corrupted copies fail with an error, never a panic.
    let bytes = std::fs::read(&path).unwrap();
    for cut in [0, 3, 8, 100, bytes.len() / 2, bytes.len() - 1] {
        assert!(pathtrace_scene::mesh::parse_mesh(&bytes[..cut], &path).is_err());
    }
    for at in (0..bytes.len()).step_by(bytes.len() / 50 + 1) {
        let mut b = bytes.clone();
        b[at] ^= 0x5a;
        let _ = pathtrace_scene::mesh::parse_mesh(&b, &path);
    }
    // In a scene: shape_index picks the part.
    let xml = scene(
        r#"<shape type="serialized"><string name="filename" value="m.serialized"/><integer name="shape_index" value="1"/></shape>"#,
    );
    let tmp = std::env::temp_dir().join(format!("pathtrace-mitsuba-ser-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    std::fs::copy(&path, tmp.join("m.serialized")).unwrap();
    let (f, w) = convert_str(&xml, &tmp.join("s.xml"), &[]).unwrap();
    assert!(w.is_empty(), "{w:?}");
    assert_eq!(
        f.objects[0].shape,
        ShapeDef::Mesh { file: "m.serialized".into(), part: Some(1), flip_v: false, normals: Default::default() }
    );
    let bad = xml.replace("value=\"1\"", "value=\"99\"").replace("</scene>", &format!("{LIGHT}</scene>"));
    let e = load_str(&bad, &tmp.join("s.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("part 99 does not exist") && !e.contains("s.xml:1:1:"), "{e}");
    let huge = xml.replace("value=\"1\"", "value=\"4294967296\"");
    let e = convert_str(&huge, &tmp.join("s.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("shape_index") && e.contains("4294967295"), "{e}");
    let _ = std::fs::remove_dir_all(&tmp);
}

#[test]
fn a_point_light_gives_its_inverse_square_irradiance() {
    let xml = r#"<scene version="3.0.0">
        <integrator type="direct"/>
        <sensor type="perspective">
            <float name="fov" value="10"/>
            <transform name="to_world"><lookat origin="0, 0, 10" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
        </sensor>
        <emitter type="point"><point name="position" value="0, 3, 4"/><rgb name="intensity" value="25"/></emitter>
        <shape type="rectangle"><transform name="to_world"><scale value="10"/></transform>
            <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
    </scene>"#;
    let (loaded, _) = load_str(xml, Path::new("p.xml"), &[]).unwrap();
    let mut s = RenderSettings { width: 16, height: 16, spp: 256, seed: 1, ..Default::default() };
    s.path.max_depth = loaded.defaults.max_depth;
    let film = render(Arc::new(loaded.scene), s).unwrap().film;
    // E = I cos θ / d² = 25 · 0.8 / 25 at the centre; the central pixels span ±0.2, where E
    // varies by under 1% on average.
    let expected = 0.5 / std::f64::consts::PI * 0.8;
    let r = film.region_estimate(6, 6, 10, 10);
    for c in 0..3 {
        assert!(
            (r.mean[c] - expected).abs() < 0.02 * expected + 4.0 * r.variance_of_mean[c].sqrt(),
            "{:?} vs {expected}",
            r
        );
    }
}

#[test]
fn without_fov_a_50mm_lens_on_35mm_film_is_assumed() {
    // Mitsuba 3 renders the teapot tutorial scene (square film, no fov) with x_fov = 34.022°.
    let xml = scene(LIGHT).replace(r#"<float name="fov" value="40"/>"#, "").replace("value=\"32\"", "value=\"64\"");
    let vfov = conv(&xml, &[]).0.camera.vfov.unwrap().get();
    assert!((vfov - 34.022).abs() < 0.01, "{vfov}");
    let xml = xml.replace(
        "<sensor type=\"perspective\">",
        "<sensor type=\"perspective\"><string name=\"focal_length\" value=\"abcmm\"/>",
    );
    assert!(err(&xml).contains("`abc` is not a number"));
}

#[test]
fn metals_rough_glass_and_plastics_import_without_warnings() {
    let xml = scene(&format!(
        r#"<bsdf type="conductor" id="gold"><string name="material" value="Au"/></bsdf>
        <bsdf type="twosided" id="brushed"><bsdf type="roughconductor">
            <string name="distribution" value="ggx"/><float name="alpha_u" value="0.05"/>
            <float name="alpha_v" value="0.3"/><boolean name="sample_visible" value="true"/>
            <rgb name="eta" value="0.2, 0.9, 1.1"/><rgb name="k" value="3.9, 2.4, 2.1"/></bsdf></bsdf>
        <bsdf type="roughdielectric" id="frosted"><string name="int_ior" value="water"/>
            <float name="alpha" value="0.2"/></bsdf>
        <bsdf type="roughplastic" id="shell"><rgb name="diffuse_reflectance" value="0.1, 0.2, 0.3"/>
            <float name="int_ior" value="2"/><boolean name="nonlinear" value="true"/></bsdf>
        <bsdf type="plastic" id="toy"/>
        <shape type="sphere"><ref id="gold"/></shape><shape type="sphere"><ref id="brushed"/></shape>
        <shape type="sphere"><ref id="frosted"/></shape><shape type="sphere"><ref id="shell"/></shape>
        <shape type="sphere"><ref id="toy"/></shape>{LIGHT}"#
    ));
    let (f, w) = conv(&xml, &[]);
    assert!(w.is_empty(), "{w:?}");
    // Opaque BSDFs outside `twosided` are one-sided (tested apart); the models are compared here.
    let kind = |name: &str| f.materials[name].kind.sides().0.clone();
    let MaterialKind::Conductor { metal: MetalDef::Named(name), .. } = kind("gold") else {
        panic!("{:?}", kind("gold"))
    };
    assert_eq!(name.0, "Au");
    let MaterialKind::RoughConductor { metal: MetalDef::Custom { .. }, roughness, .. } = kind("brushed") else {
        panic!("{:?}", kind("brushed"))
    };
    assert_eq!((roughness.alpha_u.get(), roughness.alpha_v.get()), (0.05, 0.3));
    let MaterialKind::RoughDielectric { ior, roughness, .. } = kind("frosted") else { panic!("{:?}", kind("frosted")) };
    // int_ior / ext_ior with Mitsuba's defaults: water in air; beckmann by default.
    assert!((ior.get() - 1.333 / 1.000277).abs() < 1e-6, "{ior:?}");
    assert_eq!(roughness.distribution, pathtrace::material::MicrofacetKind::Beckmann);
    let MaterialKind::RoughPlastic { nonlinear: true, ior, .. } = kind("shell") else { panic!("{:?}", kind("shell")) };
    assert!((ior.get() - 2.0 / 1.000277).abs() < 1e-6);
    let MaterialKind::Plastic { ior, .. } = kind("toy") else { panic!("{:?}", kind("toy")) };
    assert!((ior.get() - 1.49 / 1.000277).abs() < 1e-6);
    // And the scene builds and renders.
    assert!(load_str(&xml, Path::new("t.xml"), &[]).is_ok());
    let bad = scene(&format!(
        r#"<shape type="sphere"><bsdf type="conductor"><string name="material" value="gold"/></bsdf></shape>{LIGHT}"#
    ));
    let err = convert_str(&bad, Path::new("t.xml"), &[]).unwrap_err().to_string();
    assert!(err.contains("unknown metal") && err.contains("t.xml:"), "{err}");
}

#[test]
fn matpreview_scenes_load_their_environment_map() {
    let Some(dir) = shared_scenes() else {
        eprintln!("skipped: ../shared/scenes is absent");
        return;
    };
    for s in ["bsdf_diffuse_plain", "bsdf_plastic_shiny", "bsdf_roughconductor_copper", "bsdf_dielectric_glass"] {
        let path = dir.join(format!("matpreview/docs/scenes/{s}.xml"));
        let (loaded, w) = load_mitsuba(&path, &[]).unwrap_or_else(|e| panic!("{s}: {e}"));
        assert!(w.is_empty(), "{s}: {w:#?}");
        let env = loaded.scene.lights.environment().unwrap_or_else(|| panic!("{s}: no environment"));
        let map = env.env_map().unwrap_or_else(|| panic!("{s}: the environment is not a map"));
        // museum.exr at scale 3 is bright somewhere: its mean radiance over the sphere.
        let mean = map.luminance_integral() / (4.0 * std::f64::consts::PI);
        eprintln!("{s}: envmap mean luminance {mean:.4}, {} warning(s)", w.len());
        assert!(mean.is_finite() && mean > 0.0, "{s}: {mean}");
    }
}

#[test]
fn directional_emitters_and_face_normals_convert() {
    use pathtrace_scene::native::model::{LightDef, MeshNormals, ShapeDef};
    let xml = scene(&format!(
        r#"<emitter type="directional"><vector name="direction" value="0, -2, 0"/><rgb name="irradiance" value="3"/></emitter>
        <emitter type="directional"><transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>
        <shape type="ply"><string name="filename" value="a.ply"/><boolean name="face_normals" value="true"/></shape>
        <shape type="ply"><string name="filename" value="b.ply"/></shape>{LIGHT}"#
    ));
    let tmp = std::env::temp_dir().join(format!("pathtrace-xml-normals-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    for name in ["a.ply", "b.ply"] {
        std::fs::write(tmp.join(name), "").unwrap();
    }
    let (f, w) = convert_str(&xml, &tmp.join("t.xml"), &[]).unwrap();
    std::fs::remove_dir_all(&tmp).unwrap();
    assert!(w.is_empty(), "{w:?}");
    let directions: Vec<_> = f
        .lights
        .iter()
        .filter_map(|l| match l {
            LightDef::Directional { direction, transform, .. } => Some((direction.is_some(), transform.len())),
            _ => None,
        })
        .collect();
    assert_eq!(directions, vec![(true, 0), (false, 1)]);
    let normals: Vec<_> = f
        .objects
        .iter()
        .filter_map(|o| match &o.shape {
            ShapeDef::Mesh { normals, .. } => Some(*normals),
            _ => None,
        })
        .collect();
    assert_eq!(normals, vec![MeshNormals::Face, MeshNormals::Smooth]);
    let both = scene(&format!(
        r#"<emitter type="directional"><vector name="direction" value="0, -1, 0"/><transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>{LIGHT}"#
    ));
    let e = err(&both);
    assert!(e.contains("t.xml:") && e.contains("not both"), "{e}");
}

/// A scene written for Mitsuba 0.6 (camelCase names, `diffuseReflectance`, `toWorld`, uoffset
/// and uscale) converts to the same model as its Mitsuba 3 spelling, as Mitsuba 3.9.1 upgrades it.
#[test]
fn mitsuba_0_6_scenes_are_upgraded() {
    let old = r#"<scene version="0.6.0">
        <sensor type="perspective"><float name="fov" value="30"/>
            <transform name="toWorld"><lookAt origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
        </sensor>
        <bsdf type="dielectric" id="glass"><float name="intIOR" value="1.7"/><float name="extIOR" value="1.1"/></bsdf>
        <bsdf type="diffuse" id="wall"><texture type="checkerboard" name="diffuseReflectance">
            <float name="uoffset" value="0.25"/><float name="uscale" value="4"/><float name="vscale" value="2"/>
        </texture></bsdf>
        <shape type="sphere"><ref id="glass"/></shape>
        <shape type="sphere"><point name="center" x="2" y="0" z="0"/><ref id="wall"/></shape>
        <shape type="sphere" id="lamp"><emitter type="area"><rgb name="radiance" value="1, 2, 3"/></emitter></shape>
    </scene>"#;
    let new = r#"<scene version="3.0.0">
        <sensor type="perspective"><float name="fov" value="30"/>
            <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
        </sensor>
        <bsdf type="dielectric" id="glass"><float name="int_ior" value="1.7"/><float name="ext_ior" value="1.1"/></bsdf>
        <bsdf type="diffuse" id="wall"><texture type="checkerboard" name="reflectance">
            <transform name="to_uv"><translate x="0.25" y="0"/><scale x="4" y="2" z="1"/></transform>
        </texture></bsdf>
        <shape type="sphere"><ref id="glass"/></shape>
        <shape type="sphere"><point name="center" x="2" y="0" z="0"/><ref id="wall"/></shape>
        <shape type="sphere" id="lamp"><emitter type="area"><rgb name="radiance" value="1, 2, 3"/></emitter></shape>
    </scene>"#;
    let (a, wa) = conv(old, &[]);
    let (b, wb) = conv(new, &[]);
    assert!(wa.is_empty() && wb.is_empty(), "{wa:?} {wb:?}");
    assert_eq!(a, b);
    // Mitsuba 3 files are not upgraded: `intIOR` there is not the interior index.
    let (c, _) = conv(&new.replace("int_ior", "intIOR"), &[]);
    assert_ne!(c, b);
}

#[test]
fn opaque_bsdfs_outside_twosided_are_one_sided_and_dielectrics_never_are() {
    let bsdfs = [
        ("conductor", true),
        ("roughconductor", true),
        ("plastic", true),
        ("roughplastic", true),
        ("diffuse", true),
        ("dielectric", false),
        ("thindielectric", false),
        ("roughdielectric", false),
    ];
    for (ty, opaque) in bsdfs {
        for wrapped in [false, true] {
            let bsdf = format!(r#"<bsdf type="{ty}" id="m"/>"#);
            let bsdf = if wrapped {
                format!(r#"<bsdf type="twosided" id="m">{}</bsdf>"#, bsdf.replace(r#" id="m""#, ""))
            } else {
                bsdf
            };
            let (f, _) = conv(&scene(&format!(r#"{bsdf}<shape type="sphere"><ref id="m"/></shape>{LIGHT}"#)), &[]);
            let (_, one_sided) = f.materials["m"].kind.sides();
            assert_eq!(one_sided, opaque && !wrapped, "{ty}, inside twosided: {wrapped}");
        }
    }
}
