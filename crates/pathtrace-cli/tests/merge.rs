//! `render --sample-range … --film-out` and `merge`: a render split into sample ranges and merged
//! in any order writes the same bytes as one render — its feature buffers and denoised image
//! too; merge refuses what does not belong together.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pathtrace-merge-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pathtrace")).args(args).output().unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Renders the Cornell box at 9 spp (samples `range` of them, if given) to `image` and `film`.
fn render(dir: &Path, name: &str, range: Option<&str>, threads: &str, seed: &str) -> (PathBuf, PathBuf) {
    render_with(dir, &format!("{name}.pfm"), range, threads, seed, &[])
}

/// [`render`] to the image file `image_name`, with `extra` options.
fn render_with(
    dir: &Path,
    image_name: &str,
    range: Option<&str>,
    threads: &str,
    seed: &str,
    extra: &[&str],
) -> (PathBuf, PathBuf) {
    let image = dir.join(image_name);
    let film = image.with_extension("ptfilm");
    let mut args = vec!["render", "cornell-box", "--size", "24x20", "--spp", "9", "--max-depth", "6", "-q"];
    args.extend(["--threads", threads, "--seed", seed, "-o", s(&image), "--film-out", s(&film)]);
    if let Some(r) = range {
        args.extend(["--sample-range", r]);
    }
    args.extend_from_slice(extra);
    let o = run(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (image, film)
}

/// Whether OIDN is found here; in CI (which installs it: .ci/run) it must be.
fn denoiser_available() -> bool {
    match pathtrace_denoise::Denoiser::new() {
        Ok(_) => true,
        Err(e) => {
            let ci = std::env::var("CI").is_ok_and(|v| v == "true" || v == "1");
            assert!(!ci, "CI=true but the denoiser is unavailable (.ci/run should install it): {e}");
            eprintln!("note: the --denoise half is skipped, {e}");
            false
        }
    }
}

fn error_line(o: &Output) -> String {
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    err
}

#[test]
fn three_ranges_merged_in_any_order_equal_the_whole_render_byte_for_byte() {
    let dir = temp_dir("roundtrip");
    let (whole_image, whole_film) = render(&dir, "whole", None, "2", "5");
    let (_, a) = render(&dir, "a", Some("0..2"), "1", "5");
    let (_, b) = render(&dir, "b", Some("2..7"), "2", "5");
    let (_, c) = render(&dir, "c", Some("7..9"), "1", "5");
    for (k, order) in [[&c, &a, &b], [&b, &c, &a]].iter().enumerate() {
        let (image, film) = (dir.join(format!("merged{k}.pfm")), dir.join(format!("merged{k}.ptfilm")));
        let o = run(&["merge", s(order[0]), s(order[1]), s(order[2]), "-o", s(&image), "--film-out", s(&film)]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stderr).contains("samples 0..9 of 9 spp"));
        assert_eq!(std::fs::read(&image).unwrap(), std::fs::read(&whole_image).unwrap(), "order {k}");
        assert_eq!(std::fs::read(&film).unwrap(), std::fs::read(&whole_film).unwrap(), "order {k}");
    }
    // A part is not the whole: the comparison above can fail.
    let (a_image, _) = (dir.join("a.pfm"), ());
    assert_ne!(std::fs::read(&a_image).unwrap(), std::fs::read(&whole_image).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn feature_buffers_and_the_denoised_image_of_merged_ranges_equal_the_whole_renders() {
    let dir = temp_dir("features");
    // Every buffer as EXR channels; denoised too where OIDN is found. The parts only need to
    // carry the buffers (any --aov does), and are rendered with other thread counts.
    let mut flags = vec!["--aov", "albedo,normal,depth"];
    if denoiser_available() {
        flags.push("--denoise");
    }
    let (whole_image, whole_film) = render_with(&dir, "whole.exr", None, "2", "5", &flags);
    let (_, a) = render_with(&dir, "a.pfm", Some("0..4"), "1", "5", &["--aov", "depth"]);
    let (_, b) = render_with(&dir, "b.png", Some("4..9"), "2", "5", &["--aov", "albedo"]);
    let (image, film) = (dir.join("merged.exr"), dir.join("merged.ptfilm"));
    let mut args = vec!["merge", s(&b), s(&a), "-o", s(&image), "--film-out", s(&film)];
    args.extend_from_slice(&flags);
    let o = run(&args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("with channels albedo, normal, depth"), "{err}");
    assert_eq!(flags.contains(&"--denoise"), err.contains("denoised in"), "{err}");
    assert_eq!(std::fs::read(&film).unwrap(), std::fs::read(&whole_film).unwrap(), "the films with their buffers");
    assert_eq!(std::fs::read(&image).unwrap(), std::fs::read(&whole_image).unwrap(), "the image and its channels");
    // The comparison can fail: half the samples give other buffers.
    let half = dir.join("half.exr");
    let o = run(&["merge", s(&a), "--partial", "-o", s(&half), "--aov", "albedo,normal,depth"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_ne!(std::fs::read(&half).unwrap(), std::fs::read(&whole_image).unwrap());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn merge_refuses_a_mix_with_and_without_feature_buffers_and_aov_from_films_without_them() {
    let dir = temp_dir("mixed");
    let (_, plain) = render(&dir, "plain", Some("0..4"), "1", "5");
    let (_, with) = render_with(&dir, "with.pfm", Some("4..9"), "1", "5", &["--aov", "normal"]);
    let out = dir.join("m.exr");
    let err = error_line(&run(&["merge", s(&plain), s(&with), "-o", s(&out)]));
    assert!(err.contains("with.ptfilm") && err.contains("it has feature buffers but the others have none"), "{err}");
    let err = error_line(&run(&["merge", s(&with), s(&plain), "-o", s(&out)]));
    assert!(err.contains("plain.ptfilm") && err.contains("it has no feature buffers but the others have"), "{err}");
    let (_, rest) = render(&dir, "rest", Some("4..9"), "1", "5");
    let err = error_line(&run(&["merge", s(&plain), s(&rest), "-o", s(&out), "--aov", "albedo"]));
    assert!(err.contains("the films have none") && err.contains("--aov"), "{err}");
    let err =
        error_line(&run(&["merge", s(&plain), s(&rest), "--film-out", s(&dir.join("f.ptfilm")), "--aov", "depth"]));
    assert!(err.contains("give -o"), "{err}");
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn merge_refuses_overlap_mismatch_and_garbage_and_names_missing_ranges() {
    let dir = temp_dir("refuse");
    let (_, a) = render(&dir, "a", Some("0..3"), "1", "5");
    let (_, overlapping) = render(&dir, "overlap", Some("2..4"), "1", "5");
    let (_, reseeded) = render(&dir, "seed", Some("3..9"), "1", "6");
    let (_, c) = render(&dir, "c", Some("6..9"), "1", "5");
    let out = dir.join("m.png");

    let err = error_line(&run(&["merge", s(&a), s(&overlapping), "-o", s(&out)]));
    assert!(err.contains("overlap.ptfilm") && err.contains("2..4") && err.contains("0..3"), "{err}");
    let err = error_line(&run(&["merge", s(&a), s(&reseeded), "-o", s(&out)]));
    assert!(err.contains("seed.ptfilm") && err.contains("another scene or other settings"), "{err}");
    let garbage = dir.join("garbage.ptfilm");
    std::fs::write(&garbage, b"not a film").unwrap();
    let err = error_line(&run(&["merge", s(&a), s(&garbage), "-o", s(&out)]));
    assert!(err.contains("garbage.ptfilm") && err.contains("not a pathtrace film"), "{err}");
    let mut truncated = std::fs::read(&a).unwrap();
    truncated.truncate(truncated.len() / 2);
    std::fs::write(dir.join("cut.ptfilm"), truncated).unwrap();
    let err = error_line(&run(&["merge", s(&dir.join("cut.ptfilm")), "-o", s(&out)]));
    assert!(err.contains("cut.ptfilm"), "{err}");

    // Missing samples: no image unless asked for; a film may still be written and completed later.
    let err = error_line(&run(&["merge", s(&c), s(&a), "-o", s(&out)]));
    assert!(err.contains("samples 3..6 of the 9 spp render are missing"), "{err}");
    assert!(!out.exists());
    let partial = dir.join("partial.ptfilm");
    let o = run(&["merge", s(&c), s(&a), "--film-out", s(&partial)]);
    assert!(o.status.success() && String::from_utf8_lossy(&o.stderr).contains("3..6"));
    let (_, middle) = render(&dir, "middle", Some("3..6"), "2", "5");
    let o = run(&["merge", s(&partial), s(&middle), "-o", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run(&["merge", s(&c), s(&a), "--partial", "-o", s(&out)]);
    assert!(o.status.success() && String::from_utf8_lossy(&o.stderr).contains("warning"));

    // Bad ranges are refused before rendering.
    let o = run(&["render", "cornell-box", "--spp", "4", "--sample-range", "2..9", "-o", s(&out)]);
    assert!(error_line(&o).contains("2..9"));
    let o = run(&["render", "cornell-box", "--spp", "4", "--sample-range", "3..1", "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}
