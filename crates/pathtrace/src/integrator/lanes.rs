//! The state of a group of `N` paths, one per SIMD lane (structure of arrays), and where their
//! finished estimates go.
//!
//! `N` is 16 with AVX2, 8 in the portable build, 32 with AVX-512, and 1 for the one-lane
//! instance of the same estimator (`Kernel::Scalar`, kept for debugging and tests).

use crate::film::{small_terms, FeaturePixel, FeatureSample, PixelFilter, PixelStats, SplatBlock, SMALL_SAMPLE};
use crate::integrator::PathStats;
use crate::math::{Rgb, Vec2, Vec3, Vec4};
use crate::medium::MediumId;
use crate::scene::{Interaction, Primitive};
use crate::shape::{unit_normals, SurfacePoint};
use crate::wide::simd::{rgb_black, F32s, Ms, Vec3s};

/// The state of `N` paths (lanes outside `active` hold stale values).
pub(crate) struct Paths<const N: usize> {
    pub active: Ms<N>,
    pub origin: Vec3s<N>,
    pub dir: Vec3s<N>,
    pub beta: [F32s<N>; 3],
    pub radiance: [F32s<N>; 3],
    /// Product of η² over the refractions so far, undone by Russian roulette (pbrt-v4 §13.4.3).
    pub eta_scale: F32s<N>,
    /// The previous vertex and the solid-angle pdf of the direction sampled there.
    pub prev_p: Vec3s<N>,
    pub prev_pdf: F32s<N>,
    /// The direction came from a Dirac lobe or the camera: emission found counts in full.
    pub prev_specular: Ms<N>,
    /// Where in its pixel each lane's camera sample is (`[0, 1)²` from the corner), for
    /// splatting filters (`film/splat.rs`): x and y.
    pub jitter: [F32s<N>; 2],
    /// Path segments so far (Mitsuba's depth convention).
    pub segments: [u32; N],
    /// The medium each lane's ray travels in (`MediumId::NONE`: vacuum; always so in scenes
    /// without media).
    pub medium: [u32; N],
    /// The colour channel whose free-flight density the lane's path follows (chosen at its first
    /// medium event; [`Paths::NO_CHANNEL`] before).
    pub hero: [u8; N],
    /// Per channel, the density of the path's medium events had that channel been followed,
    /// relative to the followed one's (pbrt-v4's r_u); `beta` already holds the throughput
    /// divided by their average (`integrator::media`). Per channel, over the lanes.
    pub channel_density: [F32s<N>; 3],
    /// The pixel (index in the tile) each lane's sample belongs to.
    pub pixel: [u32; N],
    /// Lanes whose feature sample still waits for its first non-specular hit (never set when
    /// the render records no features, so the estimator skips them at one test per vertex).
    pub feature_pending: Ms<N>,
    /// Each lane's feature sample so far (`integrator::features`).
    pub feature: [FeatureSample; N],
    /// Product of the albedos of the specular surfaces the lane's path has followed.
    pub feature_tint: [Rgb; N],
}

/// Where finished samples go.
pub(crate) struct Output {
    pub pixels: Vec<PixelStats>,
    pub stats: PathStats,
    pub dropped: u64,
    /// Per-pixel feature sums, when the render records features.
    pub features: Option<Vec<FeaturePixel>>,
    /// The tile's splatted sums, when the filter is wider than the pixel.
    pub splat: Option<TileSplat>,
}

/// Where a tile's samples are splatted: its halo block, and what places a tile pixel on the film.
pub(crate) struct TileSplat {
    pub block: SplatBlock,
    pub filter: PixelFilter,
    /// The tile's corner and width, to turn a tile pixel index into film coordinates.
    pub x0: u32,
    pub y0: u32,
    pub w: u32,
}

impl TileSplat {
    /// Splats a finished sample of tile pixel `pixel` at `jitter` within it.
    #[inline(always)]
    pub fn add(&mut self, pixel: u32, jitter: Vec2, l: Rgb) {
        let (x, y) = (self.x0 + pixel % self.w, self.y0 + pixel / self.w);
        self.block.splat(&self.filter, x, y, jitter, l);
    }
}

