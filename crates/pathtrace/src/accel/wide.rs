//! An eight-wide BVH collapsed from the binary SAH tree (Dammertz et al., "Shallow Bounding
//! Volume Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays", EGSR 2008; eight children
//! as Embree's BVH8 on AVX CPUs): each node holds its eight child boxes one per SIMD lane and
//! tests them with the slab test (Kay & Kajiya 1986), all eight in 256-bit vectors where the
//! caller is compiled for AVX (the render loops' group walks), four at a time elsewhere (see
//! [`BoxLanes`]). Eight children halve the tree's depth against four: a walk is a chain of
//! dependent node loads, and on trees larger than the caches fewer, larger visits are faster
//! (docs/bvh.md, "Eight-wide nodes").

use glam::Vec4;

use super::bvh::Node;
use super::lanes::Lane;
use crate::math::Ray;
use crate::wide::simd::{F32s, Ms, Vec3s};

/// Child tag for leaves (the low bits are the leaf record).
pub(super) const LEAF: u32 = 1 << 31;
/// Child slot without a child.
pub(super) const EMPTY: u32 = u32::MAX;

/// Children per node.
pub(super) const WIDTH: usize = 8;
/// Eight children: their boxes (per plane, min x, y, z, max x, y, z, one child per lane) and
/// indices (an interior node, `LEAF | leaf reference` (see `leaf.rs`), or
/// `EMPTY`; the children fill the first slots, so the first empty slot ends them). Empty lanes
/// have the box `[+∞, +∞]`, whose slab distances are all +∞ or all −∞: never hit within a
/// finite range, but maybe "hit" at +∞ by a ray whose `t_max` is +∞, so the walks check the slot's
/// index, not only the test's bit. 224 bytes, aligned to 64 so that a node spans exactly four
/// cache lines (the 32 bytes of padding are counted in the memory figures of docs/bvh.md).
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
pub(super) struct WideNode {
    planes: [[f32; WIDTH]; 6],
    pub children: [u32; WIDTH],
}

const _: () = assert!(std::mem::size_of::<WideNode>() == 256);

/// Asks the caches for node `index`'s four lines when it is pushed, ahead of its visit: a
/// traversal is a chain of dependent loads, and a far child waits on the stack while the near
/// one's subtree is searched, time in which its miss can be served. A hint only (it changes no
/// value); out of range, nothing is asked.
#[inline(always)]
pub(super) fn prefetch(nodes: &[WideNode], index: u32) {
    if let Some(node) = nodes.get(index as usize) {
        crate::wide::prefetch::prefetch(std::slice::from_ref(node));
    }
}

/// The lanes a node's boxes are tested in: `F32s<8>`, all eight boxes at once, for code
/// compiled for AVX; `Vec4`, four at a time, for code that is not (there, LLVM made the
/// eight-lane form's `far` a shuffle through the stack that stalled on every visit: 1.14–1.21
/// against 1.43–1.90 M incoherent rays/s in `bench bvh`; docs/bvh.md, "Eight boxes in one
/// test").
pub(super) trait BoxLanes: Lane {
    /// Boxes per test.
    const COUNT: usize;
    /// `COUNT` values from `v`.
    fn load(v: &[f32]) -> Self;
    /// `COUNT` values into `out`.
    fn store(self, out: &mut [f32]);
    /// One bit per lane, lane 0 lowest.
    fn bits(m: Self::Mask) -> u32;
}

impl BoxLanes for Vec4 {
    const COUNT: usize = 4;
    #[inline(always)]
    fn load(v: &[f32]) -> Self {
        Vec4::from_slice(v)
    }
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        self.write_to_slice(out);
    }
    #[inline(always)]
    fn bits(m: glam::BVec4A) -> u32 {
        m.bitmask()
    }
}

impl BoxLanes for F32s<WIDTH> {
    const COUNT: usize = WIDTH;
    #[inline(always)]
    fn load(v: &[f32]) -> Self {
        F32s(std::array::from_fn(|i| v[i]))
    }
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        out.copy_from_slice(&self.0);
    }
    #[inline(always)]
    fn bits(m: Ms<WIDTH>) -> u32 {
        m.bitmask()
    }
}

