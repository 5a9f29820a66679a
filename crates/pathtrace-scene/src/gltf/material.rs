//! glTF metallic-roughness materials as native materials.
//!
//! glTF's BRDF (glTF 2.0 specification, Appendix B) mixes a metal (Schlick Fresnel with F0 = the
//! base colour, GGX with α = roughness²) and a dielectric (a GGX specular layer of index `ior`,
//! 1.5 by default, with `KHR_materials_specular`'s factor, over a Lambertian base) by `metallic`.
//! Exact here: a dielectric with `specularFactor` 0 is pure Lambertian with the base colour.
//! Substituted, with a warning: other dielectrics become `rough_plastic` (GGX, same α and ior),
//! metals a `rough_conductor` of a perfect mirror metal tinted by the base colour (no Schlick
//! edge brightening), partial `metallic` the nearer of the two, transmission a `rough_dielectric`.
//! A base colour texture becomes an image texture times baseColorFactor (see `texture.rs`), an
//! emissive texture the
//! texture the emitted radiance is multiplied by, the metallic-roughness texture's green channel
//! (times roughnessFactor, squared after filtering) the α of the rough conductor, dielectric or
//! plastic; its blue channel (metallic, times metallicFactor) makes the material a `blend` of the
//! dielectric and the metal, texel by texel, as glTF's BRDF mixes them (see [`convert`]);
//! a normal texture a normal map (see [`normal_map`]), `alphaMode` an opacity (see
//! [`alpha_opacity`]).

use super::num;
use crate::native::model::{Colour, EmissionDef, MaterialDef, MaterialKind, MetalDef, RoughnessDef};
use crate::native::model::{MetalName, NormalDef, NormalPerturbationDef, OpacityDef, TextureDef, Triple};
use pathtrace::material::MicrofacetKind;
use std::collections::BTreeMap;

fn triple(c: [f32; 3]) -> Triple {
    if c[0] == c[1] && c[1] == c[2] {
        Triple::Splat(num(c[0]))
    } else {
        Triple::Each(c.map(num))
    }
}

