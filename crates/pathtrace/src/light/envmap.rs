//! An environment map: a latitude-longitude image of the radiance arriving from infinity,
//! looked up bilinearly and importance-sampled in proportion to luminance × sin θ.
//!
//! Conventions follow Mitsuba 3's `envmap` emitter so its scenes look the same here: in the
//! map's local frame +y is up; a direction d has u = atan2(d.x, −d.z) / 2π and
//! v = acos(d.y) / π, i.e. d = (sin θ sin φ, cos θ, −sin θ cos φ) with φ = 2πu, θ = πv. Column
//! i sits at u = (i + ½)/W and wraps around; row j sits at v = j/(H − 1), so the first and last
//! rows are the poles. `to_world` takes the local frame to the world (rotations, possibly a
//! mirror and a uniform scale, which directions ignore).
//!
//! Sampling (pbrt-v4 §12.5.2 `ImageInfiniteLight`): a [`Distribution2D`] over the cells between
//! texels, each weighted by the mean luminance of its four corner texels times sin θ at its
//! centre, so every direction with radiance has a positive density. A point (u, v) of density
//! p_uv maps to a direction of solid-angle density p_uv / (2π² sin θ), since
//! dω = sin θ dθ dφ = 2π² sin θ du dv.
//!
//! MIS compensation (Karlík, Šik, Vévoda, Skřivan & Křivánek, "MIS Compensation: Optimizing
//! Sampling Techniques in Multiple Importance Sampling", SIGGRAPH Asia 2019; pbrt-v4's
//! `ImageInfiniteLight::compensatedDistribution`): where next-event estimation is combined by MIS
//! with material sampling, the light's density can leave to the material the directions whose
//! radiance is at most the map's mean, L̄ = ∫ L dω / 4π, and sample in proportion to
//! max(L − L̄, 0) instead; material sampling still covers every direction, so the estimate
//! stays unbiased, and the light's samples concentrate on the bright parts MIS gives them.
//! [`EnvSampling`] says which density an estimator uses, for its samples and its MIS weights
//! alike.

use crate::math::{Mat4, Rgb, Transform, Vec2, Vec3, PI};
use crate::sampling::Distribution2D;
use crate::wide::inverse_trig;
use crate::wide::prefetch::prefetch;
use crate::wide::simd::{F32s, Ms, Vec3s};
use crate::wide::warp::cos_sin_turn;

/// Which density the map is sampled with (and its MIS weights computed with).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EnvSampling {
    /// In proportion to luminance × sin θ: every direction with radiance has a positive
    /// density. Light sampling alone (the `light` and `mixture` strategies, media) needs this.
    #[default]
    Complete,
    /// In proportion to max(luminance − mean, 0) × sin θ (MIS compensation, see the module
    /// comment): for estimators that weigh light samples by MIS against material samples,
    /// which reach the directions this density leaves out. A map with nothing above its mean
    /// (a constant one) keeps the complete density.
    Compensated,
}

/// A lat-long radiance image with its sampling distributions.
#[derive(Clone, Debug)]
pub struct EnvMap {
    width: usize,
    height: usize,
    /// Row-major linear RGB radiance, scale included, negatives clamped to 0.
    pixels: Vec<Rgb>,
    to_world: Transform,
    /// Distribution over `width × cell_rows` cells (in u shifted by half a texel).
    distribution: Distribution2D,
    /// The same cells weighted by the luminance above the map's mean ([`EnvSampling`]);
    /// `None` when no cell is above it.
    compensated: Option<Distribution2D>,
    /// ∫ luminance dω over the sphere (of the piecewise-constant approximation the sampler uses).
    luminance_integral: f64,
}

/// Directions drawn by [`EnvMap::sample_lanes`], meaningful in the lanes asked for.
#[derive(Clone, Copy, Debug)]
pub struct EnvSamples<const N: usize> {
    pub dir: Vec3s<N>,
    /// Solid-angle density (0 where the sample hit a pole: discard it).
    pub pdf: F32s<N>,
    /// The radiance along `dir`, per channel.
    pub radiance: [F32s<N>; 3],
}

