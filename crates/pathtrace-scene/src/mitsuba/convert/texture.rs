//! Mitsuba's `<texture>` → a native texture table, for any colour parameter of a BSDF, nested
//! (`<texture type="checkerboard" name="reflectance">…`) or by reference
//! (`<ref name="reflectance" id="planetex"/>`):
//!
//! - `checkerboard`: `color0`, `color1` (constants), `to_uv`;
//! - `bitmap`: `filename` (found in the search folders), `raw`, `filter_type` (bilinear,
//!   nearest), `wrap_mode` (repeat, clamp; `mirror` becomes repeat with a warning), `to_uv`.
//!
//! `to_uv` is a 4×4 transform of which Mitsuba uses the upper-left 2×2 block and the fourth
//! column's translation (see pathtrace's `texture/uv_transform.rs`).

use super::{num, Conv, R};
use crate::mitsuba::parse::Element;
use crate::native::model::{identity_uv, Colour, TextureDef, Triple, UvRows};
use crate::native::transform::compose;

/// The texture properties each type understands (others are warned about).
const CHECKERBOARD: &[&str] = &["color0", "color1", "to_uv"];
const BITMAP: &[&str] = &["filename", "raw", "filter_type", "wrap_mode", "to_uv", "format"];

impl<'a> Conv<'a, '_> {
    /// A colour parameter of a BSDF: a constant (see `color`) or a texture.
    pub(super) fn colour(&mut self, e: &'a Element, name: &str) -> R<Option<Colour>> {
        let texture = match self.prop(e, name) {
            Some(p) if p.tag == "texture" => Some(p),
            Some(_) => None,
            None => match e.children.iter().find(|c| c.tag == "ref" && c.attr("name") == Some(name)) {
                Some(r) => {
                    let target = self.deref(r)?;
                    if target.tag != "texture" {
                        return Err(self
                            .src
                            .error(r.offset, format!("`{name}` must name a <texture>, not <{}>", target.tag)));
                    }
                    Some(target)
                }
                None => None,
            },
        };
        match texture {
            Some(t) => self.texture(t).map(|t| Some(Colour::Texture(t))),
            None => Ok(self.color(e, name)?.map(Colour::Constant)),
        }
    }

    /// A parameter Mitsuba reads as one number per hit (`eval_1`: roughness, blend weight,
    /// mask opacity): as [`Self::colour`], with a checkerboard's squares exchanged. Mitsuba 3's
    /// checkerboard (`src/textures/checkerboard.cpp`) puts `color0` where the two half-period
    /// tests agree in `eval` but where they differ in `eval_1`; its scenes are drawn that way.
    pub(super) fn scalar_colour(&mut self, e: &'a Element, name: &str) -> R<Option<Colour>> {
        Ok(self.colour(e, name)?.map(|c| match c {
            Colour::Texture(TextureDef::Checkerboard { color0, color1, to_uv }) => {
                Colour::Texture(TextureDef::Checkerboard { color0: color1, color1: color0, to_uv })
            }
            other => other,
        }))
    }

    pub(super) fn texture(&mut self, t: &'a Element) -> R<TextureDef> {
        let ty = self.req_attr(t, "type")?;
        let known = match ty {
            "checkerboard" => CHECKERBOARD,
            "bitmap" => BITMAP,
            other => {
                self.warn(t, &format!("texture type `{other}` is not supported, using a constant 0.5"));
                let half = Triple::Splat(num(0.5));
                return Ok(TextureDef::Checkerboard { color0: half, color1: half, to_uv: identity_uv() });
            }
        };
        for c in &t.children {
            if let Some(n) = c.attr("name") {
                if !known.contains(&n) {
                    self.warn(c, &format!("{ty} texture parameter `{n}` is not supported and is ignored"));
                }
            }
        }
        let to_uv = match self.prop(t, "to_uv") {
            Some(p) if p.tag == "transform" => self.uv_rows(p)?,
            Some(p) => return Err(self.src.error(p.offset, "`to_uv` must be a <transform>")),
            None => identity_uv(),
        };
        if ty == "checkerboard" {
            let color0 = self.color(t, "color0")?.unwrap_or(Triple::Splat(num(0.4)));
            let color1 = self.color(t, "color1")?.unwrap_or(Triple::Splat(num(0.2)));
            return Ok(TextureDef::Checkerboard { color0, color1, to_uv });
        }
        let Some(file) = self.string(t, "filename")? else {
            return Err(self.src.error(t.offset, "a bitmap texture needs a `filename` string"));
        };
        let filename = self.find_file(t, file, "texture")?;
        let raw = self.boolean(t, "raw")?.unwrap_or(false);
        let nearest = match self.string(t, "filter_type")? {
            None | Some("bilinear") => false,
            Some("nearest") => true,
            Some(other) => {
                self.warn(t, &format!("filter_type `{other}` is not supported, using bilinear"));
                false
            }
        };
        let clamp = match self.string(t, "wrap_mode")? {
            None | Some("repeat") => false,
            Some("clamp") => true,
            Some(other) => {
                self.warn(t, &format!("wrap_mode `{other}` is not supported, using repeat"));
                false
            }
        };
        if let Some(f) = self.string(t, "format")? {
            if f != "variant" {
                self.warn(t, &format!("bitmap format `{f}` is not supported, using full precision"));
            }
        }
        // Mitsuba's bitmap has no scale: the factor is 1.
        Ok(TextureDef::Bitmap { filename, raw, nearest, clamp, to_uv, alpha: false, factor: Triple::ONE })
    }

    /// The uv rows of a `to_uv` transform.
    fn uv_rows(&self, p: &'a Element) -> R<UvRows> {
        let steps = self.transform(p)?;
        let m = compose(&steps).map_err(|(_, e)| self.src.error(p.offset, format!("invalid `to_uv`: {e}")))?.matrix;
        let f = |x: f32| num(f64::from(x));
        Ok([[f(m.x_axis.x), f(m.y_axis.x), f(m.w_axis.x)], [f(m.x_axis.y), f(m.y_axis.y), f(m.w_axis.y)]])
    }
}
