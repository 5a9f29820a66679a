//! BVH leaves: their quads and triangles packed four to a SIMD packet (lanes = primitives, as
//! in Embree's "quad4"/"triangle4" leaves), other shapes kept as indices tested one by one.

use super::group_hits::GroupHits;
use super::lanes::{lane_of, HitL, HitX4, RayX4, Rays};
use super::quad4::Quad4;
use super::tri4::Tri4;
use super::wide::RayInterval;
use super::PrimitiveSet;
use crate::math::Ray;
use crate::shape::{PrimHit, Quad, Triangle};
use crate::wide::simd::{F32s, Vec3s};

/// How a primitive is stored in a leaf.
#[derive(Clone, Copy, Debug)]
pub enum Packable {
    Quad(Quad),
    Triangle(Triangle),
    /// Tested with [`PrimitiveSet::intersect_one`].
    No,
}

/// A packet and the primitive index of each lane (unused lanes repeat a valid index; they
/// never hit).
#[derive(Clone, Copy, Debug)]
struct Packed<G> {
    geom: G,
    ids: [u32; 4],
}

/// A four-lane primitive packet (quads or triangles).
trait Packet {
    /// One ray against the packet's primitives.
    fn hits(&self, rx4: &RayX4, t_min: f32, t_max: f32) -> HitX4;
    /// Primitive `k` of the packet against a group of rays (the same bits per ray).
    fn hits_rays<const N: usize>(&self, k: usize, rays: &Rays<N>, t_min: f32, t_max: F32s<N>) -> HitL<F32s<N>>;
    /// A bitmask of the packet's primitives that some ray of a bounded group may hit (every
    /// primitive whose test [`Packet::hits_rays`] passes for some ray of the group is in it).
    fn may_hit(&self, group: &GroupBounds) -> u32;
}

/// A coherent group's rays bounded together ([`RayInterval`]), with their range: `t_min`, and
/// the least and greatest `t_far` of the rays. A leaf's triangles are tested against the bounds
/// before they are tested against each ray: camera rays of one pixel, or shadow rays from its
/// points to one light, pass through one or two of a leaf's four triangles, and a triangle no
/// ray can hit costs a box test on four lanes instead of its test on every ray of the group.
#[derive(Clone, Copy, Debug)]
pub(super) struct GroupBounds<'a> {
    pub rays: &'a RayInterval,
    pub t_min: f32,
    pub far: (f32, f32),
}

impl Packet for Quad4 {
    #[inline(always)]
    fn hits(&self, rx4: &RayX4, t_min: f32, t_max: f32) -> HitX4 {
        self.intersect(rx4, t_min, t_max)
    }
    #[inline(always)]
    fn hits_rays<const N: usize>(&self, k: usize, rays: &Rays<N>, t_min: f32, t_max: F32s<N>) -> HitL<F32s<N>> {
        self.intersect_rays(k, rays, t_min, t_max)
    }
    /// Quads are not bounded here: every quad may be hit.
    #[inline(always)]
    fn may_hit(&self, _group: &GroupBounds) -> u32 {
        0b1111
    }
}

impl Packet for Tri4 {
    #[inline(always)]
    fn hits(&self, rx4: &RayX4, t_min: f32, t_max: f32) -> HitX4 {
        self.intersect(rx4, t_min, t_max)
    }
    #[inline(always)]
    fn hits_rays<const N: usize>(&self, k: usize, rays: &Rays<N>, t_min: f32, t_max: F32s<N>) -> HitL<F32s<N>> {
        self.intersect_rays(k, rays, t_min, t_max)
    }
    /// The triangles' padded boxes against the group's bounds: a ray that hits a triangle
    /// passes its box's slab test ([`Tri4::padded_bounds`]), and a box the bounds say no ray
    /// hits fails every ray's slab test ([`RayInterval::boxes_hit`]).
    #[inline(always)]
    fn may_hit(&self, group: &GroupBounds) -> u32 {
        group.rays.boxes_hit(&self.padded_bounds(), group.t_min, group.far.0, group.far.1).0.bitmask()
    }
}

