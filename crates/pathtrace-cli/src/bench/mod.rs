//! `pathtrace bench`: the benchmark suite (scenes.rs) — speed, ray counts, path length, peak
//! memory, time to a target error against stored references, and a correctness check of each
//! image against its reference. Each scene is measured in a child process of this binary so
//! its peak memory is its own. `bench bvh` benchmarks the BVH alone (`bench_bvh.rs`).

mod check;
mod references;
mod report;
mod run;
mod scenes;
mod system;

use crate::args::{BenchArgs, BenchTarget};
use crate::stats_json::effective_threads;
use crate::CliError;
use check::{check_against_reference, Check};
use report::{Measurement, Scaling, SceneReport, SuiteReport, SCHEMA};
use run::{median, render_run, time_to_reach, Run};
use scenes::{SuiteScene, BENCH_SEED};
use std::process::{Command, ExitCode, Stdio};
use std::sync::Arc;

/// Options of one suite run, resolved from the arguments.
struct Options<'a> {
    a: &'a BenchArgs,
    runs: u32,
    threads: usize,
    references: std::path::PathBuf,
}

pub fn run(a: BenchArgs) -> Result<ExitCode, CliError> {
    if let Some(BenchTarget::Bvh(b)) = a.target {
        return crate::bench_bvh::run(b);
    }
    if let Some(files) = &a.compare {
        report::compare(&files[0], &files[1])?;
        return Ok(ExitCode::SUCCESS);
    }
    let selected = scenes::select(&a.scenes)?;
    let references = a.references.clone().unwrap_or_else(references::default_dir);
    let threads = effective_threads(a.threads.unwrap_or(0));
    if a.make_references {
        references::make(&references, &selected, a.reference_spp, threads)?;
        return Ok(ExitCode::SUCCESS);
    }
    let runs = a.runs.unwrap_or(if a.quick { 1 } else { 3 });
    let options = Options { a: &a, runs, threads, references };
    let report = SuiteReport {
        schema: SCHEMA.to_string(),
        version: env!("CARGO_PKG_VERSION").to_string(),
        commit: system::source_commit(),
        date_utc: system::utc_now(),
        machine: system::Machine::current(),
        quick: a.quick,
        runs,
        target_rel_mse: a.target_rel_mse,
        scenes: selected
            .iter()
            .map(|s| if a.in_process { measure(s, &options, selected.len()) } else { measure_in_child(s, &options) })
            .collect::<Result<_, _>>()?,
    };
    if a.json {
        println!("{}", serde_json::to_string_pretty(&report).map_err(|e| CliError::runtime(e.to_string()))?);
    } else {
        report::print_table(&report);
    }
    let failed: Vec<&str> = report
        .scenes
        .iter()
        .filter(|s| s.result.as_ref().is_some_and(|m| m.check.failed()))
        .map(|s| s.name.as_str())
        .collect();
    if failed.is_empty() {
        Ok(ExitCode::SUCCESS)
    } else {
        eprintln!("error: the image of {} disagrees with its reference (check FAIL)", failed.join(", "));
        Ok(ExitCode::from(1))
    }
}

/// Runs this binary on one scene (`--in-process --json`) and takes its report, so the peak
/// resident set it reports covers that scene alone.
fn measure_in_child(scene: &SuiteScene, o: &Options) -> Result<SceneReport, CliError> {
    let exe = std::env::current_exe().map_err(|e| CliError::runtime(format!("cannot find this binary: {e}")))?;
    let mut cmd = Command::new(exe);
    cmd.args(["bench", "--in-process", "--json", "--scenes", scene.name]);
    cmd.args(["--runs", &o.runs.to_string(), "--threads", &o.threads.to_string()]);
    cmd.args(["--target-rel-mse", &o.a.target_rel_mse.to_string()]);
    cmd.arg("--references").arg(&o.references);
    if o.a.quick {
        cmd.arg("--quick");
    }
    if o.a.scaling {
        cmd.arg("--scaling");
    }
    if let Some(spp) = o.a.spp {
        cmd.args(["--spp", &spp.to_string()]);
    }
    let out = cmd
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| CliError::runtime(format!("cannot run the bench of {}: {e}", scene.name)))?;
    let child: SuiteReport = serde_json::from_slice(&out.stdout).map_err(|e| {
        CliError::runtime(format!("the bench of {} failed ({}) without a report: {e}", scene.name, out.status))
    })?;
    let mut reports = child.scenes;
    match reports.pop() {
        Some(mut r) if reports.is_empty() => {
            if let Some(m) = &mut r.result {
                m.peak_rss_scope = "child process".to_string();
            }
            Ok(r)
        }
        _ => Err(CliError::runtime(format!("the bench of {} reported no single scene", scene.name))),
    }
}

