//! A texture over an emissive triangle or quad: the light emits its `Emission::radiance` times the
//! texture's value at the point's (u, v) (glTF's `emissiveTexture`, Mitsuba's `area` emitter with
//! a `bitmap` radiance).
//!
//! The light is still sampled uniformly by area and selected by its power computed from the
//! texture's mean, so the estimator stays unbiased: the radiance is looked up at the sampled
//! point (where the texture is dark the sample simply carries less). Sampling in proportion to
//! the texture (importance sampling the image) would lower the noise, not change the mean.

use crate::math::{Rgb, Vec2, Vec3};
use crate::shape::barycentric_mix;
use crate::texture::Texture;
use std::sync::Arc;

/// The texture and the (u, v) at the triangle's corners `p0`, `p0 + e1`, `p0 + e2` (on a mesh
/// without texture coordinates: (0, 0), (1, 0), (0, 1), so that uv = the barycentrics, as a
/// mesh hit reports them). A quad `q + a·u + b·v` uses the same three corners (q, q + u, q + v)
/// with uv (0, 0), (1, 0), (0, 1): the blend below is affine, so it gives uv = (a, b) over the
/// whole parallelogram, as a quad hit reports it.
#[derive(Clone, Debug, PartialEq)]
pub struct RadianceTexture {
    pub texture: Arc<Texture>,
    pub corner_uv: [Vec2; 3],
}

impl RadianceTexture {
    /// A texture over a quad, whose uv is (a, b) at `q + a·u + b·v` (see the type's comment).
    pub fn on_quad(texture: Arc<Texture>) -> Self {
        Self { texture, corner_uv: [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)] }
    }

    /// The texture's value at a point `p` of the triangle `p0 + b1·e1 + b2·e2`: its barycentrics
    /// from the 2×2 normal equations of the edges (exact for a point in the plane), then the
    /// corners' uv blended with them, as a mesh hit does.
    pub fn at_point(&self, p: Vec3, p0: Vec3, e1: Vec3, e2: Vec3) -> Rgb {
        let d = p - p0;
        let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let (d1, d2) = (d.dot(e1), d.dot(e2));
        let det = d11 * d22 - d12 * d12;
        let (b1, b2) = if det > 0.0 { ((d22 * d1 - d12 * d2) / det, (d11 * d2 - d12 * d1) / det) } else { (0.0, 0.0) };
        self.at_barycentrics(b1, b2)
    }

    /// The texture's value at barycentrics (b1, b2) (weights of the second and third corner).
    pub fn at_barycentrics(&self, b1: f32, b2: f32) -> Rgb {
        self.texture.eval(barycentric_mix(b1, b2, self.corner_uv))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::Bitmap;

    #[test]
    fn a_point_is_looked_up_at_its_interpolated_uv() {
        // A 2×1 image: red left, green right, nearest lookups.
        let mut bm = Bitmap::new(2, 1, vec![Rgb::new(1.0, 0.0, 0.0), Rgb::new(0.0, 1.0, 0.0)]).unwrap();
        bm.filter = crate::texture::FilterType::Nearest;
        let t = RadianceTexture {
            texture: Arc::new(Texture::Bitmap(bm)),
            corner_uv: [Vec2::new(0.0, 0.5), Vec2::new(1.0, 0.5), Vec2::new(0.0, 0.5)],
        };
        let (p0, e1, e2) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.5, 1.0, 0.0));
        // b1 = 0.2 → u = 0.2 (red); b1 = 0.8 → u = 0.8 (green), whatever b2.
        assert_eq!(t.at_point(p0 + e1 * 0.2 + e2 * 0.3, p0, e1, e2), Rgb::new(1.0, 0.0, 0.0));
        assert_eq!(t.at_point(p0 + e1 * 0.8 + e2 * 0.1, p0, e1, e2), Rgb::new(0.0, 1.0, 0.0));
        assert_eq!(t.at_barycentrics(0.7, 0.2), Rgb::new(0.0, 1.0, 0.0));
    }
}
