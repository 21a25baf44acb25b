//! A four-wide bounding volume hierarchy: a binary [`Bvh`] collapsed so
//! that every node holds up to [`WIDTH`] children's boxes side by side, one
//! array per coordinate, and a ray enters all of them in one pass (the
//! slab test written lane by lane, which the compiler turns into vector
//! instructions).
//!
//! # Collapse
//! A wide node starts from a binary node's two children and repeatedly
//! replaces the inner child of largest surface area by its own two
//! children until it holds four or only leaves remain; each inner child
//! left becomes a wide node in turn. Leaves keep the binary leaves' item
//! ranges, so items are stored in the order [`Bvh::build`] returned.
//!
//! # Traversal
//! The children a ray enters are pushed on a fixed-size stack farthest
//! first, so the nearest is popped next; an entry whose distance is beyond
//! the best hit found meanwhile is skipped when popped. Leaves are reached
//! in near-to-far order of their boxes, as in [`Bvh::traverse`], and the
//! callback sees the same items with the same narrowing `t_max`.

use super::bvh::{BoxRay, Bvh, MAX_DEPTH};
use std::ops::ControlFlow;

/// Children per node.
pub const WIDTH: usize = 4;
/// A slot's count for an empty slot.
const EMPTY: u32 = u32::MAX;
/// Stack entries: at most `WIDTH − 1` left behind per level, plus the
/// children of the last node.
const STACK: usize = (WIDTH - 1) * (MAX_DEPTH + 2) + WIDTH;

/// One node: per slot, a child's box (`min`/`max` per coordinate, lane by
/// lane), and either an inner node (`count == 0`, `link` its index), a
/// leaf (`count > 0` items from `link`) or nothing (`count == EMPTY`, the
/// box of the point at infinity).
#[derive(Debug, Clone, Copy, PartialEq)]
struct WideNode {
    min: [[f64; WIDTH]; 3],
    max: [[f64; WIDTH]; 3],
    link: [u32; WIDTH],
    count: [u32; WIDTH],
}

impl WideNode {
    /// A node with every slot empty: the box of the one point at infinity,
    /// which a ray from a finite origin never enters (its slab distances
    /// are both `+∞` or both `−∞`, whatever the direction).
    fn empty() -> Self {
        WideNode {
            min: [[f64::INFINITY; WIDTH]; 3],
            max: [[f64::INFINITY; WIDTH]; 3],
            link: [0; WIDTH],
            count: [EMPTY; WIDTH],
        }
    }

    /// The entry distance of the ray into each slot's closed box, clipped
    /// to `[t_min, t_max]`, or infinity where it does not enter (and in
    /// empty slots). NaN from `0 · ∞` is ignored by `max`/`min`, as in the
    /// binary test.
    #[inline(always)]
    fn enter(&self, ray: &BoxRay, t_min: f64, t_max: f64) -> [f64; WIDTH] {
        let mut lo = [t_min; WIDTH];
        let mut hi = [t_max; WIDTH];
        for axis in 0..3 {
            let (o, inv) = (ray.origin[axis], ray.inv[axis]);
            for k in 0..WIDTH {
                let t0 = (self.min[axis][k] - o) * inv;
                let t1 = (self.max[axis][k] - o) * inv;
                lo[k] = lo[k].max(t0.min(t1));
                hi[k] = hi[k].min(t0.max(t1));
            }
        }
        std::array::from_fn(|k| if lo[k] <= hi[k] { lo[k] } else { f64::INFINITY })
    }
}

/// The four-wide hierarchy; the items live with the caller, in the order
/// the binary hierarchy's build returned.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WideBvh {
    nodes: Vec<WideNode>,
}

impl WideBvh {
    /// The binary hierarchy `bvh` collapsed to four-wide nodes.
    pub fn new(bvh: &Bvh) -> WideBvh {
        let mut wide = WideBvh { nodes: Vec::new() };
        if bvh.node_count() > 0 {
            wide.collapse(bvh, &[0]);
        }
        wide.nodes.shrink_to_fit();
        wide
    }

    /// Adds the wide node over the binary nodes `start` (one or two; more
    /// are gathered here) and returns its index.
    fn collapse(&mut self, bvh: &Bvh, start: &[usize]) -> u32 {
        let mut slots: Vec<usize> = start.to_vec();
        // Open the inner slot of largest area while there is room.
        while slots.len() < WIDTH {
            let widest = slots
                .iter()
                .enumerate()
                .filter(|&(_, &n)| bvh.children(n).is_some())
                .max_by(|a, b| bvh.half_area(*a.1).total_cmp(&bvh.half_area(*b.1)))
                .map(|(i, _)| i);
            let Some(i) = widest else { break };
            let (left, right) = bvh.children(slots[i]).expect("an inner slot");
            slots[i] = left;
            slots.push(right);
        }
        let index = self.nodes.len();
        self.nodes.push(WideNode::empty());
        let mut node = WideNode::empty();
        for (k, &n) in slots.iter().enumerate() {
            let (min, max) = bvh.node_box(n);
            for axis in 0..3 {
                node.min[axis][k] = min[axis];
                node.max[axis][k] = max[axis];
            }
            match bvh.leaf_items(n) {
                Some((first, count)) => {
                    node.link[k] = first;
                    node.count[k] = count;
                }
                None => {
                    let (left, right) = bvh.children(n).expect("an inner node");
                    node.link[k] = self.collapse(bvh, &[left, right]);
                    node.count[k] = 0;
                }
            }
        }
        self.nodes[index] = node;
        index as u32
    }

