//! `pathtrace converge`: how fast each strategy × sampler × sampling (uniform or adaptive)
//! approaches a reference. Renders at 1, 2, 4, … spp (a fresh seed per level, so levels are
//! independent; adaptive levels spend that many samples per pixel on average), measures relative
//! MSE against the reference, and writes a CSV, log–log plots (SVG and PNG) of error against
//! samples and against time, and a table: each method's error at equal time and the time it needs
//! to reach a target error.

use crate::args::ConvergeArgs;
use crate::plot::{LinePlot, Series};
use crate::progress::format_rate;
use crate::{scene_arg, CliError};
use indicatif::{ProgressBar, ProgressStyle};
use pathtrace::film::Image;
use pathtrace::film::ToneMapSettings;
use pathtrace::integrator::Strategy;
use pathtrace::metrics;
use pathtrace::sampling::SamplerKind;
use pathtrace::{AdaptiveSettings, RenderSettings, Scene};
use pathtrace_scene::image_io::{read_image, write_image};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

/// One way of rendering that is measured.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Method {
    strategy: Strategy,
    sampler: SamplerKind,
    adaptive: bool,
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} + {}", self.strategy, self.sampler)?;
        if self.adaptive {
            f.write_str(" + adaptive")?;
        }
        Ok(())
    }
}

/// `uniform` or `adaptive`.
fn parse_sampling(s: &str) -> Result<bool, String> {
    match s.to_ascii_lowercase().as_str() {
        "uniform" => Ok(false),
        "adaptive" => Ok(true),
        _ => Err(format!("unknown sampling '{s}' (expected uniform or adaptive)")),
    }
}

/// One measurement.
struct Point {
    method: Method,
    spp: u32,
    seconds: f64,
    relative_mse: f64,
    mse: f64,
    psnr_8bit: f64,
}

fn parse_list<T: std::str::FromStr<Err = String>>(list: &str) -> Result<Vec<T>, CliError> {
    list.split(',').map(|s| s.trim().parse::<T>().map_err(CliError::usage)).collect()
}

fn render(
    scene: &Arc<Scene>,
    base: &RenderSettings,
    method: Method,
    min_spp: u32,
    spp: u32,
    seed: u64,
) -> Result<(Image, f64), CliError> {
    let mut s = base.clone();
    s.spp = spp;
    s.seed = seed;
    s.sampler = method.sampler;
    s.path.strategy = method.strategy;
    s.adaptive = method.adaptive.then(|| AdaptiveSettings { min_spp, ..Default::default() });
    let out = pathtrace::render(Arc::clone(scene), s)?;
    Ok((out.film.image(), out.progress.elapsed.as_secs_f64()))
}

