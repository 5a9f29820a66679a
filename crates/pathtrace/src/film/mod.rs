//! The film: accumulation buffer, variance, tone mapping.

mod accumulator;
#[allow(clippy::module_inception)]
mod film;
mod image;
mod noise;
pub mod tonemap;

pub use accumulator::PixelStats;
pub use film::{Film, RegionEstimate};
pub use image::Image;
pub use noise::{relative_variance, RELATIVE_EPSILON};
pub use tonemap::{ToneMap, ToneMapSettings};