impl<const N: usize> Paths<N> {
    /// No channel chosen yet.
    pub const NO_CHANNEL: u8 = u8::MAX;

    #[inline(always)]
    pub fn new() -> Self {
        Self {
            active: Ms::default(),
            origin: Vec3s::default(),
            dir: Vec3s::default(),
            beta: [F32s::default(); 3],
            radiance: [F32s::default(); 3],
            eta_scale: F32s::default(),
            prev_p: Vec3s::default(),
            prev_pdf: F32s::default(),
            prev_specular: Ms::default(),
            jitter: [F32s::ZERO; 2],
            segments: [0; N],
            medium: [MediumId::NONE; N],
            hero: [Self::NO_CHANNEL; N],
            channel_density: [F32s::ONE; 3],
            pixel: [0; N],
            feature_pending: Ms::default(),
            feature: [FeatureSample::default(); N],
            feature_tint: [Rgb::BLACK; N],
        }
    }

    /// Starts camera paths in the lanes of `fresh`: lane `i` for tile pixel `pixel[i]`, its ray
    /// from `origin` along `dir` in `medium`, at `jitter` in its pixel; `features`: the paths
    /// record feature samples. The fields are set for the whole group at once, as SIMD blends
    /// (lane by lane, the twenty-odd stores per lane were 10% of the teapot's render; the last
    /// few, the jitter and the media fields, were still 7% of the instructions of a frame of
    /// camera rays that miss everything).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn start(
        &mut self,
        fresh: Ms<N>,
        pixel: &[u32; N],
        origin: &Vec3s<N>,
        dir: &Vec3s<N>,
        medium: u32,
        jitter: &[F32s<N>; 2],
        features: bool,
    ) {
        self.active = self.active | fresh;
        self.origin = Vec3s::select(fresh, origin, &self.origin);
        self.dir = Vec3s::select(fresh, dir, &self.dir);
        for c in 0..3 {
            self.beta[c] = F32s::select(fresh, F32s::ONE, self.beta[c]);
            self.radiance[c] = F32s::select(fresh, F32s::ZERO, self.radiance[c]);
        }
        self.eta_scale = F32s::select(fresh, F32s::ONE, self.eta_scale);
        self.prev_p = Vec3s::select(fresh, origin, &self.prev_p);
        self.prev_pdf = F32s::select(fresh, F32s::ZERO, self.prev_pdf);
        self.prev_specular = self.prev_specular | fresh;
        for (old, new) in self.jitter.iter_mut().zip(jitter) {
            *old = F32s::select(fresh, *new, *old);
        }
        for c in 0..3 {
            self.channel_density[c] = F32s::select(fresh, F32s::ONE, self.channel_density[c]);
        }
        // One index walks five arrays (the mask and four fields) in step.
        #[allow(clippy::needless_range_loop)]
        for i in 0..N {
            // Blended through the lane mask (all bits set or clear), so these compile to SIMD
            // blends too (`if` per lane compiled to a branch per lane).
            let new = fresh.0[i];
            self.segments[i] = (1 & new) | (self.segments[i] & !new);
            self.medium[i] = (medium & new) | (self.medium[i] & !new);
            self.pixel[i] = (pixel[i] & new) | (self.pixel[i] & !new);
            self.hero[i] = (Self::NO_CHANNEL & new as u8) | (self.hero[i] & !new as u8);
        }
        if features {
            for i in fresh.lanes() {
                self.feature_pending.0[i] = u32::MAX;
                self.feature[i] = FeatureSample::default();
                self.feature_tint[i] = Rgb::splat(1.0);
            }
        }
    }

    /// Lane `i`'s throughput.
    #[inline(always)]
    pub fn beta(&self, i: usize) -> Rgb {
        Rgb::new(self.beta[0].0[i], self.beta[1].0[i], self.beta[2].0[i])
    }

    /// Adds `throughput × l` to lane `i`'s estimate.
    #[inline(always)]
    pub fn add_weighted(&mut self, i: usize, l: Rgb) {
        for (c, v) in l.to_array().into_iter().enumerate() {
            self.radiance[c].0[i] += self.beta[c].0[i] * v;
        }
    }

    /// Ends lane `i`'s path: its estimate (and feature sample, if recorded) goes to its pixel
    /// (non-finite estimates are dropped with their feature sample, and counted).
    #[inline(always)]
    pub fn finish(&mut self, i: usize, out: &mut Output) {
        self.active.0[i] = 0;
        self.feature_pending.0[i] = 0;
        let l = Rgb::new(self.radiance[0].0[i], self.radiance[1].0[i], self.radiance[2].0[i]);
        if l.is_finite() {
            out.pixels[self.pixel[i] as usize].add(l);
            if let Some(features) = &mut out.features {
                features[self.pixel[i] as usize].add(&self.feature[i], 1.0);
            }
            if let Some(splat) = &mut out.splat {
                splat.add(self.pixel[i], Vec2::new(self.jitter[0].0[i], self.jitter[1].0[i]), l);
            }
        } else {
            out.dropped += 1;
        }
    }

    /// Marks the lanes of `lanes` ended, their estimates taken.
    #[inline(always)]
    fn end(&mut self, lanes: Ms<N>) {
        self.active = self.active & !lanes;
        self.feature_pending = self.feature_pending & !lanes;
    }

    /// Calls `add(pixel, same)` for the lanes `same` of `lanes` that sample the first lane's
    /// pixel, then for those of the next pixel among the rest, and returns the lanes left for
    /// lane-by-lane adds. Two pixels: a group started as a run takes one pixel's samples, or,
    /// when a wave's count is not a multiple of the lanes (15 samples per pixel in 16 lanes),
    /// the end of one pixel's and the start of the next's. Lane by lane, that second case made
    /// `finish_all` 9.9% of the teapot's render at 16 spp, against 2.6% at 17 (docs/benchmarks.md).
    #[inline(always)]
    fn by_pixel(&self, lanes: Ms<N>, mut add: impl FnMut(u32, Ms<N>)) -> Ms<N> {
        let mut left = lanes;
        for _ in 0..2 {
            if !left.any() {
                break;
            }
            let pixel = self.pixel[left.bitmask().trailing_zeros() as usize];
            let same = left & Ms::from_fn(|i| self.pixel[i] == pixel);
            add(pixel, same);
            left = left & !same;
        }
        left
    }

    /// Ends every lane of `mask`, as [`Paths::finish`] does each.
    #[inline(always)]
    pub fn finish_all(&mut self, mask: Ms<N>, out: &mut Output) {
        let mut rest = mask;
        // Black estimates (a camera ray that left an unlit scene, a path that found no light;
        // 81% of the teapot's samples) only count towards their pixel when no feature sample
        // or splatting filter takes them too: found for the group at once, they skip the
        // lane-by-lane checks (which were about a tenth of an empty frame's render).
        if out.features.is_none() && out.splat.is_none() {
            let black = mask & rgb_black(&self.radiance);
            if black.any() {
                let pixels = &mut *out.pixels;
                // The closures are inlined by force, as the hit callback is (`path.rs`): left
                // to LLVM, the small terms' one was compiled out of line for baseline x86-64,
                // summing the group's 64-bit terms two at a time (3% of a teapot's profile).
                let left = self.by_pixel(
                    black,
                    #[inline(always)]
                    |pixel, same| {
                        pixels[pixel as usize].add_blacks(same.bitmask().count_ones());
                    },
                );
                for i in left.lanes() {
                    pixels[self.pixel[i] as usize].add_black();
                }
                self.end(black);
                rest = rest & !black;
            }
            // Nearly all other estimates are small (below SMALL_SAMPLE in every channel, so
            // finite): their fixed-point terms are converted in SIMD (lane by lane this was 4%
            // of the teapot's time), and when the lanes share a pixel (a pixel's consecutive
            // samples, started together) summed before one addition to it.
            let limit = F32s::splat(SMALL_SAMPLE);
            let small = rest
                & self.radiance[0].abs().lt(limit)
                & self.radiance[1].abs().lt(limit)
                & self.radiance[2].abs().lt(limit);
            if small.any() {
                let (mut sum, mut sum_sq) = ([[0i64; N]; 3], [[0i64; N]; 3]);
                for c in 0..3 {
                    // Other lanes convert zero (their values may be outside `small_terms`'s range).
                    let x = F32s::select(small, self.radiance[c], F32s::ZERO);
                    for i in 0..N {
                        (sum[c][i], sum_sq[c][i]) = small_terms(f64::from(x.0[i]));
                    }
                }
                let pixels = &mut *out.pixels;
                let left = self.by_pixel(
                    small,
                    #[inline(always)]
                    |pixel, same| {
                        let [s0, s1, s2] = &sum;
                        let [q0, q1, q2] = &sum_sq;
                        pixels[pixel as usize].add_small_terms(
                            same.bitmask().count_ones(),
                            [masked_sum(s0, same), masked_sum(s1, same), masked_sum(s2, same)],
                            [masked_sum(q0, same), masked_sum(q1, same), masked_sum(q2, same)],
                        );
                    },
                );
                for i in left.lanes() {
                    pixels[self.pixel[i] as usize].add_small_terms(
                        1,
                        sum.map(|lanes| lanes[i]),
                        sum_sq.map(|lanes| lanes[i]),
                    );
                }
                self.end(small);
                rest = rest & !small;
            }
        }
        for i in rest.lanes() {
            self.finish(i, out);
        }
    }
}

