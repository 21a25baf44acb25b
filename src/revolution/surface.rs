//! Surfaces of revolution: a planar profile turned about an axis.

use super::profile_approximation::approximate;
use super::profile_refine::refine_on_profile;
use super::query::LocalHit;
use super::span_search::ExactReport;
use super::span_table::SpanTable;
use crate::curve::RationalBezierSpan;
use crate::ray::acceptance::Acceptance;
use crate::{Aabb, Curve, Error, Hit, Intersect, Ray, Surface, Tolerance};
use nalgebra::{
    Isometry3, Point3, Rotation3, Translation3, Unit, UnitQuaternion, Vector2, Vector3,
};
use std::f64::consts::TAU;

/// The surface swept by a profile curve `(x(u), y(u))` turning about an axis.
///
/// In its local frame the axis is the `y` axis and
///
/// `S(u, θ) = (x(u) cos θ, y(u), −x(u) sin θ)`, `u` in the profile's domain,
/// `θ ∈ [0, 2π]`.
///
/// Partial derivatives are analytic: `∂S/∂u = (x′ cos θ, y′, −x′ sin θ)` and
/// `∂S/∂θ = (−x sin θ, 0, −x cos θ)`. Their cross product is
/// `x·(−y′ cos θ, x′, y′ sin θ)`, so the unit normal (orientation of the
/// parametrization, `∂S/∂u × ∂S/∂θ`) is `sign(x)·(−y′ cos θ, x′, y′ sin θ)`
/// with `(x′, y′)` the profile's unit tangent. For a profile traced upward
/// (increasing `y`) it points toward the axis, on either side of it (negative
/// `x`, as course scene files write profiles, gives the same surface and
/// orientation as positive `x`).
///
/// # Edge rules: the axis
/// Where the profile meets the axis (`x = 0`) the cross product vanishes. The
/// normal there is the limit from the profile's neighbourhood: the profile's
/// tangent comes from its first non-vanishing derivative (so repeated control
/// points on the axis work), and `sign(x)` from the side the profile leaves
/// the axis to. If the profile meets the axis perpendicularly (a pole, as at
/// the bottom of a vase) the normal is `±` the axis; if it meets it at an angle
/// (a cone's apex) there is no tangent plane and the normal is `None`.
///
/// A NaN or infinite angle evaluates at `θ = 0`.
///
/// A revolution can be placed anywhere with [`with_axis`](Self::with_axis).
///
/// # Which profiles, and what ray intersection guarantees
/// - **Profiles with [Bézier spans](Curve::bezier_spans) or
///   [rational Bézier spans](Curve::rational_bezier_spans)** ([`Bezier`],
///   [`BSpline`], [`RationalBezier`], [`Nurbs`], or your own type that
///   provides them; spans of different degrees are raised to the highest):
///   the exact intersector. Certified: every transversal hit is found, no
///   false hit is reported, the nearest in `(t_min, t_max)` to the
///   [`Tolerance`]. A rational profile makes exact spheres (a half circle
///   about the axis), tori (an off-axis circle) and lathed parts; its hit
///   condition is multiplied by `W²` and stays one polynomial of degree `2n`
///   per span.
/// - **Any other [`Curve<2>`]** (your own type with the three required
///   methods): at construction the profile is replaced by its piecewise
///   cubic Hermite approximation (points and derivatives matched at the
///   breakpoints, pieces halved until the approximation is within `1e-7` of
///   the profile's size at test points; at most 4096 pieces). A ray is
///   intersected exactly with the approximation's surface and each hit,
///   nearest first, is refined by Newton's method on your profile and kept
///   only if it lands on it (to the same residual as the exact intersector).
///   Every hit of a ray that crosses the surface at an angle is found; a
///   ray that grazes a silhouette within the approximation's deviation
///   ([`approximation_deviation`](Self::approximation_deviation)) may be
///   found or not. The profile should be `C¹` (a kink costs many pieces; a
///   jump is refused). `bounds()` is that of the approximation widened by
///   twice its deviation. Nothing known only through samples can be
///   certified: for a guarantee, give the profile Bézier spans.
/// - **A profile that breaks the [`Curve`] contract**: no hits, empty
///   bounds ([`Revolution::try_new`] says why).
///
/// Coordinates up to [`MAX_COORDINATE`](crate::MAX_COORDINATE) work at any
/// scale: the intersector rescales the profile by a power of two, takes the
/// ray direction at unit length whatever its `|dir|`, and moves far ray
/// origins along their line first.
///
/// [`Bezier`]: crate::Bezier
/// [`BSpline`]: crate::BSpline
/// [`RationalBezier`]: crate::RationalBezier
/// [`Nurbs`]: crate::Nurbs
#[derive(Debug, Clone, PartialEq)]
pub struct Revolution<C> {
    profile: C,
    /// Local frame → world: rotation taking the local `y` axis to the axis,
    /// then translation to the axis origin.
    to_world: Isometry3<f64>,
    /// `to_world`'s rotation as a matrix: rays and hits are turned with it
    /// (9 products a vector, against about twice that for the quaternion).
    rotation: Rotation3<f64>,
    /// The exact intersector's per-surface data: of the profile's Bézier
    /// spans, or of its cubic approximation (`approximation`). `None` when
    /// the profile breaks the [`Curve`] contract (`broken` says how).
    exact: Option<SpanTable>,
    /// For a profile without Bézier spans: the largest deviation of the
    /// approximation that `exact` was built from, measured at its test
    /// points.
    approximation: Option<f64>,
    /// Why the profile breaks the [`Curve`] contract, if it does.
    broken: Option<Error>,
    tolerance: Tolerance,
    /// The axis of the last successful placement as [`placement`] scales it
    /// before normalizing (largest component ±1; `y` before any placement):
    /// the placement's defining data, which serialization writes so that a
    /// round trip rebuilds `to_world` bit for bit (the axis read back from
    /// the rotation, or the unit axis normalized again, may differ by an
    /// ulp; this one scales by exactly 1 again).
    scaled_axis: Vector3<f64>,
}

