//! First-hit auxiliary images (AOVs) for inspecting a scene: albedo, shading normal and depth
//! at the surface seen through each pixel centre. One deterministic ray per pixel, no light
//! transport: a debugging view (the live viewer's alternative displays), not an estimate.

use crate::camera::{Camera, CameraDesc, CameraError};
use crate::film::Image;
use crate::material::Material;
use crate::math::{Frame, Rgb, Vec2, Vec3};
use crate::scene::Scene;
use rayon::prelude::*;

/// Directions per axis of the grid that estimates a hit's albedo (GRID² BSDF samples).
const ALBEDO_GRID: u32 = 4;

/// The first-hit images of one view; pixels where the camera ray escapes are black (depth 0).
#[derive(Clone, Debug, PartialEq)]
pub struct FirstHitAovs {
    /// Directional albedo towards the camera: the fraction of light the surface scatters.
    pub albedo: Image,
    /// Shading normal facing the camera, world space, mapped from [-1, 1] to [0, 1] per axis.
    pub normal: Image,
    /// Distance along the ray to the hit (scene units), the same in all three channels.
    pub depth: Image,
}

/// What the camera ray through one pixel centre hits.
#[derive(Clone, Copy, Debug, PartialEq)]
struct HitSample {
    albedo: Rgb,
    normal: Vec3,
    depth: f32,
}

/// Renders the first-hit AOVs of `scene` seen through `camera` at `width × height`.
pub fn first_hit_aovs(
    scene: &Scene,
    camera: &CameraDesc,
    width: u32,
    height: u32,
) -> Result<FirstHitAovs, CameraError> {
    let cam = Camera::new(camera, width, height)?;
    let samples: Vec<Option<HitSample>> =
        (0..width * height).into_par_iter().map(|i| first_hit(scene, &cam, i % width, i / width)).collect();
    let image = |f: &dyn Fn(&HitSample) -> Rgb| {
        let pixels = samples.iter().map(|s| s.as_ref().map_or(Rgb::BLACK, f)).collect();
        Image { width, height, pixels }
    };
    Ok(FirstHitAovs {
        albedo: image(&|s| s.albedo),
        normal: image(&|s| {
            let n = s.normal * 0.5 + Vec3::splat(0.5);
            Rgb::new(n.x, n.y, n.z)
        }),
        depth: image(&|s| Rgb::splat(s.depth)),
    })
}

fn first_hit(scene: &Scene, cam: &Camera, x: u32, y: u32) -> Option<HitSample> {
    let ray = cam.generate_ray(x, y, Vec2::splat(0.5), Vec2::splat(0.5));
    let hit = scene.intersect(&ray, f32::INFINITY)?;
    let it = scene.interaction(&ray, &hit);
    let wo_world = -ray.dir;
    // Face the viewer, as the path tracer does for two-sided materials; shown for all here.
    let mut n = it.surface.n_shading;
    if it.surface.n_geometric.dot(wo_world) < 0.0 {
        n = -n;
    }
    let frame = Frame::from_normal(n);
    let material = if scene.is_textured(&it) { scene.textured_material(&it) } else { *it.material };
    let albedo = directional_albedo(&material, frame.to_local(wo_world));
    Some(HitSample { albedo, normal: n, depth: hit.hit.t })
}

/// ρ(wo) = ∫ f(wo, wi)|cos θi| dwi, estimated as the mean BSDF sample weight f·|cos|/pdf over a
/// fixed stratified grid (the Monte Carlo estimator of the BSDF's sampling routine itself, so it
/// works for every material and is exact for cosine-sampled Lambertian surfaces).
fn directional_albedo(material: &Material, wo: Vec3) -> Rgb {
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
