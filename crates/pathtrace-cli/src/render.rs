//! `pathtrace render`.

use crate::aov_output::FeatureOutputs;
use crate::args::{AdaptiveArgs, QualityArgs, RenderArgs};
use crate::destination::{check_destination, check_image_destination};
use crate::interrupt::Interrupt;
use crate::memory::Extras;
use crate::progress::{format_rate, Bar};
use crate::stats_json::RenderStats;
use crate::{scene_arg, CliError};
use pathtrace::film::{engine_build, render_key, Film, Fnv64, Image, RangedFilm, ToneMapSettings};
use pathtrace::math::Rgb;
use pathtrace::{AdaptiveSettings, RenderSession, RenderSettings};
use pathtrace_scene::film_file::{scene_source_key, write_film, SceneSource};
use pathtrace_scene::image_io::write_image;
use pathtrace_scene::{RenderDefaults, RenderOverrides};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

/// Render settings: each from the command line if given, else from the scene, else the
/// engine's default (the rule is the scene crate's, shared with the Python module).
pub fn settings_from(q: &QualityArgs, spp: Option<u32>, time: Option<f64>, d: &RenderDefaults) -> RenderSettings {
    d.settings(&RenderOverrides {
        size: q.size,
        spp,
        time: time.map(Duration::from_secs_f64),
        max_depth: q.max_depth,
        rr_depth: q.rr_depth,
        strategy: q.strategy,
        sampler: q.sampler,
        filter: q.filter.clone(),
        seed: q.seed,
        threads: q.threads,
        kernel: q.kernel,
    })
}

/// Adaptive settings from `--adaptive`, `--target-error` and `--min-spp`; with a target error and
/// no time limit, an unset `--spp` means no cap.
fn with_adaptive(mut s: RenderSettings, a: &AdaptiveArgs, spp_given: bool) -> RenderSettings {
    if a.adaptive || a.target_error.is_some() {
        s.adaptive = Some(AdaptiveSettings { min_spp: a.min_spp, target_error: a.target_error, ..Default::default() });
        if a.target_error.is_some() && !spp_given && s.time_limit.is_none() {
            s.spp = 0;
        }
    }
    s
}

/// Each pixel's sample count over the largest count, as grey (linear; sRGB-encoded in a PNG).
fn spp_image(film: &Film, spp_max: u32) -> Image {
    let scale = 1.0 / spp_max.max(1) as f32;
    let pixels = film.pixels().iter().map(|p| Rgb::splat(p.count as f32 * scale)).collect();
    Image { width: film.width(), height: film.height(), pixels }
}

/// Pixels that hold no sample (all of theirs were dropped, or none was taken): written black.
fn pixels_without_samples(film: &Film) -> usize {
    film.pixels().iter().filter(|p| p.count == 0).count()
}

/// The scene half of a film's key: the scene file's bytes and defines (or the built-in name),
/// and the light selection mode if given, which changes samples.
fn scene_key(a: &RenderArgs) -> Result<u64, CliError> {
    let bytes;
    let source = if scene_arg::is_file(&a.scene) || !a.defines.is_empty() {
        bytes = std::fs::read(&a.scene).map_err(|e| CliError::usage(format!("{}: cannot read: {e}", a.scene)))?;
        SceneSource::File { bytes: &bytes, defines: &a.defines }
    } else {
        SceneSource::Builtin(&a.scene)
    };
    let key = scene_source_key(&source);
    // Without --light-selection the key is the source's alone, as the Python module's is, so
    // parts from either merge.
    Ok(match a.quality.light_selection {
        None => key,
        Some(mode) => Fnv64::default().write(&key.to_le_bytes()).field(format!("{mode:?}").as_bytes()).finish(),
    })
}

