//! Hostile input and farm conditions, run as a careless user or pipeline would: images whose
//! headers lie, sizes and thread counts beyond reason, outputs that cannot be written. Every case
//! runs the binary under a memory limit and must end in exit 0 or 2 with a message that points the
//! right way, never an abort.

mod hostile {
    pub mod harness;
}

use hostile::harness::{assert_refused, run_limited, temp_dir};
use pathtrace::film::Image;
use pathtrace::film::ToneMapSettings;
use std::path::{Path, PathBuf};

/// A small scene: an emissive sphere, optionally textured with `texture` and lit by `envmap`.
fn scene(texture: Option<&str>, envmap: Option<&str>) -> String {
    let albedo = texture
        .map_or("albedo = 0.5\n".to_owned(), |t| format!("albedo = {{ type = \"bitmap\", filename = \"{t}\" }}\n"));
    let light = envmap.map_or(String::new(), |e| format!("\n[[lights]]\ntype = \"envmap\"\nfilename = \"{e}\"\n"));
    format!(
        "[render]\nwidth = 8\nheight = 8\nspp = 1\n\n[camera]\nlook_from = [0, 0, -4]\nlook_at = [0, 0, 0]\n\n\
         [materials.lamp]\ntype = \"emissive\"\nradiance = 2\n\n[materials.skin]\ntype = \"lambertian\"\n{albedo}\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"lamp\"\n\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 2, 0]\nradius = 0.5\nmaterial = \"skin\"\n{light}"
    )
}

/// A small EXR whose data window is rewritten to claim `side` × `side` pixels.
fn lying_exr(dir: &Path, name: &str, side: i32) -> PathBuf {
    let path = dir.join(name);
    let image = Image { width: 4, height: 4, pixels: vec![pathtrace::math::Rgb::splat(0.5); 16] };
    pathtrace_scene::image_io::write_image(&path, &image, &ToneMapSettings::default()).unwrap();
    let mut bytes = std::fs::read(&path).unwrap();
    let tag = b"dataWindow\0box2i\0";
    let at = bytes.windows(tag.len()).position(|w| w == tag).unwrap() + tag.len() + 4;
    bytes[at + 8..at + 12].copy_from_slice(&(side - 1).to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&(side - 1).to_le_bytes());
    std::fs::write(&path, bytes).unwrap();
    path
}

/// A Radiance HDR header claiming `side` × `side` pixels, followed by almost nothing.
fn lying_hdr(dir: &Path, name: &str, side: u32) -> PathBuf {
    let path = dir.join(name);
    let header = format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {side} +X {side}\n");
    std::fs::write(&path, [header.as_bytes(), b"\x02\x02\x80\x00"].concat()).unwrap();
    path
}

