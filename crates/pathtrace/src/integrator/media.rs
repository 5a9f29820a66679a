//! The estimator's media route (Mitsuba 3's `volpath` semantics, pbrt-v4 §14.2): only scenes
//! with participating media or index-matched (`null`) surfaces take it (`Scene::is_volumetric`),
//! so every other scene keeps the plain surface path.
//!
//! - [`travel`]: after the closest hits, each lane inside a medium samples a free-flight
//!   distance up to its hit. In chromatic media the path follows one channel's density (the
//!   "hero" channel, drawn uniformly at its first medium event, as Mitsuba 3 draws one per
//!   path) and is weighted by the average over the channels of the whole path's density
//!   (one-sample MIS over channels at the level of the path, pbrt-v4 §14.2.2's r_u): the weight
//!   of every channel then stays below 3 however many events the path has, where weighting
//!   each event on its own multiplies such bounds. A lane that scatters
//!   becomes a medium vertex at that point; a lane whose ray reaches a `null` surface crosses it
//!   (its medium changes, its depth does not, as Mitsuba does not count null interactions) and
//!   travels on, until it scatters, reaches a real surface or leaves the scene.
//! - [`medium_vertex`]: a medium interaction shaded like a surface: a light sample weighted by
//!   the phase function (MIS against phase sampling, as for a BSDF) and a phase-sampled
//!   direction of weight 1 (the phase function is sampled exactly).
//! - [`shadow_transmittance`]: a shadow ray through null surfaces and media; each medium's
//!   segment multiplies by its exact Beer–Lambert transmittance (Mitsuba estimates it by ratio
//!   tracking; for homogeneous media the exact value has the same mean and no variance).

use super::lanes::{Paths, Surfaces};
use super::regenerate::LaneJob;
use super::shade::{Continuation, Shading, ShadowRay, VertexNumbers, SHADOW_EPSILON};
use super::Strategy;
use crate::math::{offset_ray_origin, Ray, Rgb, Vec3};
use crate::medium::MediumId;
use crate::scene::{Primitive, Scene};
use crate::wide::simd::{F32s, Ms};
use crate::wide::LaneSamplers;

/// Null surfaces a ray may cross before it is given up (a path trapped between coinciding
/// null surfaces would otherwise never end); such a path is dropped as black.
const MAX_CROSSINGS: u32 = 256;

