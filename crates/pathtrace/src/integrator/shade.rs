//! Shading one lane's vertex through the scene's own materials: the material at the hit
//! (textures applied), its shading frame, the shadow ray of the light sample drawn for the lane
//! group (`integrator::path`) and the continuation direction by the path's strategy.
//!
//! Every material, texture and strategy is served here, one lane at a time, by the same
//! `Material` and `LightSet` code the sampling tests check; the lane-parallel form in
//! `integrator::path` takes over the Lambertian lanes. Light samples are drawn for the whole
//! lane group before either runs (in SIMD for area lights and the environment).

use super::shading_frame::ShadingFrame;
use super::Strategy;
use crate::material::{Material, Scattering};
use crate::math::{offset_ray_origin, Frame, Rgb, Vec2, Vec3};
use crate::scene::{Interaction, Scene};
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::LaneLightSample;

/// Light-sampling shadow rays stop this fraction short of the light, so they do not hit it.
pub(crate) const SHADOW_EPSILON: f32 = 1e-4;

/// The random numbers of one vertex, in the sampler's dimension order.
#[derive(Clone, Copy)]
pub(crate) struct VertexNumbers {
    pub select: f32,
    pub light: Vec2,
    pub lobe: f32,
    pub direction: Vec2,
}

/// A shadow ray towards a light sample and what it adds if unoccluded (throughput included).
#[derive(Clone, Copy)]
pub(crate) struct ShadowRay {
    pub origin: Vec3,
    pub dir: Vec3,
    pub t_max: f32,
    pub contribution: Rgb,
}

/// A chosen continuation: the next ray and the throughput weight `f·|cos|/pdf`.
#[derive(Clone, Copy)]
pub(crate) struct Continuation {
    pub origin: Vec3,
    pub dir: Vec3,
    pub weight: Rgb,
    /// Solid-angle pdf of the direction (for MIS at the next emission hit).
    pub pdf: f32,
    pub specular: bool,
    pub eta: f32,
}

/// What one lane's vertex produced.
pub(crate) struct Shading {
    pub shadow: Option<ShadowRay>,
    pub next: Option<Continuation>,
}

/// Shades the hit `it`, seen along `-wo_world`, for a path of throughput `beta`. `light` is the
/// vertex's light sample for next-event estimation, drawn with the lane group's (`u.select`
/// and `u.light`); `None` when the vertex samples no light or the sample found none.
/// Not inlined: it holds every material, and the lane loop stays small without it.
#[inline(never)]
pub(crate) fn shade(
    scene: &Scene,
    strategy: Strategy,
    it: &Interaction,
    wo_world: Vec3,
    beta: Rgb,
    u: VertexNumbers,
    light: Option<LaneLightSample>,
) -> Shading {
    // Textured colours at this hit (untextured materials are used as they are).
    let textured: Material;
    let material = if scene.is_textured(it) {
        textured = scene.textured_material(it);
        &textured
    } else {
        it.material
    };
    match material {
        // A blend: its two models at this hit, mixed by its (textured) weight.
        Material::Blend(b) => shade_with(scene, strategy, it, &scene.mixture(b, &it.surface), wo_world, beta, u, light),
        _ => shade_with(scene, strategy, it, material, wo_world, beta, u, light),
    }
}

