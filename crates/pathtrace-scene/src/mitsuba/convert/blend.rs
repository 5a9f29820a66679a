//! Mitsuba's `blendbsdf` → the native `blend`: `weight` (a float in [0, 1] or a texture, default
//! 0.5 as Mitsuba's) and its two nested BSDFs, each added to the file as a material of its own
//! (`NAME-model0`, `NAME-model1`, after the blend's place in the file) that the blend names.
//! A nested BSDF's `twosided` wrapper is dropped with a warning: the blend's own (a `twosided`
//! around the `blendbsdf`) decides which faces it shades.

use super::{Conv, R};
use crate::mitsuba::parse::Element;
use crate::native::model::{Colour, MaterialDef, MaterialKind};
use crate::native::ItemPath;

use super::wrappers::Wrappers;

impl<'a> Conv<'a, '_> {
    pub(super) fn blend_bsdf(&mut self, e: &'a Element, depth: usize) -> R<MaterialKind> {
        let weight = self.scalar_colour(e, "weight")?.unwrap_or(Colour::grey(0.5));
        if let Colour::Constant(w) = &weight {
            let w = w.vec3();
            if !(w.min_element() >= 0.0 && w.max_element() <= 1.0) {
                let at = self.prop(e, "weight").map_or(e.offset, |p| p.offset_of("value"));
                return Err(self.src.error(at, format!("blendbsdf weight {} must be from 0 to 1", w.x)));
            }
        }
        let nested: Vec<&'a Element> = e.children.iter().filter(|c| c.tag == "bsdf" || c.tag == "ref").collect();
        if nested.len() != 2 {
            return Err(self
                .src
                .error(e.offset, format!("a blendbsdf needs exactly two nested BSDFs, found {}", nested.len())));
        }
        let mut names = [String::new(), String::new()];
        for (k, c) in nested.into_iter().enumerate() {
            let d = self.deref(c)?;
            let mut maps = Wrappers::default();
            let kind = self.bsdf_kind_at(d, depth + 1, &mut maps)?;
            if maps.normal.is_some() || maps.opacity.is_some() {
                return Err(self.src.error(
                    d.offset,
                    "a normalmap, bumpmap or mask inside a blendbsdf is not supported (wrap the blendbsdf instead)",
                ));
            }
            if maps.two_sided {
                self.warn(d, "a twosided inside a blendbsdf is ignored: wrap the blendbsdf in twosided");
            }
            let name = self.unique_name(&format!("blend@{}-model{k}", e.offset));
            let def = MaterialDef { kind, emission: None, normal: None, opacity: None, roughness: maps.roughness };
            self.materials.insert(name.clone(), def);
            self.origins.push((ItemPath::root().field("materials").field(&name), d.offset));
            names[k] = name;
        }
        Ok(MaterialKind::Blend { weight, bsdfs: names })
    }
}
