//! Mitsuba's `normalmap`, `bumpmap` and `mask` BSDF wrappers → a native material's `normal_map`,
//! `bump_map` or `opacity`:
//!
//! - `normalmap`: the `normalmap` texture (Mitsuba's documentation asks for `raw = true`; the
//!   native normal map is always read raw, and a file without it is warned about), the nested
//!   BSDF, `use_shadowing_function` (default true); `flip_invalid_normals` is always on;
//! - `bumpmap`: the one nested texture (a height field), `scale` (default 1), the nested BSDF,
//!   `use_shadowing_function`.
//!
//! - `mask`: `opacity` (a float or a texture, default 0.5), the nested BSDF.
//!
//! Each may wrap, or be wrapped by, `twosided` or the others; one of each per material.

use super::{num, Conv, R};
use crate::mitsuba::parse::Element;
use crate::native::model::{Colour, NormalDef, NormalPerturbationDef, OpacityDef, TextureDef, Triple};

/// What the wrappers around a material's BSDF add to it.
#[derive(Default)]
pub(super) struct Wrappers {
    pub normal: Option<NormalPerturbationDef>,
    pub opacity: Option<OpacityDef>,
    /// A rough conductor's or dielectric's `alpha` texture.
    pub roughness: Option<Colour>,
    /// A `twosided` wrapper was met: the material shades both faces.
    pub two_sided: bool,
}

impl<'a> Conv<'a, '_> {
    /// The map of a `normalmap` or `bumpmap` element and its nested BSDF element.
    pub(super) fn normal_wrapper(&mut self, e: &'a Element, ty: &str) -> R<(NormalPerturbationDef, &'a Element)> {
        let nested = self.nested_bsdf(e, ty)?;
        if self.boolean(e, "flip_invalid_normals")? == Some(false) {
            self.warn(e, "flip_invalid_normals = false is not supported: invalid normals are flipped");
        }
        let shadowing = self.boolean(e, "use_shadowing_function")?.unwrap_or(true);
        let map = if ty == "normalmap" {
            let Some(texture) = self.colour(e, "normalmap")? else {
                return Err(self.src.error(e.offset, "a `normalmap` BSDF needs a `normalmap` texture"));
            };
            if let Colour::Texture(TextureDef::Bitmap { raw: false, .. }) = &texture {
                self.warn(e, "the normal map's bitmap is not `raw`: Mitsuba would sRGB-decode it; it is read raw");
            }
            NormalDef::Map { texture, strength: num(1.0) }
        } else {
            let height = self.unnamed_texture(e)?;
            let scale = self.float(e, "scale")?.unwrap_or(1.0);
            NormalDef::Bump { height, scale: num(scale) }
        };
        Ok((NormalPerturbationDef { map, shadowing }, nested))
    }

    /// The opacity of a `mask` element and its nested BSDF element.
    pub(super) fn mask_wrapper(&mut self, e: &'a Element) -> R<(OpacityDef, &'a Element)> {
        let nested = self.nested_bsdf(e, "mask")?;
        let texture = self.scalar_colour(e, "opacity")?.unwrap_or(Colour::Constant(Triple::Splat(num(0.5))));
        Ok((OpacityDef { texture, cutoff: None }, nested))
    }

    /// The one BSDF nested in a wrapper (or referenced from it).
    fn nested_bsdf(&mut self, e: &'a Element, ty: &str) -> R<&'a Element> {
        let nested = e
            .children
            .iter()
            .find(|c| c.tag == "bsdf" || (c.tag == "ref" && c.attr("name").is_none_or(|n| n == "bsdf")));
        let Some(nested) = nested else {
            return Err(self
                .src
                .error(e.offset, format!("a `{ty}` BSDF needs a nested <bsdf> (the surface it wraps)")));
        };
        self.deref(nested)
    }

    /// A `bumpmap`'s height field: its one nested (or referenced) texture, named or not.
    fn unnamed_texture(&mut self, e: &'a Element) -> R<Colour> {
        if let Some(t) = e.children.iter().find(|c| c.tag == "texture") {
            return self.texture(t).map(Colour::Texture);
        }
        for r in e.children.iter().filter(|c| c.tag == "ref") {
            let target = self.deref(r)?;
            if target.tag == "texture" {
                return self.texture(target).map(Colour::Texture);
            }
        }
        Err(self.src.error(e.offset, "a `bumpmap` BSDF needs a nested <texture> (the height field)"))
    }
}
