//! `pathtrace view` end to end: under a virtual X server (Xvfb, software OpenGL) the window's own
//! framebuffer must show what `pathtrace render` writes; without a display it must fail cleanly.
#![cfg(feature = "viewer")]

use pathtrace::metrics::psnr_8bit;
use pathtrace_scene::image_io::read_image;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

fn pathtrace() -> Command {
    Command::new(env!("CARGO_BIN_EXE_pathtrace"))
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pathtrace-view-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The first directory on PATH holding `program`.
fn on_path(program: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path).map(|d| d.join(program)).find(|p| p.is_file())
}

/// True in CI (CI=true), where a missing Xvfb is a failure rather than a skip.
fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true" || v == "1")
}

#[test]
fn the_window_shows_what_render_writes() {
    let Some(xvfb_run) = on_path("xvfb-run") else {
        assert!(!in_ci(), "CI=true but xvfb-run (Debian package xvfb) is missing: .ci/run should install it");
        eprintln!("SKIP the_window_shows_what_render_writes: xvfb-run not found (apt-get install xvfb xauth)");
        return;
    };
    let dir = temp_dir("e2e");
    let reference = dir.join("render.png");
    let shot = dir.join("shot.png");
    let common = ["cornell-box", "--size", "256x256", "--spp", "64", "--seed", "1"];
    let o = pathtrace().arg("render").args(common).arg("-q").arg("-o").arg(&reference).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    let start = Instant::now();
    let o = Command::new(xvfb_run)
        .args(["-a", "-s", "-screen 0 1024x768x24"])
        .arg(env!("CARGO_BIN_EXE_pathtrace"))
        .arg("view")
        .args(common)
        .arg("--screenshot")
        .arg(&shot)
        .arg("--exit-when-done")
        // Mesa's software rasteriser: the same pixels on any machine, GPU or not.
        .env("LIBGL_ALWAYS_SOFTWARE", "1")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "view failed ({:?}): {stderr}", o.status);
    eprintln!("view under Xvfb took {:.1} s", start.elapsed().as_secs_f64());

    let window = read_image(&shot).unwrap_or_else(|e| panic!("no screenshot: {e}; stderr: {stderr}"));
    let rendered = read_image(&reference).unwrap();
    assert_eq!((window.width, window.height), (256, 256));
    let psnr = psnr_8bit(&window, &rendered).unwrap();
    eprintln!("window vs render: PSNR {psnr:.2} dB");
    assert!(psnr >= 40.0, "the window differs from `pathtrace render`: PSNR {psnr:.2} dB < 40");
    // The scene is not black: a blank framebuffer would not compare this well.
    assert!(rendered.mean().g > 0.05);
}

#[test]
fn without_a_display_view_fails_with_one_line_and_exit_code_2() {
    let o =
        pathtrace().args(["view", "cornell-box"]).env_remove("DISPLAY").env_remove("WAYLAND_DISPLAY").output().unwrap();
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("pathtrace render"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(Path::new(env!("CARGO_BIN_EXE_pathtrace")).exists());
}

#[test]
fn an_unreachable_display_fails_with_one_line_and_exit_code_2() {
    // A display name that no X server answers: the window cannot open.
    let o = pathtrace()
        .args(["view", "cornell-box", "--size", "16x16", "--spp", "1"])
        .env("DISPLAY", ":917")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("pathtrace render") && !stderr.contains("panicked"), "{stderr}");
}