/// How many hits of a profile's approximation are tried, nearest first,
/// before a ray is called a miss (each that does not refine onto the
/// profile, as near a silhouette, moves the search past it).
const REFINE_TRIES: usize = 8;

/// The intersector's data for `profile`, and the deviation of the
/// approximation it was built from if the profile has no Bézier spans;
/// an error if the profile breaks the [`Curve`] contract.
fn intersector_data<C: Curve<2>>(profile: &C) -> Result<(SpanTable, Option<f64>), Error> {
    let (a, b) = profile.domain();
    let limit = crate::MAX_COORDINATE;
    if !(a < b && a.abs() <= limit && b.abs() <= limit) {
        return Err(Error::InvalidDomain { start: a, end: b });
    }
    // The points the surface's own evaluation will show.
    const CHECKS: usize = 16;
    for k in 0..=CHECKS {
        let t = if k == CHECKS {
            b
        } else {
            a + (b - a) * (k as f64 / CHECKS as f64)
        };
        let (p, d) = profile.eval_with_derivative(t);
        if !p.coords.iter().chain(d.iter()).all(|v| v.is_finite()) || p.coords.amax() > limit {
            return Err(Error::CurveNotFinite { t });
        }
    }
    match profile.rational_bezier_spans() {
        Some(spans) => {
            check_spans(&spans)?;
            let table = SpanTable::new(&spans).ok_or(Error::SpansOutOfOrder { index: 0 })?;
            Ok((table, None))
        }
        None => {
            let approx = approximate(profile, (a, b))?;
            let spans: Vec<RationalBezierSpan<2>> = approx
                .spans
                .into_iter()
                .map(RationalBezierSpan::from)
                .collect();
            let table = SpanTable::new(&spans).ok_or(Error::ProfileTooRough { pieces: 0 })?;
            Ok((table, Some(approx.deviation)))
        }
    }
}

/// Checks what [`Curve::rational_bezier_spans`] promises: at least one span, each
/// on a non-empty interval within [`MAX_COORDINATE`](crate::MAX_COORDINATE)
/// that starts where the previous one ends or later, with finite control
/// points within
/// [`MAX_COORDINATE`](crate::MAX_COORDINATE) (and its rounding).
fn check_spans(spans: &[RationalBezierSpan<2>]) -> Result<(), Error> {
    if spans.is_empty() {
        return Err(Error::SpansOutOfOrder { index: 0 });
    }
    let limit = crate::MAX_COORDINATE * (1.0 + 1e-9);
    let mut end = f64::NEG_INFINITY;
    for (index, span) in spans.iter().enumerate() {
        let (a, b) = span.knots;
        let knots_ok = a.abs() <= crate::MAX_COORDINATE && b.abs() <= crate::MAX_COORDINATE;
        if !(a < b && a >= end && knots_ok) {
            return Err(Error::SpansOutOfOrder { index });
        }
        end = b;
        let finite = span
            .curve
            .points()
            .iter()
            .all(|p| p.coords.iter().all(|v| v.abs() <= limit));
        if !finite {
            return Err(Error::SpanPointNotFinite { span: index });
        }
    }
    Ok(())
}

