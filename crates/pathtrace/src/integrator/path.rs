//! The path tracer: one loop per camera sample, in four phases per vertex — emission hit,
//! light sampling, direction sampling, Russian roulette.
//!
//! Depth counts path segments, as Mitsuba does: `max_depth = 1` shows only emitters seen
//! directly, 2 adds direct lighting, -1 is unlimited.

use super::Strategy;
use crate::material::Material;
use crate::math::{offset_ray_origin, Frame, Ray, Rgb, Vec3};
use crate::sampling::Sampler;
use crate::scene::{Primitive, Scene};

/// Settings of the path loop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathSettings {
    pub strategy: Strategy,
    /// Maximum number of path segments; negative means unlimited.
    pub max_depth: i32,
    /// Russian roulette starts once a path has this many segments (Mitsuba's default is 5).
    pub rr_depth: u32,
}

impl Default for PathSettings {
    fn default() -> Self {
        Self { strategy: Strategy::Mis, max_depth: -1, rr_depth: 5 }
    }
}

/// Ray counts, accumulated per thread and summed by the render session.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PathStats {
    pub camera_rays: u64,
    pub extension_rays: u64,
    pub shadow_rays: u64,
}

impl PathStats {
    pub fn add(&mut self, o: &PathStats) {
        self.camera_rays += o.camera_rays;
        self.extension_rays += o.extension_rays;
        self.shadow_rays += o.shadow_rays;
    }

    pub fn total_rays(&self) -> u64 {
        self.camera_rays + self.extension_rays + self.shadow_rays
    }
}

/// Where the path came from, for weighting emission found by the next hit.
#[derive(Clone, Copy)]
struct PrevVertex {
    p: Vec3,
    /// Solid-angle pdf of the direction chosen there (by the material, under MIS).
    pdf: f32,
    /// The direction came from a Dirac lobe (or the camera): emission counts in full.
    specular: bool,
}

/// Light-sampling shadow rays stop this fraction short of the light, so they do not hit it.
const SHADOW_EPSILON: f32 = 1e-4;

/// Estimates the radiance arriving along `ray` (a camera ray).
#[inline(always)]
pub fn radiance(
    scene: &Scene,
    camera_ray: Ray,
    sampler: &mut Sampler,
    settings: &PathSettings,
    stats: &mut PathStats,
) -> Rgb {
    stats.camera_rays += 1;
    let max_depth = if settings.max_depth < 0 { u32::MAX } else { settings.max_depth as u32 };
    if max_depth == 0 {
        return Rgb::BLACK;
    }
    let strategy = settings.strategy;
    let lights = &scene.lights;
    let mut l = Rgb::BLACK;
    let mut beta = Rgb::WHITE;
    let mut eta_scale = 1.0f32;
    let mut ray = camera_ray;
    let mut segments = 1u32;
    let mut prev = PrevVertex { p: ray.origin, pdf: 0.0, specular: true };
    // Asked once per path, so untextured scenes pay one register test per hit.
    let has_textures = scene.has_textures();

    loop {
        // ---- Escape: the environment (if any) is seen, then the path ends ------------------
        let Some(hit) = scene.intersect(&ray, f32::INFINITY) else {
            if let Some(env) = lights.environment() {
                let weight = if strategy.is_mis() && !prev.specular {
                    strategy.mis_weight(prev.pdf, lights.pdf_environment(ray.dir))
                } else {
                    1.0
                };
                l += beta * env.radiance(ray.dir) * weight;
            }
            break;
        };
        let it = scene.interaction(&ray, &hit);
        let p = it.surface.p;
        let wo_world = -ray.dir;

        // ---- Emission hit -------------------------------------------------------------
        if it.light != Primitive::NO_LIGHT {
            if let Some(light) = lights.get(it.light) {
                let le = light.emitted(it.surface.n_geometric, wo_world);
                if !le.is_black() {
                    let weight = if strategy.is_mis() && !prev.specular {
                        let pdf_light = lights.pdf_hit(it.light, prev.p, p, it.surface.n_geometric);
                        strategy.mis_weight(prev.pdf, pdf_light)
                    } else {
                        1.0
                    };
                    l += beta * le * weight;
                }
            }
        }
        if segments >= max_depth || it.material.is_black() {
            break;
        }

        // Textured colours at this hit (untextured materials are used as they are).
        let textured: Material;
        let material = if has_textures && scene.is_textured(&it) {
            textured = scene.textured_material(&it);
            &textured
        } else {
            it.material
        };

        // Shading frame, flipped to the viewer's side for two-sided materials.
        let mut n_g = it.surface.n_geometric;
        let mut n_s = it.surface.n_shading;
        if material.is_two_sided() && n_g.dot(wo_world) < 0.0 {
            n_g = -n_g;
            n_s = -n_s;
        }
        // Anisotropic roughness is aligned with ∂p/∂u, as in Mitsuba; isotropic models do not
        // depend on the tangent, and keep the cheaper (and historical) basis of the normal.
        let frame = if material.is_anisotropic() {
            Frame::from_normal_tangent(n_s, it.surface.tangent())
        } else {
            Frame::from_normal(n_s)
        };
        let wo = frame.to_local(wo_world);
        let delta = material.is_delta();
        let can_sample_lights = !delta && !lights.is_empty();
        // The `light` and `mixture` strategies follow the sampled direction, which point
        // lights (Dirac deltas) cannot provide: they sample the other lights only.
        let can_follow_lights = !delta && lights.has_continuous();

        // ---- Light sampling (next-event estimation, MIS only) ----------------------------
        if strategy.is_mis() && can_sample_lights {
            let u_select = sampler.next_1d();
            let u_light = sampler.next_2d();
            if let Some(ls) = lights.sample(p, u_select, u_light) {
                let wi = frame.to_local(ls.wi);
                let f = material.eval(wo, wi);
                if !ls.radiance.is_black() && !f.is_black() && same_side(n_g, wo_world, ls.wi) {
                    let origin = offset_ray_origin(p, n_g, ls.wi);
                    let (shadow, t_max) = if ls.dist.is_infinite() {
                        // The environment: unoccluded if the ray leaves the scene.
                        (Ray::new(origin, ls.wi), f32::INFINITY)
                    } else {
                        let to_light = ls.point - origin;
                        let dist = to_light.length();
                        (Ray::new(origin, to_light / dist), dist * (1.0 - SHADOW_EPSILON))
                    };
                    stats.shadow_rays += 1;
                    if !scene.occluded(&shadow, t_max) {
                        // A point light cannot be found by bsdf sampling: its sample counts in full.
                        let w = if ls.delta { 1.0 } else { strategy.mis_weight(ls.pdf, material.pdf(wo, wi)) };
                        l += beta * f * ls.radiance * (w / ls.pdf);
                    }
                }
            }
        }

        // ---- Direction sampling --------------------------------------------------------
        let u_lobe = sampler.next_1d();
        let u_dir = sampler.next_2d();
        let next = match strategy {
            // A Dirac lobe (plastic's coating) cannot be reached by light sampling alone: such
            // materials are sampled by the material under the `light` strategy.
            Strategy::Light if can_follow_lights && !material.has_delta_lobe() => {
                sample_towards_lights(scene, material, &frame, p, wo, u_lobe, u_dir)
            }
            Strategy::Mixture if can_follow_lights => sample_mixture(scene, material, &frame, p, wo, u_lobe, u_dir),
            _ => material.sample(wo, u_lobe, u_dir).map(|s| Scatter {
                wi_world: frame.to_world(s.wi),
                weight: s.weight,
                pdf: s.pdf,
                specular: s.delta,
                eta: s.eta,
            }),
        };
        let Some(next) = next else { break };
        // Reject directions on the wrong geometric side (shading normals can disagree with the
        // true surface): reflection must stay on wo's side, transmission must cross.
        let wi_local_z = frame.to_local(next.wi_world).z;
        let reflects = wi_local_z * wo.z > 0.0;
        if reflects != same_side(n_g, wo_world, next.wi_world) || next.weight.is_black() {
            break;
        }
        beta *= next.weight;
        eta_scale *= next.eta * next.eta;

        // ---- Russian roulette ------------------------------------------------------------
        // Survival probability from the throughput, with the η² of refractions undone so that
        // radiance compression inside glass does not kill paths (pbrt-v4 §13.4.3).
        if segments >= settings.rr_depth {
            let q = (beta.max_component() * eta_scale).min(0.95);
            if sampler.next_1d() >= q {
                break;
            }
            beta = beta / q;
        }

        prev = PrevVertex { p, pdf: next.pdf, specular: next.specular };
        ray = Ray::new(offset_ray_origin(p, n_g, next.wi_world), next.wi_world);
        stats.extension_rays += 1;
        segments += 1;
    }
    l
}