/// [`shade`] with the model at the hit resolved (textures applied, a blend's models mixed).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn shade_with<M: Scattering>(
    scene: &Scene,
    strategy: Strategy,
    it: &Interaction,
    material: &M,
    wo_world: Vec3,
    beta: Rgb,
    u: VertexNumbers,
    light: Option<LaneLightSample>,
) -> Shading {
    let lights = &scene.lights;
    let p = it.surface.p;

    // Shading frame, flipped to the viewer's side for two-sided materials. A one-sided one
    // reaches here only with its shading normal facing the viewer (path.rs), which is its
    // front even where the true surface faces away, as Mitsuba's cos θ_o in the shading frame.
    let mut n_g = it.surface.n_geometric;
    let mut n_s = it.surface.n_shading;
    let flipped = material.is_two_sided() && !scene.is_one_sided(it.material_id) && n_g.dot(wo_world) < 0.0;
    if flipped {
        n_g = -n_g;
        n_s = -n_s;
    }
    let frame = match scene.normal_perturbation(it.material_id) {
        Some(p) => ShadingFrame::perturbed(scene, it, p, flipped, wo_world),
        // Anisotropic roughness is aligned with ∂p/∂u, as in Mitsuba; isotropic models do not
        // depend on the tangent, and keep the cheaper basis of the normal.
        None if material.is_anisotropic() => ShadingFrame::plain(Frame::from_normal_tangent(n_s, it.surface.tangent())),
        None => ShadingFrame::plain(Frame::from_normal(n_s)),
    };
    let wo = frame.to_local(wo_world);

    // ---- Light sampling (next-event estimation, MIS only) ----------------------------
    let shadow = light.and_then(|ls| shadow_ray(strategy, material, &frame, n_g, p, wo, wo_world, beta, &ls));

    // ---- Direction sampling --------------------------------------------------------
    // The `light` and `mixture` strategies follow the sampled direction, which point lights
    // (Dirac deltas) cannot provide: they sample the other lights only.
    let can_follow_lights = !material.is_delta() && lights.has_continuous();
    let next = match strategy {
        // A Dirac lobe (plastic's coating) cannot be reached by light sampling alone: such
        // materials are sampled by the material under the `light` strategy.
        Strategy::Light if can_follow_lights && !material.has_delta_lobe() => {
            sample_towards_lights(scene, material, &frame, p, wo, u.lobe, u.direction)
        }
        Strategy::Mixture if can_follow_lights => sample_mixture(scene, material, &frame, p, wo, u.lobe, u.direction),
        _ => frame.sample(material, wo, u.lobe, u.direction).map(|(s, wi_world)| Scatter {
            wi_world,
            weight: s.weight,
            pdf: s.pdf,
            specular: s.delta,
            eta: s.eta,
        }),
    };
    // Reject directions on the wrong geometric side (shading normals can disagree with the
    // true surface): reflection must stay on wo's side, transmission must cross.
    let next = next.filter(|s| {
        sides_agree(n_g, wo_world, s.wi_world, frame.to_local(s.wi_world).z * wo.z > 0.0) && !s.weight.is_black()
    });
    let next = next.map(|s| Continuation {
        origin: offset_ray_origin(p, n_g, s.wi_world),
        dir: s.wi_world,
        weight: s.weight,
        pdf: s.pdf,
        specular: s.specular,
        eta: s.eta,
    });
    Shading { shadow, next }
}

/// The shadow ray of the light sample `ls`, weighted by MIS against the material's density.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn shadow_ray<M: Scattering>(
    strategy: Strategy,
    material: &M,
    frame: &ShadingFrame,
    n_g: Vec3,
    p: Vec3,
    wo: Vec3,
    wo_world: Vec3,
    beta: Rgb,
    ls: &LaneLightSample,
) -> Option<ShadowRay> {
    // The material's value and, for MIS against a light with a density, its own density of the
    // light's direction, in one evaluation.
    let (f, pdf_material) =
        if ls.delta { (frame.eval(material, wo, ls.wi), 0.0) } else { frame.eval_pdf(material, wo, ls.wi) };
    // The light's direction obeys the rule the material's sampled directions obey (see
    // `sides_agree_lanes`): a transmitting surface is lit through itself, or MIS would weigh
    // down the sampled paths that cross it with no light sample making up for it.
    if ls.radiance.is_black()
        || f.is_black()
        || !sides_agree(n_g, wo_world, ls.wi, frame.to_local(ls.wi).z * wo.z > 0.0)
    {
        return None;
    }
    let origin = offset_ray_origin(p, n_g, ls.wi);
    let (dir, t_max) = if ls.at_infinity {
        // The environment: unoccluded if the ray leaves the scene.
        (ls.wi, f32::INFINITY)
    } else {
        let to_light = ls.point - origin;
        let dist = to_light.length();
        (to_light / dist, dist * (1.0 - SHADOW_EPSILON))
    };
    // A point light cannot be found by material sampling: its sample counts in full.
    let w = if ls.delta { 1.0 } else { strategy.mis_weight(ls.pdf, pdf_material) };
    Some(ShadowRay { origin, dir, t_max, contribution: beta * f * ls.radiance * (w / ls.pdf) })
}