/// Where a bilinear lookup reads (the offsets of its two texel rows and its two columns) and
/// its weights.
#[derive(Clone, Copy, Debug, Default)]
struct Footprint {
    row0: usize,
    row1: usize,
    i0: usize,
    i1: usize,
    fx: f32,
    fy: f32,
}

impl EnvMap {
    /// A map of `width × height` linear RGB `pixels` (row-major, top row = up), multiplied by
    /// `scale`. Errors: wrong sizes, non-finite values, a `to_world` that is not a rotation
    /// (or mirror) times a uniform scale, or an image that is black everywhere.
    pub fn new(width: u32, height: u32, pixels: Vec<Rgb>, scale: f32, to_world: Transform) -> Result<EnvMap, String> {
        let (w, h) = (width as usize, height as usize);
        if w == 0 || h == 0 || pixels.len() != w * h {
            return Err(format!("an environment map of {width}×{height} needs {} pixels, got {}", w * h, pixels.len()));
        }
        if !(scale.is_finite() && scale >= 0.0) {
            return Err(format!("an environment map's scale must be finite and ≥ 0, got {scale}"));
        }
        if pixels.iter().any(|p| !p.is_finite()) {
            return Err("an environment map has non-finite pixels".into());
        }
        if to_world.uniform_scale().is_none() {
            return Err("an environment map's to_world must be a rotation (times a uniform scale)".into());
        }
        // Negative radiance (ringing in some HDR files) has no meaning for a light.
        let pixels: Vec<Rgb> =
            pixels.into_iter().map(|p| Rgb::new(p.r.max(0.0), p.g.max(0.0), p.b.max(0.0)) * scale).collect();
        if pixels.iter().any(|p| !p.is_finite()) {
            return Err(format!(
                "an environment map's radiance times its scale {scale} overflows single precision (3.4e38): \
                 lower the scale or the map's values"
            ));
        }
        let rows = cell_rows(h);
        // Per cell, the mean luminance of its corners and sin θ at its centre.
        let mut cells = Vec::with_capacity(w * rows);
        for j in 0..rows {
            let sin_theta = f64::from((PI * (j as f32 + 0.5) / rows as f32).sin());
            let (j0, j1) = (j.min(h - 1), (j + 1).min(h - 1));
            for i in 0..w {
                let i1 = (i + 1) % w;
                let corners = [(i, j0), (i1, j0), (i, j1), (i1, j1)];
                let mean = corners.iter().map(|&(x, y)| pixels[y * w + x].luminance_f64().max(0.0)).sum::<f64>() / 4.0;
                cells.push((mean, sin_theta));
            }
        }
        let weights: Vec<f64> = cells.iter().map(|&(l, sin_theta)| l * sin_theta).collect();
        let total: f64 = weights.iter().sum();
        let distribution = cell_distribution(&weights, w, rows)
            .ok_or_else(|| "an environment map must have some positive radiance".to_string())?;
        // The mean over solid angle: cells equal in uv cover solid angle in proportion to sin θ.
        let mean = total / cells.iter().map(|&(_, sin_theta)| sin_theta).sum::<f64>();
        let compensated = cell_distribution(&compensated_weights(&cells, mean), w, rows);
        // Σ weight · (cell area in uv) · 2π² (the Jacobian above).
        let luminance_integral = total * 2.0 * (PI as f64).powi(2) / (w * rows) as f64;
        Ok(EnvMap { width: w, height: h, pixels, to_world, distribution, compensated, luminance_integral })
    }

    /// The distribution `how` asks for.
    #[inline(always)]
    fn distribution(&self, how: EnvSampling) -> &Distribution2D {
        match (how, &self.compensated) {
            (EnvSampling::Compensated, Some(d)) => d,
            _ => &self.distribution,
        }
    }

