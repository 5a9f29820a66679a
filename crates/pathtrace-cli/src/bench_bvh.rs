//! `pathtrace bench bvh`: build time, memory per triangle and rays per second of the BVH on
//! generated meshes from 10² to 10⁷ triangles, next to the median-split baseline and brute
//! force. Writes a table (or JSON), optionally a CSV, plots and an export for the Embree
//! comparison (benches/peers/bvh_embree.py). docs/bvh.md discusses the results.

use crate::args::BvhBenchArgs;
use crate::bvh_meshes::{self, MeshKind};
use crate::bvh_rays::{self, BruteTracer, BvhTracer, Query, RaySet, Tracer};
use crate::cpu_clock::Clock;
use crate::{bvh_plots, CliError};
use pathtrace::accel::{BruteForce, BuildOptions, Bvh, Packable, SplitMethod};
use pathtrace::math::{Aabb, Transform, Vec3};
use pathtrace::shape::{MeshGeometry, TriangleMesh};
use std::collections::HashMap;
use std::io::Write;
use std::process::ExitCode;

/// One measured quantity: its CSV/JSON name and what it is.
pub struct Metric {
    pub name: &'static str,
    pub doc: &'static str,
}

const fn m(name: &'static str, doc: &'static str) -> Metric {
    Metric { name, doc }
}

/// Every column, in table order. Rays/s are millions per second; "1t" is one thread, "mt"
/// every thread of the pool.
pub const METRICS: &[Metric] = &[
    m("build_sah_serial_ms", "SAH build, one thread (ms)"),
    m("build_sah_parallel_ms", "SAH build on rayon (ms)"),
    m("build_median_ms", "median-split build, one thread (ms)"),
    m("bytes_per_tri", "mesh + BVH bytes per triangle"),
    m("mesh_bytes_per_tri", "compact mesh (shared vertices + indices) bytes per triangle"),
    m("bvh_bytes_per_tri", "BVH bytes per triangle"),
    m("wide_node_bytes_per_tri", "BVH eight-wide nodes bytes per triangle"),
    m("leaf_bytes_per_tri", "BVH leaves and packets bytes per triangle"),
    m("sah_incoherent_closest_1t", "SAH, incoherent closest hit, 1 thread (Mrays/s)"),
    m("sah_incoherent_closest_mt", "SAH, incoherent closest hit, all threads (Mrays/s)"),
    m("sah_incoherent_any_1t", "SAH, incoherent any hit, 1 thread (Mrays/s)"),
    m("sah_incoherent_any_mt", "SAH, incoherent any hit, all threads (Mrays/s)"),
    m("sah_coherent_closest_1t", "SAH, camera closest hit, 1 thread (Mrays/s)"),
    m("sah_coherent_closest_mt", "SAH, camera closest hit, all threads (Mrays/s)"),
    m("sah_coherent_any_1t", "SAH, camera any hit, 1 thread (Mrays/s)"),
    m("sah_coherent_any_mt", "SAH, camera any hit, all threads (Mrays/s)"),
    m("median_incoherent_closest_1t", "median split, incoherent closest hit, 1 thread (Mrays/s)"),
    m("median_coherent_closest_1t", "median split, camera closest hit, 1 thread (Mrays/s)"),
    m("brute_incoherent_closest_1t", "brute force, incoherent closest hit, 1 thread (Mrays/s)"),
    m("brute_coherent_closest_1t", "brute force, camera closest hit, 1 thread (Mrays/s)"),
];

