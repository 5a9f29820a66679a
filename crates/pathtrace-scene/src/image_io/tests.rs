//! File-level tests of `write_image` / `read_image`.

use std::fs;
use std::path::Path;

use pathtrace::film::tonemap::{srgb_encode, ToneMap, ToneMapSettings};
use pathtrace::film::Image;
use pathtrace::math::Rgb;

use super::scratch::ScratchDir;
use super::{read_image, write_image, ImageFormat, ImageIoError};

/// A deterministic test image with awkward float values (tiny, huge, negative).
fn hdr_image(width: u32, height: u32) -> Image {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        // Xorshift64 (Marsaglia 2003), just to vary the pixel values.
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut img = Image::new(width, height);
    for p in &mut img.pixels {
        *p = Rgb::new(next() * 100.0, next() * 1e-6, next() - 0.5);
    }
    img.pixels[0] = Rgb::new(f32::MAX, f32::MIN_POSITIVE, 1e-40);
    img
}

/// A test image with display-range values, as PNG can hold.
fn ldr_image(width: u32, height: u32) -> Image {
    let mut img = Image::new(width, height);
    for y in 0..height {
        for x in 0..width {
            let (u, v) = (x as f32 / width as f32, y as f32 / height as f32);
            img.set(x, y, Rgb::new(u, v, (u * v).sqrt()));
        }
    }
    img
}

fn default_settings() -> ToneMapSettings {
    ToneMapSettings::default()
}

#[test]
fn exr_round_trip_is_exact() {
    let dir = ScratchDir::new("io-exr");
    let path = dir.path().join("out.exr");
    let img = hdr_image(37, 21);
    write_image(&path, &img, &default_settings()).unwrap();
    assert_eq!(read_image(&path).unwrap(), img);
    assert_eq!(dir.entries(), ["out.exr"]);
}

#[test]
fn pfm_round_trip_is_exact() {
    let dir = ScratchDir::new("io-pfm");
    let path = dir.path().join("out.PFM");
    let img = hdr_image(13, 8);
    write_image(&path, &img, &default_settings()).unwrap();
    assert_eq!(read_image(&path).unwrap(), img);
}

#[test]
fn linear_formats_ignore_exposure_and_tone_map() {
    let dir = ScratchDir::new("io-linear");
    let settings = ToneMapSettings { exposure: 3.0, tone_map: ToneMap::Aces };
    let img = hdr_image(4, 4);
    for name in ["a.exr", "a.pfm"] {
        let path = dir.path().join(name);
        write_image(&path, &img, &settings).unwrap();
        assert_eq!(read_image(&path).unwrap(), img, "{name}");
    }
}

#[test]
fn pfm_file_layout_is_bottom_row_first() {
    let dir = ScratchDir::new("io-pfm-layout");
    let path = dir.path().join("layout.pfm");
    let top = Rgb::new(1.0, 2.0, 3.0);
    let bottom = Rgb::new(4.0, 5.0, 6.0);
    let img = Image::from_pixels(1, 2, vec![top, bottom]).unwrap();
    write_image(&path, &img, &default_settings()).unwrap();
    let bytes = fs::read(&path).unwrap();
    let mut expected = b"PF\n1 2\n-1.0\n".to_vec();
    for v in [4.0f32, 5.0, 6.0, 1.0, 2.0, 3.0] {
        expected.extend_from_slice(&v.to_le_bytes());
    }
    assert_eq!(bytes, expected);
}

#[test]
fn png_round_trip_within_8_bit_quantisation() {
    let dir = ScratchDir::new("io-png");
    let path = dir.path().join("out.png");
    let img = ldr_image(32, 16);
    write_image(&path, &img, &default_settings()).unwrap();
    let back = read_image(&path).unwrap();
    assert_eq!((back.width, back.height), (32, 16));
    for (a, b) in img.pixels.iter().zip(&back.pixels) {
        for (x, y) in a.to_array().into_iter().zip(b.to_array()) {
            // Half a code value in the encoded domain, plus float slack.
            let err = (srgb_encode(x) - srgb_encode(y)).abs();
            assert!(err <= 0.5 / 255.0 + 1e-6, "{x} vs {y}");
        }
    }
}

#[test]
fn png_applies_exposure_and_clamps() {
    let dir = ScratchDir::new("io-png-exposure");
    let path = dir.path().join("out.png");
    let img = Image::from_pixels(3, 1, vec![Rgb::splat(0.25), Rgb::splat(9.0), Rgb::BLACK]).unwrap();
    let settings = ToneMapSettings { exposure: 1.0, tone_map: ToneMap::Clamp };
    write_image(&path, &img, &settings).unwrap();
    let back = read_image(&path).unwrap();
    assert!((back.pixels[0].g - 0.5).abs() < 0.003, "{:?}", back.pixels[0]);
    assert_eq!(back.pixels[1], Rgb::WHITE);
    assert_eq!(back.pixels[2], Rgb::BLACK);
}

