//! `pathtrace bench`: renders the Cornell box several times and reports the median speed
//! (`pathtrace bench bvh` benchmarks the BVH alone, see `bench_bvh.rs`).

use crate::args::{BenchArgs, BenchTarget};
use crate::progress::format_rate;
use crate::render::settings_from;
use crate::stats_json::RenderStats;
use crate::{scene_arg, CliError};
use pathtrace::RenderSettings;
use std::process::ExitCode;
use std::sync::Arc;

const SCENE: &str = "cornell-box";

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

pub fn run(a: BenchArgs) -> Result<ExitCode, CliError> {
    if let Some(BenchTarget::Bvh(b)) = a.target {
        return crate::bench_bvh::run(b);
    }
    let loaded = scene_arg::load(SCENE)?;
    let mut defaults = loaded.defaults;
    defaults.max_depth = 8;
    let settings: RenderSettings = settings_from(&a.quality, Some(a.spp), None, &defaults);
    let scene = Arc::new(loaded.scene);
    let mut runs = Vec::new();
    for i in 0..a.runs {
        let outcome =
            pathtrace::render(Arc::clone(&scene), settings.clone()).map_err(|e| CliError::runtime(e.to_string()))?;
        let (spp, _) = outcome.film.spp_range();
        let stats = RenderStats::new(SCENE, &settings, &outcome.progress, spp, None, false);
        if !a.json {
            eprintln!(
                "run {}/{}: {:.2} s, {}, {}",
                i + 1,
                a.runs,
                stats.render_seconds,
                format_rate(stats.samples_per_second, "samples/s"),
                format_rate(stats.rays_per_second, "rays/s")
            );
        }
        runs.push(stats);
    }
    let med_sps = median(runs.iter().map(|r| r.samples_per_second).collect());
    let med_rps = median(runs.iter().map(|r| r.rays_per_second).collect());
    if a.json {
        let out = serde_json::json!({
            "scene": SCENE,
            "median_samples_per_second": med_sps,
            "median_rays_per_second": med_rps,
            "runs": runs,
        });
        println!("{}", serde_json::to_string_pretty(&out).map_err(|e| CliError::runtime(e.to_string()))?);
    } else {
        let r = &runs[0];
        let per_sample = |n: u64| n as f64 / r.samples.max(1) as f64;
        println!(
            "scene            {SCENE} {}×{}, {} spp, max depth {}, {}, {}",
            r.width, r.height, r.spp_target, r.max_depth, r.strategy, r.sampler
        );
        println!("threads          {}", r.threads);
        println!("samples/s        {} (median of {})", format_rate(med_sps, "samples/s"), a.runs);
        println!("rays/s           {} (median)", format_rate(med_rps, "rays/s"));
        println!(
            "rays per sample  {:.2} camera, {:.2} extension, {:.2} shadow",
            per_sample(r.camera_rays),
            per_sample(r.extension_rays),
            per_sample(r.shadow_rays)
        );
        println!("path length      {:.2} segments per sample", r.mean_path_length);
    }
    Ok(ExitCode::SUCCESS)
}
