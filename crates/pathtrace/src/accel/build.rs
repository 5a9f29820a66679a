//! The binned surface area heuristic (Wald, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies", RT 2007): where to split a set of primitives, or whether to make a leaf.
//! Leaf costs count SIMD packets of four primitives, not primitives.

use glam::Vec3A;

use crate::math::Aabb;

/// SAH costs relative to one node visit (a box test). A four-wide packet test costs about as
/// much as two box tests; a leaf of `n` primitives costs `ceil(n / 4)` packets.
const TRAVERSAL_COST: f32 = 1.0;
const PACKET_COST: f32 = 2.0;
/// Most SAH bins per axis and largest leaf [`BuildOptions`] accept.
pub const MAX_BINS: usize = 32;
pub const MAX_LEAF_LIMIT: usize = 64;
/// Below this depth the SAH decides; deeper subtrees split at the object median, which bounds
/// the depth (and the traversal stack) for pathological inputs.
const SAH_DEPTH_LIMIT: usize = 32;

/// How nodes are split.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SplitMethod {
    /// Binned surface area heuristic: the production build.
    Sah,
    /// Object median on the widest centroid axis down to `max_leaf` primitives: only the
    /// baseline of the analysis in docs/bvh.md.
    Median,
}

/// Build parameters. The defaults are the production build; docs/bvh.md has the measurements
/// behind `bins` and `max_leaf`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BuildOptions {
    pub method: SplitMethod,
    /// SAH candidate planes per axis (clamped to `2..=MAX_BINS`).
    pub bins: usize,
    /// Largest leaf (clamped to `1..=MAX_LEAF_LIMIT`); the SAH may stop earlier.
    pub max_leaf: usize,
    /// Subtrees of more primitives than this are built on separate rayon tasks; `usize::MAX`
    /// builds serially. Either way the tree is the same.
    pub parallel_above: usize,
}

impl BuildOptions {
    /// Above this size a subtree is worth a rayon task: a task costs about a microsecond, far
    /// less than building thousands of primitives, and there are still many more tasks than cores.
    pub const PARALLEL_ABOVE: usize = 4096;

    pub fn serial(self) -> Self {
        Self { parallel_above: usize::MAX, ..self }
    }

    pub(super) fn clamped(self) -> Self {
        Self {
            bins: self.bins.clamp(2, MAX_BINS),
            max_leaf: self.max_leaf.clamp(1, MAX_LEAF_LIMIT),
            parallel_above: self.parallel_above.max(1),
            ..self
        }
    }
}

impl Default for BuildOptions {
    fn default() -> Self {
        Self { method: SplitMethod::Sah, bins: 16, max_leaf: 8, parallel_above: Self::PARALLEL_ABOVE }
    }
}

/// A box on SIMD lanes: the build's unit of work is unions and areas of these.
#[derive(Clone, Copy, Debug)]
pub(super) struct Box3 {
    pub min: Vec3A,
    pub max: Vec3A,
}

impl Box3 {
    pub const EMPTY: Box3 = Box3 { min: Vec3A::INFINITY, max: Vec3A::NEG_INFINITY };

    #[inline(always)]
    pub fn union(self, o: Box3) -> Box3 {
        Box3 { min: self.min.min(o.min), max: self.max.max(o.max) }
    }

    #[inline(always)]
    pub fn grow(self, p: Vec3A) -> Box3 {
        Box3 { min: self.min.min(p), max: self.max.max(p) }
    }

