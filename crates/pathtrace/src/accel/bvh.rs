//! A bounding volume hierarchy built with the binned surface area heuristic (Wald, "On fast
//! Construction of SAH-based Bounding Volume Hierarchies", RT 2007), stored as a flat node array
//! in depth-first order (the left child follows its parent), and traversed near child first.

use crate::math::{Aabb, Ray, Vec3};
use crate::shape::PrimHit;

/// Anything the BVH can hold.
pub trait Intersectable {
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<PrimHit>;
}

/// One node: 32 bytes. Leaves hold `count > 0` primitives from `offset`; interior nodes have
/// their left child at `index + 1` and their right child at `offset`.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    offset: u32,
    count: u16,
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
}

const BINS: usize = 16;
/// SAH costs relative to one primitive test: a node visit costs about as much as one
/// ray–primitive test for the small primitives used here (quads, triangles, spheres).
const TRAVERSAL_COST: f32 = 1.0;
const MAX_LEAF: usize = 8;
/// Below this depth the SAH decides; deeper subtrees split at the object median, which bounds
/// the depth (and the traversal stack) for pathological inputs.
const SAH_DEPTH_LIMIT: usize = 32;
/// Depth ≤ 32 + log2(n) < 64 for any n below 2³².
const STACK_SIZE: usize = 64;

struct BuildItem {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
}

impl Bvh {
    /// Builds over the given primitive bounds. Returns the tree and the primitive order it
    /// expects (position `i` in the reordered array holds original primitive `order[i]`).
    pub fn build(bounds: &[Aabb]) -> (Bvh, Vec<u32>) {
        let mut items: Vec<BuildItem> = bounds
            .iter()
            .enumerate()
            .map(|(i, b)| BuildItem { bounds: b.padded(), centroid: b.centroid(), index: i as u32 })
            .collect();
        let mut bvh = Bvh { nodes: Vec::with_capacity(2 * bounds.len().max(1)) };
        if !items.is_empty() {
            let n = items.len();
            bvh.build_node(&mut items, 0, n, 0);
        }
        let order = items.iter().map(|it| it.index).collect();
        (bvh, order)
    }