/// Keeps `hit` on primitive `id` if it comes before `best` in one fixed order — nearer, or as
/// near and a lower primitive index — and shrinks `t_max` to it. With this order the closest hit
/// is a function of the ray and the primitives alone, not of the order a traversal meets them
/// in: a group of rays traversed together visits nodes in another order than a single ray,
/// and both must name the same primitive when two are hit at one distance (a shared edge).
/// `hit.t ≤ *t_max` (the tests' bound).
#[inline(always)]
pub(super) fn offer(hit: PrimHit, id: u32, t_max: &mut f32, best: &mut Option<(PrimHit, u32)>) {
    if hit.t < *t_max || (hit.t == *t_max && best.is_none_or(|(_, b)| id < b)) {
        *t_max = hit.t;
        *best = Some((hit, id));
    }
}

/// Closest hit among `packets`, shrinking `t_max` and updating `best` as it goes.
#[inline(always)]
fn closest_in<G: Packet>(
    packets: &[Packed<G>],
    rx4: &RayX4,
    t_min: f32,
    t_max: &mut f32,
    best: &mut Option<(PrimHit, u32)>,
) {
    for p in packets {
        let h = p.geom.hits(rx4, t_min, *t_max);
        let mut lanes = h.mask.bitmask();
        while lanes != 0 {
            let lane = lanes.trailing_zeros() as usize;
            lanes &= lanes - 1;
            let hit = PrimHit { t: lane_of(&h.t, lane), u: lane_of(&h.u, lane), v: lane_of(&h.v, lane) };
            offer(hit, p.ids[lane], t_max, best);
        }
    }
}

/// [`closest_in`] for the rays of `lanes` (a bitmask) of a group, testing each primitive
/// against all of them at once and offering its hits to all of them ([`GroupHits::offer`]).
/// Per ray the same hit as [`closest_in`]: the same bits per test, and [`offer`]'s order does
/// not depend on the order the hits come in.
#[inline(always)]
fn closest_in_rays<G: Packet, const N: usize>(
    packets: &[Packed<G>],
    rays: &Rays<N>,
    lanes: u32,
    t_min: f32,
    group: Option<&GroupBounds>,
    best: &mut GroupHits<N>,
) {
    for p in packets {
        let may_hit = group.map_or(0b1111, |g| p.geom.may_hit(g));
        for k in 0..4 {
            // Padding lanes repeat the previous primitive (and never hit).
            if k > 0 && p.ids[k] == p.ids[k - 1] {
                break;
            }
            if may_hit >> k & 1 == 0 {
                continue;
            }
            let h = p.geom.hits_rays(k, rays, t_min, best.t);
            best.offer(&h, p.ids[k], lanes);
        }
    }
}

/// The rays of `lanes` (a bitmask) that hit any primitive of `packets` within their `t_max`.
#[inline(always)]
fn any_in_rays<G: Packet, const N: usize>(
    packets: &[Packed<G>],
    rays: &Rays<N>,
    lanes: u32,
    t_min: f32,
    t_max: F32s<N>,
    group: Option<&GroupBounds>,
) -> u32 {
    let mut blocked = 0;
    for p in packets {
        let may_hit = group.map_or(0b1111, |g| p.geom.may_hit(g));
        for k in 0..4 {
            if blocked == lanes || (k > 0 && p.ids[k] == p.ids[k - 1]) {
                break;
            }
            if may_hit >> k & 1 == 0 {
                continue;
            }
            blocked |= p.geom.hits_rays(k, rays, t_min, t_max).mask.bitmask() & lanes;
        }
    }
    blocked
}

/// True if any lane of any packet is hit.
#[inline(always)]
fn any_in<G: Packet>(packets: &[Packed<G>], rx4: &RayX4, t_min: f32, t_max: f32) -> bool {
    packets.iter().any(|p| p.geom.hits(rx4, t_min, t_max).mask.any())
}

/// One leaf: ranges in the packet and index arrays.
#[derive(Clone, Copy, Debug, Default)]
struct Leaf {
    quads: u32,
    tris: u32,
    scalar: u32,
    n_quads: u8,
    n_tris: u8,
    n_scalar: u8,
}

