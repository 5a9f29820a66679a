//! Four triangles tested at once: Möller–Trumbore ("Fast, Minimum Storage Ray/Triangle
//! Intersection", JGT 1997) on SIMD lanes, in the operation order of
//! [`crate::shape::Triangle::intersect`] so every lane agrees bit for bit with the scalar test.

use glam::Vec4;

use super::lanes::{HitX4, RayX4, Vec3x4};
use crate::shape::{Triangle, EDGE_SLACK};

/// Up to four triangles in structure-of-arrays form. Unused lanes have zero edges, so their
/// determinant is 0 and they never hit.
#[derive(Clone, Copy, Debug)]
pub(super) struct Tri4 {
    p0: Vec3x4,
    e1: Vec3x4,
    e2: Vec3x4,
}

impl Tri4 {
    /// Packs one to four triangles.
    pub fn new(tris: &[Triangle]) -> Self {
        debug_assert!((1..=4).contains(&tris.len()));
        let field = |f: fn(&Triangle) -> glam::Vec3| Vec3x4::gather_with(tris, f);
        Self { p0: field(|t| t.p0), e1: field(|t| t.e1), e2: field(|t| t.e2) }
    }

    /// Per-lane hits with `t ∈ [t_min, t_max]`.
    #[inline(always)]
    pub fn intersect(&self, ray: &RayX4, t_min: f32, t_max: f32) -> HitX4 {
        let pvec = ray.dir.cross(&self.e2);
        let det = self.e1.dot(&pvec);
        let ok = det.cmpne(Vec4::ZERO) & det.is_finite_mask();
        let inv_det = Vec4::ONE / det;
        let tvec = ray.origin.sub(&self.p0);
        let u = tvec.dot(&pvec) * inv_det;
        let lo = Vec4::splat(-EDGE_SLACK);
        let hi = Vec4::splat(1.0 + EDGE_SLACK);
        let qvec = tvec.cross(&self.e1);
        let v = ray.dir.dot(&qvec) * inv_det;
        let t = self.e2.dot(&qvec) * inv_det;
        // The scalar test rejects `v < −ε || u + v > 1 + ε`, which lets NaN through; so here.
        let v_ok = !(v.cmplt(lo) | (u + v).cmpgt(hi));
        let mask = ok & u.cmpge(lo) & u.cmple(hi) & v_ok & t.cmpge(Vec4::splat(t_min)) & t.cmple(Vec4::splat(t_max));
        HitX4 { mask, t, u, v }
    }
}
