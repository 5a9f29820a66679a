//! A four-wide BVH collapsed from the binary SAH tree (Dammertz et al., "Shallow Bounding Volume
//! Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays", EGSR 2008): each node holds four
//! child boxes in SIMD lanes and tests them with one slab test (Kay & Kajiya 1986).

use glam::{BVec4A, Vec4};

use super::bvh::Node;
use super::lanes::lane_of;
use crate::math::Ray;
use crate::wide::simd::{F32s, Ms, Vec3s};

/// Child tag for leaves (the low bits are the leaf record).
pub(super) const LEAF: u32 = 1 << 31;
/// Child slot without a child.
pub(super) const EMPTY: u32 = u32::MAX;

/// Four children: their boxes (min x, y, z, max x, y, z; one child per lane) and indices (an
/// interior node, `LEAF | leaf reference` (see `leaf.rs`), or `EMPTY`). Empty lanes have the box `[+∞, +∞]`,
/// whose slab distances all have one sign, so it is never hit. 112 bytes, aligned to 64 so
/// that a node spans exactly two cache lines (at 16-byte alignment half of them touch three).
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
pub(super) struct Node4 {
    bounds: [Vec4; 6],
    pub children: [u32; 4],
}

// Two cache lines exactly, as `prefetch` asks for.
const _: () = assert!(std::mem::size_of::<Node4>() == 128);

/// Asks the caches for node `index`'s two lines when it is pushed, ahead of its visit: a
/// traversal is a chain of dependent loads, and a far child waits on the stack while the near
/// one's subtree is searched, time in which its miss can be served. A hint only (it changes no
/// value); out of range, nothing is asked.
#[inline(always)]
pub(super) fn prefetch(nodes: &[Node4], index: u32) {
    if let Some(node) = nodes.get(index as usize) {
        crate::wide::prefetch::prefetch(std::slice::from_ref(node));
    }
}

/// A ray prepared for slab tests on four boxes.
#[derive(Clone, Copy, Debug)]
pub(super) struct RayBox4 {
    origin: [Vec4; 3],
    inv_dir: [Vec4; 3],
}

impl RayBox4 {
    #[inline(always)]
    pub fn new(ray: &Ray) -> Self {
        let inv = ray.dir.recip();
        Self {
            origin: [ray.origin.x, ray.origin.y, ray.origin.z].map(Vec4::splat),
            inv_dir: [inv.x, inv.y, inv.z].map(Vec4::splat),
        }
    }
}

/// Rays in SIMD lanes (one ray per lane) prepared for slab tests against one box at a time.
#[derive(Clone, Copy, Debug)]
pub(super) struct RayBoxes<const N: usize> {
    origin: [F32s<N>; 3],
    inv_dir: [F32s<N>; 3],
}

impl<const N: usize> RayBoxes<N> {
    /// The same reciprocals as [`RayBox4::new`] takes per ray.
    #[inline(always)]
    pub fn new(origin: &Vec3s<N>, dir: &Vec3s<N>) -> Self {
        Self { origin: [origin.x, origin.y, origin.z], inv_dir: [dir.x, dir.y, dir.z].map(|d| F32s::ONE / d) }
    }
}

/// A group of rays bounded together, for testing a node's four boxes against the whole group at
/// once (Boulos et al., "Geometric and Arithmetic Culling Methods for Entire Ray Packets", 2006):
/// per axis, the extremes of the rays' origins and of their reciprocal directions, which all have
/// one sign. Made only for such groups (a pixel's camera rays, the shadow rays of nearby points
/// to one light); a group whose directions' signs differ on some axis gets none.
#[derive(Clone, Copy, Debug)]
pub(super) struct RayInterval {
    /// Per axis: which of a box's planes the rays enter through (`axis` for the min plane,
    /// `axis + 3` for the max), and which they leave through.
    entry_plane: [usize; 3],
    exit_plane: [usize; 3],
    /// Per axis: the origin bound that gives the least entry distance (the greatest origin for
    /// rays going up the axis, the least for rays going down), and the one that gives the
    /// greatest exit distance.
    entry_origin: [Vec4; 3],
    exit_origin: [Vec4; 3],
    /// Per axis: the least and greatest reciprocal direction.
    inv_lo: [Vec4; 3],
    inv_hi: [Vec4; 3],
}

