//! Every common point of a space curve with rational Bézier spans and a
//! tensor-product surface, certified where the crossing is transversal
//! (see [`BezierSurface::intersect_curve`]).

use super::patch_table::PatchTable;
use crate::curve::{
    Homogeneous, LocalRoot, MAX_BOXES, Net, PairOutcome, check_spans, power_of_two_near,
    search_pair, span_net, span_parameter, working_scale,
};
use crate::{BSplineSurface, BezierSurface, Curve, Error, NurbsSurface};
use nalgebra::Point3;

/// Results closer than this in every parameter (relative to the span's and
/// the patch's widths) are one intersection found twice.
const DUPLICATE: f64 = 1e-9;

/// A result with the widths of its span and patch and its parameter region
/// (the cluster's hull for an uncertified one).
type Entry = (CurveSurfaceHit, [f64; 3], [(f64, f64); 3]);

/// One common point of a curve `C` and a surface `S`:
/// `C(t) = S(u, v) = point`.
///
/// `t` is in the curve's domain, `uv` in the surface's own parameters;
/// `point` is the midpoint of `C(t)` and `S(u, v)`. `certified` is `true`
/// when a box of `(t, u, v)` around the result was proven to hold exactly
/// one root of `C(t) − S(u, v)` (Krawczyk's test), the result being that
/// root polished by Newton's method; `false` marks a place where the curve
/// comes within about the tolerance of the surface without a proven single
/// crossing (the curve tangent to the surface, two crossings closer than
/// the tolerance, or a near miss closer than it), accurate to about the
/// tolerance.
///
/// ```
/// use revolve::tensor::CurveSurfaceHit;
/// use revolve::{Bezier, BezierSurface};
/// use revolve::nalgebra::Point3;
///
/// let plane = BezierSurface::new(vec![
///     vec![Point3::new(-1.0, -1.0, 0.0), Point3::new(-1.0, 1.0, 0.0)],
///     vec![Point3::new(1.0, -1.0, 0.0), Point3::new(1.0, 1.0, 0.0)],
/// ])?;
/// let segment = Bezier::new(vec![Point3::new(0.5, 0.0, -1.0), Point3::new(0.5, 0.0, 3.0)])?;
/// let hits: Vec<CurveSurfaceHit> = plane.intersect_curve(&segment, 1e-9)?;
/// assert_eq!(hits.len(), 1);
/// assert!(hits[0].certified && (hits[0].t - 0.25).abs() < 1e-15);
/// assert!((hits[0].uv.0 - 0.75).abs() < 1e-15 && (hits[0].uv.1 - 0.5).abs() < 1e-15);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveSurfaceHit {
    /// The curve's parameter.
    pub t: f64,
    /// The surface's parameters `(u, v)`.
    pub uv: (f64, f64),
    /// The common point.
    pub point: Point3<f64>,
    /// Whether the crossing is proven single (see the type's docs).
    pub certified: bool,
}

