//! The top-down build of the binary tree, serial or on rayon. Subtrees larger than
//! `parallel_above` split their two halves with `rayon::join`; each task fills its own node
//! array, and [`flatten`] stitches them in depth-first order (left child right after its
//! parent), so the result is the very array the serial recursion writes.

use super::build::{choose_split, extents, BuildItem, BuildOptions};
use super::bvh::Node;

/// Builds the tree over `items` (reordered in place); root at index 0. Leaves hold the
/// position of their first item in `offset`.
pub(super) fn build_tree(items: &mut [BuildItem], opts: &BuildOptions) -> Vec<Node> {
    let mut out = Vec::new();
    if !items.is_empty() {
        let tree = build(items, 0, 0, opts);
        out.reserve_exact(tree.len());
        flatten(tree, &mut out);
    }
    out
}

/// A partly built tree: flat arrays from serial tasks, joined by the nodes split in parallel.
enum Subtree {
    /// Nodes in depth-first order, right-child indices relative to the array.
    Flat(Vec<Node>),
    Join {
        node: Node,
        left: Box<Subtree>,
        right: Box<Subtree>,
    },
}

impl Subtree {
    fn len(&self) -> usize {
        match self {
            Subtree::Flat(v) => v.len(),
            Subtree::Join { left, right, .. } => 1 + left.len() + right.len(),
        }
    }
}

/// `items` are the build items at positions `start..start + items.len()`.
fn build(items: &mut [BuildItem], start: usize, depth: usize, opts: &BuildOptions) -> Subtree {
    if items.len() <= opts.parallel_above {
        let mut nodes = Vec::new();
        build_serial(items, start, depth, opts, &mut nodes);
        return Subtree::Flat(nodes);
    }
    let (boxes, centroids) = extents(items);
    let bounds = boxes.to_aabb();
    let leaf = Node { bounds, offset: start as u32, count: items.len() as u16, axis: 0 };
    let Some((axis, mid)) = choose_split(items, &boxes, &centroids, depth, opts) else {
        return Subtree::Flat(vec![leaf]);
    };
    let (l, r) = items.split_at_mut(mid);
    let (left, right) = rayon::join(|| build(l, start, depth + 1, opts), || build(r, start + mid, depth + 1, opts));
    let node = Node { bounds, offset: 0, count: 0, axis: axis as u16 };
    Subtree::Join { node, left: Box::new(left), right: Box::new(right) }
}

/// The serial recursion: appends the subtree over `items` to `nodes`; returns its root index.
fn build_serial(
    items: &mut [BuildItem],
    start: usize,
    depth: usize,
    opts: &BuildOptions,
    nodes: &mut Vec<Node>,
) -> usize {
    let me = nodes.len();
    let (boxes, centroids) = extents(items);
    let bounds = boxes.to_aabb();
    nodes.push(Node { bounds, offset: start as u32, count: items.len() as u16, axis: 0 });
    if items.len() == 1 {
        return me;
    }
    let Some((axis, mid)) = choose_split(items, &boxes, &centroids, depth, opts) else {
        return me; // a leaf is cheapest
    };
    let (l, r) = items.split_at_mut(mid);
    build_serial(l, start, depth + 1, opts, nodes);
    let right = build_serial(r, start + mid, depth + 1, opts, nodes);
    nodes[me] = Node { bounds, offset: right as u32, count: 0, axis: axis as u16 };
    me
}

/// Appends `tree` to `out` in depth-first order, rebasing right-child indices.
fn flatten(tree: Subtree, out: &mut Vec<Node>) {
    match tree {
        Subtree::Flat(nodes) => {
            let base = out.len() as u32;
            out.extend(nodes.into_iter().map(|n| if n.count == 0 { Node { offset: n.offset + base, ..n } } else { n }));
        }
        Subtree::Join { node, left, right } => {
            let me = out.len();
            out.push(node);
            flatten(*left, out);
            out[me].offset = out.len() as u32;
            flatten(*right, out);
        }
    }
}
