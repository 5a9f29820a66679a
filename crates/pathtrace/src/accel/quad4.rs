//! Four quads tested at once: the plane + dual-vector test of [`crate::shape::Quad`] on SIMD
//! lanes (one quad per lane), computed in the same operation order so every lane agrees bit
//! for bit with the scalar test.

use glam::Vec4;

use super::lanes::{HitX4, RayX4, Vec3x4};
use crate::shape::{Quad, EDGE_SLACK};

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
        // t = n·(q − o) / n·d ("Ray Tracing: The Next Week" §6).
        let denom = self.n.dot(&ray.dir);
        let t = self.n.dot(&self.q.sub(&ray.origin)) / denom;
        // Ordered comparisons are false for NaN (parallel rays, padding lanes).
        let in_range = t.cmpge(Vec4::splat(t_min)) & t.cmple(Vec4::splat(t_max));
        // h = o + t·d − q; edge coordinates a = h·ũ, b = h·ṽ.
        let h = Vec3x4 {
            x: ray.origin.x + t * ray.dir.x - self.q.x,
            y: ray.origin.y + t * ray.dir.y - self.q.y,
            z: ray.origin.z + t * ray.dir.z - self.q.z,
        };
        let a = h.dot(&self.u_dual);
        let b = h.dot(&self.v_dual);
        let lo = Vec4::splat(-EDGE_SLACK);
        let hi = Vec4::splat(1.0 + EDGE_SLACK);
        let mask = in_range & a.cmpge(lo) & a.cmple(hi) & b.cmpge(lo) & b.cmple(hi);
        HitX4 { mask, t, u: a, v: b }
    }
}
