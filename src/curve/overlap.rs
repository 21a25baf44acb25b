//! A proof that two rational Bézier spans run within a tolerance of each
//! other along a stretch: the same arc, up to a change of parameter.
//!
//! # The certificate
//! Two rational Bézier pieces of one degree `n`, `a(u) = Σ Bᵢ wᵢ aᵢ / Σ Bᵢ wᵢ`
//! and `b(u) = Σ Bᵢ vᵢ bᵢ / Σ Bᵢ vᵢ`, are compared control point by control
//! point. A Möbius change of parameter multiplies the weights by `c·ρⁱ` and
//! keeps the control points (Farin, *NURBS*, §13.5), so let
//! `eᵢ = ln(vᵢ/wᵢ) − (r₀ + i·(rₙ − r₀)/n)` with `rᵢ = ln(vᵢ/wᵢ)` be what no
//! such change absorbs, and `m = max |eᵢ|`. After the change the two
//! pieces' normalized basis weights `βᵢ(u)` and `γᵢ(u)` differ by a factor
//! within `e^{±2m}`, and for every `u`
//!
//! ```text
//! |a(u) − b(φ(u))| ≤ maxᵢ |aᵢ − bᵢ| + (e^{2m} − 1)·diam{bᵢ}
//! ```
//!
//! (write `Σβᵢaᵢ − Σγᵢbᵢ = Σβᵢ(aᵢ − bᵢ) + Σ(βᵢ − γᵢ)(bᵢ − c)`, the weights
//! summing to one). When that bound and the rounding of the restrictions
//! stay within the tolerance, every point of either piece is within the
//! tolerance of the other: the curves overlap there.
//!
//! # Finding the stretch
//! The candidates for its ends are the spans' end points that lie within
//! half the tolerance of the other span (certified nearest points). The
//! stretch runs between the extreme candidates; both spans are restricted
//! to it (de Casteljau), the lower degree elevated, `b` reversed when it
//! runs the other way, and the certificate is tried. A span pair that does
//! not pass (curves that agree within the tolerance without being one
//! arc, such as a spline and its approximation) is left to the search.

use super::homogeneous::{Homogeneous, homogeneous_points};
use super::query::CurveProjector;
use super::{Curve, RationalBezier, RationalBezierSpan};
use crate::bernstein::restrict;
use nalgebra::Point;

/// A stretch shorter than this many tolerances (in space) is not reported
/// as an overlap (two spans meeting at an end point are not one arc).
const SHORTEST_STRETCH: f64 = 16.0;

/// The local parameter ranges (`[0, 1]` each, the second possibly
/// decreasing) along which `a` and `b` are proven within `tolerance` of
/// each other, or `None` when no such stretch is proven.
pub(crate) fn coincident_stretch<const D: usize>(
    a: &RationalBezier<D>,
    b: &RationalBezier<D>,
    tolerance: f64,
) -> Option<[(f64, f64); 2]> {
    let (a, b) = same_degree(a, b)?;
    let project = |c: &RationalBezier<D>| {
        CurveProjector::from_spans(vec![RationalBezierSpan {
            knots: (0.0, 1.0),
            curve: c.clone(),
        }])
        .ok()
    };
    let (on_a, on_b) = (project(&a)?, project(&b)?);
    // (s on a, t on b) for every span end within half the tolerance.
    let mut ends: Vec<(f64, f64)> = Vec::with_capacity(4);
    for s in [0.0, 1.0] {
        let near = on_b.nearest(&a.eval(s)).ok()?;
        if near.distance <= 0.5 * tolerance {
            ends.push((s, near.t));
        }
    }
    for t in [0.0, 1.0] {
        let near = on_a.nearest(&b.eval(t)).ok()?;
        if near.distance <= 0.5 * tolerance {
            ends.push((near.t, t));
        }
    }
    let first = *ends.iter().min_by(|x, y| x.0.total_cmp(&y.0))?;
    let last = *ends.iter().max_by(|x, y| x.0.total_cmp(&y.0))?;
    if (a.eval(first.0) - a.eval(last.0)).norm() < SHORTEST_STRETCH * tolerance || first.1 == last.1
    {
        return None;
    }
    let mut pa = homogeneous_points(a.points(), a.weights().iter().copied());
    let mut pb = homogeneous_points(b.points(), b.weights().iter().copied());
    restrict(&mut pa, (first.0, last.0));
    restrict(&mut pb, (first.1.min(last.1), first.1.max(last.1)));
    if first.1 > last.1 {
        pb.reverse();
    }
    within(&pa, &pb, tolerance).then_some([(first.0, last.0), (first.1, last.1)])
}

