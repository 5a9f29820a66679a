//! Textures through the file formats: texture images (PNG and JPEG sRGB-decoded unless `raw`,
//! EXR linear), native texture tables (defaults, located errors, round trip), Mitsuba's
//! `<texture>` nested and by `<ref>`, and a textured square under a white sky whose rendered
//! mean is the texture's mean albedo (the furnace idea: ∫ ρ/π · 1 · cos dω = ρ).

use pathtrace::film::tonemap::{srgb_decode, ToneMapSettings};
use pathtrace::film::Image;
use pathtrace::math::Rgb;
use pathtrace::{render, RenderSettings};
use pathtrace_scene::image_io::{read_texture, write_image};
use pathtrace_scene::mitsuba::convert_str;
use pathtrace_scene::native::model::{Colour, MaterialKind, TextureDef};
use pathtrace_scene::native::{load_str, parse_str, to_string, Format};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A fresh folder under the system temp dir for this test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pathtrace-textures-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A flat 4×4 8-bit grey image of value `v`, saved in `format`.
fn flat_grey(path: &Path, v: u8, format: image::ImageFormat) {
    image::RgbImage::from_pixel(4, 4, image::Rgb([v, v, v])).save_with_format(path, format).unwrap();
}

#[test]
fn eight_bit_images_are_srgb_decoded_unless_raw_and_float_images_are_linear() {
    let dir = scratch("decode");
    let png = dir.join("grey.png");
    flat_grey(&png, 128, image::ImageFormat::Png);
    let srgb = read_texture(&png, false).unwrap();
    let raw = read_texture(&png, true).unwrap();
    // sRGB 128/255 is 0.21586 linear (IEC 61966-2-1).
    assert!((srgb.pixels[0].r - 0.21586).abs() < 1e-4, "{:?}", srgb.pixels[0]);
    assert_eq!(srgb.pixels[0].r, srgb_decode(128.0 / 255.0));
    assert_eq!(raw.pixels[5].g, 128.0 / 255.0);
    assert_eq!((srgb.width, srgb.height), (4, 4));

    // A flat JPEG decodes to its value within the codec's rounding.
    let jpg = dir.join("grey.jpg");
    flat_grey(&jpg, 200, image::ImageFormat::Jpeg);
    let j = read_texture(&jpg, false).unwrap();
    let expected = srgb_decode(200.0 / 255.0);
    assert!((j.pixels[0].b - expected).abs() < 0.01, "{:?} vs {expected}", j.pixels[0]);
    let jraw = read_texture(&jpg, true).unwrap();
    assert!((jraw.pixels[0].b - 200.0 / 255.0).abs() < 0.01, "{:?}", jraw.pixels[0]);

    // EXR keeps its linear values whatever `raw` says.
    let exr = dir.join("two.exr");
    let image = Image { width: 2, height: 1, pixels: vec![Rgb::new(0.25, 2.0, 0.0), Rgb::new(1.5, 0.0, 0.125)] };
    write_image(&exr, &image, &ToneMapSettings::default()).unwrap();
    for raw in [false, true] {
        assert_eq!(read_texture(&exr, raw).unwrap().pixels, image.pixels);
    }
    assert!(read_texture(&dir.join("missing.png"), false).unwrap_err().to_string().contains("missing.png"));
}

/// The unit square [-1, 1]² at z = 0 filling a 90° view from (0, 0, 1) under a white sky.
fn square_scene(albedo: &str) -> String {
    format!(
        r#"
[render]
width = 16
height = 16
filter = {{ type = "box" }}
max_depth = -1

[camera]
look_from = [0, 0, 1]
look_at = [0, 0, 0]
vfov = 90

[materials.floor]
type = "lambertian"
albedo = {albedo}

[[objects]]
type = "quad"
q = [-1, -1, 0]
u = [2, 0, 0]
v = [0, 2, 0]
material = "floor"

[[lights]]
type = "constant"
radiance = 1
"#
    )
}

fn rendered_mean(scene_text: &str, dir: &Path) -> [f64; 3] {
    let loaded = load_str(scene_text, Format::Toml, &dir.join("scene.toml")).unwrap();
    let mut s = RenderSettings { width: 16, height: 16, spp: 64, seed: 5, ..Default::default() };
    s.filter = loaded.defaults.filter.unwrap();
    s.path.max_depth = loaded.defaults.max_depth;
    let out = render(Arc::new(loaded.scene), s).unwrap();
    out.film.region_estimate(0, 0, 16, 16).mean
}

