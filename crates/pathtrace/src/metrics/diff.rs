//! Difference images: a grey copy of the reference with every pixel that differs from the test
//! image by more than a threshold (in 8-bit display steps, largest channel) painted red.

use super::error::{check, to_8bit, MetricError};
use crate::film::tonemap::srgb_decode;
use crate::film::Image;
use crate::math::Rgb;

/// Returns the difference image and the number of pixels marked.
pub fn difference_image(test: &Image, reference: &Image, threshold: u8) -> Result<(Image, usize), MetricError> {
    check(test, reference)?;
    let (a, b) = (to_8bit(test), to_8bit(reference));
    let mut marked = 0;
    let pixels = a
        .chunks(3)
        .zip(b.chunks(3))
        .map(|(pa, pb)| {
            let d = pa.iter().zip(pb).map(|(&x, &y)| x.abs_diff(y)).max().unwrap_or(0);
            if d > threshold {
                marked += 1;
                Rgb::new(1.0, 0.0, 0.0)
            } else {
                // Grey at half brightness of the reference's display luminance, so red stands out.
                let l = (0.2126 * pb[0] as f32 + 0.7152 * pb[1] as f32 + 0.0722 * pb[2] as f32) / 255.0;
                Rgb::splat(srgb_decode(0.5 * l))
            }
        })
        .collect();
    Ok((Image { width: test.width, height: test.height, pixels }, marked))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marks_only_pixels_beyond_the_threshold() {
        let a = Image::from_pixels(3, 1, vec![Rgb::splat(0.5), Rgb::splat(0.52), Rgb::splat(0.9)]).unwrap();
        let b = Image::from_pixels(3, 1, vec![Rgb::splat(0.5); 3]).unwrap();
        let (d, n) = difference_image(&a, &b, 8).unwrap();
        // 0.5 vs 0.52 is ~3 steps in sRGB 8-bit: below 8; 0.9 vs 0.5 is far above.
        assert_eq!(n, 1);
        assert_eq!(d.pixels[2], Rgb::new(1.0, 0.0, 0.0));
        assert_ne!(d.pixels[1], Rgb::new(1.0, 0.0, 0.0));
    }
}
