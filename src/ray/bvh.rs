//! A bounding volume hierarchy over axis-aligned boxes, built by the binned
//! surface area heuristic and traversed near-child-first with a fixed-size
//! stack (no allocation per ray).
//!
//! One structure serves every collection of boxed items: the pieces of a
//! tensor surface's patches (one item per piece), and in an application the
//! world (one item per object), a triangle mesh (one per triangle) or a tube
//! (one per capsule). The builder returns the order in which the caller must
//! store its items: a leaf covers the contiguous range `start .. start +
//! count` of that order.
//!
//! # Build
//! Items are split recursively. At each node the centroids' box is cut into
//! 12 equal bins along each axis; every cut between bins is scored by
//! the surface area heuristic `A_L·n_L + A_R·n_R` (`A` the half surface area
//! of a side's bounding box, `n` its item count; one traversal step costs as
//! much as one item test). A node becomes a leaf when splitting does not pay
//! and it holds at most `max_leaf` items, when all its centroids coincide (no
//! cut separates them), or at depth [`MAX_DEPTH`]; so leaves may exceed
//! `max_leaf` only for items no plane can separate. Both sides of a chosen
//! cut are non-empty: the smallest centroid falls in the first bin and the
//! largest in the last.
//!
//! # Traversal
//! The ray is entered into both children's boxes with the slab test (on the
//! precomputed reciprocal direction); the nearer child is visited first and
//! the farther pushed with its entry distance, to be skipped when popped if a
//! hit found meanwhile is nearer. The stack holds at most one entry per level,
//! so `MAX_DEPTH + 2` entries always suffice.

use std::ops::ControlFlow;

use crate::{Aabb, Ray};
use nalgebra::Point3;

/// The deepest a node can be; deeper subtrees become leaves.
pub const MAX_DEPTH: usize = 48;
/// Entries of a traversal stack: one per level.
const TRAVERSAL_STACK: usize = MAX_DEPTH + 2;
/// Candidate cuts per axis and node: `BINS − 1`.
const BINS: usize = 12;

/// One node: a leaf when `count > 0` (items `start .. start + count`),
/// otherwise an interior node whose children are the next node and `start`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Node {
    min: [f64; 3],
    max: [f64; 3],
    start: u32,
    count: u32,
}

impl Node {
    /// The entry distance of the ray into the node's closed box, clipped to
    /// `[t_min, t_max]`, or `None` when they do not overlap.
    ///
    /// A zero direction component gives an infinite reciprocal: the slab is
    /// then `(−∞, ∞)` or empty, as it should be. The one NaN case (`0 · ∞`,
    /// the origin exactly on a slab plane with the ray parallel to it) is
    /// ignored by `f64::max`/`min`, i.e. that slab does not constrain the
    /// ray; builders pad item boxes so this can only widen, never lose, a hit.
    #[inline(always)]
    fn enter(&self, ray: &BoxRay, t_min: f64, t_max: f64) -> Option<f64> {
        let (mut lo, mut hi) = (t_min, t_max);
        for i in 0..3 {
            let t0 = (self.min[i] - ray.origin[i]) * ray.inv[i];
            let t1 = (self.max[i] - ray.origin[i]) * ray.inv[i];
            lo = lo.max(t0.min(t1));
            hi = hi.min(t0.max(t1));
        }
        (lo <= hi).then_some(lo)
    }
}

/// A ray prepared for box tests: origin and reciprocal direction.
#[derive(Debug, Clone, Copy)]
pub struct BoxRay {
    pub(crate) origin: [f64; 3],
    pub(crate) inv: [f64; 3],
}

impl BoxRay {
    /// The ray's origin and reciprocal direction.
    pub fn new(ray: &Ray) -> BoxRay {
        BoxRay {
            origin: [ray.origin.x, ray.origin.y, ray.origin.z],
            inv: [1.0 / ray.dir.x, 1.0 / ray.dir.y, 1.0 / ray.dir.z],
        }
    }
}

/// The hierarchy: nodes only; the items live with the caller, in the order
/// [`Bvh::build`] returned.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Bvh {
    nodes: Vec<Node>,
}

