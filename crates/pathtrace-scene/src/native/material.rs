//! `[materials.NAME]`: a surface model by `type`, its parameters, and optional emission.
//!
//! Files are read into a flat [`RawMaterial`] (every field optional, unknown fields rejected, so a
//! wrongly typed value is reported at its own position), then checked into a [`MaterialDef`].

use super::optics::{DistributionName, Ior, MetalDef, MetalName, RoughnessDef};
use super::texture::Colour;
use super::values::{Num, Triple};
use pathtrace::material::MicrofacetKind;
use serde::{Deserialize, Serialize};

/// The surface models, as named by `type`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MaterialType {
    Diffuse,
    Lambertian,
    Mirror,
    Glossy,
    Dielectric,
    /// Mitsuba's name (`thin_dielectric`, spelled like the other two-word types, is accepted too).
    #[serde(rename = "thindielectric", alias = "thin_dielectric")]
    ThinDielectric,
    Emissive,
    Conductor,
    RoughConductor,
    RoughDielectric,
    Plastic,
    RoughPlastic,
    /// An index-matched boundary of a medium (Mitsuba's `null`).
    Null,
    /// A mix of two other materials of the file (Mitsuba's `blendbsdf`).
    Blend,
}

/// A material's scattering model and parameters. Colour parameters may be textures.
#[derive(Clone, Debug, PartialEq)]
pub enum MaterialKind {
    /// The naive "uniform diffuse" model: scatters uniformly over the hemisphere (not Lambertian).
    Diffuse { albedo: Colour },
    /// Lambertian reflector with cosine-weighted sampling.
    Lambertian { albedo: Colour },
    /// Perfect specular reflector; `reflectance` defaults to 1.
    Mirror { reflectance: Colour },
    /// Phong lobe of the given exponent.
    Glossy { albedo: Colour, exponent: Num },
    /// Smooth glass; `ior` defaults to 1.5, `tint` to 1.
    Dielectric { ior: Num, tint: Colour },
    /// A thin glass sheet (Mitsuba's `thindielectric`); `ior` defaults to 1.5, `tint` to 1.
    ThinDielectric { ior: Num, tint: Colour },
    /// A black surface that emits `radiance` (set on the [`MaterialDef`]'s emission).
    Emissive,
    /// Smooth metal: Fresnel reflection with a complex index (named `metal` or `eta` + `k`),
    /// times `reflectance` (default 1).
    Conductor { metal: MetalDef, reflectance: Colour },
    /// Rough metal (microfacets).
    RoughConductor { metal: MetalDef, reflectance: Colour, roughness: RoughnessDef },
    /// Rough glass (microfacets); `ior` defaults to 1.5, `tint` to 1.
    RoughDielectric { ior: Num, tint: Colour, roughness: RoughnessDef },
    /// Diffuse base under a smooth coating (Mitsuba's `plastic`).
    Plastic { albedo: Colour, specular: Colour, ior: Num, nonlinear: bool },
    /// Diffuse base under a rough coating (Mitsuba's `roughplastic`; isotropic roughness).
    RoughPlastic { albedo: Colour, specular: Colour, ior: Num, nonlinear: bool, roughness: RoughnessDef },
    /// An index-matched boundary (Mitsuba's `null`): light passes straight through; it marks
    /// where the media of its objects' `interior` and `exterior` begin and end.
    Null,
    /// The inner model scattering from its front only (`one_sided = true`): black seen from
    /// behind, as Mitsuba's BSDFs outside `twosided`. Without it, opaque models shade both faces.
    OneSided(Box<MaterialKind>),
    /// (1 − `weight`) × the material named `bsdfs[0]` + `weight` × the one named `bsdfs[1]`
    /// (Mitsuba's `blendbsdf`); `weight` a number in [0, 1] or a texture (its luminance).
    Blend { weight: Colour, bsdfs: [String; 2] },
}

impl MaterialKind {
    /// The scattering model without its [`MaterialKind::OneSided`] wrapper, and whether it had one.
    pub fn sides(&self) -> (&MaterialKind, bool) {
        match self {
            MaterialKind::OneSided(inner) => (inner, true),
            k => (k, false),
        }
    }