/// The sum of the lanes of `lanes` set in `mask`.
#[inline(always)]
fn masked_sum<const N: usize>(lanes: &[i64; N], mask: Ms<N>) -> i64 {
    (0..N).map(|i| if mask.lane(i) { lanes[i] } else { 0 }).sum()
}

/// The hit points of `N` rays.
pub(crate) struct Surfaces<const N: usize> {
    pub hit: Ms<N>,
    pub p: Vec3s<N>,
    pub n_geometric: Vec3s<N>,
    pub n_shading: Vec3s<N>,
    /// Texture coordinates and ∂p/∂u, for textures and anisotropic frames (not set where the
    /// brute-force intersector found the hit: it serves only scenes that need neither).
    pub uv: [Vec2; N],
    pub dpdu: [Vec3; N],
    pub dpdv: [Vec3; N],
    /// The mesh's own tangent and bitangent sign (zero where it has none).
    pub vertex_tangent: [Vec4; N],
    pub material: [u32; N],
    pub light: [u32; N],
}

impl<const N: usize> Surfaces<N> {
    /// No lane has hit anything (yet).
    #[inline(always)]
    pub fn none() -> Self {
        Self {
            hit: Ms::NONE,
            p: Vec3s::default(),
            n_geometric: Vec3s::default(),
            n_shading: Vec3s::default(),
            uv: [Vec2::ZERO; N],
            dpdu: [Vec3::ZERO; N],
            dpdv: [Vec3::ZERO; N],
            vertex_tangent: [Vec4::ZERO; N],
            material: [0; N],
            light: [Primitive::NO_LIGHT; N],
        }
    }