    /// Radiance seen looking along the unit world direction `dir` (bilinear between texels).
    #[inline]
    pub fn radiance(&self, dir: Vec3) -> Rgb {
        lane_rgb(self.lookup_lanes(&Vec3s::splat(dir), Ms::ALL, Ms::NONE, EnvSampling::Complete).0)
    }

    /// [`EnvMap::radiance`] and [`EnvMap::pdf`] of one direction (an escaped path weighs what it
    /// sees by MIS), mapping the direction to the image once.
    #[inline]
    pub fn radiance_and_pdf(&self, dir: Vec3) -> (Rgb, f32) {
        let (radiance, pdf) = self.lookup_lanes(&Vec3s::splat(dir), Ms::ALL, Ms::ALL, EnvSampling::Complete);
        (lane_rgb(radiance), pdf.0[0])
    }

    /// Solid-angle density of [`EnvMap::sample`] for the unit world direction `dir`.
    #[inline]
    pub fn pdf(&self, dir: Vec3) -> f32 {
        self.pdf_with(dir, EnvSampling::Complete)
    }

    /// Solid-angle density of [`EnvMap::sample_with`] under `how` for the unit world direction
    /// `dir`.
    #[inline]
    pub fn pdf_with(&self, dir: Vec3, how: EnvSampling) -> f32 {
        let (local, cell_u, v) = self.image_coordinates(&Vec3s::<1>::splat(dir));
        self.pdf_at_lanes(cell_u, v, &local, Ms::ALL, how).0[0]
    }

    /// Per lane of `active`, the radiance seen along the unit world direction `dir` and, in the
    /// lanes of `with_pdf` (a subset), [`EnvMap::pdf_with`] of it under `how` (0 elsewhere). The
    /// one-lane instance is [`EnvMap::radiance`] and [`EnvMap::radiance_and_pdf`].
    #[inline(always)]
    pub fn lookup_lanes<const N: usize>(
        &self,
        dir: &Vec3s<N>,
        active: Ms<N>,
        with_pdf: Ms<N>,
        how: EnvSampling,
    ) -> ([F32s<N>; 3], F32s<N>) {
        let (local, cell_u, v) = self.image_coordinates(dir);
        // The texels are asked for first, so their misses are served while the density's rows
        // are found and read.
        let texels = self.footprints_lanes(cell_u, v, active);
        let pdf = if with_pdf.any() { self.pdf_at_lanes(cell_u, v, &local, with_pdf, how) } else { F32s::ZERO };
        (self.blend_lanes(&texels, active), pdf)
    }

    /// The map's local direction of each world direction, and its image coordinates: u from
    /// the first texel column's centre (see [`EnvMap::cell_u`]) and v.
    #[inline(always)]
    fn image_coordinates<const N: usize>(&self, dir: &Vec3s<N>) -> (Vec3s<N>, F32s<N>, F32s<N>) {
        let local = transform_vectors(&self.to_world.inverse, dir).normalize();
        let (u, v) = direction_to_uv(&local);
        (local, self.cell_u(u), v)
    }

    /// u measured from the first texel column's centre (texel i at u = (i + ½)/W), wrapped to
    /// [0, 1): the cells of the sampling distribution and of the bilinear lookup start there.
    #[inline(always)]
    fn cell_u<const N: usize>(&self, u: F32s<N>) -> F32s<N> {
        wrap01(u - 0.5 / self.width as f32)
    }