/// Converts `m` (the glTF default material when `None`), named `name` in the converted file;
/// unsupported parts are reported through `warn` with the material's location. A material
/// whose metallic-roughness texture gives metallic per texel (metallicFactor > 0) becomes a
/// `blend` with weight = blue × metallicFactor of model 0, the dielectric (`NAME-dielectric`),
/// and model 1, the metal (`NAME-metal`), which are added to `models`.
pub fn convert(
    m: Option<&gltf::Material>,
    file_name: &str,
    name: &str,
    models: &mut BTreeMap<String, MaterialDef>,
    warn: &mut dyn FnMut(String),
) -> MaterialDef {
    let at =
        m.and_then(|m| m.index()).map_or_else(|| "the default material".to_string(), |i| format!("materials[{i}]"));
    let mut w = |msg: &str| warn(format!("{at}: {msg}"));
    let pbr = m.map(|m| m.pbr_metallic_roughness());
    let base_factor = pbr.as_ref().map_or([1.0; 4], |p| p.base_color_factor());
    let metallic = pbr.as_ref().map_or(1.0, |p| p.metallic_factor());
    let roughness = pbr.as_ref().map_or(1.0, |p| p.roughness_factor());
    let metal_rough = pbr.as_ref().and_then(|p| p.metallic_roughness_texture());
    // Metallic is the blue channel times metallicFactor (a weight, not squared).
    let metallic_texture = metal_rough.as_ref().filter(|_| metallic > 0.0).and_then(|info| {
        match super::texture::channel_texture(info, file_name, 2, metallic, false) {
            Ok(t) => Some(Colour::Texture(t)),
            Err(e) => {
                w(&format!("metallic-roughness texture: {e}: using metallicFactor"));
                None
            }
        }
    });
    let roughness_texture = metal_rough.and_then(|info| {
        // Roughness is the green channel times roughnessFactor; α is its square.
        match super::texture::channel_texture(&info, file_name, 1, roughness, true) {
            Ok(t) => Some(Colour::Texture(t)),
            Err(e) => {
                w(&format!("metallic-roughness texture: {e}: using roughnessFactor"));
                None
            }
        }
    });
    let factor = [base_factor[0], base_factor[1], base_factor[2]];
    // glTF 2.0 §3.9.2: the base colour is baseColorFactor × the (sRGB-decoded) texture.
    let base = match pbr.as_ref().and_then(|p| p.base_color_texture()) {
        Some(info) => match super::texture::colour_texture(&info, file_name, triple(factor)) {
            Ok(t) => Colour::Texture(t),
            Err(e) => {
                w(&format!("base colour texture: {e}: using baseColorFactor"));
                Colour::Constant(triple(factor))
            }
        },
        None => Colour::Constant(triple(factor)),
    };
    let ior = m.and_then(|m| m.ior()).unwrap_or(1.5);
    let specular = m.and_then(|m| m.specular()).map_or(1.0, |s| s.specular_factor());
    let transmission = m.and_then(|m| m.transmission()).map_or(0.0, |t| t.transmission_factor());
    let alpha = num(roughness * roughness);
    let ggx = RoughnessDef { distribution: MicrofacetKind::Ggx, alpha_u: alpha, alpha_v: alpha };
    // glTF's dielectric: exactly Lambertian without a specular layer, else the rough plastic
    // approximation (with the roughness texture, if any).
    let dielectric = |w: &mut dyn FnMut(&str)| {
        if specular == 0.0 {
            (MaterialKind::Lambertian { albedo: base.clone() }, None)
        } else {
            w("the dielectric BRDF is approximated by `rough_plastic` (GGX coating over the base colour)");
            let spec = Colour::Constant(Triple::Splat(num(specular)));
            let albedo = base.clone();
            let kind =
                MaterialKind::RoughPlastic { albedo, specular: spec, ior: num(ior), nonlinear: false, roughness: ggx };
            (kind, roughness_texture.clone())
        }
    };
    let metal = |w: &mut dyn FnMut(&str)| {
        w("the metal BRDF is approximated by `rough_conductor` (a perfect mirror metal tinted by the base colour)");
        let none = MetalDef::Named(MetalName("none"));
        MaterialKind::RoughConductor { metal: none, reflectance: base.clone(), roughness: ggx }
    };
    // Only the microfacet models take a roughness texture.
    let mut textured_alpha = None;
    let kind = if transmission > 0.0 && metallic < 0.5 {
        if transmission < 1.0 {
            w("transmissionFactor below 1 is rendered fully transmissive");
        }
        if metallic_texture.is_some() {
            w("the metallic channel is not read on a transmissive material");
        }
        w("KHR_materials_transmission is approximated by rough glass (`rough_dielectric`)");
        textured_alpha = roughness_texture.clone();
        MaterialKind::RoughDielectric { ior: num(ior), tint: base.clone(), roughness: ggx }
    } else if let Some(weight) = metallic_texture {
        // glTF 2.0 Appendix B: f = mix(dielectric, metal, metallic), per texel.
        let (kind, alpha) = dielectric(&mut w);
        let dielectric = MaterialDef { roughness: alpha, ..MaterialDef::plain(kind) };
        let metal = MaterialDef { roughness: roughness_texture.clone(), ..MaterialDef::plain(metal(&mut w)) };
        let names = [format!("{name}-dielectric"), format!("{name}-metal")];
        models.insert(names[0].clone(), dielectric);
        models.insert(names[1].clone(), metal);
        MaterialKind::Blend { weight, bsdfs: names }
    } else if metallic < 0.5 {
        if metallic > 0.0 {
            w("metallic between 0 and 1 is rendered as a dielectric");
        }
        let (kind, alpha) = dielectric(&mut w);
        textured_alpha = alpha;
        kind
    } else {
        if metallic < 1.0 {
            w("metallic between 0 and 1 is rendered as a metal");
        }
        textured_alpha = roughness_texture.clone();
        metal(&mut w)
    };
    let strength = m.and_then(|m| m.emissive_strength()).unwrap_or(1.0);
    let e = m.map_or([0.0; 3], |m| m.emissive_factor()).map(|c| c * strength);
    let emission = (e.iter().any(|&c| c > 0.0)).then(|| EmissionDef {
        radiance: triple(e),
        two_sided: m.is_some_and(|m| m.double_sided()),
        texture: m.and_then(|m| emissive_texture(m, file_name, &mut w)),
    });
    let normal = m.and_then(|m| m.normal_texture()).and_then(|n| normal_map(&n, file_name, &mut w));
    let mut opacity = m.and_then(|m| alpha_opacity(m, base_factor[3], file_name));
    if opacity.is_some() && emission.is_some() {
        w("an emissive material cannot be cut out: alphaMode ignored");
        opacity = None;
    }
    MaterialDef { kind, emission, normal, opacity, roughness: textured_alpha }
}