impl PatchTable {
    /// Every intersection of `curve` with the table's patches (see
    /// [`BezierSurface::intersect_curve`]).
    pub(crate) fn intersect_curve<C: Curve<3> + ?Sized>(
        &self,
        curve: &C,
        tolerance: f64,
    ) -> Result<Vec<CurveSurfaceHit>, Error> {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(Error::InvalidTolerance { tolerance });
        }
        let spans = curve
            .rational_bezier_spans()
            .ok_or(Error::NotPiecewiseRational)?;
        check_spans(&spans)?;
        let (p, q) = self.degrees;
        let patch_box = |net: &[Homogeneous<3>]| {
            net.iter().fold(
                (
                    Point3::from([f64::INFINITY; 3]),
                    Point3::from([f64::NEG_INFINITY; 3]),
                ),
                |(lo, hi), h| {
                    let x = Point3::from(h.wp / h.w);
                    (lo.inf(&x), hi.sup(&x))
                },
            )
        };
        let boxes: Vec<(Point3<f64>, Point3<f64>)> = self
            .patches
            .iter()
            .map(|patch| patch_box(&patch.net))
            .collect();
        let magnitude = spans
            .iter()
            .flat_map(|s| s.curve.points().iter().map(|x| x.coords.amax()))
            .chain(
                boxes
                    .iter()
                    .map(|(lo, hi)| lo.coords.amax().max(hi.coords.amax())),
            )
            .fold(0.0, f64::max);
        let longest = spans
            .iter()
            .map(|s| s.curve.points().len())
            .max()
            .unwrap_or(0);
        let scale = working_scale(tolerance, magnitude, longest * (p + 1) * (q + 1))?;
        let patch_nets: Vec<Net<3>> = self
            .patches
            .iter()
            .map(|patch| {
                let ws = power_of_two_near(patch.net.iter().fold(0.0_f64, |m, h| m.max(h.w)));
                Net {
                    coefs: patch
                        .net
                        .iter()
                        .map(|h| Homogeneous {
                            wp: h.wp / ws / scale,
                            w: h.w / ws,
                        })
                        .collect(),
                    degrees: vec![p, q],
                }
            })
            .collect();
        let mut found: Vec<Entry> = Vec::new();
        for span in &spans {
            let net = span_net(&span.curve, scale);
            let (lo, hi) = span.curve.bounds();
            for (k, patch) in self.patches.iter().enumerate() {
                let (plo, phi) = boxes[k];
                let meet = (0..3).all(|c| {
                    let pad = tolerance
                        + 1e-12 * (lo[c].abs() + hi[c].abs() + plo[c].abs() + phi[c].abs());
                    lo[c] <= phi[c] + pad && plo[c] <= hi[c] + pad
                });
                if !meet {
                    continue;
                }
                let at = |(a, b): (f64, f64), s: f64| {
                    if s <= 0.0 {
                        a
                    } else if s >= 1.0 {
                        b
                    } else {
                        (a + (b - a) * s).clamp(a, b)
                    }
                };
                match search_pair(&net, &patch_nets[k], tolerance / scale, MAX_BOXES) {
                    PairOutcome::Roots(roots) => {
                        for LocalRoot { x, certified, hull } in roots {
                            let (u, v) = (at(patch.u, x[1]), at(patch.v, x[2]));
                            let on_curve = span.curve.eval(x[0]);
                            let on_surface = Point3::from(self.jet(u, v, 0)[0][0]);
                            let widths = [
                                span.knots.1 - span.knots.0,
                                patch.u.1 - patch.u.0,
                                patch.v.1 - patch.v.0,
                            ];
                            found.push((
                                CurveSurfaceHit {
                                    t: span_parameter(span, x[0]),
                                    uv: (u, v),
                                    point: Point3::from(
                                        (on_curve.coords + on_surface.coords) * 0.5,
                                    ),
                                    certified,
                                },
                                widths,
                                [
                                    (
                                        span_parameter(span, hull[0].0),
                                        span_parameter(span, hull[0].1),
                                    ),
                                    (at(patch.u, hull[1].0), at(patch.u, hull[1].1)),
                                    (at(patch.v, hull[2].0), at(patch.v, hull[2].1)),
                                ],
                            ));
                        }
                    }
                    // The budget is the cap, so the search always finishes
                    // (an unfinished one would be reported as the caps are).
                    outcome @ (PairOutcome::Overlap(_) | PairOutcome::Unfinished) => {
                        let h = match outcome {
                            PairOutcome::Overlap(h) => h,
                            _ => [(0.0, 1.0); 3],
                        };
                        return Err(Error::CurveOnSurface {
                            t: (span_parameter(span, h[0].0), span_parameter(span, h[0].1)),
                            u: (at(patch.u, h[1].0), at(patch.u, h[1].1)),
                            v: (at(patch.v, h[2].0), at(patch.v, h[2].1)),
                        });
                    }
                }
            }
        }
        let ends = (spans[0].knots.0, spans[spans.len() - 1].knots.1);
        let seam = |x: f64, y: f64| {
            let at = |p: f64, q: f64| (p - q).abs() <= DUPLICATE * (ends.1 - ends.0);
            (at(x, ends.0) && at(y, ends.1)) || (at(x, ends.1) && at(y, ends.0))
        };
        let coincide = 64.0 * f64::EPSILON * magnitude;
        let mut out: Vec<Entry> = Vec::new();
        for (hit, w, region) in found {
            let same = |o: &Entry| {
                let wide = |k: usize| DUPLICATE * w[k].max(o.1[k]);
                let points = (o.0.point - hit.point).norm() <= coincide;
                let same_t = (o.0.t - hit.t).abs() <= wide(0) || (points && seam(o.0.t, hit.t));
                let same_uv = ((o.0.uv.0 - hit.uv.0).abs() <= wide(1)
                    && (o.0.uv.1 - hit.uv.1).abs() <= wide(2))
                    || points;
                let close = (!o.0.certified || !hit.certified)
                    && (o.0.point - hit.point).norm() <= 4.0 * tolerance;
                // Clusters that touch across a span join or a patch edge
                // are one.
                let touch = !o.0.certified
                    && !hit.certified
                    && (0..3).all(|k| {
                        region[k].0 <= o.2[k].1 + wide(k) && o.2[k].0 <= region[k].1 + wide(k)
                    });
                (same_t && same_uv) || close || touch
            };
            match out.iter_mut().find(|o| same(o)) {
                Some(o) => {
                    if hit.certified && !o.0.certified {
                        *o = (hit, w, region);
                    } else if !hit.certified && !o.0.certified {
                        for (slot, r) in o.2.iter_mut().zip(&region) {
                            *slot = (slot.0.min(r.0), slot.1.max(r.1));
                        }
                    }
                }
                None => out.push((hit, w, region)),
            }
        }
        let mut out: Vec<CurveSurfaceHit> = out.into_iter().map(|o| o.0).collect();
        out.sort_by(|a, b| {
            a.t.total_cmp(&b.t)
                .then(a.uv.0.total_cmp(&b.uv.0))
                .then(a.uv.1.total_cmp(&b.uv.1))
        });
        Ok(out)
    }
}