impl<C: Curve<2>> Revolution<C> {
    /// The surface of `profile` turned about the `y` axis through the origin.
    ///
    /// The intersector's data is computed here, once: from the profile's
    /// [Bézier spans](Curve::bezier_spans) if it has them (as
    /// [`Bezier`](crate::Bezier) and [`BSpline`](crate::BSpline) do), else
    /// from its cubic approximation (see the type's docs).
    ///
    /// Never panics. A profile that breaks the [`Curve`] contract (a domain
    /// that is not a finite interval, NaN or infinite values, Bézier spans
    /// empty or out of order, a curve too rough to approximate) gives a
    /// surface that rays do not hit and whose [`bounds`](Intersect::bounds)
    /// are [`Aabb::EMPTY`]; [`try_new`](Self::try_new) reports why, and so
    /// does [`contract_error`](Self::contract_error).
    pub fn new(profile: C) -> Self {
        let (exact, approximation, broken) = match intersector_data(&profile) {
            Ok((table, approximation)) => (Some(table), approximation, None),
            Err(e) => (None, None, Some(e)),
        };
        Revolution {
            profile,
            to_world: Isometry3::identity(),
            rotation: Rotation3::identity(),
            exact,
            approximation,
            broken,
            tolerance: Tolerance::default(),
            scaled_axis: Vector3::y(),
        }
    }

