//! `[materials.NAME]`: a surface model by `type`, its parameters, and optional emission.
//!
//! Files are read into a flat [`RawMaterial`] (every field optional, unknown fields rejected, so a
//! wrongly typed value is reported at its own position), then checked into a [`MaterialDef`].

use super::values::{Num, Triple};
use serde::{Deserialize, Serialize};

/// The surface models, as named by `type`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MaterialType {
    Diffuse,
    Lambertian,
    Mirror,
    Glossy,
    Dielectric,
    ThinDielectric,
    Emissive,
}

/// A material's scattering model and parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MaterialKind {
    /// The naive "uniform diffuse" model: scatters uniformly over the hemisphere (not Lambertian).
    Diffuse { albedo: Triple },
    /// Lambertian reflector with cosine-weighted sampling.
    Lambertian { albedo: Triple },
    /// Perfect specular reflector; `reflectance` defaults to 1.
    Mirror { reflectance: Triple },
    /// Phong lobe of the given exponent.
    Glossy { albedo: Triple, exponent: Num },
    /// Smooth glass; `ior` defaults to 1.5, `tint` to 1.
    Dielectric { ior: Num, tint: Triple },
    /// A thin glass sheet (Mitsuba's `thindielectric`); `ior` defaults to 1.5, `tint` to 1.
    ThinDielectric { ior: Num, tint: Triple },
    /// A black surface that emits `radiance` (set on the [`MaterialDef`]'s emission).
    Emissive,
}

/// Light given off by a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmissionDef {
    /// Emitted radiance per channel.
    pub radiance: Triple,
    /// Emit from both faces (default: only the front face).
    pub two_sided: bool,
}

/// One named material of a scene file.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(try_from = "RawMaterial", into = "RawMaterial")]
pub struct MaterialDef {
    /// How the surface scatters light.
    pub kind: MaterialKind,
    /// How it emits (always present for `emissive`; optional otherwise, e.g. a furnace).
    pub emission: Option<EmissionDef>,
}

/// The file form of a material: every field of every type, checked by [`MaterialDef::try_from`].
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    #[serde(rename = "type")]
    kind: Option<MaterialType>,
    #[serde(skip_serializing_if = "Option::is_none")]
    albedo: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    reflectance: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    exponent: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ior: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    tint: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    radiance: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    emission: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    two_sided: Option<bool>,
}

/// The fields each type accepts besides `type`, `emission` and `two_sided`.
fn allowed(t: MaterialType) -> &'static [&'static str] {
    match t {
        MaterialType::Diffuse | MaterialType::Lambertian => &["albedo"],
        MaterialType::Mirror => &["reflectance"],
        MaterialType::Glossy => &["albedo", "exponent"],
        MaterialType::Dielectric | MaterialType::ThinDielectric => &["ior", "tint"],
        MaterialType::Emissive => &["radiance"],
    }
}

impl RawMaterial {
    fn present(&self) -> Vec<&'static str> {
        let fields = [
            ("albedo", self.albedo.is_some()),
            ("reflectance", self.reflectance.is_some()),
            ("exponent", self.exponent.is_some()),
            ("ior", self.ior.is_some()),
            ("tint", self.tint.is_some()),
            ("radiance", self.radiance.is_some()),
        ];
        fields.iter().filter(|f| f.1).map(|f| f.0).collect()
    }
}

fn required<T>(v: Option<T>, t: &str, field: &str) -> Result<T, String> {
    v.ok_or_else(|| format!("a {t} material needs `{field}`"))
}

impl TryFrom<RawMaterial> for MaterialDef {
    type Error = String;

