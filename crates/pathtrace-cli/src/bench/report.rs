//! The suite's results: the JSON schema of `bench --json`, the readable table, and
//! `bench --compare OLD NEW`.

use super::check::Check;
use super::system::Machine;
use crate::CliError;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Identifies the JSON layout, so `--compare` can refuse files it does not understand.
pub const SCHEMA: &str = "pathtrace-bench-suite/1";

/// A whole suite run.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SuiteReport {
    pub schema: String,
    pub version: String,
    pub commit: Option<String>,
    pub date_utc: String,
    pub machine: Machine,
    pub quick: bool,
    pub runs: u32,
    pub target_rel_mse: f64,
    pub scenes: Vec<SceneReport>,
}

/// One scene: measured, or skipped with a note.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SceneReport {
    pub name: String,
    pub description: String,
    pub skipped: Option<String>,
    pub result: Option<Measurement>,
}

/// Medians over the runs of one scene.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Measurement {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub max_depth: i32,
    pub threads: usize,
    pub render_seconds: f64,
    pub samples_per_second: f64,
    /// Every run's samples/s, in order.
    pub samples_per_second_runs: Vec<f64>,
    pub rays_per_second: f64,
    pub camera_rays_per_second: f64,
    pub extension_rays_per_second: f64,
    pub shadow_rays_per_second: f64,
    pub camera_rays_per_sample: f64,
    pub extension_rays_per_sample: f64,
    pub shadow_rays_per_sample: f64,
    /// Path segments per sample: (camera + extension rays) / samples.
    pub mean_path_length: f64,
    /// Peak resident set (VmHWM) in MiB.
    pub peak_rss_mib: Option<f64>,
    /// What the peak covers: "child process" (this scene alone: load, BVH, renders) or
    /// "process" (everything the process did before, with `--in-process`).
    pub peak_rss_scope: String,
    /// Seconds to reach the target relative MSE against the reference (median over runs);
    /// `None` without a reference or if a run never got there.
    pub time_to_target_seconds: Option<f64>,
    /// Relative MSE of the final image against the reference (median over runs).
    pub final_rel_mse: Option<f64>,
    pub reference_spp: Option<u32>,
    pub check: Check,
    pub scaling: Option<Scaling>,
}

/// Samples/s with one thread against all threads.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Scaling {
    pub samples_per_second_1_thread: f64,
    pub threads: usize,
    /// All threads' samples/s over one thread's.
    pub ratio: f64,
}

fn mega(x: f64) -> String {
    format!("{:.3}", x / 1e6)
}

fn opt(x: Option<f64>, digits: usize) -> String {
    x.map_or("–".to_string(), |v| format!("{v:.digits$}"))
}

/// The readable table (stdout).
pub fn print_table(r: &SuiteReport) {
    let load = r.machine.load_average.map_or("?".into(), |l| format!("{:.1} {:.1} {:.1}", l[0], l[1], l[2]));
    println!(
        "pathtrace {} ({}) · {} · {} logical CPUs · load {} · {}",
        r.version,
        r.commit.as_deref().map_or("unknown commit", |c| &c[..c.len().min(12)]),
        r.machine.cpu_model.as_deref().unwrap_or("unknown CPU"),
        r.machine.logical_cpus,
        load,
        r.date_utc
    );
    println!(
        "{:<20} {:>5} {:>9} {:>8} {:>24} {:>6} {:>8} {:>10} {:>8} {:>7}",
        "scene",
        "spp",
        "Msmp/s",
        "Mrays/s",
        "cam / ext / shadow M/s",
        "len",
        "peak MiB",
        "t(relMSE)",
        "scaling",
        "check"
    );
    for s in &r.scenes {
        let Some(m) = &s.result else {
            println!("{:<20} {}", s.name, s.skipped.as_deref().unwrap_or("skipped"));
            continue;
        };
        let rays = format!(
            "{} / {} / {}",
            mega(m.camera_rays_per_second),
            mega(m.extension_rays_per_second),
            mega(m.shadow_rays_per_second)
        );
        let scaling = m.scaling.as_ref().map(|x| format!("{:.2}×", x.ratio));
        println!(
            "{:<20} {:>5} {:>9} {:>8} {:>24} {:>6.2} {:>8} {:>10} {:>8} {:>7}",
            s.name,
            m.spp,
            mega(m.samples_per_second),
            mega(m.rays_per_second),
            rays,
            m.mean_path_length,
            opt(m.peak_rss_mib, 0),
            m.time_to_target_seconds.map_or("–".into(), |t| format!("{t:.3} s")),
            scaling.as_deref().unwrap_or("–"),
            m.check.status
        );
    }
    println!(
        "median of {} run(s); t(relMSE) = time to relative MSE {:.0e} against benches/references; peak = VmHWM of {}",
        r.runs,
        r.target_rel_mse,
        r.scenes.iter().find_map(|s| s.result.as_ref()).map_or("each scene's process", |m| m.peak_rss_scope.as_str())
    );
    for s in &r.scenes {
        if let Some(m) = &s.result {
            if m.check.failed() || m.check.status == "SKIP" {
                let detail = match (&m.check.note, m.check.max_z, m.check.threshold) {
                    (Some(note), _, _) => note.clone(),
                    (None, Some(z), Some(t)) => {
                        format!(
                            "{} of {} regions beyond |z| {t:.2} (max {z:.2})",
                            m.check.failing_regions, m.check.regions
                        )
                    }
                    _ => String::new(),
                };
                println!("{}: check {}: {detail}", s.name, m.check.status);
            }
        }
    }
}

