//! A bounding volume hierarchy built with the binned surface area heuristic (see `build.rs`),
//! stored as a flat node array in depth-first order (the left child follows its parent), and
//! traversed as an eight-wide tree (see `wide.rs`). Leaves test their quads and triangles four
//! at a time (see `leaf.rs`).

use arrayvec::ArrayVec;
use rayon::prelude::*;

use super::build::{BuildItem, BuildOptions};
use super::group_hits::GroupHits;
use super::lanes::RayX4;
use super::leaf::{GroupBounds, Leaves, Packable};
use super::subtree::build_tree;
use super::wide::{
    collapse, prefetch, wide_depth, BoxLanes, RayBox, RayBoxes, RayInterval, WideNode, EMPTY, LEAF, WIDTH,
};
use crate::math::{Aabb, Ray};
use crate::shape::PrimHit;
use crate::wide::simd::{F32s, Ms, Vec3s, LANES_256};
use glam::Vec4;

/// Anything the BVH can hold.
pub trait Intersectable {
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit>;
}

/// The primitives a BVH was built over, addressed by the indices given to the build: a slice,
/// or a scene's mix of shapes and compact meshes. The BVH only asks for the primitives it does
/// not keep in SIMD packets (spheres, disks, …); packed quads and triangles are tested from
/// the packets alone.
pub trait PrimitiveSet {
    fn intersect_one(&self, index: u32, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit>;
}

impl<P: Intersectable> PrimitiveSet for [P] {
    #[inline(always)]
    fn intersect_one(&self, index: u32, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        self[index as usize].intersect(ray, t_min, t_max)
    }
}

impl<P: Intersectable> PrimitiveSet for Vec<P> {
    #[inline(always)]
    fn intersect_one(&self, index: u32, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit> {
        self[index as usize].intersect(ray, t_min, t_max)
    }
}

/// One node of the binary tree the build makes (and the collapse into [`WideNode`]s consumes):
/// 32 bytes. Leaves have `count > 0` primitives and `offset` indexes their leaf
/// record; interior nodes have their left child at `index + 1` and their right child at
/// `offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Node {
    pub bounds: Aabb,
    pub offset: u32,
    pub count: u16,
    pub axis: u16,
}

/// Shape statistics of a built tree.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BvhStats {
    pub nodes: usize,
    pub leaves: usize,
    pub max_depth: usize,
    pub max_leaf_size: usize,
}

/// Bytes held by a [`Bvh`], per structure.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BvhMemory {
    /// The wide tree that rays traverse.
    pub wide_nodes: usize,
    /// Leaf records, SIMD packets of quads and triangles, indices of other shapes.
    pub leaves: usize,
}

impl BvhMemory {
    pub fn total(&self) -> usize {
        self.wide_nodes + self.leaves
    }
}

/// The hierarchy. Leaves name primitives by their index in the arrays given to [`Bvh::build`]
/// (the caller's primitives need not be reordered). The binary tree the build makes is
/// dropped after the collapse into wide nodes (it cost 16 bytes per triangle); its
/// bounds and statistics are kept.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// The tree, eight children per node, for traversal.
    wide: Vec<WideNode>,
    bounds: Aabb,
    /// `bounds` as a node's only child, for the group walk's first test.
    outer: WideNode,
    stats: BvhStats,
    leaves: Leaves,
}

