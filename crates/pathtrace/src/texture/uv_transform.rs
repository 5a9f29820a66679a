//! The affine map applied to a hit's (u, v) before a texture is looked up: Mitsuba's `to_uv`.
//!
//! ```toml
//! reflectance = { type = "checkerboard", to_uv = [[8, 0, 0], [0, 8, 0]] }  # eight times smaller
//! ```
//!
//! Mitsuba takes a 4×4 `to_uv` and uses its upper-left 2×2 block with the translation from the
//! fourth column (checked against Mitsuba 3.9.1: a `to_uv` translating x by ½ moves the checker
//! by half a period), which is what [`UvTransform::from_rows`] receives.

use crate::math::Vec2;

/// `uv' = [a b; c d]·uv + (tx, ty)`, stored as two rows `[a, b, tx]` and `[c, d, ty]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    rows: [[f32; 3]; 2],
}

impl Default for UvTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl UvTransform {
    /// The identity map.
    pub const IDENTITY: Self = Self { rows: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] };

    /// The map with rows `[a, b, tx]` and `[c, d, ty]`.
    pub fn from_rows(rows: [[f32; 3]; 2]) -> Self {
        Self { rows }
    }

    /// Scaling by `s` (uv' = s·uv): `s = (8, 8)` repeats a texture eight times along each axis.
    pub fn scale(s: Vec2) -> Self {
        Self { rows: [[s.x, 0.0, 0.0], [0.0, s.y, 0.0]] }
    }

    /// The two rows `[a, b, tx]`, `[c, d, ty]`.
    pub fn rows(&self) -> [[f32; 3]; 2] {
        self.rows
    }

    /// True for the identity map.
    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }

    /// True if every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.rows.iter().flatten().all(|x| x.is_finite())
    }

    /// The transformed coordinates.
    #[inline]
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        let [r0, r1] = self.rows;
        Vec2::new(r0[0] * uv.x + r0[1] * uv.y + r0[2], r1[0] * uv.x + r1[1] * uv.y + r1[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn applies_linear_part_then_translation() {
        let t = UvTransform::from_rows([[2.0, 1.0, 0.5], [0.0, 3.0, -1.0]]);
        assert_eq!(t.apply(Vec2::new(1.0, 2.0)), Vec2::new(4.5, 5.0));
        assert_eq!(UvTransform::IDENTITY.apply(Vec2::new(0.3, 0.7)), Vec2::new(0.3, 0.7));
        assert_eq!(UvTransform::scale(Vec2::new(8.0, 4.0)).apply(Vec2::new(0.5, 0.5)), Vec2::new(4.0, 2.0));
    }
}
