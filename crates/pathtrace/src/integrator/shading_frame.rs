//! The frame a material is evaluated in at a hit: the shading normal's, or — for materials with
//! a normal or bump map — a frame around the perturbed normal, with Mitsuba 3's rules for it
//! (`normalmap.cpp`, `bumpmap.cpp`):
//!
//! - the perturbed normal n' is given in the base frame (s, t, n) of the hit, s = ∂p/∂u made
//!   perpendicular to n, t = n × s; the material's frame around n' takes its first axis from the
//!   base frame's s, made perpendicular to n';
//! - a perturbed normal facing away from the viewer has its tangential part mirrored
//!   (`flip_invalid_normals`: (x, y, z) → (−x, −y, z) when cos θ_o · (ω_o · n') ≤ 0);
//! - a direction counts only if it lies on the same side of both normals (so light never leaks
//!   through the true surface), and the material's value (not its density) is attenuated by
//!   the shadowing term of Estevez et al. (2019) when `shadowing` is on.
//!
//! Two-sided materials seen from the back are shaded, as in Mitsuba's `twosided`, with the base
//! frame's normal reversed and its tangents kept: (s, t, −n).

use crate::material::{BsdfSample, Scattering};
use crate::math::{Frame, Rgb, Vec2, Vec3};
use crate::scene::{Interaction, Scene};
use crate::texture::{shadow_terminator, NormalPerturbation};

/// A material's frame at one hit.
pub(crate) struct ShadingFrame {
    /// The frame the material works in (around the perturbed normal, if any).
    pub frame: Frame,
    perturbed: Option<Perturbed>,
}

/// What a perturbed frame keeps of its base frame.
struct Perturbed {
    /// The base frame (its normal reversed for the back of two-sided materials).
    base: Frame,
    /// The perturbed normal in `base`'s coordinates.
    n_local: Vec3,
    shadowing: bool,
}

impl ShadingFrame {
    /// The frame of an unperturbed material around the (oriented) shading normal `n_s`.
    #[inline(always)]
    pub fn plain(frame: Frame) -> Self {
        Self { frame, perturbed: None }
    }

    /// The frame of a material with perturbation `p` at hit `it`, seen along `-wo_world`;
    /// `flipped`: the material is two-sided and seen from the back.
    pub fn perturbed(scene: &Scene, it: &Interaction, p: &NormalPerturbation, flipped: bool, wo_world: Vec3) -> Self {
        let surface = &it.surface;
        let unflipped = Frame::from_normal_tangent(surface.n_shading, surface.tangent());
        let mut n_local = p.local_normal(scene.textures(), surface, &unflipped);
        let base = if flipped { Frame { n: -unflipped.n, ..unflipped } } else { unflipped };
        let wo = base.to_local(wo_world);
        if wo.z * wo.dot(n_local) <= 0.0 {
            n_local = Vec3::new(-n_local.x, -n_local.y, n_local.z);
        }
        let local = Frame::from_normal_tangent(n_local, Vec3::X);
        let frame = Frame { s: base.to_world(local.s), t: base.to_world(local.t), n: base.to_world(local.n) };
        Self { frame, perturbed: Some(Perturbed { base, n_local, shadowing: p.shadowing }) }
    }