/// Traversal stack slots: a node visit pushes at most `WIDTH` children and pops one, so
/// `WIDTH - 1` per level of the wide tree, plus 1; depth ≤ 32 + log2(n) < 64 for any n below 2³²,
/// so `(WIDTH - 1) · 64 + 1` slots always suffice.
const STACK_SIZE: usize = (WIDTH - 1) * 64 + 1;
/// A walk's stack: room for any tree, with nothing written before it is used. Zeroed arrays
/// were a `memset` call per walk (1.5 KB for the group walks, 3.3% of the teapot's time; 512
/// bytes for a single ray on trees of depth 6 to 21), and smaller arrays for shallower trees
/// stamped each single-ray walk three times into the render loop.
type WalkStack<T> = ArrayVec<T, STACK_SIZE>;
/// A node that fewer rays of a group reach is traversed ray by ray (see
/// [`Bvh::intersect_lanes`]). A group visit tests every lane of the group (32 with AVX-512), so
/// with few rays left a single-ray walk is cheaper: 6 against 3 took 0.947 of mesh-1m's time,
/// 0.975 of the bunny's and 0.969 of copper's, within 1% elsewhere (docs/benchmarks.md,
/// "The switch to single rays at 6"); 9 and 12 gained nothing more. With the AVX2 kernel's
/// 16-lane groups, 3 and 8 (with `RAY_LANES_FROM` 4 and 8) gained nothing either, and walking
/// incoherent groups ray by ray from the root was 12–35% slower ("The group walks' thresholds
/// and prefetches with 16-lane AVX2 groups").
const SINGLE_RAY_BELOW: u32 = 6;
/// A leaf reached by at least this many rays of a group tests each of its primitives against
/// those rays at once (lanes = rays); fewer rays test it one at a time (lanes = primitives). A
/// ray-lane test costs one primitive's test in every lane, a single-ray test four primitives'
/// for one ray; measured, 6 was 1–2% faster than 4 on mesh-1m, bunny and copper, and 8 the
/// same as 6.
const RAY_LANES_FROM: u32 = 6;

/// Whether a group walk of `lanes` lanes runs in code compiled for AVX: groups wider than the
/// portable build's 8 lanes exist only inside the render loops compiled for AVX2 or AVX-512
/// (`render/tile.rs`). Such walks test a node's eight boxes in one 256-bit vector, others
/// four at a time (see [`BoxLanes`]).
const fn compiled_for_avx(lanes: usize) -> bool {
    lanes > LANES_256
}

impl Bvh {
    /// Builds over the given primitive bounds with the production options (binned SAH, on
    /// rayon for large inputs); `kinds[i]` says whether primitive `i` goes into a SIMD packet.
    /// Hits name primitives by their index `i` in these arrays.
    pub fn build(bounds: &[Aabb], kinds: &[Packable]) -> Bvh {
        Self::build_with(bounds, kinds, &BuildOptions::default())
    }

    /// [`Bvh::build`] with explicit options (split method, bins, leaf size, parallelism).
    pub fn build_with(bounds: &[Aabb], kinds: &[Packable], opts: &BuildOptions) -> Bvh {
        assert_eq!(bounds.len(), kinds.len());
        let opts = opts.clamped();
        let item = |(i, b): (usize, &Aabb)| BuildItem { bounds: b.padded().into(), index: i as u32 };
        let mut items: Vec<BuildItem> = if bounds.len() > opts.parallel_above {
            bounds.par_iter().enumerate().map(item).collect()
        } else {
            bounds.iter().enumerate().map(item).collect()
        };
        let mut nodes = build_tree(&mut items, &opts);
        let mut leaves = Leaves::default();
        for node in nodes.iter_mut().filter(|n| n.count > 0) {
            let start = node.offset as usize;
            let ids = items[start..start + node.count as usize].iter().map(|it| (it.index, kinds[it.index as usize]));
            node.offset = leaves.push(ids);
        }
        leaves.shrink_to_fit();
        let mut wide = collapse(&nodes);
        wide.shrink_to_fit();
        debug_assert!((WIDTH - 1) * wide_depth(&wide) < STACK_SIZE, "a tree deeper than the walks' stack");
        let bounds = nodes.first().map_or(Aabb::EMPTY, |n| n.bounds);
        let stats = binary_stats(&nodes);
        Bvh { wide, bounds, outer: WideNode::single(bounds), stats, leaves }
    }

    /// True if both trees have the same wide nodes (boxes and children) and the same
    /// leaves (the same primitives in the same packets). Packet contents are derived from the
    /// primitives deterministically, so the whole structure is then the same.
    pub fn same_structure(&self, other: &Bvh) -> bool {
        self.wide.len() == other.wide.len()
            && self.wide.iter().zip(&other.wide).all(|(a, b)| a.same_as(b))
            && self.leaves.same_layout(&other.leaves)
    }

    /// Bytes held by the tree (see [`Bvh::memory`]).
    pub fn memory_bytes(&self) -> usize {
        self.memory().total()
    }

    /// Bytes held by the tree, per structure, from the vectors' capacities.
    pub fn memory(&self) -> BvhMemory {
        BvhMemory {
            wide_nodes: self.wide.capacity() * std::mem::size_of::<WideNode>(),
            leaves: self.leaves.memory_bytes() + std::mem::size_of_val(self),
        }
    }

