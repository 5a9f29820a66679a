//! An orthonormal shading frame: local coordinates with the normal along +z.

use crate::wide::simd::Vec3s;
use glam::Vec3;

/// An orthonormal basis (s, t, n). BSDFs work in this frame, where `cos θ = w.z`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub s: Vec3,
    pub t: Vec3,
    pub n: Vec3,
}

impl Frame {
    /// Builds a frame around a unit normal with the branchless construction of
    /// Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017).
    pub fn from_normal(n: Vec3) -> Self {
        let (s, t) = crate::wide::warp::basis(&Vec3s::<1>::splat(n));
        Self { s: s.lane(0), t: t.lane(0), n }
    }

    /// A frame around the unit normal `n` whose first tangent follows `tangent` (made
    /// perpendicular to `n` by Gram–Schmidt, as Mitsuba 3 builds its shading frame from ∂p/∂u);
    /// when `tangent` is (nearly) parallel to `n` or zero, [`Frame::from_normal`]. The one-lane
    /// instance of [`crate::wide::warp::tangent_basis`].
    pub fn from_normal_tangent(n: Vec3, tangent: Vec3) -> Self {
        let (s, t) = crate::wide::warp::tangent_basis(&Vec3s::<1>::splat(n), &Vec3s::splat(tangent));
        Self { s: s.lane(0), t: t.lane(0), n }
    }

    /// World → local.
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// Local → world.
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_orthonormal_and_invertible() {
        let normals = [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.4, 0.866).normalize(),
            Vec3::new(1e-8, 0.0, -1.0).normalize(),
        ];
        for n in normals {
            let f = Frame::from_normal(n);
            assert!((f.s.length() - 1.0).abs() < 1e-5);
            assert!((f.t.length() - 1.0).abs() < 1e-5);
            assert!(f.s.dot(f.t).abs() < 1e-5 && f.s.dot(n).abs() < 1e-5 && f.t.dot(n).abs() < 1e-5);
            assert!((f.s.cross(f.t) - n).length() < 1e-5, "right-handed");
            let v = Vec3::new(0.2, -0.7, 0.5);
            assert!((f.to_world(f.to_local(v)) - v).length() < 1e-5);
        }
    }
}
