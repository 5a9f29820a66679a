//! Rays `R(t) = O + tD`, intersected over an interval `[t_min, t_max]`.

use crate::wide::simd::{F32s, Vec3s};
use glam::Vec3;

/// A ray with origin `origin` and direction `dir` (not necessarily unit length for every use,
/// but the renderer always creates unit directions so `t` is a distance).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
}

impl Ray {
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Self { origin, dir }
    }

    /// The point `O + tD`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}

/// Moves a surface point off its surface, to the side that `dir` leaves towards, so a ray
/// spawned there does not re-hit the surface it starts on ("shadow acne").
///
/// The offset is relative to the point's magnitude: f32 intersection points carry an error of
/// a few ulps of their largest coordinate, and 1e-4 of it keeps well clear of that while staying
/// far below any feature size the scenes use (0.06 units in the 555-unit Cornell box).
pub fn offset_ray_origin(p: Vec3, geometric_normal: Vec3, dir: Vec3) -> Vec3 {
    let one = |v: Vec3| Vec3s::<1>::splat(v);
    offset_ray_origin_lanes(&one(p), &one(geometric_normal), &one(dir)).lane(0)
}

/// [`offset_ray_origin`] in every lane.
#[inline(always)]
pub fn offset_ray_origin_lanes<const N: usize>(p: &Vec3s<N>, geometric_normal: &Vec3s<N>, dir: &Vec3s<N>) -> Vec3s<N> {
    let scale = (p.max_abs() + 1.0) * 1e-4;
    let towards = geometric_normal.dot(dir).ge(F32s::ZERO);
    let n = Vec3s::select(towards, geometric_normal, &geometric_normal.neg());
    p.add(&n.scale(scale))
}