    /// The bilinear lookups at `cell_u` (see [`EnvMap::cell_u`]) and v in the lanes of `active`,
    /// their texels asked of the caches lane by lane before any is read (see
    /// [`crate::wide::prefetch`]): a map of f32 RGB is 1.5 MB at 512 × 256, three times this
    /// machine's L2 cache, so nearly every lane's texels are a miss, and read lane by lane the
    /// misses waited one after another (the texel loads were 8% of matpreview copper's render
    /// loop).
    #[inline(always)]
    fn footprints_lanes<const N: usize>(&self, cell_u: F32s<N>, v: F32s<N>, active: Ms<N>) -> [Footprint; N] {
        let mut out = [Footprint::default(); N];
        for i in active.lanes() {
            let f = self.footprint(cell_u.0[i], v.0[i]);
            for row in [f.row0, f.row1] {
                if f.i1 == f.i0 + 1 {
                    prefetch(&self.pixels[row + f.i0..=row + f.i1]);
                } else {
                    prefetch(&self.pixels[row + f.i0..=row + f.i0]);
                    prefetch(&self.pixels[row + f.i1..=row + f.i1]);
                }
            }
            out[i] = f;
        }
        out
    }

    /// The radiance of [`EnvMap::footprints_lanes`]' lookups, per channel.
    #[inline(always)]
    fn blend_lanes<const N: usize>(&self, footprints: &[Footprint; N], active: Ms<N>) -> [F32s<N>; 3] {
        let mut out = [F32s::ZERO; 3];
        for i in active.lanes() {
            let c = self.blend(&footprints[i]);
            [out[0].0[i], out[1].0[i], out[2].0[i]] = c.to_array();
        }
        out
    }

    /// Bilinear radiance at `cell_u` (see [`EnvMap::cell_u`]) and v in the lanes of `active`.
    #[inline(always)]
    fn radiance_at_lanes<const N: usize>(&self, cell_u: F32s<N>, v: F32s<N>, active: Ms<N>) -> [F32s<N>; 3] {
        self.blend_lanes(&self.footprints_lanes(cell_u, v, active), active)
    }

    /// Where the bilinear lookup at `cell_u` (see [`EnvMap::cell_u`]) and v reads, and its
    /// weights.
    #[inline(always)]
    fn footprint(&self, cell_u: f32, v: f32) -> Footprint {
        let (w, h) = (self.width, self.height);
        // Both are ≥ 0 (or NaN), so truncation is the floor (and needs no library call).
        let x = cell_u * w as f32;
        let y = v * (h - 1) as f32;
        let (x0, y0) = (x as usize, y as usize);
        let (fx, fy) = (x - x0 as f32, y - y0 as f32);
        let (i0, j0) = (x0.min(w - 1), y0.min(h - 1));
        // The column after the last wraps to the first (no integer division on this path).
        let i1 = if i0 + 1 == w { 0 } else { i0 + 1 };
        let j1 = (j0 + 1).min(h - 1);
        Footprint { row0: j0 * w, row1: j1 * w, i0, i1, fx, fy }
    }

    /// The bilinear blend of a lookup's four texels.
    #[inline(always)]
    fn blend(&self, f: &Footprint) -> Rgb {
        let p = |row: usize, i: usize| self.pixels[row + i];
        let (fx, fy) = (f.fx, f.fy);
        (p(f.row0, f.i0) * (1.0 - fx) + p(f.row0, f.i1) * fx) * (1.0 - fy)
            + (p(f.row1, f.i0) * (1.0 - fx) + p(f.row1, f.i1) * fx) * fy
    }

