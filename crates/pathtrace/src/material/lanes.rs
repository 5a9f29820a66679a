//! The materials' lane forms, as the estimator's lane-parallel shading
//! (`integrator::material_lanes`) asks them: a material's value, density and samples for a
//! group of lanes at once, each lane with its own material of that model. Each model's scalar
//! methods are the one-lane instance of its lane form, so a formula exists once.

use super::BsdfSample;
use crate::math::{Rgb, Vec2, Vec3};
use crate::wide::simd::{F32s, Ms, Vec3s};

/// Sampled directions per lane: the valid lanes' direction `wi` (local frame), weight
/// f·cos/pdf per RGB channel and density (solid angle; for a Dirac lobe, the lobe's
/// probability), whether the lobe is a Dirac one, and the relative index crossed (1 for
/// reflection).
pub(crate) struct LaneSamples<const N: usize> {
    pub valid: Ms<N>,
    pub wi: Vec3s<N>,
    pub weight: [F32s<N>; 3],
    pub pdf: F32s<N>,
    pub specular: Ms<N>,
    pub eta: F32s<N>,
}

impl<const N: usize> LaneSamples<N> {
    /// Lane `i`'s sample, if valid.
    #[inline(always)]
    pub fn lane(&self, i: usize) -> Option<BsdfSample> {
        self.valid.lane(i).then(|| BsdfSample {
            wi: self.wi.lane(i),
            weight: rgb_lane(&self.weight, i),
            pdf: self.pdf.0[i],
            delta: self.specular.lane(i),
            eta: self.eta.0[i],
        })
    }
}

/// Lane `i` of a colour held as one lane group per channel.
#[inline(always)]
pub(crate) fn rgb_lane<const N: usize>(c: &[F32s<N>; 3], i: usize) -> Rgb {
    Rgb::new(c[0].0[i], c[1].0[i], c[2].0[i])
}

/// A model's lane form, in the local frame (normal = +z), as [`crate::material::Material`]'s
/// `eval_pdf` and `sample`: the models with a smooth lobe, which take part in light sampling
/// (`eval_pdf` covers the smooth lobes; a Dirac lobe's samples are flagged `specular`).
pub(crate) trait LaneScattering<const N: usize> {
    /// Scatters from both sides: the frame turns over to the viewer's side (a dielectric's
    /// does not: the side the ray comes from decides whether it enters or leaves).
    const TWO_SIDED: bool = true;
    /// f·cos θi and the density of `wi` per lane.
    fn eval_pdf(&self, wo: &Vec3s<N>, wi: &Vec3s<N>) -> ([F32s<N>; 3], F32s<N>);
    /// A direction per lane of `active`, from the lobe number `u_lobe` and the direction's
    /// `u1`, `u2`.
    fn sample(&self, wo: &Vec3s<N>, u_lobe: F32s<N>, u1: F32s<N>, u2: F32s<N>, active: Ms<N>) -> LaneSamples<N>;
}

/// The lane form of a model of Dirac lobes only (mirrors, smooth conductors and glass): no
/// light sampling, a sampled direction only.
pub(crate) trait LaneDeltaScattering<const N: usize> {
    /// Scatters from both sides: the frame turns over to the viewer's side (a dielectric does
    /// not: the side the ray comes from decides whether it enters or leaves).
    const TWO_SIDED: bool;
    /// A direction per lane of `active`, from the lobe number `u_lobe`.
    fn sample(&self, wo: &Vec3s<N>, u_lobe: F32s<N>, active: Ms<N>) -> LaneSamples<N>;
}

/// A model with a smooth lobe, as [`super::Material`] dispatches to it: its lane form in every
/// lane of a group, and its scalar methods, which are that form's one-lane instance (so a
/// model writes its formulas once, in [`LaneScattering`]).
pub(crate) trait SmoothModel {
    type Lanes<'a, const N: usize>: LaneScattering<N>
    where
        Self: 'a;

    /// This model in every lane of a group.
    fn lanes<const N: usize>(&self) -> Self::Lanes<'_, N>;

    /// Samples `wi` given `wo`, a number for lobe selection and a 2D point.
    #[inline]
    fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        self.lanes::<1>().sample(&Vec3s::splat(wo), F32s([u_lobe]), F32s([u.x]), F32s([u.y]), Ms::ALL).lane(0)
    }

    /// f·cos θi and the density of `wi` together, sharing what the two have in common.
    #[inline]
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        let (f, pdf) = self.lanes::<1>().eval_pdf(&Vec3s::splat(wo), &Vec3s::splat(wi));
        (rgb_lane(&f, 0), pdf.0[0])
    }

    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        self.eval_pdf(wo, wi).0
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_pdf(wo, wi).1
    }
}

/// A model of Dirac lobes only, as [`super::Material`] dispatches to it: its lane form, and
/// its scalar sample as that form's one-lane instance.
pub(crate) trait DeltaModel {
    type Lanes<const N: usize>: LaneDeltaScattering<N>;

    /// This model in every lane of a group.
    fn lanes<const N: usize>(&self) -> Self::Lanes<N>;

    /// Samples `wi` given `wo` and a number for lobe selection.
    #[inline]
    fn sample(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        self.lanes::<1>().sample(&Vec3s::splat(wo), F32s([u_lobe]), Ms::ALL).lane(0)
    }
}