/// A chosen continuation direction with its throughput weight `f·|cos|/pdf`.
struct Scatter {
    wi_world: Vec3,
    weight: Rgb,
    pdf: f32,
    specular: bool,
    eta: f32,
}

/// [`sides_agree_lanes`] for one direction: its one-lane instance.
fn sides_agree(n_g: Vec3, wo_world: Vec3, wi_world: Vec3, reflects: bool) -> bool {
    let one = Vec3s::<1>::splat;
    sides_agree_lanes(&one(n_g), &one(wo_world), &one(wi_world), Ms::from_fn(|_| reflects)).lane(0)
}

/// Lanes where `wi_world` is on `wo_world`'s side of the true surface (normal `n_g`) exactly
/// where it `reflects` by the shading frame: a reflection must not pass through the surface, a
/// transmission must cross it (shading normals can disagree with the true surface). One rule
/// for the sampled direction and the light's, so that MIS weighs both strategies over the same
/// directions. (A function, not a closure in `material_lanes`: as a closure it was compiled out
/// of line, without the SIMD kernels' target features, and called from them.)
#[inline(always)]
pub(super) fn sides_agree_lanes<const N: usize>(
    n_g: &Vec3s<N>,
    wo_world: &Vec3s<N>,
    wi_world: &Vec3s<N>,
    reflects: Ms<N>,
) -> Ms<N> {
    let stays = (n_g.dot(wo_world) * n_g.dot(wi_world)).gt(F32s::ZERO);
    (reflects & stays) | (!reflects & !stays)
}

/// The `light` strategy: continue towards a light point; pdf of the direction summed over all
/// lights (point lights excepted).
fn sample_towards_lights<M: Scattering>(
    scene: &Scene,
    material: &M,
    frame: &ShadingFrame,
    p: Vec3,
    wo: Vec3,
    u_select: f32,
    u: Vec2,
) -> Option<Scatter> {
    let ls = scene.lights.sample_continuous(p, u_select, u)?;
    let pdf = scene.lights.pdf_direction(p, ls.wi);
    let f = frame.eval(material, wo, ls.wi);
    (pdf > 0.0).then(|| Scatter { wi_world: ls.wi, weight: f * (1.0 / pdf), pdf, specular: false, eta: 1.0 })
}

/// The `mixture` strategy: half the time towards a light, half by the material; weighted by the
/// mixture density 0.5·p_light + 0.5·p_bsdf of the chosen direction.
fn sample_mixture<M: Scattering>(
    scene: &Scene,
    material: &M,
    frame: &ShadingFrame,
    p: Vec3,
    wo: Vec3,
    u_choice: f32,
    u: Vec2,
) -> Option<Scatter> {
    // Reuse the one number for both the coin flip and the sub-strategy's 1D choice.
    let wi_world = if u_choice < 0.5 {
        scene.lights.sample_continuous(p, u_choice * 2.0, u)?.wi
    } else {
        let (s, wi_world) = frame.sample(material, wo, u_choice * 2.0 - 1.0, u)?;
        if s.delta {
            // Only the material's half of the mixture produces a Dirac lobe's direction: its
            // probability is 0.5·p_lobe, so the weight is f/(0.5·p_lobe) = 2·(f/p_lobe).
            return Some(Scatter { wi_world, weight: s.weight * 2.0, pdf: s.pdf, specular: true, eta: s.eta });
        }
        wi_world
    };
    let (f, pdf_material) = frame.eval_pdf(material, wo, wi_world);
    let pdf = 0.5 * scene.lights.pdf_direction(p, wi_world) + 0.5 * pdf_material;
    (pdf > 0.0).then(|| Scatter { wi_world, weight: f * (1.0 / pdf), pdf, specular: false, eta: 1.0 })
}