    /// As [`new`](Self::new), but a profile that breaks the [`Curve`]
    /// contract is an error.
    ///
    /// # Errors
    /// [`Error::InvalidDomain`] (not a finite interval `a < b` within
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE)); [`Error::CurveNotFinite`]
    /// (a NaN, infinite or too large point or derivative inside the
    /// domain); [`Error::SpansOutOfOrder`] or [`Error::SpanPointNotFinite`]
    /// (Bézier spans that break their promise); [`Error::ProfileTooRough`]
    /// (a profile without spans that cubic pieces cannot follow: a jump, or
    /// a kink away from where the pieces meet).
    ///
    /// ```
    /// use revolve::{Curve, Error, Revolution};
    /// use revolve::nalgebra::{Point2, Vector2};
    ///
    /// struct Backwards;
    /// impl Curve<2> for Backwards {
    ///     fn domain(&self) -> (f64, f64) { (1.0, 0.0) }
    ///     fn eval(&self, t: f64) -> Point2<f64> { Point2::new(1.0, t) }
    ///     fn derivative(&self, _: f64) -> Vector2<f64> { Vector2::new(0.0, 1.0) }
    /// }
    /// assert!(matches!(Revolution::try_new(Backwards), Err(Error::InvalidDomain { .. })));
    /// ```
    pub fn try_new(profile: C) -> Result<Self, Error> {
        let surface = Self::new(profile);
        match surface.broken {
            Some(e) => Err(e),
            None => Ok(surface),
        }
    }

    /// Why the profile breaks the [`Curve`] contract, if it does (the
    /// surface is then empty to rays).
    pub fn contract_error(&self) -> Option<&Error> {
        self.broken.as_ref()
    }

    /// The same surface with the given intersection accuracy (the default is
    /// full double precision), [clamped](Tolerance::clamped) into the valid
    /// range.
    pub fn with_tolerance(mut self, tolerance: Tolerance) -> Self {
        self.tolerance = tolerance.clamped();
        self
    }

    /// As [`Intersect::intersect`], with a report of how the exact
    /// intersector finished (spans entered and solved, roots, candidates,
    /// Newton iterations, the hit's residual). The fast path
    /// (`Intersect::intersect`) computes the same hit.
    pub fn intersect_with_report(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
    ) -> (Option<Hit>, ExactReport) {
        let mut report = ExactReport::default();
        let hit = self.intersect_reporting(ray, t_min, t_max, &mut report);
        if hit.is_none() {
            report.residual = None;
        }
        (hit, report)
    }

    fn intersect_reporting(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        report: &mut ExactReport,
    ) -> Option<Hit> {
        let exact = self.exact.as_ref()?;
        let origin = &self.to_world.translation.vector;
        let o = Point3::from(
            self.rotation
                .inverse_transform_vector(&(ray.origin.coords - origin)),
        );
        let d = self.rotation.inverse_transform_vector(&ray.dir);
        let local = match self.approximation {
            None => exact.intersect(o, d, t_min, t_max, &self.tolerance, report)?,
            Some(_) => self.refined_hit(exact, o, d, t_min, t_max, report)?,
        };
        report.residual = Some(local.residual);
        let at_end = local.u >= self.profile.domain().1;
        let finite = |n: &Unit<Vector3<f64>>| n.iter().all(|c| c.is_finite());
        let normal_local = match local.tangent {
            Some(t) => profile_normal(local.x, t, at_end, local.sin_cos),
            None => self.normal_local(local.u, local.theta),
        }
        .filter(finite)
        // No tangent plane (a cone's apex): face the ray.
        .or_else(|| Unit::try_new(-d / d.amax(), 0.0))?;
        let point = Point3::from(self.rotation * local.point.coords + origin);
        if !point.coords.iter().all(|c| c.is_finite()) {
            return None;
        }
        Some(Hit {
            t: local.t,
            point,
            normal: Unit::new_unchecked(self.rotation * normal_local.into_inner()),
            uv: (local.u, local.theta),
        })
    }

    /// The nearest hit for a profile without Bézier spans: the hits of its
    /// approximation, nearest first, refined by Newton's method on the
    /// profile itself; one that does not refine (a ray grazing the
    /// approximation where the profile is missed) moves the search past it.
    fn refined_hit(
        &self,
        table: &SpanTable,
        o: Point3<f64>,
        d: Vector3<f64>,
        t_min: f64,
        t_max: f64,
        report: &mut ExactReport,
    ) -> Option<LocalHit> {
        let (r_max, y_range) = table.local_bounds();
        let scale = r_max.max(y_range.0.abs()).max(y_range.1.abs());
        // As in the exact intersector, a hit within the position
        // uncertainty of the origin is the origin itself (a secondary ray
        // leaving the surface): the floor is `accept/|d|` past `t_min`.
        let m = d.amax();
        let dn = m * (d / m).norm();
        let t_floor = Acceptance::certified(&self.tolerance, scale, &o.coords).t_floor(t_min, dn);
        let mut from = t_min;
        for _ in 0..REFINE_TRIES {
            let guess = table.intersect(o, d, from, t_max, &self.tolerance, report)?;
            let refined = refine_on_profile(
                &self.profile,
                self.profile.domain(),
                &o.coords,
                &d,
                (guess.u, guess.t),
                scale,
                &self.tolerance,
                &mut report.iterations,
            );
            if let Some(hit) = refined.filter(|h| h.t > t_floor && h.t < t_max) {
                return Some(hit);
            }
            from = guess.t;
        }
        None
    }

    /// Whether [`Intersect`] runs the exact intersector on the profile's own
    /// Bézier spans (certified: no hit missed, none false). `false` for a
    /// profile without spans (its hits come from an approximation refined
    /// on the profile, see the type's docs) and for one that breaks the
    /// [`Curve`] contract.
    pub fn has_exact_intersector(&self) -> bool {
        self.exact.is_some() && self.approximation.is_none()
    }

    /// For a profile without Bézier spans: the largest deviation of its
    /// cubic approximation from the profile, measured at the approximation's
    /// test points (`None` for profiles with spans, and broken ones).
    pub fn approximation_deviation(&self) -> Option<f64> {
        self.approximation
    }

    /// The bytes this surface holds on the heap beyond its profile: the
    /// exact intersector's tables (the spans with their ranges and Bézier
    /// coefficients, the culling groups, and the line-class cells, whose
    /// size is proportional to the number of spans). 0 without an exact
    /// intersector. The profile curve is stored by value; its own heap
    /// storage (control points, knots) is not counted, as [`Curve`] does
    /// not report it.
    pub fn heap_bytes(&self) -> usize {
        self.exact.as_ref().map_or(0, SpanTable::heap_bytes)
    }

    /// The intersection accuracy.
    pub fn tolerance(&self) -> &Tolerance {
        &self.tolerance
    }

    /// The same surface placed so that its axis passes through `origin` along
    /// `axis` (the local `y` axis maps to `axis`, the local origin to
    /// `origin`). The rotation is the shortest one taking `y` to `axis`; for
    /// `axis = −y` it is the half turn about `x`.
    ///
    /// Never panics. An `origin` with a NaN or infinite coordinate, or one
    /// beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE), or an `axis` that is
    /// not a finite non-zero vector, is not applied: the surface stays where
    /// it was, becomes empty to rays (no hits, empty bounds), and
    /// [`contract_error`](Self::contract_error) says why;
    /// [`try_with_axis`](Self::try_with_axis) returns the error instead.
    pub fn with_axis(mut self, origin: Point3<f64>, axis: Unit<Vector3<f64>>) -> Self {
        match placement(origin, axis) {
            Ok(unit) => self.place(origin, unit, axis),
            Err(e) => {
                self.exact = None;
                self.broken = Some(e);
                self
            }
        }
    }

    /// As [`with_axis`](Self::with_axis), but a bad placement is an error.
    ///
    /// # Errors
    /// [`Error::InvalidPlacement`] for an origin that is not finite or
    /// beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE), or an axis that is
    /// not a finite non-zero vector.
    pub fn try_with_axis(
        self,
        origin: Point3<f64>,
        axis: Unit<Vector3<f64>>,
    ) -> Result<Self, Error> {
        let unit = placement(origin, axis)?;
        Ok(self.place(origin, unit, axis))
    }

    /// Places the surface (`origin` and `given` checked by [`placement`],
    /// which made the unit `axis` of `given`).
    fn place(
        mut self,
        origin: Point3<f64>,
        axis: Unit<Vector3<f64>>,
        given: Unit<Vector3<f64>>,
    ) -> Self {
        // The angle from atan2(|y × a|, y · a), accurate near 0 and π (acos
        // of the dot product loses half the digits there).
        let y = Vector3::y();
        let cross = y.cross(&axis);
        let angle = cross.norm().atan2(y.dot(&axis));
        // Scaled before normalizing: an axis within 1e-154 of ±y has a
        // cross product whose squares are subnormal (a norm off by 1e-10).
        let m = cross.amax();
        let about = (m > 0.0).then(|| Unit::try_new(cross / m, 0.0)).flatten();
        let rotation = match about {
            Some(about) => Rotation3::from_axis_angle(&about, angle),
            None if angle > 1.0 => {
                Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
            }
            None => Rotation3::identity(),
        };
        self.to_world = Isometry3::from_parts(
            Translation3::from(origin.coords),
            UnitQuaternion::from_rotation_matrix(&rotation),
        );
        self.rotation = self.to_world.rotation.to_rotation_matrix();
        self.scaled_axis = given.into_inner() / given.amax();
        self
    }

    /// The axis of the last placement, scaled to largest component ±1 (`y`
    /// if never placed): placing a surface along it rebuilds the same
    /// rotation bit for bit.
    #[cfg(feature = "serde")]
    pub(crate) fn scaled_axis(&self) -> &Vector3<f64> {
        &self.scaled_axis
    }

    /// The profile curve.
    pub fn profile(&self) -> &C {
        &self.profile
    }

    /// The rigid motion from the local frame (axis = `y`) to the world.
    pub fn to_world(&self) -> &Isometry3<f64> {
        &self.to_world
    }

    /// The point in the local frame.
    #[inline]
    pub fn eval_local(&self, u: f64, theta: f64) -> Point3<f64> {
        let p = self.profile.eval(u);
        let (s, c) = finite_angle(theta).sin_cos();
        Point3::new(p.x * c, p.y, -p.x * s)
    }

    /// The partials `(∂S/∂u, ∂S/∂θ)` in the local frame.
    #[inline]
    pub fn partials_local(&self, u: f64, theta: f64) -> (Vector3<f64>, Vector3<f64>) {
        let (p, d) = self.profile.eval_with_derivative(u);
        let (s, c) = finite_angle(theta).sin_cos();
        (
            Vector3::new(d.x * c, d.y, -d.x * s),
            Vector3::new(-p.x * s, 0.0, -p.x * c),
        )
    }

    /// The unit normal in the local frame (see the type's edge rules).
    pub fn normal_local(&self, u: f64, theta: f64) -> Option<Unit<Vector3<f64>>> {
        let x = self.profile.eval(u).x;
        let at_end = u >= self.profile.domain().1;
        profile_normal(
            x,
            self.profile.tangent(u)?,
            at_end,
            finite_angle(theta).sin_cos(),
        )
    }
}