/// Both pieces at the higher of their degrees (`None` if elevation fails).
fn same_degree<const D: usize>(
    a: &RationalBezier<D>,
    b: &RationalBezier<D>,
) -> Option<(RationalBezier<D>, RationalBezier<D>)> {
    let (da, db) = (a.degree(), b.degree());
    let raise = |c: &RationalBezier<D>, times: usize| {
        if times == 0 {
            Some(c.clone())
        } else {
            c.elevate_degree(times).ok()
        }
    };
    Some((
        raise(a, db.saturating_sub(da))?,
        raise(b, da.saturating_sub(db))?,
    ))
}

/// The certificate of the module docs on two restricted nets of one
/// degree, with a bound on the rounding of their restriction.
fn within<const D: usize>(a: &[Homogeneous<D>], b: &[Homogeneous<D>], tolerance: f64) -> bool {
    let n = a.len() - 1;
    if b.len() != a.len() || a.iter().chain(b).any(|h| !(h.w > 0.0 && h.w.is_finite())) {
        return false;
    }
    let point = |h: &Homogeneous<D>| Point::from(h.wp / h.w);
    let ratios: Vec<f64> = a.iter().zip(b).map(|(x, y)| (y.w / x.w).ln()).collect();
    let slope = if n == 0 {
        0.0
    } else {
        (ratios[n] - ratios[0]) / n as f64
    };
    let unabsorbed = ratios
        .iter()
        .enumerate()
        .map(|(i, r)| (r - ratios[0] - slope * i as f64).abs())
        .fold(0.0_f64, f64::max);
    let apart = a
        .iter()
        .zip(b)
        .map(|(x, y)| (point(x) - point(y)).norm())
        .fold(0.0_f64, f64::max);
    let (lo, hi) = b.iter().map(point).fold(
        (
            Point::from([f64::INFINITY; D]),
            Point::from([f64::NEG_INFINITY; D]),
        ),
        |(lo, hi), p| (lo.inf(&p), hi.sup(&p)),
    );
    let diameter = (hi - lo).norm();
    // Two restrictions of degree n err by about 8(n + 1)ε of the largest
    // homogeneous coordinate each, which the projection divides by the
    // least weight; the weights' logarithms add a few ε more. Sixteen
    // times that covers them.
    let spread = |net: &[Homogeneous<D>]| {
        let (lo, hi) = net.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), h| {
            (lo.min(h.w), hi.max(h.w))
        });
        let largest = net.iter().map(|h| h.wp.amax()).fold(0.0_f64, f64::max);
        (largest / lo).max(hi / lo * net.iter().map(|h| (h.wp / h.w).amax()).fold(0.0, f64::max))
    };
    let magnitude = spread(a).max(spread(b));
    let rounding = 16.0 * (8.0 * (n as f64 + 1.0) + 4.0) * f64::EPSILON * magnitude;
    let bound = apart + (2.0 * unabsorbed).exp_m1() * diameter + rounding;
    bound.is_finite() && bound <= tolerance
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point2;

    fn conic(middle_weight: f64) -> RationalBezier<2> {
        let pts = vec![
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
        ];
        RationalBezier::new(pts, vec![1.0, middle_weight, 1.0]).unwrap()
    }

    #[test]
    fn one_arc_in_two_parameterizations_is_proven() {
        // The quarter circle with weights (1, √½, 1) and its Möbius
        // reparameterization (weights times 2ⁱ): the same arc.
        let a = conic(0.5f64.sqrt());
        let b =
            RationalBezier::new(a.points().to_vec(), vec![1.0, 2.0 * 0.5f64.sqrt(), 4.0]).unwrap();
        let stretch = coincident_stretch(&a, &b, 1e-9).unwrap();
        assert_eq!(stretch, [(0.0, 1.0), (0.0, 1.0)]);
    }

    #[test]
    fn one_control_polygon_with_another_weight_is_not() {
        // Same control points and end points, another conic: apart by
        // about 1e-7 in the middle, more than the tolerance.
        let a = conic(0.5f64.sqrt());
        let b = conic(0.5f64.sqrt() + 1e-6);
        assert!(coincident_stretch(&a, &b, 1e-9).is_none());
        // Within a tolerance larger than the bound (4e-6 here), it is one
        // stretch.
        assert!(coincident_stretch(&a, &b, 1e-5).is_some());
    }

    #[test]
    fn spans_meeting_at_an_end_are_not_a_stretch() {
        let a = conic(1.0);
        let b = RationalBezier::new(
            vec![
                Point2::new(0.0, 1.0),
                Point2::new(-1.0, 1.0),
                Point2::new(-1.0, 0.0),
            ],
            vec![1.0, 1.0, 1.0],
        )
        .unwrap();
        assert!(coincident_stretch(&a, &b, 1e-9).is_none());
    }
}