    /// The number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Calls `leaf(k, t_max)` for every stored item `k` whose leaf box the
    /// ray enters within `[t_min, t_max]`, nearer leaves first, as
    /// [`Bvh::traverse`] does. The callback returns `Continue(t)` with the
    /// new `t_max` (the same, or the `t` of a hit it found), or `Break` to
    /// stop.
    #[inline]
    pub fn traverse(
        &self,
        ray: &BoxRay,
        t_min: f64,
        mut t_max: f64,
        mut leaf: impl FnMut(usize, f64) -> ControlFlow<(), f64>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        // Entries: node index × WIDTH + slot, and the slot's entry distance.
        let mut stack_slot = [0u32; STACK];
        let mut stack_t = [0.0f64; STACK];
        let mut sp = 0;
        let mut node = 0usize;
        loop {
            let n = &self.nodes[node];
            let t = n.enter(ray, t_min, t_max);
            // Push the entered slots farthest first (insertion by distance
            // into the top of the stack).
            let base = sp;
            for (k, &tk) in t.iter().enumerate() {
                if tk == f64::INFINITY {
                    continue;
                }
                let mut at = sp;
                while at > base && stack_t[at - 1] < tk {
                    stack_t[at] = stack_t[at - 1];
                    stack_slot[at] = stack_slot[at - 1];
                    at -= 1;
                }
                stack_t[at] = tk;
                stack_slot[at] = (node * WIDTH + k) as u32;
                sp += 1;
            }
            // Pop the nearest entry still nearer than the best hit; leaves
            // are visited on the spot, an inner node becomes the next one.
            loop {
                if sp == 0 {
                    return;
                }
                sp -= 1;
                if stack_t[sp] > t_max {
                    continue;
                }
                let slot = stack_slot[sp] as usize;
                let owner = &self.nodes[slot / WIDTH];
                let (link, count) = (owner.link[slot % WIDTH], owner.count[slot % WIDTH]);
                if count == 0 {
                    node = link as usize;
                    break;
                }
                if count == EMPTY {
                    // Entered only by a ray from a point at infinity.
                    continue;
                }
                for k in link as usize..(link + count) as usize {
                    match leaf(k, t_max) {
                        ControlFlow::Continue(t) => t_max = t,
                        ControlFlow::Break(()) => return,
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::WideBvh;
    use crate::ray::bvh::{BoxRay, Bvh};
    use crate::{Aabb, Ray};
    use nalgebra::{Point3, Vector3};
    use std::ops::ControlFlow;

    /// Boxes scattered over a cube, of varied sizes (a deterministic
    /// stream).
    fn boxes(n: usize) -> Vec<Aabb> {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n)
            .map(|_| {
                let c = Point3::new(next(), next(), next()) * 10.0;
                let h = Vector3::new(next(), next(), next()) * 0.6;
                Aabb {
                    min: c - h,
                    max: c + h,
                }
            })
            .collect()
    }

    /// The wide hierarchy hands the callback the same items as the binary
    /// one it was collapsed from when the callback never narrows `t_max`;
    /// and when it narrows `t_max` to the entry of the box of every third
    /// item (a "hit"), both end with the same nearest hit.
    #[test]
    fn finds_what_the_binary_hierarchy_finds() {
        for (n, max_leaf) in [(1, 1), (2, 1), (7, 1), (300, 1), (300, 4)] {
            let items = boxes(n);
            let (bvh, order) = Bvh::build(&items, max_leaf);
            let wide = WideBvh::new(&bvh);
            assert!(wide.node_count() <= bvh.node_count());
            for r in 0..400 {
                let (a, b) = (r as f64 * 2.399_963, (r as f64 + 0.5) / 200.0 - 1.0);
                let c = (1.0 - b * b).sqrt();
                let dir = Vector3::new(c * a.cos(), c * a.sin(), b);
                let ray = Ray::new(Point3::new(5.0, 5.0, 5.0) - dir * 12.0, dir);
                let box_ray = BoxRay::new(&ray);
                for narrowing in [false, true] {
                    let mut seen = [Vec::new(), Vec::new()];
                    let mut nearest = [f64::INFINITY; 2];
                    for (side, found) in seen.iter_mut().enumerate() {
                        let mut callback = |k: usize, t_max: f64| {
                            found.push(k);
                            let entry = items[order[k]].clip(&ray, 0.0, t_max).map(|(t, _)| t);
                            match entry {
                                Some(t) if narrowing && k % 3 == 0 => ControlFlow::Continue(t),
                                _ => ControlFlow::Continue(t_max),
                            }
                        };
                        let mut last = f64::INFINITY;
                        let mut tracked = |k: usize, t_max: f64| {
                            let flow = callback(k, t_max);
                            if let ControlFlow::Continue(t) = flow {
                                last = t;
                            }
                            flow
                        };
                        if side == 0 {
                            bvh.traverse(&box_ray, 0.0, f64::INFINITY, &mut tracked);
                        } else {
                            wide.traverse(&box_ray, 0.0, f64::INFINITY, &mut tracked);
                        }
                        nearest[side] = last;
                        found.sort_unstable();
                    }
                    if narrowing {
                        assert_eq!(nearest[0], nearest[1], "{n} boxes, ray {r}");
                    } else {
                        assert_eq!(seen[0], seen[1], "{n} boxes, ray {r}");
                    }
                }
            }
        }
    }
}
