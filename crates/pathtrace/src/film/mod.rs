//! The film: accumulation buffer, variance, tone mapping, pixel reconstruction filters.

mod accumulator;
mod allocation;
mod features;
mod file;
#[allow(clippy::module_inception)]
mod film;
pub mod filter;
mod fingerprint;
mod grid;
mod image;
mod noise;
mod ranged;
mod splat;
pub mod tonemap;

pub(crate) use accumulator::{small_terms, SMALL_SAMPLE};
pub use accumulator::{PixelStats, FRACTION_BITS, SAMPLE_LIMIT};
pub use allocation::{FilmTooLarge, FILM_BYTES_PER_PIXEL};
pub use features::{FeatureBuffers, FeaturePixel, FeatureSample, FEATURE_BYTES_PER_PIXEL};
pub use file::{FilmFileError, FILE_BYTES_PER_PIXEL, FILE_FEATURE_BYTES_PER_PIXEL, FORMAT_VERSION};
pub use film::{Film, RegionEstimate};
pub use filter::{GaussianFilter, PixelFilter};
pub use fingerprint::{engine_build, render_key, Fnv64};
pub use grid::{Mergeable, PixelGrid};
pub use image::Image;
pub use noise::{relative_variance, RELATIVE_EPSILON};
pub use ranged::{MergeError, RangedFilm};
pub use splat::{splat_margin, SplatBlock, SplatPixel};
pub use tonemap::{ToneMap, ToneMapSettings};
