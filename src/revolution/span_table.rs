//! Exact ray intersection for surfaces of revolution: the angle is
//! eliminated and each Bézier span of the profile gives one polynomial.
//!
//! In the local frame (axis = `y`) a ray `o + t·d` meets the surface where, for
//! some profile parameter `u`, the ray point at height `y(u)` is at distance
//! `|x(u)|` from the axis. Multiplying by `d_y²` instead of dividing by `d_y`:
//!
//! `f(u) = A(u)² + B(u)² − (d_y·x(u))² = 0`, with
//! `A = o_x d_y + (y(u) − o_y) d_x`, `B = o_z d_y + (y(u) − o_y) d_z`.
//!
//! `A`, `B` and `d_y x` are polynomials of the span's degree `n` whose Bernstein
//! coefficients come straight from the control points, so `f` has degree `2n`
//! with coefficients `f_k = Σ_{i+j=k} C(n,i)C(n,j)/C(2n,k) (aᵢaⱼ + bᵢbⱼ − cᵢcⱼ)`.
//! The same sums over magnitudes give a rounding bound for every
//! coefficient, so [`find_roots`](crate::roots::find_roots) can isolate all roots without missing one.
//! Each root `u` gives `t` (from the height, or from the radius for shallow
//! rays), and Newton's method on the unsquared system polishes the hit: in
//! the meridian plane, with the angle eliminated exactly (`θ` is the ray
//! point's own angle), `ρ(t) = |x(u)|`, `p_y(t) = y(u)`.
//! Rays perpendicular to the axis (`d_y = 0`) solve `y(u) = o_y` instead.
//!
//! Spans are culled by their height and radius ranges and visited in order of
//! where the ray enters their bounding cylinder; the search stops once the
//! best hit is nearer than the next span. Which spans a ray tests at all is
//! looked up in a table built once per surface
//! ([`MeridianCells`]): from the ray's distance from the axis, the height of
//! its closest approach and its angle with the axis, to the spans a line
//! like it can meet.
//!
//! The same table marks the spans on which every line of the ray's class
//! has a strictly monotonic `f`. On those, `f` at the span's two end
//! control points decides: certainly of one sign, no root (the span is
//! passed over without its cylinder test); certainly of opposite signs,
//! exactly one simple root, which safeguarded Newton on `f` itself finds
//! from the chord's crossing before the polish, with no polynomial formed
//! (such a span is ordered by the least `t` its heights allow). An end
//! value within its rounding of zero, or a span not so marked, takes the
//! path below.
//!
//! Spans of degree ≤ 5 are worked on as fixed-size arrays
//! ([`span_form`](super::span_form)): the polynomial, the root decision, the
//! refinement and the polish are compiled for that size. Most spans are
//! decided by [`quick_roots`] (no root, or one certain sign change and its
//! refined root); the rest go to the full search, [`find_roots_to`].

use super::meridian_cells::{MeridianCells, SpanBox, product_weights};
use super::monotone_spans::SpanCurves;
use super::span_culling::{Group, Span, group_size};
use crate::RationalBezierSpan;
use crate::bernstein::Coefficient;
use nalgebra::{Vector2, Vector3 as Homogeneous2};

/// Profiles of more spans than this get no [`MeridianCells`] (its masks and
/// its construction grow with cells × spans); they cull by groups alone.
const MAX_CELL_SPANS: usize = 1024;
/// The per-surface data of the exact intersector, computed once.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SpanTable {
    pub(super) degree: usize,
    pub(super) spans: Vec<Span>,
    /// Runs of [`group_size`] consecutive spans with their joint ranges: a
    /// ray that misses a group's cylinder skips its spans' tests.
    pub(super) groups: Vec<Group>,
    /// The spans each kind of line can meet (profiles of two spans or more,
    /// up to [`MAX_CELL_SPANS`]); rays it cannot place use the groups.
    pub(super) cells: Option<MeridianCells>,
    /// `x` and `y` Bernstein coefficients, `degree + 1` per span: the
    /// control points (of a rational span too).
    pub(super) xs: Vec<f64>,
    pub(super) ys: Vec<f64>,
    /// The weights, `degree + 1` per span (the largest of each span 1);
    /// empty when every span is polynomial.
    pub(super) ws: Vec<f64>,
    /// `C(n,i)·C(n,j)/C(2n,i+j)`, row-major `(n + 1) × (n + 1)`.
    pub(super) weights: Vec<f64>,
    /// Largest `|x|`, and the height range, over all control points.
    pub(super) r_max: f64,
    pub(super) y_range: (f64, f64),
    /// Largest absolute local coordinate: the scale of relative tolerances.
    pub(crate) scale: f64,
    /// The power of two that brought the profile into the working frame
    /// (every length above is in it): it brings the object's scale into
    /// `[0.5, 1)`, exactly.
    pub(super) unit: f64,
    /// The profile's parameter domain (first span's start, last span's end).
    pub(super) domain: (f64, f64),
}

