//! Acceleration: a bounding volume hierarchy over the scene's bounded primitives.

mod build;
mod bvh;
mod lanes;
mod leaf;
mod quad4;
mod tri4;
mod wide;

pub use bvh::{Bvh, BvhStats, Intersectable};
pub use leaf::Packable;
