//! Sampling: random numbers, warps from the unit square with their pdfs, MIS heuristics,
//! discrete distributions and the per-pixel samplers.

mod distribution;
mod distribution2d;
pub mod hash;
mod mis;
mod pcg;
mod sampler;
pub mod sobol;
pub mod warp;

pub use distribution::Distribution1D;
pub use distribution2d::Distribution2D;
pub use mis::{balance_heuristic, power_heuristic};
pub use pcg::Pcg32;
pub(crate) use pcg::MULTIPLIER as PCG_MULTIPLIER;
pub use sampler::{Sampler, SamplerKind};
