//! `pathtrace bench bvh --export FILE`: one mesh, its incoherent rays and this program's
//! closest hits, written for benches/peers/bvh_embree.py, which traces the same rays in Embree.
//!
//! File layout (little endian): the 8 bytes `PTBVHEX1`, the triangle count `T` and ray count
//! `R` as u64, then `T × 9` f32 vertex coordinates (a, b, c), `R × 6` f32 rays (origin,
//! unit direction; `t ∈ [0, ∞)`), and `R` f32 closest-hit distances (+∞ for a miss).

use crate::bench_bvh::{input, median_of, mesh, timed_build};
use crate::bvh_meshes::MeshKind;
use crate::bvh_rays::{self, BvhTracer, Query};
use crate::cpu_clock::Clock;
use crate::CliError;
use pathtrace::accel::BuildOptions;
use pathtrace::math::Vec3;
use pathtrace::shape::Triangle;
use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

#[allow(clippy::too_many_arguments)]
pub fn run(
    pool: &rayon::ThreadPool,
    clock: Clock,
    kind: MeshKind,
    n: usize,
    rays: usize,
    runs: u32,
    sah: &BuildOptions,
    path: &Path,
) -> Result<ExitCode, CliError> {
    let tris: Vec<[Vec3; 3]> = mesh(kind, n)
        .map_err(CliError::runtime)?
        .into_iter()
        .filter(|&[a, b, c]| Triangle::new(a, b, c, Triangle::FLAT).is_some())
        .collect();
    let inp = input(&tris);
    let (build_s, bvh) = pool.install(|| timed_build(&inp, &sah.serial(), runs, clock));
    let prims = &inp.mesh;
    let set = bvh_rays::incoherent(&inp.scene_bounds, rays, 7);
    let tracer = BvhTracer { bvh: &bvh, prims };
    let rate = |parallel: bool| {
        let r: Vec<f64> = (0..runs)
            .map(|_| pool.install(|| bvh_rays::trace(&tracer, &set, rays, Query::Closest, parallel, clock)).0)
            .collect();
        median_of(r) / 1e6
    };
    let (one, all) = (rate(false), rate(true));
    let hits: Vec<f32> = set
        .rays
        .iter()
        .map(|r| bvh.intersect(prims, r, 0.0, f32::INFINITY).map_or(f32::INFINITY, |(h, _)| h.t))
        .collect();

    let write = || -> std::io::Result<()> {
        let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
        f.write_all(b"PTBVHEX1")?;
        f.write_all(&(tris.len() as u64).to_le_bytes())?;
        f.write_all(&(set.rays.len() as u64).to_le_bytes())?;
        for v in tris.iter().flatten() {
            for c in v.to_array() {
                f.write_all(&c.to_le_bytes())?;
            }
        }
        for r in &set.rays {
            for c in r.origin.to_array().into_iter().chain(r.dir.to_array()) {
                f.write_all(&c.to_le_bytes())?;
            }
        }
        for t in &hits {
            f.write_all(&t.to_le_bytes())?;
        }
        f.flush()
    };
    write().map_err(|e| CliError::runtime(format!("cannot write {}: {e}", path.display())))?;
    let out = serde_json::json!({
        "file": path.display().to_string(),
        "mesh": kind.name(),
        "triangles": tris.len(),
        "rays": set.rays.len(),
        "hits": hits.iter().filter(|t| t.is_finite()).count(),
        "build_ms": build_s * 1e3,
        "threads": pool.current_num_threads(),
        "cpu_time_for_one_thread": clock == Clock::ThreadCpu,
        "closest_mrays_per_s_1t": one,
        "closest_mrays_per_s_mt": all,
    });
    println!("{}", serde_json::to_string_pretty(&out).map_err(|e| CliError::runtime(e.to_string()))?);
    Ok(ExitCode::SUCCESS)
}
