//! Ray sets and tracers for `pathtrace bench bvh`: coherent camera rays and incoherent rays,
//! traced through an accelerator on one thread or on every rayon thread.

use crate::cpu_clock::Clock;
use pathtrace::accel::{BruteForce, Bvh};
use pathtrace::math::{Aabb, Ray, Vec3};
use pathtrace::sampling::Pcg32;
use pathtrace::shape::MeshGeometry;
use rayon::prelude::*;

/// Rays with the `t_max` their any-hit query uses (closest-hit queries use `t_max = ∞`).
pub struct RaySet {
    pub rays: Vec<Ray>,
    pub shadow_t_max: Vec<f32>,
}

/// Pinhole camera rays over a square image of about `n` pixels, looking at the box from
/// outside, in 8×8-pixel tiles as the renderer traces them (neighbouring rays are neighbours
/// in memory and in the tree). Any-hit queries use `t_max = ∞`.
pub fn coherent(bounds: &Aabb, n: usize) -> RaySet {
    let side = ((n as f64).sqrt().round() as usize).max(8) / 8 * 8;
    let centre = bounds.centroid();
    let radius = 0.5 * (bounds.max - bounds.min).length();
    let eye = centre + 2.5 * radius * Vec3::new(0.5, 0.4, 1.0).normalize();
    let forward = (centre - eye).normalize();
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    // A 40° vertical field of view: the object fills most of the image.
    let half = (20f32).to_radians().tan();
    let mut rays = Vec::with_capacity(side * side);
    for tile_y in (0..side).step_by(8) {
        for tile_x in (0..side).step_by(8) {
            for y in tile_y..tile_y + 8 {
                for x in tile_x..tile_x + 8 {
                    let sx = (2.0 * (x as f32 + 0.5) / side as f32 - 1.0) * half;
                    let sy = (1.0 - 2.0 * (y as f32 + 0.5) / side as f32) * half;
                    rays.push(Ray::new(eye, (forward + sx * right + sy * up).normalize()));
                }
            }
        }
    }
    let shadow_t_max = vec![f32::INFINITY; rays.len()];
    RaySet { rays, shadow_t_max }
}

/// `n` rays from a uniform point `o` in the box towards another uniform point `p`: random
/// directions, most starting among the triangles. Any-hit queries stop at `p` (`t_max = |p − o|`),
/// like shadow rays between two surfaces.
pub fn incoherent(bounds: &Aabb, n: usize, seed: u64) -> RaySet {
    let mut rng = Pcg32::new(seed, 29);
    let mut uniform =
        || bounds.min + (bounds.max - bounds.min) * Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
    let (mut rays, mut shadow_t_max) = (Vec::with_capacity(n), Vec::with_capacity(n));
    while rays.len() < n {
        let (o, p) = (uniform(), uniform());
        let d = p - o;
        let len = d.length();
        if len > 1e-6 * (1.0 + o.abs().max_element()) {
            rays.push(Ray::new(o, d / len));
            shadow_t_max.push(len);
        }
    }
    RaySet { rays, shadow_t_max }
}

/// Closest-hit and any-hit queries of one accelerator.
pub trait Tracer: Sync {
    fn closest(&self, ray: &Ray, t_max: f32) -> Option<f32>;
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool;
}

/// A BVH over a mesh's triangles.
pub struct BvhTracer<'a> {
    pub bvh: &'a Bvh,
    pub prims: &'a MeshGeometry,
}

impl Tracer for BvhTracer<'_> {
    fn closest(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        self.bvh.intersect(self.prims, ray, 0.0, t_max).map(|(h, _)| h.t)
    }
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.bvh.occluded(self.prims, ray, 0.0, t_max)
    }
}

pub struct BruteTracer<'a> {
    pub brute: &'a BruteForce,
    pub prims: &'a MeshGeometry,
}

impl Tracer for BruteTracer<'_> {
    fn closest(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        self.brute.intersect(self.prims, ray, 0.0, t_max).map(|(h, _)| h.t)
    }
    fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.brute.occluded(self.prims, ray, 0.0, t_max)
    }
}

/// Shortest time a measurement runs for (seconds).
pub const MIN_SECONDS: f64 = 0.2;

/// Which query.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Query {
    Closest,
    Any,
}

/// Traces the first `count` rays of `set` and returns rays per second and the number of hits.
/// `parallel` spreads chunks of rays over the rayon pool (timed by the wall clock); otherwise
/// this thread traces them all, timed by `clock`.
pub fn trace(
    tracer: &dyn Tracer,
    set: &RaySet,
    count: usize,
    query: Query,
    parallel: bool,
    clock: Clock,
) -> (f64, usize) {
    let count = count.min(set.rays.len());
    let one = |i: usize| -> bool {
        let ray = &set.rays[i];
        match query {
            Query::Closest => tracer.closest(ray, f32::INFINITY).is_some(),
            Query::Any => tracer.occluded(ray, set.shadow_t_max[i]),
        }
    };
    // Every set is traced for at least MIN_SECONDS (whole passes), so short sets are not
    // dominated by clock resolution.
    let (hits, seconds) = if parallel {
        // Chunks of 256 rays: enough work per task to hide rayon's overhead, and contiguous
        // (coherent) rays stay together.
        Clock::Wall
            .time_repeated(MIN_SECONDS, || (0..count).into_par_iter().with_min_len(256).filter(|&i| one(i)).count())
    } else {
        clock.time_repeated(MIN_SECONDS, || (0..count).filter(|&i| one(i)).count())
    };
    (count as f64 / seconds, std::hint::black_box(hits))
}
