//! A bounding-volume hierarchy over boxed items (the pieces of tensor
//! patches, for one), so that a ray visits only the items whose boxes it
//! enters, nearest first.
//!
//! The tree is built once, top down: a node's items are split along the axis
//! and at the position (between items sorted by box centre) that minimise
//! the surface area heuristic `area(left)·count(left) +
//! area(right)·count(right)` (MacDonald & Booth 1990); a node of one item is
//! a leaf. Below depth [`SAH_DEPTH`]
//! splits are at the median, so the depth is at most
//! `SAH_DEPTH + ⌈log₂ n⌉` and the traversal stack stays on the stack.
//!
//! A ray visits the tree depth first, the nearer child first, and skips a
//! node whose box it enters beyond the best hit found so far.

use super::slab::Slab;
use crate::Aabb;
use nalgebra::Point3;

/// Depth below which nodes split by the surface area heuristic; deeper
/// nodes split at the median.
const SAH_DEPTH: usize = 40;

/// Nodes the traversal stack holds: one per level.
const TRAVERSAL_STACK: usize = SAH_DEPTH + 64 + 2;

/// One node: a leaf holds item `order[first]`; an inner node's children
/// are nodes `first` and `first + 1`.
#[derive(Debug, Clone, PartialEq)]
struct Node {
    bounds: Aabb,
    first: u32,
    leaf: bool,
}

/// The hierarchy over a list of boxed items.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Bvh {
    nodes: Vec<Node>,
    /// Item indices, in leaf order.
    order: Vec<u32>,
}

impl Bvh {
    /// The hierarchy over `boxes` (one per item; item `i` is `boxes[i]`).
    pub(crate) fn new(boxes: &[Aabb]) -> Self {
        let all = boxes.iter().fold(Aabb::EMPTY, |a, b| a.union(b));
        let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
        let mut nodes = vec![Node {
            bounds: all,
            first: 0,
            leaf: true,
        }];
        if !order.is_empty() {
            let centres: Vec<Point3<f64>> = boxes.iter().map(Aabb::center).collect();
            build(boxes, &centres, &mut order, 0, 0, 0, &mut nodes);
        }
        Bvh { nodes, order }
    }

    /// The union of the items' boxes.
    pub(crate) fn bounds(&self) -> Aabb {
        self.nodes[0].bounds
    }

    /// Calls `search(item, enter)` for every item whose box the ray enters
    /// at some `t` in `[lo, best]`, nearer subtrees first, where `best`
    /// starts at `hi` and is replaced by each value `search` returns (the
    /// best hit so far; it must not grow).
    pub(crate) fn visit(
        &self,
        slab: &Slab,
        lo: f64,
        hi: f64,
        mut search: impl FnMut(usize, f64) -> f64,
    ) {
        let mut best = hi;
        let Some(enter) = slab.enter(&self.nodes[0].bounds, lo, best) else {
            return;
        };
        let mut stack = [(0_u32, 0.0_f64); TRAVERSAL_STACK];
        stack[0] = (0, enter);
        let mut len = 1;
        while len > 0 {
            len -= 1;
            let (mut index, enter) = stack[len];
            if enter > best {
                continue;
            }
            loop {
                let node = &self.nodes[index as usize];
                if node.leaf {
                    let patch = self.order[node.first as usize] as usize;
                    best = best.min(search(patch, enter));
                    break;
                }
                let (a, b) = (node.first, node.first + 1);
                let ea = slab.enter(&self.nodes[a as usize].bounds, lo, best);
                let eb = slab.enter(&self.nodes[b as usize].bounds, lo, best);
                match (ea, eb) {
                    (None, None) => break,
                    (Some(_), None) => index = a,
                    (None, Some(_)) => index = b,
                    (Some(x), Some(y)) => {
                        let (near, far, far_enter) = if x <= y { (a, b, y) } else { (b, a, x) };
                        stack[len] = (far, far_enter);
                        len += 1;
                        index = near;
                    }
                }
            }
        }
    }
}

/// Fills node `at` with the patches `order` (a slice of the whole order,
/// starting at `offset`), at `depth`: a leaf for one patch, else two
/// children appended to `nodes` and built in turn.
fn build(
    boxes: &[Aabb],
    centres: &[Point3<f64>],
    order: &mut [u32],
    offset: usize,
    at: usize,
    depth: usize,
    nodes: &mut Vec<Node>,
) {
    let bounds = order
        .iter()
        .fold(Aabb::EMPTY, |a, &k| a.union(&boxes[k as usize]));
    if order.len() == 1 {
        nodes[at] = Node {
            bounds,
            first: offset as u32,
            leaf: true,
        };
        return;
    }
    let centre = |k: u32| centres[k as usize];
    let split = if depth < SAH_DEPTH {
        sah_split(boxes, centres, order)
    } else {
        let axis = widest_centre_axis(centres, order);
        let mid = order.len() / 2;
        order.select_nth_unstable_by(mid, |&x, &y| centre(x)[axis].total_cmp(&centre(y)[axis]));
        mid
    };
    let first = nodes.len();
    let placeholder = Node {
        bounds: Aabb::EMPTY,
        first: 0,
        leaf: true,
    };
    nodes.push(placeholder.clone());
    nodes.push(placeholder);
    nodes[at] = Node {
        bounds,
        first: first as u32,
        leaf: false,
    };
    let (left, right) = order.split_at_mut(split);
    build(boxes, centres, left, offset, first, depth + 1, nodes);
    build(
        boxes,
        centres,
        right,
        offset + split,
        first + 1,
        depth + 1,
        nodes,
    );
}

/// The axis along which the boxes' centres spread most.
fn widest_centre_axis(centres: &[Point3<f64>], order: &[u32]) -> usize {
    let spread = order
        .iter()
        .fold(Aabb::EMPTY, |a, &k| a.include(&centres[k as usize]));
    let e = spread.extent();
    if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    }
}

/// Half the surface area of a box (zero for an empty one).
fn half_area(b: &Aabb) -> f64 {
    if b.is_empty() {
        return 0.0;
    }
    let e = b.extent();
    e.x * e.y + e.y * e.z + e.z * e.x
}

/// Sorts `order` along the best axis and returns the split position
/// (`1 ..= len − 1`) of least surface-area cost.
fn sah_split(boxes: &[Aabb], centres: &[Point3<f64>], order: &mut [u32]) -> usize {
    let n = order.len();
    let mut best = (f64::INFINITY, 0_usize, n / 2);
    let mut suffix = vec![0.0_f64; n + 1];
    let key = |axis: usize| move |&k: &u32| centres[k as usize][axis];
    for axis in 0..3 {
        let key = key(axis);
        order.sort_unstable_by(|x, y| key(x).total_cmp(&key(y)));
        let mut acc = Aabb::EMPTY;
        for i in (0..n).rev() {
            acc = acc.union(&boxes[order[i] as usize]);
            suffix[i] = half_area(&acc);
        }
        let mut acc = Aabb::EMPTY;
        for i in 1..n {
            acc = acc.union(&boxes[order[i - 1] as usize]);
            let cost = half_area(&acc) * i as f64 + suffix[i] * (n - i) as f64;
            if cost < best.0 {
                best = (cost, axis, i);
            }
        }
    }
    let key = key(best.1);
    order.sort_unstable_by(|x, y| key(x).total_cmp(&key(y)));
    best.2
}