#[test]
fn png_16_bit_and_grey_are_decoded() {
    let dir = ScratchDir::new("io-png16");
    let path16 = dir.path().join("deep.png");
    image::ImageBuffer::from_fn(2, 1, |x, _| image::Rgb([0u16, 65535, if x == 0 { 0 } else { 65535 }]))
        .save(&path16)
        .unwrap();
    let img = read_image(&path16).unwrap();
    assert_eq!(img.pixels, [Rgb::new(0.0, 1.0, 0.0), Rgb::new(0.0, 1.0, 1.0)]);

    let grey = dir.path().join("grey.png");
    image::GrayImage::from_raw(1, 1, vec![188]).unwrap().save(&grey).unwrap();
    let img = read_image(&grey).unwrap();
    let v = img.pixels[0];
    assert!(v.r == v.g && v.g == v.b && (v.r - 0.5).abs() < 0.003, "{v:?}");
}

#[test]
fn exr_half_float_rgba_is_read() {
    use exr::prelude::f16;
    let dir = ScratchDir::new("io-exr-half");
    let path = dir.path().join("half.exr");
    exr::prelude::write_rgba_file(&path, 3, 2, |x, y| {
        let v = f16::from_f32((x + 3 * y) as f32 * 0.5);
        (v, f16::from_f32(2.0), f16::from_f32(-1.0), f16::from_f32(0.25))
    })
    .unwrap();
    let img = read_image(&path).unwrap();
    assert_eq!((img.width, img.height), (3, 2));
    assert_eq!(img.get(2, 1), Rgb::new(2.5, 2.0, -1.0));
    assert_eq!(img.get(0, 0), Rgb::new(0.0, 2.0, -1.0));
}

#[test]
fn exr_without_rgb_channels_is_an_error() {
    use exr::prelude::*;
    let dir = ScratchDir::new("io-exr-depth");
    let path = dir.path().join("depth.exr");
    let channels = SpecificChannels::build().with_channel("Z").with_pixel_fn(|_: Vec2<usize>| (1.5f32,));
    Image::from_channels((4, 4), channels).write().to_file(&path).unwrap();
    let err = read_image(&path).unwrap_err();
    assert!(matches!(err, ImageIoError::MissingChannels { .. }), "{err}");
    let msg = err.to_string();
    assert!(msg.contains("depth.exr") && msg.contains('Z'), "{msg}");
}

#[test]
fn garbage_and_truncated_files_are_errors() {
    let dir = ScratchDir::new("io-garbage");
    let pfm = dir.path().join("bad.pfm");
    fs::write(&pfm, b"PF\n4 4\n-1.0\n\x00\x00\x80\x3f").unwrap();
    let err = read_image(&pfm).unwrap_err();
    assert!(matches!(err, ImageIoError::InvalidPfm { .. }), "{err}");
    assert!(err.to_string().contains("bad.pfm") && err.to_string().contains("truncated"));

    for name in ["bad.exr", "bad.png", "worse.pfm"] {
        let path = dir.path().join(name);
        fs::write(&path, b"this is not an image at all").unwrap();
        let err = read_image(&path).unwrap_err();
        assert!(err.to_string().contains(name), "{err}");
    }

    // A valid file cut short.
    let exr = dir.path().join("cut.exr");
    write_image(&exr, &hdr_image(16, 16), &default_settings()).unwrap();
    let bytes = fs::read(&exr).unwrap();
    fs::write(&exr, &bytes[..bytes.len() / 2]).unwrap();
    assert!(read_image(&exr).is_err());
}

#[test]
fn missing_file_is_an_io_error_naming_it() {
    let dir = ScratchDir::new("io-missing");
    for name in ["nope.png", "nope.exr", "nope.pfm"] {
        let err = read_image(&dir.path().join(name)).unwrap_err();
        assert!(matches!(err, ImageIoError::Io { .. }), "{err}");
        assert!(err.to_string().contains(name), "{err}");
    }
}

#[test]
fn format_from_extension() {
    assert_eq!(ImageFormat::from_path(Path::new("a/b.png")).unwrap(), ImageFormat::Png);
    assert_eq!(ImageFormat::from_path(Path::new("B.EXR")).unwrap(), ImageFormat::Exr);
    assert_eq!(ImageFormat::from_path(Path::new("c.Pfm")).unwrap(), ImageFormat::Pfm);
    for f in [ImageFormat::Png, ImageFormat::Exr, ImageFormat::Pfm] {
        let name = format!("x.{}", f.extension());
        assert_eq!(ImageFormat::from_path(Path::new(&name)).unwrap(), f);
    }
}