/// The axis of a placement, renormalized (a `Unit` made unchecked may not
/// be of unit length), if `origin` and `axis` are acceptable (see
/// [`Revolution::with_axis`]).
fn placement(origin: Point3<f64>, axis: Unit<Vector3<f64>>) -> Result<Unit<Vector3<f64>>, Error> {
    let limit = crate::MAX_COORDINATE;
    let origin_ok = origin.coords.iter().all(|c| c.abs() <= limit);
    let axis = axis.into_inner();
    let m = axis.amax();
    let unit = (m > 0.0 && m.is_finite())
        .then(|| Unit::try_new(axis / m, 0.0))
        .flatten();
    match unit {
        Some(unit) if origin_ok => Ok(unit),
        _ => Err(Error::InvalidPlacement { origin, axis }),
    }
}

/// The angle itself, or 0 for a NaN or infinite one (whose sine and cosine
/// would be NaN): see [`Revolution`]'s edge rules.
#[inline(always)]
fn finite_angle(theta: f64) -> f64 {
    if theta.is_finite() { theta } else { 0.0 }
}

/// The local unit normal at the angle `θ`, given as `(sin θ, cos θ)`, of the
/// profile point with radius coordinate `x` and unit tangent `tangent` (see
/// [`Revolution`]'s edge rules); `at_end` says the point is where the profile
/// ends, so that on the axis the profile arrives rather than leaves.
pub(crate) fn profile_normal(
    x: f64,
    tangent: Unit<Vector2<f64>>,
    at_end: bool,
    (s, c): (f64, f64),
) -> Option<Unit<Vector3<f64>>> {
    let (dx, dy) = (tangent.x, tangent.y);
    let side = if x != 0.0 {
        x.signum()
    } else {
        // On the axis. A tangent plane exists only if the profile meets the
        // axis perpendicularly (to within √ε: a steeper "cone" is a disk to
        // double precision).
        if dy.abs() > f64::EPSILON.sqrt() {
            return None;
        }
        // The profile leaves the axis toward sign(x′), and arrives from
        // −sign(x′) at its end.
        if at_end { -dx.signum() } else { dx.signum() }
    };
    Unit::try_new(Vector3::new(-dy * c, dx, dy * s) * side, 0.0)
}

