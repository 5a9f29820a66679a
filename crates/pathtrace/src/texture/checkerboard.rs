//! `checkerboard`: two colours alternating on a 2×2 grid over the unit uv square, as Mitsuba 3's
//! `checkerboard` texture.
//!
//! ```toml
//! [materials.floor]
//! type = "diffuse"
//! albedo = { type = "checkerboard", color0 = 0.4, color1 = 0.2, scale = 8 }
//! ```
//!
//! With (u, v) the transformed coordinates, `color0` is shown where the fractional parts of u
//! and v are both ≤ ½ or both > ½, `color1` elsewhere — Mitsuba's rule (src/textures/
//! checkerboard.cpp), checked against Mitsuba 3.9.1 at (0.1, 0.1) → color0, (0.6, 0.1) →
//! color1. Mitsuba's defaults are color0 = 0.4, color1 = 0.2. The mean is their average.

use super::UvTransform;
use crate::math::{Rgb, Vec2};

/// Two colours on a checker grid of period 1 in (transformed) uv.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checkerboard {
    pub color0: Rgb,
    pub color1: Rgb,
    pub to_uv: UvTransform,
}

impl Checkerboard {
    /// The colour at `uv` (before the transform).
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Rgb {
        let t = self.to_uv.apply(uv);
        let upper_u = t.x - t.x.floor() > 0.5;
        let upper_v = t.y - t.y.floor() > 0.5;
        if upper_u == upper_v {
            self.color0
        } else {
            self.color1
        }
    }

    /// The mean over the uv square (exact for any integer scale).
    pub fn mean(&self) -> Rgb {
        (self.color0 + self.color1) * 0.5
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn board(to_uv: UvTransform) -> Checkerboard {
        Checkerboard { color0: Rgb::new(1.0, 0.0, 0.0), color1: Rgb::new(0.0, 1.0, 0.0), to_uv }
    }

    #[test]
    fn matches_mitsubas_pattern() {
        let b = board(UvTransform::IDENTITY);
        let at = |u, v| b.eval(Vec2::new(u, v));
        assert_eq!(at(0.1, 0.1), b.color0);
        assert_eq!(at(0.6, 0.1), b.color1);
        assert_eq!(at(0.1, 0.6), b.color1);
        assert_eq!(at(0.6, 0.6), b.color0);
        assert_eq!(at(1.1, 0.1), b.color0); // period 1
        assert_eq!(at(-0.4, 0.1), b.color1); // negative coordinates continue the pattern
    }

    #[test]
    fn uv_transform_scales_and_shifts_the_pattern() {
        let scaled = board(UvTransform::scale(Vec2::splat(8.0)));
        assert_eq!(scaled.eval(Vec2::new(0.1 / 8.0, 0.1 / 8.0)), scaled.color0);
        assert_eq!(scaled.eval(Vec2::new(0.6 / 8.0, 0.1 / 8.0)), scaled.color1);
        // Mitsuba 3.9.1: a to_uv translating u by ½ shows color1 at (0.1, 0.1).
        let shifted = board(UvTransform::from_rows([[1.0, 0.0, 0.5], [0.0, 1.0, 0.0]]));
        assert_eq!(shifted.eval(Vec2::new(0.1, 0.1)), shifted.color1);
    }

    #[test]
    fn mean_is_the_area_average() {
        let b = board(UvTransform::scale(Vec2::splat(3.0)));
        let n = 300;
        let mut sum = Rgb::BLACK;
        for i in 0..n {
            for j in 0..n {
                sum += b.eval(Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32));
            }
        }
        let avg = sum / (n * n) as f32;
        assert!((avg.r - b.mean().r).abs() < 1e-3 && (avg.g - b.mean().g).abs() < 1e-3, "{avg:?}");
    }
}
