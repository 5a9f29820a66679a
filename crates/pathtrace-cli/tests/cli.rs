//! The `pathtrace` binary end to end: outputs, statistics, errors and exit codes, Ctrl-C.

use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn pathtrace() -> Command {
    Command::new(env!("CARGO_BIN_EXE_pathtrace"))
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pathtrace-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(args: &[&str]) -> Output {
    pathtrace().args(args).output().unwrap()
}

#[test]
fn renders_png_exr_and_pfm_with_statistics() {
    let dir = temp_dir("formats");
    for ext in ["png", "exr", "pfm"] {
        let out = dir.join(format!("box.{ext}"));
        let stats = dir.join(format!("stats-{ext}.json"));
        let o = run(&[
            "render",
            "cornell-box",
            "--size",
            "32x24",
            "--spp",
            "4",
            "--max-depth",
            "4",
            "-o",
            out.to_str().unwrap(),
            "--stats-json",
            stats.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let img = pathtrace_scene::image_io::read_image(&out).unwrap();
        assert_eq!((img.width, img.height), (32, 24));
        assert!(img.mean().g > 0.01, "image is black");
        let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
        assert_eq!(json["spp"], 4);
        assert_eq!(json["samples"], 32 * 24 * 4);
        assert_eq!(json["camera_rays"], 32 * 24 * 4);
        assert!(json["samples_per_second"].as_f64().unwrap() > 0.0);
        assert_eq!(json["interrupted"], false);
        let summary = String::from_utf8_lossy(&o.stderr);
        assert!(summary.contains("4 spp") && summary.contains("samples/s"), "{summary}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn same_seed_same_image_different_seed_different_image() {
    let dir = temp_dir("seeds");
    let render = |seed: &str, threads: &str, name: &str| {
        let out = dir.join(name);
        let o = run(&[
            "render",
            "--size",
            "16x16",
            "--spp",
            "3",
            "--seed",
            seed,
            "--threads",
            threads,
            "-q",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success());
        std::fs::read(out).unwrap()
    };
    assert_eq!(render("1", "1", "a.pfm"), render("1", "2", "b.pfm"));
    assert_ne!(render("1", "2", "c.pfm"), render("2", "2", "d.pfm"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_arguments_give_one_line_and_exit_code_2() {
    let dir = temp_dir("errors");
    let cases: Vec<Vec<String>> = vec![
        vec!["render".into(), "--size".into(), "12".into()],
        vec!["render".into(), "--spp".into(), "0".into()],
        vec!["render".into(), "--strategy".into(), "magic".into()],
        vec!["render".into(), "--sampler".into(), "sobol9".into()],
        vec!["render".into(), "--light-selection".into(), "random".into()],
        vec!["render".into(), "--max-depth".into(), "-5".into()],
        vec!["render".into(), "--time".into(), "-1".into()],
        vec!["render".into(), "--spp".into(), "4".into(), "--time".into(), "2".into()],
        vec!["render".into(), "no-such-scene".into()],
        vec!["render".into(), "-o".into(), dir.join("x.jpg").to_string_lossy().into()],
        vec!["render".into(), "-o".into(), dir.join("missing/x.png").to_string_lossy().into()],
        vec!["render".into(), "--frobnicate".into()],
        vec!["explode".into()],
        vec!["compare".into()],
    ];
    for args in cases {
        let o = pathtrace().args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: expected one line, got:\n{err}");
        assert!(err.starts_with("error"), "{args:?}: {err}");
    }
    assert!(std::fs::read_dir(&dir).unwrap().next().is_none(), "no output may be written on error");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn light_selection_is_an_option() {
    let dir = temp_dir("selection");
    for mode in ["power", "uniform"] {
        let out = dir.join(format!("{mode}.pfm"));
        let o = run(&[
            "render",
            "--size",
            "16x16",
            "--spp",
            "2",
            "--light-selection",
            mode,
            "-q",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{mode}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(pathtrace_scene::image_io::read_image(&out).unwrap().mean().g > 0.01, "{mode}: black image");
    }
    let o = run(&["render", "--help"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("--light-selection"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn help_explains_the_commands() {
    let o = run(&["--help"]);
    assert!(o.status.success());
    let help = String::from_utf8_lossy(&o.stdout);
    assert!(help.contains("render") && help.contains("bench"));
    let o = run(&["render", "--help"]);
    let help = String::from_utf8_lossy(&o.stdout);
    for word in ["--spp", "--time", "--strategy", "--sampler", "--max-depth", "Ctrl-C"] {
        assert!(help.contains(word), "render --help lacks {word}");
    }
}

/// SIGINT (Ctrl-C), and the SIGTERM and SIGHUP that farms (Slurm, Kubernetes, systemd, `timeout`)
/// send: the render stops, writes what it has and says how many spp it holds.
#[cfg(unix)]
fn a_signal_writes_the_image_rendered_so_far(signal: &str) {
    let dir = temp_dir(&format!("interrupt-{signal}"));
    let out = dir.join("partial.exr");
    let stats = dir.join("stats.json");
    let mut child = pathtrace()
        .args([
            "render",
            "--size",
            "64x64",
            "--spp",
            "100000",
            "-o",
            out.to_str().unwrap(),
            "--stats-json",
            stats.to_str().unwrap(),
        ])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(1500));
    let status = Command::new("kill").args([&format!("-{signal}"), &child.id().to_string()]).status().unwrap();
    assert!(status.success());
    let start = Instant::now();
    let output = loop {
        if let Some(_status) = child.try_wait().unwrap() {
            break child.wait_with_output().unwrap();
        }
        assert!(start.elapsed() < Duration::from_secs(30), "render did not stop after SIG{signal}");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert_eq!(output.status.code(), Some(130));
    let err = String::from_utf8_lossy(&output.stderr);
    assert!(err.contains("interrupted") && err.contains("spp"), "{err}");
    let img = pathtrace_scene::image_io::read_image(&out).unwrap();
    assert!(img.mean().g > 0.01);
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(json["interrupted"], true);
    let spp = json["spp"].as_u64().unwrap();
    assert!((1..100_000).contains(&spp), "{spp}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(unix)]
#[test]
fn ctrl_c_writes_the_image_rendered_so_far() {
    a_signal_writes_the_image_rendered_so_far("INT");
}

#[cfg(unix)]
#[test]
fn sigterm_writes_the_image_rendered_so_far() {
    a_signal_writes_the_image_rendered_so_far("TERM");
}

#[cfg(unix)]
#[test]
fn sighup_writes_the_image_rendered_so_far() {
    a_signal_writes_the_image_rendered_so_far("HUP");
}

/// The bench suite's quick mode on the Cornell box: the JSON report's fields, the check against
/// the stored reference (PASS), and `--compare` of two reports.
#[test]
fn bench_suite_reports_checks_and_compares() {
    let dir = temp_dir("bench");
    let o = run(&["bench", "--quick", "--scenes", "cornell-d8", "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["schema"], "pathtrace-bench-suite/1");
    assert!(json["machine"]["logical_cpus"].as_u64().unwrap() >= 1);
    assert!(json["date_utc"].as_str().unwrap().ends_with('Z'));
    let scene = &json["scenes"][0];
    assert_eq!(scene["name"], "cornell-d8");
    let m = &scene["result"];
    assert_eq!(m["max_depth"], 8);
    assert_eq!((m["width"].as_u64(), m["height"].as_u64()), (Some(128), Some(128)));
    assert!(m["samples_per_second"].as_f64().unwrap() > 0.0);
    assert_eq!(m["camera_rays_per_sample"].as_f64().unwrap(), 1.0);
    let ext = m["extension_rays_per_sample"].as_f64().unwrap();
    assert!(ext > 0.5 && ext < 7.0, "{ext}");
    assert!((m["mean_path_length"].as_f64().unwrap() - 1.0 - ext).abs() < 1e-9);
    assert!(m["peak_rss_mib"].as_f64().unwrap() > 1.0);
    assert_eq!(m["peak_rss_scope"], "child process");
    assert!(m["final_rel_mse"].as_f64().unwrap() > 0.0);
    assert_eq!(m["check"]["status"], "PASS", "{}", m["check"]);
    let a = dir.join("a.json");
    std::fs::write(&a, &o.stdout).unwrap();
    let o = run(&["bench", "--compare", a.to_str().unwrap(), a.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(table.lines().any(|l| l.starts_with("cornell-d8") && l.contains("1.000×")), "{table}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The suite's scenes from ../shared/scenes load and pass the check against their stored
/// references: the teapot (a PLY under point lights) and Bitterli's Veach scene (loaded with
/// `-D integrator=path`, as the Mitsuba comparison renders it). Skipped with a note when ../shared/scenes is absent.
#[test]
fn bench_suite_runs_the_shared_scenes_against_their_references() {
    let shared = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes");
    if !shared.is_dir() {
        eprintln!("skipped: {} is absent", shared.display());
        return;
    }
    let o = run(&["bench", "--quick", "--scenes", "teapot,veach-mis-bitterli", "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let scenes = json["scenes"].as_array().unwrap();
    let names: Vec<&str> = scenes.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["teapot", "veach-mis-bitterli"]);
    for s in scenes {
        assert_eq!(s["result"]["check"]["status"], "PASS", "{}: {}", s["name"], s["result"]["check"]);
    }
    // The Veach scene keeps its own settings: the file's path tracer of max depth 3.
    assert_eq!(scenes[1]["result"]["max_depth"], 3, "{}", scenes[1]["result"]);
}

/// An exposure that is not a finite number is a usage error (exit 2) for every command that
/// takes one, before any work.
#[test]
fn a_non_finite_exposure_is_refused() {
    for args in [
        &["render", "cornell-box", "--spp", "1", "--exposure", "nan", "-o", "x.png"][..],
        &["merge", "missing.ptfilm", "--exposure", "inf", "-o", "x.png"][..],
    ] {
        let o = run(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("--exposure must be a finite number of stops"), "{args:?}: {err}");
    }
}

/// A wrong reference (the Cornell box 5% too bright) fails the check with a non-zero exit code.
#[test]
fn bench_check_fails_against_a_wrong_reference() {
    let dir = temp_dir("bench-wrong");
    let refs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../benches/references");
    let mut img = pathtrace_scene::image_io::read_linear_image(&refs.join("cornell-d8.exr")).unwrap();
    img.pixels.iter_mut().for_each(|p| *p *= 1.05);
    let settings = pathtrace::film::ToneMapSettings::default();
    pathtrace_scene::image_io::write_image(&dir.join("cornell-d8.exr"), &img, &settings).unwrap();
    std::fs::copy(refs.join("references.json"), dir.join("references.json")).unwrap();
    let o = run(&["bench", "--quick", "--scenes", "cornell-d8", "--references", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(table.contains("FAIL"), "{table}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn compare_reports_metrics_writes_a_diff_and_rejects_mismatched_sizes() {
    let dir = temp_dir("compare");
    let a = dir.join("a.exr");
    let b = dir.join("b.exr");
    let small = dir.join("small.pfm");
    for (path, spp, size) in [(&a, "2", "24x24"), (&b, "64", "24x24"), (&small, "1", "8x8")] {
        let o = run(&["render", "--size", size, "--spp", spp, "-q", "-o", path.to_str().unwrap()]);
        assert!(o.status.success());
    }
    let diff = dir.join("diff.png");
    let o = run(&["compare", a.to_str().unwrap(), b.to_str().unwrap(), "--diff", diff.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let psnr = json["psnr_8bit_db"].as_f64().unwrap();
    assert!(psnr > 5.0 && psnr < 60.0, "{psnr}");
    assert!(json["mse"].as_f64().unwrap() > 0.0);
    assert!(json["changed_pixels"].as_u64().unwrap() > 0);
    assert!(pathtrace_scene::image_io::read_image(&diff).is_ok());
    // An image against itself: zero error, infinite PSNR (null in JSON), SSIM 1.
    let o = run(&["compare", a.to_str().unwrap(), a.to_str().unwrap(), "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["mse"], 0.0);
    assert!(json["psnr_8bit_db"].is_null());
    assert!((json["ssim"].as_f64().unwrap() - 1.0).abs() < 1e-12);
    // Different sizes: one line, exit code 2.
    let o = run(&["compare", a.to_str().unwrap(), small.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("differ in size") && err.trim_end().lines().count() == 1, "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn converge_writes_csv_plots_and_a_table() {
    let dir = temp_dir("converge");
    let o = run(&[
        "converge",
        "--size",
        "16x16",
        "--max-spp",
        "4",
        "--reference-spp",
        "64",
        "--strategies",
        "bsdf,mis",
        "--samplers",
        "independent,sobol",
        "--sampling",
        "uniform,adaptive",
        "--min-spp",
        "2",
        "--max-depth",
        "4",
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(dir.join("convergence.csv")).unwrap();
    // Header + 2 strategies × 2 samplers × 2 samplings × 3 levels (1, 2, 4 spp).
    assert_eq!(csv.lines().count(), 1 + 24, "{csv}");
    assert!(csv.contains(",sobol,adaptive,4,"), "{csv}");
    for name in ["error-vs-spp", "error-vs-time"] {
        let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap();
        // One line per method and its legend entry.
        assert!(svg.contains("mis + sobol + adaptive") && svg.contains("bsdf + independent"), "{name}");
        let png = std::fs::read(dir.join(format!("{name}.png"))).unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }
    let table = std::fs::read_to_string(dir.join("table.md")).unwrap();
    assert!(table.contains("mis + sobol + adaptive") && table.contains("bsdf + independent"));
    assert!(table.contains(" s |"), "{table}");
    assert!(dir.join("reference.exr").is_file());
    let o = run(&["converge", "--max-spp", "3"]);
    assert_eq!(o.status.code(), Some(2));
    let o = run(&["converge", "--sampling", "clever"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("uniform or adaptive"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn render_stops_at_a_target_error_and_reports_it() {
    let dir = temp_dir("target-error");
    let out = dir.join("box.exr");
    let stats = dir.join("stats.json");
    let o = run(&[
        "render",
        "cornell-box",
        "--size",
        "24x24",
        "--max-depth",
        "3",
        "--target-error",
        "0.2",
        "--min-spp",
        "4",
        "-o",
        out.to_str().unwrap(),
        "--stats-json",
        stats.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(json["adaptive"], true);
    assert_eq!(json["target_error"], 0.2);
    let reached = json["relative_error_estimate"].as_f64().unwrap();
    assert!(reached <= 0.2 && reached > 0.0, "{reached}");
    assert!(json["mean_spp"].as_f64().unwrap() >= 4.0);
    let summary = String::from_utf8_lossy(&o.stderr);
    assert!(summary.contains("estimated error") && summary.contains("target 20.00%"), "{summary}");
    // --adaptive with --spp spends that many samples per pixel on average.
    let counts = dir.join("spp.pfm");
    let o = run(&["render", "--size", "16x16", "--max-depth", "3", "--spp", "8", "--adaptive", "--min-spp", "4"]
        .iter()
        .copied()
        .chain(["-o", out.to_str().unwrap(), "--stats-json", stats.to_str().unwrap()])
        .chain(["--spp-image", counts.to_str().unwrap()])
        .collect::<Vec<_>>());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(json["samples"], 16 * 16 * 8);
    // The sample-count image: the busiest pixel is 1, the others at least min_spp / max.
    let spp = pathtrace_scene::image_io::read_image(&counts).unwrap();
    let max = spp.pixels.iter().map(|p| p.g).fold(0.0f32, f32::max);
    let min = spp.pixels.iter().map(|p| p.g).fold(1.0f32, f32::min);
    assert!(max == 1.0 && min > 0.0 && min < 1.0, "{min}..{max}");
    let o = run(&["render", "--target-error", "-1"]);
    assert_eq!(o.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `bench bvh --instances`: the mesh alone, its instances and flattened copies, with the
/// instances' memory a small multiple of one mesh (here 8 copies of a 200-triangle sphere).
#[test]
fn bench_bvh_instances_compares_with_the_mesh_and_its_copies() {
    let o = run(&["bench", "bvh", "--instances", "8", "--max-tris", "200", "--rays", "2000", "--runs", "1"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    for row in ["| mesh alone |", "| instances |", "| copies (flattened) |"] {
        assert!(out.lines().any(|l| l.starts_with(row)), "{row} missing:\n{out}");
    }
    let ratio: f64 = out
        .split("instances use ")
        .nth(1)
        .and_then(|s| s.split('×').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no memory ratio in:\n{out}"));
    assert!(ratio > 1.0 && ratio < 8.0, "{ratio}");
}