impl SpanTable {
    /// The table for a profile given as (rational) Bézier spans (in
    /// parameter order, as
    /// [`Curve::rational_bezier_spans`](crate::Curve::rational_bezier_spans)
    /// promises); `None` when there are none. Spans of lower degree are
    /// raised to the highest.
    ///
    /// With positive weights a rational span lies in the convex hull of its
    /// control points, so the height and radius ranges below hold for it as
    /// for a polynomial one.
    pub(crate) fn new(spans: &[RationalBezierSpan<2>]) -> Option<Self> {
        let degree = spans.iter().map(|s| s.curve.degree()).max()?;
        let unit = working_unit(spans);
        let split = refine_spans(spans, degree, unit);
        let spans = &split[..];
        let rational = spans.iter().any(|s| s.weights.is_some());
        let mut xs = Vec::with_capacity(spans.len() * (degree + 1));
        let mut ys = Vec::with_capacity(xs.capacity());
        let mut ws = Vec::with_capacity(if rational { xs.capacity() } else { 0 });
        let mut table = Vec::with_capacity(spans.len());
        for s in spans {
            let pts = &s.points[..];
            xs.extend(pts.iter().map(|p| p.x));
            ys.extend(pts.iter().map(|p| p.y));
            if rational {
                match &s.weights {
                    Some(w) => ws.extend_from_slice(w),
                    None => ws.extend(pts.iter().map(|_| 1.0)),
                }
            }
            let (y0, y1) = pts
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    (a.min(p.y), b.max(p.y))
                });
            let r1 = pts.iter().fold(0.0_f64, |m, p| m.max(p.x.abs()));
            // If the control points' x keep one sign, |x| ≥ min |xᵢ|.
            let one_side = pts.iter().all(|p| p.x > 0.0) || pts.iter().all(|p| p.x < 0.0);
            let r0 = if one_side {
                pts.iter().fold(f64::INFINITY, |m, p| m.min(p.x.abs()))
            } else {
                0.0
            };
            table.push(Span {
                u: s.knots,
                y: (y0, y1),
                r: (r0, r1),
            });
        }
        let weights = product_weights(degree);
        let r_max = table.iter().fold(0.0_f64, |m, s| m.max(s.r.1));
        let y_range = table
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
                (a.min(s.y.0), b.max(s.y.1))
            });
        let scale = r_max.max(y_range.0.abs()).max(y_range.1.abs());
        let domain = (table[0].u.0, table[table.len() - 1].u.1);
        let group = group_size(table.len());
        let boxes: Vec<SpanBox> = table.iter().map(|s| SpanBox { y: s.y, r: s.r }).collect();
        let cells = (table.len() > 1 && table.len() <= MAX_CELL_SPANS && scale > 0.0).then(|| {
            let mut cells = MeridianCells::new(&boxes, scale);
            // The monotonicity certificates are for polynomial spans; a
            // rational profile's spans all take the full search.
            if !rational {
                cells.certify_monotone(SpanCurves {
                    xs: &xs,
                    ys: &ys,
                    w: degree + 1,
                    weights: &weights,
                });
            }
            cells
        });
        Some(SpanTable {
            cells,
            domain,
            degree,
            groups: table
                .chunks(group)
                .enumerate()
                .map(|(g, run)| Group {
                    bounds: run.iter().skip(1).fold(run[0], |b, s| Span {
                        u: (b.u.0, s.u.1),
                        y: (b.y.0.min(s.y.0), b.y.1.max(s.y.1)),
                        r: (b.r.0.min(s.r.0), b.r.1.max(s.r.1)),
                    }),
                    first: g * group,
                    end: g * group + run.len(),
                })
                .collect(),
            spans: table,
            xs,
            ys,
            ws,
            weights,
            r_max,
            y_range,
            scale,
            unit,
        })
    }
    /// The bytes the table holds on the heap: its spans, groups and
    /// coefficients, and the line-class cells.
    pub(crate) fn heap_bytes(&self) -> usize {
        fn held<T>(v: &Vec<T>) -> usize {
            v.capacity() * size_of::<T>()
        }
        held(&self.spans)
            + held(&self.groups)
            + held(&self.xs)
            + held(&self.ys)
            + held(&self.ws)
            + held(&self.weights)
            + self.cells.as_ref().map_or(0, MeridianCells::heap_bytes)
    }
    /// The first and last control points `(x, y)` of span `k`.
    pub(super) fn end_points(&self, k: usize) -> [(f64, f64); 2] {
        let w = self.degree + 1;
        let (first, last) = (k * w, k * w + self.degree);
        [
            (self.xs[first], self.ys[first]),
            (self.xs[last], self.ys[last]),
        ]
    }
    /// Span `k`'s `x` and `y` coefficients, and its weights if the profile
    /// is rational.
    pub(super) fn coeffs(&self, k: usize) -> (&[f64], &[f64], Option<&[f64]>) {
        let w = self.degree + 1;
        let range = k * w..(k + 1) * w;
        let ws = (!self.ws.is_empty()).then(|| &self.ws[range.clone()]);
        (&self.xs[range.clone()], &self.ys[range], ws)
    }
    /// The largest `|x|` and the height range of the profile's control
    /// points, in the profile's own units.
    pub(crate) fn local_bounds(&self) -> (f64, (f64, f64)) {
        let back = 1.0 / self.unit;
        (
            self.r_max * back,
            (self.y_range.0 * back, self.y_range.1 * back),
        )
    }
}