impl<C: Curve<2>> Surface for Revolution<C> {
    fn domain(&self) -> [(f64, f64); 2] {
        [self.profile.domain(), (0.0, TAU)]
    }

    fn eval(&self, u: f64, v: f64) -> Point3<f64> {
        self.to_world * self.eval_local(u, v)
    }

    fn partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>) {
        let (su, sv) = self.partials_local(u, v);
        (self.to_world * su, self.to_world * sv)
    }

    fn normal(&self, u: f64, v: f64) -> Option<Unit<Vector3<f64>>> {
        self.normal_local(u, v)
            .map(|n| Unit::new_unchecked(self.to_world.rotation * n.into_inner()))
    }
}

impl<C: Curve<2>> Intersect for Revolution<C> {
    /// The nearest hit with `t_min < t < t_max`, or `None`: the exact
    /// intersector for profiles with Bézier spans, the refined
    /// approximation for others (see [`Revolution`]'s docs for what each
    /// guarantees; [`Revolution::has_exact_intersector`] tells which
    /// applies). `t_min` or `t_max` NaN, or `t_min ≥ t_max`, is a miss; so
    /// is a zero, NaN or infinite direction.
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        self.intersect_reporting(ray, t_min, t_max, &mut ExactReport::default())
    }

    fn bounds(&self) -> Aabb {
        match &self.exact {
            // The cylinder around the profile's radius and height ranges
            // (of its approximation, widened by twice its deviation).
            Some(e) => {
                let (r, (y0, y1)) = e.local_bounds();
                let pad = 2.0 * self.approximation.unwrap_or(0.0);
                Aabb::new(
                    Point3::new(-r - pad, y0 - pad, -r - pad),
                    Point3::new(r + pad, y1 + pad, r + pad),
                )
                .transformed(&self.to_world)
            }
            None => Aabb::EMPTY,
        }
    }
}