    fn build_node(&mut self, items: &mut [BuildItem], start: usize, end: usize, depth: usize) -> usize {
        let node_index = self.nodes.len();
        let slice = &mut items[start..end];
        let bounds = slice.iter().fold(Aabb::EMPTY, |b, it| b.union(it.bounds));
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
    #[inline]
    pub fn intersect<P: Intersectable>(
        &self,
        prims: &[P],
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
    ) -> Option<(PrimHit, u32)> {
        if self.nodes.is_empty() {
            return None;
        }
        let inv_dir = glam::Vec3A::from(ray.dir).recip();
        let origin = glam::Vec3A::from(ray.origin);
        let neg = [ray.dir.x < 0.0, ray.dir.y < 0.0, ray.dir.z < 0.0];
        let mut stack = [0u32; STACK_SIZE];
        let mut sp = 0;
        let mut node_index = 0usize;
        let mut best = None;
        loop {
            let node = &self.nodes[node_index];
            if node.bounds.hit(origin, inv_dir, t_min, t_max).is_some() {
                if node.count > 0 {
                    let first = node.offset as usize;
                    for (k, prim) in prims[first..first + node.count as usize].iter().enumerate() {
                        if let Some(hit) = prim.intersect(ray, t_min, t_max) {
                            t_max = hit.t;
                            best = Some((hit, (first + k) as u32));
                        }
                    }
                } else {
                    // Visit the child on the ray's near side first; push the far one.
                    let (near, far) = if neg[node.axis as usize] {
                        (node.offset as usize, node_index + 1)
                    } else {
                        (node_index + 1, node.offset as usize)
                    };
                    stack[sp] = far as u32;
                    sp += 1;
                    node_index = near;
                    continue;
                }
            }
            if sp == 0 {
                break;
            }
            sp -= 1;
            node_index = stack[sp] as usize;
        }
        best
    }

    /// True if anything blocks the ray within `[t_min, t_max]` (stops at the first blocker).
    #[inline]
    pub fn occluded<P: Intersectable>(&self, prims: &[P], ray: &Ray, t_min: f32, t_max: f32) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let inv_dir = glam::Vec3A::from(ray.dir).recip();
        let origin = glam::Vec3A::from(ray.origin);
        let mut stack = [0u32; STACK_SIZE];
        let mut sp = 0;
        let mut node_index = 0usize;
        loop {
            let node = &self.nodes[node_index];
            if node.bounds.hit(origin, inv_dir, t_min, t_max).is_some() {
                if node.count > 0 {
                    let first = node.offset as usize;
                    if prims[first..first + node.count as usize]
                        .iter()
                        .any(|p| p.intersect(ray, t_min, t_max).is_some())
                    {
                        return true;
                    }
                } else {
                    stack[sp] = node.offset;
                    sp += 1;
                    node_index += 1;
                    continue;
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            node_index = stack[sp] as usize;
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
        let Some(n) = self.nodes.get(index) else { return };
        let kind = if n.count > 0 {
            format!("leaf {} prims from {}", n.count, n.offset)
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

/// Picks a split: (axis, number of items going left), after partitioning `items` in place.
/// `None` means "make a leaf".
fn choose_split(items: &mut [BuildItem], bounds: &Aabb, depth: usize) -> Option<(usize, usize)> {
    let n = items.len();
    let centroid_bounds = items.iter().fold(Aabb::EMPTY, |b, it| b.grow(it.centroid));
    let extent = centroid_bounds.extent();
    let widest = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    if extent[widest] <= 0.0 {
        // All centroids coincide: no spatial split helps.
        return (n > MAX_LEAF).then(|| median_split(items, widest));
    }
    if depth >= SAH_DEPTH_LIMIT {
        return Some(median_split(items, widest));
    }

    // Binned SAH over all three axes: cost = C_trav + (A_L N_L + A_R N_R) / A_parent.
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, bins on the left)
    for axis in 0..3 {
        let lo = centroid_bounds.min[axis];
        let width = extent[axis];
        if width <= 0.0 {
            continue;
        }
        let scale = BINS as f32 / width;
        let mut bin_bounds = [Aabb::EMPTY; BINS];
        let mut bin_counts = [0usize; BINS];
        for it in items.iter() {
            let b = (((it.centroid[axis] - lo) * scale) as usize).min(BINS - 1);
            bin_counts[b] += 1;
            bin_bounds[b] = bin_bounds[b].union(it.bounds);
        }
        // Sweep from the right to get suffix areas, then from the left.
        let mut right_area = [0.0f32; BINS];
        let mut right_count = [0usize; BINS];
        let (mut acc_b, mut acc_n) = (Aabb::EMPTY, 0);
        for i in (1..BINS).rev() {
            acc_b = acc_b.union(bin_bounds[i]);
            acc_n += bin_counts[i];
            right_area[i] = acc_b.surface_area();
            right_count[i] = acc_n;
        }
        let (mut left_b, mut left_n) = (Aabb::EMPTY, 0);
        for split in 1..BINS {
            left_b = left_b.union(bin_bounds[split - 1]);
            left_n += bin_counts[split - 1];
            if left_n == 0 || right_count[split] == 0 {
                continue;
            }
            let cost = left_b.surface_area() * left_n as f32 + right_area[split] * right_count[split] as f32;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, split));
            }
        }
    }
    let parent_area = bounds.surface_area().max(f32::MIN_POSITIVE);
    let Some((cost, axis, split)) = best else {
        return (n > MAX_LEAF).then(|| median_split(items, widest));
    };
    let split_cost = TRAVERSAL_COST + cost / parent_area;
    let leaf_cost = n as f32;
    if split_cost >= leaf_cost && n <= MAX_LEAF {
        return None;
    }
    let lo = centroid_bounds.min[axis];
    let scale = BINS as f32 / extent[axis];
    let mid = partition(items, |it| ((((it.centroid[axis] - lo) * scale) as usize).min(BINS - 1)) < split);
    if mid == 0 || mid == n {
        return Some(median_split(items, axis));
    }
    Some((axis, mid))
}

fn median_split(items: &mut [BuildItem], axis: usize) -> (usize, usize) {
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    (axis, mid)
}

/// In-place partition; returns the number of items for which `pred` holds (now at the front).
fn partition(items: &mut [BuildItem], pred: impl Fn(&BuildItem) -> bool) -> usize {
    let mut first = 0;
    for i in 0..items.len() {
        if pred(&items[i]) {
            items.swap(first, i);
            first += 1;
        }
    }
    first
}