impl RayInterval {
    /// The bounds of the rays of `lanes`; `None` if, on some axis, their directions do not all
    /// have one sign or some origin or reciprocal direction is not finite.
    #[inline(always)]
    pub fn of<const N: usize>(r: &RayBoxes<N>, lanes: Ms<N>) -> Option<Self> {
        // One ray's bounds are the ray: its own test is as cheap.
        if N == 1 {
            return None;
        }
        // Mixed signs, the usual way out (bounce rays), are found by six compares, before the
        // finiteness test and the folds.
        let zero = F32s::splat(0.0);
        for axis in 0..3 {
            let (up, down) = (r.inv_dir[axis].gt(zero), r.inv_dir[axis].lt(zero));
            if (lanes & !up).any() && (lanes & !down).any() {
                return None;
            }
        }
        let finite = (0..3).fold(lanes, |m, a| m & r.origin[a].is_finite() & r.inv_dir[a].is_finite());
        if (lanes & !finite).any() {
            return None;
        }
        let mut iv = RayInterval {
            entry_plane: [0; 3],
            exit_plane: [0; 3],
            entry_origin: [Vec4::ZERO; 3],
            exit_origin: [Vec4::ZERO; 3],
            inv_lo: [Vec4::ZERO; 3],
            inv_hi: [Vec4::ZERO; 3],
        };
        for axis in 0..3 {
            let (lo, hi) = (r.inv_dir[axis].min_over(lanes), r.inv_dir[axis].max_over(lanes));
            let up = if lo > 0.0 {
                true
            } else if hi < 0.0 {
                false
            } else {
                return None;
            };
            let (o_lo, o_hi) = (r.origin[axis].min_over(lanes), r.origin[axis].max_over(lanes));
            // Going up the axis the rays enter through the min plane, and the entry distance
            // (plane − o)·inv is least for the greatest origin; going down, through the max
            // plane, least for the least origin. The exit the other way round.
            iv.entry_plane[axis] = if up { axis } else { axis + 3 };
            iv.exit_plane[axis] = if up { axis + 3 } else { axis };
            iv.entry_origin[axis] = Vec4::splat(if up { o_hi } else { o_lo });
            iv.exit_origin[axis] = Vec4::splat(if up { o_lo } else { o_hi });
            iv.inv_lo[axis] = Vec4::splat(lo);
            iv.inv_hi[axis] = Vec4::splat(hi);
        }
        Some(iv)
    }

    /// Four boxes (`bounds`: min x, y, z, max x, y, z, one box per lane) against the rays
    /// bounded by `self`, as [`Node4::interval_hits`] (which see) tests a node's children: the
    /// boxes some ray may hit, those every ray hits, and lower bounds of the entry distances.
    #[inline(always)]
    pub fn boxes_hit(&self, bounds: &[Vec4; 6], t_min: f32, far_lo: f32, far_hi: f32) -> (u32, u32, Vec4) {
        let (mut near_lo, mut near_hi) = (Vec4::splat(t_min), Vec4::splat(t_min));
        let (mut exit_lo, mut exit_hi) = (Vec4::splat(far_lo), Vec4::splat(far_hi));
        for axis in 0..3 {
            let (entry, exit) = (bounds[self.entry_plane[axis]], bounds[self.exit_plane[axis]]);
            let (lo, hi) = (self.inv_lo[axis], self.inv_hi[axis]);
            // The least entry and greatest exit: the origin bounds that make them extreme.
            let (d_in, d_out) = (entry - self.entry_origin[axis], exit - self.exit_origin[axis]);
            near_lo = near_lo.max((d_in * lo).min(d_in * hi));
            exit_hi = exit_hi.min((d_out * lo).max(d_out * hi));
            // The greatest entry and least exit: the other origin bounds.
            let (d_in, d_out) = (entry - self.exit_origin[axis], exit - self.entry_origin[axis]);
            near_hi = near_hi.max((d_in * lo).max(d_in * hi));
            exit_lo = exit_lo.min((d_out * lo).min(d_out * hi));
        }
        (near_lo.cmple(exit_hi).bitmask(), near_hi.cmple(exit_lo).bitmask(), near_lo)
    }
}

impl Default for Node4 {
    /// No children.
    fn default() -> Self {
        Node4 { bounds: [Vec4::INFINITY; 6], children: [EMPTY; 4] }
    }
}

impl Node4 {
    /// A node whose only child (lane 0, no index) has the box `b`: for testing rays against
    /// one box with the same operations as a child box.
    pub fn single(b: crate::math::Aabb) -> Node4 {
        let mut n = Node4::default();
        for axis in 0..3 {
            n.bounds[axis][0] = b.min[axis];
            n.bounds[axis + 3][0] = b.max[axis];
        }
        n
    }