/// Conservative patch bounds (for the generic Newton intersector).
///
/// The box of `S([u₀, u₁] × [θ₀, θ₁])` is built in three exact-or-outward
/// steps:
///
/// 1. **Profile ranges.** With [Bézier spans](Curve::bezier_spans) (as
///    [`Bezier`](crate::Bezier) and [`BSpline`](crate::BSpline) give), every
///    span overlapping `[u₀, u₁]` is cut to the overlap by two de Casteljau
///    subdivisions and the ranges of `x` and `y` are those of the cut
///    control points: by the convex hull property (Farin, *Curves and
///    Surfaces for CAGD*, §4.2) they contain the profile. Profiles without
///    spans are sampled at 33 points with their derivatives and the ranges
///    widened by `h·M` (`h` the sample spacing, `M` the largest sampled
///    speed `|P′|`): every point lies within `h/2·sup|P′|` of a sample, so
///    this is conservative whenever the speed on the patch is at most twice
///    its largest sampled value. No bound from samples can be unconditional
///    for an arbitrary curve; give the profile Bézier spans for a guarantee.
/// 2. **Annular sectors.** A profile point `(x, y)` at angle `θ` is
///    `(x cos θ, y, −x sin θ)`; negative `x` is `|x|` at `θ + π`. So the
///    patch lies in the union of the sector `r ∈ [max(x_min, 0), x_max]`,
///    `θ ∈ [θ₀, θ₁]` (when `x_max ≥ 0`) and the sector
///    `r ∈ [max(−x_max, 0), −x_min]`, `θ ∈ [θ₀ + π, θ₁ + π]` (when
///    `x_min < 0`). The box of a sector is exact: `r cos θ` over
///    `[r₀, r₁] × [θ₀, θ₁]` ranges over the products of the ends of
///    `[r₀, r₁]` and of the range of `cos θ`, which is the range at the ends
///    widened to `±1` where the interval contains a multiple of `π` (and
///    likewise `−r sin θ` with the odd multiples of `π/2`).
/// 3. **World frame.** The local box is moved by the rigid motion
///    [`to_world`](Revolution::to_world) by interval arithmetic
///    ([`Aabb::transformed`]: exactly the box of the rotated box). Finally the box grows by `16(n + 2)·ε` times the local
///    plus world coordinate magnitudes (`n` the profile degree), which covers
///    the rounding of subdivision, of the transform and of
///    [`eval`](Surface::eval).
impl<C: Curve<2>> crate::surface::PatchBounds for Revolution<C> {
    fn bound_patch(&self, u: (f64, f64), v: (f64, f64)) -> Aabb {
        let (u0, u1) = (u.0.min(u.1), u.0.max(u.1));
        let (v0, v1) = (v.0.min(v.1), v.0.max(v.1));
        let (xr, yr, degree) = profile_ranges(&self.profile, u0, u1);
        if !(xr.0 <= xr.1 && yr.0 <= yr.1) {
            return Aabb::EMPTY;
        }
        // Local x and z ranges of the sector(s).
        let mut xz = (
            (f64::INFINITY, f64::NEG_INFINITY),
            (f64::INFINITY, f64::NEG_INFINITY),
        );
        let mut add = |(a, b): ((f64, f64), (f64, f64))| {
            xz.0 = (xz.0.0.min(a.0), xz.0.1.max(a.1));
            xz.1 = (xz.1.0.min(b.0), xz.1.1.max(b.1));
        };
        if xr.1 >= 0.0 {
            add(sector_box((xr.0.max(0.0), xr.1), (v0, v1)));
        }
        if xr.0 < 0.0 {
            let pi = std::f64::consts::PI;
            add(sector_box(((-xr.1).max(0.0), -xr.0), (v0 + pi, v1 + pi)));
        }
        let local = Aabb {
            min: Point3::new(xz.0.0, yr.0, xz.1.0),
            max: Point3::new(xz.0.1, yr.1, xz.1.1),
        };
        let world = local.transformed(&self.to_world);
        let world_mag = world.center().coords.amax() + (world.extent() * 0.5).amax();
        let pad = 16.0 * (degree as f64 + 2.0) * f64::EPSILON * (local.scale() + world_mag);
        world.expand(pad)
    }

    /// The angle `θ` is periodic (period `2π`); the profile parameter is not.
    fn periodic(&self) -> [bool; 2] {
        [false, true]
    }
}

