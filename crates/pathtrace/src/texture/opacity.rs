//! Opacity masks (cut-outs): a texture saying how much of a surface is there, as Mitsuba 3's
//! `mask` BSDF (opacity = the texture's value clamped to [0, 1], the luminance of a colour) or
//! glTF's `alphaMode` (`MASK`: opaque where alpha ≥ `alphaCutoff`, else absent; `BLEND`: alpha as
//! the opacity).
//!
//! ```toml
//! [materials.leaf]
//! type = "diffuse"
//! albedo = 0.5
//! opacity = { type = "bitmap", filename = "leaf_alpha.png", raw = true }
//! ```
//!
//! How the estimator uses it: see `crate::cutout`.

use super::{Texture, TextureId};
use crate::math::Vec2;

/// A material's opacity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Opacity {
    pub texture: TextureId,
    /// glTF's `alphaCutoff`: opacity is 1 where the value is at least this, else 0.
    pub cutoff: Option<f32>,
}

impl Opacity {
    /// The opacity in [0, 1] at `uv`.
    #[inline]
    pub fn at(&self, textures: &[Texture], uv: Vec2) -> f32 {
        let a = textures[self.texture.0 as usize].eval(uv).luminance();
        match self.cutoff {
            Some(c) => f32::from(u8::from(a >= c)),
            None if a.is_nan() => 1.0,
            None => a.clamp(0.0, 1.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;

    #[test]
    fn opacity_is_clamped_luminance_or_a_cutoff_step() {
        let textures = [Texture::Constant(Rgb::splat(0.3)), Texture::Constant(Rgb::splat(1.7))];
        let uv = Vec2::ZERO;
        assert!((Opacity { texture: TextureId(0), cutoff: None }.at(&textures, uv) - 0.3).abs() < 1e-6);
        assert_eq!(Opacity { texture: TextureId(1), cutoff: None }.at(&textures, uv), 1.0);
        assert_eq!(Opacity { texture: TextureId(0), cutoff: Some(0.5) }.at(&textures, uv), 0.0);
        assert_eq!(Opacity { texture: TextureId(0), cutoff: Some(0.3) }.at(&textures, uv), 1.0);
    }
}
