//! Surfaces of revolution: a planar profile turned about an axis.

use super::profile_approximation::approximate;
use super::span_table::SpanTable;
use crate::curve::RationalBezierSpan;
use crate::surface::oriented;
use crate::{Curve, Error, Surface, Tolerance};
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
/// orientation as positive `x`); [`reversed`](Self::reversed) turns every
/// normal the other way.
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
    pub(super) profile: C,
    /// Local frame → world: rotation taking the local `y` axis to the axis,
    /// then translation to the axis origin.
    pub(super) to_world: Isometry3<f64>,
    /// `to_world`'s rotation as a matrix: rays and hits are turned with it
    /// (9 products a vector, against about twice that for the quaternion).
    pub(super) rotation: Rotation3<f64>,
    /// The exact intersector's per-surface data: of the profile's Bézier
    /// spans, or of its cubic approximation (`approximation`). `None` when
    /// the profile breaks the [`Curve`] contract (`broken` says how).
    pub(super) exact: Option<SpanTable>,
    /// For a profile without Bézier spans: the largest deviation of the
    /// approximation that `exact` was built from, measured at its test
    /// points.
    pub(super) approximation: Option<f64>,
    /// Why the profile breaks the [`Curve`] contract, if it does.
    pub(super) broken: Option<Error>,
    pub(super) tolerance: Tolerance,
    /// The axis of the last successful placement as [`placement`] scales it
    /// before normalizing (largest component ±1; `y` before any placement):
    /// the placement's defining data, which serialization writes so that a
    /// round trip rebuilds `to_world` bit for bit (the axis read back from
    /// the rotation, or the unit axis normalized again, may differ by an
    /// ulp; this one scales by exactly 1 again).
    pub(super) scaled_axis: Vector3<f64>,
    /// The orientation is reversed ([`reversed`](Revolution::reversed)):
    /// every normal is negated, nothing else changes.
    pub(crate) reversed: bool,
    /// The angle (radians) of the turn about the local `y` axis that
    /// `to_world` applies before the placement's shortest rotation: 0
    /// after [`with_axis`](Revolution::with_axis), any angle after
    /// [`transformed`](Revolution::transformed) (written by serialization
    /// when not 0).
    pub(crate) turn: f64,
}
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
    /// surface that rays do not hit and whose [`bounds`](crate::Intersect::bounds)
    /// are [`Aabb::EMPTY`](crate::Aabb::EMPTY); [`try_new`](Self::try_new) reports why, and so
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
            reversed: false,
            turn: 0.0,
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

    /// The same surface with the opposite orientation: the unit normal
    /// becomes `−(∂S/∂u × ∂S/∂θ)/|∂S/∂u × ∂S/∂θ|` (and its limits on the
    /// axis are negated), while the points, the partials
    /// [`partials`](Surface::partials) (unchanged, so no longer crossing to
    /// the normal), the parameters and the hits' `t`, `point` and `uv` are
    /// exactly the original's. Every normal is negated: [`Surface::normal`],
    /// [`normal_local`](Self::normal_local), each [`Hit`](crate::Hit)'s
    /// from [`Intersect`](crate::Intersect), and [`tessellate`](Self::tessellate)'s
    /// vertex normals, whose triangles are wound the other way to match.
    /// Where no tangent plane exists (a cone's apex) a hit's normal faces
    /// the ray as before. `reversed().reversed()` is the original.
    ///
    /// A profile traced upward (increasing `y`) gives normals toward the
    /// axis; reversing gives outward ones:
    ///
    /// ```
    /// use revolve::{Intersect, Nurbs, Ray, Revolution, Surface};
    /// use revolve::nalgebra::{Point2, Point3, Vector3};
    /// use std::f64::consts::FRAC_PI_2;
    ///
    /// // The unit sphere from its south pole up to its north pole.
    /// let inward = Revolution::new(Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2)?);
    /// let sphere = inward.reversed();
    /// let p = sphere.eval(0.3, 1.0);
    /// assert!(sphere.normal(0.3, 1.0).unwrap().dot(&p.coords) > 0.999);
    /// assert_eq!(sphere.normal(0.3, 1.0).map(|n| -n), inward.normal(0.3, 1.0));
    /// let ray = Ray::new(Point3::new(0.0, 0.0, -3.0), Vector3::z());
    /// let (a, b) = (sphere.intersect(&ray, 0.0, 9.0).unwrap(), inward.intersect(&ray, 0.0, 9.0).unwrap());
    /// assert_eq!((a.t, a.point, a.uv), (b.t, b.point, b.uv));
    /// assert_eq!(a.normal, -b.normal);
    /// assert!((a.normal.into_inner() - Vector3::new(0.0, 0.0, -1.0)).norm() < 1e-15);
    /// assert_eq!(sphere.reversed(), inward);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn reversed(&self) -> Self
    where
        C: Clone,
    {
        let mut surface = self.clone();
        surface.reversed = !surface.reversed;
        surface
    }

    /// Whether [`Intersect`](crate::Intersect) runs the exact intersector on the profile's own
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
        let rotation = axis_rotation(&axis);
        self.to_world = Isometry3::from_parts(
            Translation3::from(origin.coords),
            UnitQuaternion::from_rotation_matrix(&rotation),
        );
        self.rotation = self.to_world.rotation.to_rotation_matrix();
        self.scaled_axis = given.into_inner() / given.amax();
        self.turn = 0.0;
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

    /// The unit normal in the local frame (see the type's edge rules;
    /// negated on a [reversed](Self::reversed) surface).
    pub fn normal_local(&self, u: f64, theta: f64) -> Option<Unit<Vector3<f64>>> {
        let x = self.profile.eval(u).x;
        let at_end = u >= self.profile.domain().1;
        profile_normal(
            x,
            self.profile.tangent(u)?,
            at_end,
            finite_angle(theta).sin_cos(),
        )
        .map(|n| oriented(n, self.reversed))
    }
}

/// The shortest rotation taking `y` to the unit `axis` (the half turn
/// about `x` for `−y`): the rotation of [`Revolution::with_axis`].
pub(super) fn axis_rotation(axis: &Unit<Vector3<f64>>) -> Rotation3<f64> {
    // The angle from atan2(|y × a|, y · a), accurate near 0 and π (acos
    // of the dot product loses half the digits there).
    let y = Vector3::y();
    let cross = y.cross(axis);
    let angle = cross.norm().atan2(y.dot(axis));
    // Scaled before normalizing: an axis within 1e-154 of ±y has a
    // cross product whose squares are subnormal (a norm off by 1e-10).
    let m = cross.amax();
    let about = (m > 0.0).then(|| Unit::try_new(cross / m, 0.0)).flatten();
    match about {
        Some(about) => Rotation3::from_axis_angle(&about, angle),
        None if angle > 1.0 => Rotation3::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI),
        None => Rotation3::identity(),
    }
}
/// The axis of a placement, renormalized (a `Unit` made unchecked may not
/// be of unit length), if `origin` and `axis` are acceptable (see
/// [`Revolution::with_axis`]).
pub(super) fn placement(
    origin: Point3<f64>,
    axis: Unit<Vector3<f64>>,
) -> Result<Unit<Vector3<f64>>, Error> {
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