/// Measures one scene in this process: `runs` timed renders (medians), the check of the first
/// run's image, and with `--scaling` the same runs on one thread.
fn measure(scene: &SuiteScene, o: &Options, scenes_in_process: usize) -> Result<SceneReport, CliError> {
    let mut report = SceneReport {
        name: scene.name.to_string(),
        description: scene.description.to_string(),
        skipped: None,
        result: None,
    };
    let loaded = match scene.load()? {
        Ok(l) => l,
        Err(note) => {
            eprintln!("{}: {note}", scene.name);
            report.skipped = Some(note);
            return Ok(report);
        }
    };
    let reference = references::load(&o.references, scene);
    let spp = o.a.spp.unwrap_or(if o.a.quick { scene.quick_spp } else { scene.spp });
    let settings = scene.settings(&loaded, spp, BENCH_SEED, o.threads);
    let scene_arc = Arc::new(loaded.scene);
    let image = reference.as_ref().ok().map(|(img, _)| img);
    let mut runs: Vec<Run> = Vec::new();
    for i in 0..o.runs {
        let r = render_run(Arc::clone(&scene_arc), settings.clone(), image)?;
        eprintln!(
            "{}: run {}/{}: {:.2} s, {:.3} M samples/s",
            scene.name,
            i + 1,
            o.runs,
            r.progress.elapsed.as_secs_f64(),
            r.progress.samples_per_second / 1e6
        );
        runs.push(r);
    }
    let check = match &reference {
        Ok((img, info)) => check_against_reference(&runs[0].film, img, info.spp),
        Err(note) => Check::skipped(note.clone()),
    };
    let scaling = if o.a.scaling { Some(scaling(&scene_arc, &settings, o, &runs)?) } else { None };
    let med = |f: &dyn Fn(&Run) -> f64| median(runs.iter().map(f).collect());
    let per_second = |n: fn(&Run) -> u64| med(&|r: &Run| n(r) as f64 / r.progress.elapsed.as_secs_f64().max(1e-9));
    let per_sample = |n: u64, r: &Run| n as f64 / r.progress.samples.max(1) as f64;
    let crossings: Option<Vec<f64>> = runs.iter().map(|r| time_to_reach(&r.curve, o.a.target_rel_mse)).collect();
    let r0 = &runs[0];
    let rays = r0.progress.rays;
    report.result = Some(Measurement {
        width: settings.width,
        height: settings.height,
        spp,
        max_depth: settings.path.max_depth,
        threads: o.threads,
        render_seconds: med(&|r: &Run| r.progress.elapsed.as_secs_f64()),
        samples_per_second: med(&|r: &Run| r.progress.samples_per_second),
        samples_per_second_runs: runs.iter().map(|r| r.progress.samples_per_second).collect(),
        rays_per_second: med(&|r: &Run| r.progress.rays_per_second),
        camera_rays_per_second: per_second(|r| r.progress.rays.camera_rays),
        extension_rays_per_second: per_second(|r| r.progress.rays.extension_rays),
        shadow_rays_per_second: per_second(|r| r.progress.rays.shadow_rays),
        camera_rays_per_sample: per_sample(rays.camera_rays, r0),
        extension_rays_per_sample: per_sample(rays.extension_rays, r0),
        shadow_rays_per_sample: per_sample(rays.shadow_rays, r0),
        mean_path_length: per_sample(rays.camera_rays + rays.extension_rays, r0),
        peak_rss_mib: system::peak_rss_mib(),
        peak_rss_scope: if scenes_in_process == 1 { "process" } else { "process (cumulative over the scenes)" }
            .to_string(),
        time_to_target_seconds: crossings.map(median),
        final_rel_mse: reference.is_ok().then(|| med(&|r: &Run| r.curve.last().map_or(f64::NAN, |c| c.1))),
        reference_spp: reference.as_ref().ok().map(|(_, info)| info.spp),
        check,
        scaling,
    });
    Ok(report)
}

/// The same runs on one thread: all threads' median samples/s over one thread's.
fn scaling(
    scene: &Arc<pathtrace::Scene>,
    settings: &pathtrace::RenderSettings,
    o: &Options,
    all: &[Run],
) -> Result<Scaling, CliError> {
    let one = pathtrace::RenderSettings { threads: 1, ..settings.clone() };
    let mut sps = Vec::new();
    for _ in 0..o.runs {
        sps.push(render_run(Arc::clone(scene), one.clone(), None)?.progress.samples_per_second);
    }
    let one_thread = median(sps);
    let all_threads = median(all.iter().map(|r| r.progress.samples_per_second).collect());
    eprintln!("scaling: 1 thread {:.3} M samples/s, {} threads {:.3}", one_thread / 1e6, o.threads, all_threads / 1e6);
    Ok(Scaling { samples_per_second_1_thread: one_thread, threads: o.threads, ratio: all_threads / one_thread })
}