/// `emissiveTexture` (sRGB-encoded, glTF 2.0 §3.9.3) as the texture the emitted radiance
/// (`emissiveFactor` × `emissive_strength`) is multiplied by.
fn emissive_texture(m: &gltf::Material, file_name: &str, w: &mut dyn FnMut(&str)) -> Option<Colour> {
    let info = m.emissive_texture()?;
    match super::texture::colour_texture(&info, file_name, Triple::ONE) {
        Ok(t) => Some(Colour::Texture(t)),
        Err(e) => {
            w(&format!("emissive texture: {e}: using emissiveFactor alone"));
            None
        }
    }
}

/// `alphaMode` `MASK` (opaque where alpha ≥ `alphaCutoff`, default 0.5) or `BLEND` (alpha as
/// the opacity: the surface is there with that probability, which is how a path tracer sees a
/// blended surface) as a native opacity: the base colour texture's alpha channel times
/// `baseColorFactor`'s alpha, or that alpha alone without a texture (glTF 2.0 §3.9.2; MASK
/// compares the product with the cutoff, as the specification's alpha coverage says).
fn alpha_opacity(m: &gltf::Material, factor_alpha: f32, file_name: &str) -> Option<OpacityDef> {
    let cutoff = match m.alpha_mode() {
        gltf::material::AlphaMode::Opaque => return None,
        gltf::material::AlphaMode::Mask => Some(num(m.alpha_cutoff().unwrap_or(0.5))),
        gltf::material::AlphaMode::Blend => None,
    };
    let factor = Triple::Splat(num(factor_alpha));
    let texture = m.pbr_metallic_roughness().base_color_texture().and_then(|info| {
        super::texture::colour_texture(&info, file_name, factor).ok().map(|t| match t {
            TextureDef::Bitmap { filename, nearest, clamp, to_uv, factor, .. } => {
                TextureDef::Bitmap { filename, raw: true, nearest, clamp, to_uv, alpha: true, factor }
            }
            other => other,
        })
    });
    let texture = match texture {
        Some(t) => Colour::Texture(t),
        None => Colour::Constant(factor),
    };
    Some(OpacityDef { texture, cutoff })
}

/// A `normalTexture` as a native normal map: glTF's tangent space (+x along increasing u, +y
/// towards decreasing v, the image's up) is the base frame's (s = ∂p/∂u, t = n × s) wherever the
/// texture coordinates are not mirrored; `scale` scales x and y, as the glTF specification says.
/// A mesh's TANGENT attribute, where it has one, replaces s and the sign of t (see
/// `geometry.rs` and `SurfacePoint::vertex_tangent`); glTF has no terminator shadowing.
fn normal_map(
    n: &gltf::material::NormalTexture,
    file_name: &str,
    w: &mut dyn FnMut(&str),
) -> Option<NormalPerturbationDef> {
    match super::texture::normal_texture(n, file_name) {
        Ok(t) => Some(NormalPerturbationDef {
            map: NormalDef::Map { texture: Colour::Texture(t), strength: num(n.scale()) },
            shadowing: false,
        }),
        Err(e) => {
            w(&format!("normal texture: {e}: ignored"));
            None
        }
    }
}