/// A ray prepared for slab tests on boxes in lanes `L`.
#[derive(Clone, Copy, Debug)]
pub(super) struct RayBox<L> {
    origin: [L; 3],
    inv_dir: [L; 3],
}

impl<L: BoxLanes> RayBox<L> {
    #[inline(always)]
    pub fn new(ray: &Ray) -> Self {
        let inv = ray.dir.recip();
        Self {
            origin: [ray.origin.x, ray.origin.y, ray.origin.z].map(L::splat),
            inv_dir: [inv.x, inv.y, inv.z].map(L::splat),
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
    /// The same reciprocals as [`RayBox::new`] takes per ray.
    #[inline(always)]
    pub fn new(origin: &Vec3s<N>, dir: &Vec3s<N>) -> Self {
        Self { origin: [origin.x, origin.y, origin.z], inv_dir: [dir.x, dir.y, dir.z].map(|d| F32s::ONE / d) }
    }
}

/// A group of rays bounded together, for testing four of a node's boxes at a time against the whole
/// group at once (Boulos et al., "Geometric and Arithmetic Culling Methods for Entire Ray Packets",
/// 2006): per axis, the extremes of the rays' origins and of their reciprocal directions, which all
/// have one sign. Made only for such groups (a pixel's camera rays, the shadow rays of nearby
/// points to one light); a group whose directions' signs differ on some axis gets none.
#[derive(Clone, Copy, Debug)]
pub(super) struct RayInterval {
    /// Per axis: which of a box's planes the rays enter through (`axis` for the min plane,
    /// `axis + 3` for the max), and which they leave through.
    entry_plane: [usize; 3],
    exit_plane: [usize; 3],
    /// Per axis: the origin bound that gives the least entry distance (the greatest origin for
    /// rays going up the axis, the least for rays going down), and the one that gives the
    /// greatest exit distance.
    entry_origin: [f32; 3],
    exit_origin: [f32; 3],
    /// Per axis: the least and greatest reciprocal direction.
    inv_lo: [f32; 3],
    inv_hi: [f32; 3],
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
            entry_origin: [0.0; 3],
            exit_origin: [0.0; 3],
            inv_lo: [0.0; 3],
            inv_hi: [0.0; 3],
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
            iv.entry_origin[axis] = if up { o_hi } else { o_lo };
            iv.exit_origin[axis] = if up { o_lo } else { o_hi };
            iv.inv_lo[axis] = lo;
            iv.inv_hi[axis] = hi;
        }
        Some(iv)
    }

    /// Boxes (`bounds`: min x, y, z, max x, y, z, one box per lane: a packet's four, a node's
    /// eight) against the rays bounded by `self`, as [`WideNode::interval_hits`] (which see)
    /// tests a node's children: the boxes some ray may hit, those every ray hits (lane masks),
    /// and lower bounds of the entry distances.
    #[inline(always)]
    pub fn boxes_hit<L: Lane>(&self, bounds: &[L; 6], t_min: f32, far_lo: f32, far_hi: f32) -> (L::Mask, L::Mask, L) {
        let (mut near_lo, mut near_hi) = (L::splat(t_min), L::splat(t_min));
        let (mut exit_lo, mut exit_hi) = (L::splat(far_lo), L::splat(far_hi));
        for axis in 0..3 {
            let (entry, exit) = (bounds[self.entry_plane[axis]], bounds[self.exit_plane[axis]]);
            let (lo, hi) = (L::splat(self.inv_lo[axis]), L::splat(self.inv_hi[axis]));
            let (o_entry, o_exit) = (L::splat(self.entry_origin[axis]), L::splat(self.exit_origin[axis]));
            // The least entry and greatest exit: the origin bounds that make them extreme.
            let (d_in, d_out) = (entry - o_entry, exit - o_exit);
            near_lo = near_lo.max((d_in * lo).min(d_in * hi));
            exit_hi = exit_hi.min((d_out * lo).max(d_out * hi));
            // The greatest entry and least exit: the other origin bounds.
            let (d_in, d_out) = (entry - o_exit, exit - o_entry);
            near_hi = near_hi.max((d_in * lo).max(d_in * hi));
            exit_lo = exit_lo.min((d_out * lo).min(d_out * hi));
        }
        (near_lo.le(exit_hi), near_hi.le(exit_lo), near_lo)
    }
}

