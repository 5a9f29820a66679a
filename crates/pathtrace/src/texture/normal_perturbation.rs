//! Normal maps and bump maps: a texture that tilts a material's shading normal at each hit, as
//! Mitsuba 3's `normalmap` and `bumpmap` BSDF wrappers do.
//!
//! ```toml
//! [materials.bricks]
//! type = "diffuse"
//! albedo = 0.6
//! normal_map = { type = "bitmap", filename = "bricks_normal.png" }   # read as raw (linear) values
//! # or: bump_map = { type = "bitmap", filename = "height.png", raw = true }, bump_scale = 0.02
//! ```
//!
//! Both give the perturbed normal in the local coordinates of the hit's *base* frame
//! (s, t, n): n the shading normal, s = ∂p/∂u made perpendicular to n, t = n × s — Mitsuba's
//! `sh_frame`. The integrator then evaluates the material in a frame around that normal
//! (`integrator::shading_frame`).

use super::{Texture, TextureId};
use crate::math::{Frame, Vec3};
use crate::shape::SurfacePoint;

/// How a material's shading normal is perturbed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalPerturbation {
    pub kind: PerturbationKind,
    /// Attenuate the material by the microfacet shadowing term of Estevez et al., "A
    /// Microfacet-Based Shadowing Function to Solve the Bump Terminator Problem" (Ray Tracing
    /// Gems, 2019), as Mitsuba does by default (`use_shadowing_function = true`).
    pub shadowing: bool,
}

/// The two perturbations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PerturbationKind {
    /// A tangent-space normal map: a texel `c` encodes the normal `2c − 1` in the base frame
    /// (so (0.5, 0.5, 1) changes nothing); `strength` scales its x and y (glTF's
    /// `normalTexture.scale`; Mitsuba has none, i.e. 1).
    NormalMap { texture: TextureId, strength: f32 },
    /// A height field `h` (the texture's luminance) displacing the surface by `scale·h` along the
    /// normal: the normal of the displaced surface, to first order.
    BumpMap { texture: TextureId, scale: f32 },
}

impl NormalPerturbation {
    /// The texture it reads.
    pub fn texture(&self) -> TextureId {
        match self.kind {
            PerturbationKind::NormalMap { texture, .. } | PerturbationKind::BumpMap { texture, .. } => texture,
        }
    }

    /// The perturbed unit normal at `surface`, in the local coordinates of `base` (the hit's
    /// unflipped shading frame), before any flip towards the viewer. Degenerate input (no ∂p/∂v
    /// for a bump map, a texel of (0.5, 0.5, 0.5)) leaves the normal as it is: (0, 0, 1).
    pub fn local_normal(&self, textures: &[Texture], surface: &SurfacePoint, base: &Frame) -> Vec3 {
        let n = match self.kind {
            PerturbationKind::NormalMap { texture, strength } => {
                let c = textures[texture.0 as usize].eval(surface.uv);
                // A mesh's own tangents may say the bitangent is −(n × tangent) (glTF's w = −1):
                // the texel's y then points against the base frame's t.
                let y = surface.bitangent_sign() * (2.0 * c.g - 1.0);
                let n = Vec3::new(2.0 * c.r - 1.0, y, 2.0 * c.b - 1.0);
                Vec3::new(n.x * strength, n.y * strength, n.z).normalize_or_zero()
            }
            PerturbationKind::BumpMap { texture, scale } => {
                bump_normal(scale * textures[texture.0 as usize].luminance_gradient(surface.uv), surface, base)
            }
        };
        if n == Vec3::ZERO || !n.is_finite() {
            Vec3::Z
        } else {
            n
        }
    }
}

/// Mitsuba 3's `bumpmap` normal: the tangents ∂p/∂u, ∂p/∂v of the surface displaced along the
/// shading normal n by the height field, with gradient `grad` = (∂h/∂u, ∂h/∂v):
/// ∂p'/∂u = ∂p/∂u − n(n·∂p/∂u) + n·∂h/∂u (likewise for v); the normal is their cross product,
/// turned to the geometric normal's side, in `base`'s coordinates. Zero if a tangent is missing.
fn bump_normal(grad: glam::Vec2, surface: &SurfacePoint, base: &Frame) -> Vec3 {
    let n = base.n;
    let dpdu = surface.dpdu + n * (grad.x - n.dot(surface.dpdu));
    let dpdv = surface.dpdv + n * (grad.y - n.dot(surface.dpdv));
    if surface.dpdu == Vec3::ZERO || surface.dpdv == Vec3::ZERO {
        return Vec3::ZERO;
    }
    let mut bumped = dpdu.cross(dpdv).normalize_or_zero();
    if bumped.dot(surface.n_geometric) < 0.0 {
        bumped = -bumped;
    }
    base.to_local(bumped)
}