/// An item during the build.
#[derive(Debug, Clone, Copy)]
struct Item {
    index: usize,
    bounds: Aabb,
    centroid: Point3<f64>,
}

/// A box grown by `1e-9` of its scale (plus a denormal-safe floor), so that
/// rounding in the slab test of a leaf cannot reject a hit on the box's boundary, and a
/// flat box (an axis-aligned triangle) has thickness.
pub fn pad(b: &Aabb) -> Aabb {
    let scale = b.scale().max(b.extent().amax());
    b.expand(1e-9 * scale + 1e-300)
}

/// Half the surface area of a non-empty box.
fn half_area(b: &Aabb) -> f64 {
    let e = b.extent();
    e.x * e.y + e.y * e.z + e.z * e.x
}

impl Bvh {
    /// Builds the hierarchy over finite, non-empty item boxes; returns it and
    /// the order in which the items must be stored (`order[k]` is the index
    /// into `bounds` of the `k`-th stored item).
    pub fn build(bounds: &[Aabb], max_leaf: usize) -> (Bvh, Vec<usize>) {
        let mut items: Vec<Item> = bounds
            .iter()
            .enumerate()
            .map(|(index, b)| Item {
                index,
                bounds: *b,
                centroid: b.center(),
            })
            .collect();
        let mut nodes = Vec::with_capacity(2 * items.len());
        if !items.is_empty() {
            build_node(&mut items, 0, 0, max_leaf.max(1), &mut nodes);
        }
        let order = items.iter().map(|i| i.index).collect();
        (Bvh { nodes }, order)
    }

    /// The box of everything (empty for no items).
    pub fn bounds(&self) -> Aabb {
        match self.nodes.first() {
            Some(n) => Aabb {
                min: Point3::from(n.min),
                max: Point3::from(n.max),
            },
            None => Aabb::EMPTY,
        }
    }

