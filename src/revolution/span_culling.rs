//! Which spans a ray can meet: each span's height and radius ranges, the
//! groups of spans that share a bounding cylinder, and where a ray enters a
//! span's slab of heights or its cylinder.

use super::query::Query;

/// Spans per culling group for a profile of `n` spans: `⌈√n⌉`. A ray tests
/// all `n / g` groups and the `g` spans of each group it enters; for the one
/// or two groups a ray typically enters, that is least for `g` near `√n`.
pub(super) fn group_size(n: usize) -> usize {
    let root = n.isqrt();
    if root * root < n {
        root + 1
    } else {
        root.max(1)
    }
}
/// Consecutive spans `first..end` and the union of their ranges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Group {
    pub(super) bounds: Span,
    pub(super) first: usize,
    pub(super) end: usize,
}
/// One profile span and its conservative ranges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Span {
    /// The profile parameters the span covers.
    pub(super) u: (f64, f64),
    pub(super) y: (f64, f64),
    /// `|x|` ranges between `r.0` and `r.1` on the span.
    pub(super) r: (f64, f64),
}
/// The least `t` at which the ray is within the span's padded height
/// range, clipped to `(t_floor, t_best)` as [`span_entry`]'s height slab
/// is; `None` when that range lies outside.
#[inline]
pub(super) fn height_entry(span: &Span, q: &Query, t_floor: f64, t_best: f64) -> Option<f64> {
    let (near, far) = height_slab(span, q);
    let lo = t_floor - q.pad_t;
    let enter = if near > lo { near } else { lo };
    let leave = if far < t_best { far } else { t_best };
    (enter <= leave).then_some(enter)
}
/// The `t` at which the ray (`d_y ≠ 0`) enters and leaves the span's
/// height range padded by the position tolerance, in order.
#[inline(always)]
pub(super) fn height_slab(span: &Span, q: &Query) -> (f64, f64) {
    let pad = q.acceptance.distance;
    let (a, b) = (
        (span.y.0 - pad - q.o.y) * q.inv_dy,
        (span.y.1 + pad - q.o.y) * q.inv_dy,
    );
    if a < b { (a, b) } else { (b, a) }
}
/// Where `o + t d` is at distance `|x|` from the axis: the roots of
/// `|o_xz + t d_xz|² = x²`, nearest first. A ray that only approaches the
/// circle (negative discriminant within rounding) gets its closest approach.
#[inline(always)]
pub(super) fn circle_times(q: &Query, x: f64) -> [Option<f64>; 2] {
    let a = q.d.x * q.d.x + q.d.z * q.d.z;
    if a == 0.0 {
        return [None, None];
    }
    let b = q.o.x * q.d.x + q.o.z * q.d.z; // half of the linear coefficient
    let c = q.o.x * q.o.x + q.o.z * q.o.z - x * x;
    let disc = b * b - a * c;
    if disc <= 0.0 {
        return [Some(-b / a), None];
    }
    // Stable: the larger-magnitude root first, the other from the product.
    let h = -(b + b.signum() * disc.sqrt());
    let (t1, t2) = if h != 0.0 { (h / a, c / h) } else { (0.0, 0.0) };
    [Some(t1.min(t2)), Some(t1.max(t2))]
}
/// Where the ray enters span's bounding cylinder (clipped to
/// `(t_floor, t_best)`), or `None` if it misses it or stays within the
/// span's inner radius.
///
/// The height slab gives an interval of `t`; on it the squared distance
/// from the axis `r²(t)` is convex, so the span is missed when `r²` at the
/// closest approach (clamped to the interval) exceeds the outer radius, or
/// when both ends lie inside the inner radius. Only spans that pass get the
/// square root that moves the entry to the outer cylinder.
#[inline]
pub(super) fn span_entry(span: &Span, q: &Query, t_floor: f64, t_best: f64) -> Option<f64> {
    let o = q.o;
    let pad = q.acceptance.distance;
    let (mut lo, mut hi) = (t_floor - q.pad_t, t_best);
    // Height slab.
    let (y0, y1) = (span.y.0 - pad, span.y.1 + pad);
    if q.inv_dy == 0.0 {
        if o.y < y0 || o.y > y1 {
            return None;
        }
    } else {
        let (near, far) = height_slab(span, q);
        if near > lo {
            lo = near;
        }
        if far < hi {
            hi = far;
        }
    }
    if lo > hi {
        return None;
    }
    // r²(t) as the squared length of the ray point's horizontal part: no
    // cancellation between large terms for distant origins.
    let r2 = |t: f64| {
        let (x, z) = (o.x + t * q.d.x, o.z + t * q.d.z);
        x * x + z * z
    };
    let outer = span.r.1 + pad;
    let outer2 = outer * outer;
    // (Plain comparisons rather than `clamp`/`max`: no NaN reaches here,
    // and this loop runs for every span.)
    let closest = if q.t_closest < lo { lo } else { q.t_closest };
    let closest = if closest > hi { hi } else { closest };
    if r2(closest) > outer2 {
        return None;
    }
    let inner = span.r.0 - pad;
    if inner > 0.0 && r2(lo) < inner * inner && r2(hi) < inner * inner {
        return None;
    }
    // Enter at the outer cylinder when the slab starts outside it.
    let (a, b, c) = q.radius;
    if a > 0.0 && r2(lo) > outer2 {
        let disc = b * b - a * (c - outer2);
        if disc > 0.0 {
            let enter = (-b - disc.sqrt()) / a;
            if enter > lo {
                lo = enter;
            }
        }
    }
    Some(lo)
}