    /// Bitmask of the rays whose slab test against child `lane`'s box passes within
    /// `[t_min, t_far]` (per ray), and their entry distances: per ray, the same operations as
    /// [`Node4::hit`] (the lane type's `min`/`max` have the SIMD instructions' NaN rule too).
    #[inline(always)]
    pub fn child_hit_lanes<const N: usize>(
        &self,
        lane: usize,
        r: &RayBoxes<N>,
        t_min: F32s<N>,
        t_far: F32s<N>,
    ) -> (u32, F32s<N>) {
        let mut near = t_min;
        let mut far = t_far;
        for axis in 0..3 {
            let t0 = (F32s::splat(lane_of(&self.bounds[axis], lane)) - r.origin[axis]) * r.inv_dir[axis];
            let t1 = (F32s::splat(lane_of(&self.bounds[axis + 3], lane)) - r.origin[axis]) * r.inv_dir[axis];
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        (near.le(far).bitmask(), near)
    }

    /// The group bounded by `iv` against the four boxes, each ray's range `[t_min, t_far]`
    /// with `t_far` within `[far_lo, far_hi]`: the children some ray may hit, the children
    /// every ray hits (bitmasks, lane 0 lowest), and per child a lower bound of the rays' entry
    /// distances. Both masks agree with [`Node4::child_hit_lanes`]'s own test of each ray: a
    /// child outside the first is missed by all of them, a child in the second hit by all.
    ///
    /// Why: the per-ray test computes, per axis, fl(fl(plane − o) · inv). Rounding is
    /// monotone, so fl(plane − o) falls as o grows, and the product is monotone in each factor
    /// for a fixed sign of the other; so over the interval, a ray's entry distance lies between
    /// the least and the greatest of fl(fl(entry plane − o) · inv) at the ends of o's and
    /// inv's ranges (for the least: the origin bound `entry_origin`, both ends of inv), and
    /// its exit distance likewise. If the greatest entry bound over the axes (and `t_min`)
    /// exceeds the least exit bound (and `far_hi`), every ray's near distance exceeds its far
    /// one: the per-ray test fails for all. If the greatest entry is at most the least exit
    /// (and `far_lo`), it passes for all.
    #[inline(always)]
    pub fn interval_hits(&self, iv: &RayInterval, t_min: f32, far_lo: f32, far_hi: f32) -> (u32, u32, Vec4) {
        iv.boxes_hit(&self.bounds, t_min, far_lo, far_hi)
    }

    /// Same boxes (bit for bit) and children.
    pub fn same_as(&self, o: &Node4) -> bool {
        self.children == o.children
            && self
                .bounds
                .iter()
                .zip(&o.bounds)
                .all(|(a, b)| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits))
    }

    /// The box of child `lane`.
    pub fn child_bounds(&self, lane: usize) -> crate::math::Aabb {
        let axis = |k: usize| {
            glam::Vec3::new(
                lane_of(&self.bounds[k], lane),
                lane_of(&self.bounds[k + 1], lane),
                lane_of(&self.bounds[k + 2], lane),
            )
        };
        crate::math::Aabb { min: axis(0), max: axis(3) }
    }

