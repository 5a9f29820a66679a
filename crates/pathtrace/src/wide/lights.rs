//! Next-event estimation for eight lanes at once, over scenes lit only by flat area lights
//! (quads and triangles).
//!
//! Each lane picks its light with the scene's own selection distribution ([`LightSet::pick`]),
//! then the point on it, the direction and the density are computed for all lanes together:
//! uniform by area, pdf_ω = pmf · r² / (|cos θ_l| · A), as `light/area.rs` (derived in
//! docs/sampling.md). Triangles use the square-root warp of `sampling::warp`.

use super::simd::{F32s, Ms, Vec3s};
use crate::light::{LightSet, LightShape};
use crate::math::{Rgb, Vec3};

/// One flat light: `origin + s·e1 + t·e2`.
#[derive(Clone, Copy, Debug)]
struct FlatLight {
    origin: Vec3,
    e1: Vec3,
    e2: Vec3,
    triangle: bool,
    normal: Vec3,
    area: f32,
    radiance: Rgb,
    two_sided: bool,
}

/// The scene's lights, when all are flat area lights.
#[derive(Clone, Debug)]
pub struct WideLights {
    lights: Vec<FlatLight>,
}

/// Eight light samples (meaningful in `valid` lanes).
#[derive(Clone, Copy, Debug)]
pub struct LightSamples<const N: usize> {
    pub point: Vec3s<N>,
    /// Unit direction from the reference point to `point`.
    pub wi: Vec3s<N>,
    /// Solid-angle density, light selection included.
    pub pdf: F32s<N>,
    pub radiance: [F32s<N>; 3],
    /// A point was found, with a positive finite density, on a face that emits towards the
    /// reference point.
    pub valid: Ms<N>,
}

impl WideLights {
    /// `None` unless every light is a quad or triangle area light (no point, spot, sphere, disk
    /// or environment light).
    pub fn new(set: &LightSet) -> Option<Self> {
        if set.has_delta() || set.environment().is_some() {
            return None;
        }
        let lights = set
            .iter()
            .map(|l| {
                let (origin, e1, e2, triangle) = match l.shape {
                    LightShape::Quad(q) => (q.q, q.u, q.v, false),
                    LightShape::Triangle(t) => (t.p0, t.e1, t.e2, true),
                    _ => return None,
                };
                Some(FlatLight {
                    origin,
                    e1,
                    e2,
                    triangle,
                    normal: e1.cross(e2).normalize(),
                    area: l.area(),
                    radiance: l.emission.radiance,
                    two_sided: l.emission.two_sided,
                })
            })
            .collect::<Option<Vec<_>>>()?;
        Some(Self { lights })
    }

    /// Samples a light point for each lane of `active` from `p`, with the selection numbers
    /// `u_select` and the point numbers `(u1, u2)`.
    #[inline(always)]
    pub fn sample<const N: usize>(
        &self,
        set: &LightSet,
        p: &Vec3s<N>,
        active: Ms<N>,
        u_select: &F32s<N>,
        u1: F32s<N>,
        u2: F32s<N>,
    ) -> LightSamples<N> {
        // Gather each lane's light (scalar: one table lookup per lane).
        let mut origin = Vec3s::<N>::default();
        let mut e1 = Vec3s::<N>::default();
        let mut e2 = Vec3s::<N>::default();
        let mut normal = Vec3s::<N>::default();
        let mut pmf_per_area = F32s::<N>::ZERO;
        let mut radiance = [F32s::<N>::ZERO; 3];
        let mut triangle = Ms::<N>::NONE;
        let mut two_sided = Ms::<N>::NONE;
        let mut picked = Ms::<N>::NONE;
        for i in 0..N {
            if !active.lane(i) {
                continue;
            }
            let Some((id, pmf)) = set.pick(u_select.0[i]) else { continue };
            let Some(l) = self.lights.get(id) else { continue };
            origin.set(i, l.origin);
            e1.set(i, l.e1);
            e2.set(i, l.e2);
            normal.set(i, l.normal);
            pmf_per_area.0[i] = pmf / l.area;
            [radiance[0].0[i], radiance[1].0[i], radiance[2].0[i]] = [l.radiance.r, l.radiance.g, l.radiance.b];
            triangle.0[i] = if l.triangle { u32::MAX } else { 0 };
            two_sided.0[i] = if l.two_sided { u32::MAX } else { 0 };
            picked.0[i] = u32::MAX;
        }
        // Triangles: (1 − √u1, u2·√u1) (sampling::warp::square_to_uniform_triangle).
        let su = u1.sqrt();
        let s = F32s::<N>::select(triangle, 1.0 - su, u1);
        let t = F32s::<N>::select(triangle, u2 * su, u2);
        let point = origin.add(&e1.scale(s)).add(&e2.scale(t));
        let d = point.sub(p);
        let dist2 = d.dot(&d);
        let dist = dist2.sqrt();
        let wi = d.scale(1.0 / dist);
        let cos_l = normal.dot(&wi);
        let pdf = dist2 * pmf_per_area / cos_l.abs();
        // One-sided lights emit along their normal: towards p when cos θ_l = n·wi < 0.
        let faces_p = two_sided | cos_l.lt(F32s::<N>::ZERO);
        let valid = picked & faces_p & pdf.gt(F32s::<N>::ZERO) & pdf.is_finite() & dist.gt(F32s::<N>::ZERO);
        LightSamples { point, wi, pdf, radiance, valid }
    }
}
