//! `bitmap`: an image of linear RGB texels, looked up bilinearly and repeated outside the unit
//! square, as Mitsuba 3's `bitmap` texture with its defaults (`filter_type = "bilinear"`,
//! `wrap_mode = "repeat"`).
//!
//! ```toml
//! [materials.wood]
//! type = "diffuse"
//! albedo = { type = "bitmap", filename = "textures/wood.png", scale = 4 }
//! ```
//!
//! Conventions (checked against Mitsuba 3.9.1 on a 2×2 image): uv (0, 0) is the top-left
//! corner of the image as stored (first row first), v grows downwards; texel (i, j) has its
//! centre at ((i + ½)/w, (j + ½)/h), so the lookup position is (u·w − ½, v·h − ½) and the four
//! surrounding texels are blended; `repeat` wraps texel indices modulo the size, `clamp` clamps
//! them. Decoding (sRGB or linear) happens when the file is read, not here.

use super::UvTransform;
use crate::math::{Rgb, Vec2};
use std::sync::Arc;

/// How texel indices outside the image are mapped back into it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum WrapMode {
    /// Tile the image (Mitsuba's default).
    #[default]
    Repeat,
    /// Repeat the border texels.
    Clamp,
}

/// How texels are blended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FilterType {
    /// Blend the four nearest texels (Mitsuba's default).
    #[default]
    Bilinear,
    /// The texel containing the point.
    Nearest,
}

/// A texture image with its lookup options. The texels are shared, so copies are cheap.
#[derive(Clone, Debug, PartialEq)]
pub struct Bitmap {
    width: u32,
    height: u32,
    texels: Arc<[Rgb]>,
    mean: Rgb,
    max: f32,
    pub filter: FilterType,
    pub wrap: WrapMode,
    pub to_uv: UvTransform,
}

impl Bitmap {
    /// A bitmap of `width × height` texels, rows from the top; `None` if the sizes disagree, the
    /// image is empty or a texel is negative or not finite.
    pub fn new(width: u32, height: u32, texels: Vec<Rgb>) -> Option<Self> {
        let ok = |c: &Rgb| c.is_finite() && c.r >= 0.0 && c.g >= 0.0 && c.b >= 0.0;
        if width == 0 || height == 0 || texels.len() != width as usize * height as usize || !texels.iter().all(ok) {
            return None;
        }
        let sum = texels.iter().fold([0.0f64; 3], |s, c| [s[0] + c.r as f64, s[1] + c.g as f64, s[2] + c.b as f64]);
        let n = texels.len() as f64;
        let mean = Rgb::new((sum[0] / n) as f32, (sum[1] / n) as f32, (sum[2] / n) as f32);
        let max = texels.iter().fold(0.0f32, |m, c| m.max(c.max_component()));
        Some(Self {
            width,
            height,
            texels: texels.into(),
            mean,
            max,
            filter: FilterType::default(),
            wrap: WrapMode::default(),
            to_uv: UvTransform::IDENTITY,
        })
    }

    /// Width and height in texels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The mean texel (the texture's mean over the uv square, for either filter under `repeat`).
    pub fn mean(&self) -> Rgb {
        self.mean
    }

    /// The largest channel value of any texel.
    pub fn max_value(&self) -> f32 {
        self.max
    }

    /// The texel at integer coordinates, wrapped into the image.
    #[inline]
    fn texel(&self, x: i64, y: i64) -> Rgb {
        let (w, h) = (self.width as i64, self.height as i64);
        let (x, y) = match self.wrap {
            WrapMode::Repeat => (x.rem_euclid(w), y.rem_euclid(h)),
            WrapMode::Clamp => (x.clamp(0, w - 1), y.clamp(0, h - 1)),
        };
        self.texels[(y * w + x) as usize]
    }

    /// The filtered colour at `uv` (before the transform).
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Rgb {
        let t = self.to_uv.apply(uv);
        if !t.is_finite() {
            return Rgb::BLACK;
        }
        // Far-out coordinates would overflow the integer texel index: wrap them first.
        let t = match self.wrap {
            WrapMode::Repeat => t - t.floor(),
            WrapMode::Clamp => t.clamp(Vec2::splat(-1.0), Vec2::splat(2.0)),
        };
        let (w, h) = (self.width as f32, self.height as f32);
        match self.filter {
            FilterType::Nearest => self.texel((t.x * w).floor() as i64, (t.y * h).floor() as i64),
            FilterType::Bilinear => {
                let (x, y) = (t.x * w - 0.5, t.y * h - 0.5);
                let (x0, y0) = (x.floor(), y.floor());
                let (fx, fy) = (x - x0, y - y0);
                let (x0, y0) = (x0 as i64, y0 as i64);
                let top = self.texel(x0, y0) * (1.0 - fx) + self.texel(x0 + 1, y0) * fx;
                let bottom = self.texel(x0, y0 + 1) * (1.0 - fx) + self.texel(x0 + 1, y0 + 1) * fx;
                top * (1.0 - fy) + bottom * fy
            }
        }
    }

