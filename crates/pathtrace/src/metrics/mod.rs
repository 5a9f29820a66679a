//! Image comparison: errors (MSE, RMSE, relative MSE), PSNR on 8-bit and linear values, SSIM,
//! and difference images. Every function takes the test image first and the reference second.

mod diff;
mod error;
mod ssim;

pub use diff::difference_image;
pub use error::{check_finite, mse, psnr_8bit, psnr_linear, relative_mse, rmse, to_8bit, MetricError};
pub use ssim::ssim;

use crate::film::Image;

/// All the metrics of one comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Comparison {
    pub mse: f64,
    pub rmse: f64,
    pub relative_mse: f64,
    /// PSNR of the 8-bit sRGB images (MAX = 255), in dB; infinite for identical images.
    pub psnr_8bit: f64,
    /// PSNR of the linear values with the reference's peak as MAX, in dB; infinite for identical
    /// images, NaN (undefined) against a black reference.
    pub psnr_linear: f64,
    pub ssim: f64,
}

/// Computes every metric of `test` against `reference`.
pub fn compare(test: &Image, reference: &Image) -> Result<Comparison, MetricError> {
    let mse = mse(test, reference)?;
    Ok(Comparison {
        mse,
        rmse: mse.sqrt(),
        relative_mse: relative_mse(test, reference)?,
        psnr_8bit: psnr_8bit(test, reference)?,
        psnr_linear: psnr_linear(test, reference)?,
        ssim: ssim(test, reference)?,
    })
}
