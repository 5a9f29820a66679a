//! The film: accumulation buffer, variance, tone mapping.

mod accumulator;
#[allow(clippy::module_inception)]
mod film;
mod image;
pub mod tonemap;

pub use accumulator::PixelStats;
pub use film::{Film, RegionEstimate};
pub use image::Image;
pub use tonemap::{ToneMap, ToneMapSettings};
