//! Allocating a film without aborting: a size the machine cannot hold is an error that says how
//! much memory it needs, not a process abort with a backtrace.

use super::accumulator::PixelStats;

/// The bytes one film pixel takes (its count, mean and variance sums).
pub const FILM_BYTES_PER_PIXEL: u64 = std::mem::size_of::<PixelStats>() as u64;

/// A film (or its feature buffers) too large to allocate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("a {width}x{height} film needs {:.1} GB of memory ({bytes_per_pixel} bytes per pixel), which cannot be allocated", *.bytes as f64 / 1e9)]
pub struct FilmTooLarge {
    pub width: u32,
    pub height: u32,
    /// The bytes the film would need.
    pub bytes: u64,
    pub bytes_per_pixel: u64,
}

impl FilmTooLarge {
    /// The error for `width` × `height` pixels of type `P`.
    pub fn of<P>(width: u32, height: u32) -> Self {
        let bytes_per_pixel = std::mem::size_of::<P>() as u64;
        let bytes = (u64::from(width) * u64::from(height)).saturating_mul(bytes_per_pixel);
        Self { width, height, bytes, bytes_per_pixel }
    }
}

/// `len` default pixels, or `None` if the allocator refuses them.
pub(super) fn try_pixels<P: Clone + Default>(len: u64) -> Option<Vec<P>> {
    let len = usize::try_from(len).ok()?;
    let mut pixels = Vec::new();
    pixels.try_reserve_exact(len).ok()?;
    pixels.resize(len, P::default());
    Some(pixels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pixel_takes_the_bytes_docs_distributed_md_states() {
        // count (4) + three i128 sums (48) + three u128 sums of squares (48), aligned to 16 where
        // 128-bit integers are (x86-64, aarch64): docs/distributed.md's memory figure.
        if std::mem::align_of::<u128>() == 16 {
            assert_eq!(FILM_BYTES_PER_PIXEL, 112);
        }
    }
}