/// Moves the active lanes of `paths` through media and null surfaces to their next real event,
/// updating `s` (the lanes' closest hits) and the lanes' media and throughputs. Returns the lanes
/// that scattered inside a medium: their `s.p` is the interaction point, `s.light` is none.
#[inline(never)]
pub(super) fn travel<const N: usize>(
    job: &LaneJob,
    paths: &mut Paths<N>,
    samplers: &mut LaneSamplers<N>,
    s: &mut Surfaces<N>,
) -> Ms<N> {
    let scene = job.scene;
    let materials = scene.materials();
    let mut scatter = Ms::NONE;
    let mut origin: [Vec3; N] = std::array::from_fn(|i| paths.origin.lane(i));
    let mut crossings = [0u32; N];
    let mut pending = paths.active;
    while pending.any() {
        // Every lane draws its free-flight numbers in its own sequence, whichever lanes share
        // the group, so one lane and sixteen give the same paths.
        let in_medium = pending & Ms::from_fn(|i| paths.medium[i] != MediumId::NONE);
        let (u_channel, u_distance) =
            if in_medium.any() { samplers.next_2d(in_medium) } else { (F32s::<N>::ZERO, F32s::<N>::ZERO) };
        let mut next = Ms::NONE;
        for i in pending.lanes() {
            let dir = paths.dir.lane(i);
            if in_medium.lane(i) {
                let t_hit = if s.hit.lane(i) { (s.p.lane(i) - origin[i]).length() } else { f32::INFINITY };
                if paths.hero[i] == Paths::<N>::NO_CHANNEL {
                    paths.hero[i] = ((u_channel.0[i] * 3.0) as u8).min(2);
                }
                let hero = paths.hero[i] as usize;
                let flight = scene.medium(paths.medium[i]).sample_distance_in(t_hit, hero, u_distance.0[i]);
                let mut r = Rgb::new(
                    paths.channel_density[0].0[i],
                    paths.channel_density[1].0[i],
                    paths.channel_density[2].0[i],
                );
                let w = path_weight(&mut r, flight.throughput, flight.density, hero);
                for (density, r) in paths.channel_density.iter_mut().zip(r.to_array()) {
                    density.0[i] = r;
                }
                for (beta, w) in paths.beta.iter_mut().zip(w) {
                    beta.0[i] *= w;
                }
                if flight.scattered {
                    scatter.0[i] = u32::MAX;
                    s.hit.0[i] = u32::MAX;
                    s.p.set(i, origin[i] + dir * flight.t);
                    s.light[i] = Primitive::NO_LIGHT;
                    continue;
                }
            }
            if !s.hit.lane(i) || !materials[s.material[i] as usize].is_null() {
                continue;
            }
            // A null surface: cross it into the medium behind it and look further along.
            let n_g = s.n_geometric.lane(i);
            if let Some(b) = scene.boundary(s.material[i]) {
                paths.medium[i] = b.target(n_g.dot(dir));
            }
            crossings[i] += 1;
            if crossings[i] > MAX_CROSSINGS {
                for c in 0..3 {
                    paths.beta[c].0[i] = 0.0;
                }
                s.hit.0[i] = 0;
                continue;
            }
            origin[i] = offset_ray_origin(s.p.lane(i), n_g, dir);
            set_closest_hit(scene, s, i, &Ray::new(origin[i], dir));
            next.0[i] = u32::MAX;
        }
        pending = next;
    }
    scatter
}

/// The factor by which a medium event multiplies a path's throughput, with the path's relative
/// channel densities `r` (updated here). The event contributes `f` per channel with density `p`
/// per channel, of which the followed channel's, `p[hero]`, is the one actually sampled. The
/// throughput holds f_path / avg(p_path) for the path so far; after the event that is
/// f_path·f / avg(p_path·p) = (f_path / avg(p_path)) · (f / p[hero]) · avg(r_old) / avg(r_new), with
/// r = p_path / p_path[hero] (so r[hero] = 1 and avg(r) ≥ 1/3).
#[inline(always)]
fn path_weight(r: &mut Rgb, f: Rgb, p: Rgb, hero: usize) -> [f32; 3] {
    let p_hero = p.to_array()[hero];
    let r_new = *r * p / p_hero;
    if p_hero <= 0.0 || p_hero.is_nan() || !r_new.is_finite() {
        // A channel's relative density overflowed: its path's weight is 0 to f32 precision.
        return [0.0; 3];
    }
    let scale = r.average() / (r_new.average() * p_hero);
    *r = r_new;
    (f * scale).to_array()
}

/// Lane `i`'s closest hit along `ray`, found through the scene's BVH.
#[inline(always)]
fn set_closest_hit<const N: usize>(scene: &Scene, s: &mut Surfaces<N>, i: usize, ray: &Ray) {
    match scene.intersect(ray, f32::INFINITY) {
        Some(hit) => s.set_hit(i, &scene.interaction(ray, &hit)),
        None => s.hit.0[i] = 0,
    }
}

