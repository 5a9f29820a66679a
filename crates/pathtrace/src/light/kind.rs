//! Every kind of light, as one closed enum: a new kind is a variant here, and the compiler then
//! flags each place that must handle it (its power for selection, its sample, its density).

use super::area::AreaLight;
use super::directional::DirectionalLight;
use super::environment::EnvironmentLight;
use super::point::PointLight;
use super::set::LightSample;
use super::spot::SpotLight;
use crate::math::{Vec2, Vec3};

/// One light of the scene.
#[derive(Clone, Debug)]
pub enum Light {
    /// An emissive surface (its primitives refer to it by id).
    Area(AreaLight),
    Point(PointLight),
    Spot(SpotLight),
    Directional(DirectionalLight),
    /// The radiance arriving from every direction that leaves the scene (at most one per scene).
    Environment(EnvironmentLight),
}

impl Light {
    /// Emitted power in luminance units, the weight of power-proportional selection. Lights at
    /// infinity (directional, environment) count what crosses a scene bounded by a sphere of
    /// radius `scene_radius`.
    pub fn power(&self, scene_radius: f32) -> f64 {
        match self {
            Light::Area(l) => l.power(),
            Light::Point(l) => l.power(),
            Light::Spot(l) => l.power(),
            Light::Directional(l) => l.power(scene_radius),
            Light::Environment(l) => l.power(scene_radius),
        }
    }

    /// True for a Dirac delta in direction (point, spot, directional): material sampling can
    /// never find it, and it has no density in solid angle.
    pub fn is_delta(&self) -> bool {
        match self {
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) => true,
            Light::Area(_) | Light::Environment(_) => false,
        }
    }

    /// A point on the light seen from `ref_p`, with its solid-angle density (1 for a delta
    /// light) not yet multiplied by the probability of having picked this light.
    #[inline(always)]
    pub(super) fn sample(&self, ref_p: Vec3, u: Vec2) -> Option<LightSample> {
        match self {
            Light::Area(light) => {
                let s = light.sample(ref_p, u)?;
                Some(LightSample {
                    point: s.point,
                    normal: s.normal,
                    wi: s.wi,
                    dist: s.dist,
                    pdf: s.pdf,
                    radiance: light.emitted_at_point(s.point, s.normal, -s.wi),
                    delta: false,
                })
            }
            Light::Point(light) => {
                let (wi, dist, radiance) = light.sample(ref_p)?;
                Some(LightSample { point: light.position, normal: -wi, wi, dist, pdf: 1.0, radiance, delta: true })
            }
            Light::Spot(light) => {
                let (wi, dist, radiance) = light.sample(ref_p)?;
                Some(LightSample { point: light.position(), normal: -wi, wi, dist, pdf: 1.0, radiance, delta: true })
            }
            Light::Directional(light) => {
                // At infinity, like the environment: the shadow ray is unoccluded if it leaves.
                let (wi, radiance) = light.sample();
                let (point, dist) = (ref_p + wi, f32::INFINITY);
                Some(LightSample { point, normal: -wi, wi, dist, pdf: 1.0, radiance, delta: true })
            }
            Light::Environment(env) => {
                let (wi, pdf, radiance) = env.sample(u);
                if pdf <= 0.0 {
                    return None;
                }
                Some(LightSample {
                    point: ref_p + wi,
                    normal: -wi,
                    wi,
                    dist: f32::INFINITY,
                    pdf,
                    radiance,
                    delta: false,
                })
            }
        }
    }

    /// Solid-angle density with which [`Light::sample`] picks direction `dir` from `ref_p`; 0
    /// for delta lights, which have none.
    pub(super) fn pdf_direction(&self, ref_p: Vec3, dir: Vec3) -> f32 {
        match self {
            Light::Area(l) => l.pdf_direction(ref_p, dir),
            Light::Environment(l) => l.pdf(dir),
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) => 0.0,
        }
    }
}
