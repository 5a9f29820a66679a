//! Four quads tested at once: the plane + dual-vector test of [`crate::shape::Quad`] on SIMD
//! lanes (one quad per lane), computed in the same operation order so every lane agrees bit
//! for bit with the scalar test. The test is written once over the lane type: one ray against
//! the packet's four quads, or one of its quads against a group of rays.

use glam::Vec4;

use super::lanes::{HitL, HitX4, Lane, RayL, RayX4, Rays, Vec3L, Vec3x4};
use crate::shape::{Quad, EDGE_SLACK};
use crate::wide::simd::F32s;

/// Up to four quads in structure-of-arrays form. Unused lanes have `n = 0`, so their distance
/// is `0/0 = NaN` and they never hit.
#[derive(Clone, Copy, Debug)]
pub(super) struct Quad4 {
    q: Vec3x4,
    n: Vec3x4,
    u_dual: Vec3x4,
    v_dual: Vec3x4,
}

impl Quad4 {
    /// Packs one to four quads.
    pub fn new(quads: &[Quad]) -> Self {
        debug_assert!((1..=4).contains(&quads.len()));
        let field = |k: usize| Vec3x4::gather_with(quads, |q| q.intersection_data()[k]);
        Self { q: field(0), n: field(1), u_dual: field(2), v_dual: field(3) }
    }

    /// Per-lane hits with `t ∈ [t_min, t_max]`.
    #[inline(always)]
    pub fn intersect(&self, ray: &RayX4, t_min: f32, t_max: f32) -> HitX4 {
        plane_and_duals(ray, [&self.q, &self.n, &self.u_dual, &self.v_dual], t_min, Vec4::splat(t_max))
    }

    /// Quad `k` of the packet against every ray of a group (lanes = rays), ray `i` within
    /// `[t_min, t_max[i]]`: per ray the same bits as [`Quad4::intersect`].
    #[inline(always)]
    pub fn intersect_rays<const N: usize>(
        &self,
        k: usize,
        rays: &Rays<N>,
        t_min: f32,
        t_max: F32s<N>,
    ) -> HitL<F32s<N>> {
        // One splat each, not `[_; 4]::map` (see `Tri4::intersect_rays`).
        let q = Vec3L::splat(self.q.lane(k));
        let n = Vec3L::splat(self.n.lane(k));
        let u_dual = Vec3L::splat(self.u_dual.lane(k));
        let v_dual = Vec3L::splat(self.v_dual.lane(k));
        plane_and_duals(rays, [&q, &n, &u_dual, &v_dual], t_min, t_max)
    }
}

/// The quad test per lane (rays or quads in the lanes), in the scalar test's order; `quad` is
/// its corner, normal and the two dual edge vectors.
#[inline(always)]
fn plane_and_duals<L: Lane>(ray: &RayL<L>, quad: [&Vec3L<L>; 4], t_min: f32, t_max: L) -> HitL<L> {
    let [q, n, u_dual, v_dual] = quad;
    // t = n·(q − o) / n·d ("Ray Tracing: The Next Week" §6).
    let denom = n.dot(&ray.dir);
    let t = n.dot(&q.sub(&ray.origin)) / denom;
    // Ordered comparisons are false for NaN (parallel rays, padding lanes).
    let in_range = t.ge(L::splat(t_min)) & t.le(t_max);
    // h = o + t·d − q; edge coordinates a = h·ũ, b = h·ṽ.
    let h = Vec3L {
        x: ray.origin.x + t * ray.dir.x - q.x,
        y: ray.origin.y + t * ray.dir.y - q.y,
        z: ray.origin.z + t * ray.dir.z - q.z,
    };
    let a = h.dot(u_dual);
    let b = h.dot(v_dual);
    let lo = L::splat(-EDGE_SLACK);
    let hi = L::splat(1.0 + EDGE_SLACK);
    let mask = in_range & a.ge(lo) & a.le(hi) & b.ge(lo) & b.le(hi);
    HitL { mask, t, u: a, v: b }
}
