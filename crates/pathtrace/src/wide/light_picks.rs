//! The lights a group's lanes drew, gathered per kind for the lane-parallel sampling rules of
//! [`super::lights::WideLights::sample`].
//!
//! A light's fields go to its lanes in one of two ways, with one description of what each kind
//! needs ([`Picks::take`]): to all the lanes that drew it at once, as blends ([`Masked`]), or to
//! one lane, as stores ([`Lane`]). Scenes with a few lights take the first: the group's lanes
//! drew one or two of them, and lane by lane every field was a scalar store read back as a
//! vector (measured in docs/benchmarks.md, "Lanes that drew the same light set up together").
//! With many lights (an emissive mesh's triangles) nearly every lane drew its own, and a blend
//! over the whole group per lane cost 8% of such a scene's time: those go lane by lane.

use super::lights::WideLight;
use super::simd::{made, map_rgb, F32s, Ms, Vec3s};
use crate::light::area::{DiskLights, FlatLights, SphereLights};
use crate::light::SpotLanes;
use crate::math::{Rgb, Vec3};

/// Scenes with at most this many lights set their lanes up per light drawn ([`Masked`]); more,
/// per lane ([`Lane`]). The same count up to which a light is picked by a plain scan, in SIMD
/// (`Distribution1D::sample_lanes`).
pub(super) const GROUPED_LIGHTS: usize = 8;

/// Each lane's drawn light: the fields of its kind, which kinds were drawn where, the selection
/// pmf (over the area for flat lights), the emitted radiance (where it does not depend on the
/// sample) and the facing. Each kind's lanes are set up when a lane first draws one, filled
/// with that light (the kind's other lanes are never read): a group pays for the kinds it drew,
/// not for every kind (zeroing them all for every group was 1.7% of the Cornell box's
/// instructions, and zeroing the flat lights' lanes, a `memset`, 1.6% of its time).
pub(super) struct Picks<const N: usize> {
    pub flat: Option<FlatLights<N>>,
    /// Light ids of the lanes whose flat light has a radiance texture.
    pub textured: Option<[usize; N]>,
    pub on_textured: Ms<N>,
    pub disks: Option<DiskLights<N>>,
    pub on_disk: Ms<N>,
    pub spheres: Option<SphereLights<N>>,
    pub on_sphere: Ms<N>,
    pub on_environment: Ms<N>,
    /// Point lights' positions and intensities.
    pub points: Option<(Vec3s<N>, [F32s<N>; 3])>,
    pub on_point: Ms<N>,
    pub spots: Option<SpotLanes<N>>,
    pub on_spot: Ms<N>,
    /// Directional lights' direction towards the light.
    pub directional_wi: Option<Vec3s<N>>,
    pub on_directional: Ms<N>,
    /// The selection pmf, divided by the area for flat lights (whose density is per area).
    pub pmf_factor: F32s<N>,
    pub radiance: [F32s<N>; 3],
    pub two_sided: Ms<N>,
    pub picked: Ms<N>,
}

/// Where a light's fields go: the lanes of a mask or a single lane.
pub(super) trait Target<const N: usize>: Copy {
    fn vec3(self, to: &mut Vec3s<N>, v: Vec3);
    fn value(self, to: &mut F32s<N>, v: f32);
    /// The lanes' `pmf`, or `pmf / area` with `Some(area)`: one division per lane either way,
    /// so both targets give the same bits.
    fn pmf(self, to: &mut F32s<N>, pmf: &F32s<N>, area: Option<f32>);
    /// Sets the target's lanes of `to`.
    fn mark(self, to: &mut Ms<N>);
    /// The target's lanes, for the fields kept per lane (texture ids, spot lights).
    fn lanes(self) -> impl Iterator<Item = usize>;
}

/// The lanes of a mask, set by blends.
#[derive(Clone, Copy)]
pub(super) struct Masked<const N: usize>(pub Ms<N>);

/// One lane, set by stores.
#[derive(Clone, Copy)]
pub(super) struct Lane(pub usize);

impl<const N: usize> Target<N> for Masked<N> {
    #[inline(always)]
    fn vec3(self, to: &mut Vec3s<N>, v: Vec3) {
        *to = Vec3s::select(self.0, &Vec3s::splat(v), to);
    }
    #[inline(always)]
    fn value(self, to: &mut F32s<N>, v: f32) {
        *to = F32s::select(self.0, F32s::splat(v), *to);
    }
    #[inline(always)]
    fn pmf(self, to: &mut F32s<N>, pmf: &F32s<N>, area: Option<f32>) {
        let v = match area {
            Some(a) => *pmf / F32s::splat(a),
            None => *pmf,
        };
        *to = F32s::select(self.0, v, *to);
    }
    #[inline(always)]
    fn mark(self, to: &mut Ms<N>) {
        *to = *to | self.0;
    }
    #[inline(always)]
    fn lanes(self) -> impl Iterator<Item = usize> {
        self.0.lanes()
    }
}

impl<const N: usize> Target<N> for Lane {
    #[inline(always)]
    fn vec3(self, to: &mut Vec3s<N>, v: Vec3) {
        to.set(self.0, v);
    }
    #[inline(always)]
    fn value(self, to: &mut F32s<N>, v: f32) {
        to.0[self.0] = v;
    }
    #[inline(always)]
    fn pmf(self, to: &mut F32s<N>, pmf: &F32s<N>, area: Option<f32>) {
        let p = pmf.0[self.0];
        to.0[self.0] = match area {
            Some(a) => p / a,
            None => p,
        };
    }
    #[inline(always)]
    fn mark(self, to: &mut Ms<N>) {
        to.0[self.0] = u32::MAX;
    }
    #[inline(always)]
    fn lanes(self) -> impl Iterator<Item = usize> {
        std::iter::once(self.0)
    }
}