    /// Calls `leaf(k, t_max)` for every stored item `k` whose leaf box the
    /// ray enters within `[t_min, t_max]`, nearer leaves first. The callback
    /// returns `Continue(t)` with the new `t_max` (the same, or the `t` of a
    /// hit it found), or `Break` to stop.
    #[inline]
    pub fn traverse(
        &self,
        ray: &BoxRay,
        t_min: f64,
        mut t_max: f64,
        mut leaf: impl FnMut(usize, f64) -> ControlFlow<(), f64>,
    ) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        if root.enter(ray, t_min, t_max).is_none() {
            return;
        }
        // Two plain arrays (not an array of pairs): zeroing them is one
        // bulk fill, not one store per padded pair.
        let mut stack_node = [0u32; TRAVERSAL_STACK];
        let mut stack_t = [0.0f64; TRAVERSAL_STACK];
        let mut sp = 0;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            if n.count > 0 {
                let start = n.start as usize;
                for k in start..start + n.count as usize {
                    match leaf(k, t_max) {
                        ControlFlow::Continue(t) => t_max = t,
                        ControlFlow::Break(()) => return,
                    }
                }
            } else {
                let (l, r) = (node + 1, n.start as usize);
                let tl = self.nodes[l].enter(ray, t_min, t_max);
                let tr = self.nodes[r].enter(ray, t_min, t_max);
                match (tl, tr) {
                    (Some(a), Some(b)) => {
                        let (near, far, t_far) = if a <= b { (l, r, b) } else { (r, l, a) };
                        stack_node[sp] = far as u32;
                        stack_t[sp] = t_far;
                        sp += 1;
                        node = near;
                        continue;
                    }
                    (Some(_), None) => {
                        node = l;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = r;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the next subtree that may still hold a nearer hit.
            loop {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                if stack_t[sp] <= t_max {
                    node = stack_node[sp] as usize;
                    break;
                }
            }
        }
    }

    /// The two children of inner node `i` (`None` for a leaf).
    pub(crate) fn children(&self, i: usize) -> Option<(usize, usize)> {
        let n = &self.nodes[i];
        (n.count == 0).then_some((i + 1, n.start as usize))
    }

    /// The first stored item and the item count of leaf `i` (`None` for an
    /// inner node).
    pub(crate) fn leaf_items(&self, i: usize) -> Option<(u32, u32)> {
        let n = &self.nodes[i];
        (n.count > 0).then_some((n.start, n.count))
    }

    /// The box of node `i`: its least and greatest corners.
    pub(crate) fn node_box(&self, i: usize) -> ([f64; 3], [f64; 3]) {
        (self.nodes[i].min, self.nodes[i].max)
    }

    /// Half the surface area of node `i`'s box.
    pub(crate) fn half_area(&self, i: usize) -> f64 {
        let (min, max) = self.node_box(i);
        half_area(&Aabb {
            min: Point3::from(min),
            max: Point3::from(max),
        })
    }

    /// The number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The depth of the deepest leaf (the root is at depth 0).
    pub fn depth(&self) -> usize {
        fn go(nodes: &[Node], i: usize) -> usize {
            if nodes[i].count > 0 {
                0
            } else {
                1 + go(nodes, i + 1).max(go(nodes, nodes[i].start as usize))
            }
        }
        if self.nodes.is_empty() {
            0
        } else {
            go(&self.nodes, 0)
        }
    }
}

/// A traversal that can be paused at every item: [`Walk::next`] yields the
/// items [`Bvh::traverse`] would pass to its callback, in the same order,
/// given the current `t_max` each time; so several rays can walk the tree
/// side by side and have their items tested together. (`traverse` keeps its
/// own loop: built on `Walk`, the single-ray query cost 6% more
/// instructions, moving the walk's stack.)
#[derive(Debug, Clone)]
pub struct Walk {
    // Two plain arrays (not an array of pairs): zeroing them is one bulk
    // fill, not one store per padded pair.
    stack_node: [u32; TRAVERSAL_STACK],
    stack_t: [f64; TRAVERSAL_STACK],
    sp: usize,
    /// The node to enter next, if any (else pop the stack).
    node: Option<usize>,
    /// The items of the current leaf still to yield.
    items: std::ops::Range<usize>,
}

impl Walk {
    /// A walk of `bvh` for the ray: empty unless it enters the root box
    /// within `[t_min, t_max]`.
    #[inline]
    pub fn new(bvh: &Bvh, ray: &BoxRay, t_min: f64, t_max: f64) -> Walk {
        let enters = bvh
            .nodes
            .first()
            .is_some_and(|root| root.enter(ray, t_min, t_max).is_some());
        Walk {
            stack_node: [0; TRAVERSAL_STACK],
            stack_t: [0.0; TRAVERSAL_STACK],
            sp: 0,
            node: enters.then_some(0),
            items: 0..0,
        }
    }

