//! Parallelepipeds (boxes, also rotated or sheared) recognised among a small scene's quads and
//! intersected as one slab test instead of six quad tests.
//!
//! Why: the `box` objects of scene files become six quads (`Quad::box_faces`), and testing the
//! six one by one costs about four times the slab test (Kay & Kajiya 1986) that finds the same
//! first hit. The slab test works in the box's own coordinates s = (x − p)·D_k, where D_k is
//! the dual basis of the edges E_k (D_k·E_j = δ_kj), so the box is 0 ≤ s_k ≤ 1 and each pair
//! of faces is one slab.

use super::simd::{F32s, Ms, Vec3s};
use crate::math::Vec3;
use crate::primitive_store::FlatPolygon;

/// A parallelepiped `p + a·E0 + b·E1 + c·E2`, a, b, c ∈ [0, 1], whose faces are six quads in
/// `Quad::box_faces` order: (−E0, +E0, −E1, +E1, −E2, +E2) sides.
#[derive(Clone, Copy, Debug)]
pub(super) struct Parallelepiped {
    p: Vec3,
    dual: [Vec3; 3],
}

impl Parallelepiped {
    /// The box whose faces are `quads`, if they are the six faces in `Quad::box_faces` order
    /// with outward normals (up to rounding of 10⁻⁵ of the box's size).
    pub fn recognise(quads: &[FlatPolygon]) -> Option<Self> {
        let [f0, f1, f2, f3, f4, f5] = quads else { return None };
        if quads.iter().any(|q| q.triangle) {
            return None;
        }
        let p = f0.origin;
        let e = [f1.origin - p, f3.origin - p, f5.origin - p];
        let size = e.iter().map(|v| v.length()).fold(0.0, f32::max);
        let close = |a: Vec3, b: Vec3| (a - b).length() <= 1e-5 * size;
        // Each face: (corner, first edge, second edge), as Quad::box_faces makes them.
        let expected = [
            (p, e[2], e[1]),
            (p + e[0], e[1], e[2]),
            (p, e[0], e[2]),
            (p + e[1], e[2], e[0]),
            (p, e[1], e[0]),
            (p + e[2], e[0], e[1]),
        ];
        let faces = [f0, f1, f2, f3, f4, f5];
        let matches =
            faces.iter().zip(&expected).all(|(f, &(q, u, v))| close(f.origin, q) && close(f.e1, u) && close(f.e2, v));
        let volume = e[0].dot(e[1].cross(e[2]));
        if !(matches && volume > 0.0 && volume.is_finite()) {
            return None;
        }
        // Rows of the inverse edge matrix: D_k = (E_{k+1} × E_{k+2}) / volume.
        let dual = [e[1].cross(e[2]) / volume, e[2].cross(e[0]) / volume, e[0].cross(e[1]) / volume];
        Some(Self { p, dual })
    }

    /// Lanes whose ray meets the box surface at 0 ≤ t < limit: the hit mask, t, and the face
    /// hit (0..6 in the order above, as a float).
    #[inline(always)]
    pub fn test<const N: usize>(&self, o: &Vec3s<N>, d: &Vec3s<N>, limit: F32s<N>) -> (Ms<N>, F32s<N>, F32s<N>) {
        let rel = o.sub(&Vec3s::splat(self.p));
        let mut near = F32s::splat(f32::NEG_INFINITY);
        let mut far = F32s::splat(f32::INFINITY);
        let mut near_face = F32s::ZERO;
        let mut far_face = F32s::ZERO;
        for (k, dual) in self.dual.iter().enumerate() {
            let dual = Vec3s::splat(*dual);
            let s = rel.dot(&dual);
            let inv = 1.0 / d.dot(&dual);
            let t0 = -s * inv;
            let t1 = (1.0 - s) * inv;
            // Going up the axis the ray enters at the s = 0 face (2k) and leaves at s = 1
            // (2k + 1); going down, the other way round.
            let up = inv.ge(F32s::ZERO);
            let (t_in, t_out) = (F32s::select(up, t0, t1), F32s::select(up, t1, t0));
            let (face_in, face_out) = ((2 * k) as f32, (2 * k + 1) as f32);
            let (f_in, f_out) = (
                F32s::select(up, F32s::splat(face_in), F32s::splat(face_out)),
                F32s::select(up, F32s::splat(face_out), F32s::splat(face_in)),
            );
            let later = t_in.gt(near);
            near = F32s::select(later, t_in, near);
            near_face = F32s::select(later, f_in, near_face);
            let sooner = t_out.lt(far);
            far = F32s::select(sooner, t_out, far);
            far_face = F32s::select(sooner, f_out, far_face);
        }
        // From outside the first hit is the entry; from inside (entry behind), the exit.
        let outside = near.ge(F32s::ZERO);
        let t = F32s::select(outside, near, far);
        let face = F32s::select(outside, near_face, far_face);
        let hit = near.le(far) & t.ge(F32s::ZERO) & t.lt(limit);
        (hit, t, face)
    }
}
