//! A bounding volume hierarchy built with the binned surface area heuristic (see `build.rs`),
//! stored as a flat node array in depth-first order (the left child follows its parent), and
//! traversed as a four-wide tree (see `wide.rs`). Leaves test their quads and triangles four
//! at a time (see `leaf.rs`).

use super::build::{choose_split, BuildItem};
use super::lanes::RayX4;
use super::leaf::{Leaves, Packable};
use super::wide::{collapse, Node4, RayBox4, EMPTY, LEAF};
use crate::math::{Aabb, Ray};
use crate::shape::PrimHit;

/// Anything the BVH can hold.
pub trait Intersectable {
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit>;
}

/// One node: 32 bytes. Leaves have `count > 0` primitives and `offset` indexes their leaf
/// record; interior nodes have their left child at `index + 1` and their right child at
/// `offset`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Node {
    pub bounds: Aabb,
    pub offset: u32,
    pub count: u16,
    axis: u16,
}

/// Shape statistics of a built tree.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BvhStats {
    pub nodes: usize,
    pub leaves: usize,
    pub max_depth: usize,
    pub max_leaf_size: usize,
}

/// The hierarchy. Primitive indices in leaves refer to the order returned by [`Bvh::build`].
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// The same tree, four children per node, for traversal.
    wide: Vec<Node4>,
    leaves: Leaves,
    /// Traversal stack slots needed: a four-wide node visit pushes at most four children and
    /// pops one, so 3 per level (the wide tree is no deeper than the binary one) plus 1.
    stack_need: usize,
}

/// Depth ≤ 32 + log2(n) < 64 for any n below 2³², so 3 · 64 + 1 slots always suffice.
const STACK_SIZE: usize = 3 * 64 + 1;
/// Most trees fit this smaller stack, which is cheaper to zero for every ray (zeroing the
/// large one cost ~4% of all instructions on the Cornell box).
const SMALL_STACK: usize = 16;