    /// No lane has hit anything, for the group's next vertex. Only what is read of lanes
    /// without a hit is reset: the hit mask and the lights (the emission step reads every live
    /// lane's). The rest keeps the last hit's values, which are read only where a lane hits
    /// again, or computed on in lanes whose results are then dropped. Zeroing all of it at every
    /// vertex (3 KB with 32 lanes) was most of the 2.5% `memset` in the zoomed teapot's
    /// profile (docs/benchmarks.md, "Surfaces kept from vertex to vertex").
    #[inline(always)]
    pub fn clear(&mut self) {
        self.hit = Ms::NONE;
        self.light = [Primitive::NO_LIGHT; N];
    }

    /// Records lane `i`'s hit: the surface, material and light of `it`.
    #[inline(always)]
    pub fn set_hit(&mut self, i: usize, it: &Interaction) {
        self.hit.0[i] = u32::MAX;
        self.p.set(i, it.surface.p);
        self.n_geometric.set(i, it.surface.n_geometric);
        self.n_shading.set(i, it.surface.n_shading);
        self.uv[i] = it.surface.uv;
        self.dpdu[i] = it.surface.dpdu;
        self.dpdv[i] = it.surface.dpdv;
        self.vertex_tangent[i] = it.surface.vertex_tangent;
        self.material[i] = it.material_id;
        self.light[i] = it.light;
    }