#[test]
fn unknown_extension_error_lists_supported_ones() {
    for name in ["render.jpg", "render", "render.png.bak"] {
        let err = ImageFormat::from_path(Path::new(name)).unwrap_err();
        assert!(matches!(err, ImageIoError::UnsupportedFormat { .. }));
        let msg = err.to_string();
        assert!(msg.contains(name), "{msg}");
        for ext in ImageFormat::SUPPORTED_EXTENSIONS {
            assert!(msg.contains(ext), "{msg}");
        }
    }
    let dir = ScratchDir::new("io-unknown");
    let path = dir.path().join("out.jpg");
    assert!(write_image(&path, &ldr_image(2, 2), &default_settings()).is_err());
    assert!(dir.entries().is_empty());
}

#[test]
fn writing_into_a_missing_directory_fails_and_creates_nothing() {
    let dir = ScratchDir::new("io-nodir");
    let missing = dir.path().join("no").join("such");
    for name in ["out.png", "out.exr", "out.pfm"] {
        let path = missing.join(name);
        let err = write_image(&path, &ldr_image(2, 2), &default_settings()).unwrap_err();
        assert!(matches!(err, ImageIoError::Io { .. }), "{err}");
        assert!(err.to_string().contains(name), "{err}");
    }
    assert!(!dir.path().join("no").exists());
    assert!(dir.entries().is_empty());
}

#[test]
fn empty_and_inconsistent_images_are_rejected() {
    let dir = ScratchDir::new("io-empty");
    for name in ["e.png", "e.exr", "e.pfm"] {
        let path = dir.path().join(name);
        for (w, h) in [(0, 0), (0, 3), (3, 0)] {
            let err = write_image(&path, &Image::new(w, h), &default_settings()).unwrap_err();
            assert!(matches!(err, ImageIoError::EmptyImage { .. }), "{err}");
        }
        let bad = Image { width: 2, height: 2, pixels: vec![Rgb::WHITE; 3] };
        let err = write_image(&path, &bad, &default_settings()).unwrap_err();
        assert!(matches!(err, ImageIoError::PixelCountMismatch { .. }), "{err}");
    }
    assert!(dir.entries().is_empty());
}

#[test]
fn overwriting_replaces_the_file_and_leaves_no_temporaries() {
    let dir = ScratchDir::new("io-overwrite");
    let path = dir.path().join("img.pfm");
    write_image(&path, &hdr_image(3, 3), &default_settings()).unwrap();
    let second = hdr_image(5, 2);
    write_image(&path, &second, &default_settings()).unwrap();
    assert_eq!(read_image(&path).unwrap(), second);
    assert_eq!(dir.entries(), ["img.pfm"]);
}

/// A small EXR whose header's data window is rewritten to claim `side` × `side` pixels.
pub(crate) fn exr_with_lying_header(dir: &Path, side: i32) -> std::path::PathBuf {
    let path = dir.join("liar.exr");
    write_image(&path, &ldr_image(4, 4), &default_settings()).unwrap();
    let mut bytes = fs::read(&path).unwrap();
    let tag = b"dataWindow\0box2i\0";
    let at = bytes.windows(tag.len()).position(|w| w == tag).expect("data window attribute") + tag.len() + 4;
    // box2i: x_min, y_min, x_max, y_max (inclusive), little-endian i32.
    bytes[at + 8..at + 12].copy_from_slice(&(side - 1).to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&(side - 1).to_le_bytes());
    fs::write(&path, bytes).unwrap();
    path
}

#[test]
fn lying_image_headers_are_refused_before_allocating() {
    let dir = ScratchDir::new("io-liars");
    for side in [20_000, 100_000] {
        let exr = exr_with_lying_header(dir.path(), side);
        for read in [read_image, super::read_linear_image, |p: &Path| super::read_texture(p, false)] {
            let err = read(&exr).unwrap_err();
            assert!(matches!(err, ImageIoError::ImplausibleSize { .. }), "{err}");
            assert!(err.to_string().contains(&format!("{side}x{side}")), "{err}");
        }
    }
    let hdr = dir.path().join("liar.hdr");
    fs::write(&hdr, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n\x02\x02\x80\x00").unwrap();
    let err = super::read_linear_image(&hdr).unwrap_err();
    assert!(matches!(err, ImageIoError::ImplausibleSize { .. }), "{err}");
    let empty = dir.path().join("empty.hdr");
    fs::write(&empty, b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 0\n").unwrap();
    let err = super::read_texture(&empty, false).map(|i| (i.width, i.height));
    assert!(err.as_ref().is_err_and(|e| !e.to_string().contains("texel")), "{err:?}");
}