#[test]
fn a_textured_square_under_a_white_sky_reflects_the_texture_mean() {
    let dir = scratch("furnace");
    flat_grey(&dir.join("grey.png"), 128, image::ImageFormat::Png);
    let cases = [
        (
            r#"{ type = "checkerboard", color0 = [0.8, 0.2, 0.5], color1 = [0.2, 0.6, 0.1], scale = 4 }"#,
            [0.5, 0.4, 0.3],
        ),
        (r#"{ type = "bitmap", filename = "grey.png" }"#, [0.21586; 3]),
        (r#"{ type = "bitmap", filename = "grey.png", raw = true, scale = 3 }"#, [128.0 / 255.0; 3]),
        // `factor` multiplies the decoded texels (glTF's baseColorFactor × baseColorTexture).
        (r#"{ type = "bitmap", filename = "grey.png", factor = [1, 0.5, 0.25] }"#, [0.21586, 0.10793, 0.053965]),
    ];
    for (albedo, expected) in cases {
        let mean = rendered_mean(&square_scene(albedo), &dir);
        eprintln!("{albedo}: {mean:.5?} vs {expected:?}");
        for k in 0..3 {
            assert!((mean[k] - expected[k]).abs() < 0.01 * expected[k], "{albedo}: {mean:?} vs {expected:?}");
        }
    }
}

#[test]
fn bad_texture_tables_are_errors_at_their_line_and_column() {
    let dir = scratch("errors");
    let e = load_str(&square_scene(r#"{ type = "bitmap" }"#), Format::Toml, &dir.join("s.toml")).unwrap_err();
    let text = e.to_string();
    assert!(text.contains("s.toml:15:10:") && text.contains("filename"), "{text}");
    let e = load_str(&square_scene(r#"{ type = "checkerboard", colour0 = 1 }"#), Format::Toml, &dir.join("s.toml"))
        .unwrap_err()
        .to_string();
    // The unknown field itself is pointed at.
    assert!(e.contains("s.toml:15:35:") && e.contains("colour0"), "{e}");
    let e = load_str(&square_scene(r#"{ type = "bitmap", filename = "nope.png" }"#), Format::Toml, &dir.join("s.toml"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("s.toml:15:") && e.contains("cannot load texture") && e.contains("nope.png"), "{e}");
    // A bad bitmap `factor` is pointed at: the texture for a value the texture checks, the
    // number itself for one that is not a number.
    for (factor, at, what) in [("-1", "s.toml:15:10:", "≥ 0"), ("[1, 2]", "s.toml:15:", "three numbers")] {
        let t = format!(r#"{{ type = "bitmap", filename = "grey.png", factor = {factor} }}"#);
        let e = load_str(&square_scene(&t), Format::Toml, &dir.join("s.toml")).unwrap_err().to_string();
        assert!(e.contains(at) && e.contains(what), "{factor}: {e}");
    }
    // A texture where a plain colour is required (a light's radiance) is a type error.
    let bad = square_scene("0.5").replace("radiance = 1", r#"radiance = { type = "checkerboard" }"#);
    assert!(load_str(&bad, Format::Toml, &dir.join("s.toml")).is_err());
}

#[test]
fn textured_scenes_round_trip_through_toml_and_json() {
    let file = parse_str(
        &square_scene(
            r#"{ type = "bitmap", filename = "a.png", filter_type = "nearest", to_uv = [[2, 0, 0.5], [0, 2, 0]] }"#,
        ),
        Format::Toml,
        Path::new("s.toml"),
    )
    .unwrap();
    for format in [Format::Toml, Format::Json] {
        let text = to_string(&file, format).unwrap();
        assert_eq!(parse_str(&text, format, Path::new("x")).unwrap(), file, "{text}");
    }
}

const LIGHT: &str = r#"<emitter type="constant"/><sensor type="perspective"/>"#;

/// Mitsuba 3's checkerboard puts `color0` on the other squares when read as a number (`eval_1`:
/// roughness, blend weight, mask opacity) than as a colour (`eval`); the import keeps its
/// pictures by exchanging the two for number parameters only.
#[test]
fn a_mitsuba_checkerboard_read_as_a_number_exchanges_its_squares() {
    let checks = r#"<texture type="checkerboard" name="NAME"><float name="color0" value="0.1"/><float name="color1" value="0.4"/></texture>"#;
    let xml = format!(
        r#"<scene version="3.0.0">
        <bsdf type="roughdielectric" id="glass">{}</bsdf>
        <bsdf type="diffuse" id="floor">{}</bsdf>
        <shape type="sphere"><ref id="glass"/></shape><shape type="sphere"><ref id="floor"/></shape>
        {LIGHT}</scene>"#,
        checks.replace("NAME", "alpha"),
        checks.replace("NAME", "reflectance")
    );
    let (file, warnings) = convert_str(&xml, Path::new("t.xml"), &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let squares = |c: &Option<Colour>| match c {
        Some(Colour::Texture(TextureDef::Checkerboard { color0, color1, .. })) => (color0.vec3().x, color1.vec3().x),
        other => panic!("{other:?}"),
    };
    assert_eq!(squares(&file.materials["glass"].roughness), (0.4, 0.1));
    let MaterialKind::Lambertian { albedo } = file.materials["floor"].kind.sides().0 else { panic!() };
    assert_eq!(squares(&Some(albedo.clone())), (0.1, 0.4));
}

#[test]
fn mitsuba_textures_nested_and_by_reference() {
    let dir = scratch("mitsuba");
    flat_grey(&dir.join("wood.png"), 90, image::ImageFormat::Png);
    let xml = format!(
        r#"<scene version="3.0.0">
        <texture type="checkerboard" id="checks">
            <rgb name="color0" value="0.9"/>
            <transform name="to_uv"><scale x="8" y="4"/><translate x="0.25"/></transform>
        </texture>
        <bsdf type="diffuse" id="floor"><ref name="reflectance" id="checks"/></bsdf>
        <bsdf type="plastic" id="toy">
            <texture type="bitmap" name="diffuse_reflectance">
                <string name="filename" value="wood.png"/>
                <boolean name="raw" value="true"/>
                <string name="wrap_mode" value="clamp"/>
            </texture>
        </bsdf>
        <shape type="sphere"><ref id="floor"/></shape>
        <shape type="sphere"><ref id="toy"/></shape>
        {LIGHT}</scene>"#
    );
    let path = dir.join("scene.xml");
    std::fs::write(&path, &xml).unwrap();
    let (file, warnings) = pathtrace_scene::mitsuba::convert_file(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let MaterialKind::Lambertian { albedo: Colour::Texture(TextureDef::Checkerboard { color0, color1, to_uv }) } =
        file.materials["floor"].kind.sides().0
    else {
        panic!("{:?}", file.materials["floor"])
    };
    assert_eq!((color0.vec3().x, color1.vec3().x), (0.9, 0.2));
    // Document order: scale first, then translate: u' = 8u + 0.25, v' = 4v.
    let rows = to_uv.map(|r| r.map(|x| x.get()));
    assert_eq!(rows, [[8.0, 0.0, 0.25], [0.0, 4.0, 0.0]]);
    let MaterialKind::Plastic { albedo: Colour::Texture(TextureDef::Bitmap { filename, raw, clamp, .. }), .. } =
        file.materials["toy"].kind.sides().0
    else {
        panic!("{:?}", file.materials["toy"])
    };
    assert_eq!((filename.as_str(), *raw, *clamp), ("wood.png", true, true));
}

#[test]
fn mitsuba_texture_options_we_lack_are_warned_about_and_bad_refs_are_located() {
    let xml = format!(
        r#"<scene version="3.0.0">
        <bsdf type="diffuse" id="a"><texture type="checkerboard" name="reflectance">
            <float name="wobble" value="1"/></texture></bsdf>
        <bsdf type="diffuse" id="b"><texture type="voronoi" name="reflectance"/></bsdf>
        <bsdf type="diffuse" id="c"><ref name="reflectance" id="a"/></bsdf>
        <shape type="sphere"><ref id="a"/></shape><shape type="sphere"><ref id="b"/></shape>
        {LIGHT}</scene>"#
    );
    let (_, w) = convert_str(&xml, Path::new("t.xml"), &[]).unwrap();
    assert!(w.iter().any(|w| w.contains("`wobble`") && w.contains("t.xml:3:")), "{w:?}");
    assert!(w.iter().any(|w| w.contains("`voronoi`") && w.contains("t.xml:4:")), "{w:?}");
    let bad =
        xml.replace(r#"<shape type="sphere"><ref id="a"/></shape>"#, r#"<shape type="sphere"><ref id="c"/></shape>"#);
    let e = convert_str(&bad, Path::new("t.xml"), &[]).unwrap_err().to_string();
    assert!(e.contains("t.xml:5:") && e.contains("must name a <texture>"), "{e}");
}

#[test]
fn mitsuba_obj_meshes_flip_v_as_mitsuba_does_and_ply_do_not() {
    let dir = scratch("flip");
    std::fs::write(dir.join("t.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.1 0.2\nvt 0.3 0.4\nvt 0.5 0.6\nf 1/1 2/2 3/3\n")
        .unwrap();
    std::fs::copy(dir.join("t.obj"), dir.join("u.obj")).unwrap();
    std::fs::write(dir.join("t.ply"), "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
    let xml = format!(
        r#"<scene version="3.0.0">
        <shape type="obj"><string name="filename" value="t.obj"/></shape>
        <shape type="obj"><string name="filename" value="u.obj"/><boolean name="flip_tex_coords" value="false"/></shape>
        <shape type="ply"><string name="filename" value="t.ply"/></shape>
        {LIGHT}</scene>"#
    );
    let path = dir.join("scene.xml");
    std::fs::write(&path, &xml).unwrap();
    let (file, warnings) = pathtrace_scene::mitsuba::convert_file(&path, &[]).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let flips: Vec<bool> = file
        .objects
        .iter()
        .filter_map(|o| match &o.shape {
            pathtrace_scene::native::model::ShapeDef::Mesh { flip_v, .. } => Some(*flip_v),
            _ => None,
        })
        .collect();
    assert_eq!(flips, [true, false, false]);
    // The flag survives the native round trip and the scene builds.
    let text = to_string(&file, Format::Toml).unwrap();
    assert!(text.contains("flip_v = true"), "{text}");
    pathtrace_scene::mitsuba::build_model(&file, &path).unwrap();
}