fn read_report(path: &Path) -> Result<SuiteReport, CliError> {
    let text =
        std::fs::read_to_string(path).map_err(|e| CliError::usage(format!("cannot read {}: {e}", path.display())))?;
    let report: SuiteReport = serde_json::from_str(&text).map_err(|e| {
        CliError::usage(format!("{}:{}:{}: not a bench suite report: {e}", path.display(), e.line(), e.column()))
    })?;
    if report.schema != SCHEMA {
        return Err(CliError::usage(format!("{}: schema '{}' is not '{SCHEMA}'", path.display(), report.schema)));
    }
    Ok(report)
}

fn ratio(new: f64, old: f64) -> String {
    if old > 0.0 && new.is_finite() {
        format!("{:.3}×", new / old)
    } else {
        "–".into()
    }
}

/// `bench --compare OLD NEW`: per scene, new / old samples/s and rays/s, old / new time to the
/// target error (so > 1 is faster everywhere), new / old peak memory.
pub fn compare(old_path: &Path, new_path: &Path) -> Result<(), CliError> {
    let (old, new) = (read_report(old_path)?, read_report(new_path)?);
    let short = |c: &Option<String>| c.as_deref().map_or("?".to_string(), |c| c[..c.len().min(12)].to_string());
    println!("old: {} {} ({})", old_path.display(), short(&old.commit), old.date_utc);
    println!("new: {} {} ({})", new_path.display(), short(&new.commit), new.date_utc);
    println!(
        "{:<20} {:>18} {:>10} {:>10} {:>22} {:>10} {:>10}",
        "scene", "Msmp/s old → new", "samples/s", "rays/s", "t(relMSE) old → new", "speedup", "memory"
    );
    for n in &new.scenes {
        let Some(nm) = &n.result else { continue };
        let Some(om) = old.scenes.iter().find(|o| o.name == n.name).and_then(|o| o.result.as_ref()) else {
            println!("{:<20} only in the new report", n.name);
            continue;
        };
        let times = format!("{} → {}", opt(om.time_to_target_seconds, 3), opt(nm.time_to_target_seconds, 3));
        let speedup = match (om.time_to_target_seconds, nm.time_to_target_seconds) {
            (Some(o), Some(n)) => ratio(o, n),
            _ => "–".into(),
        };
        let memory = match (om.peak_rss_mib, nm.peak_rss_mib) {
            (Some(o), Some(n)) => ratio(n, o),
            _ => "–".into(),
        };
        println!(
            "{:<20} {:>18} {:>10} {:>10} {:>22} {:>10} {:>10}",
            n.name,
            format!("{} → {}", mega(om.samples_per_second), mega(nm.samples_per_second)),
            ratio(nm.samples_per_second, om.samples_per_second),
            ratio(nm.rays_per_second, om.rays_per_second),
            times,
            speedup,
            memory
        );
    }
    println!("ratios: samples/s, rays/s and memory new / old; speedup = old / new time to the target relative MSE");
    Ok(())
}