/// Profiles are cut into at least this many pieces (each span into equal
/// parameter parts): tighter height and radius ranges cull more spans per
/// ray and leave simpler polynomials to the ones that remain.
const MIN_PIECES: usize = 8;
/// One refined span in the working frame: its profile parameters, control
/// points and, for a rational span, weights (the largest 1).
struct Piece {
    knots: (f64, f64),
    points: Vec<Vector2<f64>>,
    weights: Option<Vec<f64>>,
}
/// The exponent of the largest working unit, `2^1000`.
const MAX_UNIT_EXPONENT: i32 = 1000;
/// The power of two that brings the largest control-point coordinate of
/// `spans` into `[0.5, 1)` (1 when they are all zero): multiplying by it is
/// exact, so the working frame is the same profile, only rescaled.
fn working_unit(spans: &[RationalBezierSpan<2>]) -> f64 {
    let size = spans
        .iter()
        .flat_map(|s| s.curve.points())
        .fold(0.0_f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    if !(size > 0.0 && size.is_finite()) {
        return 1.0;
    }
    // size = f·2^e with f in [0.5, 1): the unit is 2^−e. A profile below
    // 2^−1000 (subnormal coordinates) is brought up by 2^1000 only, the
    // largest unit whose reciprocal stays a normal number: its working
    // scale is then below 0.5, which the solver's relative bounds allow.
    let e = size.log2().floor() as i32 + 1;
    if e < -MAX_UNIT_EXPONENT {
        return 2.0_f64.powi(MAX_UNIT_EXPONENT);
    }
    let unit = 2.0_f64.powi(-e);
    // log2 may round across a power of two: settle it exactly.
    if size * unit >= 1.0 {
        unit * 0.5
    } else if size * unit < 0.5 {
        unit * 2.0
    } else {
        unit
    }
}
/// The spans raised to `degree` and cut by de Casteljau subdivision into
/// `⌈MIN_PIECES / n⌉` equal parameter parts each (the same curve, exactly
/// up to rounding), control points multiplied by `unit`. Nothing is dropped.
///
/// Polynomial spans (equal weights) are worked on as points; rational ones
/// as homogeneous points `(wx, wy, w)`, whose raising and subdivision are
/// the same linear steps, then divided back into points and weights.
fn refine_spans(spans: &[RationalBezierSpan<2>], degree: usize, unit: f64) -> Vec<Piece> {
    let parts = MIN_PIECES.div_ceil(spans.len()).max(1);
    let mut out = Vec::with_capacity(spans.len() * parts);
    for span in spans {
        let curve = &span.curve;
        let points = curve.points().iter().map(|p| p.coords * unit);
        if curve.is_polynomial() {
            for (knots, points) in split_span(points.collect(), span.knots, degree, parts) {
                out.push(Piece {
                    knots,
                    points,
                    weights: None,
                });
            }
        } else {
            let homogeneous = points
                .zip(curve.weights())
                .map(|(p, &w)| Homogeneous2::new(p.x * w, p.y * w, w))
                .collect();
            for (knots, h) in split_span(homogeneous, span.knots, degree, parts) {
                let top = h.iter().fold(0.0_f64, |m, h| m.max(h.z));
                out.push(Piece {
                    knots,
                    points: h
                        .iter()
                        .map(|h| Vector2::new(h.x / h.z, h.y / h.z))
                        .collect(),
                    weights: Some(h.iter().map(|h| h.z / top).collect()),
                });
            }
        }
    }
    out
}
/// The Bézier coefficients `rest` on `knots`, raised to `degree` and cut
/// into `parts` equal parameter parts.
fn split_span<T: Coefficient>(
    mut rest: Vec<T>,
    (a, b): (f64, f64),
    degree: usize,
    parts: usize,
) -> Vec<((f64, f64), Vec<T>)> {
    use crate::bernstein::subdivide;
    while rest.len() <= degree {
        rest = raise_degree(&rest);
    }
    let (mut left, mut right) = (rest.clone(), rest.clone());
    let mut out = Vec::with_capacity(parts);
    for k in 0..parts {
        let (lo, hi) = (
            a + (b - a) * k as f64 / parts as f64,
            if k + 1 == parts {
                b
            } else {
                a + (b - a) * (k + 1) as f64 / parts as f64
            },
        );
        let points = if k + 1 == parts {
            rest.clone()
        } else {
            // Split what remains at the share this part takes of it.
            subdivide(&rest, 1.0 / (parts - k) as f64, &mut left, &mut right);
            rest.copy_from_slice(&right);
            left.clone()
        };
        out.push(((lo, hi), points));
    }
    out
}
/// The control points of the same Bézier curve one degree higher:
/// `Qᵢ = (i/(n+1))·Pᵢ₋₁ + (1 − i/(n+1))·Pᵢ`, `i = 0 … n+1` (Farin, *Curves
/// and Surfaces for CAGD*, §5.1). The same curve as
/// [`elevate_degree`](crate::bernstein::elevate_degree) by one, but not the
/// same bits: that kernel rounds each weight as a ratio of binomials, this
/// one takes `1 − i/(n+1)` for the second, and the span table's hits are
/// kept as they are.
fn raise_degree<T: Coefficient>(points: &[T]) -> Vec<T> {
    let m = points.len() as f64;
    (0..=points.len())
        .filter_map(|i| {
            let a = i as f64 / m;
            match (i.checked_sub(1).map(|j| points[j]), points.get(i)) {
                (Some(p), Some(q)) => Some(p * a + *q * (1.0 - a)),
                (Some(p), None) => Some(p),
                (None, Some(q)) => Some(*q),
                (None, None) => None,
            }
        })
        .collect()
}
#[cfg(test)]
mod tests {
    use super::super::one_root::EndValues;
    use super::super::query::Query;
    use super::super::span_search::ExactReport;
    use super::*;
    use crate::{BSpline, Curve, Tolerance};
    use nalgebra::{Point2, Point3, Vector3};

    use crate::test_unit::unit;

    /// A clamped cubic B-spline profile of `count` points at size `scale`:
    /// radii in `[0, scale]` (the ends on the axis), heights rising with
    /// random steps, some of them backwards (overhangs).
    fn profile(state: &mut u64, count: usize, scale: f64) -> BSpline<2> {
        let mut y = -scale;
        let points = (0..count)
            .map(|i| {
                let x = if i == 0 || i + 1 == count {
                    0.0
                } else {
                    scale * (0.1 + 0.9 * unit(state))
                };
                y += scale * (0.3 * unit(state) - 0.08);
                Point2::new(x, y)
            })
            .collect();
        BSpline::clamped(3, points).expect("valid profile")
    }

    /// The table of `curve`, and the same table with no span certified
    /// monotonic (every span then takes the full solve).
    fn tables(curve: &BSpline<2>) -> (SpanTable, SpanTable) {
        let spans = curve.rational_bezier_spans().expect("spans");
        let table = SpanTable::new(&spans).expect("one degree");
        let mut full = table.clone();
        if let Some(cells) = &mut full.cells {
            cells.forget_monotone();
        }
        (table, full)
    }

    /// Spans decided by the monotonicity table and their end values
    /// (exactly one root, found by Newton on the hit function) give the
    /// same hits as the full solve (the polynomial, its certified root
    /// isolation and refinement): same t, parameter and point to rounding,
    /// and the same misses. Rays through the profile's box from all
    /// directions, at three scales; the table must decide a good share of
    /// the spans solved, or the comparison would be vacuous.
    #[test]
    fn one_root_spans_agree_with_the_full_solve() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let (mut decided, mut hits) = (0, 0);
        for (case, scale) in [1e-3, 1.0, 1e3].into_iter().cycle().take(12).enumerate() {
            let curve = profile(&mut state, 8 + case * 2, scale);
            let (table, full) = tables(&curve);
            let tol = Tolerance::default();
            for _ in 0..4000 {
                let pick = |state: &mut u64| {
                    Vector3::new(
                        (2.0 * unit(state) - 1.0) * scale,
                        (3.0 * unit(state) - 1.5) * scale,
                        (2.0 * unit(state) - 1.0) * scale,
                    )
                };
                let target = pick(&mut state);
                let o = pick(&mut state) * 4.0;
                let d = target - o;
                let o = Point3::from(o);
                let (mut report, mut report_full) =
                    (ExactReport::default(), ExactReport::default());
                let got = table.intersect::<false>(o, d, 0.0, f64::INFINITY, &tol, &mut report);
                let want =
                    full.intersect::<false>(o, d, 0.0, f64::INFINITY, &tol, &mut report_full);
                if report != report_full {
                    decided += 1;
                }
                match (got, want) {
                    (None, None) => {}
                    (Some(a), Some(b)) => {
                        hits += 1;
                        let size = scale + o.coords.amax();
                        assert!(
                            (a.t - b.t).abs() * d.norm() <= 1e-12 * size,
                            "t {} against {} (o {o:?}, d {d:?})",
                            a.t,
                            b.t
                        );
                        assert!((a.point - b.point).norm() <= 1e-12 * size);
                        assert!((a.u - b.u).abs() <= 1e-9 * (1.0 + b.u.abs()));
                    }
                    (a, b) => panic!("one-root path {a:?}, full solve {b:?}: o {o:?}, d {d:?}"),
                }
            }
        }
        assert!(hits > 10_000, "only {hits} hits");
        assert!(
            decided > 5_000,
            "the table decided spans on only {decided} rays"
        );
    }

    /// The hit function at control points is within [`EndValues`]' bound
    /// of its value in double-double arithmetic, for random rays and
    /// points, origins up to 1e6 away and rays aimed at the point itself
    /// (where `A² + B²` and `(d_y x)²` cancel); and the bound is not
    /// vacuous (a worst case, but no more than a thousand times the worst
    /// error seen).
    #[test]
    fn end_values_are_within_their_rounding_bound() {
        use super::super::double_double::Dd;
        let mut state = 0x5851_f42d_4c95_7f2d_u64;
        let mut worst = 0.0_f64;
        let curve = profile(&mut state, 10, 1.0);
        let spans = curve.rational_bezier_spans().expect("spans");
        let table = SpanTable::new(&spans).expect("one degree");
        for case in 0..20_000 {
            let k = case % table.spans.len();
            let point = table.end_points(k)[case / 7 % 2];
            let far = [1.0, 1e3, 1e6][case % 3];
            let pick = |state: &mut u64| 2.0 * unit(state) - 1.0;
            let o = Vector3::new(pick(&mut state), pick(&mut state), pick(&mut state)) * far;
            let d = if case % 2 == 0 {
                // At the point's circle, at a random angle.
                let angle = 6.0 * unit(&mut state);
                Vector3::new(point.0 * angle.cos(), point.1, point.0 * angle.sin()) - o
            } else {
                Vector3::new(pick(&mut state), pick(&mut state), pick(&mut state))
            };
            if d.y == 0.0 {
                continue;
            }
            let q = Query::new(o, d, &Tolerance::default(), table.scale);
            let ends = EndValues::new(&q, &table);
            let got = ends.value(point);
            let dd = Dd::from;
            let h = dd(point.1).add(dd(-o.y));
            let a = dd(o.x).mul(dd(d.y)).add(h.mul(dd(d.x)));
            let b = dd(o.z).mul(dd(d.y)).add(h.mul(dd(d.z)));
            let c = dd(d.y).mul(dd(point.0));
            let exact = a.mul(a).add(b.mul(b)).add(c.mul(c).neg());
            let off = ((got - exact.0) - exact.1).abs();
            assert!(
                off <= ends.err,
                "f = {got} is {off:e} off {}, bound {:e}",
                exact.value(),
                ends.err
            );
            worst = worst.max(off / ends.err);
        }
        assert!(worst > 1e-3, "largest error only {worst:e} of the bound");
    }

    /// A rational quarter circle (weights 1, √½, 1) turned about the axis
    /// is the upper unit hemisphere: the exact intersector's hits agree with
    /// the ray–sphere quadratic (its roots with `y ≥ 0`), to 1e-12, with
    /// the same misses, for rays from all directions at three scales, and
    /// perpendicular rays (`d_y = 0`) too.
    #[test]
    fn rational_hemisphere_matches_the_sphere_quadratic() {
        use crate::RationalBezier;
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut hits = 0;
        for scale in [1e-3, 1.0, 1e3] {
            let quarter = RationalBezier::new(
                vec![
                    Point2::new(scale, 0.0),
                    Point2::new(scale, scale),
                    Point2::new(0.0, scale),
                ],
                vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
            )
            .expect("valid arc");
            let spans = quarter.rational_bezier_spans().expect("spans");
            let table = SpanTable::new(&spans).expect("spans");
            let tol = Tolerance::default();
            for case in 0..20_000 {
                let pick = |state: &mut u64| {
                    Vector3::new(
                        (2.4 * unit(state) - 1.2) * scale,
                        (1.4 * unit(state) - 0.2) * scale,
                        (2.4 * unit(state) - 1.2) * scale,
                    )
                };
                let target = pick(&mut state);
                let mut o = pick(&mut state) * 3.0;
                if case % 10 == 0 {
                    o.y = target.y;
                }
                let d = target - o;
                let o = Point3::from(o);
                // Reference: |o + t d|² = r², roots with y ≥ 0, nearest > 0.
                let (a, b, c) = (
                    d.norm_squared(),
                    o.coords.dot(&d),
                    o.coords.norm_squared() - scale * scale,
                );
                let disc = b * b - a * c;
                let mut want = None;
                if disc >= 0.0 {
                    let q = -(b + b.signum() * disc.sqrt());
                    let mut roots = [q / a, c / q];
                    roots.sort_by(f64::total_cmp);
                    want = roots
                        .into_iter()
                        .find(|&t| t > 0.0 && (o.y + t * d.y) >= 0.0);
                }
                // Skip rays whose reference hit is within rounding of the
                // rim (y = 0) or of tangency: either answer is right there.
                let near_rim = want.is_some_and(|t| (o.y + t * d.y).abs() < 1e-9 * scale)
                    || disc.abs() < 1e-9 * a * scale * scale;
                if near_rim {
                    continue;
                }
                let got = table.intersect::<false>(
                    o,
                    d,
                    0.0,
                    f64::INFINITY,
                    &tol,
                    &mut ExactReport::default(),
                );
                match (got, want) {
                    (None, None) => {}
                    (Some(g), Some(t)) => {
                        hits += 1;
                        assert!(
                            (g.t - t).abs() * d.norm() <= 1e-12 * scale * 10.0,
                            "t {} against {t} (o {o:?}, d {d:?})",
                            g.t
                        );
                        let p = o + d * g.t;
                        assert!((p.coords.norm() - scale).abs() <= 1e-12 * scale * 10.0);
                    }
                    (g, t) => panic!("got {g:?}, want {t:?}: o {o:?}, d {d:?}"),
                }
            }
        }
        assert!(hits > 20_000, "only {hits} hits");
    }
}
