//! Four triangles tested at once: Möller–Trumbore ("Fast, Minimum Storage Ray/Triangle
//! Intersection", JGT 1997) on SIMD lanes, in the operation order of
//! [`crate::shape::Triangle::intersect`] so every lane agrees bit for bit with the scalar test.
//! The test is written once over the lane type: one ray against the packet's four triangles, or
//! one of its triangles against a group of rays.

use glam::Vec4;

use super::lanes::{HitL, HitX4, Lane, RayL, RayX4, Rays, Vec3L, Vec3x4};
use crate::shape::{Triangle, EDGE_SLACK};
use crate::wide::simd::F32s;

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

    /// Each lane's triangle's box, padded as the tree pads a primitive's box (`Aabb::padded`,
    /// in its operation order), over the corners `p0`, `p0 + e1`, `p0 + e2`: min x, y, z, max
    /// x, y, z, one triangle per lane. A ray that hits the triangle passes this box's slab test,
    /// as it passes the box of every node above the triangle (the padding holds the tests'
    /// rounding and the edge slack; the corners here differ from the mesh's own by at most the
    /// rounding of `p0 + e1`, far inside the padding).
    #[inline(always)]
    pub fn padded_bounds(&self) -> [Vec4; 6] {
        let axes = |v: &Vec3x4| [v.x, v.y, v.z];
        let (p0, e1, e2) = (axes(&self.p0), axes(&self.e1), axes(&self.e2));
        let mut lo = [Vec4::ZERO; 3];
        let mut hi = [Vec4::ZERO; 3];
        for a in 0..3 {
            let (p1, p2) = (p0[a] + e1[a], p0[a] + e2[a]);
            lo[a] = p0[a].min(p1).min(p2);
            hi[a] = p0[a].max(p1).max(p2);
        }
        let largest = (0..3).map(|a| hi[a].abs().max(lo[a].abs())).fold(Vec4::ZERO, Vec4::max);
        let floor = Vec4::splat(1e-6) * (Vec4::ONE + largest);
        let mut out = [Vec4::ZERO; 6];
        for a in 0..3 {
            let pad = ((hi[a] - lo[a]).max(Vec4::ZERO) * Vec4::splat(1e-5)).max(floor);
            out[a] = lo[a] - pad;
            out[a + 3] = hi[a] + pad;
        }
        out
    }

    /// Per-lane hits with `t ∈ [t_min, t_max]`.
    #[inline(always)]
    pub fn intersect(&self, ray: &RayX4, t_min: f32, t_max: f32) -> HitX4 {
        moller_trumbore(ray, &self.p0, &self.e1, &self.e2, t_min, Vec4::splat(t_max))
    }

    /// Triangle `k` of the packet against every ray of a group (lanes = rays), ray `i` within
    /// `[t_min, t_max[i]]`: per ray the same bits as [`Tri4::intersect`].
    #[inline(always)]
    pub fn intersect_rays<const N: usize>(
        &self,
        k: usize,
        rays: &Rays<N>,
        t_min: f32,
        t_max: F32s<N>,
    ) -> HitL<F32s<N>> {
        // Each corner splatted on its own: through `[_; 3]::map`, LLVM put the three splats
        // out of line in a function compiled for baseline x86-64, which wrote the group-wide
        // vectors (over 1 KB with 32 lanes) to memory in 16-byte pieces for the test to load
        // back (`try_map`, 2% of a teapot's profile on its own).
        let p0 = Vec3L::splat(self.p0.lane(k));
        let e1 = Vec3L::splat(self.e1.lane(k));
        let e2 = Vec3L::splat(self.e2.lane(k));
        moller_trumbore(rays, &p0, &e1, &e2, t_min, t_max)
    }
}

/// Möller–Trumbore per lane (rays or triangles in the lanes), in the scalar test's order.
#[inline(always)]
fn moller_trumbore<L: Lane>(
    ray: &RayL<L>,
    p0: &Vec3L<L>,
    e1: &Vec3L<L>,
    e2: &Vec3L<L>,
    t_min: f32,
    t_max: L,
) -> HitL<L> {
    let pvec = ray.dir.cross(e2);
    let det = e1.dot(&pvec);
    let ok = det.finite_nonzero();
    let inv_det = L::splat(1.0) / det;
    let tvec = ray.origin.sub(p0);
    let u = tvec.dot(&pvec) * inv_det;
    let lo = L::splat(-EDGE_SLACK);
    let hi = L::splat(1.0 + EDGE_SLACK);
    let qvec = tvec.cross(e1);
    let v = ray.dir.dot(&qvec) * inv_det;
    let t = e2.dot(&qvec) * inv_det;
    // The scalar test rejects `v < −ε || u + v > 1 + ε`, which lets NaN through; so here.
    let v_ok = !(v.lt(lo) | (u + v).gt(hi));
    let mask = ok & u.ge(lo) & u.le(hi) & v_ok & t.ge(L::splat(t_min)) & t.le(t_max);
    HitL { mask, t, u, v }
}