/// Shades a medium interaction at `p` of the medium `medium`, seen along −`wo`, for a path of
/// throughput `beta`: a light sample (when `nee`) and a phase-sampled continuation.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(super) fn medium_vertex(
    scene: &Scene,
    strategy: Strategy,
    p: Vec3,
    wo: Vec3,
    medium: u32,
    beta: Rgb,
    u: VertexNumbers,
    nee: bool,
) -> Shading {
    let phase = scene.medium(medium).phase;
    let shadow = if nee {
        scene.lights.sample(p, u.select, u.light).filter(|ls| !ls.radiance.is_black()).map(|ls| {
            let f = phase.eval(wo, ls.wi);
            let (dir, t_max) = if ls.dist.is_infinite() {
                (ls.wi, f32::INFINITY)
            } else {
                let to_light = ls.point - p;
                let dist = to_light.length();
                (to_light / dist, dist * (1.0 - SHADOW_EPSILON))
            };
            // The phase function is its own sampling density (a point light cannot be found by
            // phase sampling: its sample counts in full).
            let w = if ls.delta { 1.0 } else { strategy.mis_weight(ls.pdf, f) };
            ShadowRay { origin: p, dir, t_max, contribution: beta * ls.radiance * (f * w / ls.pdf) }
        })
    } else {
        None
    };
    // Every strategy continues by the phase function (`light` and `mixture` treat a medium
    // vertex like `bsdf`): its weight f/pdf is exactly 1.
    let ps = phase.sample(wo, u.direction);
    let next = (ps.pdf > 0.0).then_some(Continuation {
        origin: p,
        dir: ps.wi,
        weight: Rgb::splat(1.0),
        pdf: ps.pdf,
        specular: false,
        eta: 1.0,
    });
    Shading { shadow, next }
}

/// The fraction of light that travels from `origin` to `origin + t_max·dir` starting in
/// `medium`: the product of each medium segment's transmittance, crossing null surfaces; black
/// when a real surface is in the way.
pub(super) fn shadow_transmittance(scene: &Scene, origin: Vec3, dir: Vec3, t_max: f32, medium: u32) -> Rgb {
    let mut tr = Rgb::splat(1.0);
    let (mut origin, mut remaining, mut medium) = (origin, t_max, medium);
    for _ in 0..=MAX_CROSSINGS {
        let ray = Ray::new(origin, dir);
        let hit = scene.intersect(&ray, remaining);
        let segment = hit.map_or(remaining, |h| h.hit.t);
        tr *= segment_transmittance(scene, medium, segment);
        let Some(hit) = hit else { return tr };
        let it = scene.interaction(&ray, &hit);
        if !it.material.is_null() || tr.is_black() {
            return Rgb::BLACK;
        }
        let n_g = it.surface.n_geometric;
        if let Some(b) = scene.boundary(it.material_id) {
            medium = b.target(n_g.dot(dir));
        }
        let next = offset_ray_origin(it.surface.p, n_g, dir);
        remaining -= (next - origin).dot(dir);
        origin = next;
        if remaining <= 0.0 {
            return tr;
        }
    }
    Rgb::BLACK
}

/// The transmittance of a segment of length `t` inside `medium` ([`MediumId::NONE`]: vacuum, 1).
/// With no `null` surfaces in the scene, this is a shadow ray's whole transmittance once it is
/// known to be unoccluded: it crosses no surface, so it stays in the medium it starts in.
#[inline(always)]
pub(super) fn segment_transmittance(scene: &Scene, medium: u32, t: f32) -> Rgb {
    if medium == MediumId::NONE {
        Rgb::splat(1.0)
    } else {
        scene.medium(medium).transmittance(t)
    }
}

/// The medium a ray leaving lane `i`'s vertex along `dir` starts in: the boundary's side at a
/// surface that bounds media, else the lane's current medium.
#[inline(always)]
pub(super) fn leaving_medium<const N: usize>(
    scene: &Scene,
    paths: &Paths<N>,
    s: &Surfaces<N>,
    scatter: Ms<N>,
    i: usize,
    dir: Vec3,
) -> u32 {
    if scatter.lane(i) {
        return paths.medium[i];
    }
    match scene.boundary(s.material[i]) {
        Some(b) => b.target(s.n_geometric.lane(i).dot(dir)),
        None => paths.medium[i],
    }
}