impl<const N: usize> Picks<N> {
    /// No lane has drawn a light.
    #[inline(always)]
    pub fn none() -> Self {
        Self {
            flat: None,
            textured: None,
            on_textured: Ms::NONE,
            disks: None,
            on_disk: Ms::NONE,
            spheres: None,
            on_sphere: Ms::NONE,
            on_environment: Ms::NONE,
            points: None,
            on_point: Ms::NONE,
            spots: None,
            on_spot: Ms::NONE,
            directional_wi: None,
            on_directional: Ms::NONE,
            pmf_factor: F32s::ZERO,
            radiance: [F32s::ZERO; 3],
            two_sided: Ms::NONE,
            picked: Ms::NONE,
        }
    }

    /// The lanes of `to` drew `light`, with the selection probabilities `pmf`.
    #[inline(always)]
    pub fn take<T: Target<N>>(&mut self, to: T, light: &WideLight, pmf: &F32s<N>) {
        let (emitted, both_faces) = match light {
            WideLight::Flat(l) => {
                let f = made(&mut self.flat, || FlatLights {
                    origin: Vec3s::splat(l.origin),
                    e1: Vec3s::splat(l.e1),
                    e2: Vec3s::splat(l.e2),
                    normal: Vec3s::splat(l.normal),
                    triangle: Ms::NONE,
                });
                to.vec3(&mut f.origin, l.origin);
                to.vec3(&mut f.e1, l.e1);
                to.vec3(&mut f.e2, l.e2);
                to.vec3(&mut f.normal, l.normal);
                if l.triangle {
                    to.mark(&mut f.triangle);
                }
                if let Some(id) = l.textured {
                    let textured = made(&mut self.textured, || [id; N]);
                    for i in to.lanes() {
                        textured[i] = id;
                    }
                    to.mark(&mut self.on_textured);
                }
                to.pmf(&mut self.pmf_factor, pmf, Some(l.area));
                (l.radiance, l.two_sided)
            }
            WideLight::Disk(l) => {
                let disks = made(&mut self.disks, || DiskLights {
                    center: Vec3s::splat(l.center),
                    u: Vec3s::splat(l.u),
                    v: Vec3s::splat(l.v),
                    normal: Vec3s::splat(l.normal),
                    area: F32s::splat(l.area),
                });
                to.vec3(&mut disks.center, l.center);
                to.vec3(&mut disks.u, l.u);
                to.vec3(&mut disks.v, l.v);
                to.vec3(&mut disks.normal, l.normal);
                to.value(&mut disks.area, l.area);
                to.mark(&mut self.on_disk);
                to.pmf(&mut self.pmf_factor, pmf, None);
                (l.radiance, l.two_sided)
            }
            WideLight::Sphere(l) => {
                let spheres = made(&mut self.spheres, || SphereLights {
                    center: Vec3s::splat(l.center),
                    radius: F32s::splat(l.radius),
                    inward: Ms::NONE,
                });
                to.vec3(&mut spheres.center, l.center);
                to.value(&mut spheres.radius, l.radius);
                if l.inward {
                    to.mark(&mut spheres.inward);
                }
                to.mark(&mut self.on_sphere);
                to.pmf(&mut self.pmf_factor, pmf, None);
                (l.radiance, l.two_sided)
            }
            // Its radiance depends on the direction (set by the sampling); it faces every point.
            WideLight::Environment => {
                to.mark(&mut self.on_environment);
                to.pmf(&mut self.pmf_factor, pmf, None);
                (Rgb::BLACK, true)
            }
            // I/r², set by the sampling; a point has no facing.
            WideLight::Point(l) => {
                to.mark(&mut self.on_point);
                let (position, intensity) =
                    made(&mut self.points, || (Vec3s::splat(l.position), map_rgb(l.intensity.to_array(), F32s::splat)));
                to.vec3(position, l.position);
                for (c, v) in intensity.iter_mut().zip(l.intensity.to_array()) {
                    to.value(c, v);
                }
                to.pmf(&mut self.pmf_factor, pmf, None);
                (Rgb::BLACK, true)
            }
            // I·falloff/r², set by the sampling.
            WideLight::Spot(l) => {
                to.mark(&mut self.on_spot);
                let spots = made(&mut self.spots, || l.lanes());
                for i in to.lanes() {
                    spots.set(i, l);
                }
                to.pmf(&mut self.pmf_factor, pmf, None);
                (Rgb::BLACK, true)
            }
            // The same direction and irradiance from every point.
            WideLight::Directional { wi, irradiance } => {
                to.mark(&mut self.on_directional);
                to.vec3(made(&mut self.directional_wi, || Vec3s::splat(*wi)), *wi);
                to.pmf(&mut self.pmf_factor, pmf, None);
                (*irradiance, true)
            }
        };
        for (c, v) in self.radiance.iter_mut().zip(emitted.to_array()) {
            to.value(c, v);
        }
        if both_faces {
            to.mark(&mut self.two_sided);
        }
        to.mark(&mut self.picked);
    }
}