impl Bvh {
    /// Builds over the given primitive bounds; `kinds[i]` says whether primitive `i` goes into
    /// a SIMD packet. Returns the tree and the primitive order it expects (position `i` in the
    /// reordered array holds original primitive `order[i]`).
    pub fn build(bounds: &[Aabb], kinds: &[Packable]) -> (Bvh, Vec<u32>) {
        assert_eq!(bounds.len(), kinds.len());
        let mut items: Vec<BuildItem> = bounds
            .iter()
            .enumerate()
            .map(|(i, b)| BuildItem { bounds: b.padded(), centroid: b.centroid(), index: i as u32 })
            .collect();
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * bounds.len().max(1)),
            wide: Vec::new(),
            leaves: Leaves::default(),
            stack_need: 0,
        };
        if !items.is_empty() {
            let n = items.len();
            bvh.build_node(&mut items, 0, n, 0);
        }
        let order: Vec<u32> = items.iter().map(|it| it.index).collect();
        for node in bvh.nodes.iter_mut().filter(|n| n.count > 0) {
            let start = node.offset as usize;
            node.offset = bvh.leaves.push(|i| kinds[order[i] as usize], start..start + node.count as usize);
        }
        bvh.stack_need = 3 * bvh.stats().max_depth + 1;
        bvh.wide = collapse(&bvh.nodes);
        (bvh, order)
    }

    fn build_node(&mut self, items: &mut [BuildItem], start: usize, end: usize, depth: usize) -> usize {
        let node_index = self.nodes.len();
        let slice = &mut items[start..end];
        let bounds = slice.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds));
        // Leaves hold their first item's position until `build` replaces it by a leaf record.
        self.nodes.push(Node { bounds, offset: start as u32, count: slice.len() as u16, axis: 0 });
        if slice.len() == 1 {
            return node_index;
        }
        let Some((axis, mid)) = choose_split(slice, &bounds, depth) else {
            return node_index; // a leaf is cheapest
        };
        let left = self.build_node(items, start, start + mid, depth + 1);
        debug_assert_eq!(left, node_index + 1);
        let right = self.build_node(items, start + mid, end, depth + 1);
        let node = &mut self.nodes[node_index];
        node.offset = right as u32;
        node.count = 0;
        node.axis = axis as u16;
        node_index
    }

    /// Closest hit among `prims` (in build order) with `t ∈ [t_min, t_max]`.
    #[inline(always)]
    pub fn intersect<P: Intersectable>(
        &self,
        prims: &[P],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
    ) -> Option<(PrimHit, u32)> {
        if self.nodes.is_empty() {
            return None;
        }
        if self.stack_need <= SMALL_STACK {
            self.closest::<P, SMALL_STACK>(prims, ray, t_min, t_max)
        } else {
            self.closest::<P, STACK_SIZE>(prims, ray, t_min, t_max)
        }
    }

    #[inline(always)]
    fn closest<P: Intersectable, const N: usize>(
        &self,
        prims: &[P],
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
    ) -> Option<(PrimHit, u32)> {
        let rb = RayBox4::new(ray);
        let rx4 = RayX4::new(ray);
        let mut stack = [0u32; N];
        let mut sp = 0;
        let mut node = 0u32;
        let mut best = None;
        loop {
            let n = &self.wide[node as usize];
            let mut lanes = n.hit(&rb, t_min, t_max).bitmask();
            // Leaves are tested at once (shrinking t_max for the rest); interior children wait.
            while lanes != 0 {
                let child = n.children[lanes.trailing_zeros() as usize];
                lanes &= lanes - 1;
                if child & LEAF == 0 {
                    stack[sp] = child;
                    sp += 1;
                } else if child != EMPTY {
                    self.leaves.intersect(child & !LEAF, prims, ray, &rx4, t_min, &mut t_max, &mut best);
                }
            }
            if sp == 0 {
                return best;
            }
            sp -= 1;
            node = stack[sp];
        }
    }

    /// True if anything blocks the ray within `[t_min, t_max]` (stops at the first blocker).
    #[inline(always)]
    pub fn occluded<P: Intersectable>(&self, prims: &[P], ray: &Ray, t_min: f32, t_max: f32) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        if self.stack_need <= SMALL_STACK {
            self.any_hit::<P, SMALL_STACK>(prims, ray, t_min, t_max)
        } else {
            self.any_hit::<P, STACK_SIZE>(prims, ray, t_min, t_max)
        }
    }

    #[inline(always)]
    fn any_hit<P: Intersectable, const N: usize>(&self, prims: &[P], ray: &Ray, t_min: f32, t_max: f32) -> bool {
        let rb = RayBox4::new(ray);
        let rx4 = RayX4::new(ray);
        let mut stack = [0u32; N];
        let mut sp = 0;
        let mut node = 0u32;
        loop {
            let n = &self.wide[node as usize];
            let mut lanes = n.hit(&rb, t_min, t_max).bitmask();
            while lanes != 0 {
                let child = n.children[lanes.trailing_zeros() as usize];
                lanes &= lanes - 1;
                if child & LEAF == 0 {
                    stack[sp] = child;
                    sp += 1;
                } else if child != EMPTY && self.leaves.occluded(child & !LEAF, prims, ray, &rx4, t_min, t_max) {
                    return true;
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            node = stack[sp];
        }
    }

    /// Bounds of everything in the tree.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    /// One line per node, indented by depth (for debugging and the docs).
    pub fn dump(&self) -> String {
        let mut out = String::new();
        self.dump_node(0, 0, &mut out);
        out
    }

    fn dump_node(&self, index: usize, depth: usize, out: &mut String) {
        let Some(n) = self.nodes.get(index) else {
            return;
        };
        let kind = if n.count > 0 {
            let (packets, scalar) = self.leaves.sizes(n.offset);
            format!("leaf {} prims ({packets} packets + {scalar} single)", n.count)
        } else {
            format!("split axis {}", n.axis)
        };
        out.push_str(&format!(
            "{:indent$}{kind} [{:.0?} – {:.0?}]\n",
            "",
            n.bounds.min.to_array(),
            n.bounds.max.to_array(),
            indent = 2 * depth
        ));
        if n.count == 0 {
            self.dump_node(index + 1, depth + 1, out);
            self.dump_node(n.offset as usize, depth + 1, out);
        }
    }

    pub fn stats(&self) -> BvhStats {
        let mut stats = BvhStats { nodes: self.nodes.len(), ..Default::default() };
        if !self.nodes.is_empty() {
            self.walk_stats(0, 1, &mut stats);
        }
        stats
    }

    fn walk_stats(&self, index: usize, depth: usize, stats: &mut BvhStats) {
        let node = &self.nodes[index];
        stats.max_depth = stats.max_depth.max(depth);
        if node.count > 0 {
            stats.leaves += 1;
            stats.max_leaf_size = stats.max_leaf_size.max(node.count as usize);
        } else {
            self.walk_stats(index + 1, depth + 1, stats);
            self.walk_stats(node.offset as usize, depth + 1, stats);
        }
    }
}