    /// The colour parameters, for edits that apply to every texture (e.g. rebasing file paths).
    pub fn colours_mut(&mut self) -> Vec<&mut Colour> {
        match self {
            MaterialKind::Diffuse { albedo }
            | MaterialKind::Lambertian { albedo }
            | MaterialKind::Glossy { albedo, .. } => {
                vec![albedo]
            }
            MaterialKind::Mirror { reflectance }
            | MaterialKind::Conductor { reflectance, .. }
            | MaterialKind::RoughConductor { reflectance, .. } => vec![reflectance],
            MaterialKind::Dielectric { tint, .. }
            | MaterialKind::ThinDielectric { tint, .. }
            | MaterialKind::RoughDielectric { tint, .. } => vec![tint],
            MaterialKind::Plastic { albedo, specular, .. } | MaterialKind::RoughPlastic { albedo, specular, .. } => {
                vec![albedo, specular]
            }
            MaterialKind::Emissive | MaterialKind::Null => Vec::new(),
            MaterialKind::OneSided(inner) => inner.colours_mut(),
            MaterialKind::Blend { weight, .. } => vec![weight],
        }
    }
}

/// A normal or bump map on a material (`normal_map`, or `bump_map` with `bump_scale`).
#[derive(Clone, Debug, PartialEq)]
pub enum NormalDef {
    /// A tangent-space normal map: texel c encodes the normal 2c − 1 (bitmaps are read raw,
    /// whatever their `raw` says); `strength` scales its tangential part (glTF's `scale`).
    Map { texture: Colour, strength: Num },
    /// A height field (its luminance) scaled by `scale`.
    Bump { height: Colour, scale: Num },
}

impl NormalDef {
    /// The texture it reads.
    pub fn texture_mut(&mut self) -> &mut Colour {
        match self {
            NormalDef::Map { texture, .. } => texture,
            NormalDef::Bump { height, .. } => height,
        }
    }
}

/// How a material tilts its shading normal.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalPerturbationDef {
    pub map: NormalDef,
    /// Attenuate by the microfacet shadowing term at the bump terminator (Mitsuba's
    /// `use_shadowing_function`, default true).
    pub shadowing: bool,
}

/// An opacity mask: how much of the surface is there (the texture's luminance, clamped to
/// [0, 1]), or with `cutoff` (glTF's `alphaCutoff`) all where the value reaches it and none
/// elsewhere.
#[derive(Clone, Debug, PartialEq)]
pub struct OpacityDef {
    pub texture: Colour,
    pub cutoff: Option<Num>,
}

/// Light given off by a surface.
#[derive(Clone, Debug, PartialEq)]
pub struct EmissionDef {
    /// Emitted radiance per channel.
    pub radiance: Triple,
    /// Emit from both faces (default: only the front face).
    pub two_sided: bool,
    /// A texture the radiance is multiplied by (`emission_texture`; glTF's `emissiveTexture`),
    /// looked up at each point's (u, v); meshes and quads only. Always a [`Colour::Texture`].
    pub texture: Option<Colour>,
}

/// One named material of a scene file.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(try_from = "RawMaterial", into = "RawMaterial")]
pub struct MaterialDef {
    /// How the surface scatters light.
    pub kind: MaterialKind,
    /// How it emits (always present for `emissive`; optional otherwise, e.g. a furnace).
    pub emission: Option<EmissionDef>,
    /// A normal or bump map, if any.
    pub normal: Option<NormalPerturbationDef>,
    /// An opacity mask (cut-out), if any.
    pub opacity: Option<OpacityDef>,
    /// A texture of the isotropic roughness α (`alpha_texture`: rough conductors, dielectrics and
    /// plastics).
    pub roughness: Option<Colour>,
}

impl MaterialDef {
    /// A material of scattering model `kind` alone: no emission, maps or textured roughness.
    pub fn plain(kind: MaterialKind) -> Self {
        MaterialDef { kind, emission: None, normal: None, opacity: None, roughness: None }
    }

    /// Every colour parameter and map, for edits that apply to every texture (e.g. rebasing file
    /// paths).
    pub fn textures_mut(&mut self) -> Vec<&mut Colour> {
        let mut all = self.kind.colours_mut();
        if let Some(n) = &mut self.normal {
            all.push(n.map.texture_mut());
        }
        if let Some(o) = &mut self.opacity {
            all.push(&mut o.texture);
        }
        if let Some(r) = &mut self.roughness {
            all.push(r);
        }
        if let Some(t) = self.emission.as_mut().and_then(|e| e.texture.as_mut()) {
            all.push(t);
        }
        all
    }
}