/// Every leaf of a tree.
#[derive(Clone, Debug, Default)]
pub(super) struct Leaves {
    leaves: Vec<Leaf>,
    quads: Vec<Packed<Quad4>>,
    tris: Vec<Packed<Tri4>>,
    scalar: Vec<u32>,
}

/// Up to four primitives of one kind waiting to become a packet (no allocation per leaf or
/// packet: the build packs hundreds of thousands of them).
struct Pending<S> {
    ids: [u32; 4],
    shapes: [Option<S>; 4],
    n: usize,
    packets: u8,
}

impl<S: Copy> Pending<S> {
    fn new() -> Self {
        Self { ids: [0; 4], shapes: [None; 4], n: 0, packets: 0 }
    }

    fn add<G>(&mut self, id: u32, shape: S, make: fn(&[S]) -> G, out: &mut Vec<Packed<G>>) {
        self.ids[self.n] = id;
        self.shapes[self.n] = Some(shape);
        self.n += 1;
        if self.n == 4 {
            self.flush(make, out);
        }
    }

    /// Packs what is pending; unused lanes repeat the last id.
    fn flush<G>(&mut self, make: fn(&[S]) -> G, out: &mut Vec<Packed<G>>) {
        if self.n == 0 {
            return;
        }
        let n = self.n;
        let first = self.shapes[0].expect("a pending shape");
        let shapes = self.shapes.map(|s| s.unwrap_or(first));
        let ids = [0, 1, 2, 3].map(|k| self.ids[k.min(n - 1)]);
        out.push(Packed { geom: make(&shapes[..n]), ids });
        self.n = 0;
        self.packets += 1;
    }
}

/// `v[start..start + n]`, skipping the bounds checks when the range is empty (most leaves
/// hold one kind of primitive).
#[inline(always)]
fn part<T>(v: &[T], start: u32, n: u8) -> &[T] {
    if n == 0 {
        &[]
    } else {
        let start = start as usize;
        &v[start..start + n as usize]
    }
}

/// A leaf is named by a 31-bit reference (the wide nodes store it under their leaf tag).
/// A leaf of one to eight triangle packets and nothing else — nearly every leaf of a mesh — is
/// named directly by its packet range: `DIRECT | (packets − 1) << COUNT_SHIFT | first packet`,
/// so it needs no leaf record (16 bytes, about 4 bytes per triangle) and traversal skips one
/// dependent load. Other leaves are named by the index of their record (below `DIRECT`).
const DIRECT: u32 = 1 << 30;
const COUNT_SHIFT: u32 = 27;
const START_MASK: u32 = (1 << COUNT_SHIFT) - 1;
const MAX_DIRECT_PACKETS: u8 = 8;

