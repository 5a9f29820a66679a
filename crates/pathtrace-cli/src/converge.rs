//! `pathtrace converge`: how fast each strategy × sampler approaches a reference. Renders at
//! 1, 2, 4, … spp (a fresh seed per level, so levels are independent), measures relative MSE
//! against the reference, and writes a CSV, log–log plots (SVG and PNG) of error against samples and
//! against time, and the time each method needs to reach a target error.

use crate::args::ConvergeArgs;
use crate::plot::{LinePlot, Series};
use crate::progress::format_rate;
use crate::{scene_arg, CliError};
use indicatif::{ProgressBar, ProgressStyle};
use pathtrace::film::Image;
use pathtrace::integrator::Strategy;
use pathtrace::metrics;
use pathtrace::sampling::SamplerKind;
use pathtrace::{RenderSettings, Scene};
use pathtrace_scene::image_io::read_image;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

/// One measurement.
struct Point {
    strategy: Strategy,
    sampler: SamplerKind,
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
    strategy: Strategy,
    sampler: SamplerKind,
    spp: u32,
    seed: u64,
) -> Result<(Image, f64), CliError> {
    let mut s = base.clone();
    s.spp = spp;
    s.seed = seed;
    s.sampler = sampler;
    s.path.strategy = strategy;
    let out = pathtrace::render(Arc::clone(scene), s).map_err(|e| CliError::runtime(e.to_string()))?;
    Ok((out.film.image(), out.progress.elapsed.as_secs_f64()))
}

pub fn run(a: ConvergeArgs) -> Result<ExitCode, CliError> {
    let strategies: Vec<Strategy> = parse_list(&a.strategies)?;
    let samplers: Vec<SamplerKind> = parse_list(&a.samplers)?;
    if !a.max_spp.is_power_of_two() {
        return Err(CliError::usage(format!("--max-spp {} must be a power of two", a.max_spp)));
    }
    let loaded = scene_arg::load(&a.scene)?;
    let d = loaded.defaults;
    let (width, height) = a.size.unwrap_or((d.width.min(256), d.height.min(256)));
    let mut base = RenderSettings { width, height, threads: a.threads.unwrap_or(0), ..RenderSettings::default() };
    base.path.max_depth = a.max_depth.unwrap_or(d.max_depth);
    let out_dir = a.out.clone().unwrap_or_else(|| PathBuf::from(format!("converge-{}", scene_arg::stem(&a.scene))));
    std::fs::create_dir_all(&out_dir)
        .map_err(|e| CliError::usage(format!("cannot create {}: {e}", out_dir.display())))?;
    let scene = Arc::new(loaded.scene);

    let reference = match &a.reference {
        Some(path) => read_image(path).map_err(|e| CliError::usage(e.to_string()))?,
        None => {
            eprintln!("rendering the reference: mis + sobol, {} spp at {width}×{height}…", a.reference_spp);
            render(&scene, &base, Strategy::Mis, SamplerKind::Sobol, a.reference_spp, a.seed ^ 0x5eed)?.0
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
    let methods: Vec<(Strategy, SamplerKind)> =
        strategies.iter().flat_map(|&st| samplers.iter().map(move |&sa| (st, sa))).collect();
    let bar = ProgressBar::new(per_method * methods.len() as u64 * (width * height) as u64);
    if let Ok(style) = ProgressStyle::with_template("{spinner} [{bar:30}] {msg} · ETA {eta}") {
        bar.set_style(style.progress_chars("=> "));
    }
    let mut points = Vec::new();
    for &(strategy, sampler) in &methods {
        for &spp in &levels {
            bar.set_message(format!("{strategy}+{sampler} at {spp} spp"));
            let (image, seconds) = render(&scene, &base, strategy, sampler, spp, a.seed.wrapping_add(spp as u64))?;
            let m = metrics::compare(&image, &reference).map_err(|e| CliError::runtime(e.to_string()))?;
            points.push(Point {
                strategy,
                sampler,
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
    let mut csv = String::from("strategy,sampler,spp,seconds,relative_mse,mse,psnr_8bit_db\n");
    for p in &points {
        let _ = writeln!(
            csv,
            "{},{},{},{:.6},{:.6e},{:.6e},{:.3}",
            p.strategy, p.sampler, p.spp, p.seconds, p.relative_mse, p.mse, p.psnr_8bit
        );
    }
    write(&out_dir.join("convergence.csv"), &csv)?;

    // Plots.
    let series = |x: fn(&Point) -> f64| -> Vec<Series> {
        methods
            .iter()
            .map(|&(st, sa)| Series {
                label: format!("{st} + {sa}"),
                points: points
                    .iter()
                    .filter(|p| p.strategy == st && p.sampler == sa)
                    .map(|p| (x(p), p.relative_mse))
                    .collect(),
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

    // Time to reach the target error: log–log interpolation between the two levels around it.
    let mut table = format!(
        "| method | relative MSE at {} spp | time to relative MSE {:.0e} |\n| --- | --- | --- |\n",
        a.max_spp, a.target_error
    );
    for &(st, sa) in &methods {
        let mine: Vec<&Point> = points.iter().filter(|p| p.strategy == st && p.sampler == sa).collect();
        let last = mine.last().map_or(f64::NAN, |p| p.relative_mse);
        let reach = mine.windows(2).find_map(|w| {
            let (p, q) = (w[0], w[1]);
            (p.relative_mse > a.target_error && q.relative_mse <= a.target_error).then(|| {
                let f = (a.target_error.ln() - p.relative_mse.ln()) / (q.relative_mse.ln() - p.relative_mse.ln());
                (p.seconds.ln() + f * (q.seconds.ln() - p.seconds.ln())).exp()
            })
        });
        let reach = match (mine.first(), reach) {
            (Some(p), _) if p.relative_mse <= a.target_error => format!("≤ {:.3} s", p.seconds),
            (_, Some(t)) => format!("{t:.3} s"),
            _ => "not reached".into(),
        };
        let _ = writeln!(table, "| {st} + {sa} | {last:.3e} | {reach} |");
    }
    write(&out_dir.join("table.md"), &table)?;
    print!("{table}");
    let total: f64 = points.iter().map(|p| p.seconds).sum();
    let samples: f64 = points.iter().map(|p| p.spp as f64 * (width * height) as f64).sum();
    eprintln!(
        "wrote {}/convergence.csv, error-vs-{{spp,time}}.{{svg,png}}, table.md ({:.1} s rendering, {})",
        out_dir.display(),
        total,
        format_rate(samples / total.max(1e-9), "samples/s")
    );
    Ok(ExitCode::SUCCESS)
}

fn write(path: &std::path::Path, text: &str) -> Result<(), CliError> {
    std::fs::write(path, text).map_err(|e| CliError::runtime(format!("cannot write {}: {e}", path.display())))
}
