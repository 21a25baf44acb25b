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
//! The children a ray enters are pushed on a stack farthest first, so the
//! nearest is popped next (the stack is sized by the hierarchy's depth: on
//! the stack up to 16 levels, on the heap beyond); an entry whose distance is beyond
//! the best hit found meanwhile is skipped when popped. Leaves are reached
//! in near-to-far order of their boxes, as in [`Bvh::traverse`], and the
//! callback sees the same items with the same narrowing `t_max`.

use super::bvh::{BoxRay, Bvh};
use std::ops::ControlFlow;

/// Children per node.
pub const WIDTH: usize = 4;
/// A slot's count for an empty slot.
const EMPTY: u32 = u32::MAX;
/// Stack entries a traversal needs for a hierarchy `depth` levels deep: at
/// most `WIDTH − 1` left behind per level, plus the children of the last
/// node.
const fn stack_entries(depth: usize) -> usize {
    (WIDTH - 1) * (depth + 1) + WIDTH
}
/// Hierarchies at most this deep are walked with a stack on the stack
/// (zeroed per ray, so kept short); deeper ones (lopsided item sets) with
/// one on the heap.
const SHALLOW: usize = 16;

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
    /// The number of node levels (0 for no nodes).
    depth: usize,
}

impl WideBvh {
    /// The binary hierarchy `bvh` collapsed to four-wide nodes.
    pub fn new(bvh: &Bvh) -> WideBvh {
        let mut wide = WideBvh {
            nodes: Vec::new(),
            depth: 0,
        };
        if bvh.node_count() > 0 {
            wide.depth = wide.collapse(bvh, &[0]).1;
        }
        wide.nodes.shrink_to_fit();
        wide
    }

    /// Adds the wide node over the binary nodes `start` (one or two; more
    /// are gathered here) and returns its index and the levels of nodes
    /// from it down.
    fn collapse(&mut self, bvh: &Bvh, start: &[usize]) -> (u32, usize) {
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
        let mut below = 0;
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
                    let (child, levels) = self.collapse(bvh, &[left, right]);
                    node.link[k] = child;
                    node.count[k] = 0;
                    below = below.max(levels);
                }
            }
        }
        self.nodes[index] = node;
        (index as u32, below + 1)
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
        t_max: f64,
        mut leaf: impl FnMut(usize, f64) -> ControlFlow<(), f64>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        if self.depth <= SHALLOW {
            let mut slots = [0u32; stack_entries(SHALLOW)];
            let mut ts = [0.0f64; stack_entries(SHALLOW)];
            self.walk(ray, t_min, t_max, &mut leaf, &mut slots, &mut ts);
        } else {
            let n = stack_entries(self.depth);
            let (mut slots, mut ts) = (vec![0u32; n], vec![0.0f64; n]);
            self.walk(ray, t_min, t_max, &mut leaf, &mut slots, &mut ts);
        }
    }

    /// [`traverse`](Self::traverse) with the stack `stack_slot`,
    /// `stack_t` (entries: node index × WIDTH + slot, and the slot's entry
    /// distance; at least `stack_entries(depth)` of them).
    #[inline(always)]
    fn walk(
        &self,
        ray: &BoxRay,
        t_min: f64,
        mut t_max: f64,
        leaf: &mut impl FnMut(usize, f64) -> ControlFlow<(), f64>,
        stack_slot: &mut [u32],
        stack_t: &mut [f64],
    ) {
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
        let mut next = || crate::test_unit::unit(&mut state);
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

    /// Boxes along the x axis at `2ᵏ`, growing with `k`: the binned build
    /// splits off one box at a time, so the hierarchy is a deep chain.
    fn chain(n: usize) -> Vec<Aabb> {
        (0..n)
            .map(|k| {
                let c = Point3::new(2f64.powi(k as i32), 0.5, 0.5);
                let h = Vector3::new(0.1 * 2f64.powi(k as i32), 0.4, 0.4);
                Aabb {
                    min: c - h,
                    max: c + h,
                }
            })
            .collect()
    }

    /// The chain of [`chain`] is deeper than a stack on the stack holds, so
    /// its walks take the heap's.
    #[test]
    fn a_deep_chain_is_walked_with_a_stack_on_the_heap() {
        let (bvh, _) = Bvh::build(&chain(120), 1);
        assert!(WideBvh::new(&bvh).depth > super::SHALLOW);
    }

    /// The wide hierarchy hands the callback the same items as the binary
    /// one it was collapsed from when the callback never narrows `t_max`;
    /// and when it narrows `t_max` to the entry of the box of every third
    /// item (a "hit"), both end with the same nearest hit.
    #[test]
    fn finds_what_the_binary_hierarchy_finds() {
        for (n, max_leaf) in [(0, 1), (1, 1), (2, 1), (7, 1), (300, 1), (300, 4), (120, 1)] {
            let items = if n == 120 { chain(n) } else { boxes(n) };
            let (bvh, order) = Bvh::build(&items, max_leaf);
            let wide = WideBvh::new(&bvh);
            assert!(wide.node_count() <= bvh.node_count());
            for r in 0..400 {
                let (a, b) = (r as f64 * 2.399_963, (r as f64 + 0.5) / 200.0 - 1.0);
                let c = (1.0 - b * b).sqrt();
                let dir = Vector3::new(c * a.cos(), c * a.sin(), b);
                let centre = if n == 120 {
                    Point3::new(1e3, 0.5, 0.5)
                } else {
                    Point3::new(5.0, 5.0, 5.0)
                };
                let ray = Ray::new(centre - dir * 12.0, dir);
                let box_ray = BoxRay::new(&ray);
                for narrowing in [false, true] {
                    // Per side: the items seen, and the last t_max returned
                    // (the nearest "hit").
                    let mut seen = [Vec::new(), Vec::new()];
                    let mut nearest = [f64::INFINITY; 2];
                    for (side, (found, last)) in seen.iter_mut().zip(&mut nearest).enumerate() {
                        let mut callback = |k: usize, t_max: f64| {
                            found.push(k);
                            let entry = items[order[k]].clip(&ray, 0.0, t_max).map(|(t, _)| t);
                            *last = match entry {
                                Some(t) if narrowing && k % 3 == 0 => t,
                                _ => t_max,
                            };
                            ControlFlow::Continue(*last)
                        };
                        if side == 0 {
                            bvh.traverse(&box_ray, 0.0, f64::INFINITY, &mut callback);
                        } else {
                            wide.traverse(&box_ray, 0.0, f64::INFINITY, &mut callback);
                        }
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
