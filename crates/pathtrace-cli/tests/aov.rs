//! `render --aov` and `--denoise` end to end: the feature buffers land in the EXR under the
//! channel names tools expect (read back with the `exr` crate's generic reader, not our writer's
//! code), or beside PNG/PFM output; a missing denoiser is a usage error (exit 2) in one line.

use exr::prelude::{read_all_flat_layers_from_file, FlatSamples};
use std::collections::HashMap;
use std::path::PathBuf;
use std::process::{Command, Output};

fn pathtrace() -> Command {
    Command::new(env!("CARGO_BIN_EXE_pathtrace"))
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pathtrace-aov-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn render(args: &[&str]) -> Output {
    let mut base = vec!["render", "cornell-box", "--size", "32x24", "--spp", "4", "--max-depth", "4", "--quiet"];
    base.extend_from_slice(args);
    pathtrace().args(&base).output().unwrap()
}

/// Every channel of the file's one layer, by name.
fn channels(path: &std::path::Path) -> HashMap<String, Vec<f32>> {
    let image = read_all_flat_layers_from_file(path).unwrap();
    assert_eq!(image.layer_data.len(), 1);
    let layer = &image.layer_data[0];
    assert_eq!((layer.size.width(), layer.size.height()), (32, 24));
    layer
        .channel_data
        .list
        .iter()
        .map(|c| {
            let values = match &c.sample_data {
                FlatSamples::F32(v) => v.clone(),
                other => panic!("{}: expected f32 samples, got {other:?}", c.name),
            };
            (c.name.to_string(), values)
        })
        .collect()
}

#[test]
fn exr_output_carries_the_buffers_as_named_channels() {
    let dir = temp_dir("exr");
    let (plain, with) = (dir.join("plain.exr"), dir.join("aov.exr"));
    let o = render(&["-o", plain.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = render(&["--aov", "albedo,normal,depth", "-o", with.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let c = channels(&with);
    let mut names: Vec<&str> = c.keys().map(String::as_str).collect();
    names.sort();
    assert_eq!(names, ["B", "G", "N.X", "N.Y", "N.Z", "R", "Z", "albedo.B", "albedo.G", "albedo.R"]);
    // The radiance is the same render with or without the buffers.
    let p = channels(&plain);
    for k in ["R", "G", "B"] {
        assert_eq!(p[k], c[k], "channel {k} changed");
    }
    let mut inside = 0;
    for (i, &depth) in c["Z"].iter().enumerate() {
        let n = [c["N.X"][i], c["N.Y"][i], c["N.Z"][i]];
        let len = n.iter().map(|v| v * v).sum::<f32>().sqrt();
        // At this wide aspect the corners see past the open box: no hit, no features.
        if depth == 0.0 {
            assert_eq!(len, 0.0, "pixel {i}: a normal without a hit");
            continue;
        }
        inside += 1;
        assert!(len > 0.2 && len <= 1.0 + 1e-5, "pixel {i}: |N| = {len}");
        for a in ["albedo.R", "albedo.G", "albedo.B"] {
            assert!((0.0..=1.0).contains(&c[a][i]), "pixel {i}: {a} = {}", c[a][i]);
        }
    }
    assert!(inside > 32 * 24 / 2, "only {inside} pixels see the box");
    // The walls are coloured: red on one side, green on the other.
    let red = (0..32 * 24).filter(|&i| c["albedo.R"][i] > 2.0 * c["albedo.G"][i]).count();
    let green = (0..32 * 24).filter(|&i| c["albedo.G"][i] > 2.0 * c["albedo.R"][i]).count();
    assert!(red > 20 && green > 20, "red {red}, green {green} pixels");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn png_and_pfm_output_get_sibling_files() {
    let dir = temp_dir("siblings");
    for (ext, sibling_ext) in [("png", "exr"), ("pfm", "pfm")] {
        let out = dir.join(format!("box.{ext}"));
        let o = render(&["--aov", "albedo,depth", "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        for aov in ["albedo", "depth"] {
            let path = dir.join(format!("box.{aov}.{sibling_ext}"));
            let img = pathtrace_scene::image_io::read_image(&path).unwrap();
            assert_eq!((img.width, img.height), (32, 24));
            assert!(img.mean().r > 0.0, "{} is black", path.display());
        }
        assert!(!dir.join(format!("box.normal.{sibling_ext}")).exists());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_unknown_buffer_is_a_usage_error() {
    let o = render(&["--aov", "albedo,motion", "-o", "/nonexistent/x.exr"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown feature buffer 'motion'"));
}

#[test]
fn denoise_without_the_library_exits_2_saying_how_to_get_it() {
    let dir = temp_dir("nolib");
    let out = dir.join("box.png");
    // With OIDN_DIR set the library is looked for there only; an empty folder has none.
    let o = pathtrace()
        .args(["render", "cornell-box", "--size", "8x8", "--spp", "1", "--denoise", "-o", out.to_str().unwrap()])
        .env("OIDN_DIR", &dir)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line expected: {err}");
    assert!(
        err.contains("--denoise") && err.contains("pip install pyoidn==2.5.1.0") && err.contains("OIDN_DIR"),
        "{err}"
    );
    assert!(!out.exists(), "no image is written");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_memory_check_counts_the_feature_buffers_before_allocating_anything() {
    // 32768² pixels (the largest --size) are over a hundred gigabytes with or without the buffers; what is checked is that the
    // refusal (exit 2, one line, nothing written) names the buffers and their bytes per pixel.
    let dir = temp_dir("memory");
    let out = dir.join("huge.exr");
    let plain = pathtrace()
        .args(["render", "cornell-box", "--size", "32768x32768", "--spp", "1", "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    let plain_err = String::from_utf8_lossy(&plain.stderr).to_string();
    assert_eq!(plain.status.code(), Some(2), "{plain_err}");
    let bytes_per_pixel = |err: &str| -> u64 {
        let at = err.find(" bytes per pixel").unwrap_or_else(|| panic!("no bytes per pixel in: {err}"));
        err[..at].rsplit('(').next().unwrap().parse().unwrap()
    };
    for (flags, what) in [
        (vec!["--aov", "depth"], "with feature buffers needs"),
        (vec!["--denoise"], "with feature buffers and denoising needs"),
    ] {
        let mut args =
            vec!["render", "cornell-box", "--size", "32768x32768", "--spp", "1", "-o", out.to_str().unwrap()];
        args.extend(flags);
        let o = pathtrace().args(&args).env("OIDN_DIR", &dir).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "one line expected: {err}");
        assert!(err.contains(what) && err.contains("--size"), "{err}");
        // The buffers' 128 bytes of sums and their three images: at least that much more.
        assert!(bytes_per_pixel(&err) >= bytes_per_pixel(&plain_err) + 128 + 36, "{err} vs {plain_err}");
    }
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
