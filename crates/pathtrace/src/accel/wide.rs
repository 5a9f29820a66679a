//! A four-wide BVH collapsed from the binary SAH tree (Dammertz et al., "Shallow Bounding Volume
//! Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays", EGSR 2008): each node holds four
//! child boxes in SIMD lanes and tests them with one slab test (Kay & Kajiya 1986).

use glam::{BVec4A, Vec4};

use super::bvh::Node;
use super::lanes::lane_of;
use crate::math::Ray;
use crate::wide::simd::{F32s, Vec3s};

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
