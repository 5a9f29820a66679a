//! The film: accumulation buffer, variance, tone mapping, pixel reconstruction filters.

mod accumulator;
mod allocation;
mod features;
#[allow(clippy::module_inception)]
mod film;
pub mod filter;
mod image;
mod noise;
pub mod tonemap;

pub use accumulator::PixelStats;
pub use allocation::{FilmTooLarge, FILM_BYTES_PER_PIXEL};
pub use features::{FeatureBuffers, FeaturePixel, FeatureSample};
pub use film::{Film, RegionEstimate};
pub use filter::{FilterSample, GaussianFilter, PixelFilter};
pub use image::Image;
pub use noise::{relative_variance, RELATIVE_EPSILON};
pub use tonemap::{ToneMap, ToneMapSettings};