    /// Closest hit among `prims` (indexed as given to the build) with `t ∈ [t_min, t_max]`.
    #[inline(always)]
    pub fn intersect<P: PrimitiveSet + ?Sized>(
        &self,
        prims: &P,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
    ) -> Option<(PrimHit, u32)> {
        if self.wide.is_empty() {
            return None;
        }
        self.closest_from::<P, Vec4>(0, prims, ray, t_min, t_max, None)
    }

    /// Closest hits of the rays of `active` (lane `i`: `origin[i] + t·dir[i]`, `t` in
    /// `[t_min, t_max]`), the same as [`Bvh::intersect`] gives each (bit for bit, and the same
    /// primitive on ties), found by traversing the tree with the group: each node's boxes are
    /// tested against every ray of the group at once (SIMD over rays), so rays that go the same
    /// way (the camera rays of neighbouring pixel samples, shadow rays to one light) share the
    /// node visits; a node reached by at most [`SINGLE_RAY_BELOW`] rays is finished ray by
    /// ray (incoherent rays would only drag each other through nodes they miss). Leaves are
    /// tested ray by ray with the single-ray code. (Wald et al., "Interactive Rendering with
    /// Coherent Ray Tracing", 2001, for packets; Benthin et al., "Combining Single and Packet
    /// Ray Tracing for Arbitrary Ray Distributions on the Intel MIC Architecture", 2012, for
    /// the switch to single rays.)
    #[inline(always)]
    pub fn intersect_lanes<P: PrimitiveSet + ?Sized, const N: usize>(
        &self,
        prims: &P,
        origin: &Vec3s<N>,
        dir: &Vec3s<N>,
        active: Ms<N>,
        t_min: f32,
        t_max: f32,
    ) -> [Option<(PrimHit, u32)>; N] {
        if self.wide.is_empty() || !active.any() {
            return [None; N];
        }
        let ray = |i: usize| Ray::new(origin.lane(i), dir.lane(i));
        let rays = RayBoxes::new(origin, dir);
        let mut best = GroupHits::<N>::new(t_max);
        let lo = F32s::<N>::splat(t_min);
        // Rays that miss the box around the whole tree stop here: one slab test for the group
        // where the root's visit makes eight, for camera rays that pass beside the scene's
        // geometry (most of the teapot's frame). They hit nothing: every primitive lies inside
        // its padded box (`Aabb::padded`), so inside this box, and a ray that meets a
        // primitive within `[t_min, t_max]` passes the slab test of every box around it, as
        // the walk below already relies on for each node on the way to a leaf.
        let (inside, _) = self.outer.child_hit_lanes(0, &rays, lo, best.t);
        let entering = active.bitmask() & inside;
        if entering == 0 {
            return [None; N];
        }
        // A group whose rays go one way on every axis is bounded once (`RayInterval`), and each
        // node's boxes are first tested against the bounds: the children no ray can hit
        // are dropped, and those every ray hits taken by all, without their per-ray tests
        // (most of a coherent group's walk). `far` holds the least and greatest `t_far` of the
        // walk's rays, lowered as they find hits.
        let walk = Ms::<N>::from_fn(|i| entering >> i & 1 != 0);
        let interval = RayInterval::of(&rays, walk);
        let mut far = (t_max, t_max);
        let mut stack = WalkStack::new();
        stack.push((0, entering));
        while let Some((node, mask)) = stack.pop() {
            if mask.count_ones() < SINGLE_RAY_BELOW {
                let mut lanes = mask;
                while lanes != 0 {
                    let i = lanes.trailing_zeros() as usize;
                    lanes &= lanes - 1;
                    let (r, t_far, hit) = (ray(i), best.t.0[i], best.get(i));
                    best.put(
                        i,
                        if compiled_for_avx(N) {
                            self.closest_from::<P, F32s<WIDTH>>(node, prims, &r, t_min, t_far, hit)
                        } else {
                            self.closest_from::<P, Vec4>(node, prims, &r, t_min, t_far, hit)
                        },
                    );
                }
                if interval.is_some() {
                    far = best.t_range(walk);
                }
                continue;
            }
            let n = &self.wide[node as usize];
            let (may_hit, all_hit, entries) = match &interval {
                Some(iv) if compiled_for_avx(N) => n.interval_hits::<F32s<WIDTH>>(iv, t_min, far.0, far.1),
                Some(iv) => n.interval_hits::<Vec4>(iv, t_min, far.0, far.1),
                None => ((1 << WIDTH) - 1, 0, [0.0; WIDTH]),
            };
            let mut kids = [(0u32, 0u32, 0f32); WIDTH];
            let mut k = 0;
            let mut leaf_tested = false;
            for (lane, &child) in n.children.iter().enumerate() {
                if child == EMPTY {
                    break;
                }
                if may_hit >> lane & 1 == 0 {
                    continue;
                }
                // The entry of the first ray that hits orders the children (or, for a child
                // every ray hits, the group's least entry). Any order gives the same hits (the
                // closest hit and its tie rule do not depend on it), so this only has to be a
                // good guess, and one lane's entry is nearly the group's nearest for the
                // coherent rays that reach here; the nearest over the hit lanes was a scalar
                // loop, about 6% of the teapot's time.
                let (hit, entry) = if all_hit >> lane & 1 != 0 {
                    (mask, entries[lane])
                } else {
                    let (hit, near) = n.child_hit_lanes(lane, &rays, lo, best.t);
                    let hit = hit & mask;
                    if hit == 0 {
                        continue;
                    }
                    (hit, near.0[hit.trailing_zeros() as usize])
                };
                if child & LEAF == 0 {
                    let mut i = k;
                    while i > 0 && kids[i - 1].2 < entry {
                        kids[i] = kids[i - 1];
                        i -= 1;
                    }
                    kids[i] = (child, hit, entry);
                    k += 1;
                } else if hit.count_ones() >= RAY_LANES_FROM {
                    leaf_tested = true;
                    let group = interval.as_ref().map(|rays| GroupBounds { rays, t_min, far });
                    self.leaves.intersect_rays(
                        child & !LEAF,
                        prims,
                        origin,
                        dir,
                        hit,
                        t_min,
                        group.as_ref(),
                        &mut best,
                    );
                } else {
                    leaf_tested = true;
                    let mut lanes = hit;
                    while lanes != 0 {
                        let i = lanes.trailing_zeros() as usize;
                        lanes &= lanes - 1;
                        let r = ray(i);
                        let (mut t_far, mut hit) = (best.t.0[i], best.get(i));
                        self.leaves.intersect(child & !LEAF, prims, &r, &RayX4::new(&r), t_min, &mut t_far, &mut hit);
                        best.put(i, hit);
                    }
                }
            }
            if leaf_tested && interval.is_some() {
                far = best.t_range(walk);
            }
            for &(child, hit, _) in &kids[..k] {
                prefetch(&self.wide, child);
                stack.push((child, hit));
            }
        }
        best.into_array()
    }

