//! Pixel-wise error metrics.

use crate::film::tonemap::{to_srgb8, ToneMapSettings};
use crate::film::Image;

/// Why two images cannot be compared.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MetricError {
    #[error("images differ in size: {0}×{1} vs {2}×{3}")]
    SizeMismatch(u32, u32, u32, u32),
    #[error("images are empty")]
    Empty,
    /// Errors against NaN or infinite values are NaN or infinite themselves: nothing to report.
    #[error("the {which} image has {count} NaN or infinite pixels; its errors are undefined")]
    NonFinite { which: &'static str, count: usize },
}

/// Checks that `test` and `reference` can be compared: same size, not empty, finite.
pub(super) fn check(test: &Image, reference: &Image) -> Result<(), MetricError> {
    if test.width != reference.width || test.height != reference.height {
        return Err(MetricError::SizeMismatch(test.width, test.height, reference.width, reference.height));
    }
    if test.pixels.is_empty() || test.pixels.len() != reference.pixels.len() {
        return Err(MetricError::Empty);
    }
    check_finite(reference, "reference")?;
    check_finite(test, "test")
}

/// Refuses an image with NaN or infinite pixels (`which` names it in the error).
pub fn check_finite(image: &Image, which: &'static str) -> Result<(), MetricError> {
    let count = image.pixels.iter().filter(|p| !p.to_array().iter().all(|v| v.is_finite())).count();
    if count > 0 {
        return Err(MetricError::NonFinite { which, count });
    }
    Ok(())
}

fn channels(img: &Image) -> impl Iterator<Item = f64> + '_ {
    img.pixels.iter().flat_map(|p| p.to_array()).map(|v| v as f64)
}

/// Mean squared error over all pixels and channels: (1/3mn) Σ (a − b)².
pub fn mse(test: &Image, reference: &Image) -> Result<f64, MetricError> {
    check(test, reference)?;
    let n = 3 * test.pixels.len();
    Ok(channels(test).zip(channels(reference)).map(|(a, b)| (a - b) * (a - b)).sum::<f64>() / n as f64)
}

/// Root mean squared error.
pub fn rmse(test: &Image, reference: &Image) -> Result<f64, MetricError> {
    mse(test, reference).map(f64::sqrt)
}

/// Relative MSE: (1/3mn) Σ (a − b)² / (b² + 0.01). The 0.01 keeps black reference pixels from
/// dominating (the usual choice in rendering papers, e.g. Rousselle et al. 2011).
pub fn relative_mse(test: &Image, reference: &Image) -> Result<f64, MetricError> {
    check(test, reference)?;
    let n = 3 * test.pixels.len();
    Ok(channels(test).zip(channels(reference)).map(|(a, b)| (a - b) * (a - b) / (b * b + 0.01)).sum::<f64>() / n as f64)
}

/// The image as displayed: clamped, sRGB-encoded 8-bit values, three per pixel.
pub fn to_8bit(img: &Image) -> Vec<u8> {
    let settings = ToneMapSettings::default();
    img.pixels.iter().flat_map(|&p| to_srgb8(p, &settings)).collect()
}

/// 10 log₁₀(MAX² / MSE): infinite for identical images, NaN (undefined) when MAX is 0 but the
/// images differ, as against a black reference in linear PSNR.
fn psnr(mse: f64, max: f64) -> f64 {
    if mse == 0.0 {
        f64::INFINITY
    } else if max <= 0.0 {
        f64::NAN
    } else {
        10.0 * (max * max / mse).log10()
    }
}

/// PSNR = 10 log₁₀(MAX² / MSE) on the 8-bit displayed images with MAX = 255, as the design
/// document defines it (its MSE averaged over the three channels).
pub fn psnr_8bit(test: &Image, reference: &Image) -> Result<f64, MetricError> {
    check(test, reference)?;
    let (a, b) = (to_8bit(test), to_8bit(reference));
    let mse = a.iter().zip(&b).map(|(&x, &y)| (x as f64 - y as f64).powi(2)).sum::<f64>() / a.len() as f64;
    Ok(psnr(mse, 255.0))
}

/// PSNR on linear (HDR) values, with the reference's largest channel value as MAX.
pub fn psnr_linear(test: &Image, reference: &Image) -> Result<f64, MetricError> {
    let mse = mse(test, reference)?;
    let peak = channels(reference).fold(0.0f64, f64::max);
    Ok(psnr(mse, peak))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;

    fn img(w: u32, h: u32, px: &[f32]) -> Image {
        Image::from_pixels(w, h, px.iter().map(|&v| Rgb::splat(v)).collect()).unwrap()
    }

    #[test]
    fn hand_computed_errors() {
        let a = img(2, 1, &[0.5, 1.0]);
        let b = img(2, 1, &[0.25, 1.0]);
        // Differences 0.25 (×3 channels) and 0 (×3): MSE = 3·0.0625 / 6 = 0.03125.
        assert!((mse(&a, &b).unwrap() - 0.03125).abs() < 1e-12);
        assert!((rmse(&a, &b).unwrap() - 0.03125f64.sqrt()).abs() < 1e-12);
        // Relative: 0.0625 / (0.0625 + 0.01) for three channels, 0 for the rest, over 6.
        let rel = 3.0 * 0.0625 / (0.0625 + 0.01) / 6.0;
        assert!((relative_mse(&a, &b).unwrap() - rel).abs() < 1e-9);
        // Linear PSNR with peak 1: 10 log10(1 / 0.03125) = 15.051 dB.
        assert!((psnr_linear(&a, &b).unwrap() - 15.051_499_783).abs() < 1e-6);
    }

    #[test]
    fn psnr_8bit_uses_display_values() {
        // 1.0 → 255 and 0.0 → 0: MSE over 6 channels = 3·255² / 6, PSNR = 10 log10(2) = 3.0103 dB.
        let a = img(2, 1, &[1.0, 0.0]);
        let b = img(2, 1, &[0.0, 0.0]);
        assert!((psnr_8bit(&a, &b).unwrap() - 3.010_299_956).abs() < 1e-6);
        assert_eq!(psnr_8bit(&a, &a).unwrap(), f64::INFINITY);
    }

    #[test]
    fn non_finite_pixels_are_counted_and_refused_and_black_references_have_no_linear_psnr() {
        let nan = img(2, 1, &[f32::NAN, 1.0]);
        let inf = img(2, 1, &[f32::INFINITY, f32::NEG_INFINITY]);
        let fine = img(2, 1, &[0.5, 1.0]);
        assert_eq!(mse(&nan, &fine), Err(MetricError::NonFinite { which: "test", count: 1 }));
        assert_eq!(psnr_8bit(&fine, &inf), Err(MetricError::NonFinite { which: "reference", count: 2 }));
        assert_eq!(psnr_linear(&nan, &nan), Err(MetricError::NonFinite { which: "reference", count: 1 }));
        let black = img(2, 1, &[0.0, 0.0]);
        assert!(psnr_linear(&fine, &black).unwrap().is_nan());
        assert_eq!(psnr_linear(&black, &black).unwrap(), f64::INFINITY);
    }

    #[test]
    fn sizes_must_match() {
        let a = img(2, 1, &[0.5, 1.0]);
        let b = img(1, 2, &[0.5, 1.0]);
        assert_eq!(mse(&a, &b), Err(MetricError::SizeMismatch(2, 1, 1, 2)));
    }
}