    /// Lanes whose box overlaps the ray within `[t_min, t_max]`, and each lane's entry
    /// distance (meaningful where the lane hits).
    #[inline(always)]
    pub fn hit(&self, r: &RayBox4, t_min: f32, t_max: f32) -> (BVec4A, Vec4) {
        let mut near = Vec4::splat(t_min);
        let mut far = Vec4::splat(t_max);
        for axis in 0..3 {
            let t0 = (self.bounds[axis] - r.origin[axis]) * r.inv_dir[axis];
            let t1 = (self.bounds[axis + 3] - r.origin[axis]) * r.inv_dir[axis];
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        (near.cmple(far), near)
    }
}

/// Collapses the binary tree `nodes` (root at 0) into four-wide nodes (root at 0).
pub(super) fn collapse(nodes: &[Node]) -> Vec<Node4> {
    let mut out = Vec::new();
    if let Some(root) = nodes.first() {
        if root.count > 0 {
            out.push(node4(nodes, &[0], |_| LEAF | root.offset));
        } else {
            collapse_node(nodes, 0, &mut out);
        }
    }
    out
}

fn node4(nodes: &[Node], kids: &[usize], mut child: impl FnMut(usize) -> u32) -> Node4 {
    let mut n = Node4 { bounds: [Vec4::INFINITY; 6], children: [EMPTY; 4] };
    for (lane, &k) in kids.iter().enumerate() {
        let b = nodes[k].bounds;
        for axis in 0..3 {
            n.bounds[axis][lane] = b.min[axis];
            n.bounds[axis + 3][lane] = b.max[axis];
        }
        n.children[lane] = child(k);
    }
    n
}

/// Gathers up to four descendants of interior node `index` by repeatedly opening the interior
/// child with the largest surface area (the most likely to be hit), then recurses.
fn collapse_node(nodes: &[Node], index: usize, out: &mut Vec<Node4>) -> u32 {
    let children = |i: usize| [i + 1, nodes[i].offset as usize];
    let mut kids: Vec<usize> = children(index).to_vec();
    while kids.len() < 4 {
        let open = kids
            .iter()
            .enumerate()
            .filter(|(_, &k)| nodes[k].count == 0)
            .max_by(|(_, &a), (_, &b)| nodes[a].bounds.surface_area().total_cmp(&nodes[b].bounds.surface_area()))
            .map(|(pos, _)| pos);
        let Some(pos) = open else { break };
        let k = kids.remove(pos);
        kids.extend(children(k));
    }
    let me = out.len();
    out.push(Node4 { bounds: [Vec4::INFINITY; 6], children: [EMPTY; 4] });
    let node =
        node4(nodes, &kids, |k| if nodes[k].count > 0 { LEAF | nodes[k].offset } else { collapse_node(nodes, k, out) });
    out[me] = node;
    me as u32
}

/// Levels of four-wide nodes on the longest root-to-leaf path (0 for an empty tree).
pub(super) fn wide_depth(nodes: &[Node4]) -> usize {
    fn depth(nodes: &[Node4], i: u32) -> usize {
        1 + nodes[i as usize].children.iter().filter(|&&c| c & LEAF == 0).map(|&c| depth(nodes, c)).max().unwrap_or(0)
    }
    if nodes.is_empty() {
        0
    } else {
        depth(nodes, 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Pcg32;
    use glam::Vec3;

    use super::super::test_draws::{point, uniform};

    /// A child the interval test drops is missed by every ray of the group in the per-ray test,
    /// and a child it says every ray hits is hit by all (the walks' results depend on that
    /// alone); for groups that go one way the test finds most of the children all rays miss,
    /// and many that all rays hit. Groups: one origin or a patch of origins,
    /// directions in a narrow or a wide cone, some lanes off, and `t_far` finite or not.
    #[test]
    fn interval_masks_agree_with_each_rays_test() {
        const N: usize = 32;
        let mut rng = Pcg32::new(11, 5);
        let (mut missed_by_all, mut dropped, mut groups) = (0, 0, 0);
        let (mut hit_by_all, mut kept_whole) = (0, 0);
        for g in 0..3000 {
            let centre = point(&mut rng, 6.0);
            let aim = point(&mut rng, 1.0).normalize_or(Vec3::X);
            let spread = [0.0, 0.02, 0.3][g % 3];
            let patch = [0.0, 0.05, 1.0][g / 3 % 3];
            let (mut origin, mut dir) = (Vec3s::<N>::default(), Vec3s::<N>::default());
            for i in 0..N {
                origin.set(i, centre + point(&mut rng, patch));
                dir.set(i, (aim + point(&mut rng, spread)).normalize_or(Vec3::X));
            }
            let lanes = Ms::<N>::from_fn(|_| g % 4 != 3 || !rng.next_u32().is_multiple_of(3));
            let rays = RayBoxes::new(&origin, &dir);
            let Some(iv) = RayInterval::of(&rays, lanes) else { continue };
            groups += 1;
            let t_far = F32s::<N>::from_fn(|_| if g % 2 == 0 { f32::INFINITY } else { uniform(&mut rng, 0.5, 12.0) });
            let t_min = F32s::<N>::splat(0.0);
            let (least, bound) = (t_far.min_over(lanes), t_far.max_over(lanes));
            for _ in 0..8 {
                let mut node = Node4::default();
                for lane in 0..4 {
                    let (c, h) = (point(&mut rng, 8.0), point(&mut rng, 1.5).abs());
                    for axis in 0..3 {
                        node.bounds[axis][lane] = c[axis] - h[axis];
                        node.bounds[axis + 3][lane] = c[axis] + h[axis];
                    }
                }
                let (may, all, _) = node.interval_hits(&iv, 0.0, least, bound);
                for lane in 0..4 {
                    let hits = node.child_hit_lanes(lane, &rays, t_min, t_far).0 & lanes.bitmask();
                    if may >> lane & 1 == 0 {
                        assert_eq!(hits, 0, "group {g}: a dropped box is hit by rays {hits:#x}");
                        dropped += 1;
                    }
                    if all >> lane & 1 != 0 {
                        assert_eq!(hits, lanes.bitmask(), "group {g}: a box said hit by all is missed by some");
                        kept_whole += 1;
                    }
                    missed_by_all += usize::from(hits == 0);
                    hit_by_all += usize::from(hits == lanes.bitmask());
                }
            }
        }
        assert!(groups > 1500, "{groups} groups went one way");
        assert!(dropped * 10 > missed_by_all * 9, "dropped {dropped} of {missed_by_all} boxes all rays miss");
        assert!(kept_whole * 2 > hit_by_all, "{kept_whole} of {hit_by_all} boxes every ray hits said so");
    }
}