    /// Closest hit in the subtree of wide node `start`, nearer than `t_max` or as near and on
    /// a lower primitive than `best` (see `leaf::offer`). Near-child-first traversal with
    /// distance culling: a node's hit leaves are tested at once (shrinking `t_max`); its hit
    /// interior children are pushed farthest first with their entry distances, so the nearest
    /// is visited next and a popped child that starts beyond the closest hit so far is skipped
    /// without loading it.
    #[inline(always)]
    fn closest_from<P: PrimitiveSet + ?Sized, L: BoxLanes>(
        &self,
        start: u32,
        prims: &P,
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
        mut best: Option<(PrimHit, u32)>,
    ) -> Option<(PrimHit, u32)> {
        let rb = RayBox::<L>::new(ray);
        let rx4 = RayX4::new(ray);
        let mut stack = WalkStack::<(u32, f32)>::new();
        let mut node = start;
        loop {
            let n = &self.wide[node as usize];
            let (mut lanes, near) = n.hit(&rb, t_min, t_max);
            // The nearest interior child is visited next straight from registers: through the
            // stack, the next node's index would wait on a store and its reload on every
            // visit. The others go onto the stack, insertion-sorted farthest first among
            // themselves (a separate buffer copied over afterwards compiled to a `memmove`
            // call per node: 4–6% of the time on small meshes).
            let (mut next, mut next_entry) = (EMPTY, f32::INFINITY);
            let base = stack.len();
            while lanes != 0 {
                let lane = lanes.trailing_zeros() as usize;
                let child = n.children[lane];
                lanes &= lanes - 1;
                if child & LEAF == 0 {
                    prefetch(&self.wide, child);
                    let (mut child, mut entry) = (child, near[lane]);
                    if entry <= next_entry {
                        std::mem::swap(&mut child, &mut next);
                        std::mem::swap(&mut entry, &mut next_entry);
                        if child == EMPTY {
                            continue;
                        }
                    }
                    stack.push((child, entry));
                    let pushed = stack.as_mut_slice();
                    let mut i = pushed.len() - 1;
                    while i > base && pushed[i - 1].1 < entry {
                        pushed[i] = pushed[i - 1];
                        i -= 1;
                    }
                    pushed[i] = (child, entry);
                } else if child != EMPTY {
                    self.leaves.intersect(child & !LEAF, prims, ray, &rx4, t_min, &mut t_max, &mut best);
                }
            }
            if next != EMPTY && next_entry <= t_max {
                node = next;
                continue;
            }
            loop {
                let Some((next, entry)) = stack.pop() else { return best };
                if entry <= t_max {
                    node = next;
                    break;
                }
            }
        }
    }