/// The measurements of one mesh at one size.
pub struct Row {
    pub scene: &'static str,
    pub triangles: usize,
    pub values: Vec<(&'static str, f64)>,
}

impl Row {
    pub fn get(&self, name: &str) -> Option<f64> {
        self.values.iter().find(|(n, _)| *n == name).map(|&(_, v)| v)
    }
}

pub fn median_of(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Triangle counts from `min` to `max`, `steps` per decade (10^(k/steps), rounded).
fn sizes(min: usize, max: usize, steps: u32) -> Vec<usize> {
    let mut out = Vec::new();
    let mut k = ((min.max(1) as f64).log10() * steps as f64).ceil() as i32;
    loop {
        let n = 10f64.powf(k as f64 / steps as f64).round() as usize;
        if n > max {
            return out;
        }
        if n >= min && out.last() != Some(&n) {
            out.push(n);
        }
        k += 1;
    }
}

/// The bunny's own size (bunny.ply of the Mitsuba scenes): its sizes are this times 4^k.
const BUNNY_TRIANGLES: usize = 69_451;

/// Triangle counts to measure for a mesh: [`sizes`], except for the bunny, whose counts are
/// its subdivision levels in `[min, 1.25 · max]` (so `--max-tris 1e6` includes 1.1M).
fn counts(kind: MeshKind, a: &BvhBenchArgs) -> Vec<usize> {
    if kind != MeshKind::Bunny {
        return sizes(a.min_tris, a.max_tris, a.steps_per_decade);
    }
    std::iter::successors(Some(BUNNY_TRIANGLES), |n| Some(4 * n))
        .take_while(|&n| n as f64 <= 1.25 * a.max_tris as f64)
        .filter(|&n| n >= a.min_tris)
        .collect()
}

/// The mesh as the renderer stores it (shared vertices and indices), its triangles' bounds and
/// packet kinds. Degenerate triangles are dropped.
pub struct Input {
    pub mesh: MeshGeometry,
    pub bounds: Vec<Aabb>,
    pub kinds: Vec<Packable>,
    pub scene_bounds: Aabb,
}

/// An indexed mesh from a triangle list: corners with the same coordinates (bit for bit) become
/// one shared vertex, as in the mesh files the triangles came from.
pub fn indexed(tris: &[[Vec3; 3]]) -> TriangleMesh {
    let mut ids: HashMap<[u32; 3], u32> = HashMap::with_capacity(tris.len());
    let mut mesh = TriangleMesh::default();
    for tri in tris {
        mesh.indices.push(tri.map(|p| {
            *ids.entry(p.to_array().map(f32::to_bits)).or_insert_with(|| {
                mesh.positions.push(p);
                mesh.positions.len() as u32 - 1
            })
        }));
    }
    mesh
}

pub fn input(tris: &[[Vec3; 3]]) -> Input {
    let (mesh, _) = MeshGeometry::new(&indexed(tris), &Transform::IDENTITY).unwrap_or_default();
    let ids = 0..mesh.len() as u32;
    let bounds: Vec<Aabb> = ids.clone().map(|i| mesh.bounds(i)).collect();
    let scene_bounds = bounds.iter().fold(Aabb::EMPTY, |a, b| a.union(*b));
    let kinds = ids.map(|i| Packable::Triangle(mesh.triangle(i))).collect();
    Input { mesh, bounds, kinds, scene_bounds }
}

pub fn mesh(kind: MeshKind, n: usize) -> Result<Vec<[Vec3; 3]>, String> {
    match kind {
        MeshKind::Sphere => Ok(bvh_meshes::sphere(n)),
        MeshKind::Soup => Ok(bvh_meshes::soup(n, n as u64)),
        MeshKind::Bunny => bvh_meshes::bunny(n),
    }
}

/// Median build time (seconds) of `runs` builds, and the last tree. Serial builds are timed
/// by `clock`, parallel ones by the wall clock.
pub fn timed_build(inp: &Input, opts: &BuildOptions, runs: u32, clock: Clock) -> (f64, Bvh) {
    let clock = if opts.parallel_above == usize::MAX { clock } else { Clock::Wall };
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..runs {
        let (built, seconds) =
            clock.time_repeated(bvh_rays::MIN_SECONDS, || Bvh::build_with(&inp.bounds, &inp.kinds, opts));
        times.push(seconds);
        last = Some(built);
    }
    (median_of(times), last.unwrap_or_default())
}

/// Median Mrays/s of `runs` traces.
#[allow(clippy::too_many_arguments)]
fn timed_trace(
    pool: &rayon::ThreadPool,
    clock: Clock,
    t: &dyn Tracer,
    set: &RaySet,
    count: usize,
    q: Query,
    parallel: bool,
    runs: u32,
) -> f64 {
    let rates: Vec<f64> =
        (0..runs).map(|_| pool.install(|| bvh_rays::trace(t, set, count, q, parallel, clock)).0).collect();
    median_of(rates) / 1e6
}

struct Settings<'a> {
    a: &'a BvhBenchArgs,
    clock: Clock,
    sah: BuildOptions,
    pool: rayon::ThreadPool,
}

fn measure(s: &Settings, scene: &'static str, inp: &Input) -> Row {
    let (a, runs) = (s.a, s.a.runs);
    let n = inp.mesh.len();
    let mut values = Vec::new();
    let (serial_s, _) = timed_build(inp, &s.sah.serial(), runs, s.clock);
    let (parallel_s, bvh) = s.pool.install(|| timed_build(inp, &s.sah, runs, s.clock));
    let median_opts = BuildOptions { method: SplitMethod::Median, ..s.sah }.serial();
    let (median_s, median_bvh) = timed_build(inp, &median_opts, runs, s.clock);
    values.extend([
        ("build_sah_serial_ms", serial_s * 1e3),
        ("build_sah_parallel_ms", parallel_s * 1e3),
        ("build_median_ms", median_s * 1e3),
    ]);

    let mem = bvh.memory();
    let mesh_bytes = inp.mesh.memory_bytes();
    let per = |b: usize| b as f64 / n as f64;
    values.extend([
        ("bytes_per_tri", per(mesh_bytes + mem.total())),
        ("mesh_bytes_per_tri", per(mesh_bytes)),
        ("bvh_bytes_per_tri", per(mem.total())),
        ("wide_node_bytes_per_tri", per(mem.wide_nodes)),
        ("leaf_bytes_per_tri", per(mem.leaves)),
    ]);

    let coherent = bvh_rays::coherent(&inp.scene_bounds, a.rays);
    let incoherent = bvh_rays::incoherent(&inp.scene_bounds, a.rays, 7);
    let sah = BvhTracer { bvh: &bvh, prims: &inp.mesh };
    let sets = [("incoherent", &incoherent), ("coherent", &coherent)];
    let all = a.rays;
    for (set_name, set) in sets {
        for (q_name, q) in [("closest", Query::Closest), ("any", Query::Any)] {
            for (threads, parallel) in [("1t", false), ("mt", true)] {
                let name = metric_name(&format!("sah_{set_name}_{q_name}_{threads}"));
                values.push((name, timed_trace(&s.pool, s.clock, &sah, set, all, q, parallel, runs)));
            }
        }
    }
    let med = BvhTracer { bvh: &median_bvh, prims: &inp.mesh };
    for (set_name, set) in sets {
        let name = metric_name(&format!("median_{set_name}_closest_1t"));
        values.push((name, timed_trace(&s.pool, s.clock, &med, set, all, Query::Closest, false, runs)));
    }
    if n <= a.brute_max {
        let brute = BruteForce::new(&inp.kinds);
        let bt = BruteTracer { brute: &brute, prims: &inp.mesh };
        // O(n) per ray: about 5·10⁷ ray–triangle pairs per pass, at least 1,000 rays.
        let count = (5e7 as usize / n).clamp(1_000, all);
        for (set_name, set) in sets {
            let name = metric_name(&format!("brute_{set_name}_closest_1t"));
            values.push((name, timed_trace(&s.pool, s.clock, &bt, set, count, Query::Closest, false, runs)));
        }
    }
    Row { scene, triangles: n, values }
}

fn metric_name(name: &str) -> &'static str {
    METRICS.iter().find(|m| m.name == name).map_or("unknown", |m| m.name)
}