/// The file form of a material: every field of every type, checked by [`MaterialDef::try_from`].
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    #[serde(rename = "type")]
    kind: Option<MaterialType>,
    #[serde(skip_serializing_if = "Option::is_none")]
    albedo: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    reflectance: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    exponent: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ior: Option<Ior>,
    #[serde(skip_serializing_if = "Option::is_none")]
    tint: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    radiance: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    emission: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    two_sided: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    one_sided: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    emission_texture: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    metal: Option<MetalName>,
    #[serde(skip_serializing_if = "Option::is_none")]
    eta: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    k: Option<Triple>,
    #[serde(skip_serializing_if = "Option::is_none")]
    specular: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    nonlinear: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    distribution: Option<DistributionName>,
    #[serde(skip_serializing_if = "Option::is_none")]
    alpha: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    alpha_u: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    alpha_v: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    normal_map: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    normal_strength: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    bump_map: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    bump_scale: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    normal_shadowing: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    opacity: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    alpha_cutoff: Option<Num>,
    #[serde(skip_serializing_if = "Option::is_none")]
    alpha_texture: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    weight: Option<Colour>,
    #[serde(skip_serializing_if = "Option::is_none")]
    bsdfs: Option<Vec<String>>,
}

/// The fields each type accepts besides `type`, `emission` and `two_sided`.
fn allowed(t: MaterialType) -> &'static [&'static str] {
    match t {
        MaterialType::Diffuse | MaterialType::Lambertian => &["albedo"],
        MaterialType::Mirror => &["reflectance"],
        MaterialType::Glossy => &["albedo", "exponent"],
        MaterialType::Dielectric | MaterialType::ThinDielectric => &["ior", "tint"],
        MaterialType::Emissive => &["radiance"],
        MaterialType::Null => &[],
        MaterialType::Conductor => &["metal", "eta", "k", "reflectance"],
        MaterialType::RoughConductor => {
            &["metal", "eta", "k", "reflectance", "distribution", "alpha", "alpha_u", "alpha_v", "alpha_texture"]
        }
        MaterialType::RoughDielectric => {
            &["ior", "tint", "distribution", "alpha", "alpha_u", "alpha_v", "alpha_texture"]
        }
        MaterialType::Plastic => &["albedo", "specular", "ior", "nonlinear"],
        MaterialType::RoughPlastic => {
            &["albedo", "specular", "ior", "nonlinear", "distribution", "alpha", "alpha_texture"]
        }
        MaterialType::Blend => &["weight", "bsdfs"],
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
            ("metal", self.metal.is_some()),
            ("eta", self.eta.is_some()),
            ("k", self.k.is_some()),
            ("specular", self.specular.is_some()),
            ("nonlinear", self.nonlinear.is_some()),
            ("distribution", self.distribution.is_some()),
            ("alpha", self.alpha.is_some()),
            ("alpha_u", self.alpha_u.is_some()),
            ("alpha_v", self.alpha_v.is_some()),
            ("alpha_texture", self.alpha_texture.is_some()),
            ("weight", self.weight.is_some()),
            ("bsdfs", self.bsdfs.is_some()),
        ];
        fields.iter().filter(|f| f.1).map(|f| f.0).collect()
    }

    /// `metal = "Au"`, or `eta` and `k` together; neither means `none` (a perfect mirror), as
    /// Mitsuba's default.
    fn metal_def(&self) -> Result<MetalDef, String> {
        match (self.metal, self.eta, self.k) {
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
                Err("give either `metal` or `eta` and `k`, not both".into())
            }
            (Some(name), None, None) => Ok(MetalDef::Named(name)),
            (None, Some(eta), Some(k)) => {
                let ok = |t: Triple| t.vec3().min_element() >= 0.0;
                if !ok(eta) || !ok(k) {
                    return Err("`eta` and `k` must be ≥ 0".into());
                }
                Ok(MetalDef::Custom { eta, k })
            }
            (None, Some(_), None) | (None, None, Some(_)) => Err("`eta` and `k` go together".into()),
            (None, None, None) => Ok(MetalDef::Named(MetalName("none"))),
        }
    }

    /// `distribution` (default beckmann, as Mitsuba) and `alpha` (default 0.1), or `alpha_u`
    /// and `alpha_v` for anisotropic roughness.
    fn roughness(&self) -> Result<RoughnessDef, String> {
        let distribution = self.distribution.map_or(MicrofacetKind::Beckmann, |d| d.0);
        let (alpha_u, alpha_v) = match (self.alpha, self.alpha_u, self.alpha_v) {
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
                return Err("give either `alpha` or `alpha_u` and `alpha_v`, not both".into())
            }
            (Some(a), None, None) => (a, a),
            (None, Some(u), Some(v)) => (u, v),
            (None, Some(_), None) | (None, None, Some(_)) => return Err("`alpha_u` and `alpha_v` go together".into()),
            (None, None, None) => (Num::from(0.1), Num::from(0.1)),
        };
        if alpha_u.get() < 0.0 || alpha_v.get() < 0.0 {
            return Err("roughness `alpha` must be ≥ 0".into());
        }
        Ok(RoughnessDef { distribution, alpha_u, alpha_v })
    }
}

