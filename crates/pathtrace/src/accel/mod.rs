//! Acceleration: a bounding volume hierarchy over the scene's bounded primitives.

mod bvh;

pub use bvh::{Bvh, BvhStats, Intersectable};
