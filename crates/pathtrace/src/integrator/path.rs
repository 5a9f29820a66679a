//! The path tracer's one estimator: each vertex of a group of paths, in banner-marked phases —
//! escape, emission hit, light sampling, direction sampling, Russian roulette.
//!
//! Paths run in groups of `N` SIMD lanes (16 with AVX2, 32 with AVX-512, 8 in the portable build, 1 for the one-lane
//! instance of `Kernel::Scalar`); `integrator::regenerate` refills a lane with the tile's next
//! camera sample as soon as its path ends. Each phase runs for all live lanes: lanes whose
//! material has a lane form (Lambertian surfaces, and the models `wide::LaneForm` lists) are
//! shaded together in SIMD, every other lane by `integrator::shade` through the scene's own
//! materials; light samples are drawn for the group together. Both take the same random
//! numbers in the same order, so every sampler keeps its properties.
//!
//! Depth counts path segments, as Mitsuba does: `max_depth = 1` shows only emitters seen
//! directly, 2 adds direct lighting, -1 is unlimited.

// Lane loops index several structure-of-arrays fields with the same lane or channel number;
// iterator chains over them would hide that and vectorise no better.
#![allow(clippy::needless_range_loop)]

use super::features::record_features;
use super::lanes::{Output, Paths, Surfaces};
use super::material_lanes::{delta_lanes, material_lanes, LaneVertex};
use super::media::{leaving_medium, medium_vertex, segment_transmittance, shadow_transmittance, travel};
use super::regenerate::LaneJob;
use super::shade::{shade, Continuation, ShadowRay, VertexNumbers, SHADOW_EPSILON};
use super::shading_frame::ShadingFrame;
use super::Strategy;
use crate::material::{
    lambertian, DeltaModel, DielectricLanes, DiffuseLanes, GlossyLanes, LambertianLanes, Material, PlasticLanes,
    RoughConductorLanes, RoughDielectricLanes, RoughPlasticLanes, SmoothConductorLanes, SmoothModel,
    ThinDielectricLanes,
};
use crate::math::{offset_ray_origin_lanes, Ray, Rgb, Vec2, Vec3};
use crate::scene::{Interaction, Primitive, Scene};
use crate::texture::NormalPerturbation;
use crate::wide::simd::{made, F32s, Ms, Vec3s};
use crate::wide::warp;
use crate::wide::{LaneForm, LaneSamplers, LightSamples};

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