#[test]
fn images_with_lying_headers_are_refused_everywhere_without_allocating() {
    let dir = temp_dir("liars");
    let mut liars = Vec::new();
    for side in [20_000, 100_000] {
        liars.push(lying_exr(&dir, &format!("exr{side}.exr"), side as i32));
        liars.push(lying_hdr(&dir, &format!("hdr{side}.hdr"), side));
    }
    liars.push(lying_hdr(&dir, "empty.hdr", 0));
    let good = dir.join("good.exr");
    let image = Image { width: 8, height: 8, pixels: vec![pathtrace::math::Rgb::splat(0.5); 64] };
    pathtrace_scene::image_io::write_image(&good, &image, &ToneMapSettings::default()).unwrap();
    for liar in &liars {
        let name = liar.file_name().unwrap().to_str().unwrap();
        let as_texture = dir.join("texture.toml");
        std::fs::write(&as_texture, scene(Some(name), None)).unwrap();
        assert_refused(&run_limited(&dir, &["render", "texture.toml", "-q", "-o", "t.pfm"]), &[name]);
        let as_envmap = dir.join("envmap.toml");
        std::fs::write(&as_envmap, scene(None, Some(name))).unwrap();
        assert_refused(&run_limited(&dir, &["render", "envmap.toml", "-q", "-o", "e.pfm"]), &[name]);
        let xml = format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n<shape type=\"sphere\">\n<bsdf type=\"diffuse\"><texture type=\"bitmap\" \
             name=\"reflectance\"><string name=\"filename\" value=\"{name}\"/></texture></bsdf>\n</shape>\n\
             <emitter type=\"constant\"/>\n</scene>\n"
        );
        std::fs::write(dir.join("bitmap.xml"), xml).unwrap();
        assert_refused(&run_limited(&dir, &["render", "bitmap.xml", "-q", "--size", "8x8", "-o", "b.pfm"]), &[name]);
        if liar.extension().unwrap() == "exr" {
            assert_refused(&run_limited(&dir, &["compare", name, "good.exr"]), &[name]);
            assert_refused(&run_limited(&dir, &["compare", "good.exr", name]), &[name]);
        }
    }
    assert!(!dir.join("t.pfm").exists() && !dir.join("e.pfm").exists() && !dir.join("b.pfm").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn films_too_large_for_memory_are_refused_with_the_size_they_need() {
    let dir = temp_dir("films");
    for size in ["32768x32768", "16384x16384"] {
        let o = run_limited(&dir, &["render", "cornell-box", "--size", size, "--spp", "1", "-q", "-o", "big.png"]);
        assert_refused(&o, &[size, "GB"]);
    }
    assert!(!dir.join("big.png").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn thread_counts_beyond_reason_are_refused_at_once() {
    let dir = temp_dir("threads");
    let start = std::time::Instant::now();
    let o = run_limited(&dir, &["render", "cornell-box", "--threads", "100000", "--size", "8x8", "--spp", "1"]);
    assert_refused(&o, &["--threads", "0 (one per core)", "1024"]);
    assert!(start.elapsed().as_secs_f64() < 5.0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_kernel_renders_every_scene() {
    // Sphere lights were outside the old wide kernel's reach; the one estimator takes any scene
    // with any lane count.
    let dir = temp_dir("kernel");
    std::fs::write(dir.join("s.toml"), scene(None, None)).unwrap();
    for kernel in ["wide", "scalar", "auto"] {
        let o = run_limited(&dir, &["render", "s.toml", "--kernel", kernel, "-q", "-o", "s.png"]);
        assert!(o.status.success(), "--kernel {kernel}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(dir.join("s.png").is_file());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_output_destination_is_checked_before_rendering() {
    let dir = temp_dir("destinations");
    let cases: Vec<(&str, &str)> = vec![
        ("--stats-json", "missing/stats.json"),
        ("--stats-json", "/dev/full"),
        ("--stats-json", "."),
        ("-o", "missing/out.png"),
        ("-o", "out.txt"),
        ("--spp-image", "missing/spp.png"),
    ];
    for (option, value) in cases {
        let start = std::time::Instant::now();
        // A render of many minutes: the refusal must come before it.
        let mut args = vec!["render", "cornell-box", "--size", "64x64", "--spp", "1000000", "-q"];
        if option != "-o" {
            args.extend(["-o", "out.png"]);
        }
        args.extend([option, value]);
        let o = run_limited(&dir, &args);
        if value == "/dev/full" && !Path::new(value).exists() {
            continue;
        }
        assert_refused(&o, &[option]);
        assert!(start.elapsed().as_secs_f64() < 10.0, "{option} {value} was checked late");
        assert!(!dir.join("out.png").exists());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn compare_and_converge_refuse_non_finite_images_and_never_call_different_images_identical() {
    let dir = temp_dir("compare");
    let write = |name: &str, values: [f32; 4]| {
        let pixels = values.iter().map(|&v| pathtrace::math::Rgb::splat(v)).collect();
        let image = Image { width: 2, height: 2, pixels };
        pathtrace_scene::image_io::write_image(&dir.join(name), &image, &ToneMapSettings::default()).unwrap();
    };
    write("nan.pfm", [f32::NAN, 0.5, 0.5, 0.5]);
    write("inf.pfm", [f32::INFINITY, f32::NEG_INFINITY, 0.5, 0.5]);
    write("grey.pfm", [0.5; 4]);
    write("black.pfm", [0.0; 4]);
    assert_refused(&run_limited(&dir, &["compare", "nan.pfm", "grey.pfm"]), &["test image has 1 NaN or infinite"]);
    assert_refused(&run_limited(&dir, &["compare", "grey.pfm", "inf.pfm"]), &["reference image has 2 NaN"]);
    assert_refused(&run_limited(&dir, &["compare", "nan.pfm", "nan.pfm", "--json"]), &["NaN"]);
    let black = run_limited(&dir, &["compare", "grey.pfm", "black.pfm"]);
    assert!(black.status.success());
    let text = String::from_utf8_lossy(&black.stdout);
    assert!(!text.contains("identical") && text.contains("undefined"), "{text}");
    let same = run_limited(&dir, &["compare", "grey.pfm", "grey.pfm", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&same.stdout).unwrap();
    assert_eq!(json["identical"], true);
    let o = run_limited(&dir, &["converge", "cornell-box", "--reference", "nan.pfm", "--size", "2x2", "--out", "c"]);
    assert_refused(&o, &["nan.pfm", "NaN"]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Writes `text` as `name` in `dir` and renders it (8×8, 1 spp) under the memory limit.
fn render_file(dir: &Path, name: &str, text: &str) -> std::process::Output {
    std::fs::write(dir.join(name), text).unwrap();
    // Two threads: the address-space limit must not depend on the machine's core count.
    run_limited(dir, &["render", name, "-q", "--size", "8x8", "--spp", "1", "--threads", "2", "-o", "out.pfm"])
}

#[test]
fn mitsuba_build_errors_point_at_their_xml_element() {
    let dir = temp_dir("mitsuba");
    let scene = |extra: &str| {
        format!(
            "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"/>\n<shape type=\"sphere\">\n<bsdf \
             type=\"diffuse\"/>\n</shape>\n<emitter type=\"constant\"/>\n{extra}\n</scene>\n"
        )
    };
    let cases = [
        ("<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"500\"/></emitter>", "spot"),
        ("<emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"0\"/></emitter>", "spot"),
        (
            "<shape type=\"rectangle\"><emitter type=\"area\"><rgb name=\"radiance\" value=\"-1\"/></emitter></shape>",
            "≥ 0",
        ),
        ("<emitter type=\"constant\"><rgb name=\"radiance\" value=\"-1\"/></emitter>", "≥ 0"),
        ("<integrator type=\"path\"><integer name=\"max_depth\" value=\"99999999999\"/></integrator>", "2147483647"),
    ];
    for (extra, needle) in cases {
        let o = render_file(&dir, "x.xml", &scene(extra));
        assert_refused(&o, &["x.xml:7:", needle]);
    }
    let o = render_file(
        &dir,
        "x.xml",
        "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><sampler type=\"independent\">\n<integer \
         name=\"sample_count\" value=\"4294967296\"/></sampler></sensor>\n</scene>\n",
    );
    assert_refused(&o, &["x.xml:3:", "sample_count", "4294967295"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn megabyte_values_give_short_error_lines() {
    let dir = temp_dir("long-values");
    let long = "n".repeat(1 << 20);
    let digits = format!("1{}", "0".repeat(1 << 20));
    for (text, needle) in [
        (scene(None, None).replace("material = \"lamp\"", &format!("material = \"{long}\"")), "bytes]"),
        (scene(None, None).replace("radius = 1\n", &format!("radius = {digits}\n")), "radius"),
        (scene(Some(&format!("{long}.png")), None), "bytes]"),
    ] {
        // assert_refused also bounds the error line's length.
        assert_refused(&render_file(&dir, "s.toml", &text), &["s.toml:", needle]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn meshes_that_add_nothing_are_named_at_their_line() {
    let dir = temp_dir("meshes");
    let meshes = [
        ("flat.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\n", "triangles"),
        ("huge.obj", "v 0 0 0\nv 3e38 0 0\nv 0 3e38 0\nf 1 2 3\n", "triangles"),
        ("empty.obj", "v 0 0 0\nv 1 0 0\n", "no faces"),
    ];
    for (name, text, why) in meshes {
        std::fs::write(dir.join(name), text).unwrap();
        let scene =
            format!("{}\n[[objects]]\ntype = \"mesh\"\nfile = \"{name}\"\nmaterial = \"skin\"\n", scene(None, None));
        let line = scene.lines().position(|l| l.starts_with("file =")).unwrap() + 1;
        assert_refused(&render_file(&dir, "s.toml", &scene), &[&format!("s.toml:{line}:"), name, why]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn very_bright_finite_lights_render() {
    let dir = temp_dir("bright");
    let base = scene(None, None);
    for text in [
        base.replace("radiance = 2", "radiance = 1e38"),
        format!("{base}\n[[lights]]\ntype = \"point\"\nposition = [0, 3, 0]\nintensity = 3e38\n"),
        format!("{base}\n[[lights]]\ntype = \"constant\"\nradiance = 3e38\n"),
    ] {
        let o = render_file(&dir, "s.toml", &text);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_jpeg_environment_map_renders_as_the_docs_say() {
    let dir = temp_dir("jpeg-envmap");
    image::RgbImage::from_pixel(16, 8, image::Rgb([200, 180, 160])).save(dir.join("sky.jpg")).unwrap();
    let o = render_file(&dir, "s.toml", &scene(None, Some("sky.jpg")));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn physically_meaningless_optics_are_refused_at_their_material() {
    let dir = temp_dir("optics");
    let base = scene(None, None);
    let line = base.lines().position(|l| l == "[materials.skin]").unwrap() + 1;
    for (material, needle) in [
        ("type = \"plastic\"\nalbedo = 0.5\nior = 1e6", "ior"),
        ("type = \"plastic\"\nalbedo = 0.5\nior = 1e-30", "ior"),
        ("type = \"rough_plastic\"\nalbedo = 0.5\nalpha = 3e38", "alpha"),
        ("type = \"rough_dielectric\"\nior = 1e30", "ior"),
    ] {
        let text = base.replace("type = \"lambertian\"\nalbedo = 0.5", material);
        assert_refused(&render_file(&dir, "s.toml", &text), &[&format!("s.toml:{line}:"), needle]);
    }
    let _ = std::fs::remove_dir_all(&dir);
}