    /// A world direction drawn in proportion to luminance × sin θ, and its solid-angle density
    /// (0 when the sample hits a pole, where the density is undefined).
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        self.sample_with(u, EnvSampling::Complete)
    }

    /// [`EnvMap::sample`] with the density `how` asks for.
    pub fn sample_with(&self, u: Vec2, how: EnvSampling) -> (Vec3, f32) {
        let s = self.sample_lanes(&F32s::<1>::splat(u.x), &F32s::splat(u.y), Ms::ALL, how);
        (s.dir.lane(0), s.pdf.0[0])
    }

    /// [`EnvMap::sample`] and the radiance along the sampled direction: the one-lane instance of
    /// [`EnvMap::sample_lanes`].
    #[inline]
    pub fn sample_with_radiance(&self, u: Vec2) -> (Vec3, f32, Rgb) {
        let s = self.sample_lanes(&F32s::<1>::splat(u.x), &F32s::splat(u.y), Ms::ALL, EnvSampling::Complete);
        (s.dir.lane(0), s.pdf.0[0], lane_rgb(s.radiance))
    }

    /// One direction per lane of `active` from the numbers `(u1, u2)`, drawn with the density
    /// `how` asks for, with that density and the
    /// radiance along it, looked up at the sampled image coordinates (as Mitsuba's `envmap`
    /// does), so the direction is not mapped back to the image; equal to `radiance(dir)` up to
    /// the rounding of that round trip.
    #[inline(always)]
    pub fn sample_lanes<const N: usize>(
        &self,
        u1: &F32s<N>,
        u2: &F32s<N>,
        active: Ms<N>,
        how: EnvSampling,
    ) -> EnvSamples<N> {
        let (cell_u, cell_v, pdf_uv) = self.distribution(how).sample_lanes(u1, u2, active);
        let radiance = self.radiance_at_lanes(cell_u, cell_v, active);
        let u = wrap01(cell_u + 0.5 / self.width as f32);
        // θ = πv and φ = 2πu, as turns.
        let (cos_theta, sin_theta) = cos_sin_turn(0.5 * cell_v);
        let (cos_phi, sin_phi) = cos_sin_turn(u);
        let local = Vec3s { x: sin_theta * sin_phi, y: cos_theta, z: -(sin_theta * cos_phi) };
        let dir = transform_vectors(&self.to_world.matrix, &local).normalize();
        EnvSamples { dir, pdf: solid_angle_pdf(pdf_uv, sin_theta), radiance }
    }

    /// The density under `how` at `cell_u` and v of the local direction `local`, in the lanes
    /// of `active` (0 in the others).
    #[inline(always)]
    fn pdf_at_lanes<const N: usize>(
        &self,
        cell_u: F32s<N>,
        v: F32s<N>,
        local: &Vec3s<N>,
        active: Ms<N>,
        how: EnvSampling,
    ) -> F32s<N> {
        let pdf_uv = self.distribution(how).pdf_lanes(&cell_u, &v, active);
        let sin_theta = (1.0 - local.y * local.y).max(F32s::ZERO).sqrt();
        solid_angle_pdf(pdf_uv, sin_theta)
    }

    /// ∫ luminance dω over the whole sphere.
    pub fn luminance_integral(&self) -> f64 {
        self.luminance_integral
    }
}

/// Rows of cells between texel rows: H − 1, or one row for a single-row image.
fn cell_rows(height: usize) -> usize {
    (height - 1).max(1)
}

/// The distribution over `w × rows` cells of the non-negative `weights`; `None` if all are 0.
fn cell_distribution(weights: &[f64], w: usize, rows: usize) -> Option<Distribution2D> {
    // Normalised to the largest weight so that maps near the f32 limit keep a finite sum; a
    // cell with any weight keeps a nonzero one, however dim beside the brightest.
    let max = weights.iter().copied().fold(0.0, f64::max);
    let weights: Vec<f32> =
        weights.iter().map(|&x| if x > 0.0 { ((x / max) as f32).max(f32::MIN_POSITIVE) } else { 0.0 }).collect();
    Distribution2D::new(&weights, w, rows)
}

/// MIS compensation's cell weights: each cell's (mean corner luminance, sin θ) gives
/// max(luminance − `mean`, 0) · sin θ. Excesses within a millionth of the mean count as none:
/// they are the rounding of a mean over cells that all hold it (a constant map), not light.
fn compensated_weights(cells: &[(f64, f64)], mean: f64) -> Vec<f64> {
    cells
        .iter()
        .map(|&(l, sin_theta)| {
            let excess = l - mean;
            if excess > 1e-6 * mean {
                excess * sin_theta
            } else {
                0.0
            }
        })
        .collect()
}

