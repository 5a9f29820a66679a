//! Acceleration: a bounding volume hierarchy over the scene's bounded primitives.

mod brute;
mod build;
mod bvh;
mod group_hits;
mod lanes;
mod leaf;
mod quad4;
mod subtree;
#[cfg(test)]
mod test_draws;
mod tri4;
mod wide;

pub use brute::BruteForce;
pub use build::{BuildOptions, SplitMethod, MAX_BINS, MAX_LEAF_LIMIT};
pub use bvh::{Bvh, BvhMemory, BvhStats, Intersectable, PrimitiveSet};
pub use leaf::Packable;
