//! The analysis of `pathtrace bench bvh`: growth exponents fitted on log–log axes, and the
//! plots of docs/bvh.md. All plotting goes through [`plot`], one small function, so the
//! plotting back end can be swapped in one place.

use crate::bench_bvh::Row;
use crate::plot::{LinePlot, Series};
use std::path::{Path, PathBuf};

/// A quantity followed across triangle counts: its label and how to read it from a row.
struct Curve {
    label: &'static str,
    value: fn(&Row) -> Option<f64>,
}

fn per_ray_us(mrays: Option<f64>) -> Option<f64> {
    mrays.filter(|&r| r > 0.0).map(|r| 1.0 / r)
}

/// Time per incoherent closest-hit ray (µs, one thread), for each accelerator.
const TRACE: [Curve; 3] = [
    Curve { label: "brute force", value: |r| per_ray_us(r.get("brute_incoherent_closest_1t")) },
    Curve { label: "median", value: |r| per_ray_us(r.get("median_incoherent_closest_1t")) },
    Curve { label: "SAH", value: |r| per_ray_us(r.get("sah_incoherent_closest_1t")) },
];

const BUILD: [Curve; 3] = [
    Curve { label: "SAH 1 thread", value: |r| r.get("build_sah_serial_ms") },
    Curve { label: "SAH rayon", value: |r| r.get("build_sah_parallel_ms") },
    Curve { label: "median", value: |r| r.get("build_median_ms") },
];

const RATE: [Curve; 3] = [
    Curve { label: "SAH incoherent", value: |r| r.get("sah_incoherent_closest_1t") },
    Curve { label: "SAH camera", value: |r| r.get("sah_coherent_closest_1t") },
    Curve { label: "SAH shadow", value: |r| r.get("sah_incoherent_any_1t") },
];

/// Scenes in first-seen order.
fn scenes(rows: &[Row]) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for r in rows {
        if !out.contains(&r.scene) {
            out.push(r.scene);
        }
    }
    out
}

/// `(n, value)` points of one curve on one scene.
fn points(rows: &[Row], scene: &str, c: &Curve) -> Vec<(f64, f64)> {
    rows.iter()
        .filter(|r| r.scene == scene)
        .filter_map(|r| (c.value)(r).map(|v| (r.triangles as f64, v)))
        .filter(|&(_, v)| v > 0.0 && v.is_finite())
        .collect()
}

/// A fitted growth exponent: `value ∝ n^slope`.
pub struct Slope {
    pub scene: &'static str,
    pub metric: String,
    pub slope: f64,
    pub points: usize,
}

/// Least-squares slope of `log y` against `log n` over the points with `n ≥ 1000` (smaller
/// trees fit in the first-level cache and show fixed per-ray overheads, not growth), or over
/// all points if fewer than two are that large.
pub fn fit_slope(points: &[(f64, f64)]) -> Option<(f64, usize)> {
    let large: Vec<_> = points.iter().copied().filter(|&(n, _)| n >= 1000.0).collect();
    let pts = if large.len() >= 2 { large } else { points.to_vec() };
    if pts.len() < 2 {
        return None;
    }
    let k = pts.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = pts.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / k, ly.iter().sum::<f64>() / k);
    let sxx: f64 = lx.iter().map(|x| (x - mx).powi(2)).sum();
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    (sxx > 0.0).then(|| (sxy / sxx, pts.len()))
}

pub fn slopes(rows: &[Row]) -> Vec<Slope> {
    let mut out = Vec::new();
    let groups: [(&str, &[Curve]); 2] = [("time per ray", &TRACE), ("build time", &BUILD)];
    for scene in scenes(rows) {
        for (what, curves) in groups {
            for c in curves {
                if let Some((slope, points)) = fit_slope(&points(rows, scene, c)) {
                    out.push(Slope { scene, metric: format!("{what}, {}", c.label), slope, points });
                }
            }
        }
    }
    out
}

pub fn print_slopes(slopes: &[Slope]) {
    println!();
    println!("growth: fitted exponent k of value ∝ n^k (log–log least squares, n ≥ 1000)");
    for s in slopes {
        println!("{:<7} {:<28} k = {:>5.2} ({} sizes)", s.scene, s.metric, s.slope, s.points);
    }
}

/// The three plots of docs/bvh.md, written into `dir`.
pub fn write_plots(dir: &Path, rows: &[Row]) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let plots: [(&str, &str, &str, &[Curve]); 3] = [
        ("bvh-trace-time", "Time per incoherent ray (one thread)", "µs per ray", &TRACE),
        ("bvh-build-time", "BVH build time", "build time (ms)", &BUILD),
        ("bvh-rays-per-second", "Rays per second (one thread; shadow = incoherent any hit)", "million rays/s", &RATE),
    ];
    let mut written = Vec::new();
    for (file, title, y_label, curves) in plots {
        let series: Vec<Series> = scenes(rows)
            .into_iter()
            .flat_map(|scene| {
                curves
                    .iter()
                    .map(move |c| Series { label: format!("{scene} {}", c.label), points: points(rows, scene, c) })
            })
            .filter(|s| !s.points.is_empty())
            .collect();
        written.extend(plot(dir, file, title, "triangles", y_label, series)?);
    }
    Ok(written)
}

/// The only call into the plotting code: a log–log line plot saved as `dir/name.svg` and
/// `dir/name.png`.
fn plot(
    dir: &Path,
    name: &str,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: Vec<Series>,
) -> std::io::Result<[PathBuf; 2]> {
    let mut chart = LinePlot::log_log(title, x_label, y_label);
    chart.series = series;
    let svg = dir.join(format!("{name}.svg"));
    let png = dir.join(format!("{name}.png"));
    chart.write_svg(&svg).map_err(std::io::Error::other)?;
    chart.write_png(&png).map_err(std::io::Error::other)?;
    Ok([svg, png])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slopes_recover_power_laws() {
        let linear: Vec<_> = [1e2, 1e3, 1e4, 1e5].iter().map(|&n| (n, 3.0 * n)).collect();
        let (k, used) = fit_slope(&linear).unwrap();
        assert!((k - 1.0).abs() < 1e-9 && used == 3);
        let flat: Vec<_> = [1e3, 1e4].iter().map(|&n| (n, 5.0)).collect();
        assert!(fit_slope(&flat).unwrap().0.abs() < 1e-9);
        assert!(fit_slope(&[(1e3, 1.0)]).is_none());
    }
}