impl BezierSurface {
    /// Every intersection of the space curve `curve` with the surface, in
    /// increasing curve parameter `t`.
    ///
    /// # Method
    /// The curve is taken as its [rational Bézier
    /// spans](Curve::rational_bezier_spans), the surface as its (rational)
    /// Bézier patches. For a span `C(r) = X(r)/W(r)` and a patch `S(s, t) =
    /// Y(s, t)/V(s, t)` the common points are the roots in `[0, 1]³` of the
    /// polynomial system `G = X(r)·V(s, t) − Y(s, t)·W(r) = 0` (three
    /// equations; equivalent, the weights being positive). Boxes of
    /// `(r, s, t)` are examined from a stack: a box is dropped when the
    /// restricted control points of the curve piece and of the patch piece
    /// are separated along an axis or along the patch piece's normal (its
    /// diagonals' cross product), with every rounding error bounded; a box
    /// is done when Krawczyk's operator maps it (widened by an eighth on each
    /// side) strictly into itself, which proves exactly one root, polished
    /// by Newton's method on the 3×3 system `C(r) − S(s, t) = 0`; otherwise
    /// each piece wider than `tolerance` is halved. Undecided boxes whose
    /// pieces are within `tolerance` are grouped into clusters of touching
    /// boxes, one `certified: false` result each (the search is the one of
    /// [`intersect_curves`](crate::curve::intersect_curves), documented in
    /// the `curve::intersection_search` module).
    ///
    /// # What is certified
    /// No intersection is missed (a box is dropped only on a proof that it
    /// holds none). Every `certified` result is a true, single crossing; a
    /// transversal crossing is found certified once the boxes around it are
    /// small enough for Krawczyk's test. A curve tangent to the surface,
    /// crossings closer than the tolerance and near misses closer than it
    /// are reported once, `certified: false`. A crossing on a patch edge or
    /// at a span join, found from both sides, is reported once; so is one at
    /// the seam of a closed curve.
    ///
    /// # Caps
    /// At most 2¹⁸ boxes and 2¹³ undecided leaves per span and patch, boxes
    /// at most 48 halvings deep; systems of at most 2¹⁴ coefficients.
    ///
    /// ```
    /// use revolve::{BezierSurface, Nurbs};
    /// use revolve::nalgebra::Point3;
    ///
    /// // The plane z = 0 and an ellipse tilted through it (the unit circle's
    /// // NURBS control points mapped by (x, y) ↦ (x, y, y + 0.5)): it crosses
    /// // where y = −1/2, at x = ±√3/2.
    /// let plane = BezierSurface::new(vec![
    ///     vec![Point3::new(-2.0, -2.0, 0.0), Point3::new(-2.0, 2.0, 0.0)],
    ///     vec![Point3::new(2.0, -2.0, 0.0), Point3::new(2.0, 2.0, 0.0)],
    /// ])?;
    /// let circle = Nurbs::circle(revolve::nalgebra::Point2::origin(), 1.0)?;
    /// let points = circle.points().iter().map(|p| Point3::new(p.x, p.y, p.y + 0.5)).collect();
    /// let ellipse = Nurbs::new(2, circle.knots().to_vec(), points, circle.weights().to_vec())?;
    /// let hits = plane.intersect_curve(&ellipse, 1e-9)?;
    /// assert_eq!(hits.len(), 2);
    /// for h in &hits {
    ///     assert!(h.certified);
    ///     assert!((h.point.x.abs() - 0.75f64.sqrt()).abs() < 1e-14 && (h.point.y + 0.5).abs() < 1e-14);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] unless `tolerance` is finite and
    /// positive; [`Error::ToleranceTooSmall`] below
    /// [`MIN_INTERSECTION_TOLERANCE`](crate::curve::MIN_INTERSECTION_TOLERANCE)
    /// times the largest absolute control-point coordinate (curve and
    /// surface); [`Error::NotPiecewiseRational`] for a curve without
    /// rational spans; [`Error::SpansOutOfOrder`] or
    /// [`Error::SpanPointNotFinite`] for spans that break their contract;
    /// [`Error::IntersectionTooLarge`] when a span and a patch would need
    /// more than `2¹⁴` coefficients; [`Error::CurveOnSurface`] when the
    /// curve runs within `tolerance` of the surface along a stretch (lies
    /// on it), with the parameter ranges of the part found.
    pub fn intersect_curve<C: Curve<3> + ?Sized>(
        &self,
        curve: &C,
        tolerance: f64,
    ) -> Result<Vec<CurveSurfaceHit>, Error> {
        self.table().intersect_curve(curve, tolerance)
    }
}