fn required<T>(v: Option<T>, t: &str, field: &str) -> Result<T, String> {
    v.ok_or_else(|| format!("a {t} material needs `{field}`"))
}

impl TryFrom<RawMaterial> for MaterialDef {
    type Error = String;

    fn try_from(r: RawMaterial) -> Result<Self, String> {
        let t = r.kind.ok_or(
            "a material needs a `type` (diffuse, lambertian, mirror, glossy, dielectric, thindielectric, emissive, \
             conductor, rough_conductor, rough_dielectric, plastic, rough_plastic, null, blend)",
        )?;
        let name = serde_json::to_value(t).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default();
        if let Some(extra) = r.present().into_iter().find(|f| !allowed(t).contains(f)) {
            let ok = allowed(t).iter().map(|f| format!("`{f}`")).collect::<Vec<_>>().join(", ");
            let ok = if ok.is_empty() { "no parameters".to_string() } else { ok };
            return Err(format!("`{extra}` is not a parameter of a {name} material (it takes {ok})"));
        }
        let normal = r.normal_def()?;
        let opacity = match (&r.opacity, r.alpha_cutoff) {
            (Some(texture), cutoff) => Some(OpacityDef { texture: texture.clone(), cutoff }),
            (None, Some(_)) => return Err("`alpha_cutoff` needs an `opacity`".into()),
            (None, None) => None,
        };
        let one = Colour::grey(1.0);
        let kind = match t {
            MaterialType::Diffuse => MaterialKind::Diffuse { albedo: required(r.albedo, &name, "albedo")? },
            MaterialType::Lambertian => MaterialKind::Lambertian { albedo: required(r.albedo, &name, "albedo")? },
            MaterialType::Mirror => MaterialKind::Mirror { reflectance: r.reflectance.unwrap_or(one.clone()) },
            MaterialType::Glossy => MaterialKind::Glossy {
                albedo: required(r.albedo, &name, "albedo")?,
                exponent: required(r.exponent, &name, "exponent")?,
            },
            MaterialType::Dielectric => MaterialKind::Dielectric {
                ior: r.ior.map_or(Num::from(1.5), |i| i.0),
                tint: r.tint.unwrap_or(one.clone()),
            },
            MaterialType::ThinDielectric => MaterialKind::ThinDielectric {
                ior: r.ior.map_or(Num::from(1.5), |i| i.0),
                tint: r.tint.unwrap_or(one.clone()),
            },
            MaterialType::Emissive => MaterialKind::Emissive,
            MaterialType::Null => MaterialKind::Null,
            MaterialType::Conductor => {
                MaterialKind::Conductor { metal: r.metal_def()?, reflectance: r.reflectance.unwrap_or(one.clone()) }
            }
            MaterialType::RoughConductor => MaterialKind::RoughConductor {
                metal: r.metal_def()?,
                reflectance: r.reflectance.clone().unwrap_or(one.clone()),
                roughness: r.roughness()?,
            },
            MaterialType::RoughDielectric => MaterialKind::RoughDielectric {
                ior: r.ior.map_or(Num::from(1.5), |i| i.0),
                tint: r.tint.clone().unwrap_or(one.clone()),
                roughness: r.roughness()?,
            },
            // Plastics default to Mitsuba's: albedo 0.5, polypropylene (1.49), linear.
            MaterialType::Plastic => MaterialKind::Plastic {
                albedo: r.albedo.clone().unwrap_or(Colour::grey(0.5)),
                specular: r.specular.clone().unwrap_or(one.clone()),
                ior: r.ior.map_or(Num::from(1.49), |i| i.0),
                nonlinear: r.nonlinear.unwrap_or(false),
            },
            MaterialType::RoughPlastic => MaterialKind::RoughPlastic {
                albedo: r.albedo.clone().unwrap_or(Colour::grey(0.5)),
                specular: r.specular.clone().unwrap_or(one.clone()),
                ior: r.ior.map_or(Num::from(1.49), |i| i.0),
                nonlinear: r.nonlinear.unwrap_or(false),
                roughness: r.roughness()?,
            },
            MaterialType::Blend => {
                let weight = required(r.weight.clone(), &name, "weight")?;
                if let Colour::Constant(w) = &weight {
                    let w = w.vec3();
                    if !(w.min_element() >= 0.0 && w.max_element() <= 1.0) {
                        return Err(format!("a blend's `weight` must be from 0 to 1 (found {:?})", w.to_array()));
                    }
                }
                let bsdfs = required(r.bsdfs.clone(), &name, "bsdfs")?;
                let bsdfs: [String; 2] = bsdfs.try_into().map_err(|v: Vec<String>| {
                    format!("a blend's `bsdfs` names two materials (model 0, model 1), not {}", v.len())
                })?;
                MaterialKind::Blend { weight, bsdfs }
            }
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
        let texture = match r.emission_texture.clone() {
            None => None,
            Some(t @ Colour::Texture(_)) => Some(t),
            Some(Colour::Constant(_)) => {
                return Err("`emission_texture` must be a texture table (scale `radiance` or `emission` instead)".into())
            }
        };
        let emission = match (radiance, r.two_sided, texture) {
            (Some(radiance), two_sided, texture) => {
                Some(EmissionDef { radiance, two_sided: two_sided.unwrap_or(false), texture })
            }
            (None, Some(_), _) => return Err("`two_sided` applies only to emitting materials (add `emission`)".into()),
            (None, None, Some(_)) => {
                return Err("`emission_texture` applies only to emitting materials (add `emission`)".into())
            }
            (None, None, None) => None,
        };
        if normal.is_some() && t == MaterialType::Emissive {
            return Err("an emissive material cannot take a normal or bump map (it does not scatter)".into());
        }
        if opacity.is_some() && emission.is_some() {
            return Err(
                "an emitting material cannot take an `opacity` (its light would shine from the cut-out parts)".into()
            );
        }
        if r.alpha_texture.is_some() && (r.alpha_u.is_some() || r.alpha_v.is_some()) {
            return Err("`alpha_texture` is an isotropic α: give it without `alpha_u` and `alpha_v`".into());
        }
        let kind = match (r.one_sided, t) {
            (Some(true), MaterialType::Dielectric | MaterialType::RoughDielectric | MaterialType::Null) => {
                return Err(format!("a {name} material cannot be `one_sided`: light crosses it"));
            }
            (Some(true), MaterialType::Emissive) => {
                return Err("an emissive material cannot be `one_sided` (it does not scatter; see `two_sided`)".into());
            }
            (Some(true), _) => MaterialKind::OneSided(Box::new(kind)),
            _ => kind,
        };
        Ok(MaterialDef { kind, emission, normal, opacity, roughness: r.alpha_texture })
    }
}

impl RawMaterial {
    /// `normal_map` (with an optional `normal_strength`) or `bump_map` (with an optional
    /// `bump_scale`, default 1), and `normal_shadowing` (default true).
    fn normal_def(&self) -> Result<Option<NormalPerturbationDef>, String> {
        let map = match (&self.normal_map, &self.bump_map) {
            (Some(_), Some(_)) => return Err("give either `normal_map` or `bump_map`, not both".into()),
            (Some(texture), None) => {
                if self.bump_scale.is_some() {
                    return Err("`bump_scale` goes with `bump_map`, not `normal_map`".into());
                }
                NormalDef::Map { texture: texture.clone(), strength: self.normal_strength.unwrap_or(Num::from(1.0)) }
            }
            (None, Some(height)) => {
                if self.normal_strength.is_some() {
                    return Err("`normal_strength` goes with `normal_map`, not `bump_map`".into());
                }
                NormalDef::Bump { height: height.clone(), scale: self.bump_scale.unwrap_or(Num::from(1.0)) }
            }
            (None, None) => {
                if let Some(f) = [
                    ("normal_strength", self.normal_strength.is_some()),
                    ("bump_scale", self.bump_scale.is_some()),
                    ("normal_shadowing", self.normal_shadowing.is_some()),
                ]
                .iter()
                .find(|f| f.1)
                {
                    return Err(format!("`{}` needs a `normal_map` or `bump_map`", f.0));
                }
                return Ok(None);
            }
        };
        Ok(Some(NormalPerturbationDef { map, shadowing: self.normal_shadowing.unwrap_or(true) }))
    }
}

impl From<MaterialDef> for RawMaterial {
    fn from(m: MaterialDef) -> Self {
        let mut r = RawMaterial::default();
        let emissive = m.kind == MaterialKind::Emissive;
        let mut kind = m.kind;
        while let MaterialKind::OneSided(inner) = kind {
            r.one_sided = Some(true);
            kind = *inner;
        }
        match kind {
            MaterialKind::Diffuse { albedo } => (r.kind, r.albedo) = (Some(MaterialType::Diffuse), Some(albedo)),
            MaterialKind::Lambertian { albedo } => (r.kind, r.albedo) = (Some(MaterialType::Lambertian), Some(albedo)),
            MaterialKind::Mirror { reflectance } => {
                (r.kind, r.reflectance) = (Some(MaterialType::Mirror), Some(reflectance))
            }
            MaterialKind::Glossy { albedo, exponent } => {
                (r.kind, r.albedo, r.exponent) = (Some(MaterialType::Glossy), Some(albedo), Some(exponent))
            }
            MaterialKind::Dielectric { ior, tint } => {
                (r.kind, r.ior, r.tint) = (Some(MaterialType::Dielectric), Some(Ior(ior)), Some(tint))
            }
            MaterialKind::ThinDielectric { ior, tint } => {
                (r.kind, r.ior, r.tint) = (Some(MaterialType::ThinDielectric), Some(Ior(ior)), Some(tint))
            }
            MaterialKind::Emissive => r.kind = Some(MaterialType::Emissive),
            MaterialKind::Null => r.kind = Some(MaterialType::Null),
            MaterialKind::Conductor { metal, reflectance } => {
                (r.kind, r.reflectance) = (Some(MaterialType::Conductor), Some(reflectance));
                r.set_metal(metal);
            }
            MaterialKind::RoughConductor { metal, reflectance, roughness } => {
                (r.kind, r.reflectance) = (Some(MaterialType::RoughConductor), Some(reflectance));
                r.set_metal(metal);
                r.set_roughness(roughness);
            }
            MaterialKind::RoughDielectric { ior, tint, roughness } => {
                (r.kind, r.ior, r.tint) = (Some(MaterialType::RoughDielectric), Some(Ior(ior)), Some(tint));
                r.set_roughness(roughness);
            }
            MaterialKind::Plastic { albedo, specular, ior, nonlinear } => {
                r.kind = Some(MaterialType::Plastic);
                (r.albedo, r.specular, r.ior, r.nonlinear) =
                    (Some(albedo), Some(specular), Some(Ior(ior)), Some(nonlinear));
            }
            MaterialKind::RoughPlastic { albedo, specular, ior, nonlinear, roughness } => {
                r.kind = Some(MaterialType::RoughPlastic);
                (r.albedo, r.specular, r.ior, r.nonlinear) =
                    (Some(albedo), Some(specular), Some(Ior(ior)), Some(nonlinear));
                r.set_roughness(roughness);
            }
            MaterialKind::Blend { weight, bsdfs } => {
                (r.kind, r.weight, r.bsdfs) = (Some(MaterialType::Blend), Some(weight), Some(bsdfs.to_vec()));
            }
            // Unwrapped above.
            MaterialKind::OneSided(_) => {}
        }
        if let Some(e) = m.emission {
            if emissive {
                r.radiance = Some(e.radiance);
            } else {
                r.emission = Some(e.radiance);
            }
            r.two_sided = e.two_sided.then_some(true);
            r.emission_texture = e.texture;
        }
        if let Some(n) = m.normal {
            match n.map {
                NormalDef::Map { texture, strength } => {
                    r.normal_map = Some(texture);
                    r.normal_strength = (strength.get() != 1.0).then_some(strength);
                }
                NormalDef::Bump { height, scale } => (r.bump_map, r.bump_scale) = (Some(height), Some(scale)),
            }
            r.normal_shadowing = (!n.shadowing).then_some(false);
        }
        if let Some(o) = m.opacity {
            (r.opacity, r.alpha_cutoff) = (Some(o.texture), o.cutoff);
        }
        r.alpha_texture = m.roughness;
        r
    }
}

impl RawMaterial {
    fn set_metal(&mut self, m: MetalDef) {
        match m {
            MetalDef::Named(name) => self.metal = Some(name),
            MetalDef::Custom { eta, k } => (self.eta, self.k) = (Some(eta), Some(k)),
        }
    }

