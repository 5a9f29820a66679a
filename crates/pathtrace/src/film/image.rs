//! A linear RGB image (placeholder, being written).
use crate::math::Rgb;

/// A linear-light RGB image, row-major from the top-left pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Rgb>,
}