    fn try_from(r: RawMaterial) -> Result<Self, String> {
        let t = r.kind.ok_or(
            "a material needs a `type` (diffuse, lambertian, mirror, glossy, dielectric, thindielectric, emissive)",
        )?;
        let name = serde_json::to_value(t).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default();
        if let Some(extra) = r.present().into_iter().find(|f| !allowed(t).contains(f)) {
            let ok = allowed(t).iter().map(|f| format!("`{f}`")).collect::<Vec<_>>().join(", ");
            return Err(format!("`{extra}` is not a parameter of a {name} material (it takes {ok})"));
        }
        let one = Triple::Splat(Num::from(1.0));
        let kind = match t {
            MaterialType::Diffuse => MaterialKind::Diffuse { albedo: required(r.albedo, &name, "albedo")? },
            MaterialType::Lambertian => MaterialKind::Lambertian { albedo: required(r.albedo, &name, "albedo")? },
            MaterialType::Mirror => MaterialKind::Mirror { reflectance: r.reflectance.unwrap_or(one) },
            MaterialType::Glossy => MaterialKind::Glossy {
                albedo: required(r.albedo, &name, "albedo")?,
                exponent: required(r.exponent, &name, "exponent")?,
            },
            MaterialType::Dielectric => {
                MaterialKind::Dielectric { ior: r.ior.unwrap_or(Num::from(1.5)), tint: r.tint.unwrap_or(one) }
            }
            MaterialType::ThinDielectric => {
                MaterialKind::ThinDielectric { ior: r.ior.unwrap_or(Num::from(1.5)), tint: r.tint.unwrap_or(one) }
            }
            MaterialType::Emissive => MaterialKind::Emissive,
        };
        let radiance = match t {
            MaterialType::Emissive => {
                if r.emission.is_some() {
                    return Err("an emissive material takes `radiance`, not `emission`".into());
                }
                Some(required(r.radiance, &name, "radiance")?)
            }
            _ => r.emission,
        };
        let emission = match (radiance, r.two_sided) {
            (Some(radiance), two_sided) => Some(EmissionDef { radiance, two_sided: two_sided.unwrap_or(false) }),
            (None, Some(_)) => return Err("`two_sided` applies only to emitting materials (add `emission`)".into()),
            (None, None) => None,
        };
        Ok(MaterialDef { kind, emission })
    }
}

impl From<MaterialDef> for RawMaterial {
    fn from(m: MaterialDef) -> Self {
        let mut r = RawMaterial::default();
        match m.kind {
            MaterialKind::Diffuse { albedo } => (r.kind, r.albedo) = (Some(MaterialType::Diffuse), Some(albedo)),
            MaterialKind::Lambertian { albedo } => (r.kind, r.albedo) = (Some(MaterialType::Lambertian), Some(albedo)),
            MaterialKind::Mirror { reflectance } => {
                (r.kind, r.reflectance) = (Some(MaterialType::Mirror), Some(reflectance))
            }
            MaterialKind::Glossy { albedo, exponent } => {
                (r.kind, r.albedo, r.exponent) = (Some(MaterialType::Glossy), Some(albedo), Some(exponent))
            }
            MaterialKind::Dielectric { ior, tint } => {
                (r.kind, r.ior, r.tint) = (Some(MaterialType::Dielectric), Some(ior), Some(tint))
            }
            MaterialKind::ThinDielectric { ior, tint } => {
                (r.kind, r.ior, r.tint) = (Some(MaterialType::ThinDielectric), Some(ior), Some(tint))
            }
            MaterialKind::Emissive => r.kind = Some(MaterialType::Emissive),
        }
        if let Some(e) = m.emission {
            if m.kind == MaterialKind::Emissive {
                r.radiance = Some(e.radiance);
            } else {
                r.emission = Some(e.radiance);
            }
            r.two_sided = e.two_sided.then_some(true);
        }
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<MaterialDef, String> {
        toml::from_str(s).map_err(|e| e.message().to_string())
    }

    #[test]
    fn defaults_are_filled_in() {
        let glass = parse("type = \"dielectric\"").unwrap();
        assert_eq!(glass.kind, MaterialKind::Dielectric { ior: Num::from(1.5), tint: Triple::Splat(Num::from(1.0)) });
        let light = parse("type = \"emissive\"\nradiance = 4").unwrap();
        assert_eq!(light.emission, Some(EmissionDef { radiance: Triple::Splat(Num::from(4.0)), two_sided: false }));
    }

    #[test]
    fn wrong_parameters_are_named() {
        assert!(parse("type = \"mirror\"\nalbedo = 1").unwrap_err().contains("`albedo` is not a parameter"));
        assert!(parse("type = \"lambertian\"").unwrap_err().contains("needs `albedo`"));
        assert!(parse("type = \"lambertian\"\nalbedo = 1\ntwo_sided = true").unwrap_err().contains("two_sided"));
        assert!(parse("type = \"plastic\"").unwrap_err().contains("unknown variant"));
        assert!(parse("type = \"mirror\"\ncolour = 1").unwrap_err().contains("unknown field"));
    }

    #[test]
    fn emission_on_a_scattering_material_round_trips() {
        let m = parse("type = \"diffuse\"\nalbedo = 0.5\nemission = [1, 2, 3]\ntwo_sided = true").unwrap();
        let back: MaterialDef = toml::from_str(&toml::to_string(&m).unwrap()).unwrap();
        assert_eq!(m, back);
    }
}