pub fn run(a: BvhBenchArgs) -> Result<ExitCode, CliError> {
    let kinds: Vec<MeshKind> =
        a.scenes.split(',').map(MeshKind::parse).collect::<Result<_, _>>().map_err(CliError::usage)?;
    if a.min_tris > a.max_tris {
        return Err(CliError::usage(format!("--min-tris {} is above --max-tris {}", a.min_tris, a.max_tris)));
    }
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(t) = a.threads {
        builder = builder.num_threads(t);
    }
    let pool = builder.build().map_err(|e| CliError::runtime(format!("cannot start threads: {e}")))?;
    let sah = BuildOptions { bins: a.bins as usize, max_leaf: a.max_leaf as usize, ..BuildOptions::default() };
    let clock = if a.cpu_time { Clock::ThreadCpu } else { Clock::Wall };
    let settings = Settings { a: &a, clock, sah, pool };
    if let Some(n) = a.instances {
        return crate::bench_instances::run(&a, n, clock);
    }
    if let Some(path) = &a.export {
        return crate::bvh_export::run(&settings.pool, clock, kinds[0], a.max_tris, a.rays, a.runs, &sah, path);
    }

    let mut rows = Vec::new();
    for &kind in &kinds {
        if kind == MeshKind::Bunny && !bvh_meshes::bunny_path().exists() {
            eprintln!("note: {} not found; skipping the bunny", bvh_meshes::bunny_path().display());
            continue;
        }
        for n in counts(kind, &a) {
            let tris = mesh(kind, n).map_err(CliError::runtime)?;
            let inp = input(&tris);
            drop(tris);
            let row = measure(&settings, kind.name(), &inp);
            if !a.json {
                eprintln!("{} {}: done", row.scene, row.triangles);
            }
            rows.push(row);
        }
    }
    let slopes = bvh_plots::slopes(&rows);
    if let Some(path) = &a.csv {
        write_csv(path, &rows).map_err(|e| CliError::runtime(format!("cannot write {}: {e}", path.display())))?;
    }
    if let Some(dir) = &a.plots {
        let written = bvh_plots::write_plots(dir, &rows)
            .map_err(|e| CliError::runtime(format!("cannot write plots to {}: {e}", dir.display())))?;
        if !a.json {
            for p in written {
                eprintln!("wrote {}", p.display());
            }
        }
    }
    let threads = settings.pool.current_num_threads();
    if a.json {
        let rows_json: Vec<_> = rows
            .iter()
            .map(|r| {
                let mut o = serde_json::Map::new();
                o.insert("scene".into(), r.scene.into());
                o.insert("triangles".into(), r.triangles.into());
                for &(k, v) in &r.values {
                    o.insert(k.into(), v.into());
                }
                serde_json::Value::Object(o)
            })
            .collect();
        let slopes_json: Vec<_> = slopes
            .iter()
            .map(|s| serde_json::json!({"scene": s.scene, "metric": s.metric, "slope": s.slope, "points": s.points}))
            .collect();
        let out = serde_json::json!({
            "threads": threads, "rays": a.rays, "cpu_time_for_one_thread": a.cpu_time, "runs": a.runs, "bins": sah.bins, "max_leaf": sah.max_leaf,
            "columns": METRICS.iter().map(|m| (m.name.to_string(), m.doc.into())).collect::<serde_json::Map<_, _>>(),
            "rows": rows_json, "slopes": slopes_json,
        });
        println!("{}", serde_json::to_string_pretty(&out).map_err(|e| CliError::runtime(e.to_string()))?);
    } else {
        print_tables(&rows, threads, &a);
        bvh_plots::print_slopes(&slopes);
    }
    Ok(ExitCode::SUCCESS)
}

