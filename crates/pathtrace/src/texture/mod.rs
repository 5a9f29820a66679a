//! Textures: colours that vary over a surface, looked up at the hit's (u, v).
//!
//! ```toml
//! [materials.floor]
//! type = "diffuse"
//! albedo = { type = "checkerboard", color0 = 0.4, color1 = 0.2, scale = 8 }
//! ```
//!
//! A closed [`Texture`] enum (constant, checkerboard, bitmap, squared bitmap) dispatched by `match`. Any colour
//! parameter of a material may be bound to a texture ([`ColourSlot`], [`TextureBindings`]): the
//! material keeps its constant parameters (set to the texture's mean, which is what Mitsuba uses
//! for sampling weights), and at a hit the scene makes a copy with the texture's value in that
//! slot ([`crate::Scene::textured_material`]). Untextured materials are used as they are, so the
//! constant case costs one predictable branch per hit.

mod bitmap;
mod checkerboard;
mod normal_perturbation;
mod opacity;
mod uv_transform;

pub use bitmap::{Bitmap, FilterType, WrapMode};
pub use checkerboard::Checkerboard;
pub use normal_perturbation::{shadow_terminator, NormalPerturbation, PerturbationKind};
pub use opacity::Opacity;
pub use uv_transform::UvTransform;

use crate::math::{Rgb, Vec2};

/// Every texture.
#[derive(Clone, Debug, PartialEq)]
pub enum Texture {
    /// The same colour everywhere.
    Constant(Rgb),
    Checkerboard(Checkerboard),
    Bitmap(Bitmap),
    /// A bitmap whose filtered value is squared: glTF's perceptual roughness r, whose microfacet
    /// α is r² (glTF 2.0, Appendix B), interpolated before it is squared as the specification
    /// evaluates it.
    Squared(Bitmap),
}

impl Texture {
    /// The colour at surface coordinates `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Rgb {
        match self {
            Texture::Constant(c) => *c,
            Texture::Checkerboard(c) => c.eval(uv),
            Texture::Bitmap(b) => b.eval(uv),
            Texture::Squared(b) => {
                let c = b.eval(uv);
                c * c
            }
        }
    }

    /// The gradient (∂f/∂u, ∂f/∂v) of the luminance at `uv`, for bump maps: zero for a constant
    /// and (almost everywhere) for a checkerboard.
    #[inline]
    pub fn luminance_gradient(&self, uv: Vec2) -> Vec2 {
        match self {
            Texture::Constant(_) | Texture::Checkerboard(_) => Vec2::ZERO,
            Texture::Bitmap(b) => b.luminance_gradient(uv),
            // Exact for grey texels (luminance of c² = (luminance of c)²): 2·f·∇f.
            Texture::Squared(b) => b.luminance_gradient(uv) * (2.0 * b.eval(uv).luminance()),
        }
    }

    /// The mean colour over the unit uv square (for a squared bitmap, the square of the mean
    /// texel, ≤ the true mean: it only sets sampling weights).
    pub fn mean(&self) -> Rgb {
        match self {
            Texture::Constant(c) => *c,
            Texture::Checkerboard(c) => c.mean(),
            Texture::Bitmap(b) => b.mean(),
            Texture::Squared(b) => b.mean() * b.mean(),
        }
    }

    /// The largest channel value the texture can return.
    pub fn max_value(&self) -> f32 {
        match self {
            Texture::Constant(c) => c.max_component(),
            Texture::Checkerboard(c) => c.color0.max_component().max(c.color1.max_component()),
            Texture::Bitmap(b) => b.max_value(),
            Texture::Squared(b) => b.max_value() * b.max_value(),
        }
    }
}

/// Which colour parameter of a material a texture drives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColourSlot {
    /// The main colour: diffuse/lambertian/glossy `albedo`, mirror and conductor `reflectance`,
    /// glass `tint`, plastic `albedo` (the base).
    Base,
    /// A plastic's coating `specular` reflectance.
    Specular,
    /// The isotropic microfacet α of a rough conductor or rough dielectric (the texture's
    /// luminance; Mitsuba's textured `alpha`).
    Roughness,
}

/// Index of a texture in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureId(pub u32);

/// The textures bound to one material's colour slots (none for most materials).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct TextureBindings {
    /// Texture of [`ColourSlot::Base`], if any.
    pub base: Option<TextureId>,
    /// Texture of [`ColourSlot::Specular`], if any.
    pub specular: Option<TextureId>,
    /// Texture of [`ColourSlot::Roughness`], if any.
    pub roughness: Option<TextureId>,
    /// A normal or bump map tilting the shading normal, if any.
    pub normal: Option<NormalPerturbation>,
    /// An opacity mask, if any.
    pub opacity: Option<Opacity>,
}

impl TextureBindings {
    /// True if no slot is textured.
    #[inline(always)]
    pub fn is_empty(&self) -> bool {
        self.base.is_none()
            && self.specular.is_none()
            && self.roughness.is_none()
            && self.normal.is_none()
            && self.opacity.is_none()
    }

    /// Binds `slot` to `texture`.
    pub fn set(&mut self, slot: ColourSlot, texture: TextureId) {
        match slot {
            ColourSlot::Base => self.base = Some(texture),
            ColourSlot::Specular => self.specular = Some(texture),
            ColourSlot::Roughness => self.roughness = Some(texture),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_squared_bitmap_squares_after_filtering() {
        // Grey 0.2 and 0.8 side by side: halfway, the blend 0.5 squared (0.25), not the blend of
        // the squares (0.34).
        let b = Bitmap::new(2, 1, vec![Rgb::splat(0.2), Rgb::splat(0.8)]).unwrap();
        let t = Texture::Squared(b.clone());
        let v = t.eval(Vec2::new(0.5, 0.5));
        assert!((v.r - 0.25).abs() < 1e-6, "{v:?}");
        assert!((t.max_value() - 0.64).abs() < 1e-6);
        // The gradient is 2·f·∇f.
        let uv = Vec2::new(0.4, 0.5);
        let g = t.luminance_gradient(uv);
        let h = 1e-3;
        let du = (t.eval(uv + Vec2::new(h, 0.0)).luminance() - t.eval(uv - Vec2::new(h, 0.0)).luminance()) / (2.0 * h);
        assert!((g.x - du).abs() < 1e-2 * du.abs().max(1.0), "{g:?} vs {du}");
    }
}
