//! Four-wide SIMD helpers shared by the primitive packets: a ray splatted across four lanes
//! and the per-lane hit record ("structure of arrays" packets, as in Wald et al., "Embree: A
//! Kernel Framework for Efficient CPU Ray Tracing", SIGGRAPH 2014, with lanes = primitives).

use glam::{BVec4A, Vec3, Vec4};

use crate::math::Ray;

/// Three coordinates of four primitives, one `Vec4` per axis.
#[derive(Clone, Copy, Debug)]
pub(super) struct Vec3x4 {
    pub x: Vec4,
    pub y: Vec4,
    pub z: Vec4,
}

impl Vec3x4 {
    /// Packs up to four vectors; missing lanes are zero.
    pub fn gather(vs: &[Vec3]) -> Self {
        let lane = |i: usize, f: fn(&Vec3) -> f32| vs.get(i).map_or(0.0, f);
        let axis = |f: fn(&Vec3) -> f32| Vec4::new(lane(0, f), lane(1, f), lane(2, f), lane(3, f));
        Self { x: axis(|v| v.x), y: axis(|v| v.y), z: axis(|v| v.z) }
    }

    /// Packs `f` of up to four items; missing lanes are zero (no allocation).
    #[inline]
    pub fn gather_with<T>(items: &[T], f: impl Fn(&T) -> Vec3) -> Self {
        let mut v = [Vec3::ZERO; 4];
        for (slot, item) in v.iter_mut().zip(items) {
            *slot = f(item);
        }
        Self::gather(&v[..items.len().min(4)])
    }

    pub fn splat(v: Vec3) -> Self {
        Self { x: Vec4::splat(v.x), y: Vec4::splat(v.y), z: Vec4::splat(v.z) }
    }

    /// Lane-wise dot product, summed in glam's scalar order `x·x' + y·y' + z·z'` so that each
    /// lane rounds exactly as the scalar shape tests do.
    #[inline(always)]
    pub fn dot(&self, o: &Self) -> Vec4 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Lane-wise cross product, in glam's scalar operand order (bit-identical lanes).
    #[inline(always)]
    pub fn cross(&self, o: &Self) -> Self {
        Self { x: self.y * o.z - o.y * self.z, y: self.z * o.x - o.z * self.x, z: self.x * o.y - o.x * self.y }
    }

    #[inline(always)]
    pub fn sub(&self, o: &Self) -> Self {
        Self { x: self.x - o.x, y: self.y - o.y, z: self.z - o.z }
    }
}

/// A ray broadcast to four lanes.
#[derive(Clone, Copy, Debug)]
pub(super) struct RayX4 {
    pub origin: Vec3x4,
    pub dir: Vec3x4,
}

impl RayX4 {
    #[inline(always)]
    pub fn new(ray: &Ray) -> Self {
        Self { origin: Vec3x4::splat(ray.origin), dir: Vec3x4::splat(ray.dir) }
    }
}

/// Which lanes hit, and where.
#[derive(Clone, Copy, Debug)]
pub(super) struct HitX4 {
    pub mask: BVec4A,
    pub t: Vec4,
    pub u: Vec4,
    pub v: Vec4,
}