impl Default for WideNode {
    /// No children.
    fn default() -> Self {
        WideNode { planes: [[f32::INFINITY; WIDTH]; 6], children: [EMPTY; WIDTH] }
    }
}

impl WideNode {
    /// A node whose only child (lane 0, no index) has the box `b`: for testing rays against
    /// one box with the same operations as a child box.
    pub fn single(b: crate::math::Aabb) -> WideNode {
        let mut n = WideNode::default();
        for axis in 0..3 {
            n.planes[axis][0] = b.min[axis];
            n.planes[axis + 3][0] = b.max[axis];
        }
        n
    }

    /// Bitmask of the rays whose slab test against child `lane`'s box passes within
    /// `[t_min, t_far]` (per ray), and their entry distances: per ray, the same operations as
    /// [`WideNode::hit`] (the lane type's `min`/`max` have the SIMD instructions' NaN rule too).
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
            let t0 = (F32s::splat(self.planes[axis][lane]) - r.origin[axis]) * r.inv_dir[axis];
            let t1 = (F32s::splat(self.planes[axis + 3][lane]) - r.origin[axis]) * r.inv_dir[axis];
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        (near.le(far).bitmask(), near)
    }

    /// The group bounded by `iv` against the node's boxes, each ray's range `[t_min, t_far]`
    /// with `t_far` within `[far_lo, far_hi]`: the children some ray may hit, the children
    /// every ray hits (bitmasks, lane 0 lowest), and per child a lower bound of the rays' entry
    /// distances. Both masks agree with [`WideNode::child_hit_lanes`]'s own test of each ray: a
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
    pub fn interval_hits<L: BoxLanes>(
        &self,
        iv: &RayInterval,
        t_min: f32,
        far_lo: f32,
        far_hi: f32,
    ) -> (u32, u32, [f32; WIDTH]) {
        let (mut may, mut all, mut entries) = (0, 0, [0.0; WIDTH]);
        for first in self.tests::<L>() {
            let bounds = std::array::from_fn(|k| L::load(&self.planes[k][first..first + L::COUNT]));
            let (m, a, e) = iv.boxes_hit(&bounds, t_min, far_lo, far_hi);
            may |= L::bits(m) << first;
            all |= L::bits(a) << first;
            e.store(&mut entries[first..first + L::COUNT]);
        }
        (may, all, entries)
    }

    /// The first child of each test of `L::COUNT` boxes that holds any child: the children
    /// fill the first slots, so a test whose first slot is empty is skipped.
    #[inline(always)]
    fn tests<L: BoxLanes>(&self) -> impl Iterator<Item = usize> + '_ {
        (0..WIDTH).step_by(L::COUNT).take_while(|&first| first == 0 || self.children[first] != EMPTY)
    }

    /// Same boxes (bit for bit) and children.
    pub fn same_as(&self, o: &WideNode) -> bool {
        self.children == o.children
            && self.planes.iter().flatten().zip(o.planes.iter().flatten()).all(|(a, b)| a.to_bits() == b.to_bits())
    }

    /// The box of child `lane`.
    pub fn child_bounds(&self, lane: usize) -> crate::math::Aabb {
        let axis = |k: usize| glam::Vec3::new(self.planes[k][lane], self.planes[k + 1][lane], self.planes[k + 2][lane]);
        crate::math::Aabb { min: axis(0), max: axis(3) }
    }

    /// Lanes whose box overlaps the ray within `[t_min, t_max]`, and each lane's entry
    /// distance (meaningful where the lane hits).
    #[inline(always)]
    pub fn hit<L: BoxLanes>(&self, r: &RayBox<L>, t_min: f32, t_max: f32) -> (u32, [f32; WIDTH]) {
        let (mut mask, mut entries) = (0, [0.0; WIDTH]);
        for first in self.tests::<L>() {
            let plane = |k: usize| L::load(&self.planes[k][first..first + L::COUNT]);
            let mut near = L::splat(t_min);
            let mut far = L::splat(t_max);
            for axis in 0..3 {
                let t0 = (plane(axis) - r.origin[axis]) * r.inv_dir[axis];
                let t1 = (plane(axis + 3) - r.origin[axis]) * r.inv_dir[axis];
                near = near.max(t0.min(t1));
                far = far.min(t0.max(t1));
            }
            mask |= L::bits(near.le(far)) << first;
            near.store(&mut entries[first..first + L::COUNT]);
        }
        (mask, entries)
    }
}

