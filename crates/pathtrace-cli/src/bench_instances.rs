//! `pathtrace bench bvh --instances N`: one mesh placed N times as instances (a two-level BVH)
//! against the same mesh alone: build time, memory from the scene's own accounting, and
//! incoherent closest-hit and any-hit rays per second on one thread.

use crate::args::BvhBenchArgs;
use crate::bench_bvh::{indexed, median_of};
use crate::bvh_meshes;
use crate::bvh_rays::{self, Query, RaySet, Tracer};
use crate::cpu_clock::Clock;
use crate::CliError;
use pathtrace::material::{Diffuse, Material};
use pathtrace::math::{Aabb, Ray, Rgb, Transform, Vec3};
use pathtrace::{Scene, SceneBuilder, ShapeGroup};
use std::process::ExitCode;

/// Flattened copies are built only up to this many triangles in all (about 80 bytes each).
const MAX_COPIED_TRIANGLES: usize = 5_000_000;

struct SceneTracer<'a>(&'a Scene);

impl Tracer for SceneTracer<'_> {
    fn closest(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        self.0.intersect(ray, t_max).map(|h| h.hit.t)
    }
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.0.occluded(ray, t_max)
    }
}

/// Instances on a cubic grid, 3 units apart (the unit-sphere mesh has radius 1), each turned
/// by its own angle about y.
fn placement(k: usize, side: usize) -> Transform {
    let (x, y, z) = (k % side, (k / side) % side, k / (side * side));
    let at = Vec3::new(x as f32, y as f32, z as f32) * 3.0;
    Transform::rotate_y(37.0 * k as f32).then(&Transform::translate(at))
}

pub fn run(a: &BvhBenchArgs, instances: usize, clock: Clock) -> Result<ExitCode, CliError> {
    let tris = bvh_meshes::sphere(a.max_tris);
    let mesh = indexed(&tris);
    drop(tris);
    let side = (instances as f64).cbrt().ceil() as usize;
    let mut base = SceneBuilder::new();
    base.allow_no_lights(true);
    let grey = base.material(Material::Diffuse(Diffuse { albedo: Rgb::splat(0.5) }));
    let build_single = || {
        let mut b = base.clone();
        b.mesh(&mesh, grey, &Transform::IDENTITY).map(|_| b.build())
    };
    let build_instanced = || {
        let mut b = base.clone();
        let mut g = ShapeGroup::new();
        g.mesh(&mesh, grey, &Transform::IDENTITY)?;
        let id = b.group(g)?;
        for k in 0..instances {
            b.instance(id, &placement(k, side), None)?;
        }
        Ok::<_, pathtrace::scene::BuildError>(b.build())
    };
    // The same placements as ordinary meshes: every copy stored and in one BVH.
    let build_copies = || {
        let mut b = base.clone();
        for k in 0..instances {
            b.mesh(&mesh, grey, &placement(k, side))?;
        }
        Ok::<_, pathtrace::scene::BuildError>(b.build())
    };
    let err = |e: pathtrace::scene::BuildError| CliError::runtime(e.to_string());
    // Builds run on a one-thread pool, so the thread's CPU time is the whole build's.
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .map_err(|e| CliError::runtime(format!("cannot start a thread: {e}")))?;
    let time_build = |f: &(dyn Fn() -> Result<Result<Scene, _>, _> + Sync)| -> Result<(f64, Scene), CliError> {
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..a.runs {
            let (scene, s) = one.install(|| clock.time_repeated(bvh_rays::MIN_SECONDS, f));
            times.push(s);
            last = Some(scene.map_err(err)?.map_err(err)?);
        }
        Ok((median_of(times), last.ok_or_else(|| CliError::runtime("no run"))?))
    };
    let (single_s, single) = time_build(&build_single)?;
    let (inst_s, inst) = time_build(&build_instanced)?;
    let n = single.primitive_count();
    let copies = if n * instances <= MAX_COPIED_TRIANGLES { Some(time_build(&build_copies)?) } else { None };
    let single_box = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
    let inst_box = Aabb::new(Vec3::splat(-1.0), Vec3::splat(3.0 * (side - 1) as f32 + 1.0));
    let rate = |scene: &Scene, set: &RaySet, q: Query| {
        let rates: Vec<f64> =
            (0..a.runs).map(|_| bvh_rays::trace(&SceneTracer(scene), set, a.rays, q, false, clock).0).collect();
        median_of(rates) / 1e6
    };
    let single_rays = bvh_rays::incoherent(&single_box, a.rays, 7);
    let inst_rays = bvh_rays::incoherent(&inst_box, a.rays, 7);
    println!("mesh: unit sphere, {n} triangles; {instances} instances on a {side}³ grid, 3 units apart");
    println!("clock: {}", if a.cpu_time { "thread CPU time" } else { "wall" });
    println!("| scene | build, 1 thread (ms) | memory (MB) | incoherent closest (M rays/s, 1 thread) | incoherent any (M rays/s) |");
    println!("|---|---|---|---|---|");
    let mut rows = vec![("mesh alone", single_s, &single, &single_rays), ("instances", inst_s, &inst, &inst_rays)];
    if let Some((s, scene)) = &copies {
        rows.push(("copies (flattened)", *s, scene, &inst_rays));
    }
    for (name, s, scene, rays) in rows {
        println!(
            "| {name} | {:.1} | {:.2} | {:.3} | {:.3} |",
            s * 1e3,
            scene.memory_bytes() as f64 / 1e6,
            rate(scene, rays, Query::Closest),
            rate(scene, rays, Query::Any)
        );
    }
    if copies.is_none() {
        println!("(copies not built: {} triangles is above {MAX_COPIED_TRIANGLES})", n * instances);
    }
    let copies = instances as f64 * single.memory_bytes() as f64;
    println!(
        "instances use {:.3}× the memory of the mesh alone ({:.0} bytes per instance beyond it); {instances} copies would take {:.0} MB",
        inst.memory_bytes() as f64 / single.memory_bytes() as f64,
        (inst.memory_bytes() as f64 - single.memory_bytes() as f64) / instances as f64,
        copies / 1e6
    );
    Ok(ExitCode::SUCCESS)
}