pub fn run(a: RenderArgs) -> Result<ExitCode, CliError> {
    let mut loaded = scene_arg::load_with(&a.scene, &a.defines)?;
    if let Some(mode) = a.quality.light_selection {
        loaded.scene.lights.set_selection(mode);
    }
    let mut settings =
        with_adaptive(settings_from(&a.quality, a.spp, a.time, &loaded.defaults), &a.adaptive, a.spp.is_some());
    settings.features = a.features.wanted();
    settings.sample_range = a.sample_range;
    if loaded.scene.lights.has_delta() && !settings.path.strategy.is_mis() {
        eprintln!(
            "warning: the scene has point or spot lights, which only the mis strategy (or mis-balance) can see (next-event \
             estimation); with --strategy {} they render black",
            settings.path.strategy
        );
    }
    let extras = Extras { features: settings.features, denoise: a.features.denoise };
    crate::memory::check_render_fits(settings.width, settings.height, extras)?;
    let output = a.output.clone().unwrap_or_else(|| PathBuf::from(format!("{}.png", scene_arg::stem(&a.scene))));
    let feature_outputs = FeatureOutputs::prepare(&a.features, &output)?;
    if let Some(path) = &a.adaptive.spp_image {
        check_image_destination(path, "--spp-image")?;
    }
    if let Some(path) = &a.stats_json {
        check_destination(path, "--stats-json")?;
    }
    let film_key = match &a.film_out {
        Some(path) => {
            check_destination(path, "--film-out")?;
            Some(render_key(scene_key(&a)?, &settings))
        }
        None => None,
    };
    let tone = a.tone.settings()?;

    let interrupt = Interrupt::install();
    let session = RenderSession::start(Arc::new(loaded.scene), settings.clone())?;
    let pixels = settings.width as u64 * settings.height as u64;
    let bar = Bar::new(pixels, settings.spp, settings.time_limit, a.quiet);
    loop {
        // Wakes every 100 ms for the bar and Ctrl-C, and at once when the render ends.
        let ended = session.wait_finished(Duration::from_millis(100));
        bar.update(&session.progress());
        if ended {
            break;
        }
        if interrupt.triggered() {
            session.cancel();
        }
    }
    let outcome = session.wait();
    bar.finish();
    let interrupted = interrupt.triggered();

    let written = feature_outputs.write(outcome.film.image(), &tone, outcome.features.as_ref())?;

    if let (Some(path), Some(key)) = (&a.film_out, film_key) {
        if interrupted {
            eprintln!(
                "note: interrupted, so {} is not written (a film file holds whole sample ranges only)",
                path.display()
            );
        } else {
            let part = RangedFilm::new(outcome.film.clone(), key, engine_build(), settings.spp, settings.samples())
                .with_features(outcome.features.clone());
            write_film(path, &part).map_err(|e| CliError::runtime(e.to_string()))?;
        }
    }

    let (spp_min, spp_max) = outcome.film.spp_range();
    if !interrupted && outcome.progress.dropped_samples > 0 {
        // Black is not an estimate of such a pixel: say so rather than let it pass as one.
        let empty = pixels_without_samples(&outcome.film);
        if empty > 0 {
            eprintln!(
                "warning: {empty} pixels had every sample dropped as NaN/Inf and are written black (a biased value); \
                 look for extreme values in the scene"
            );
        }
    }
    if let Some(path) = &a.adaptive.spp_image {
        write_image(path, &spp_image(&outcome.film, spp_max), &ToneMapSettings::default())
            .map_err(|e| CliError::runtime(e.to_string()))?;
    }
    let noise = outcome.film.relative_rms_error_estimate();
    let p = &outcome.progress;
    if !a.quiet {
        let held = if spp_min == spp_max { format!("{spp_min} spp") } else { format!("{spp_min}–{spp_max} spp") };
        let target = settings.adaptive.and_then(|ad| ad.target_error);
        let noise_text = match (noise, target) {
            (Some(n), Some(t)) => format!(", estimated error {:.2}% (target {:.2}%)", 100.0 * n, 100.0 * t),
            (Some(n), None) => format!(", estimated error {:.2}%", 100.0 * n),
            _ => String::new(),
        };
        let held = if settings.adaptive.is_some() {
            let mean = outcome.film.total_samples() as f64 / pixels.max(1) as f64;
            format!("{held}, {mean:.1} on average, adaptive")
        } else {
            held
        };
        let dropped = if p.dropped_samples > 0 {
            format!(", {} NaN/Inf samples dropped", p.dropped_samples)
        } else {
            String::new()
        };
        let prefix = if interrupted { "interrupted: " } else { "" };
        let denoised = written.denoised_text();
        let also = written.also_text(feature_outputs.aovs());
        eprintln!(
            "{prefix}wrote {}{also} — {}×{}, {held} ({}, {}), {:.1} s, {}, {}{noise_text}{dropped}{denoised}",
            output.display(),
            settings.width,
            settings.height,
            settings.path.strategy,
            settings.sampler,
            p.elapsed.as_secs_f64(),
            format_rate(p.samples_per_second, "samples/s"),
            format_rate(p.rays_per_second, "rays/s"),
        );
    }
    if let Some(path) = &a.stats_json {
        let stats = RenderStats::new(&a.scene, &settings, p, spp_min, noise, interrupted);
        let json = serde_json::to_string_pretty(&stats).map_err(|e| CliError::runtime(e.to_string()))?;
        std::fs::write(path, json + "\n")
            .map_err(|e| CliError::runtime(format!("cannot write {}: {e}", path.display())))?;
    }
    Ok(if interrupted { ExitCode::from(crate::interrupt::EXIT_INTERRUPTED) } else { ExitCode::SUCCESS })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixels_whose_samples_were_all_dropped_are_counted() {
        let mut film = Film::new(3, 1);
        film.add_sample(0, 0, Rgb::splat(1.0));
        film.add_sample(1, 0, Rgb::splat(f32::NAN));
        assert_eq!(pixels_without_samples(&film), 2);
        assert_eq!(film.dropped_samples, 1);
    }
}
