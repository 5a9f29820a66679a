//! Random draws shared by the acceleration tests' generators of rays, boxes and triangles.

use glam::Vec3;

use crate::sampling::Pcg32;

/// A float uniform in `[lo, hi)` (24 random bits).
pub(super) fn uniform(rng: &mut Pcg32, lo: f32, hi: f32) -> f32 {
    lo + (hi - lo) * (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32
}

/// A point uniform in the cube `[-extent, extent)³`.
pub(super) fn point(rng: &mut Pcg32, extent: f32) -> Vec3 {
    Vec3::new(uniform(rng, -extent, extent), uniform(rng, -extent, extent), uniform(rng, -extent, extent))
}