    /// Surface area, the SAH's probability measure (MacDonald & Booth 1990); 0 when empty.
    #[inline(always)]
    pub fn area(self) -> f32 {
        let e = self.max - self.min;
        if e.cmplt(Vec3A::ZERO).any() {
            return 0.0;
        }
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    pub fn to_aabb(self) -> Aabb {
        Aabb::new(self.min.into(), self.max.into())
    }
}

impl From<Aabb> for Box3 {
    fn from(b: Aabb) -> Self {
        Box3 { min: b.min.into(), max: b.max.into() }
    }
}

pub(super) struct BuildItem {
    pub bounds: Box3,
    pub index: u32,
}

impl BuildItem {
    #[inline(always)]
    pub fn centroid(&self) -> Vec3A {
        0.5 * (self.bounds.min + self.bounds.max)
    }
}

/// Bounds of the items' boxes and of their centroids, in one pass.
pub(super) fn extents(items: &[BuildItem]) -> (Box3, Box3) {
    items.iter().fold((Box3::EMPTY, Box3::EMPTY), |(b, c), it| (b.union(it.bounds), c.grow(it.centroid())))
}

/// SAH cost of intersecting `n` primitives in a leaf.
fn leaf_cost(n: usize) -> f32 {
    n.div_ceil(4) as f32 * PACKET_COST
}

/// Primitives whose box has at least this fraction of their node's surface area are "large".
const LARGE_FRACTION: f32 = 0.25;

/// Picks a split of a node with box `bounds` and centroid box `centroids`: (axis, number of
/// items going left), after partitioning `items` in place. `None` means "make a leaf".
pub(super) fn choose_split(
    items: &mut [BuildItem],
    bounds: &Box3,
    centroids: &Box3,
    depth: usize,
    opts: &BuildOptions,
) -> Option<(usize, usize)> {
    let n = items.len();
    let max_leaf = opts.max_leaf;
    let extent = (centroids.max - centroids.min).max(Vec3A::ZERO);
    let widest = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    if extent[widest] <= 0.0 {
        // All centroids coincide: no spatial split helps.
        return (n > max_leaf).then(|| median_split(items, widest));
    }
    if opts.method == SplitMethod::Median {
        return (n > max_leaf).then(|| median_split(items, widest));
    }
    if depth >= SAH_DEPTH_LIMIT {
        return Some(median_split(items, widest));
    }

    // One pass bins the centroids on all three axes and sorts items into large and small.
    // Axes of zero width get scale 0: everything lands in bin 0 and no plane is valid there.
    let bins = opts.bins;
    let lo = centroids.min;
    let scale = Vec3A::select(extent.cmpgt(Vec3A::ZERO), Vec3A::splat(bins as f32) / extent, Vec3A::ZERO);
    let bin_of = |c: Vec3A| ((c - lo) * scale).to_array().map(|f| (f as usize).min(bins - 1));
    let parent_area = bounds.area().max(f32::MIN_POSITIVE);
    let large_area = LARGE_FRACTION * parent_area;
    let mut bin_bounds = [[Box3::EMPTY; MAX_BINS]; 3];
    let mut bin_counts = [[0usize; MAX_BINS]; 3];
    let (mut large, mut small) = ((Box3::EMPTY, 0usize), (Box3::EMPTY, 0usize));
    for it in items.iter() {
        let b = bin_of(it.centroid());
        for axis in 0..3 {
            bin_counts[axis][b[axis]] += 1;
            bin_bounds[axis][b[axis]] = bin_bounds[axis][b[axis]].union(it.bounds);
        }
        let side = if it.bounds.area() >= large_area { &mut large } else { &mut small };
        *side = (side.0.union(it.bounds), side.1 + 1);
    }

    // Binned SAH (Wald 2007) over all three axes: cost = C_trav + (A_L C(N_L) + A_R C(N_R)) / A.
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, bins on the left)
    for axis in 0..3 {
        let (bb, bc) = (&bin_bounds[axis], &bin_counts[axis]);
        // Sweep from the right to get suffix areas, then from the left.
        let mut right_area = [0.0f32; MAX_BINS];
        let mut right_count = [0usize; MAX_BINS];
        let (mut acc_b, mut acc_n) = (Box3::EMPTY, 0);
        for i in (1..bins).rev() {
            acc_b = acc_b.union(bb[i]);
            acc_n += bc[i];
            right_area[i] = acc_b.area();
            right_count[i] = acc_n;
        }
        let (mut left_b, mut left_n) = (Box3::EMPTY, 0);
        for split in 1..bins {
            left_b = left_b.union(bb[split - 1]);
            left_n += bc[split - 1];
            if left_n == 0 || right_count[split] == 0 {
                continue;
            }
            let cost = left_b.area() * leaf_cost(left_n) + right_area[split] * leaf_cost(right_count[split]);
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, split));
            }
        }
    }
    let Some((cost, axis, split)) = best else {
        return (n > max_leaf).then(|| median_split(items, widest));
    };
    // An extra candidate besides the centroid planes: large primitives in one child, the rest
    // in the other. Centroid splits cannot group the walls of a room (their centroids surround
    // everything else), so without it every split keeps some wall and every child spans the room.
    let large_cost =
        (large.1 > 0 && small.1 > 0).then(|| large.0.area() * leaf_cost(large.1) + small.0.area() * leaf_cost(small.1));
    if let Some(large_cost) = large_cost.filter(|&c| c < cost) {
        if TRAVERSAL_COST + large_cost / parent_area >= leaf_cost(n) && n <= max_leaf {
            return None;
        }
        let mid = partition(items, |it| it.bounds.area() >= large_area);
        return Some((widest, mid));
    }
    if TRAVERSAL_COST + cost / parent_area >= leaf_cost(n) && n <= max_leaf {
        return None;
    }
    let mid = partition(items, |it| bin_of(it.centroid())[axis] < split);
    if mid == 0 || mid == n {
        return Some(median_split(items, axis));
    }
    Some((axis, mid))
}

fn median_split(items: &mut [BuildItem], axis: usize) -> (usize, usize) {
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| a.centroid()[axis].total_cmp(&b.centroid()[axis]));
    (axis, mid)
}

/// In-place partition; returns the number of items for which `pred` holds (now at the front).
/// Hoare's scheme: it swaps only misplaced pairs, about half the swaps of a one-sided scan.
fn partition(items: &mut [BuildItem], pred: impl Fn(&BuildItem) -> bool) -> usize {
    let (mut i, mut j) = (0, items.len());
    loop {
        while i < j && pred(&items[i]) {
            i += 1;
        }
        while i < j && !pred(&items[j - 1]) {
            j -= 1;
        }
        if i == j {
            return i;
        }
        items.swap(i, j - 1);
        i += 1;
        j -= 1;
    }
}
