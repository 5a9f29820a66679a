//! Rays through opacity masks (`texture::Opacity`): a ray meets a surface of opacity α with
//! probability α and passes straight through it otherwise, as in pbrt-v4's alpha test (§6.1.3:
//! the choice is a hash of the ray, so it needs no sampler dimension and every kernel makes the
//! same one). Camera, continuation and shadow rays all pass, so light sampling sees through
//! cut-outs, and a path's next vertex (with its MIS densities) is the first surface it meets.
//!
//! Unlike Mitsuba 3's `path` integrator, where a pass through a `mask` is a null scattering
//! event that counts towards `max_depth` and shadow rays stop at masked surfaces, passing
//! through here is not a path segment; both are unbiased, and agree when depth is unlimited.

use crate::math::{offset_ray_origin, Ray};
use crate::scene::{Hit, Interaction, Scene};

/// At most this many cut-out surfaces are passed along one ray (a stack of leaves); the ray
/// stops at the next one.
const MAX_PASSES: u32 = 64;

impl Scene {
    /// The closest surface along `ray` that is there (not cut out), with the ray segment that
    /// found it (its origin moved past the surfaces passed).
    ///
    /// Out of line, like [`Scene::occluded_opaque`]: these single-ray queries are the BVH walks
    /// of every scattered ray, and inlined they put a copy of the tree traversal (several, one
    /// per stack size) into each copy of the render loop, whose compile time grows faster than
    /// its size (docs/benchmarks.md, "Build times"); a call per ray costs nothing measurable
    /// beside the walk it makes.
    #[inline(never)]
    pub fn intersect_opaque(&self, ray: &Ray) -> Option<(Ray, Hit)> {
        let hit = self.intersect(ray, f32::INFINITY)?;
        if !self.has_cutouts() {
            return Some((*ray, hit));
        }
        self.pass_cutouts(*ray, hit, f32::INFINITY).map(|(r, h, _)| (r, h))
    }

    /// True if a surface that is there lies along `ray` within `t_max`.
    #[inline(never)]
    pub fn occluded_opaque(&self, ray: &Ray, t_max: f32) -> bool {
        if !self.has_cutouts() {
            return self.occluded(ray, t_max);
        }
        self.intersect(ray, t_max).is_some_and(|hit| self.pass_cutouts(*ray, hit, t_max).is_some())
    }

    /// From `hit` on `ray`, passes cut-out surfaces until one is met within `t_max` (`None` if
    /// none is).
    #[inline(never)]
    fn pass_cutouts(&self, mut ray: Ray, mut hit: Hit, mut t_max: f32) -> Option<(Ray, Hit, f32)> {
        let key = ray_key(&ray);
        for pass in 0..MAX_PASSES {
            let it = self.interaction(&ray, &hit);
            let alpha = self.opacity(&it);
            if alpha >= 1.0 || (alpha > 0.0 && unit_hash(key, pass) < alpha) {
                return Some((ray, hit, t_max));
            }
            t_max -= hit.hit.t;
            ray = Ray::new(offset_ray_origin(it.surface.p, it.surface.n_geometric, ray.dir), ray.dir);
            hit = self.intersect(&ray, t_max)?;
        }
        Some((ray, hit, t_max))
    }

    /// The opacity of the surface at a hit (1 for materials without a mask).
    #[inline]
    pub fn opacity(&self, it: &Interaction) -> f32 {
        self.opacity_mask(it.material_id).map_or(1.0, |o| o.at(self.textures(), it.surface.uv))
    }
}

/// The bits of a ray's origin and direction, mixed into one key.
fn ray_key(ray: &Ray) -> u64 {
    let bits = [ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z].map(f32::to_bits);
    bits.iter().fold(0x9e37_79b9_7f4a_7c15u64, |h, &b| mix(h ^ u64::from(b)))
}

/// A number in [0, 1) from the key and the pass number.
fn unit_hash(key: u64, pass: u32) -> f32 {
    (mix(key ^ u64::from(pass).wrapping_mul(0xbf58_476d_1ce4_e5b9)) >> 40) as f32 / (1u64 << 24) as f32
}

/// The 64-bit finaliser of MurmurHash3 (Appleby): every input bit affects every output bit.
fn mix(mut h: u64) -> u64 {
    h ^= h >> 33;
    h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
    h ^= h >> 33;
    h = h.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    h ^ (h >> 33)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hash_is_uniform_enough_for_an_alpha_test() {
        // 16 bins of 64k keys: each bin within 5σ of 4096.
        let mut bins = [0u32; 16];
        for i in 0..65536u64 {
            bins[(unit_hash(mix(i), 0) * 16.0) as usize] += 1;
        }
        for b in bins {
            assert!((i64::from(b) - 4096).abs() < 5 * 62, "{bins:?}");
        }
        assert!((0..1000).all(|i| (0.0..1.0).contains(&unit_hash(i, 3))));
    }
}
