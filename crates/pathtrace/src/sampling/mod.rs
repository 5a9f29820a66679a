//! Sampling: random numbers, warps from the unit square with their pdfs, MIS heuristics,
//! discrete distributions and the per-pixel samplers.

mod distribution;
mod distribution2d;
pub(crate) mod guide;
pub mod hash;
mod mis;
pub(crate) mod pcg;
pub(crate) mod sampler;
pub mod sobol;
pub mod warp;

pub use distribution::Distribution1D;
pub use distribution2d::Distribution2D;
pub use mis::{balance_heuristic, balance_heuristic_lanes, power_heuristic, power_heuristic_lanes};
pub use pcg::Pcg32;
pub use sampler::{Sampler, SamplerKind};