/// What a leaf reference names.
enum LeafRef<'a> {
    Triangles(&'a [Packed<Tri4>]),
    Record(&'a Leaf),
}

impl Leaves {
    #[inline(always)]
    fn resolve(&self, reference: u32) -> LeafRef<'_> {
        if reference & DIRECT != 0 {
            let start = reference & START_MASK;
            let n = ((reference >> COUNT_SHIFT) & 7) as u8 + 1;
            LeafRef::Triangles(part(&self.tris, start, n))
        } else {
            LeafRef::Record(&self.leaves[reference as usize])
        }
    }

    /// Adds a leaf over the primitives `items` (index, how it is stored); returns its reference.
    pub fn push(&mut self, items: impl Iterator<Item = (u32, Packable)>) -> u32 {
        let (mut quads, mut tris) = (Pending::new(), Pending::new());
        let mut leaf = Leaf {
            quads: self.quads.len() as u32,
            tris: self.tris.len() as u32,
            scalar: self.scalar.len() as u32,
            ..Default::default()
        };
        for (i, kind) in items {
            match kind {
                Packable::Quad(q) => quads.add(i, q, Quad4::new, &mut self.quads),
                Packable::Triangle(t) => tris.add(i, t, Tri4::new, &mut self.tris),
                Packable::No => {
                    self.scalar.push(i);
                    leaf.n_scalar += 1;
                }
            }
        }
        quads.flush(Quad4::new, &mut self.quads);
        tris.flush(Tri4::new, &mut self.tris);
        (leaf.n_quads, leaf.n_tris) = (quads.packets, tris.packets);
        // A start below START_MASK keeps every direct reference apart from the EMPTY slot.
        let direct = leaf.n_quads == 0 && leaf.n_scalar == 0 && (1..=MAX_DIRECT_PACKETS).contains(&leaf.n_tris);
        if direct && leaf.tris < START_MASK {
            return DIRECT | ((leaf.n_tris as u32 - 1) << COUNT_SHIFT) | leaf.tris;
        }
        self.leaves.push(leaf);
        let index = self.leaves.len() as u32 - 1;
        assert!(index < DIRECT, "more than 2^30 BVH leaf records");
        index
    }

    /// Closest hit in leaf `index` with `t ≤ *t_max`; shrinks `t_max` and updates `best`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn intersect<P: PrimitiveSet + ?Sized>(
        &self,
        index: u32,
        prims: &P,
        ray: &Ray,
        rx4: &RayX4,
        t_min: f32,
        t_max: &mut f32,
        best: &mut Option<(PrimHit, u32)>,
    ) {
        let leaf = match self.resolve(index) {
            LeafRef::Triangles(tris) => return closest_in(tris, rx4, t_min, t_max, best),
            LeafRef::Record(leaf) => leaf,
        };
        closest_in(part(&self.quads, leaf.quads, leaf.n_quads), rx4, t_min, t_max, best);
        closest_in(part(&self.tris, leaf.tris, leaf.n_tris), rx4, t_min, t_max, best);
        for &i in part(&self.scalar, leaf.scalar, leaf.n_scalar) {
            if let Some(hit) = prims.intersect_one(i, ray, t_min, *t_max) {
                offer(hit, i, t_max, best);
            }
        }
    }

    /// True if anything in leaf `index` is hit within `[t_min, t_max]`.
    #[inline(always)]
    pub fn occluded<P: PrimitiveSet + ?Sized>(
        &self,
        index: u32,
        prims: &P,
        ray: &Ray,
        rx4: &RayX4,
        t_min: f32,
        t_max: f32,
    ) -> bool {
        let leaf = match self.resolve(index) {
            LeafRef::Triangles(tris) => return any_in(tris, rx4, t_min, t_max),
            LeafRef::Record(leaf) => leaf,
        };
        any_in(part(&self.quads, leaf.quads, leaf.n_quads), rx4, t_min, t_max)
            || any_in(part(&self.tris, leaf.tris, leaf.n_tris), rx4, t_min, t_max)
            || part(&self.scalar, leaf.scalar, leaf.n_scalar)
                .iter()
                .any(|&i| prims.intersect_one(i, ray, t_min, t_max).is_some())
    }

    /// [`Leaves::intersect`] for the rays of `lanes` (a bitmask) of a group (ray `i`:
    /// `origin[i] + t·dir[i]`), each packed primitive tested against all of them at once;
    /// updates the rays' closest hits `best`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn intersect_rays<P: PrimitiveSet + ?Sized, const N: usize>(
        &self,
        index: u32,
        prims: &P,
        origin: &Vec3s<N>,
        dir: &Vec3s<N>,
        lanes: u32,
        t_min: f32,
        group: Option<&GroupBounds>,
        best: &mut GroupHits<N>,
    ) {
        let rays = Rays::from_lanes(origin, dir);
        let leaf = match self.resolve(index) {
            LeafRef::Triangles(tris) => return closest_in_rays(tris, &rays, lanes, t_min, group, best),
            LeafRef::Record(leaf) => leaf,
        };
        closest_in_rays(part(&self.quads, leaf.quads, leaf.n_quads), &rays, lanes, t_min, group, best);
        closest_in_rays(part(&self.tris, leaf.tris, leaf.n_tris), &rays, lanes, t_min, group, best);
        for &p in part(&self.scalar, leaf.scalar, leaf.n_scalar) {
            let mut todo = lanes;
            while todo != 0 {
                let i = todo.trailing_zeros() as usize;
                todo &= todo - 1;
                let ray = Ray::new(origin.lane(i), dir.lane(i));
                let (mut t_max, mut hit) = (best.t.0[i], best.get(i));
                if let Some(h) = prims.intersect_one(p, &ray, t_min, t_max) {
                    offer(h, p, &mut t_max, &mut hit);
                    best.put(i, hit);
                }
            }
        }
    }

    /// [`Leaves::occluded`] for the rays of `lanes` (a bitmask) of a group: the bitmask of the
    /// blocked ones.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn occluded_rays<P: PrimitiveSet + ?Sized, const N: usize>(
        &self,
        index: u32,
        prims: &P,
        origin: &Vec3s<N>,
        dir: &Vec3s<N>,
        lanes: u32,
        t_min: f32,
        t_max: F32s<N>,
        group: Option<&GroupBounds>,
    ) -> u32 {
        let rays = Rays::from_lanes(origin, dir);
        let leaf = match self.resolve(index) {
            LeafRef::Triangles(tris) => return any_in_rays(tris, &rays, lanes, t_min, t_max, group),
            LeafRef::Record(leaf) => leaf,
        };
        let quads = part(&self.quads, leaf.quads, leaf.n_quads);
        let mut blocked = any_in_rays(quads, &rays, lanes, t_min, t_max, group);
        let tris = part(&self.tris, leaf.tris, leaf.n_tris);
        blocked |= any_in_rays(tris, &rays, lanes & !blocked, t_min, t_max, group);
        for &p in part(&self.scalar, leaf.scalar, leaf.n_scalar) {
            let mut todo = lanes & !blocked;
            while todo != 0 {
                let i = todo.trailing_zeros() as usize;
                todo &= todo - 1;
                let ray = Ray::new(origin.lane(i), dir.lane(i));
                if prims.intersect_one(p, &ray, t_min, t_max.0[i]).is_some() {
                    blocked |= 1 << i;
                }
            }
        }
        blocked
    }

    /// Same leaf records, holding the same primitives in the same packets and order.
    pub fn same_layout(&self, o: &Leaves) -> bool {
        let key = |l: &Leaf| (l.quads, l.tris, l.scalar, l.n_quads, l.n_tris, l.n_scalar);
        self.leaves.iter().map(key).eq(o.leaves.iter().map(key))
            && self.quads.iter().map(|p| p.ids).eq(o.quads.iter().map(|p| p.ids))
            && self.tris.iter().map(|p| p.ids).eq(o.tris.iter().map(|p| p.ids))
            && self.scalar == o.scalar
    }

    pub fn shrink_to_fit(&mut self) {
        self.leaves.shrink_to_fit();
        self.quads.shrink_to_fit();
        self.tris.shrink_to_fit();
        self.scalar.shrink_to_fit();
    }

    /// Heap bytes, from the vectors' capacities.
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        self.leaves.capacity() * size_of::<Leaf>()
            + self.quads.capacity() * size_of::<Packed<Quad4>>()
            + self.tris.capacity() * size_of::<Packed<Tri4>>()
            + self.scalar.capacity() * size_of::<u32>()
    }

    /// Number of SIMD packets and of primitives tested one by one in leaf `index`.
    pub fn sizes(&self, index: u32) -> (usize, usize) {
        match self.resolve(index) {
            LeafRef::Triangles(tris) => (tris.len(), 0),
            LeafRef::Record(l) => (l.n_quads as usize + l.n_tris as usize, l.n_scalar as usize),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;
    use crate::wide::simd::Ms;

    use super::super::test_draws::{point, uniform};
    use super::super::wide::RayBoxes;

    /// A packet's boxes are the tree's padded boxes of its triangles, bit for bit.
    #[test]
    fn packet_boxes_are_the_trees_padded_boxes() {
        let mut rng = Pcg32::new(3, 9);
        for _ in 0..2000 {
            let scale = [1e-3, 1.0, 1e3][rng.next_u32() as usize % 3];
            let tris: Vec<Triangle> = (0..4)
                .filter_map(|_| {
                    let a = point(&mut rng, 10.0 * scale);
                    Triangle::new(a, a + point(&mut rng, scale), a + point(&mut rng, scale), Triangle::FLAT)
                })
                .collect();
            if tris.is_empty() {
                continue;
            }
            let b = Tri4::new(&tris).padded_bounds();
            for (k, t) in tris.iter().enumerate() {
                let want = t.bounds().padded();
                for a in 0..3 {
                    assert_eq!(b[a][k].to_bits(), want.min[a].to_bits(), "{t:?}");
                    assert_eq!(b[a + 3][k].to_bits(), want.max[a].to_bits(), "{t:?}");
                }
            }
        }
    }

    /// A triangle the group's bounds drop is hit by no ray of the group (each ray's own test,
    /// within its own `t_far`), and for groups aimed at a patch of small triangles most of the
    /// triangles no ray hits are dropped. Groups: one origin or a patch of origins, narrow or
    /// wider cones, a few rays aimed exactly at corners and edges, `t_far` finite or not.
    #[test]
    fn triangles_dropped_by_the_bounds_are_hit_by_no_ray() {
        const N: usize = 32;
        let mut rng = Pcg32::new(5, 17);
        let (mut missed_by_all, mut dropped, mut hit_tests) = (0, 0, 0);
        for g in 0..3000 {
            let target = point(&mut rng, 3.0);
            let size = [0.02, 0.2][g % 2];
            let tris: Vec<Triangle> = (0..4)
                .filter_map(|_| {
                    let a = target + point(&mut rng, 4.0 * size);
                    Triangle::new(a, a + point(&mut rng, size), a + point(&mut rng, size), Triangle::FLAT)
                })
                .collect();
            if tris.is_empty() {
                continue;
            }
            let packet = Tri4::new(&tris);
            let centre = target + point(&mut rng, 10.0);
            let patch = [0.0, 0.01, 0.3][g / 2 % 3];
            let spread = [0.002, 0.02, 1e-6][g / 6 % 3];
            // Inside the first triangle, or (with the narrowest cones) on one of its corners
            // or edges, where only the padding keeps its box around the hits.
            let t0 = &tris[0];
            let on = [(0.3, 0.3), (0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.5, 0.5), (0.5, 0.0), (0.0, 0.5)][g % 7];
            let aim = (t0.p0 + t0.e1 * on.0 + t0.e2 * on.1 - centre).normalize();
            let (mut origin, mut dir) = (Vec3s::<N>::default(), Vec3s::<N>::default());
            for i in 0..N {
                let o = centre + point(&mut rng, patch);
                let d = if i < 4 {
                    // At a corner or along an edge of the triangle the group is aimed at.
                    let t = &tris[0];
                    let (s, w) = (uniform(&mut rng, 0.0, 1.0), [0.0, 1.0][rng.next_u32() as usize % 2]);
                    (t.p0 + t.e1 * s * w + t.e2 * (1.0 - s) * w - o).normalize()
                } else {
                    (aim + point(&mut rng, spread)).normalize()
                };
                origin.set(i, o);
                dir.set(i, d);
            }
            let lanes = Ms::<N>::ALL;
            let Some(iv) = RayInterval::of(&RayBoxes::new(&origin, &dir), lanes) else { continue };
            let t_far = F32s::<N>::from_fn(|_| if g % 3 == 0 { f32::INFINITY } else { uniform(&mut rng, 1.0, 14.0) });
            let t_min = 1e-4;
            let far = (t_far.min_over(lanes), t_far.max_over(lanes));
            let may_hit = packet.may_hit(&GroupBounds { rays: &iv, t_min, far });
            for (k, t) in tris.iter().enumerate() {
                let hits = (0..N)
                    .filter(|&i| t.intersect(&Ray::new(origin.lane(i), dir.lane(i)), t_min, t_far.0[i]).is_some())
                    .count();
                hit_tests += hits;
                if may_hit >> k & 1 == 0 {
                    assert_eq!(hits, 0, "group {g}: triangle {k} dropped, hit by {hits} rays");
                    dropped += 1;
                }
                missed_by_all += usize::from(hits == 0);
            }
        }
        assert!(hit_tests > 10_000, "{hit_tests} ray hits");
        assert!(dropped * 2 > missed_by_all, "dropped {dropped} of {missed_by_all} triangles no ray hits");
    }
}