    /// True if anything blocks the ray within `[t_min, t_max]` (stops at the first blocker).
    #[inline(always)]
    pub fn occluded<P: PrimitiveSet + ?Sized>(&self, prims: &P, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        if self.wide.is_empty() {
            return false;
        }
        self.occluded_from::<P, Vec4>(0, prims, ray, t_min, t_max)
    }

    /// [`Bvh::occluded`] for the rays of `active` (lane `i`: `origin[i] + t·dir[i]`, `t` in
    /// `[t_min, t_max[i]]`) as a bitmask of the blocked lanes, traversed as a group like
    /// [`Bvh::intersect_lanes`]; a ray leaves the group as soon as it is found blocked.
    #[inline(always)]
    pub fn occluded_lanes<P: PrimitiveSet + ?Sized, const N: usize>(
        &self,
        prims: &P,
        origin: &Vec3s<N>,
        dir: &Vec3s<N>,
        active: Ms<N>,
        t_min: f32,
        t_max: F32s<N>,
    ) -> u32 {
        let mut blocked = 0u32;
        if self.wide.is_empty() || !active.any() {
            return blocked;
        }
        let ray = |i: usize| Ray::new(origin.lane(i), dir.lane(i));
        let rays = RayBoxes::new(origin, dir);
        let lo = F32s::<N>::splat(t_min);
        // Coherent groups' boxes tested against the group's bounds first, as in
        // `intersect_lanes`.
        let interval = RayInterval::of(&rays, active);
        let far = if interval.is_some() { (t_max.min_over(active), t_max.max_over(active)) } else { (0.0, 0.0) };
        let mut stack = WalkStack::new();
        stack.push((0, active.bitmask()));
        while let Some((node, mask)) = stack.pop() {
            let mask = mask & !blocked;
            if mask.count_ones() < SINGLE_RAY_BELOW {
                let mut lanes = mask;
                while lanes != 0 {
                    let i = lanes.trailing_zeros() as usize;
                    lanes &= lanes - 1;
                    let blocks = if compiled_for_avx(N) {
                        self.occluded_from::<P, F32s<WIDTH>>(node, prims, &ray(i), t_min, t_max.0[i])
                    } else {
                        self.occluded_from::<P, Vec4>(node, prims, &ray(i), t_min, t_max.0[i])
                    };
                    if blocks {
                        blocked |= 1 << i;
                    }
                }
                continue;
            }
            let n = &self.wide[node as usize];
            let (may_hit, all_hit, _) = match &interval {
                Some(iv) if compiled_for_avx(N) => n.interval_hits::<F32s<WIDTH>>(iv, t_min, far.0, far.1),
                Some(iv) => n.interval_hits::<Vec4>(iv, t_min, far.0, far.1),
                None => ((1 << WIDTH) - 1, 0, [0.0; WIDTH]),
            };
            for (lane, &child) in n.children.iter().enumerate() {
                if child == EMPTY {
                    break;
                }
                if may_hit >> lane & 1 == 0 {
                    continue;
                }
                let hit =
                    if all_hit >> lane & 1 != 0 { mask } else { n.child_hit_lanes(lane, &rays, lo, t_max).0 & mask };
                let hit = hit & !blocked;
                if hit == 0 {
                    continue;
                }
                if child & LEAF == 0 {
                    prefetch(&self.wide, child);
                    stack.push((child, hit));
                } else if hit.count_ones() >= RAY_LANES_FROM {
                    let group = interval.as_ref().map(|rays| GroupBounds { rays, t_min, far });
                    blocked |=
                        self.leaves.occluded_rays(child & !LEAF, prims, origin, dir, hit, t_min, t_max, group.as_ref());
                } else {
                    let mut lanes = hit;
                    while lanes != 0 {
                        let i = lanes.trailing_zeros() as usize;
                        lanes &= lanes - 1;
                        let r = ray(i);
                        if self.leaves.occluded(child & !LEAF, prims, &r, &RayX4::new(&r), t_min, t_max.0[i]) {
                            blocked |= 1 << i;
                        }
                    }
                }
            }
        }
        blocked
    }

