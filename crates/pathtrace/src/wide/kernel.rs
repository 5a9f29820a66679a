//! The wide kernel's loop over one tile: eight lanes, each tracing one camera sample at a time,
//! refilled from the tile's queue of pixel samples as paths end (see the module docs).
//!
//! Each vertex runs the phases of `integrator::path` for all live lanes together: closest hit,
//! emission found by the hit (MIS-weighted against light sampling), next-event estimation
//! (one shadow ray per lane), cosine-weighted continuation, Russian roulette.

use super::sampler::LaneSamplers;
use super::simd::{F32s, Ms, Vec3s};
use super::{warp, WideScene};
use crate::camera::Camera;
use crate::film::{PixelFilter, PixelStats};
use crate::integrator::{PathStats, Strategy};
use crate::math::{Ray, Rgb, INV_PI};
use crate::render::tile::{Tile, TileResult, WaveSamples};
use crate::sampling::Sampler;
use crate::scene::{Primitive, Scene};

/// Light-sampling shadow rays stop this fraction short of the light (as `integrator::path`).
const SHADOW_EPSILON: f32 = 1e-4;

/// What every tile of a wide render shares.
pub(crate) struct WideJob<'a> {
    pub scene: &'a Scene,
    pub wide: &'a WideScene,
    pub camera: &'a Camera,
    pub filter: &'a PixelFilter,
}

/// The tile's pixel samples, pixel by pixel (so the camera rays of a batch are neighbours).
struct Queue<'a> {
    tile: Tile,
    samples: WaveSamples<'a>,
    pixel: u32,
    next: u32,
    end: u32,
}

/// One pixel sample to start: index of the pixel in the tile, its coordinates, sample index.
struct Job {
    pixel: u32,
    x: u32,
    y: u32,
    sample: u32,
}

impl<'a> Queue<'a> {
    fn new(tile: Tile, samples: WaveSamples<'a>) -> Self {
        let mut q = Self { tile, samples, pixel: 0, next: 0, end: 0 };
        q.enter_pixel();
        q
    }

    fn enter_pixel(&mut self) {
        if self.pixel < self.tile.w * self.tile.h {
            let (x, y) = self.coordinates();
            let (first, count) = self.samples.range(x, y);
            self.next = first;
            self.end = first + count;
        }
    }

    fn coordinates(&self) -> (u32, u32) {
        (self.tile.x0 + self.pixel % self.tile.w, self.tile.y0 + self.pixel / self.tile.w)
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<Job> {
        while self.next >= self.end {
            if self.pixel >= self.tile.w * self.tile.h {
                return None;
            }
            self.pixel += 1;
            self.enter_pixel();
        }
        if self.pixel >= self.tile.w * self.tile.h {
            return None;
        }
        let (x, y) = self.coordinates();
        let sample = self.next;
        self.next += 1;
        Some(Job { pixel: self.pixel, x, y, sample })
    }
}

/// The state of `N` paths (structure of arrays; lanes outside `active` hold stale values).
struct Paths<const N: usize> {
    active: Ms<N>,
    origin: Vec3s<N>,
    dir: Vec3s<N>,
    beta: [F32s<N>; 3],
    radiance: [F32s<N>; 3],
    /// The previous vertex and the solid-angle pdf of the direction sampled there.
    prev_p: Vec3s<N>,
    prev_pdf: F32s<N>,
    /// The direction came from the camera: emission found counts in full.
    prev_specular: Ms<N>,
    /// Pixel-filter weight of the camera sample.
    filter_weight: F32s<N>,
    segments: [u32; N],
    pixel: [u32; N],
}

/// The hit points of `N` rays.
struct Surfaces<const N: usize> {
    hit: Ms<N>,
    p: Vec3s<N>,
    n_geometric: Vec3s<N>,
    n_shading: Vec3s<N>,
    material: [u32; N],
    light: [u32; N],
}

impl<const N: usize> Surfaces<N> {
    /// No lane has hit anything (yet).
    fn none() -> Self {
        Self {
            hit: Ms::NONE,
            p: Vec3s::default(),
            n_geometric: Vec3s::default(),
            n_shading: Vec3s::default(),
            material: [0; N],
            light: [Primitive::NO_LIGHT; N],
        }
    }
}

/// Where finished samples go.
struct Output {
    pixels: Vec<PixelStats>,
    stats: PathStats,
    dropped: u64,
}

impl<const N: usize> Paths<N> {
    fn new() -> Self {
        Self {
            active: Ms::default(),
            origin: Vec3s::default(),
            dir: Vec3s::default(),
            beta: [F32s::default(); 3],
            radiance: [F32s::default(); 3],
            prev_p: Vec3s::default(),
            prev_pdf: F32s::default(),
            prev_specular: Ms::default(),
            filter_weight: F32s::default(),
            segments: [0; N],
            pixel: [0; N],
        }
    }

