//! Rays `R(t) = O + tD`, intersected over an interval `[t_min, t_max]`.

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
    let scale = 1e-4 * (1.0 + p.abs().max_element());
    let n = if geometric_normal.dot(dir) >= 0.0 { geometric_normal } else { -geometric_normal };
    p + n * scale
}