    fn set_roughness(&mut self, r: RoughnessDef) {
        self.distribution = Some(DistributionName(r.distribution));
        if r.alpha_u == r.alpha_v {
            self.alpha = Some(r.alpha_u);
        } else {
            (self.alpha_u, self.alpha_v) = (Some(r.alpha_u), Some(r.alpha_v));
        }
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
        assert_eq!(glass.kind, MaterialKind::Dielectric { ior: Num::from(1.5), tint: Colour::grey(1.0) });
        let light = parse("type = \"emissive\"\nradiance = 4").unwrap();
        let four = Triple::Splat(Num::from(4.0));
        assert_eq!(light.emission, Some(EmissionDef { radiance: four, two_sided: false, texture: None }));
    }

    #[test]
    fn wrong_parameters_are_named() {
        assert!(parse("type = \"mirror\"\nalbedo = 1").unwrap_err().contains("`albedo` is not a parameter"));
        assert!(parse("type = \"lambertian\"").unwrap_err().contains("needs `albedo`"));
        assert!(parse("type = \"lambertian\"\nalbedo = 1\ntwo_sided = true").unwrap_err().contains("two_sided"));
        assert!(parse("type = \"velvet\"").unwrap_err().contains("unknown variant"));
        assert!(parse("type = \"rough_plastic\"\nalpha_u = 0.1\nalpha_v = 0.2")
            .unwrap_err()
            .contains("not a parameter"));
        assert!(parse("type = \"rough_conductor\"\nalpha = 0.1\nalpha_u = 0.2").unwrap_err().contains("not both"));
        assert!(parse("type = \"conductor\"\neta = 0.2").unwrap_err().contains("go together"));
        assert!(parse("type = \"conductor\"\nmetal = \"gold\"").unwrap_err().contains("unknown metal"));
        assert!(parse("type = \"plastic\"\nior = \"jelly\"").unwrap_err().contains("unknown index"));
        assert!(parse("type = \"mirror\"\ncolour = 1").unwrap_err().contains("unknown field"));
    }