    fn start(&mut self, i: usize, job: &Job, ray: Ray, filter_weight: f32) {
        self.active.0[i] = u32::MAX;
        self.origin.set(i, ray.origin);
        self.dir.set(i, ray.dir);
        for c in 0..3 {
            self.beta[c].0[i] = 1.0;
            self.radiance[c].0[i] = 0.0;
        }
        self.prev_p.set(i, ray.origin);
        self.prev_pdf.0[i] = 0.0;
        self.prev_specular.0[i] = u32::MAX;
        self.filter_weight.0[i] = filter_weight;
        self.segments[i] = 1;
        self.pixel[i] = job.pixel;
    }

    /// Ends lane `i`'s path: its estimate goes to its pixel (non-finite ones are dropped).
    fn finish(&mut self, i: usize, out: &mut Output) {
        self.active.0[i] = 0;
        let w = self.filter_weight.0[i];
        let l = Rgb::new(self.radiance[0].0[i] * w, self.radiance[1].0[i] * w, self.radiance[2].0[i] * w);
        if l.is_finite() {
            out.pixels[self.pixel[i] as usize].add(l);
        } else {
            out.dropped += 1;
        }
    }

    /// Ends every lane of `mask`.
    fn finish_all(&mut self, mask: Ms<N>, out: &mut Output) {
        for i in mask.lanes() {
            self.finish(i, out);
        }
    }
}

/// Renders the wave's samples of every pixel in `tile` with the wide kernel. Each pixel
/// sample's random numbers come from a copy of `proto` started at (pixel, sample index), as in
/// the scalar kernel, so the result does not depend on the thread or the lane.
#[inline(always)]
pub(crate) fn render_tile_wide<const N: usize>(
    job: &WideJob,
    proto: &Sampler,
    tile: Tile,
    samples: WaveSamples,
) -> TileResult {
    let mut samplers = LaneSamplers::<N>::new(proto);
    let mut out = Output {
        pixels: vec![PixelStats::default(); (tile.w * tile.h) as usize],
        stats: PathStats::default(),
        dropped: 0,
    };
    let mut queue = Queue::new(tile, samples);
    let mut paths = Paths::<N>::new();
    let max_depth = job.wide.settings.max_depth;
    loop {
        for i in (!paths.active).lanes() {
            let Some(next) = queue.pop() else { break };
            // As render/tile.rs: the filter picks the point in the pixel and weights it by f/pdf.
            let fs = job.filter.sample(samplers.start(i, next.x, next.y, next.sample));
            let ray = job.camera.generate_ray(next.x, next.y, fs.jitter);
            out.stats.camera_rays += 1;
            paths.start(i, &next, ray, fs.weight);
            if max_depth == 0 {
                paths.finish(i, &mut out);
            }
        }
        if !paths.active.any() {
            break;
        }
        vertex(job, &mut paths, &mut samplers, &mut out);
    }
    TileResult { tile, pixels: out.pixels, stats: out.stats, dropped: out.dropped }
}

/// One path vertex for every active lane.
#[inline(always)]
fn vertex<const N: usize>(job: &WideJob, paths: &mut Paths<N>, samplers: &mut LaneSamplers<N>, out: &mut Output) {
    let WideJob { scene, wide, .. } = *job;
    let settings = &wide.settings;
    let lights = &scene.lights;
    let max_depth = if settings.max_depth < 0 { u32::MAX } else { settings.max_depth as u32 };

    // ---- Closest hits; escaping paths end (wide scenes have no environment) --------------
    let s = intersect(job, paths);
    paths.finish_all(paths.active & !s.hit, out);
    let mut alive = paths.active;
    let wo = paths.dir.neg();

    // ---- Emission found by the hit (rare: lane by lane) ---------------------------------
    for i in (alive & Ms::from_fn(|i| s.light[i] != Primitive::NO_LIGHT)).lanes() {
        let Some(light) = lights.get(s.light[i]) else { continue };
        let le = light.emitted(s.n_geometric.lane(i), wo.lane(i));
        if le.is_black() {
            continue;
        }
        let weight = if paths.prev_specular.lane(i) {
            1.0
        } else {
            let pdf_light = lights.pdf_hit(s.light[i], paths.prev_p.lane(i), s.p.lane(i), s.n_geometric.lane(i));
            settings.strategy.mis_weight(paths.prev_pdf.0[i], pdf_light)
        };
        for (c, e) in le.to_array().into_iter().enumerate() {
            paths.radiance[c].0[i] += paths.beta[c].0[i] * e * weight;
        }
    }

    // ---- Depth limit and black surfaces end the path; albedos of the rest ------------------
    let mut albedo = [F32s::<N>::ZERO; 3];
    for i in alive.lanes() {
        match wide.albedo.get(s.material[i] as usize).copied().flatten() {
            Some(a) if paths.segments[i] < max_depth => {
                [albedo[0].0[i], albedo[1].0[i], albedo[2].0[i]] = [a.r, a.g, a.b];
            }
            _ => {
                paths.finish(i, out);
                alive.0[i] = 0;
            }
        }
    }
    if !alive.any() {
        return;
    }

    // Lambertian surfaces are two-sided: face the normals towards the viewer.
    let back = s.n_geometric.dot(&wo).lt(F32s::<N>::ZERO);
    let n_g = Vec3s::<N>::select(back, &s.n_geometric.neg(), &s.n_geometric);
    let n_s = Vec3s::<N>::select(back, &s.n_shading.neg(), &s.n_shading);
    let wo_z = n_s.dot(&wo);
    // offset_ray_origin's scale; both rays leave on n_g's side (checked below).
    let offset = n_g.scale((s.p.max_abs() + 1.0) * 1e-4);
    let origin = s.p.add(&offset);

    // ---- Next-event estimation ----------------------------------------------------------
    let u_select = samplers.next_1d(alive);
    let (u1, u2) = samplers.next_2d(alive);
    let ls = wide.lights.sample(lights, &s.p, alive, &u_select, u1, u2);
    let cos_i = n_s.dot(&ls.wi);
    let zero = F32s::<N>::ZERO;
    let lit = ls.valid & alive & wo_z.gt(zero) & cos_i.gt(zero) & n_g.dot(&ls.wi).gt(zero);
    if lit.any() {
        let to_light = ls.point.sub(&origin);
        let dist = to_light.length();
        let dir = to_light.scale(1.0 / dist);
        let blocked = occluded(job, &origin, &dir, lit, dist * (1.0 - SHADOW_EPSILON));
        out.stats.shadow_rays += lit.bitmask().count_ones() as u64;
        let pdf_bsdf = cos_i * INV_PI;
        let w = mis_weight(settings.strategy, ls.pdf, pdf_bsdf);
        // f·cos / pdf with f = albedo/π (the albedo is applied per channel below).
        let factor = F32s::<N>::select(lit & !blocked, cos_i * INV_PI * w / ls.pdf, zero);
        for c in 0..3 {
            paths.radiance[c] = paths.radiance[c] + paths.beta[c] * albedo[c] * ls.radiance[c] * factor;
        }
    }

    // ---- Continuation: cosine-weighted hemisphere ------------------------------------------
    // The lobe choice the scalar loop draws (one lobe here: unused, but drawn so every later
    // dimension matches the scalar kernel's).
    let _ = samplers.next_1d(alive);
    let (u1, u2) = samplers.next_2d(alive);
    let local = warp::square_to_cosine_hemisphere(u1, u2);
    let wi = warp::to_world(&n_s, &local);
    // Reflection must stay on the viewer's side of the true surface (shading normals can
    // disagree with it).
    let goes_on = alive & wo_z.gt(zero) & local.z.gt(zero) & n_g.dot(&wi).gt(zero);
    paths.finish_all(alive & !goes_on, out);
    alive = goes_on;
    for c in 0..3 {
        paths.beta[c] = paths.beta[c] * albedo[c];
    }

    // ---- Russian roulette (Lambertian paths never refract: no η² to undo) -------------------
    let roulette = alive & Ms::from_fn(|i| paths.segments[i] >= settings.rr_depth);
    let u_survive = if roulette.any() { samplers.next_1d(roulette) } else { F32s::ZERO };
    for i in 0..N {
        if !roulette.lane(i) {
            continue;
        }
        let q = paths.beta[0].0[i].max(paths.beta[1].0[i]).max(paths.beta[2].0[i]).min(0.95);
        if u_survive.0[i] >= q {
            paths.finish(i, out);
            alive.0[i] = 0;
        } else {
            for c in 0..3 {
                paths.beta[c].0[i] /= q;
            }
        }
    }

    // ---- Next segment ------------------------------------------------------------------
    paths.prev_p = Vec3s::<N>::select(alive, &s.p, &paths.prev_p);
    paths.prev_pdf = F32s::<N>::select(alive, local.z * INV_PI, paths.prev_pdf);
    paths.prev_specular = paths.prev_specular & !alive;
    paths.origin = Vec3s::<N>::select(alive, &origin, &paths.origin);
    paths.dir = Vec3s::<N>::select(alive, &wi, &paths.dir);
    for i in 0..N {
        paths.segments[i] += alive.0[i] & 1;
    }
    out.stats.extension_rays += alive.bitmask().count_ones() as u64;
}

/// The MIS weight of a light sample (density `pdf_f`) against the material's density `pdf_g`,
/// per lane: `strategy.mis_weight` as 1/(1 + (g/f)^β), which cannot overflow.
#[inline(always)]
fn mis_weight<const N: usize>(strategy: Strategy, pdf_f: F32s<N>, pdf_g: F32s<N>) -> F32s<N> {
    let r = pdf_g / pdf_f;
    let r = if strategy == Strategy::MisBalance { r } else { r * r };
    1.0 / (1.0 + r)
}

/// Closest hits of the active lanes' rays.
#[inline(always)]
fn intersect<const N: usize>(job: &WideJob, paths: &Paths<N>) -> Surfaces<N> {
    let active = paths.active;
    if let Some(geometry) = &job.wide.geometry {
        let hits = geometry.intersect(&paths.origin, &paths.dir, active, F32s::<N>::splat(f32::INFINITY));
        let mut s = Surfaces::none();
        s.p = paths.origin.add(&paths.dir.scale(hits.t));
        for i in 0..N {
            if active.lane(i) && hits.polygon[i] != u32::MAX {
                let (n, material, light) = geometry.polygon(hits.polygon[i]);
                s.hit.0[i] = u32::MAX;
                s.n_geometric.set(i, n);
                s.material[i] = material;
                s.light[i] = light;
            }
        }
        s.n_shading = s.n_geometric;
        return s;
    }
    // Larger scenes: the BVH, one lane at a time.
    let mut s = Surfaces::none();
    for i in 0..N {
        if !active.lane(i) {
            continue;
        }
        let ray = Ray::new(paths.origin.lane(i), paths.dir.lane(i));
        if let Some(hit) = job.scene.intersect(&ray, f32::INFINITY) {
            let it = job.scene.interaction(&ray, &hit);
            s.hit.0[i] = u32::MAX;
            s.p.set(i, it.surface.p);
            s.n_geometric.set(i, it.surface.n_geometric);
            s.n_shading.set(i, it.surface.n_shading);
            s.material[i] = it.material_id;
            s.light[i] = it.light;
        }
    }
    s
}

/// Lanes of `active` whose shadow ray is blocked before `t_max`.
#[inline(always)]
fn occluded<const N: usize>(job: &WideJob, origin: &Vec3s<N>, dir: &Vec3s<N>, active: Ms<N>, t_max: F32s<N>) -> Ms<N> {
    if let Some(geometry) = &job.wide.geometry {
        return geometry.occluded(origin, dir, active, t_max);
    }
    Ms::<N>::from_fn(|i| active.lane(i) && job.scene.occluded(&Ray::new(origin.lane(i), dir.lane(i)), t_max.0[i]))
}
