//! A grid of per-pixel sums, row by row: the one shape the film's radiance statistics and the
//! feature buffers share — allocated without aborting, filled tile by tile, merged with another
//! grid of the same size. What a pixel holds and how two of its sums combine is the pixel type's
//! business ([`Mergeable`]); both kinds are exact integers, so any order of merges gives the same
//! bits.

use super::allocation::{try_pixels, FilmTooLarge};

/// Per-pixel sums that combine by adding (order-free: integer addition).
pub trait Mergeable: Clone + Default {
    fn merge(&mut self, other: &Self);
}

/// `width` × `height` pixels of sums.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelGrid<P> {
    width: u32,
    height: u32,
    pixels: Vec<P>,
}

impl<P: Mergeable> PixelGrid<P> {
    /// Empty sums for `width` × `height` pixels, or an error naming the memory they need.
    pub fn try_new(width: u32, height: u32) -> Result<Self, FilmTooLarge> {
        let len = u64::from(width) * u64::from(height);
        let pixels = try_pixels(len).ok_or_else(|| FilmTooLarge::of::<P>(width, height))?;
        Ok(Self { width, height, pixels })
    }

    /// A grid of the given pixels (row by row; `pixels.len()` must be `width × height`).
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<P>) -> Self {
        debug_assert_eq!(pixels.len() as u64, u64::from(width) * u64::from(height));
        Self { width, height, pixels }
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// Every pixel, row by row.
    pub fn pixels(&self) -> &[P] {
        &self.pixels
    }

    pub fn pixel(&self, x: u32, y: u32) -> &P {
        &self.pixels[(y * self.width + x) as usize]
    }

    pub fn pixel_mut(&mut self, x: u32, y: u32) -> &mut P {
        &mut self.pixels[(y * self.width + x) as usize]
    }

    /// Merges a block of pixels covering the rectangle at `(x0, y0)` of width `w`.
    /// Row by row, each block row against its slice of the grid's row, rather than a division
    /// and a bounds check per pixel (`i % w`, `i / w`, the index): the merge runs under the
    /// film's lock once per tile and wave (0.993 of teapot-simple's time, docs/benchmarks.md).
    pub fn merge_block(&mut self, x0: u32, y0: u32, w: u32, block: &[P]) {
        if w == 0 {
            return;
        }
        let (x0, w, width) = (x0 as usize, w as usize, self.width as usize);
        for (row, block_row) in block.chunks(w).enumerate() {
            let start = (y0 as usize + row) * width + x0;
            for (p, b) in self.pixels[start..start + block_row.len()].iter_mut().zip(block_row) {
                p.merge(b);
            }
        }
    }

    /// Adds every pixel of a grid of the same size; `false` (and nothing changes) if the sizes
    /// differ.
    pub fn merge(&mut self, other: &PixelGrid<P>) -> bool {
        if other.width != self.width || other.height != self.height {
            return false;
        }
        for (a, b) in self.pixels.iter_mut().zip(&other.pixels) {
            a.merge(b);
        }
        true
    }
}