    #[test]
    fn microfacet_materials_take_defaults_and_round_trip() {
        let gold = parse("type = \"rough_conductor\"\nmetal = \"Au\"\ndistribution = \"ggx\"\nalpha = 0.2").unwrap();
        let MaterialKind::RoughConductor { metal, roughness, .. } = gold.kind else { panic!("{gold:?}") };
        assert_eq!(metal, MetalDef::Named(MetalName("Au")));
        assert_eq!((roughness.distribution, roughness.alpha_u.get()), (MicrofacetKind::Ggx, 0.2));
        let plastic = parse("type = \"plastic\"\nior = \"water\"").unwrap();
        let MaterialKind::Plastic { ior, albedo, nonlinear, .. } = plastic.kind else { panic!("{plastic:?}") };
        assert!((ior.get() - 1.333).abs() < 1e-6 && albedo == Colour::grey(0.5) && !nonlinear);
        for text in [
            "type = \"rough_dielectric\"\nalpha_u = 0.1\nalpha_v = 0.3",
            "type = \"conductor\"\neta = [0.2, 0.4, 1.4]\nk = 3",
            "type = \"rough_plastic\"\nalbedo = [0.1, 0.2, 0.3]\nnonlinear = true\ndistribution = \"ggx\"",
        ] {
            let m = parse(text).unwrap();
            let back: MaterialDef = toml::from_str(&toml::to_string(&m).unwrap()).unwrap();
            assert_eq!(m, back, "{text}");
        }
    }