    /// World → the material's local coordinates.
    #[inline(always)]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        self.frame.to_local(v)
    }

    /// The material's value for light arriving from `wi_world`, seen along local `wo`.
    #[inline(always)]
    pub fn eval<M: Scattering>(&self, material: &M, wo: Vec3, wi_world: Vec3) -> Rgb {
        let wi = self.frame.to_local(wi_world);
        match &self.perturbed {
            None => material.eval(wo, wi),
            Some(p) => p.value(material.eval(wo, wi), wi_world, wi),
        }
    }

    /// The material's density of `wi_world`, seen along local `wo`.
    #[inline(always)]
    pub fn pdf<M: Scattering>(&self, material: &M, wo: Vec3, wi_world: Vec3) -> f32 {
        let wi = self.frame.to_local(wi_world);
        match &self.perturbed {
            None => material.pdf(wo, wi),
            Some(p) => p.density(material.pdf(wo, wi), wi_world, wi),
        }
    }

    /// [`ShadingFrame::eval`] and [`ShadingFrame::pdf`] of one direction (see
    /// [`Material::eval_pdf`]).
    #[inline(always)]
    pub fn eval_pdf<M: Scattering>(&self, material: &M, wo: Vec3, wi_world: Vec3) -> (Rgb, f32) {
        match &self.perturbed {
            None => material.eval_pdf(wo, self.frame.to_local(wi_world)),
            Some(_) => (self.eval(material, wo, wi_world), self.pdf(material, wo, wi_world)),
        }
    }

    /// A direction sampled by the material, seen along local `wo`, with its direction in world
    /// space; `None` where the material has none or it crosses the base surface the wrong way.
    #[inline(always)]
    pub fn sample<M: Scattering>(&self, material: &M, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<(BsdfSample, Vec3)> {
        let s = material.sample(wo, u_lobe, u)?;
        let wi_world = self.frame.to_world(s.wi);
        match &self.perturbed {
            None => Some((s, wi_world)),
            Some(p) => p.sampled(s, wi_world).map(|s| (s, wi_world)),
        }
    }

    /// The material's value `f` and density `pdf` of `wi_world` (local `wi`), as the material
    /// evaluated them in this frame, after the perturbed frame's rules ([`ShadingFrame::eval`],
    /// [`ShadingFrame::pdf`]): what a lane of the lane-parallel shading applies to its lane.
    #[inline(always)]
    pub fn apply_to_value(&self, f: Rgb, pdf: f32, wi_world: Vec3, wi: Vec3) -> (Rgb, f32) {
        match &self.perturbed {
            None => (f, pdf),
            Some(p) => (p.value(f, wi_world, wi), p.density(pdf, wi_world, wi)),
        }
    }

    /// A material's sample `s` (towards `wi_world`) after the perturbed frame's rules
    /// ([`ShadingFrame::sample`]).
    #[inline(always)]
    pub fn apply_to_sample(&self, s: BsdfSample, wi_world: Vec3) -> Option<BsdfSample> {
        match &self.perturbed {
            None => Some(s),
            Some(p) => p.sampled(s, wi_world),
        }
    }
}

impl Perturbed {
    /// The material's value `f` for light from `wi_world` (local `wi` in the perturbed frame):
    /// none unless the direction lies on the same side of both normals, else attenuated.
    #[inline(always)]
    fn value(&self, f: Rgb, wi_world: Vec3, wi: Vec3) -> Rgb {
        let wi_base = self.base.to_local(wi_world);
        if wi_base.z * wi.z <= 0.0 {
            return Rgb::BLACK;
        }
        f * self.attenuation(wi_base)
    }

    /// The material's density `pdf` of `wi_world`: none unless it lies on the same side of both
    /// normals.
    #[inline(always)]
    fn density(&self, pdf: f32, wi_world: Vec3, wi: Vec3) -> f32 {
        if self.base.n.dot(wi_world) * wi.z <= 0.0 {
            return 0.0;
        }
        pdf
    }

    /// A sample towards `wi_world`: dropped if it crosses the base surface the wrong way, its
    /// weight attenuated.
    #[inline(always)]
    fn sampled(&self, s: BsdfSample, wi_world: Vec3) -> Option<BsdfSample> {
        let wi_base = self.base.to_local(wi_world);
        if wi_base.z * s.wi.z <= 0.0 {
            return None;
        }
        Some(BsdfSample { weight: s.weight * self.attenuation(wi_base), ..s })
    }

    /// The terminator's shadowing for light along `w_base` (base frame), or 1.
    #[inline(always)]
    fn attenuation(&self, w_base: Vec3) -> f32 {
        if self.shadowing {
            shadow_terminator(self.n_local, w_base)
        } else {
            1.0
        }
    }
}
