//! The lane-parallel form of a vertex on a material with a lane form (a textured one with its
//! textures' values at the lane's hit, an anisotropic one in the frame of its tangent, a normal-
//! or bump-mapped one in its perturbed frame and under its rules; `wide::LaneForm` lists them):
//! the same steps as
//! `integrator::shade` (shading frame, the light sample's shadow ray with its MIS weight, a
//! direction sampled by the material), computed for all those lanes together through the
//! material's lane form ([`LaneScattering`], whose one-lane instance is the scalar material).
//! Every lane gets the bits `shade` would give it: the same operations in the same order.

// Channel loops index several lane groups with the same channel number.
#![allow(clippy::needless_range_loop)]

use super::path::Scattered;
use super::shade::{sides_agree_lanes, SHADOW_EPSILON};
use super::shading_frame::ShadingFrame;
use super::Strategy;
use crate::material::{rgb_lane, LaneDeltaScattering, LaneSamples, LaneScattering};
use crate::math::offset_ray_origin_lanes;
use crate::wide::simd::{rgb_black, F32s, Ms, Vec3s};
use crate::wide::{warp, LightSamples};

/// What the lane forms need of their vertex.
pub(super) struct LaneVertex<'a, const N: usize> {
    pub strategy: Strategy,
    /// Lanes whose material is one-sided (their frame is not turned over).
    pub one_sided: Ms<N>,
    pub p: &'a Vec3s<N>,
    pub n_geometric: &'a Vec3s<N>,
    pub n_shading: &'a Vec3s<N>,
    /// Lanes on anisotropic materials, whose frame follows the surface's tangent `tangent`
    /// (∂p/∂u, as in shade.rs); the others take the normal's basis.
    pub tangent_framed: Ms<N>,
    pub tangent: &'a Vec3s<N>,
    /// Lanes on normal- or bump-mapped materials, and their frames at the hit (shade.rs's
    /// `ShadingFrame`: the perturbed frame, and the base frame's rules for directions; `None`
    /// at vertices without such lanes).
    pub perturbed: Ms<N>,
    pub frames: Option<&'a [Option<ShadingFrame>; N]>,
    /// Towards the viewer (world space).
    pub wo: &'a Vec3s<N>,
    pub beta: &'a [F32s<N>; 3],
    /// Lanes with a light sample to test, and the samples.
    pub nee: Ms<N>,
    pub light: &'a LightSamples<N>,
    pub u_lobe: F32s<N>,
    pub u1: F32s<N>,
    pub u2: F32s<N>,
}

impl<const N: usize> LaneVertex<'_, N> {
    /// Lane `i`'s normal- or bump-mapped frame, if it has one.
    fn frame(&self, i: usize) -> Option<&ShadingFrame> {
        self.frames.and_then(|f| f[i].as_ref())
    }
}

/// Shades the vertex's `lanes`, each with its material in `material`, queueing their shadow
/// rays and continuations in `sc` (the other lanes' entries are kept).
#[inline(always)]
pub(super) fn material_lanes<const N: usize, M: LaneScattering<N>>(
    v: &LaneVertex<N>,
    lanes: Ms<N>,
    material: &M,
    sc: &mut Scattered<N>,
) {
    let zero = F32s::<N>::ZERO;
    // The frame, turned over for the back of a two-sided surface (shade.rs: `flipped`).
    let flippable = if M::TWO_SIDED { !v.one_sided } else { Ms::NONE };
    let frame = LaneFrame::new(v, flippable);
    let (n_g, n_s, s, t) = (&frame.n_g, &frame.n_s, &frame.s, &frame.t);
    let to_local = |w: &Vec3s<N>| Vec3s { x: w.dot(s), y: w.dot(t), z: w.dot(n_s) };
    let wo = to_local(v.wo);

    // ---- Light sampling: the shadow ray and what it adds if unoccluded -------------------
    let ls = v.light;
    let lit = lanes & v.nee & ls.valid;
    if lit.any() {
        let wi = to_local(&ls.wi);
        let (mut f, mut pdf_material) = material.eval_pdf(&wo, &wi);
        // A normal or bump map's rules: a direction counts on the same side of both normals,
        // and the value may be attenuated.
        for i in (lit & v.perturbed).lanes() {
            if let Some(frame) = v.frame(i) {
                let (fi, pdf) = frame.apply_to_value(rgb_lane(&f, i), pdf_material.0[i], ls.wi.lane(i), wi.lane(i));
                [f[0].0[i], f[1].0[i], f[2].0[i]] = fi.to_array();
                pdf_material.0[i] = pdf;
            }
        }
        // A point light cannot be found by material sampling: its sample counts in full.
        let pdf_material = F32s::select(ls.delta, zero, pdf_material);
        let lit = lit
            & !rgb_black(&ls.radiance)
            & !rgb_black(&f)
            & sides_agree_lanes(n_g, v.wo, &ls.wi, (wi.z * wo.z).gt(zero));
        if lit.any() {
            let origin = offset_ray_origin_lanes(v.p, n_g, &ls.wi);
            let to_light = ls.point.sub(&origin);
            let dist = to_light.length();
            let finite = ls.dist_finite;
            let towards = Vec3s { x: to_light.x / dist, y: to_light.y / dist, z: to_light.z / dist };
            let dir = Vec3s::select(finite, &towards, &ls.wi);
            let t_max = F32s::select(finite, dist * (1.0 - SHADOW_EPSILON), F32s::splat(f32::INFINITY));
            let w = F32s::select(ls.delta, F32s::ONE, v.strategy.mis_weight_lanes(ls.pdf, pdf_material));
            let scale = w / ls.pdf;
            sc.shadow = sc.shadow | lit;
            sc.shadow_origin = Vec3s::select(lit, &origin, &sc.shadow_origin);
            sc.shadow_dir = Vec3s::select(lit, &dir, &sc.shadow_dir);
            sc.shadow_t_max = F32s::select(lit, t_max, sc.shadow_t_max);
            for c in 0..3 {
                let term = v.beta[c] * f[c] * ls.radiance[c] * scale;
                sc.contribution[c] = F32s::select(lit, term, sc.contribution[c]);
            }
        }
    }

    // ---- Direction: sampled by the material -----------------------------------------------
    let sample = material.sample(&wo, v.u_lobe, v.u1, v.u2, lanes);
    continue_lanes(v, lanes, &frame, &wo, &sample, sc);
}

