//! `pathtrace render FILE.toml|FILE.json`: scene files load, their settings apply unless the
//! command line overrides them, and a bad file gives one `file:line:col` line and exit code 2.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pathtrace-scenes-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pathtrace")).current_dir(dir).args(args).output().unwrap()
}

const SMALL: &str = r#"[render]
width = 24
height = 16
spp = 2
seed = 3

[camera]
look_from = [0, 0, -4]
look_at = [0, 0, 0]

[materials.lamp]
type = "emissive"
radiance = 2

[[objects]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "lamp"
"#;

#[test]
fn a_small_scene_file_renders_at_its_own_settings() {
    let dir = temp_dir("small");
    std::fs::write(dir.join("ball.toml"), SMALL).unwrap();
    let o = run_in(&dir, &["render", "ball.toml", "--quiet", "--stats-json", "stats.json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The default output is the file stem + .png, at the size the file asks for.
    let img = pathtrace_scene::image_io::read_image(&dir.join("ball.png")).unwrap();
    assert_eq!((img.width, img.height), (24, 16));
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("stats.json")).unwrap()).unwrap();
    assert_eq!((stats["spp"].as_u64(), stats["seed"].as_u64()), (Some(2), Some(3)));

    // The command line wins over the file; JSON works too.
    let json = dir.join("ball.json");
    let file = pathtrace_scene::native::parse_str(SMALL, pathtrace_scene::native::Format::Toml, "x.toml".as_ref());
    std::fs::write(
        &json,
        pathtrace_scene::native::to_string(&file.unwrap(), pathtrace_scene::native::Format::Json).unwrap(),
    )
    .unwrap();
    let o =
        run_in(&dir, &["render", "ball.json", "--quiet", "--size", "8x8", "--seed", "9", "--stats-json", "s2.json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = pathtrace_scene::image_io::read_image(&dir.join("ball.png")).unwrap();
    assert_eq!((img.width, img.height), (8, 8));
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("s2.json")).unwrap()).unwrap();
    assert_eq!((stats["spp"].as_u64(), stats["seed"].as_u64()), (Some(2), Some(9)));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bad_scene_file_gives_its_location_exit_code_2_and_no_image() {
    let dir = temp_dir("bad");
    std::fs::write(dir.join("bad.toml"), SMALL.replace("material = \"lamp\"", "material = \"lmap\"")).unwrap();
    let o = run_in(&dir, &["render", "bad.toml", "--quiet"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("bad.toml:19:12: unknown material `lmap`"), "{err}");
    assert!(!dir.join("bad.png").exists());

    std::fs::write(dir.join("syntax.json"), "{\"camera\": {\"look_from\": [0, 0, -4],\n \"look_at\": [0 0 0]}}")
        .unwrap();
    let o = run_in(&dir, &["render", "syntax.json", "--quiet"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("syntax.json:2:"), "{err}");

    let o = run_in(&dir, &["render", "missing.toml", "--quiet"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("missing.toml:1:1: cannot read"));
    let _ = std::fs::remove_dir_all(&dir);
}

const XML: &str = r#"<scene version="3.0.0">
    <default name="res" value="20"/>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="2"/></sampler>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="10"/></film>
    </sensor>
    <shape type="sphere"><emitter type="area"><rgb name="radiance" value="2, 2, 2"/></emitter></shape>
    <shape type="cylinder"/>
</scene>
"#;

#[test]
fn mitsuba_xml_renders_with_defines_and_warnings_and_converts() {
    let dir = temp_dir("xml");
    std::fs::write(dir.join("ball.xml"), XML).unwrap();
    let o = run_in(&dir, &["render", "ball.xml", "--quiet", "-D", "res=12"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("warning: ball.xml:9:5: shape `cylinder` is not supported"), "{stderr}");
    let img = pathtrace_scene::image_io::read_image(&dir.join("ball.png")).unwrap();
    assert_eq!((img.width, img.height), (12, 10));

    let o = run_in(&dir, &["convert", "ball.xml", "ball.toml", "--define", "res=14"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run_in(&dir, &["render", "ball.toml", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = pathtrace_scene::image_io::read_image(&dir.join("ball.png")).unwrap();
    assert_eq!((img.width, img.height), (14, 10));

    std::fs::write(
        dir.join("bad.xml"),
        "<scene version=\"3\">\n  <shape type=\"sphere\"><ref id=\"x\"/></shape></scene>",
    )
    .unwrap();
    let o = run_in(&dir, &["render", "bad.xml", "--quiet"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&o.stderr).starts_with("error: bad.xml:2:"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

const XML_NEW_PLUGINS: &str = r#"<scene version="3.0.0">
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="2"/></sampler>
        <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="10"/>
            <rfilter type="tent"><float name="radius" value="1.5"/></rfilter></film>
    </sensor>
    <emitter type="constant"><spectrum name="radiance" value="400:0.2, 700:0.4"/></emitter>
    <emitter type="point"><point name="position" value="0, 2, -1"/><rgb name="intensity" value="3"/></emitter>
    <shape type="disk"><bsdf type="thindielectric"/></shape>
</scene>
"#;

#[test]
fn convert_writes_every_new_plugin_and_the_native_file_renders_with_any_filter() {
    let dir = temp_dir("plugins");
    std::fs::write(dir.join("new.xml"), XML_NEW_PLUGINS).unwrap();
    let o = run_in(&dir, &["convert", "new.xml", "new.toml"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!String::from_utf8_lossy(&o.stderr).contains("warning"), "{}", String::from_utf8_lossy(&o.stderr));
    let toml = std::fs::read_to_string(dir.join("new.toml")).unwrap();
    for word in ["\"disk\"", "\"thindielectric\"", "\"constant\"", "\"point\"", "\"tent\"", "radius = 1.5"] {
        assert!(toml.contains(word), "{word} missing from\n{toml}");
    }
    for filter in ["box", "tent", "gaussian"] {
        let o = run_in(&dir, &["render", "new.toml", "--quiet", "--filter", filter, "-o", "f.pfm"]);
        assert!(o.status.success(), "{filter}: {}", String::from_utf8_lossy(&o.stderr));
    }
    let o = run_in(&dir, &["render", "new.toml", "--quiet", "--filter", "mitchell"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown filter"));
    let o = run_in(&dir, &["render", "new.toml", "--quiet", "--strategy", "bsdf", "-o", "b.pfm"]);
    assert!(o.status.success());
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("only the mis strategy"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn convert_keeps_texture_and_environment_paths_working_from_another_folder() {
    let dir = temp_dir("textures");
    std::fs::create_dir_all(dir.join("scene/tex")).unwrap();
    std::fs::create_dir_all(dir.join("out")).unwrap();
    // A 2×2 PNG texture and a 2×1 PFM environment map next to the scene.
    let png = [0u8, 0, 0, 255, 255, 255, 255, 255, 255, 0, 0, 0];
    image::save_buffer(dir.join("scene/tex/checks.png"), &png, 2, 2, image::ExtendedColorType::Rgb8).unwrap();
    let mut pfm = b"PF\n2 1\n-1.0\n".to_vec();
    pfm.extend([1.0f32; 6].iter().flat_map(|x| x.to_le_bytes()));
    std::fs::write(dir.join("scene/tex/sky.pfm"), pfm).unwrap();
    let xml = r#"<scene version="3.0.0">
        <bsdf type="diffuse" id="m"><texture type="bitmap" name="reflectance">
            <string name="filename" value="tex/checks.png"/></texture></bsdf>
        <shape type="sphere"><ref id="m"/></shape>
        <emitter type="envmap"><string name="filename" value="tex/sky.pfm"/></emitter>
        <sensor type="perspective"><transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
    </scene>"#;
    std::fs::write(dir.join("scene/s.xml"), xml).unwrap();
    let o = run_in(&dir, &["convert", "scene/s.xml", "out/s.toml"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.stderr.is_empty(), "{}", String::from_utf8_lossy(&o.stderr));
    let toml = std::fs::read_to_string(dir.join("out/s.toml")).unwrap();
    assert!(toml.contains("type = \"bitmap\"") && toml.contains("checks.png"), "{toml}");
    let o = run_in(&dir, &["render", "out/s.toml", "--quiet", "--spp", "2", "-o", "out/s.pfm"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `pathtrace convert scene.gltf scene.toml` into another folder: the native file keeps reading
/// its geometry from the glTF (path rebased) and renders; a glTF renders directly too.
#[test]
fn convert_and_render_gltf() {
    let dir = temp_dir("gltf");
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../pathtrace-scene/tests/data/gltf");
    std::fs::create_dir_all(dir.join("in")).unwrap();
    for f in ["scene.gltf", "scene.bin", "scene.glb"] {
        std::fs::copy(data.join(f), dir.join("in").join(f)).unwrap();
    }
    let o = run_in(&dir, &["convert", "in/scene.gltf", "out.toml"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.stderr.is_empty(), "{}", String::from_utf8_lossy(&o.stderr));
    let toml = std::fs::read_to_string(dir.join("out.toml")).unwrap();
    assert!(toml.contains("\"directional\"") && toml.contains("scene.gltf"), "{toml}");
    for scene in ["out.toml", "in/scene.glb"] {
        let o = run_in(&dir, &["render", scene, "--quiet", "--spp", "2", "--size", "16x16", "-o", "x.pfm"]);
        assert!(o.status.success(), "{scene}: {}", String::from_utf8_lossy(&o.stderr));
    }
}