pub fn run(a: ConvergeArgs) -> Result<ExitCode, CliError> {
    let strategies: Vec<Strategy> = parse_list(&a.strategies)?;
    let samplers: Vec<SamplerKind> = parse_list(&a.samplers)?;
    let samplings: Vec<bool> =
        a.sampling.split(',').map(|s| parse_sampling(s.trim()).map_err(CliError::usage)).collect::<Result<_, _>>()?;
    if !a.max_spp.is_power_of_two() {
        return Err(CliError::usage(format!("--max-spp {} must be a power of two", a.max_spp)));
    }
    let loaded = scene_arg::load(&a.scene)?;
    let d = loaded.defaults;
    let (width, height) = a.size.unwrap_or((d.width.min(256), d.height.min(256)));
    crate::memory::check_render_fits(width, height, Default::default())?;
    let mut base = RenderSettings { width, height, threads: a.threads.unwrap_or(0), ..RenderSettings::default() };
    base.path.max_depth = a.max_depth.unwrap_or(d.max_depth);
    if let Some(rr_depth) = d.rr_depth {
        base.path.rr_depth = rr_depth;
    }
    let out_dir = a.out.clone().unwrap_or_else(|| PathBuf::from(format!("converge-{}", scene_arg::stem(&a.scene))));
    std::fs::create_dir_all(&out_dir)
        .map_err(|e| CliError::usage(format!("cannot create {}: {e}", out_dir.display())))?;
    let scene = Arc::new(loaded.scene);

    let reference = match &a.reference {
        Some(path) => {
            let image = read_image(path).map_err(|e| CliError::usage(e.to_string()))?;
            pathtrace::metrics::check_finite(&image, "reference")
                .map_err(|e| CliError::usage(format!("{}: {e}", path.display())))?;
            image
        }
        None => {
            eprintln!("rendering the reference: mis + sobol, {} spp at {width}×{height}…", a.reference_spp);
            let method = Method { strategy: Strategy::Mis, sampler: SamplerKind::Sobol, adaptive: false };
            let image = render(&scene, &base, method, a.min_spp, a.reference_spp, a.seed ^ 0x5eed)?.0;
            // Kept so that further runs (other methods, more levels) can pass it as --reference.
            let path = out_dir.join("reference.exr");
            write_image(&path, &image, &ToneMapSettings::default()).map_err(|e| CliError::runtime(e.to_string()))?;
            image
        }
    };
    if (reference.width, reference.height) != (width, height) {
        return Err(CliError::usage(format!(
            "the reference is {}×{} but the renders are {width}×{height} (pass --size)",
            reference.width, reference.height
        )));
    }

    let levels: Vec<u32> = (0..=a.max_spp.trailing_zeros()).map(|k| 1 << k).collect();
    let per_method: u64 = levels.iter().map(|&s| s as u64).sum();
    let mut methods = Vec::new();
    for &strategy in &strategies {
        for &sampler in &samplers {
            for &adaptive in &samplings {
                methods.push(Method { strategy, sampler, adaptive });
            }
        }
    }
    let bar = ProgressBar::new(per_method * methods.len() as u64 * (width * height) as u64);
    if let Ok(style) = ProgressStyle::with_template("{spinner} [{bar:30}] {msg} · ETA {eta}") {
        bar.set_style(style.progress_chars("=> "));
    }
    let mut points = Vec::new();
    // Levels outside, methods inside: every method renders each level under the same machine load,
    // which keeps the equal-time comparison fair on a shared machine.
    for &spp in &levels {
        for &method in &methods {
            bar.set_message(format!("{method} at {spp} spp"));
            let (image, seconds) = render(&scene, &base, method, a.min_spp, spp, a.seed.wrapping_add(spp as u64))?;
            let m = metrics::compare(&image, &reference).map_err(|e| CliError::runtime(e.to_string()))?;
            points.push(Point {
                method,
                spp,
                seconds,
                relative_mse: m.relative_mse,
                mse: m.mse,
                psnr_8bit: m.psnr_8bit,
            });
            bar.inc(spp as u64 * (width * height) as u64);
        }
    }
    bar.finish_and_clear();

    // CSV.
    let mut csv = String::from("strategy,sampler,sampling,spp,seconds,relative_mse,mse,psnr_8bit_db\n");
    for p in &points {
        let m = p.method;
        let sampling = if m.adaptive { "adaptive" } else { "uniform" };
        let _ = writeln!(
            csv,
            "{},{},{sampling},{},{:.6},{:.6e},{:.6e},{:.3}",
            m.strategy, m.sampler, p.spp, p.seconds, p.relative_mse, p.mse, p.psnr_8bit
        );
    }
    write(&out_dir.join("convergence.csv"), &csv)?;

    // Plots.
    let series = |x: fn(&Point) -> f64| -> Vec<Series> {
        methods
            .iter()
            .map(|&m| Series {
                label: m.to_string(),
                points: points.iter().filter(|p| p.method == m).map(|p| (x(p), p.relative_mse)).collect(),
            })
            .collect()
    };
    let title = format!("{} {width}×{height}", a.scene);
    for (name, x_label, x) in [
        ("error-vs-spp", "samples per pixel", (|p: &Point| p.spp as f64) as fn(&Point) -> f64),
        ("error-vs-time", "render time (s)", |p: &Point| p.seconds),
    ] {
        let plot = LinePlot { series: series(x), ..LinePlot::log_log(&title, x_label, "relative MSE") };
        plot.write_svg(&out_dir.join(format!("{name}.svg"))).map_err(|e| CliError::runtime(e.to_string()))?;
        plot.write_png(&out_dir.join(format!("{name}.png"))).map_err(|e| CliError::runtime(e.to_string()))?;
    }

    // Equal time: every method's error interpolated at the longest time all of them reached.
    let curve = |m: Method| -> Vec<&Point> { points.iter().filter(|p| p.method == m).collect() };
    let common_time = methods.iter().map(|&m| curve(m).last().map_or(0.0, |p| p.seconds)).fold(f64::INFINITY, f64::min);
    let mut table = format!(
        "| method | relative MSE at {} spp | relative MSE at {common_time:.3} s | time to relative MSE {:.0e} |\n\
         | --- | --- | --- | --- |\n",
        a.max_spp, a.target_error
    );
    for &m in &methods {
        let mine = curve(m);
        let last = mine.last().map_or(f64::NAN, |p| p.relative_mse);
        let at_time = log_log_at(&mine, |p| p.seconds, |p| p.relative_mse, common_time)
            .map_or("–".into(), |e| format!("{e:.3e}"));
        // Time to reach the target error: log–log interpolation between the two levels around it.
        let reach = mine.windows(2).find_map(|w| {
            let (p, q) = (w[0], w[1]);
            (p.relative_mse > a.target_error && q.relative_mse <= a.target_error)
                .then(|| log_log_at(&[p, q], |p| p.relative_mse, |p| p.seconds, a.target_error))
                .flatten()
        });
        let reach = match (mine.first(), reach) {
            (Some(p), _) if p.relative_mse <= a.target_error => format!("≤ {:.3} s", p.seconds),
            (_, Some(t)) => format!("{t:.3} s"),
            _ => "not reached".into(),
        };
        let _ = writeln!(table, "| {m} | {last:.3e} | {at_time} | {reach} |");
    }
    write(&out_dir.join("table.md"), &table)?;
    print!("{table}");
    let total: f64 = points.iter().map(|p| p.seconds).sum();
    let samples: f64 = points.iter().map(|p| p.spp as f64 * (width * height) as f64).sum();
    eprintln!(
        "wrote {}/convergence.csv, error-vs-{{spp,time}}.{{svg,png}}, table.md{} ({:.1} s rendering, {})",
        out_dir.display(),
        if a.reference.is_none() { ", reference.exr" } else { "" },
        total,
        format_rate(samples / total.max(1e-9), "samples/s")
    );
    Ok(ExitCode::SUCCESS)
}

/// `y` at `x = at` on the piecewise-linear log–log curve through `points` (in order of `x`);
/// `None` outside its range.
fn log_log_at(points: &[&Point], x: fn(&Point) -> f64, y: fn(&Point) -> f64, at: f64) -> Option<f64> {
    points.windows(2).find_map(|w| {
        let (x0, x1) = (x(w[0]), x(w[1]));
        let (lo, hi) = (x0.min(x1), x0.max(x1));
        if !(lo..=hi).contains(&at) || x0 <= 0.0 || x1 <= 0.0 || y(w[0]) <= 0.0 || y(w[1]) <= 0.0 {
            return None;
        }
        let f = if x1 == x0 { 0.0 } else { (at.ln() - x0.ln()) / (x1.ln() - x0.ln()) };
        Some((y(w[0]).ln() + f * (y(w[1]).ln() - y(w[0]).ln())).exp())
    })
}

fn write(path: &std::path::Path, text: &str) -> Result<(), CliError> {
    std::fs::write(path, text).map_err(|e| CliError::runtime(format!("cannot write {}: {e}", path.display())))
}