    /// The normals of `lanes` made unit length as a triangle's are
    /// ([`unit_normals`]), for the group's mesh hits recorded before normalising.
    #[inline(always)]
    pub fn normalise(&mut self, lanes: Ms<N>) {
        let (n, s) = unit_normals(&self.n_geometric, &self.n_shading);
        self.n_geometric = Vec3s::select(lanes, &n, &self.n_geometric);
        self.n_shading = Vec3s::select(lanes, &s, &self.n_shading);
    }

    /// Lane `i`'s hit as the shapes describe it.
    #[inline(always)]
    pub fn surface(&self, i: usize) -> SurfacePoint {
        SurfacePoint {
            p: self.p.lane(i),
            n_geometric: self.n_geometric.lane(i),
            n_shading: self.n_shading.lane(i),
            uv: self.uv[i],
            dpdu: self.dpdu[i],
            dpdv: self.dpdv[i],
            vertex_tangent: self.vertex_tangent[i],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn output(pixels: usize) -> Output {
        Output {
            pixels: vec![PixelStats::default(); pixels],
            stats: PathStats::default(),
            dropped: 0,
            features: None,
            splat: None,
        }
    }

    /// Finishing a group at once (black lanes counted together, small estimates converted
    /// together and, for the lanes of the first two pixels, summed before they are added)
    /// gives each pixel what finishing its lanes one by one gives, and ends exactly the lanes
    /// asked for: lanes of one pixel, of two (a run across pixels), of three in runs, mixed.
    #[test]
    fn finishing_a_group_is_finishing_each_lane() {
        const N: usize = 16;
        let layouts: [fn(usize) -> u32; 4] =
            [|i| (i % 5) as u32, |_| 2, |i| 3 + u32::from(i >= 11), |i| (i / 7) as u32];
        for pixel_of in layouts {
            let mut paths = Paths::<N>::new();
            paths.active = Ms::ALL;
            for i in 0..N {
                paths.pixel[i] = pixel_of(i);
                let value = match i % 6 {
                    0 => 0.0,
                    1 => -0.0,
                    2 => 0.25 * i as f32,
                    3 => f32::NAN,
                    4 => 40.0 + i as f32,
                    _ => -0.1 * i as f32,
                };
                // Lane 6 is black in two channels only, lane 8 large in one only; lane 9 is
                // not asked to finish.
                for c in 0..3 {
                    paths.radiance[c].0[i] = match (i, c) {
                        (6, 1) => 1.5,
                        (8, 2) => 1e20,
                        _ => value,
                    };
                }
            }
            let mask = Ms::from_fn(|i| i != 9);
            let mut one_by_one = paths.clone_for_test();
            let (mut together, mut each) = (output(5), output(5));
            paths.finish_all(mask, &mut together);
            for i in mask.lanes() {
                one_by_one.finish(i, &mut each);
            }
            assert_eq!(together.pixels, each.pixels);
            assert_eq!(together.dropped, each.dropped);
            assert_eq!(paths.active.bitmask(), 1 << 9);
            assert_eq!(one_by_one.active.bitmask(), 1 << 9);
        }
    }

    impl<const N: usize> Paths<N> {
        /// The fields `finish` reads and writes, copied.
        fn clone_for_test(&self) -> Self {
            let mut p = Paths::new();
            p.active = self.active;
            p.radiance = self.radiance;
            p.pixel = self.pixel;
            p
        }
    }
}
