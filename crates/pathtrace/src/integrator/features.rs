//! The feature sample of each camera path (`film::FeatureSample`): depth at the first hit,
//! albedo and shading normal at the first non-specular hit, following mirror and glass chains as
//! Intel Open Image Denoise's documentation recommends for its auxiliary images (a mirror then
//! shows the mirrored object, tinted by the mirror's reflectance, instead of a flat colour the
//! denoiser would smear the reflection into).
//!
//! A path that escapes to an environment light records the environment's radiance in that
//! direction, clamped to [0, 1] per channel (times the tint of the specular chain it followed),
//! as its albedo: what the camera sees there is the environment, and its colour is the only
//! "texture" the denoiser can keep apart from noise (OIDN's albedo input is in [0, 1], as its
//! Python binding pyoidn 2.5.1 documents). A zero albedo there, as before, told the denoiser the
//! sky was black. Without an environment the provisional sample stays (zero for a camera ray
//! that escapes; the last specular surface's albedo after a chain).
//!
//! Runs only for lanes whose feature sample is still pending, which no lane is when the render
//! records no features: the estimator pays one mask test per vertex for this.

use super::lanes::{Paths, Surfaces};
use super::regenerate::LaneJob;
use crate::material::{Material, Scattering};
use crate::math::{Frame, Rgb, Vec2, Vec3};
use crate::scene::Interaction;
use crate::wide::simd::{Ms, Vec3s};

/// Directions per axis of the grid that estimates a hit's albedo (GRID² BSDF samples).
const ALBEDO_GRID: u32 = 4;

/// Updates the pending feature samples of the lanes of `paths` that hit something in `s`.
#[inline(never)]
pub(super) fn record_features<const N: usize>(job: &LaneJob, paths: &mut Paths<N>, s: &Surfaces<N>, wo: &Vec3s<N>) {
    let scene = job.scene;
    let materials = scene.materials();
    if let Some(env) = scene.lights.environment() {
        let escaped: Ms<N> = paths.feature_pending & paths.active & !s.hit;
        for i in escaped.lanes() {
            let seen = env.radiance(paths.dir.lane(i)).map(|c| c.clamp(0.0, 1.0));
            paths.feature[i].albedo = paths.feature_tint[i] * seen;
        }
    }
    let hit: Ms<N> = paths.feature_pending & paths.active & s.hit;
    for i in hit.lanes() {
        let surface = s.surface(i);
        if paths.segments[i] == 1 {
            paths.feature[i].depth = (surface.p - paths.origin.lane(i)).length();
        }
        let wo = wo.lane(i);
        // Face the viewer, as the estimator does for two-sided materials.
        let n = if surface.n_geometric.dot(wo) < 0.0 { -surface.n_shading } else { surface.n_shading };
        let class = &job.lanes.classes[s.material[i] as usize];
        let it = Interaction {
            surface,
            material: &materials[s.material[i] as usize],
            material_id: s.material[i],
            light: s.light[i],
        };
        let material = if class.textured { scene.textured_material(&it) } else { *it.material };
        let albedo = match material {
            // A Lambertian surface's directional albedo is its albedo (the common case: no
            // BSDF sampling needed).
            Material::Lambertian(l) => l.albedo,
            // A blend: its mixture's own sampling (which mixes the two models' weights).
            Material::Blend(b) => {
                directional_albedo(&scene.mixture(&b, &it.surface), Frame::from_normal(n).to_local(wo))
            }
            _ => directional_albedo(&material, Frame::from_normal(n).to_local(wo)),
        };
        let tint = paths.feature_tint[i];
        let feature = &mut paths.feature[i];
        feature.normal = n;
        if material.is_delta() {
            // Provisional (kept if the path ends here or escapes): the specular surface itself.
            // The search goes on through the reflection or refraction.
            paths.feature_tint[i] = tint * albedo;
            feature.albedo = tint * albedo;
        } else {
            feature.albedo = tint * albedo;
            paths.feature_pending.0[i] = 0;
        }
    }
}

/// ρ(wo) = ∫ f(wo, wi)|cos θi| dwi, estimated as the mean BSDF sample weight f·|cos|/pdf over a
/// fixed stratified grid (the Monte Carlo estimator of the BSDF's own sampling routine, so it
/// serves every material, and is exact for cosine-sampled Lambertian surfaces and for mirrors).
fn directional_albedo<M: Scattering>(material: &M, wo: Vec3) -> Rgb {
    let n = ALBEDO_GRID;
    let mut sum = Rgb::BLACK;
    for j in 0..n {
        for i in 0..n {
            let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
            // The lobe choice is stratified on the flattened index so every lobe is visited.
            let u_lobe = ((j * n + i) as f32 + 0.5) / (n * n) as f32;
            if let Some(s) = material.sample(wo, u_lobe, u) {
                sum += s.weight;
            }
        }
    }
    sum * (1.0 / (n * n) as f32)
}
