//! Mitsuba's metal, rough glass and plastic BSDFs → the native microfacet and coated materials:
//! `conductor`, `roughconductor`, `roughdielectric`, `plastic`, `roughplastic` with Mitsuba's
//! parameter names and defaults (beckmann, α = 0.1, `none` metal, polypropylene plastic, BK7
//! glass in air).

use super::{num, Conv, R};
use crate::mitsuba::parse::Element;
use crate::native::model::{Colour, MaterialKind, MetalDef, MetalName, Num, RoughnessDef, Triple};
use pathtrace::material::MicrofacetKind;

impl<'a> Conv<'a, '_> {
    /// The native material for one of the BSDF types named in the module doc, or `None` for
    /// any other type.
    pub(super) fn microfacet_bsdf(&mut self, e: &'a Element, ty: &str) -> R<Option<MaterialKind>> {
        let one = Colour::grey(1.0);
        Ok(Some(match ty {
            "conductor" => {
                let metal = self.metal(e)?;
                MaterialKind::Conductor { metal, reflectance: self.colour(e, "specular_reflectance")?.unwrap_or(one) }
            }
            "roughconductor" => {
                let metal = self.metal(e)?;
                let reflectance = self.colour(e, "specular_reflectance")?.unwrap_or(one);
                MaterialKind::RoughConductor { metal, reflectance, roughness: self.roughness(e, true)? }
            }
            "roughdielectric" => {
                let ior = self.relative_ior(e, 1.5046)?;
                let tint = self.colour(e, "specular_transmittance")?.unwrap_or(one);
                MaterialKind::RoughDielectric { ior, tint, roughness: self.roughness(e, true)? }
            }
            "plastic" | "roughplastic" => {
                let albedo = self.colour(e, "diffuse_reflectance")?.unwrap_or(Colour::grey(0.5));
                let specular = self.colour(e, "specular_reflectance")?.unwrap_or(one);
                let ior = self.relative_ior(e, 1.49)?;
                let nonlinear = self.boolean(e, "nonlinear")?.unwrap_or(false);
                if ty == "plastic" {
                    MaterialKind::Plastic { albedo, specular, ior, nonlinear }
                } else {
                    let roughness = self.roughness(e, false)?;
                    MaterialKind::RoughPlastic { albedo, specular, ior, nonlinear, roughness }
                }
            }
            _ => return Ok(None),
        }))
    }

    /// `material="Au"` (default `none`, a perfect mirror) or explicit `eta` and `k`.
    fn metal(&mut self, e: &'a Element) -> R<MetalDef> {
        let (eta, k) = (self.color(e, "eta")?, self.color(e, "k")?);
        if let (Some(eta), Some(k)) = (eta, k) {
            return Ok(MetalDef::Custom { eta, k });
        }
        if eta.is_some() != k.is_some() {
            // Mitsuba's defaults for a lone one: η = 0, k = 1.
            let eta = eta.unwrap_or(Triple::Splat(num(0.0)));
            let k = k.unwrap_or(Triple::Splat(num(1.0)));
            return Ok(MetalDef::Custom { eta, k });
        }
        let name = self.string(e, "material")?.unwrap_or("none");
        MetalName::parse(name).map(MetalDef::Named).map_err(|msg| {
            let at = self.prop(e, "material").map_or(e.offset, |p| p.offset_of("value"));
            self.src.error(at, msg)
        })
    }

    /// `distribution`, `alpha` or `alpha_u`/`alpha_v` (when `anisotropic` is allowed).
    /// `sample_visible` only changes how Mitsuba samples, not the image: we always sample
    /// visible normals.
    fn roughness(&mut self, e: &'a Element, anisotropic: bool) -> R<RoughnessDef> {
        let distribution = match self.string(e, "distribution")? {
            None => MicrofacetKind::Beckmann,
            Some(name) => name.parse::<MicrofacetKind>().map_err(|msg| {
                let at = self.prop(e, "distribution").map_or(e.offset, |p| p.offset_of("value"));
                self.src.error(at, msg)
            })?,
        };
        // An `alpha` texture is read by `alpha_texture`.
        let alpha = self.roughness_value(e, "alpha", true)?;
        let (u, v) = if anisotropic {
            (self.roughness_value(e, "alpha_u", false)?, self.roughness_value(e, "alpha_v", false)?)
        } else {
            (None, None)
        };
        let a = alpha.unwrap_or(0.1);
        Ok(RoughnessDef { distribution, alpha_u: num(u.unwrap_or(a)), alpha_v: num(v.unwrap_or(a)) })
    }

    /// A non-negative roughness. A texture is read by [`Conv::alpha_texture`] when
    /// `texture_ok` (the constant is then only a placeholder); otherwise it is replaced by 0.1 with
    /// a warning.
    fn roughness_value(&mut self, e: &'a Element, name: &str, texture_ok: bool) -> R<Option<f64>> {
        let Some(p) = self.prop(e, name) else {
            if e.children.iter().any(|c| c.tag == "ref" && c.attr("name") == Some(name)) {
                if !texture_ok {
                    self.warn(e, &format!("`{name}` is a texture: not supported here, using 0.1"));
                }
                return Ok(Some(0.1));
            }
            return Ok(None);
        };
        if p.tag == "texture" {
            if !texture_ok {
                self.warn(p, &format!("`{name}` is a texture: not supported here, using 0.1"));
            }
            return Ok(Some(0.1));
        }
        let x = self.float(e, name)?.unwrap_or(0.1);
        if x < 0.0 {
            return Err(self.src.error(p.offset_of("value"), format!("`{name}` must be ≥ 0")));
        }
        Ok(Some(x))
    }

    /// The `alpha` texture of a `roughconductor` or `roughdielectric` (Mitsuba evaluates it per
    /// hit as an isotropic α), or of a `roughplastic` (an extension: Mitsuba 3.9.1 refuses a
    /// texture there, "expected float"; we read it as the others), if it is one.
    pub(super) fn alpha_texture(&mut self, e: &'a Element, ty: &str) -> R<Option<Colour>> {
        if ty != "roughconductor" && ty != "roughdielectric" && ty != "roughplastic" {
            return Ok(None);
        }
        Ok(self.scalar_colour(e, "alpha")?.filter(|c| matches!(c, Colour::Texture(_))))
    }

    /// `int_ior / ext_ior` (each a number or a name; exterior air by default).
    fn relative_ior(&mut self, e: &'a Element, interior: f64) -> R<Num> {
        let int = self.ior(e, "int_ior", interior)?;
        let ext = self.ior(e, "ext_ior", 1.000277)?;
        Ok(num(int / ext))
    }
}