/// x − ⌊x⌋ in [0, 1) per lane, for x in [−1, 2) (every caller's range: a u in [0, 1) shifted by
/// half a texel, or atan2/2π in [−½, ½]); the same operations as with `floor`, without its
/// library call on targets without SSE4.1.
#[inline(always)]
fn wrap01<const N: usize>(x: F32s<N>) -> F32s<N> {
    let f = F32s::select(x.lt(F32s::ZERO), x + 1.0, F32s::select(x.ge(F32s::ONE), x - 1.0, x));
    // x + 1 rounds to 1 for tiny negative x.
    F32s::select(f.ge(F32s::ONE), F32s::ZERO, f)
}

/// Mitsuba's lat-long coordinates (u, v) of local unit directions (see the module comment).
#[inline(always)]
fn direction_to_uv<const N: usize>(d: &Vec3s<N>) -> (F32s<N>, F32s<N>) {
    let u = inverse_trig::atan2(d.x, -d.z) / (2.0 * PI);
    let v = inverse_trig::acos(d.y.max(F32s::splat(-1.0)).min(F32s::ONE)) / PI;
    (wrap01(u), v)
}

/// p_ω = p_uv / (2π² sin θ); 0 where sin θ ≤ 0 (the poles).
#[inline(always)]
fn solid_angle_pdf<const N: usize>(pdf_uv: F32s<N>, sin_theta: F32s<N>) -> F32s<N> {
    F32s::select(sin_theta.le(F32s::ZERO), F32s::ZERO, pdf_uv / (2.0 * PI * PI * sin_theta))
}

/// `m`'s linear part applied to each lane's vector (`Mat4::transform_vector3` per lane).
#[inline(always)]
fn transform_vectors<const N: usize>(m: &Mat4, v: &Vec3s<N>) -> Vec3s<N> {
    let (a, b, c) = (m.x_axis, m.y_axis, m.z_axis);
    Vec3s {
        x: v.x * a.x + v.y * b.x + v.z * c.x,
        y: v.x * a.y + v.y * b.y + v.z * c.y,
        z: v.x * a.z + v.y * b.z + v.z * c.z,
    }
}

/// Lane 0 of three channels.
#[inline(always)]
fn lane_rgb(c: [F32s<1>; 3]) -> Rgb {
    Rgb::new(c[0].0[0], c[1].0[0], c[2].0[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uv_mapping_matches_mitsuba_axes() {
        // u = 0 looks along −z, u = ¼ along +x; v = 0 is +y.
        let c = |d: Vec3| {
            let (u, v) = direction_to_uv(&Vec3s::<1>::splat(d));
            Vec2::new(u.0[0], v.0[0])
        };
        assert!((c(Vec3::new(0.0, 0.0, -1.0)) - Vec2::new(0.0, 0.5)).length() < 1e-6);
        assert!((c(Vec3::X) - Vec2::new(0.25, 0.5)).length() < 1e-6);
        assert!(c(Vec3::Y).y.abs() < 1e-6);
    }

    #[test]
    fn texels_sit_where_mitsuba_puts_them() {
        // 4×3: column i at u = (i+½)/4, row j at v = j/2; each texel a distinct colour.
        let pixels: Vec<Rgb> = (0..12).map(|k| Rgb::new(k as f32, 1.0, 0.0)).collect();
        let map = EnvMap::new(4, 3, pixels, 1.0, Transform::IDENTITY).unwrap();
        let dir = |u: f32, v: f32| {
            let (st, ct) = (PI * v).sin_cos();
            let (sp, cp) = (2.0 * PI * u).sin_cos();
            Vec3::new(st * sp, ct, -st * cp)
        };
        assert!((map.radiance(dir(1.5 / 4.0, 0.5)).r - 5.0).abs() < 1e-4);
        // Halfway between columns 3 and 0 (wrapping) on the middle row: (7 + 4) / 2.
        assert!((map.radiance(dir(0.0, 0.5)).r - 5.5).abs() < 1e-4);
        // Top row is the pole.
        assert!((map.radiance(Vec3::Y).r - map.radiance(dir(0.125, 0.0)).r).abs() < 1e-3);
    }
}