/// Shades the vertex's `lanes` on a model of Dirac lobes only (`material`: smooth glass,
/// conductors, mirrors): as `shade` does for such a model, no light sample (the lanes have
/// none), and the reflected or refracted direction as the continuation.
#[inline(always)]
pub(super) fn delta_lanes<const N: usize, M: LaneDeltaScattering<N>>(
    v: &LaneVertex<N>,
    lanes: Ms<N>,
    material: &M,
    sc: &mut Scattered<N>,
) {
    let flippable = if M::TWO_SIDED { !v.one_sided } else { Ms::NONE };
    let frame = LaneFrame::new(v, flippable);
    let wo = Vec3s { x: v.wo.dot(&frame.s), y: v.wo.dot(&frame.t), z: v.wo.dot(&frame.n_s) };
    let sample = material.sample(&wo, v.u_lobe, lanes);
    continue_lanes(v, lanes, &frame, &wo, &sample, sc);
}

/// A vertex's frame per lane: the true and shading normals (turned over where asked) and the
/// shading normal's tangents.
struct LaneFrame<const N: usize> {
    n_g: Vec3s<N>,
    n_s: Vec3s<N>,
    s: Vec3s<N>,
    t: Vec3s<N>,
}

impl<const N: usize> LaneFrame<N> {
    /// The frame of `v`, turned over in the lanes of `flippable` that see the back.
    #[inline(always)]
    fn new(v: &LaneVertex<N>, flippable: Ms<N>) -> Self {
        let flipped = flippable & v.n_geometric.dot(v.wo).lt(F32s::ZERO);
        let n_g = Vec3s::select(flipped, &v.n_geometric.neg(), v.n_geometric);
        let n_s = Vec3s::select(flipped, &v.n_shading.neg(), v.n_shading);
        let (s, t) = if v.tangent_framed.any() {
            let (s, t) = warp::basis(&n_s);
            let (s_t, t_t) = warp::tangent_basis(&n_s, v.tangent);
            (Vec3s::select(v.tangent_framed, &s_t, &s), Vec3s::select(v.tangent_framed, &t_t, &t))
        } else {
            warp::basis(&n_s)
        };
        let mut frame = LaneFrame { n_g, n_s, s, t };
        // A normal or bump map's frame, built per lane at the hit (it reads the map).
        for i in v.perturbed.lanes() {
            if let Some(f) = v.frame(i) {
                frame.s.set(i, f.frame.s);
                frame.t.set(i, f.frame.t);
                frame.n_s.set(i, f.frame.n);
            }
        }
        frame
    }
}

/// Queues the continuations of `lanes` from their sampled directions (`sample`, local to
/// `frame`; `wo` too).
#[inline(always)]
fn continue_lanes<const N: usize>(
    v: &LaneVertex<N>,
    lanes: Ms<N>,
    frame: &LaneFrame<N>,
    wo: &Vec3s<N>,
    sample: &LaneSamples<N>,
    sc: &mut Scattered<N>,
) {
    let LaneFrame { n_g, n_s, s, t } = frame;
    let wi = &sample.wi;
    let wi_world = s.scale(wi.x).add(&t.scale(wi.y)).add(&n_s.scale(wi.z));
    // A normal or bump map's rules for the sampled direction (shade.rs: `ShadingFrame::sample`).
    let (mut valid, mut weight) = (sample.valid, sample.weight);
    for i in (lanes & v.perturbed & sample.valid).lanes() {
        let (Some(frame), Some(one)) = (v.frame(i), sample.lane(i)) else { continue };
        match frame.apply_to_sample(one, wi_world.lane(i)) {
            Some(one) => [weight[0].0[i], weight[1].0[i], weight[2].0[i]] = one.weight.to_array(),
            None => valid.0[i] = 0,
        }
    }
    // Reflection must stay on the viewer's side of the true surface (shading normals can
    // disagree with it), transmission must cross it, as in shade.rs.
    let reflects = (wi_world.dot(n_s) * wo.z).gt(F32s::ZERO);
    let goes_on = valid & sides_agree_lanes(n_g, v.wo, &wi_world, reflects) & !rgb_black(&weight);
    let origin = offset_ray_origin_lanes(v.p, n_g, &wi_world);
    sc.goes_on = (sc.goes_on & !lanes) | goes_on;
    sc.origin = Vec3s::select(lanes, &origin, &sc.origin);
    sc.dir = Vec3s::select(lanes, &wi_world, &sc.dir);
    for c in 0..3 {
        sc.weight[c] = F32s::select(lanes, weight[c], sc.weight[c]);
    }
    sc.pdf = F32s::select(lanes, sample.pdf, sc.pdf);
    sc.specular = (sc.specular & !lanes) | (lanes & sample.specular);
    sc.eta = F32s::select(lanes, sample.eta, sc.eta);
}