    #[test]
    fn normal_and_bump_maps_parse_check_and_round_trip() {
        let m = parse("type = \"diffuse\"\nalbedo = 0.5\nnormal_map = { type = \"bitmap\", filename = \"n.png\" }")
            .unwrap();
        let n = m.normal.clone().unwrap();
        assert!(n.shadowing && matches!(n.map, NormalDef::Map { strength, .. } if strength.get() == 1.0));
        let bump = parse(
            "type = \"rough_plastic\"\nbump_map = { type = \"bitmap\", filename = \"h.png\" }\nbump_scale = 0.1\n\
             normal_shadowing = false",
        )
        .unwrap();
        for m in [m, bump] {
            let back: MaterialDef = toml::from_str(&toml::to_string(&m).unwrap()).unwrap();
            assert_eq!(m, back);
        }
        let bad = |s: &str| parse(&format!("type = \"diffuse\"\nalbedo = 0.5\n{s}")).unwrap_err();
        assert!(bad("normal_map = 0.5\nbump_map = 0.5").contains("not both"));
        assert!(bad("bump_scale = 2").contains("needs a `normal_map` or `bump_map`"));
        assert!(bad("normal_map = 0.5\nbump_scale = 2").contains("goes with `bump_map`"));
        assert!(bad("bump_map = 0.5\nnormal_strength = 2").contains("goes with `normal_map`"));
        assert!(parse("type = \"emissive\"\nradiance = 1\nbump_map = 0.5").unwrap_err().contains("cannot take"));
    }