impl BSplineSurface {
    /// Every intersection of the space curve `curve` with the surface, as
    /// [`BezierSurface::intersect_curve`] over the surface's Bézier patches
    /// (`uv` in the surface's knot parameters).
    ///
    /// ```
    /// use revolve::{BSplineSurface, Bezier};
    /// use revolve::nalgebra::Point3;
    ///
    /// // A bilinear plane z = 0 on [0, 2] × [0, 1], two patches along u.
    /// let grid = (0..3)
    ///     .map(|i| (0..2).map(|j| Point3::new(i as f64, j as f64, 0.0)).collect())
    ///     .collect();
    /// let knots = (vec![0.0, 0.0, 1.0, 2.0, 2.0], vec![0.0, 0.0, 1.0, 1.0]);
    /// let plane = BSplineSurface::new((1, 1), knots, grid)?;
    /// let line = Bezier::new(vec![Point3::new(1.0, 0.5, 1.0), Point3::new(1.0, 0.5, -1.0)])?;
    /// let hits = plane.intersect_curve(&line, 1e-9)?;
    /// assert_eq!(hits.len(), 1); // on the patches' common edge: once
    /// assert!((hits[0].point - Point3::new(1.0, 0.5, 0.0)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BezierSurface::intersect_curve`].
    pub fn intersect_curve<C: Curve<3> + ?Sized>(
        &self,
        curve: &C,
        tolerance: f64,
    ) -> Result<Vec<CurveSurfaceHit>, Error> {
        self.core().table.intersect_curve(curve, tolerance)
    }
}

impl NurbsSurface {
    /// Every intersection of the space curve `curve` with the surface, as
    /// [`BezierSurface::intersect_curve`] over the surface's rational Bézier
    /// patches (`uv` in the surface's knot parameters).
    ///
    /// ```
    /// use revolve::{Bezier, NurbsSurface};
    /// use revolve::nalgebra::Point3;
    ///
    /// // A quarter cylinder x² + y² = 1 (weights 1, √2/2, 1 along u), z in [0, 1].
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let quarter = [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    /// let points = quarter
    ///     .iter()
    ///     .map(|&(x, y)| vec![Point3::new(x, y, 0.0), Point3::new(x, y, 1.0)])
    ///     .collect();
    /// let weights = vec![vec![1.0, 1.0], vec![h, h], vec![1.0, 1.0]];
    /// let knots = (vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]);
    /// let cylinder = NurbsSurface::new((2, 1), knots, points, weights)?;
    /// // The diagonal from the axis: meets the cylinder at (h, h, 0.5).
    /// let line = Bezier::new(vec![Point3::new(0.0, 0.0, 0.5), Point3::new(2.0, 2.0, 0.5)])?;
    /// let hits = cylinder.intersect_curve(&line, 1e-9)?;
    /// assert_eq!(hits.len(), 1);
    /// assert!(hits[0].certified && (hits[0].point - Point3::new(h, h, 0.5)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`BezierSurface::intersect_curve`].
    pub fn intersect_curve<C: Curve<3> + ?Sized>(
        &self,
        curve: &C,
        tolerance: f64,
    ) -> Result<Vec<CurveSurfaceHit>, Error> {
        self.core().table.intersect_curve(curve, tolerance)
    }
}