/// Collapses the binary tree `nodes` (root at 0) into wide nodes (root at 0).
pub(super) fn collapse(nodes: &[Node]) -> Vec<WideNode> {
    let mut out = Vec::new();
    if let Some(root) = nodes.first() {
        if root.count > 0 {
            out.push(wide_node(nodes, &[0], |_| LEAF | root.offset));
        } else {
            collapse_node(nodes, &slot_plans(nodes), 0, &mut out);
        }
    }
    out
}

fn wide_node(nodes: &[Node], kids: &[usize], mut child: impl FnMut(usize) -> u32) -> WideNode {
    let mut n = WideNode::default();
    for (lane, &k) in kids.iter().enumerate() {
        let b = nodes[k].bounds;
        for axis in 0..3 {
            n.planes[axis][lane] = b.min[axis];
            n.planes[axis + 3][lane] = b.max[axis];
        }
        n.children[lane] = child(k);
    }
    n
}

/// How a binary node's subtree is best represented by at most `i` slots of a wide node
/// (`i = 1 ..= WIDTH`, index `i - 1`): the least total surface area of the wide nodes it then
/// needs, and the split that gives it (0: the subtree takes one slot, as a leaf or as its own
/// wide node; `k > 0`: it is opened, its left child's subtree getting at most `k` slots and its
/// right child's the rest).
#[derive(Clone, Copy)]
struct SlotPlan {
    cost: [f64; WIDTH],
    split: [u8; WIDTH],
    /// For an interior node made into a wide node: the split of its children over `WIDTH` slots.
    own: u8,
}

/// The collapse that minimises the surface area heuristic's cost of the wide nodes: a wide
/// node is visited by a random ray in proportion to its surface area (the leaves are fixed by
/// the binary build, so their cost is the same however the tree is collapsed), and the least
/// sum of the wide nodes' areas is found by dynamic programming over the binary tree, bottom
/// up (Ylitie, Karras & Laine, "Efficient Incoherent Ray Traversal on GPUs Through Compressed
/// Wide BVHs", HPG 2017, §4.1). Greedily opening the largest child left many nodes half empty
/// (a third more node bytes per triangle); an empty slot costs nothing here, but a node made
/// for a small subtree costs its area.
fn slot_plans(nodes: &[Node]) -> Vec<SlotPlan> {
    let mut plans = vec![SlotPlan { cost: [0.0; WIDTH], split: [0; WIDTH], own: 0 }; nodes.len()];
    // Children follow their parent in the array, so a reverse pass sees them first.
    for index in (0..nodes.len()).rev() {
        let node = &nodes[index];
        if node.count > 0 {
            continue;
        }
        let (left, right) = (&plans[index + 1], &plans[node.offset as usize]);
        // Least cost of the two children's subtrees in at most `i` slots together, and how
        // many of them the left one takes.
        let mut spread = [(f64::INFINITY, 0u8); WIDTH];
        for (i, best) in spread.iter_mut().enumerate().skip(1) {
            for k in 1..=i {
                let c = left.cost[k - 1] + right.cost[i - k];
                if c < best.0 {
                    *best = (c, k as u8);
                }
            }
        }
        let (opened, own) = spread[WIDTH - 1];
        let alone = f64::from(node.bounds.surface_area()) + opened;
        let plan = &mut plans[index];
        plan.own = own;
        plan.cost[0] = alone;
        for (i, &(c, k)) in spread.iter().enumerate().skip(1) {
            (plan.cost[i], plan.split[i]) = if c < alone { (c, k) } else { (alone, 0) };
        }
    }
    plans
}

/// The binary nodes that fill the slots of binary node `index` given `slots` slots by `plans`.
fn slot_nodes(nodes: &[Node], plans: &[SlotPlan], index: usize, slots: usize, out: &mut Vec<usize>) {
    match plans[index].split[slots - 1] {
        0 => out.push(index),
        k => {
            slot_nodes(nodes, plans, index + 1, k as usize, out);
            slot_nodes(nodes, plans, nodes[index].offset as usize, slots - k as usize, out);
        }
    }
}