fn write_csv(path: &std::path::Path, rows: &[Row]) -> std::io::Result<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    let names: Vec<&str> = METRICS.iter().map(|m| m.name).collect();
    writeln!(f, "scene,triangles,{}", names.join(","))?;
    for r in rows {
        let cells: Vec<String> = names.iter().map(|n| r.get(n).map_or(String::new(), |v| format!("{v:.6}"))).collect();
        writeln!(f, "{},{},{}", r.scene, r.triangles, cells.join(","))?;
    }
    f.flush()
}

fn print_tables(rows: &[Row], threads: usize, a: &BvhBenchArgs) {
    let cell = |r: &Row, n: &str, prec: usize| r.get(n).map_or("-".to_string(), |v| format!("{v:.prec$}"));
    println!(
        "BVH: SAH with {} bins, leaves ≤ {}; {} rays per set, median of {} runs; mt = {threads} threads; {}",
        a.bins,
        a.max_leaf,
        a.rays,
        a.runs,
        if a.cpu_time { "1-thread columns in thread CPU time" } else { "wall-clock time" }
    );
    println!();
    println!(
        "{:<7} {:>9} | {:>11} {:>11} {:>11} | {:>8} {:>8} {:>8} ({:>6} {:>6})",
        "mesh", "triangles", "SAH 1t ms", "SAH mt ms", "median ms", "B/tri", "mesh", "BVH", "wide", "leaves"
    );
    for r in rows {
        println!(
            "{:<7} {:>9} | {:>11} {:>11} {:>11} | {:>8} {:>8} {:>8} ({:>6} {:>6})",
            r.scene,
            r.triangles,
            cell(r, "build_sah_serial_ms", 2),
            cell(r, "build_sah_parallel_ms", 2),
            cell(r, "build_median_ms", 2),
            cell(r, "bytes_per_tri", 1),
            cell(r, "mesh_bytes_per_tri", 1),
            cell(r, "bvh_bytes_per_tri", 1),
            cell(r, "wide_node_bytes_per_tri", 1),
            cell(r, "leaf_bytes_per_tri", 1),
        );
    }
    println!();
    println!("Mrays/s (1t / mt)     SAH incoherent           SAH camera            median (1t)     brute force (1t)");
    println!(
        "{:<7} {:>9} | {:>11} {:>11} | {:>11} {:>11} | {:>7} {:>7} | {:>7} {:>7}",
        "mesh", "triangles", "closest", "any", "closest", "any", "incoh", "camera", "incoh", "camera"
    );
    for r in rows {
        let pair = |base: &str| format!("{}/{}", cell(r, &format!("{base}_1t"), 2), cell(r, &format!("{base}_mt"), 2));
        println!(
            "{:<7} {:>9} | {:>11} {:>11} | {:>11} {:>11} | {:>7} {:>7} | {:>7} {:>7}",
            r.scene,
            r.triangles,
            pair("sah_incoherent_closest"),
            pair("sah_incoherent_any"),
            pair("sah_coherent_closest"),
            pair("sah_coherent_any"),
            cell(r, "median_incoherent_closest_1t", 2),
            cell(r, "median_coherent_closest_1t", 2),
            cell(r, "brute_incoherent_closest_1t", 3),
            cell(r, "brute_coherent_closest_1t", 3),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_step_through_decades() {
        assert_eq!(sizes(100, 10_000, 1), vec![100, 1000, 10_000]);
        assert_eq!(sizes(100, 1000, 2), vec![100, 316, 1000]);
        assert_eq!(sizes(150, 999, 1), Vec::<usize>::new());
    }

    #[test]
    fn every_metric_name_is_listed() {
        for name in ["sah_incoherent_any_mt", "median_coherent_closest_1t", "brute_incoherent_closest_1t"] {
            assert_eq!(metric_name(name), name);
        }
    }
}
