//! The binned surface area heuristic (Wald, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies", RT 2007): where to split a set of primitives, or whether to make a leaf.
//! Leaf costs count SIMD packets of four primitives, not primitives.

use crate::math::{Aabb, Vec3};

const BINS: usize = 16;
/// SAH costs relative to one node visit (a box test). A four-wide packet test costs about as
/// much as two box tests; a leaf of `n` primitives costs `ceil(n / 4)` packets.
const TRAVERSAL_COST: f32 = 1.0;
const PACKET_COST: f32 = 2.0;
pub(super) const MAX_LEAF: usize = 8;
/// Below this depth the SAH decides; deeper subtrees split at the object median, which bounds
/// the depth (and the traversal stack) for pathological inputs.
const SAH_DEPTH_LIMIT: usize = 32;

pub(super) struct BuildItem {
    pub bounds: Aabb,
    pub centroid: Vec3,
    pub index: u32,
}

/// SAH cost of intersecting `n` primitives in a leaf.
fn leaf_cost(n: usize) -> f32 {
    n.div_ceil(4) as f32 * PACKET_COST
}

/// Picks a split: (axis, number of items going left), after partitioning `items` in place.
/// `None` means "make a leaf".
pub(super) fn choose_split(items: &mut [BuildItem], bounds: &Aabb, depth: usize) -> Option<(usize, usize)> {
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

    // Binned SAH over all three axes: cost = C_trav + (A_L C(N_L) + A_R C(N_R)) / A_parent.
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
            let cost = left_b.surface_area() * leaf_cost(left_n) + right_area[split] * leaf_cost(right_count[split]);
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, split));
            }
        }
    }
    let parent_area = bounds.surface_area().max(f32::MIN_POSITIVE);
    let Some((cost, axis, split)) = best else {
        return (n > MAX_LEAF).then(|| median_split(items, widest));
    };
    let large_cost = large_small_cost(items, parent_area);
    if large_cost.is_some_and(|c| c < cost) {
        let split_cost = TRAVERSAL_COST + large_cost.unwrap_or(cost) / parent_area;
        if split_cost >= leaf_cost(n) && n <= MAX_LEAF {
            return None;
        }
        let mid = partition(items, |it| is_large(it, parent_area));
        return Some((widest, mid));
    }
    let split_cost = TRAVERSAL_COST + cost / parent_area;
    if split_cost >= leaf_cost(n) && n <= MAX_LEAF {
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

/// Primitives whose box has at least this fraction of their node's surface area are "large".
const LARGE_FRACTION: f32 = 0.25;

fn is_large(it: &BuildItem, parent_area: f32) -> bool {
    it.bounds.surface_area() >= LARGE_FRACTION * parent_area
}

/// An extra SAH candidate besides the centroid planes: large primitives in one child, the rest
/// in the other. Centroid splits cannot group the walls of a room (their centroids surround
/// everything else), so without it every split keeps some wall and every child spans the room.
/// Returns `A_L C(N_L) + A_R C(N_R)`, or `None` if either side would be empty.
fn large_small_cost(items: &[BuildItem], parent_area: f32) -> Option<f32> {
    let (mut large, mut small) = ((Aabb::EMPTY, 0), (Aabb::EMPTY, 0));
    for it in items {
        let side = if is_large(it, parent_area) { &mut large } else { &mut small };
        *side = (side.0.union(it.bounds), side.1 + 1);
    }
    (large.1 > 0 && small.1 > 0)
        .then(|| large.0.surface_area() * leaf_cost(large.1) + small.0.surface_area() * leaf_cost(small.1))
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