/// Makes interior binary node `index` a wide node (and its interior slots, recursively).
fn collapse_node(nodes: &[Node], plans: &[SlotPlan], index: usize, out: &mut Vec<WideNode>) -> u32 {
    let own = plans[index].own as usize;
    let mut kids = Vec::with_capacity(WIDTH);
    slot_nodes(nodes, plans, index + 1, own, &mut kids);
    slot_nodes(nodes, plans, nodes[index].offset as usize, WIDTH - own, &mut kids);
    let me = out.len();
    out.push(WideNode::default());
    let node = wide_node(nodes, &kids, |k| {
        if nodes[k].count > 0 {
            LEAF | nodes[k].offset
        } else {
            collapse_node(nodes, plans, k, out)
        }
    });
    out[me] = node;
    me as u32
}

/// Levels of wide nodes on the longest root-to-leaf path (0 for an empty tree).
pub(super) fn wide_depth(nodes: &[WideNode]) -> usize {
    fn depth(nodes: &[WideNode], i: u32) -> usize {
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

    /// A node of `children` children (in the first slots) with random boxes, centred within
    /// `spread` of the origin.
    fn random_node(rng: &mut Pcg32, children: usize, spread: f32) -> WideNode {
        let mut node = WideNode::default();
        for lane in 0..children {
            node.children[lane] = lane as u32;
            let (c, h) = (point(rng, spread), point(rng, 1.5).abs());
            for axis in 0..3 {
                node.planes[axis][lane] = c[axis] - h[axis];
                node.planes[axis + 3][lane] = c[axis] + h[axis];
            }
        }
        node
    }

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
                let node = random_node(&mut rng, WIDTH, 8.0);
                let (may, all, entries) = node.interval_hits::<F32s<WIDTH>>(&iv, 0.0, least, bound);
                let four_at_a_time = node.interval_hits::<Vec4>(&iv, 0.0, least, bound);
                assert_eq!(
                    (may, all, entries.map(f32::to_bits)),
                    (four_at_a_time.0, four_at_a_time.1, four_at_a_time.2.map(f32::to_bits))
                );
                for lane in 0..WIDTH {
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

    /// A node's boxes tested eight at a time and four at a time give the same mask and entry
    /// distances, bit for bit, for nodes of 1 to 8 children (with 4 or fewer, the four-lane
    /// test skips the second half), and both agree with each child's test of the ray in lanes.
    #[test]
    fn eight_and_four_lane_box_tests_agree() {
        let mut rng = Pcg32::new(7, 3);
        let mut hits = 0;
        for g in 0..20_000 {
            let children = 1 + g % WIDTH;
            let node = random_node(&mut rng, children, 4.0);
            // Aimed near the first child's centre from around the boxes.
            let origin = point(&mut rng, 8.0);
            let dir = (node.child_bounds(0).centroid() + point(&mut rng, 1.0) - origin).normalize_or(Vec3::X);
            let ray = Ray::new(origin, dir);
            let t_max = if g % 2 == 0 { f32::INFINITY } else { uniform(&mut rng, 0.5, 12.0) };
            let (mask8, near8) = node.hit(&RayBox::<F32s<WIDTH>>::new(&ray), 0.0, t_max);
            let (mask4, near4) = node.hit(&RayBox::<Vec4>::new(&ray), 0.0, t_max);
            let filled = (1u32 << children) - 1;
            assert_eq!(mask8 & filled, mask4 & filled, "node {g}");
            let rays = RayBoxes::<1>::new(&Vec3s::splat(origin), &Vec3s::splat(dir));
            for lane in 0..children {
                let (one, near) = node.child_hit_lanes(lane, &rays, F32s::splat(0.0), F32s::splat(t_max));
                assert_eq!(mask8 >> lane & 1, one, "node {g}, child {lane}");
                if one != 0 {
                    assert_eq!(near8[lane].to_bits(), near4[lane].to_bits(), "node {g}, child {lane}");
                    assert_eq!(near8[lane].to_bits(), near.0[0].to_bits(), "node {g}, child {lane}");
                    hits += 1;
                }
            }
        }
        assert!(hits > 8_000, "only {hits} boxes hit");
    }

    /// A random binary tree of `leaves` leaves in the build's layout (depth first, the left
    /// child next, the right child at `offset`), each node with a random box.
    fn random_binary_tree(rng: &mut Pcg32, leaves: usize, out: &mut Vec<Node>) {
        let c = point(rng, 4.0);
        let h = point(rng, 2.0).abs();
        let bounds = crate::math::Aabb { min: c - h, max: c + h };
        let me = out.len();
        out.push(Node { bounds, offset: me as u32, count: 1, axis: 0 });
        if leaves > 1 {
            let left = 1 + rng.next_u32() as usize % (leaves - 1);
            random_binary_tree(rng, left, out);
            out[me].offset = out.len() as u32;
            out[me].count = 0;
            random_binary_tree(rng, leaves - left, out);
        }
    }

    /// Every way to cut the subtree of `index` into slots: the lists of its nodes that hold all
    /// of its leaves exactly once (of at most `limit` nodes).
    fn cuts(nodes: &[Node], index: usize, limit: usize) -> Vec<Vec<usize>> {
        let mut all = vec![vec![index]];
        if nodes[index].count == 0 {
            for l in cuts(nodes, index + 1, limit) {
                for r in cuts(nodes, nodes[index].offset as usize, limit) {
                    if l.len() + r.len() <= limit {
                        all.push([l.clone(), r].concat());
                    }
                }
            }
        }
        all
    }

    /// The least total area of wide nodes for interior node `index` made a wide node, by trying
    /// every cut of its children into at most `WIDTH` slots.
    fn least_area_by_search(nodes: &[Node], index: usize) -> f64 {
        let area = f64::from(nodes[index].bounds.surface_area());
        let mut best = f64::INFINITY;
        for l in cuts(nodes, index + 1, WIDTH) {
            for r in cuts(nodes, nodes[index].offset as usize, WIDTH) {
                if l.len() + r.len() > WIDTH {
                    continue;
                }
                let below: f64 =
                    l.iter().chain(&r).filter(|&&k| nodes[k].count == 0).map(|&k| least_area_by_search(nodes, k)).sum();
                best = best.min(below);
            }
        }
        area + best
    }

    /// The collapse's plan is the least total node area there is (checked against a search of
    /// every collapse on small random trees), and the wide nodes it makes hold every leaf once,
    /// with that total area.
    #[test]
    fn the_collapse_has_the_least_total_node_area() {
        let mut rng = Pcg32::new(7, 3);
        for trial in 0..200 {
            let leaves = 2 + trial % 13;
            let mut nodes = Vec::new();
            random_binary_tree(&mut rng, leaves, &mut nodes);
            let plan = slot_plans(&nodes)[0].cost[0];
            let search = least_area_by_search(&nodes, 0);
            assert!((plan - search).abs() <= 1e-9 * search, "trial {trial}: plan {plan}, search {search}");
            let wide = collapse(&nodes);
            let mut seen: Vec<u32> = wide
                .iter()
                .flat_map(|n| n.children.iter().filter(|&&c| c != EMPTY && c & LEAF != 0).map(|&c| c & !LEAF))
                .collect();
            seen.sort_unstable();
            let mut expected: Vec<u32> = nodes.iter().filter(|n| n.count > 0).map(|n| n.offset).collect();
            expected.sort_unstable();
            assert_eq!(seen, expected, "trial {trial}: leaves");
            // Children fill the first slots, as the walks assume.
            for n in &wide {
                let used = n.children.iter().take_while(|&&c| c != EMPTY).count();
                assert!(used >= 2 && n.children[used..].iter().all(|&c| c == EMPTY), "trial {trial}");
            }
            // The root is the binary root, each other wide node the box of its binary node.
            let area: f64 = (0..wide.len())
                .map(|i| {
                    if i == 0 {
                        f64::from(nodes[0].bounds.surface_area())
                    } else {
                        let parent = wide.iter().find(|p| p.children.contains(&(i as u32))).unwrap();
                        let lane = parent.children.iter().position(|&c| c == i as u32).unwrap();
                        f64::from(parent.child_bounds(lane).surface_area())
                    }
                })
                .sum();
            assert!((area - plan).abs() <= 1e-4 * plan, "trial {trial}: nodes' area {area}, plan {plan}");
        }
    }
}