/// The shadowing term of Estevez et al. (2019) for a normal tilted to `n_local` in the base
/// frame, seen along `w_local` (base frame): G = 2 / (1 + √(1 + α² tan²θ_w)) with
/// α² = min(tan²θ_n / 8, 1) (Mitsuba 3's `eval_shadow_terminator`).
#[inline]
pub fn shadow_terminator(n_local: Vec3, w_local: Vec3) -> f32 {
    let tan2 = |v: Vec3| (1.0 - v.z * v.z).max(0.0) / (v.z * v.z);
    let alpha2 = (0.125 * tan2(n_local)).min(1.0);
    let g = 2.0 / (1.0 + (1.0 + alpha2 * tan2(w_local)).sqrt());
    if g.is_finite() {
        g
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Rgb, Vec2};
    use crate::texture::Bitmap;

    fn flat_point() -> SurfacePoint {
        SurfacePoint {
            p: Vec3::ZERO,
            n_geometric: Vec3::Z,
            n_shading: Vec3::Z,
            uv: Vec2::new(0.3, 0.4),
            dpdu: Vec3::X * 2.0,
            dpdv: -Vec3::Y * 2.0,
            vertex_tangent: crate::math::Vec4::ZERO,
        }
    }

    #[test]
    fn a_neutral_normal_map_changes_nothing_and_a_tilted_one_tilts() {
        let base = Frame::from_normal_tangent(Vec3::Z, Vec3::X);
        let textures = [Texture::Constant(Rgb::new(0.5, 0.5, 1.0)), Texture::Constant(Rgb::new(1.0, 0.5, 0.5))];
        let p = |t, strength| NormalPerturbation {
            kind: PerturbationKind::NormalMap { texture: TextureId(t), strength },
            shadowing: true,
        };
        assert!((p(0, 1.0).local_normal(&textures, &flat_point(), &base) - Vec3::Z).length() < 1e-6);
        // (1, 0.5, 0.5) encodes +x: the normal lies in the tangent plane.
        assert!((p(1, 1.0).local_normal(&textures, &flat_point(), &base) - Vec3::X).length() < 1e-6);
        // A grey texel (the zero vector) is degenerate: no change.
        let grey = [Texture::Constant(Rgb::splat(0.5))];
        assert_eq!(p(0, 1.0).local_normal(&grey, &flat_point(), &base), Vec3::Z);
    }

    #[test]
    fn a_bump_ramp_tilts_the_normal_against_its_slope() {
        // Height rising along u by 1 per unit u, over ∂p/∂u of length 2: slope ½ along +x.
        let ramp = Bitmap::new(2, 1, vec![Rgb::splat(0.0), Rgb::splat(0.5)]).unwrap();
        let textures = [Texture::Bitmap(ramp)];
        let base = Frame::from_normal_tangent(Vec3::Z, Vec3::X);
        let bump = NormalPerturbation {
            kind: PerturbationKind::BumpMap { texture: TextureId(0), scale: 1.0 },
            shadowing: false,
        };
        let mut sp = flat_point();
        sp.uv = Vec2::new(0.5, 0.5);
        let n = bump.local_normal(&textures, &sp, &base);
        // The gradient is 0.5·2 texels = 1 per unit u; the displaced surface rises by 1 over a
        // run of 2 along x: n ∝ (−1, 0, 2).
        let expected = Vec3::new(-1.0, 0.0, 2.0).normalize();
        assert!((n - expected).length() < 1e-5, "{n}");
    }

    #[test]
    fn the_terminator_term_is_one_for_untilted_normals_and_falls_at_grazing_angles() {
        assert_eq!(shadow_terminator(Vec3::Z, Vec3::new(0.6, 0.0, 0.8)), 1.0);
        // A normal tilted by 70°: α² = min(tan²70° / 8, 1) ≈ 0.94; light at 80° from the base
        // normal: G = 2 / (1 + √(1 + α² tan²80°)) ≈ 0.30.
        let (a, b) = (70f32.to_radians(), 80f32.to_radians());
        let tilted = Vec3::new(a.sin(), 0.0, a.cos());
        assert_eq!(shadow_terminator(tilted, Vec3::Z), 1.0);
        let g = shadow_terminator(tilted, Vec3::new(b.sin(), 0.0, b.cos()));
        let alpha2 = (a.tan().powi(2) / 8.0).min(1.0);
        let expected = 2.0 / (1.0 + (1.0 + alpha2 * b.tan().powi(2)).sqrt());
        assert!((g - expected).abs() < 1e-5 && g < 0.35, "{g} vs {expected}");
    }
}