    /// The gradient (∂f/∂u, ∂f/∂v) of the filtered luminance at `uv`, for bump maps: the exact
    /// derivative of the bilinear blend of [`Bitmap::eval`] (Mitsuba 3's `eval_1_grad`: the
    /// blend's partials in texel units times the resolution, then through the uv transform by the
    /// chain rule), zero for nearest lookups (constant almost everywhere, as in Mitsuba).
    /// Mitsuba scales by the resolution after the transform, which differs from the chain rule
    /// only for a non-square image under a rotating `to_uv`.
    #[inline]
    pub fn luminance_gradient(&self, uv: Vec2) -> Vec2 {
        let t = self.to_uv.apply(uv);
        if !t.is_finite() || self.filter == FilterType::Nearest {
            return Vec2::ZERO;
        }
        let t = match self.wrap {
            WrapMode::Repeat => t - t.floor(),
            WrapMode::Clamp => t.clamp(Vec2::splat(-1.0), Vec2::splat(2.0)),
        };
        let (w, h) = (self.width as f32, self.height as f32);
        let (x, y) = (t.x * w - 0.5, t.y * h - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let f = |dx, dy| self.texel(x0 + dx, y0 + dy).luminance();
        let (f00, f10, f01, f11) = (f(0, 0), f(1, 0), f(0, 1), f(1, 1));
        // Partials of the blend in texel units, then per unit of the transformed uv.
        let df_dx = ((1.0 - fy) * (f10 - f00) + fy * (f11 - f01)) * w;
        let df_dy = ((1.0 - fx) * (f01 - f00) + fx * (f11 - f10)) * h;
        let [r0, r1] = self.to_uv.rows();
        Vec2::new(r0[0] * df_dx + r1[0] * df_dy, r0[1] * df_dx + r1[1] * df_dy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Row 0: red, green; row 1: blue, white — the image used to probe Mitsuba 3.9.1.
    fn probe() -> Bitmap {
        let (r, g, b, w) = (Rgb::new(1.0, 0.0, 0.0), Rgb::new(0.0, 1.0, 0.0), Rgb::new(0.0, 0.0, 1.0), Rgb::WHITE);
        Bitmap::new(2, 2, vec![r, g, b, w]).unwrap()
    }

    #[test]
    fn bilinear_lookup_matches_mitsuba_on_a_two_by_two_image() {
        let bm = probe();
        let at = |u, v| bm.eval(Vec2::new(u, v));
        // Texel centres return the texel exactly.
        assert_eq!(at(0.25, 0.25), Rgb::new(1.0, 0.0, 0.0));
        assert_eq!(at(0.75, 0.25), Rgb::new(0.0, 1.0, 0.0));
        assert_eq!(at(0.25, 0.75), Rgb::new(0.0, 0.0, 1.0));
        assert_eq!(at(0.75, 0.75), Rgb::WHITE);
        // Halfway between two centres, and across the repeat seam (Mitsuba: (0.5, 0.5, 0) and
        // (0.5, 0, 0.5)).
        assert_eq!(at(0.5, 0.25), Rgb::new(0.5, 0.5, 0.0));
        assert_eq!(at(0.0, 0.25), Rgb::new(0.5, 0.5, 0.0));
        assert_eq!(at(0.25, 0.0), Rgb::new(0.5, 0.0, 0.5));
        // A quarter of the way: weights ¾ and ¼.
        let q = at(0.375, 0.25);
        assert!((q.r - 0.75).abs() < 1e-6 && (q.g - 0.25).abs() < 1e-6 && q.b == 0.0, "{q:?}");
        // Repeat: whole periods away give the same colour.
        assert_eq!(at(2.25, -0.75), at(0.25, 0.25));
    }

    #[test]
    fn luminance_gradient_is_the_derivative_of_the_lookup() {
        let mut bm = probe();
        bm.to_uv = UvTransform::from_rows([[2.0, 0.5, 0.1], [-0.3, 1.5, 0.0]]);
        let lum = |u: f32, v: f32| bm.eval(Vec2::new(u, v)).luminance();
        for (u, v) in [(0.3, 0.2), (0.61, 0.47), (0.12, 0.9)] {
            let g = bm.luminance_gradient(Vec2::new(u, v));
            let h = 1e-3;
            let du = (lum(u + h, v) - lum(u - h, v)) / (2.0 * h);
            let dv = (lum(u, v + h) - lum(u, v - h)) / (2.0 * h);
            assert!((g.x - du).abs() < 2e-2 && (g.y - dv).abs() < 2e-2, "{g:?} vs ({du}, {dv}) at ({u}, {v})");
        }
        bm.filter = FilterType::Nearest;
        assert_eq!(bm.luminance_gradient(Vec2::new(0.3, 0.2)), Vec2::ZERO);
    }

    #[test]
    fn nearest_clamp_and_bad_input() {
        let mut bm = probe();
        bm.filter = FilterType::Nearest;
        assert_eq!(bm.eval(Vec2::new(0.49, 0.25)), Rgb::new(1.0, 0.0, 0.0));
        bm.filter = FilterType::Bilinear;
        bm.wrap = WrapMode::Clamp;
        assert_eq!(bm.eval(Vec2::new(0.0, 0.25)), Rgb::new(1.0, 0.0, 0.0));
        assert_eq!(bm.eval(Vec2::new(f32::NAN, 0.25)), Rgb::BLACK);
        assert_eq!(probe().mean(), Rgb::new(0.5, 0.5, 0.5));
        assert!(Bitmap::new(2, 2, vec![Rgb::WHITE; 3]).is_none());
        assert!(Bitmap::new(1, 1, vec![Rgb::new(-1.0, 0.0, 0.0)]).is_none());
    }
}
