//! The film: accumulation buffer, variance, tone mapping.

mod image;
pub mod tonemap;

pub use image::Image;
pub use tonemap::{ToneMap, ToneMapSettings};
