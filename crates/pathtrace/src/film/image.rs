//! A linear RGB image: the renderer's output before any tone mapping or encoding.
use crate::math::Rgb;

/// A linear-light RGB image, row-major from the top-left pixel.
///
/// The fields are public for cheap access; an `Image` whose `pixels.len()` is not
/// `width * height` is inconsistent, and the file writers reject it.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` pixels, row by row from the top-left one.
    pub pixels: Vec<Rgb>,
}

impl Image {
    /// A black image of the given size (either side may be zero: an empty image).
    pub fn new(width: u32, height: u32) -> Image {
        let len = pixel_count(width, height).unwrap_or(0);
        Image { width, height, pixels: vec![Rgb::BLACK; len] }
    }

    /// An image from row-major pixels, or `None` if `pixels.len() != width * height`.
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<Rgb>) -> Option<Image> {
        (pixel_count(width, height) == Some(pixels.len())).then_some(Image { width, height, pixels })
    }

    /// True when the image has no pixels (zero width or zero height).
    pub fn is_empty(&self) -> bool {
        self.width == 0 || self.height == 0
    }

    /// True when `pixels.len() == width * height`.
    pub fn is_consistent(&self) -> bool {
        pixel_count(self.width, self.height) == Some(self.pixels.len())
    }

    /// Index into `pixels` of pixel `(x, y)`, or `None` outside the image.
    pub fn index(&self, x: u32, y: u32) -> Option<usize> {
        if x < self.width && y < self.height {
            Some(y as usize * self.width as usize + x as usize)
        } else {
            None
        }
    }

    /// The pixel at column `x`, row `y` (row 0 is the top), or `None` outside the image.
    pub fn try_get(&self, x: u32, y: u32) -> Option<Rgb> {
        self.index(x, y).and_then(|i| self.pixels.get(i).copied())
    }

    /// The pixel at column `x`, row `y` (row 0 is the top).
    ///
    /// # Panics
    /// If `(x, y)` is outside the image, like slice indexing; use [`Image::try_get`]
    /// for coordinates that come from outside the program.
    pub fn get(&self, x: u32, y: u32) -> Rgb {
        match self.try_get(x, y) {
            Some(c) => c,
            None => panic!("pixel ({x}, {y}) is outside the {}x{} image", self.width, self.height),
        }
    }

    /// Sets the pixel at column `x`, row `y`; returns false (and changes nothing)
    /// when `(x, y)` is outside the image.
    pub fn set(&mut self, x: u32, y: u32, value: Rgb) -> bool {
        match self.index(x, y).and_then(|i| self.pixels.get_mut(i)) {
            Some(p) => {
                *p = value;
                true
            }
            None => false,
        }
    }

    /// Mean of all pixels, accumulated in `f64`; black for an empty image.
    pub fn mean(&self) -> Rgb {
        mean_of(self.pixels.iter().copied())
    }

    /// Mean of the pixels in the half-open rectangle `[x0, x1) × [y0, y1)`, accumulated
    /// in `f64`. The rectangle is clipped to the image; an empty region gives black.
    pub fn mean_over(&self, x0: u32, y0: u32, x1: u32, y1: u32) -> Rgb {
        let (x1, y1) = (x1.min(self.width), y1.min(self.height));
        if x0 >= x1 || y0 >= y1 || !self.is_consistent() {
            return Rgb::BLACK;
        }
        let w = self.width as usize;
        let rows =
            (y0 as usize..y1 as usize).flat_map(move |y| self.pixels[y * w + x0 as usize..y * w + x1 as usize].iter());
        mean_of(rows.copied())
    }
}

/// `width * height` as a `usize`, or `None` on overflow.
fn pixel_count(width: u32, height: u32) -> Option<usize> {
    (width as usize).checked_mul(height as usize)
}

/// Per-channel mean of `pixels` in `f64` (black when there are none).
fn mean_of(pixels: impl Iterator<Item = Rgb>) -> Rgb {
    let mut sum = [0.0f64; 3];
    let mut n = 0usize;
    for p in pixels {
        sum[0] += f64::from(p.r);
        sum[1] += f64::from(p.g);
        sum[2] += f64::from(p.b);
        n += 1;
    }
    if n == 0 {
        return Rgb::BLACK;
    }
    let n = n as f64;
    Rgb::new((sum[0] / n) as f32, (sum[1] / n) as f32, (sum[2] / n) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp(w: u32, h: u32) -> Image {
        let mut img = Image::new(w, h);
        for y in 0..h {
            for x in 0..w {
                assert!(img.set(x, y, Rgb::new(x as f32, y as f32, 1.0)));
            }
        }
        img
    }

    #[test]
    fn new_is_black_and_sized() {
        let img = Image::new(3, 2);
        assert_eq!(img.pixels.len(), 6);
        assert!(img.pixels.iter().all(|p| p.is_black()));
        assert!(img.is_consistent() && !img.is_empty());
        assert!(Image::new(0, 5).is_empty());
    }

    #[test]
    fn from_pixels_checks_length() {
        assert!(Image::from_pixels(2, 2, vec![Rgb::WHITE; 4]).is_some());
        assert!(Image::from_pixels(2, 2, vec![Rgb::WHITE; 3]).is_none());
        assert!(Image::from_pixels(0, 2, vec![]).is_some());
    }

    #[test]
    fn get_set_are_row_major_from_top_left() {
        let img = ramp(4, 3);
        assert_eq!(img.get(3, 1), Rgb::new(3.0, 1.0, 1.0));
        assert_eq!(img.pixels[4 + 3], Rgb::new(3.0, 1.0, 1.0));
        assert_eq!(img.try_get(4, 0), None);
        assert_eq!(img.try_get(0, 3), None);
    }

    #[test]
    fn set_outside_changes_nothing() {
        let mut img = Image::new(2, 2);
        assert!(!img.set(2, 0, Rgb::WHITE));
        assert_eq!(img, Image::new(2, 2));
    }

    #[test]
    #[should_panic(expected = "outside")]
    fn get_outside_panics() {
        Image::new(2, 2).get(0, 2);
    }

    #[test]
    fn mean_of_ramp() {
        let img = ramp(4, 3);
        // x ∈ {0,1,2,3} → 1.5; y ∈ {0,1,2} → 1.
        assert_eq!(img.mean(), Rgb::new(1.5, 1.0, 1.0));
        assert_eq!(Image::new(0, 0).mean(), Rgb::BLACK);
    }

    #[test]
    fn mean_over_regions() {
        let img = ramp(4, 3);
        assert_eq!(img.mean_over(0, 0, 4, 3), img.mean());
        assert_eq!(img.mean_over(2, 1, 4, 2), Rgb::new(2.5, 1.0, 1.0));
        assert_eq!(img.mean_over(3, 2, 100, 100), Rgb::new(3.0, 2.0, 1.0));
        assert_eq!(img.mean_over(2, 0, 2, 3), Rgb::BLACK);
        assert_eq!(img.mean_over(5, 5, 9, 9), Rgb::BLACK);
    }

    #[test]
    fn mean_accumulates_in_f64() {
        // 1 + many tiny values: an f32 running sum would lose the tiny ones.
        let mut pixels = vec![Rgb::splat(1e-8); 1 << 20];
        pixels[0] = Rgb::splat(1.0);
        let img = Image::from_pixels(1 << 10, 1 << 10, pixels).unwrap();
        let expected = (1.0 + 1e-8 * ((1 << 20) - 1) as f64) / (1 << 20) as f64;
        assert!((f64::from(img.mean().r) - expected).abs() < 1e-12);
    }
}
