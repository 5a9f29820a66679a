//! Structural similarity (Wang, Bovik, Sheikh & Simoncelli, "Image Quality Assessment: From Error
//! Visibility to Structural Similarity", IEEE TIP 2004): on the 8-bit displayed luminance, with
//! the paper's 11×11 Gaussian window (σ = 1.5), K₁ = 0.01, K₂ = 0.03, L = 255; the mean SSIM over
//! all window positions that fit in the image (the whole image when it is smaller).

use super::error::{check, to_8bit, MetricError};
use crate::film::Image;

const RADIUS: usize = 5;
const SIGMA: f64 = 1.5;

/// Mean SSIM of `test` against `reference`, in [-1, 1] (1 for identical images).
pub fn ssim(test: &Image, reference: &Image) -> Result<f64, MetricError> {
    check(test, reference)?;
    let (w, h) = (test.width as usize, test.height as usize);
    let luma = |img: &Image| -> Vec<f64> {
        to_8bit(img).chunks(3).map(|c| 0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64).collect()
    };
    let (x, y) = (luma(test), luma(reference));
    let r = RADIUS.min((w.min(h) - 1) / 2);
    let size = 2 * r + 1;
    let weights: Vec<f64> = {
        let mut k = Vec::with_capacity(size * size);
        for j in 0..size {
            for i in 0..size {
                let (dx, dy) = (i as f64 - r as f64, j as f64 - r as f64);
                k.push((-(dx * dx + dy * dy) / (2.0 * SIGMA * SIGMA)).exp());
            }
        }
        let total: f64 = k.iter().sum();
        k.into_iter().map(|v| v / total).collect()
    };
    let (c1, c2) = ((0.01 * 255.0f64).powi(2), (0.03 * 255.0f64).powi(2));
    let mut sum = 0.0;
    let mut count = 0usize;
    for cy in r..h - r {
        for cx in r..w - r {
            let (mut mx, mut my, mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
            for j in 0..size {
                for i in 0..size {
                    let idx = (cy + j - r) * w + (cx + i - r);
                    let k = weights[j * size + i];
                    let (a, b) = (x[idx], y[idx]);
                    mx += k * a;
                    my += k * b;
                    sxx += k * a * a;
                    syy += k * b * b;
                    sxy += k * a * b;
                }
            }
            let (vx, vy, cov) = (sxx - mx * mx, syy - my * my, sxy - mx * my);
            sum += ((2.0 * mx * my + c1) * (2.0 * cov + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
            count += 1;
        }
    }
    Ok(sum / count.max(1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;

    #[test]
    fn identical_images_score_one_and_noise_scores_less() {
        let px: Vec<Rgb> = (0..32 * 32).map(|i| Rgb::splat(((i * 7) % 13) as f32 / 13.0)).collect();
        let a = Image::from_pixels(32, 32, px.clone()).unwrap();
        assert!((ssim(&a, &a).unwrap() - 1.0).abs() < 1e-12);
        let noisy: Vec<Rgb> = px.iter().enumerate().map(|(i, p)| *p * if i % 2 == 0 { 0.5 } else { 1.0 }).collect();
        let b = Image::from_pixels(32, 32, noisy).unwrap();
        let s = ssim(&b, &a).unwrap();
        assert!(s < 0.95 && s > -1.0, "{s}");
    }

    #[test]
    fn constant_images_follow_the_luminance_term() {
        // Two flat images: σ terms vanish, SSIM = (2μxμy + C1) / (μx² + μy² + C1).
        let a = Image::from_pixels(16, 16, vec![Rgb::splat(1.0); 256]).unwrap(); // 255
        let b = Image::from_pixels(16, 16, vec![Rgb::splat(0.0); 256]).unwrap(); // 0
        let c1 = (0.01f64 * 255.0).powi(2);
        let expected = c1 / (255.0f64 * 255.0 + c1);
        assert!((ssim(&a, &b).unwrap() - expected).abs() < 1e-9);
    }
}