/// A chosen continuation direction with its throughput weight `f·|cos|/pdf`.
struct Scatter {
    wi_world: Vec3,
    weight: Rgb,
    pdf: f32,
    specular: bool,
    eta: f32,
}

fn same_side(n: Vec3, a: Vec3, b: Vec3) -> bool {
    n.dot(a) * n.dot(b) > 0.0
}

/// The `light` strategy: continue towards a light point; pdf of the direction summed over all
/// lights (point lights excepted).
fn sample_towards_lights(
    scene: &Scene,
    material: &Material,
    frame: &Frame,
    p: Vec3,
    wo: Vec3,
    u_select: f32,
    u: crate::math::Vec2,
) -> Option<Scatter> {
    let ls = scene.lights.sample_continuous(p, u_select, u)?;
    let pdf = scene.lights.pdf_direction(p, ls.wi);
    let f = material.eval(wo, frame.to_local(ls.wi));
    (pdf > 0.0).then(|| Scatter { wi_world: ls.wi, weight: f * (1.0 / pdf), pdf, specular: false, eta: 1.0 })
}

/// The `mixture` strategy: half the time towards a light, half by the material; weighted by the
/// mixture density 0.5·p_light + 0.5·p_bsdf of the chosen direction.
fn sample_mixture(
    scene: &Scene,
    material: &Material,
    frame: &Frame,
    p: Vec3,
    wo: Vec3,
    u_choice: f32,
    u: crate::math::Vec2,
) -> Option<Scatter> {
    // Reuse the one number for both the coin flip and the sub-strategy's 1D choice.
    let wi_world = if u_choice < 0.5 {
        scene.lights.sample_continuous(p, u_choice * 2.0, u)?.wi
    } else {
        let s = material.sample(wo, u_choice * 2.0 - 1.0, u)?;
        if s.delta {
            // Only the material's half of the mixture produces a Dirac lobe's direction: its
            // probability is 0.5·p_lobe, so the weight is f/(0.5·p_lobe) = 2·(f/p_lobe).
            let wi_world = frame.to_world(s.wi);
            return Some(Scatter { wi_world, weight: s.weight * 2.0, pdf: s.pdf, specular: true, eta: s.eta });
        }
        frame.to_world(s.wi)
    };
    let wi = frame.to_local(wi_world);
    let pdf = 0.5 * scene.lights.pdf_direction(p, wi_world) + 0.5 * material.pdf(wo, wi);
    let f = material.eval(wo, wi);
    (pdf > 0.0).then(|| Scatter { wi_world, weight: f * (1.0 / pdf), pdf, specular: false, eta: 1.0 })
}
