//! Axis-aligned bounding boxes and the slab test.

use glam::{Vec3, Vec3A};

/// An axis-aligned box `[min, max]`. The empty box has `min = +∞`, `max = -∞`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb { min: Vec3::splat(f32::INFINITY), max: Vec3::splat(f32::NEG_INFINITY) };

    pub fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    pub fn from_points(points: &[Vec3]) -> Self {
        points.iter().fold(Self::EMPTY, |b, &p| b.grow(p))
    }

    pub fn grow(self, p: Vec3) -> Self {
        Self::new(self.min.min(p), self.max.max(p))
    }

    pub fn union(self, o: Aabb) -> Self {
        Self::new(self.min.min(o.min), self.max.max(o.max))
    }

    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    pub fn centroid(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    pub fn extent(&self) -> Vec3 {
        (self.max - self.min).max(Vec3::ZERO)
    }

    /// Surface area, the SAH's probability measure (MacDonald & Booth 1990).
    pub fn surface_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// Grows the box by a relative margin so that rounding in primitive tests never falls
    /// outside it (rays grazing a box face still reach the primitive).
    pub fn padded(self) -> Self {
        let pad =
            (self.extent() * 1e-5).max(Vec3::splat(1e-6 * (1.0 + self.max.abs().max(self.min.abs()).max_element())));
        Self::new(self.min - pad, self.max + pad)
    }

    /// Slab test (Kay & Kajiya 1986) with precomputed reciprocal direction; returns the entry
    /// distance when the ray overlaps the box within `[t_min, t_max]`.
    ///
    /// Computed on 4-wide SIMD lanes (`Vec3A`). A NaN from `0 · ∞` (a ray in a slab's plane)
    /// makes the comparison fail, i.e. counts as a miss, which only affects rays exactly along a
    /// box face.
    #[inline(always)]
    pub fn hit(&self, origin: Vec3A, inv_dir: Vec3A, t_min: f32, t_max: f32) -> Option<f32> {
        let t0 = (Vec3A::from(self.min) - origin) * inv_dir;
        let t1 = (Vec3A::from(self.max) - origin) * inv_dir;
        let near = t0.min(t1).max_element().max(t_min);
        let far = t0.max(t1).min_element().min(t_max);
        (near <= far).then_some(near)
    }
}