/// Conservative ranges of the profile's `x` and `y` over `[u0, u1]`, and the
/// profile degree used for the rounding pad (see the `PatchBounds` impl).
fn profile_ranges<C: Curve<2>>(profile: &C, u0: f64, u1: f64) -> ((f64, f64), (f64, f64), usize) {
    let empty = (f64::INFINITY, f64::NEG_INFINITY);
    let widen = |r: (f64, f64), x: f64| (r.0.min(x), r.1.max(x));
    let (mut xr, mut yr) = (empty, empty);
    if let Some(spans) = profile.rational_bezier_spans() {
        let mut degree = 0;
        for span in &spans {
            let (a, b) = span.knots;
            if b < u0 || a > u1 || b <= a {
                continue;
            }
            let curve = &span.curve;
            degree = degree.max(curve.degree());
            let s0 = ((u0 - a) / (b - a)).clamp(0.0, 1.0);
            let s1 = ((u1 - a) / (b - a)).clamp(0.0, 1.0);
            // A rational piece is cut in homogeneous coordinates (wx, wy, w);
            // the cut control points (divided back) bound it as well.
            let pts = curve.points().iter().zip(curve.weights());
            let cut = if curve.is_polynomial() {
                cut_piece(pts.map(|(p, _)| p.coords).collect(), s0, s1)
            } else {
                let h = pts.map(|(p, &w)| nalgebra::Vector3::new(p.x * w, p.y * w, w));
                cut_piece(h.collect(), s0, s1)
                    .into_iter()
                    .map(|h| nalgebra::Vector2::new(h.x / h.z, h.y / h.z))
                    .collect()
            };
            for q in cut.iter() {
                xr = widen(xr, q.x);
                yr = widen(yr, q.y);
            }
        }
        if xr.0 <= xr.1 {
            return (xr, yr, degree);
        }
    }
    // No spans: 33 samples, widened by h·M (see the impl's docs).
    const SAMPLES: usize = 32;
    let h = (u1 - u0) / SAMPLES as f64;
    let mut speed = 0.0_f64;
    for i in 0..=SAMPLES {
        let t = if i == SAMPLES { u1 } else { u0 + h * i as f64 };
        let (p, d) = profile.eval_with_derivative(t);
        xr = widen(xr, p.x);
        yr = widen(yr, p.y);
        speed = speed.max(d.norm());
    }
    let m = h * speed;
    ((xr.0 - m, xr.1 + m), (yr.0 - m, yr.1 + m), 3)
}

/// The Bézier coefficients `c` of a piece cut to `[s0, s1]` (two de
/// Casteljau subdivisions: to `[0, s1]`, then that to `[s0/s1, 1]`).
fn cut_piece<T: crate::bernstein::Coefficient>(c: Vec<T>, s0: f64, s1: f64) -> Vec<T> {
    let (mut left, mut right, mut cut) = (c.clone(), c.clone(), c.clone());
    crate::bernstein::subdivide(&c, s1, &mut left, &mut right);
    if s1 > 0.0 && s0 > 0.0 {
        crate::bernstein::subdivide(&left, (s0 / s1).min(1.0), &mut right, &mut cut);
    } else {
        cut.copy_from_slice(&left);
    }
    cut
}

/// The exact local `(x, z)` ranges of the sector `{(r cos θ, −r sin θ)}`,
/// `r ∈ [r0, r1]` (`0 ≤ r0 ≤ r1`), `θ ∈ [θ0, θ1]`.
fn sector_box((r0, r1): (f64, f64), (t0, t1): (f64, f64)) -> ((f64, f64), (f64, f64)) {
    use std::f64::consts::{FRAC_PI_2, PI};
    // Whether [t0, t1] contains α + 2kπ for some k; a hair of slack keeps
    // extremes that rounding might put just outside (a larger box is safe).
    let contains = |alpha: f64| {
        if t1 - t0 >= TAU {
            return true;
        }
        let slack = 1e-12 * (1.0 + t0.abs().max(t1.abs()));
        let k = ((t0 - slack - alpha) / TAU).ceil();
        alpha + k * TAU <= t1 + slack
    };
    let ((s0, c0), (s1, c1)) = (t0.sin_cos(), t1.sin_cos());
    let cos_max = if contains(0.0) { 1.0 } else { c0.max(c1) };
    let cos_min = if contains(PI) { -1.0 } else { c0.min(c1) };
    let sin_max = if contains(FRAC_PI_2) { 1.0 } else { s0.max(s1) };
    let sin_min = if contains(-FRAC_PI_2) {
        -1.0
    } else {
        s0.min(s1)
    };
    // The range of r·w over [r0, r1] × [w0, w1] is that of the corners.
    let product = |w0: f64, w1: f64| {
        let c = [r0 * w0, r0 * w1, r1 * w0, r1 * w1];
        (
            c.iter().fold(f64::INFINITY, |m, &x| m.min(x)),
            c.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x)),
        )
    };
    (product(cos_min, cos_max), product(-sin_max, -sin_min))
}