    #[test]
    fn opacity_parses_checks_and_round_trips() {
        let m = parse("type = \"diffuse\"\nalbedo = 0.5\nopacity = { type = \"bitmap\", filename = \"a.png\" }\nalpha_cutoff = 0.5")
            .unwrap();
        assert_eq!(m.opacity.as_ref().and_then(|o| o.cutoff).map(|c| c.get()), Some(0.5));
        let back: MaterialDef = toml::from_str(&toml::to_string(&m).unwrap()).unwrap();
        assert_eq!(m, back);
        assert!(parse("type = \"diffuse\"\nalbedo = 0.5\nalpha_cutoff = 0.5")
            .unwrap_err()
            .contains("needs an `opacity`"));
        assert!(parse("type = \"emissive\"\nradiance = 1\nopacity = 0.5").unwrap_err().contains("cannot take"));
    }

    #[test]
    fn one_sided_parses_checks_and_round_trips() {
        let m = parse("type = \"lambertian\"\nalbedo = 0.5\none_sided = true").unwrap();
        assert_eq!(m.kind.sides(), (&MaterialKind::Lambertian { albedo: Colour::grey(0.5) }, true));
        let text = toml::to_string(&m).unwrap();
        assert!(text.contains("one_sided = true"), "{text}");
        let back: MaterialDef = toml::from_str(&text).unwrap();
        assert_eq!(m, back);
        // The default, and `false`, shade both faces.
        for t in ["", "\none_sided = false"] {
            assert!(!parse(&format!("type = \"lambertian\"\nalbedo = 0.5{t}")).unwrap().kind.sides().1);
        }
        assert!(parse("type = \"dielectric\"\none_sided = true").unwrap_err().contains("light crosses it"));
        assert!(parse("type = \"emissive\"\nradiance = 1\none_sided = true").unwrap_err().contains("two_sided"));
    }

    #[test]
    fn alpha_textures_parse_check_and_round_trip() {
        let text =
            "type = \"rough_conductor\"\nalpha_texture = { type = \"bitmap\", filename = \"r.png\", raw = true }";
        let m = parse(text).unwrap();
        assert!(matches!(m.roughness, Some(Colour::Texture(_))));
        let back: MaterialDef = toml::from_str(&toml::to_string(&m).unwrap()).unwrap();
        assert_eq!(m, back);
        let plastic = parse("type = \"rough_plastic\"\nalpha_texture = { type = \"bitmap\", filename = \"r.png\" }");
        assert!(matches!(plastic.unwrap().roughness, Some(Colour::Texture(_))));
        assert!(parse("type = \"plastic\"\nalpha_texture = 0.2").unwrap_err().contains("not a parameter"));
        assert!(parse("type = \"rough_dielectric\"\nalpha_u = 0.1\nalpha_v = 0.2\nalpha_texture = 0.2")
            .unwrap_err()
            .contains("isotropic"));
    }

    #[test]
    fn emission_on_a_scattering_material_round_trips() {
        let m = parse("type = \"diffuse\"\nalbedo = 0.5\nemission = [1, 2, 3]\ntwo_sided = true").unwrap();
        let back: MaterialDef = toml::from_str(&toml::to_string(&m).unwrap()).unwrap();
        assert_eq!(m, back);
    }

    #[test]
    fn emission_textures_need_an_emitter_and_a_texture_table() {
        let lamp = "type = \"emissive\"\nradiance = 2\nemission_texture = { type = \"bitmap\", filename = \"e.png\" }";
        let m = parse(lamp).unwrap();
        assert!(matches!(m.emission.as_ref().and_then(|e| e.texture.as_ref()), Some(Colour::Texture(_))));
        let back: MaterialDef = toml::from_str(&toml::to_string(&m).unwrap()).unwrap();
        assert_eq!(m, back);
        let e = parse(
            "type = \"lambertian\"\nalbedo = 0.5\nemission_texture = { type = \"bitmap\", filename = \"e.png\" }",
        )
        .unwrap_err();
        assert!(e.contains("only to emitting materials"), "{e}");
        let e = parse("type = \"emissive\"\nradiance = 2\nemission_texture = 0.5").unwrap_err();
        assert!(e.contains("must be a texture table"), "{e}");
    }
}
