//! The "test every primitive" intersector: no hierarchy, the same SIMD leaf packets as the BVH
//! laid end to end. It is the reference the BVH is checked against and the O(n)-per-ray
//! baseline of the analysis in docs/bvh.md; never used for rendering.

use super::lanes::RayX4;
use super::leaf::{Leaves, Packable};
use super::PrimitiveSet;
use crate::math::Ray;
use crate::shape::PrimHit;

/// Primitives per leaf record (a leaf counts its unpacked primitives in a `u8`).
const CHUNK: usize = 128;

/// Every primitive, in the caller's order, in packets of four.
#[derive(Clone, Debug, Default)]
pub struct BruteForce {
    leaves: Leaves,
    /// The leaf references, in order.
    refs: Vec<u32>,
}

impl BruteForce {
    /// `kinds[i]` says how primitive `i` is stored (as for [`super::Bvh::build`]); the
    /// primitives keep their order.
    pub fn new(kinds: &[Packable]) -> Self {
        let mut leaves = Leaves::default();
        let mut refs = Vec::new();
        for start in (0..kinds.len()).step_by(CHUNK) {
            let end = (start + CHUNK).min(kinds.len());
            refs.push(leaves.push((start..end).map(|i| (i as u32, kinds[i]))));
        }
        leaves.shrink_to_fit();
        Self { leaves, refs }
    }

    /// Closest hit among `prims` (in the order given to [`BruteForce::new`]).
    pub fn intersect<P: PrimitiveSet + ?Sized>(
        &self,
        prims: &P,
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
    ) -> Option<(PrimHit, u32)> {
        let rx4 = RayX4::new(ray);
        let mut best = None;
        for &leaf in &self.refs {
            self.leaves.intersect(leaf, prims, ray, &rx4, t_min, &mut t_max, &mut best);
        }
        best
    }

    /// True if anything blocks the ray within `[t_min, t_max]`.
    pub fn occluded<P: PrimitiveSet + ?Sized>(&self, prims: &P, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        let rx4 = RayX4::new(ray);
        self.refs.iter().any(|&leaf| self.leaves.occluded(leaf, prims, ray, &rx4, t_min, t_max))
    }

    /// Heap bytes held (the packets), from the vectors' capacities.
    pub fn memory_bytes(&self) -> usize {
        std::mem::size_of_val(self) + self.leaves.memory_bytes() + self.refs.capacity() * std::mem::size_of::<u32>()
    }
}