impl PathSettings {
    /// The segment limit as a count (`u32::MAX` for unlimited).
    pub fn max_segments(&self) -> u32 {
        if self.max_depth < 0 {
            u32::MAX
        } else {
            self.max_depth as u32
        }
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

/// The shadow rays and continuations of a vertex, per lane.
pub(super) struct Scattered<const N: usize> {
    pub shadow: Ms<N>,
    pub shadow_origin: Vec3s<N>,
    pub shadow_dir: Vec3s<N>,
    pub shadow_t_max: F32s<N>,
    /// What an unoccluded shadow ray adds (throughput included).
    pub contribution: [F32s<N>; 3],
    pub goes_on: Ms<N>,
    pub origin: Vec3s<N>,
    pub dir: Vec3s<N>,
    pub weight: [F32s<N>; 3],
    pub pdf: F32s<N>,
    pub specular: Ms<N>,
    pub eta: F32s<N>,
}

// Always inlined, as every helper of the lane loop: a helper compiled outside the loop's
// AVX2/AVX-512 context would work on the lanes with narrower instructions.
impl<const N: usize> Scattered<N> {
    #[inline(always)]
    fn none() -> Self {
        Self {
            shadow: Ms::NONE,
            shadow_origin: Vec3s::default(),
            shadow_dir: Vec3s::default(),
            shadow_t_max: F32s::ZERO,
            contribution: [F32s::ZERO; 3],
            goes_on: Ms::NONE,
            origin: Vec3s::default(),
            dir: Vec3s::default(),
            weight: [F32s::ZERO; 3],
            pdf: F32s::ZERO,
            specular: Ms::NONE,
            eta: F32s::ONE,
        }
    }

    #[inline(always)]
    fn set_shadow(&mut self, i: usize, s: &ShadowRay) {
        self.shadow.0[i] = u32::MAX;
        self.shadow_origin.set(i, s.origin);
        self.shadow_dir.set(i, s.dir);
        self.shadow_t_max.0[i] = s.t_max;
        [self.contribution[0].0[i], self.contribution[1].0[i], self.contribution[2].0[i]] = s.contribution.to_array();
    }

    #[inline(always)]
    fn set_next(&mut self, i: usize, c: &Continuation) {
        self.goes_on.0[i] = u32::MAX;
        self.origin.set(i, c.origin);
        self.dir.set(i, c.dir);
        [self.weight[0].0[i], self.weight[1].0[i], self.weight[2].0[i]] = c.weight.to_array();
        self.pdf.0[i] = c.pdf;
        self.specular.0[i] = if c.specular { u32::MAX } else { 0 };
        self.eta.0[i] = c.eta;
    }
}

/// One path vertex for every active lane. `s` holds the group's closest hits; it is kept from
/// vertex to vertex (see [`Surfaces::clear`]).
#[inline(always)]
pub(crate) fn vertex<const N: usize>(
    job: &LaneJob,
    paths: &mut Paths<N>,
    samplers: &mut LaneSamplers<N>,
    s: &mut Surfaces<N>,
    out: &mut Output,
) {
    let LaneJob { scene, lanes, .. } = *job;
    let settings = &lanes.settings;
    let strategy = settings.strategy;
    let scene_lights = &scene.lights;
    let materials = scene.materials();

    // ---- Closest hits ----------------------------------------------------------------
    s.clear();
    intersect(job, paths, s);
    let wo = paths.dir.neg();

    // ---- Media and null surfaces (volumetric scenes only) ------------------------------
    // Lanes in a medium may scatter before their hit (`scatter`: medium vertices at `s.p`);
    // null surfaces are crossed. Scenes without media never enter this branch.
    let volumetric = scene.is_volumetric();
    let scatter = if volumetric { travel(job, paths, samplers, s) } else { Ms::NONE };

    // ---- Feature samples (AOVs), only for renders that record them -----------------------
    if paths.feature_pending.any() {
        // A medium interaction is not a surface: its lanes keep waiting for one.
        let waiting = paths.feature_pending & scatter;
        paths.feature_pending = paths.feature_pending & !scatter;
        record_features(job, paths, s, &wo);
        paths.feature_pending = paths.feature_pending | waiting;
    }

    // ---- Escape: the environment (if any) is seen, then the path ends ------------------
    let escaped = paths.active & !s.hit;
    if escaped.any() {
        if let Some(env) = scene_lights.environment() {
            // The escaped lanes look the map up together; those that MIS weighs also get the
            // density (LightSet::pdf_environment's product, with the density the light samples
            // were drawn with: `EnvSampling`), from the same lookup.
            let weighed = if strategy.is_mis() { escaped & !paths.prev_specular } else { Ms::NONE };
            let (radiance, pdf) = env.lookup_lanes(&paths.dir, escaped, weighed, lanes.lights.env_sampling());
            let pick = scene_lights.environment_pmf();
            let w = strategy.mis_weight_lanes(paths.prev_pdf, pick * pdf);
            let w = F32s::select(weighed, w, F32s::ONE);
            for c in 0..3 {
                let seen = paths.beta[c] * (radiance[c] * w);
                paths.radiance[c] = F32s::select(escaped, paths.radiance[c] + seen, paths.radiance[c]);
            }
        }
    }
    paths.finish_all(escaped, out);
    let mut alive = paths.active;

    // ---- Emission hit (rare: lane by lane) ---------------------------------------------
    for i in (alive & Ms::from_fn(|i| s.light[i] != Primitive::NO_LIGHT)).lanes() {
        let Some(light) = scene_lights.get(s.light[i]) else { continue };
        let le = light.emitted(s.n_geometric.lane(i), wo.lane(i), s.uv[i]);
        if le.is_black() {
            continue;
        }
        let weight = if strategy.is_mis() && !paths.prev_specular.lane(i) {
            let pdf_light = scene_lights.pdf_hit(s.light[i], paths.prev_p.lane(i), s.p.lane(i), s.n_geometric.lane(i));
            strategy.mis_weight(paths.prev_pdf.0[i], pdf_light)
        } else {
            1.0
        };
        paths.add_weighted(i, le * weight);
    }

    // ---- Depth limit and black surfaces end the path; the rest are classified -----------
    // Which lanes sample a light, and which the lane-parallel Lambertian form serves.
    let can_sample_lights = strategy.is_mis() && !scene_lights.is_empty();
    let max_segments = settings.max_segments();
    let mut nee = Ms::<N>::NONE;
    let mut simd = Ms::<N>::NONE;
    let mut one_sided = Ms::<N>::NONE;
    let mut albedo = [F32s::<N>::ZERO; 3];
    // Lanes of materials with a lane form, by model, and their materials.
    let mut conductor = Ms::<N>::NONE;
    let mut conductors: Option<RoughConductorLanes<N>> = None;
    let mut plastic = Ms::<N>::NONE;
    let mut plastics: Option<RoughPlasticLanes<N>> = None;
    let mut smooth_plastic = Ms::<N>::NONE;
    let mut smooth_plastics: Option<PlasticLanes<N>> = None;
    let mut dielectric = Ms::<N>::NONE;
    let mut dielectrics: Option<DielectricLanes<N>> = None;
    let mut reflector = Ms::<N>::NONE;
    let mut reflectors: Option<SmoothConductorLanes<N>> = None;
    let mut uniform = Ms::<N>::NONE;
    let mut uniforms: Option<DiffuseLanes<N>> = None;
    let mut phong = Ms::<N>::NONE;
    let mut phongs: Option<GlossyLanes<N>> = None;
    let mut lambert = Ms::<N>::NONE;
    let mut lamberts: Option<LambertianLanes<N>> = None;
    let mut rough_glass = Ms::<N>::NONE;
    let mut rough_glasses: Option<RoughDielectricLanes<N>> = None;
    let mut slab = Ms::<N>::NONE;
    let mut slabs: Option<ThinDielectricLanes<N>> = None;
    // Lanes on anisotropic materials with a lane form: their frames follow the tangent.
    let mut tangent_framed = Ms::<N>::NONE;
    let mut tangent = Vec3s::<N>::default();
    // Lanes on normal- or bump-mapped materials with a lane form: their frames at the hit.
    // Both per-lane arrays are set up only at vertices that have such a lane: scenes without
    // normal maps or textured lane forms do not pay for filling them.
    let mut perturbed = Ms::<N>::NONE;
    let mut frames: Option<[Option<ShadingFrame>; N]> = None;
    // Lanes on textured materials with a lane form: their models with the textures' values at
    // the hit, kept here for the whole vertex (a rough plastic's lanes borrow its tables).
    let mut textured: Option<[Option<Material>; N]> = None;
    if lanes.textured_forms {
        for i in (alive & !scatter).lanes() {
            let class = &lanes.classes[s.material[i] as usize];
            if class.textured && class.lane_form.is_some() {
                made(&mut textured, || [None; N])[i] = Some(textured_material(scene, s, i));
            }
        }
    }
    for i in (alive & !scatter).lanes() {
        let class = &lanes.classes[s.material[i] as usize];
        // A one-sided material seen from behind (the shading normal facing away, Mitsuba's
        // cos θ_o ≤ 0 in the shading frame) scatters nothing, like a black one. Its front is
        // the shading normal's side even where the true surface faces away (smooth normals at
        // an open mesh's edge): it is shaded there, unflipped (`one_sided` lanes).
        let from_behind = class.one_sided && s.n_shading.lane(i).dot(wo.lane(i)) <= 0.0;
        one_sided.0[i] = u32::from(class.one_sided).wrapping_neg();
        if paths.segments[i] >= max_segments || class.black || from_behind {
            paths.finish(i, out);
            alive.0[i] = 0;
            continue;
        }
        if can_sample_lights && !class.delta {
            nee.0[i] = u32::MAX;
        }
        if class.simd {
            simd.0[i] = u32::MAX;
            let a = if class.textured { textured_albedo(scene, s, i) } else { class.albedo };
            [albedo[0].0[i], albedo[1].0[i], albedo[2].0[i]] = a.to_array();
        } else if let Some(form) = class.lane_form {
            let material = textured.as_ref().and_then(|t| t[i].as_ref()).unwrap_or(&materials[s.material[i] as usize]);
            // As shade.rs: the frame follows the tangent where the model at the hit (a
            // roughness texture can make it isotropic) is anisotropic.
            if class.anisotropic && material.is_anisotropic() {
                tangent_framed.0[i] = u32::MAX;
                tangent.set(i, s.surface(i).tangent());
            }
            if let Some(p) = class.perturbed.then(|| scene.normal_perturbation(s.material[i])).flatten() {
                perturbed.0[i] = u32::MAX;
                let frame = perturbed_frame(scene, s, i, material, p, wo.lane(i));
                made(&mut frames, || std::array::from_fn(|_| None))[i] = Some(frame);
            }
            match (form, material) {
                (LaneForm::RoughConductor, Material::RoughConductor(m)) => {
                    conductor.0[i] = u32::MAX;
                    made(&mut conductors, || m.lanes()).set(i, m);
                }
                (LaneForm::RoughPlastic, Material::RoughPlastic(m)) => {
                    plastic.0[i] = u32::MAX;
                    made(&mut plastics, || m.lanes()).set(i, m);
                }
                (LaneForm::Plastic, Material::Plastic(m)) => {
                    smooth_plastic.0[i] = u32::MAX;
                    made(&mut smooth_plastics, || m.lanes()).set(i, m);
                }
                (LaneForm::Dielectric, Material::Dielectric(m)) => {
                    dielectric.0[i] = u32::MAX;
                    made(&mut dielectrics, || m.lanes()).set(i, m);
                }
                (LaneForm::SmoothConductor, Material::Conductor(m)) => {
                    reflector.0[i] = u32::MAX;
                    made(&mut reflectors, SmoothConductorLanes::none).set_conductor(i, m);
                }
                (LaneForm::SmoothConductor, Material::Mirror(m)) => {
                    reflector.0[i] = u32::MAX;
                    made(&mut reflectors, SmoothConductorLanes::none).set_mirror(i, m);
                }
                (LaneForm::Diffuse, Material::Diffuse(m)) => {
                    uniform.0[i] = u32::MAX;
                    made(&mut uniforms, || m.lanes()).set(i, m);
                }
                (LaneForm::Glossy, Material::Glossy(m)) => {
                    phong.0[i] = u32::MAX;
                    made(&mut phongs, || m.lanes()).set(i, m);
                }
                (LaneForm::Lambertian, Material::Lambertian(m)) => {
                    lambert.0[i] = u32::MAX;
                    made(&mut lamberts, || m.lanes()).set(i, m);
                }
                (LaneForm::RoughDielectric, Material::RoughDielectric(m)) => {
                    rough_glass.0[i] = u32::MAX;
                    made(&mut rough_glasses, || m.lanes()).set(i, m);
                }
                (LaneForm::ThinDielectric, Material::ThinDielectric(m)) => {
                    slab.0[i] = u32::MAX;
                    made(&mut slabs, || m.lanes()).set(i, m);
                }
                // `WideScene::new` gives each form to its model only.
                _ => unreachable!("lane form {form:?} on another material"),
            }
        }
    }
    // Medium interactions: a vertex like any other (the depth limit, then light sampling).
    if scatter.any() {
        for i in (alive & scatter).lanes() {
            if paths.segments[i] >= max_segments {
                paths.finish(i, out);
                alive.0[i] = 0;
            } else if can_sample_lights {
                nee.0[i] = u32::MAX;
            }
        }
    }
    if !alive.any() {
        return;
    }

    // The vertex's random numbers, in one path's dimension order: light selection and light
    // point (light-sampling vertices only), lobe, direction; roulette's comes last.
    let u_select = samplers.next_1d(nee);
    let (ul1, ul2) = samplers.next_2d(nee);
    let u_lobe = samplers.next_1d(alive);
    let (ud1, ud2) = samplers.next_2d(alive);

    // ---- Light samples of the surface lanes, drawn together ------------------------------
    // Every light-sampling surface lane's sample, whatever its material: in SIMD when the
    // scene's lights have lane-parallel forms, else lane by lane from the light set. (Medium
    // vertices sample theirs in `medium_vertex`.)
    let surface_nee = nee & !scatter;
    let light_samples = if surface_nee.any() {
        lanes.lights.sample(scene_lights, &s.p, surface_nee, &u_select, ul1, ul2)
    } else {
        LightSamples::none()
    };

    // Lanes whose path ends at this vertex whatever they scatter: the last segment but one in a
    // scene without emitters to find (see "Last segment" below). A Lambertian group of only
    // such lanes (every vertex of a direct-lighting render) skips drawing directions.
    let ending_here = if !lanes.emitters_hittable && max_segments != u32::MAX {
        !paths.feature_pending & Ms::from_fn(|i| paths.segments[i] + 1 >= max_segments)
    } else {
        Ms::NONE
    };
    let mut sc = Scattered::none();
    let lambert_light = if simd.any() {
        lambertian_lanes(job, s, &wo, simd, one_sided, nee, ending_here, &light_samples, [&ud1, &ud2], &mut sc)
    } else {
        LambertLight::none()
    };
    let lane_forms =
        conductor | plastic | smooth_plastic | uniform | phong | lambert | rough_glass | dielectric | reflector | slab;
    if lane_forms.any() {
        let v = LaneVertex {
            strategy,
            one_sided,
            p: &s.p,
            n_geometric: &s.n_geometric,
            n_shading: &s.n_shading,
            tangent_framed,
            tangent: &tangent,
            perturbed,
            frames: frames.as_ref(),
            wo: &wo,
            beta: &paths.beta,
            nee: surface_nee,
            light: &light_samples,
            u_lobe,
            u1: ud1,
            u2: ud2,
        };
        // Each form's other lanes take the formulas without per-lane calls (`only`).
        if let Some(mut m) = conductors {
            m.distribution = m.distribution.only(conductor);
            material_lanes(&v, conductor, &m, &mut sc);
        }
        if let Some(mut m) = plastics {
            m.distribution = m.distribution.only(plastic);
            material_lanes(&v, plastic, &m, &mut sc);
        }
        if let Some(m) = uniforms {
            material_lanes(&v, uniform, &m, &mut sc);
        }
        if let Some(m) = phongs {
            material_lanes(&v, phong, &m, &mut sc);
        }
        if let Some(m) = lamberts {
            material_lanes(&v, lambert, &m, &mut sc);
        }
        if let Some(mut m) = rough_glasses {
            m.distribution = m.distribution.only(rough_glass);
            material_lanes(&v, rough_glass, &m, &mut sc);
        }
        if let Some(m) = smooth_plastics {
            material_lanes(&v, smooth_plastic, &m, &mut sc);
        }
        if let Some(m) = dielectrics {
            delta_lanes(&v, dielectric, &m, &mut sc);
        }
        if let Some(m) = reflectors {
            delta_lanes(&v, reflector, &m, &mut sc);
        }
        if let Some(m) = slabs {
            delta_lanes(&v, slab, &m, &mut sc);
        }
    }
    for i in (alive & !simd & !lane_forms & !scatter).lanes() {
        let it = Interaction {
            surface: s.surface(i),
            material: &materials[s.material[i] as usize],
            material_id: s.material[i],
            light: s.light[i],
        };
        let u = VertexNumbers {
            select: u_select.0[i],
            light: Vec2::new(ul1.0[i], ul2.0[i]),
            lobe: u_lobe.0[i],
            direction: Vec2::new(ud1.0[i], ud2.0[i]),
        };
        let light = if surface_nee.lane(i) { light_samples.lane(i) } else { None };
        let shading = shade(scene, strategy, &it, wo.lane(i), paths.beta(i), u, light);
        if let Some(shadow) = &shading.shadow {
            sc.set_shadow(i, shadow);
        }
        if let Some(next) = &shading.next {
            sc.set_next(i, next);
        }
    }
    if scatter.any() {
        for i in (alive & scatter).lanes() {
            let u = VertexNumbers {
                select: u_select.0[i],
                light: Vec2::new(ul1.0[i], ul2.0[i]),
                lobe: u_lobe.0[i],
                direction: Vec2::new(ud1.0[i], ud2.0[i]),
            };
            let (p, wo) = (s.p.lane(i), wo.lane(i));
            let shading = medium_vertex(scene, strategy, p, wo, paths.medium[i], paths.beta(i), u, nee.lane(i));
            if let Some(shadow) = &shading.shadow {
                sc.set_shadow(i, shadow);
            }
            if let Some(next) = &shading.next {
                sc.set_next(i, next);
            }
        }
    }

    // ---- Shadow rays: unoccluded light samples add their contribution -------------------
    if sc.shadow.any() {
        out.stats.shadow_rays += sc.shadow.bitmask().count_ones() as u64;
        if volumetric {
            // Through null surfaces and media, lane by lane (kept out of line, and given copies
            // of the light terms, so the surface-only path below keeps them in registers).
            let queued = ShadowQueue {
                lanes: sc.shadow,
                origin: sc.shadow_origin,
                dir: sc.shadow_dir,
                t_max: sc.shadow_t_max,
                contribution: sc.contribution,
            };
            add_transmitted_light(job, paths, s, scatter, queued, LambertLight { ..lambert_light }, albedo);
        } else {
            // Shadow rays go through the BVH together: from first hits (neighbouring points),
            // rays to one light share most node visits, and rays to several share the upper
            // levels (one group for the teapot's two point lights cost 6% less time than a group
            // per light); where they scatter (an environment's samples, points after a bounce),
            // the walk goes on ray by ray below the nodes they no longer share (see `intersect`).
            let blocked = occluded(job, &sc.shadow_origin, &sc.shadow_dir, sc.shadow, sc.shadow_t_max);
            let seen = sc.shadow & !blocked;
            // The Lambertian lanes' contributions are formed only now: their inputs were gathered
            // lane by lane, and reading them back as vectors right away stalls on store forwarding.
            let seen_lambert = seen & lambert_light.lit;
            let seen_other = seen & !lambert_light.lit;
            for c in 0..3 {
                let lambert = paths.beta[c] * albedo[c] * lambert_light.radiance[c] * lambert_light.factor;
                paths.radiance[c] = paths.radiance[c]
                    + F32s::select(seen_other, sc.contribution[c], F32s::ZERO)
                    + F32s::select(seen_lambert, lambert, F32s::ZERO);
            }
        }
    }

    // ---- Continuation: throughput × f·cos/pdf -------------------------------------------
    paths.finish_all(alive & !sc.goes_on, out);
    alive = alive & sc.goes_on;
    for c in 0..3 {
        // A Lambertian sample's weight f·cos/pdf is its albedo.
        let weight = F32s::select(simd, albedo[c], sc.weight[c]);
        paths.beta[c] = F32s::select(alive, paths.beta[c] * weight, paths.beta[c]);
    }
    paths.eta_scale = F32s::select(alive, paths.eta_scale * sc.eta * sc.eta, paths.eta_scale);

    // ---- Russian roulette ------------------------------------------------------------
    // Survival probability from the throughput, with the η² of refractions undone so that
    // radiance compression inside glass does not kill paths (pbrt-v4 §13.4.3).
    let roulette = alive & Ms::from_fn(|i| paths.segments[i] >= settings.rr_depth);
    if roulette.any() {
        let u_survive = samplers.next_1d(roulette);
        for i in roulette.lanes() {
            let q = (paths.beta(i).max_component() * paths.eta_scale.0[i]).min(0.95);
            if u_survive.0[i] >= q {
                paths.finish(i, out);
                alive.0[i] = 0;
            } else {
                for c in 0..3 {
                    paths.beta[c].0[i] /= q;
                }
            }
        }
    }

    // ---- Last segment without emitters to find -------------------------------------------
    // A path that has used its last segment but one would trace one more ray only to look
    // for emission; with no area light or environment in the scene that ray finds nothing
    // and draws no random numbers, so the path ends here with the same result (unless its
    // feature samples still wait for a non-specular hit).
    let last = alive & ending_here;
    if last.any() {
        paths.finish_all(last, out);
        alive = alive & !last;
    }

    // ---- Next segment ------------------------------------------------------------------
    // A surface that bounds media puts the path in the medium on the side it leaves by.
    if volumetric {
        enter_media(scene, paths, s, alive & !scatter, sc.dir);
    }
    paths.prev_p = Vec3s::select(alive, &s.p, &paths.prev_p);
    paths.prev_pdf = F32s::select(alive, sc.pdf, paths.prev_pdf);
    paths.prev_specular = (sc.specular & alive) | (paths.prev_specular & !alive);
    paths.origin = Vec3s::select(alive, &sc.origin, &paths.origin);
    paths.dir = Vec3s::select(alive, &sc.dir, &paths.dir);
    for i in 0..N {
        paths.segments[i] += alive.0[i] & 1;
    }
    out.stats.extension_rays += alive.bitmask().count_ones() as u64;
}

/// Copies of the queued shadow rays of a vertex (`Scattered`'s), for the media route.
struct ShadowQueue<const N: usize> {
    lanes: Ms<N>,
    origin: Vec3s<N>,
    dir: Vec3s<N>,
    t_max: F32s<N>,
    contribution: [F32s<N>; 3],
}

/// The shadow rays of a volumetric scene: each lane's light term, scaled by the transmittance
/// along its shadow ray through null surfaces and media (`integrator::media`), is added to its
/// estimate. The Lambertian lanes' terms are formed as on the surface-only path, then scaled.
///
/// Without `null` surfaces, any surface on a shadow ray blocks it, so the group's rays go through
/// the BVH together as an occlusion test (as on the surface-only path) and an unblocked ray's
/// transmittance is its one medium's over its length: the same values as the ray-by-ray
/// closest hits of [`shadow_transmittance`], which made a third of the jelly scene's time.
#[inline(never)]
fn add_transmitted_light<const N: usize>(
    job: &LaneJob,
    paths: &mut Paths<N>,
    s: &Surfaces<N>,
    scatter: Ms<N>,
    sc: ShadowQueue<N>,
    lambert_light: LambertLight<N>,
    albedo: [F32s<N>; 3],
) {
    let scene = job.scene;
    let crossing = scene.has_null_surfaces();
    let lanes = if crossing { sc.lanes } else { sc.lanes & !occluded(job, &sc.origin, &sc.dir, sc.lanes, sc.t_max) };
    for i in lanes.lanes() {
        let dir = sc.dir.lane(i);
        let medium = leaving_medium(scene, paths, s, scatter, i, dir);
        let tr = if crossing {
            shadow_transmittance(scene, sc.origin.lane(i), dir, sc.t_max.0[i], medium)
        } else {
            segment_transmittance(scene, medium, sc.t_max.0[i])
        };
        if tr.is_black() {
            continue;
        }
        for (c, t) in tr.to_array().into_iter().enumerate() {
            let term = if lambert_light.lit.lane(i) {
                paths.beta[c].0[i] * albedo[c].0[i] * lambert_light.radiance[c].0[i] * lambert_light.factor.0[i]
            } else {
                sc.contribution[c].0[i]
            };
            paths.radiance[c].0[i] += term * t;
        }
    }
}

/// The lanes of `lanes` whose surface bounds media enter the medium on the side their next
/// direction `dir` leaves by.
#[inline(never)]
fn enter_media<const N: usize>(scene: &Scene, paths: &mut Paths<N>, s: &Surfaces<N>, lanes: Ms<N>, dir: Vec3s<N>) {
    for i in lanes.lanes() {
        if let Some(b) = scene.boundary(s.material[i]) {
            paths.medium[i] = b.target(s.n_geometric.lane(i).dot(dir.lane(i)));
        }
    }
}

/// The albedo of lane `i`'s textured Lambertian surface at its hit.
#[inline(never)]
fn textured_albedo<const N: usize>(scene: &Scene, s: &Surfaces<N>, i: usize) -> Rgb {
    match textured_material(scene, s, i) {
        Material::Lambertian(l) => l.albedo,
        _ => Rgb::BLACK,
    }
}

/// The frame of lane `i`'s normal- or bump-mapped `material` at its hit, seen along `wo`
/// (`shade.rs`'s, turned over on the back of a two-sided material).
#[inline(never)]
fn perturbed_frame<const N: usize>(
    scene: &Scene,
    s: &Surfaces<N>,
    i: usize,
    material: &Material,
    p: &NormalPerturbation,
    wo: Vec3,
) -> ShadingFrame {
    let id = s.material[i];
    let it = Interaction { surface: s.surface(i), material, material_id: id, light: s.light[i] };
    let flipped = material.is_two_sided() && !scene.is_one_sided(id) && it.surface.n_geometric.dot(wo) < 0.0;
    ShadingFrame::perturbed(scene, &it, p, flipped, wo)
}

/// Lane `i`'s material with its textures evaluated at the lane's hit.
fn textured_material<const N: usize>(scene: &Scene, s: &Surfaces<N>, i: usize) -> Material {
    let id = s.material[i];
    let it = Interaction {
        surface: s.surface(i),
        material: &scene.materials()[id as usize],
        material_id: id,
        light: s.light[i],
    };
    scene.textured_material(&it)
}

/// The light samples of the Lambertian lanes whose shadow rays were queued: what an unoccluded
/// one adds is throughput × albedo × `radiance` × `factor`.
struct LambertLight<const N: usize> {
    lit: Ms<N>,
    radiance: [F32s<N>; 3],
    /// (f·cos / albedo) · w_MIS / pdf.
    factor: F32s<N>,
}

impl<const N: usize> LambertLight<N> {
    #[inline(always)]
    fn none() -> Self {
        Self { lit: Ms::NONE, radiance: [F32s::ZERO; 3], factor: F32s::ZERO }
    }
}

/// The lane-parallel form of a Lambertian vertex (f = albedo/π, cosine-weighted continuation)
/// for the lanes of `simd`, with the light samples `ls` of the lanes of `nee`. Queues the
/// shadow rays and continuations in `sc`.
/// `one_sided`: the lanes whose material is one-sided (their shading normal is not turned over).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn lambertian_lanes<const N: usize>(
    job: &LaneJob,
    s: &Surfaces<N>,
    wo: &Vec3s<N>,
    simd: Ms<N>,
    one_sided: Ms<N>,
    nee: Ms<N>,
    ending_here: Ms<N>,
    ls: &LightSamples<N>,
    [ud1, ud2]: [&F32s<N>; 2],
    sc: &mut Scattered<N>,
) -> LambertLight<N> {
    let LaneJob { lanes, .. } = *job;
    let strategy = lanes.settings.strategy;
    let zero = F32s::<N>::ZERO;
    // Face the true normal towards the viewer (the side rays must stay on). A two-sided
    // surface's shading normal turns with it; a one-sided one's already faces the viewer (the
    // classification ended the others), even where the true surface faces away.
    let back = s.n_geometric.dot(wo).lt(zero);
    let n_g = Vec3s::select(back, &s.n_geometric.neg(), &s.n_geometric);
    let n_s = Vec3s::select(back & !one_sided, &s.n_shading.neg(), &s.n_shading);
    let wo_z = n_s.dot(wo);
    // Both rays leave on n_g's side (the viewer's; checked below), so they share one origin.
    let origin = offset_ray_origin_lanes(&s.p, &n_g, wo);

    // ---- Light sampling -------------------------------------------------------------
    let mut light = LambertLight::none();
    let nee = simd & nee;
    if nee.any() {
        let cos_i = n_s.dot(&ls.wi);
        // f·cos / albedo, and the material's density of the light's direction.
        let f_cos = lambertian::cosine_over_pi(wo_z, cos_i);
        let lit = ls.valid & nee & f_cos.gt(zero) & n_g.dot(&ls.wi).gt(zero);
        if lit.any() {
            let to_light = ls.point.sub(&origin);
            let dist = to_light.length();
            let finite = ls.dist_finite;
            let dir = Vec3s::select(finite, &to_light.scale(1.0 / dist), &ls.wi);
            let t_max = F32s::select(finite, dist * (1.0 - SHADOW_EPSILON), F32s::splat(f32::INFINITY));
            // A point light cannot be found by material sampling: its sample counts in full.
            let w = F32s::select(ls.delta, F32s::ONE, strategy.mis_weight_lanes(ls.pdf, f_cos));
            sc.shadow = sc.shadow | lit;
            sc.shadow_origin = Vec3s::select(lit, &origin, &sc.shadow_origin);
            sc.shadow_dir = Vec3s::select(lit, &dir, &sc.shadow_dir);
            sc.shadow_t_max = F32s::select(lit, t_max, sc.shadow_t_max);
            light = LambertLight { lit, radiance: ls.radiance, factor: f_cos * w / ls.pdf };
        }
    }

    // ---- Direction: cosine-weighted hemisphere (weight = albedo) ------------------------
    // Not drawn when every lane ends here anyway: they end now instead of after the
    // continuation (their numbers are drawn all the same, so no sampler changes course).
    sc.specular = sc.specular & !simd;
    if !(simd & !ending_here).any() {
        sc.goes_on = sc.goes_on & !simd;
        return light;
    }
    let (local, valid, pdf) = lambertian::sample_lanes(wo_z, *ud1, *ud2);
    let wi = warp::to_world(&n_s, &local);
    // Reflection must stay on the viewer's side of the true surface (shading normals can
    // disagree with it).
    let goes_on = simd & valid & n_g.dot(&wi).gt(zero);
    sc.goes_on = (sc.goes_on & !simd) | goes_on;
    sc.origin = Vec3s::select(simd, &origin, &sc.origin);
    sc.dir = Vec3s::select(simd, &wi, &sc.dir);
    sc.pdf = F32s::select(simd, pdf, sc.pdf);
    sc.eta = F32s::select(simd, F32s::ONE, sc.eta);
    light
}

/// Closest hits of the active lanes' rays, recorded in `s` (which has none yet). Filled in
/// place, not returned: the hit callback below holds `s` by reference, so a returned value was
/// copied out afterwards (a 1 KB `memcpy` call per vertex).
#[inline(always)]
fn intersect<const N: usize>(job: &LaneJob, paths: &Paths<N>, s: &mut Surfaces<N>) {
    let active = paths.active;
    if let Some(geometry) = &job.lanes.geometry {
        let hits = geometry.intersect(&paths.origin, &paths.dir, active, F32s::<N>::splat(f32::INFINITY));
        s.p = paths.origin.add(&paths.dir.scale(hits.t));
        for i in active.lanes() {
            if hits.polygon[i] != u32::MAX {
                let (n, material, light) = geometry.polygon(hits.polygon[i]);
                s.hit.0[i] = u32::MAX;
                s.n_geometric.set(i, n);
                s.material[i] = material;
                s.light[i] = light;
            }
        }
        // Spheres' points and normals (kept out of the polygon-only loop: the Cornell box's
        // lanes would pay for the stores).
        if geometry.has_spheres() {
            for i in (active & s.hit).lanes() {
                if let Some((p, n)) = geometry.sphere_hit(hits.polygon[i], s.p.lane(i)) {
                    s.p.set(i, p);
                    s.n_geometric.set(i, n);
                }
            }
        }
        s.n_shading = s.n_geometric;
        // Triangles of smooth-shaded meshes interpolate their vertex normals, normalised
        // together as the BVH's mesh hits are below.
        if geometry.has_corner_normals() {
            let mut smooth = 0u32;
            for i in (active & s.hit).lanes() {
                if let Some(n) = geometry.interpolated_normal(hits.polygon[i], s.p.lane(i)) {
                    s.n_shading.set(i, n);
                    smooth |= 1 << i;
                }
            }
            if smooth != 0 {
                s.normalise(Ms::from_fn(|i| smooth >> i & 1 != 0));
            }
        }
        return;
    }
    // Larger scenes: the BVH, walked by the group's rays together (`Bvh::intersect_lanes`).
    // Camera rays (neighbouring samples of one or a few pixels) share most node visits. Rays
    // that scatter after a bounce share fewer, but the group walk costs them little: those that
    // miss the scene's box (an environment's rays) stop at one slab test for the whole group,
    // and a node reached by fewer than three rays is finished ray by ray, as alone. Measured
    // against bounce rays walking alone from the root (with the shadow rays after a bounce also
    // grouped, in `occluded`): copper 0.91×, bunny 0.93×, mesh-1m 0.97× the time
    // (docs/benchmarks.md, "Bounce rays in the group walk").
    // Scenes with cut-outs trace every ray alone, passing the cut-out surfaces.
    let group = if job.scene.has_cutouts() { Ms::NONE } else { active };
    // The hit callback is inlined by force: a closure does not inherit the kernel's target
    // features, and left to itself LLVM compiled it out of line for baseline x86-64 (the hit
    // record, `Scene::interaction`: 9% of the teapot's profile as its own symbol, 3% of the
    // bunny's), with the record passed through memory.
    // Mesh triangles' hits are recorded with their normals as the triangle makes them, and the
    // group's are normalised together afterwards: lane by lane, each hit's two square roots and
    // divisions were a chain the loop waited on (zoomed teapot 0.925× the time, bunny 0.977×;
    // docs/benchmarks.md, "A group's mesh normals normalised together").
    let mut unnormalised = 0u32;
    let mut last = None;
    job.scene.intersect_lanes(
        &paths.origin,
        &paths.dir,
        group,
        f32::INFINITY,
        #[inline(always)]
        |i, hit| {
            let ray = Ray::new(paths.origin.lane(i), paths.dir.lane(i));
            let (it, normalised) = job.scene.interaction_unless_mesh_normals_reusing(&ray, &hit, &mut last);
            s.set_hit(i, &it);
            unnormalised |= u32::from(!normalised) << i;
        },
    );
    if unnormalised != 0 {
        s.normalise(Ms::from_fn(|i| unnormalised >> i & 1 != 0));
    }
    for i in (active & !group).lanes() {
        let ray = Ray::new(paths.origin.lane(i), paths.dir.lane(i));
        if let Some((ray, hit)) = job.scene.intersect_opaque(&ray) {
            s.set_hit(i, &job.scene.interaction(&ray, &hit));
        }
    }
}

/// Lanes of `active` whose shadow ray is blocked before `t_max`, traced through the BVH as a
/// group (ray by ray in scenes with cut-outs).
#[inline(always)]
fn occluded<const N: usize>(job: &LaneJob, origin: &Vec3s<N>, dir: &Vec3s<N>, active: Ms<N>, t_max: F32s<N>) -> Ms<N> {
    if let Some(geometry) = &job.lanes.geometry {
        return geometry.occluded(origin, dir, active, t_max);
    }
    // Cut-outs are passed ray by ray.
    let group = if job.scene.has_cutouts() { Ms::NONE } else { active };
    let mut blocked = job.scene.occluded_lanes(origin, dir, group, t_max);
    for i in (active & !group).lanes() {
        if job.scene.occluded_opaque(&Ray::new(origin.lane(i), dir.lane(i)), t_max.0[i]) {
            blocked.0[i] = u32::MAX;
        }
    }
    blocked
}