    /// [`Bvh::occluded`] in the subtree of wide node `start`.
    #[inline(always)]
    fn occluded_from<P: PrimitiveSet + ?Sized, L: BoxLanes>(
        &self,
        start: u32,
        prims: &P,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
    ) -> bool {
        let rb = RayBox::<L>::new(ray);
        let rx4 = RayX4::new(ray);
        let mut stack = WalkStack::<u32>::new();
        let mut node = start;
        loop {
            let n = &self.wide[node as usize];
            // Any hit ends the search, so the order of children does not matter.
            let mut lanes = n.hit(&rb, t_min, t_max).0;
            // The last interior child hit is visited next straight from a register (as in
            // `closest_from`); the others are pushed. The visiting order is the same as pushing them
            // all and popping the last.
            let mut next = EMPTY;
            while lanes != 0 {
                let child = n.children[lanes.trailing_zeros() as usize];
                lanes &= lanes - 1;
                if child & LEAF == 0 {
                    prefetch(&self.wide, child);
                    if next != EMPTY {
                        stack.push(next);
                    }
                    next = child;
                } else if child != EMPTY && self.leaves.occluded(child & !LEAF, prims, ray, &rx4, t_min, t_max) {
                    return true;
                }
            }
            if next != EMPTY {
                node = next;
                continue;
            }
            let Some(popped) = stack.pop() else { return false };
            node = popped;
        }
    }

    /// Bounds of everything in the tree.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// One line per wide node or leaf, indented by depth (for debugging and the docs).
    pub fn dump(&self) -> String {
        let mut out = String::new();
        if !self.wide.is_empty() {
            self.dump_node(0, 0, &mut out);
        }
        out
    }

    fn dump_node(&self, index: u32, depth: usize, out: &mut String) {
        let node = &self.wide[index as usize];
        out.push_str(&format!("{:indent$}node\n", "", indent = 2 * depth));
        for (lane, &child) in node.children.iter().enumerate().filter(|(_, &c)| c != EMPTY) {
            let b = node.child_bounds(lane);
            if child & LEAF == 0 {
                self.dump_node(child, depth + 1, out);
            } else {
                let (packets, scalar) = self.leaves.sizes(child & !LEAF);
                out.push_str(&format!(
                    "{:indent$}leaf ({packets} packets + {scalar} single) [{:.0?} – {:.0?}]\n",
                    "",
                    b.min.to_array(),
                    b.max.to_array(),
                    indent = 2 * depth + 2
                ));
            }
        }
    }

    /// Shape statistics of the binary tree the build made.
    pub fn stats(&self) -> BvhStats {
        self.stats
    }
}

/// Node count, leaves, depth and largest leaf of a binary tree (root at 0).
fn binary_stats(nodes: &[Node]) -> BvhStats {
    fn walk(nodes: &[Node], index: usize, depth: usize, stats: &mut BvhStats) {
        let node = &nodes[index];
        stats.max_depth = stats.max_depth.max(depth);
        if node.count > 0 {
            stats.leaves += 1;
            stats.max_leaf_size = stats.max_leaf_size.max(node.count as usize);
        } else {
            walk(nodes, index + 1, depth + 1, stats);
            walk(nodes, node.offset as usize, depth + 1, stats);
        }
    }
    let mut stats = BvhStats { nodes: nodes.len(), ..Default::default() };
    if !nodes.is_empty() {
        walk(nodes, 0, 1, &mut stats);
    }
    stats
}