    /// The next item to test, `t_max` being the nearest hit so far (the
    /// walk skips subtrees beyond it); `None` when the walk is over. Pass
    /// the same `bvh`, `ray` and `t_min` as to [`Walk::new`].
    #[inline]
    pub fn next(&mut self, bvh: &Bvh, ray: &BoxRay, t_min: f64, t_max: f64) -> Option<usize> {
        loop {
            if let Some(k) = self.items.next() {
                return Some(k);
            }
            if let Some(node) = self.node {
                let n = &bvh.nodes[node];
                if n.count > 0 {
                    let start = n.start as usize;
                    self.items = start..start + n.count as usize;
                    self.node = None;
                    continue;
                }
                let (l, r) = (node + 1, n.start as usize);
                let tl = bvh.nodes[l].enter(ray, t_min, t_max);
                let tr = bvh.nodes[r].enter(ray, t_min, t_max);
                self.node = match (tl, tr) {
                    (Some(a), Some(b)) => {
                        let (near, far, t_far) = if a <= b { (l, r, b) } else { (r, l, a) };
                        self.stack_node[self.sp] = far as u32;
                        self.stack_t[self.sp] = t_far;
                        self.sp += 1;
                        Some(near)
                    }
                    (Some(_), None) => Some(l),
                    (None, Some(_)) => Some(r),
                    (None, None) => None,
                };
                if self.node.is_some() {
                    continue;
                }
            }
            // Pop the next subtree that may still hold a nearer hit.
            loop {
                if self.sp == 0 {
                    return None;
                }
                self.sp -= 1;
                if self.stack_t[self.sp] <= t_max {
                    self.node = Some(self.stack_node[self.sp] as usize);
                    break;
                }
            }
        }
    }
}

/// Builds the subtree over `items` (stored from `offset` on) and returns its
/// node index; children follow in depth-first order.
fn build_node(
    items: &mut [Item],
    offset: usize,
    depth: usize,
    max_leaf: usize,
    nodes: &mut Vec<Node>,
) -> usize {
    let bounds = items.iter().fold(Aabb::EMPTY, |b, i| b.union(&i.bounds));
    let index = nodes.len();
    nodes.push(Node {
        min: bounds.min.into(),
        max: bounds.max.into(),
        start: offset as u32,
        count: items.len() as u32,
    });
    if items.len() <= 1 || depth >= MAX_DEPTH {
        return index;
    }
    let Some(mid) = choose_split(items, &bounds, max_leaf) else {
        return index;
    };
    build_node(&mut items[..mid], offset, depth + 1, max_leaf, nodes);
    let right = build_node(&mut items[mid..], offset + mid, depth + 1, max_leaf, nodes);
    nodes[index].start = right as u32;
    nodes[index].count = 0;
    index
}

/// The bin of a centroid coordinate `c` in `[lo, lo + extent]`.
#[inline]
fn bin_of(c: f64, lo: f64, scale: f64) -> usize {
    (((c - lo) * scale) as usize).min(BINS - 1)
}

/// Picks the best binned SAH cut, partitions `items` by it and returns the
/// size of the left part; `None` for a leaf (see the module docs).
fn choose_split(items: &mut [Item], bounds: &Aabb, max_leaf: usize) -> Option<usize> {
    let cb = items
        .iter()
        .fold(Aabb::EMPTY, |b, i| b.include(&i.centroid));
    let n = items.len();
    // (cost, axis, first bin of the right side)
    let mut best: Option<(f64, usize, usize)> = None;
    for axis in 0..3 {
        let (lo, extent) = (cb.min[axis], cb.max[axis] - cb.min[axis]);
        // Finite boxes: no NaN here.
        if extent <= 0.0 {
            continue;
        }
        let scale = BINS as f64 / extent;
        let mut counts = [0usize; BINS];
        let mut boxes = [Aabb::EMPTY; BINS];
        for it in items.iter() {
            let b = bin_of(it.centroid[axis], lo, scale);
            counts[b] += 1;
            boxes[b] = boxes[b].union(&it.bounds);
        }
        // Sweep from the right: area·count of bins cut..BINS.
        let mut right_cost = [0.0; BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for b in (1..BINS).rev() {
            acc = acc.union(&boxes[b]);
            cnt += counts[b];
            right_cost[b] = if cnt > 0 {
                half_area(&acc) * cnt as f64
            } else {
                0.0
            };
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for cut in 1..BINS {
            acc = acc.union(&boxes[cut - 1]);
            cnt += counts[cut - 1];
            if cnt == 0 || cnt == n {
                continue;
            }
            let cost = half_area(&acc) * cnt as f64 + right_cost[cut];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, cut));
            }
        }
    }
    let (cost, axis, cut) = best?;
    // Split cost (one traversal step + the sides) against testing every
    // item, both scaled by the node's area.
    let area = half_area(bounds);
    if n <= max_leaf && area + cost >= area * n as f64 {
        return None;
    }
    let (lo, scale) = (cb.min[axis], BINS as f64 / (cb.max[axis] - cb.min[axis]));
    // In-place partition: bins < cut to the left.
    let mut mid = 0;
    for k in 0..n {
        if bin_of(items[k].centroid[axis], lo, scale) < cut {
            items.swap(k, mid);
            mid += 1;
        }
    }
    (mid > 0 && mid < n).then_some(mid)
}
