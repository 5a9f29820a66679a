//! `[[lights]] type = "envmap"`: an EXR or Radiance HDR image next to the scene file becomes the
//! environment, with its scale and transform; a missing or bad file is an error at the light's
//! line. The images are written by the test.

use pathtrace::film::tonemap::ToneMapSettings;
use pathtrace::film::Image;
use pathtrace::math::{Rgb, Vec3};
use pathtrace_scene::image_io::write_image;
use pathtrace_scene::native::load_file;
use std::path::{Path, PathBuf};

/// 8 × 5 texels: black, except the middle row (the horizon) whose column 2 is (4, 2, 1).
fn horizon_image() -> Image {
    let mut img = Image::new(8, 5);
    img.set(2, 2, Rgb::new(4.0, 2.0, 1.0));
    img
}

fn write_hdr(path: &Path, img: &Image) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    let pixels: Vec<image::Rgb<f32>> = img.pixels.iter().map(|p| image::Rgb([p.r, p.g, p.b])).collect();
    image::codecs::hdr::HdrEncoder::new(file).encode(&pixels, img.width as usize, img.height as usize).unwrap();
}

fn scene(dir: &Path, light: &str) -> PathBuf {
    let text = format!(
        "[camera]\nlook_from = [0, 0, -4]\nlook_at = [0, 0, 0]\n\n[materials.grey]\ntype = \"lambertian\"\n\
         albedo = 0.5\n\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"grey\"\n\n\
         [[lights]]\n{light}\n"
    );
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn exr_and_hdr_maps_load_with_scale_and_transform() {
    let dir = std::env::temp_dir().join(format!("pathtrace-envmap-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("sky")).unwrap();
    let img = horizon_image();
    write_image(&dir.join("sky/h.exr"), &img, &ToneMapSettings::default()).unwrap();
    write_hdr(&dir.join("sky/h.hdr"), &img);
    // Column 2 of 8 sits at u = 2.5/8, φ = 2π·u; d = (sin φ, 0, −cos φ) in the map's frame.
    let phi = 2.0 * std::f32::consts::PI * 2.5 / 8.0;
    let local = Vec3::new(phi.sin(), 0.0, -phi.cos());
    // rotate_y = 90 takes +x to −z: (x, y, z) → (z, y, −x).
    let world = Vec3::new(local.z, local.y, -local.x);
    for file in ["sky/h.exr", "sky/h.hdr"] {
        let light = format!("type = \"envmap\"\nfilename = \"{file}\"\nscale = 2\ntransform = [{{ rotate_y = 90 }}]");
        let loaded = load_file(&scene(&dir, &light)).unwrap_or_else(|e| panic!("{file}: {e}"));
        let env = loaded.scene.lights.environment().expect("an environment");
        assert!(env.env_map().is_some());
        let l = env.radiance(world);
        // RGBE keeps 8 bits of mantissa: 1% for the HDR file.
        let expected = Rgb::new(8.0, 4.0, 2.0);
        for (a, b) in l.to_array().into_iter().zip(expected.to_array()) {
            assert!((a - b).abs() < 0.01 * b, "{file}: {l:?} vs {expected:?}");
        }
        assert_eq!(env.radiance(Vec3::Y), Rgb::BLACK, "{file}: the pole is black");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_maps_are_errors_at_the_light() {
    let dir = std::env::temp_dir().join(format!("pathtrace-envmap-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    write_image(&dir.join("black.exr"), &Image::new(4, 2), &ToneMapSettings::default()).unwrap();
    let cases = [
        ("type = \"envmap\"\nfilename = \"missing.exr\"", "cannot load environment map"),
        ("type = \"envmap\"\nfilename = \"black.exr\"", "positive radiance"),
        ("type = \"envmap\"\nfilename = \"black.exr\"\nscale = -1", "scale"),
        ("type = \"envmap\"\nfilename = \"black.exr\"\ntransform = [{ scale = [1, 2, 1] }]", "rotation"),
    ];
    for (light, message) in cases {
        let err = load_file(&scene(&dir, light)).map(|_| ()).unwrap_err();
        // `[[lights]]` is line 15 of the generated file (the filename line 17).
        assert!(err.to_string().contains(message), "{light}: {err}");
        assert!(err.line >= 15, "{light}: located at line {}", err.line);
    }
    std::fs::remove_dir_all(&dir).ok();
}
