//! The crate's error type: every bad input is reported as a value, never a panic.

use crate::limits::{MAX_COORDINATE, MAX_DERIVATIVE};
use std::fmt;

/// What was wrong with an input.
///
/// Every constructor and fallible operation of the crate returns `Err(Error::…)`
/// for bad input instead of panicking or producing NaN. Each variant carries the
/// values needed to find the problem (an index, the offending number, the limit).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    // The data that defines a curve: control points, weights, circles and arcs.
    /// A curve needs at least one control point.
    NoControlPoints,
    /// A control point has a NaN or infinite coordinate.
    NonFinitePoint {
        /// Index of the control point.
        index: usize,
    },
    /// A control-point coordinate is larger in magnitude than
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE), beyond which differences
    /// and derivatives could overflow.
    CoordinateTooLarge {
        /// Index of the control point.
        index: usize,
        /// The offending coordinate.
        value: f64,
    },
    /// A ray whose origin or direction has a NaN or infinite coordinate, or
    /// whose direction is zero ([`Ray::try_new`](crate::Ray::try_new)).
    InvalidRay {
        /// The origin given.
        origin: [f64; 3],
        /// The direction given.
        dir: [f64; 3],
    },
    /// A rational curve needs one weight per control point.
    WeightCount {
        /// The number of control points.
        expected: usize,
        /// The number of weights given.
        found: usize,
    },
    /// A weight is zero, negative, NaN or infinite (weights must be
    /// positive and finite).
    InvalidWeight {
        /// Index of the weight.
        index: usize,
        /// The offending weight.
        weight: f64,
    },
    /// The largest weight is more than
    /// [`MAX_WEIGHT_RATIO`](crate::curve::MAX_WEIGHT_RATIO) times the
    /// smallest.
    WeightRatioTooLarge {
        /// Largest over smallest weight.
        ratio: f64,
        /// The limit.
        max: f64,
    },
    /// A circle's or arc's radius is not a finite positive number at most
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    InvalidRadius {
        /// The radius given.
        radius: f64,
    },
    /// A circle's or arc's center has a NaN or infinite coordinate, or one
    /// beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    InvalidCenter {
        /// The center given.
        center: nalgebra::Point2<f64>,
    },
    /// An arc's sweep `end − start` (radians, counter-clockwise) is not in
    /// `(0, 2π]`, or an angle is NaN or infinite.
    InvalidSweep {
        /// The start angle given.
        start: f64,
        /// The end angle given.
        end: f64,
    },

    // Knot vectors and degrees.
    /// A knot is NaN or infinite.
    NonFiniteKnot {
        /// Index of the knot.
        index: usize,
    },
    /// The knot vector length is not `points + degree + 1`.
    KnotCount {
        /// The required number of knots.
        expected: usize,
        /// The number of knots given.
        found: usize,
    },
    /// A knot is larger in magnitude than
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    KnotTooLarge {
        /// Index of the knot.
        index: usize,
        /// The offending knot.
        value: f64,
    },
    /// Two distinct knots are closer than rounding can tell apart
    /// (`0 < knots[index] − knots[index − 1] < min`): make them one repeated
    /// knot or spread them.
    KnotGapTooSmall {
        /// Index of the upper knot of the gap.
        index: usize,
        /// The gap.
        gap: f64,
        /// The smallest non-zero gap accepted (`4ε ×` the knot range).
        min: f64,
    },
    /// The knots are not non-decreasing: `knots[index] < knots[index - 1]`.
    DecreasingKnots {
        /// Index of the first knot that is smaller than its predecessor.
        index: usize,
    },
    /// A knot value repeats more than `degree + 1` times.
    KnotMultiplicity {
        /// The repeated knot value.
        knot: f64,
        /// How often it occurs.
        multiplicity: usize,
        /// The largest multiplicity allowed (`degree + 1`).
        max: usize,
    },
    /// The parameter domain has zero length (`start == end`).
    EmptyDomain {
        /// Start of the domain.
        start: f64,
        /// End of the domain.
        end: f64,
    },
    /// The degree is too high for the number of control points (a B-spline of
    /// degree `p` needs at least `p + 1` points).
    DegreeTooHigh {
        /// The requested degree.
        degree: usize,
        /// The number of control points given.
        points: usize,
    },
    /// Degree elevation would make the degree `degree + times` larger than
    /// [`MAX_ELEVATED_DEGREE`](crate::curve::MAX_ELEVATED_DEGREE) (or
    /// overflow).
    ElevationTooHigh {
        /// The curve's degree.
        degree: usize,
        /// How many times elevation was asked for.
        times: usize,
        /// The largest degree elevation may produce.
        max: usize,
    },
    /// Degree elevation would move the curve: at high degree over short
    /// knot spans, the new control points amplify rounding beyond
    /// [`ELEVATION_ACCURACY`](crate::curve::ELEVATION_ACCURACY) of the
    /// curve's size, so the elevated curve would not be the same curve.
    ElevationInexact {
        /// The curve's degree.
        degree: usize,
        /// How many times elevation was asked for.
        times: usize,
        /// The largest distance found between the two curves, relative to
        /// the largest control-point coordinate.
        deviation: f64,
    },

    // Parameters, query points and derivatives.
    /// A parameter value is NaN or lies outside the interval where the operation
    /// is defined.
    ParameterOutOfDomain {
        /// The parameter that was given.
        t: f64,
        /// The interval it must lie in (inclusive).
        domain: (f64, f64),
    },
    /// A query point (nearest point) has a coordinate that is NaN,
    /// infinite or beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    InvalidQueryPoint {
        /// Index of the coordinate.
        coordinate: usize,
        /// The offending value.
        value: f64,
    },
    /// A derivative of the curve could exceed
    /// [`MAX_DERIVATIVE`](crate::curve::MAX_DERIVATIVE) in magnitude: knots
    /// too close together for the control points' differences (or a degree
    /// too high for the coordinates).
    DerivativeOverflow {
        /// The order of the derivative (`1 ..= degree`).
        order: usize,
    },
    /// A derivative of an order beyond the supported
    /// [`MAX_DERIVATIVE_ORDER`](crate::curve::MAX_DERIVATIVE_ORDER) was asked
    /// for (a rational curve's derivatives do not vanish above its degree;
    /// each order costs time and memory).
    DerivativeOrderTooHigh {
        /// The order asked for.
        order: usize,
        /// The highest order supported.
        max: usize,
    },

    // Tolerances and iteration caps.
    /// A tolerance is not a finite positive number.
    InvalidTolerance {
        /// The tolerance that was given.
        tolerance: f64,
    },
    /// A tolerance is smaller than double precision can guarantee at the
    /// object's scale.
    ToleranceTooSmall {
        /// The tolerance that was given.
        tolerance: f64,
        /// The smallest tolerance accepted for this object.
        min: f64,
    },
    /// A mesh within the tolerance would have more than
    /// [`Mesh::MAX_VERTICES`](crate::Mesh::MAX_VERTICES) vertices.
    MeshTooLarge {
        /// The tolerance that was given.
        tolerance: f64,
        /// How many vertices the mesh would need at least.
        vertices: f64,
        /// The vertex cap.
        max: usize,
        /// A tolerance whose mesh fits.
        min: f64,
    },
    /// A tolerance is larger than the solver accepts.
    ToleranceTooLarge {
        /// The tolerance that was given.
        tolerance: f64,
        /// The largest tolerance accepted.
        max: f64,
    },
    /// A patch tree deeper than the Newton intersector builds
    /// ([`NewtonIntersector::try_new`](crate::NewtonIntersector::try_new)).
    DepthTooLarge {
        /// The depth that was asked for.
        depth: u32,
        /// The deepest tree built.
        max: u32,
    },
    /// An iteration cap is zero or larger than the solver accepts.
    InvalidIterations {
        /// The cap that was given.
        max_iterations: u32,
        /// The largest cap accepted.
        max: u32,
    },

    // Curves handed to an operation (profiles of revolutions, curves queried):
    // what the operation needs of them, the `Curve` contract, the placement.
    /// The operation needs a piecewise polynomial curve (one that provides
    /// [`Curve::bezier_spans`](crate::Curve::bezier_spans)).
    NotPiecewisePolynomial,
    /// The operation needs a curve with rational Bézier spans (one whose
    /// [`Curve::rational_bezier_spans`](crate::Curve::rational_bezier_spans)
    /// is `Some`).
    NotPiecewiseRational,
    /// A curve's domain is not a finite interval `(a, b)` with `a < b` (a
    /// user's curve that breaks the [`Curve`](crate::Curve) contract).
    InvalidDomain {
        /// The start the curve reported.
        start: f64,
        /// The end the curve reported.
        end: f64,
    },
    /// A curve returned a NaN or infinite point or derivative, or a
    /// coordinate beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE), at a
    /// parameter inside its domain.
    CurveNotFinite {
        /// The parameter.
        t: f64,
    },
    /// A curve's [Bézier spans](crate::Curve::bezier_spans) are empty, or
    /// span `index` does not follow the previous one (its interval is empty,
    /// not finite, or starts before the previous span ends).
    SpansOutOfOrder {
        /// Index of the offending span (0 when there are none).
        index: usize,
    },
    /// A Bézier span's control point is NaN, infinite or beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    SpanPointNotFinite {
        /// Index of the span.
        span: usize,
    },
    /// A profile without Bézier spans could not be approximated within the
    /// limit of pieces (it is not smooth enough, or not continuous).
    ProfileTooRough {
        /// The number of pieces tried.
        pieces: usize,
    },
    /// A surface's placement has an origin that is not finite or beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE), or an axis that is not a
    /// finite non-zero vector.
    InvalidPlacement {
        /// The origin given.
        origin: nalgebra::Point3<f64>,
        /// The axis given.
        axis: nalgebra::Vector3<f64>,
    },

    /// A surface needs at least one row of at least one control point.
    EmptyGrid,
    /// A surface's control point has a NaN or infinite coordinate.
    NonFiniteGridPoint {
        /// Its row (along `u`).
        row: usize,
        /// Its column (along `v`).
        column: usize,
    },
    /// A surface's control-point coordinate is larger in magnitude than
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    GridCoordinateTooLarge {
        /// Its row (along `u`).
        row: usize,
        /// Its column (along `v`).
        column: usize,
        /// The offending coordinate.
        value: f64,
    },
    /// A surface's weight is zero, negative, NaN or infinite.
    InvalidGridWeight {
        /// Its row (along `u`).
        row: usize,
        /// Its column (along `v`).
        column: usize,
        /// The offending weight.
        weight: f64,
    },
    /// A surface's knot vector (or a knot to insert) in one direction is
    /// wrong; `error` is the curve's error for it.
    SurfaceKnots {
        /// `u` or `v`.
        direction: ParameterDirection,
        /// What is wrong, as for a curve's knots.
        error: Box<Error>,
    },

    // Tensor-product surfaces and models made of patches.
    /// A grid of control points (or of weights) of a tensor-product surface
    /// has rows of different lengths: row `row` has `found` entries where
    /// the first row has `expected` (for weights: where the points' rows
    /// have `expected`).
    RaggedGrid {
        /// Index of the first row of the wrong length.
        row: usize,
        /// The length of the first row (of the points' rows, for weights).
        expected: usize,
        /// The length of that row.
        found: usize,
    },
    /// A model made of patches was given none.
    NoPatches,

    // Sizes of results and memory.
    /// More segments were asked of [`Curve::try_discretize`](crate::Curve::try_discretize)
    /// than [`MAX_SEGMENTS`](crate::curve::MAX_SEGMENTS).
    TooManySegments {
        /// The number of segments asked for.
        segments: usize,
        /// The largest number accepted.
        max: usize,
    },
    /// An output buffer is too short.
    BufferLength {
        /// The number of entries needed.
        expected: usize,
        /// The number of entries given.
        found: usize,
    },
    /// Memory for a result could not be allocated.
    AllocationFailed {
        /// The number of bytes asked for (saturated at `usize::MAX`).
        bytes: usize,
    },

    // Surface constructions.
    /// A flat, row-major list of control points (or weights) for a surface
    /// cannot be cut into `rows` equal rows: its length is not a non-zero
    /// multiple of `rows` (or `rows` is zero).
    FlatGridLength {
        /// The length of the list.
        length: usize,
        /// The number of rows asked for.
        rows: usize,
    },
    /// A surface parameter (an isocurve's) is NaN or outside the surface's
    /// domain in its direction.
    SurfaceParameterOutOfDomain {
        /// `u` or `v`.
        direction: ParameterDirection,
        /// The parameter given.
        t: f64,
        /// The domain in that direction (inclusive).
        domain: (f64, f64),
    },
    /// A surface cannot be split at `t`: a split needs a parameter strictly
    /// inside the domain in its direction (at an end one half would be
    /// empty), and `t` is NaN, outside, at an end, or within rounding of an
    /// end.
    SplitOutsideDomain {
        /// `u` or `v`.
        direction: ParameterDirection,
        /// The parameter given.
        t: f64,
        /// The domain in that direction.
        domain: (f64, f64),
    },
    /// An extrusion (or sweep) direction has a NaN or infinite coordinate,
    /// or is zero (the surface would have no width).
    InvalidExtrusion {
        /// The vector given.
        vector: nalgebra::Vector3<f64>,
    },
    /// An affine map has a NaN or infinite entry.
    NonFiniteTransform,
    /// A profile's rational Bézier spans leave a gap: span `index` starts
    /// after the previous one ends, so no single spline surface follows the
    /// profile with its own parameter.
    SpanGap {
        /// Index of the span after the gap.
        index: usize,
        /// Where the previous span ends.
        previous_end: f64,
        /// Where span `index` starts.
        start: f64,
    },
    // Constructions through data: interpolation, least-squares fitting and
    // lofting (`BSpline::interpolate`, `BSpline::fit`,
    // `BSplineSurface::interpolate`, `NurbsSurface::loft`).
    /// Interpolation, fitting or lofting was asked for degree 0: a curve of
    /// degree 0 is piecewise constant and passes through no two distinct
    /// points.
    ZeroDegree,
    /// Too few data points for the degree: interpolation or fitting of
    /// degree `p` needs at least `p + 1` points.
    TooFewPoints {
        /// The requested degree.
        degree: usize,
        /// The number of data points given.
        points: usize,
    },
    /// Two consecutive data points coincide, `points[index − 1] ==
    /// points[index]` (a zero chord), or lie so close together, relative
    /// to the other chords, that their parameters cannot be told apart
    /// (a centripetal parameter step below `16ε` of the whole).
    CoincidentPoints {
        /// Index of the second point of the pair.
        index: usize,
    },
    /// A least-squares fit was asked for more control points than there
    /// are data points.
    TooManyControlPoints {
        /// The number of control points asked for.
        control_points: usize,
        /// The number of data points given.
        points: usize,
    },
    /// A least-squares fit was asked for `degree` or fewer control points;
    /// a spline of degree `p` needs at least `p + 1`.
    TooFewControlPoints {
        /// The number of control points asked for.
        control_points: usize,
        /// The requested degree.
        degree: usize,
    },
    /// A grid to interpolate has too few points along a direction for the
    /// degree there (`degree + 1` are needed): rows along `u`, columns
    /// along `v`.
    GridTooSmall {
        /// `u` (the number of rows) or `v` (the length of the rows).
        direction: ParameterDirection,
        /// The number of points along that direction.
        found: usize,
        /// The degree asked for in that direction.
        degree: usize,
    },
    /// Along `direction`, the grid's points `index − 1` and `index`
    /// coincide in every row (`v`) or every column (`u`) that has any
    /// length, so the averaged parameters cannot separate them (or no row
    /// or column has any length at all: then `index` is 1).
    CoincidentGridPoints {
        /// The direction in which the points follow each other.
        direction: ParameterDirection,
        /// Index of the second row (`u`) or column (`v`) of the pair.
        index: usize,
    },
    /// A loft of degree `degree` in `v` needs at least `max(2, degree + 1)`
    /// section curves.
    TooFewSections {
        /// The number of section curves given.
        sections: usize,
        /// The degree asked for across the sections.
        degree: usize,
    },
    /// Section curves `index − 1` and `index` of a loft have the same
    /// control points once made compatible (their average distance is
    /// zero, or too small for their parameters to be told apart), so no
    /// surface can pass through both at different parameters.
    CoincidentSections {
        /// Index of the second section of the pair.
        index: usize,
    },
    /// The linear system of an interpolation or least-squares fit is
    /// singular to working precision: elimination found no pivot larger
    /// than `ε ×` the matrix's largest entry in this column.
    SingularSystem {
        /// The column (unknown) without a usable pivot.
        column: usize,
    },
    // Intersections of curves with curves and with surfaces.
    /// Two curves run within the tolerance of each other along a stretch
    /// (they overlap there), so their intersections are not isolated points
    /// ([`intersect_curves`](crate::curve::intersect_curves)). The ranges
    /// are the parameters of the part of the stretch found.
    CurvesOverlap {
        /// The range of the first curve's parameter.
        a: (f64, f64),
        /// The range of the second curve's parameter.
        b: (f64, f64),
    },
    /// A curve runs within the tolerance of a surface along a stretch (it
    /// lies on the surface there), so its intersections with the surface
    /// are not isolated points. The ranges are those of the part found.
    CurveOnSurface {
        /// The range of the curve's parameter.
        t: (f64, f64),
        /// The range of the surface's first parameter.
        u: (f64, f64),
        /// The range of the surface's second parameter.
        v: (f64, f64),
    },
    /// An intersection of two pieces (two curve spans, or a curve span and a
    /// surface patch) would need a system of more Bézier coefficients
    /// (products of the pieces' control points) than the search accepts:
    /// the degrees are too high.
    IntersectionTooLarge {
        /// The number of coefficients the system would have.
        coefficients: usize,
        /// The largest number accepted.
        max: usize,
    },
    // Curve operations: split, transform, length parametrization, knot
    // removal, 3D arcs and ellipses.
    /// A split parameter is at an end of the curve's domain (or within
    /// rounding of it, `4ε ×` the knot range for a spline): one of the two
    /// pieces would be empty. Split strictly inside the domain.
    SplitAtDomainEnd {
        /// The parameter that was given.
        t: f64,
        /// The curve's domain; `t` must lie strictly inside it.
        domain: (f64, f64),
    },
    /// A transformation has a NaN or infinite entry.
    InvalidTransform,
    /// A projective map sends a control point's weight to zero or below:
    /// the curve meets (or crosses) the plane at infinity, so its image is
    /// not a curve with positive weights.
    ProjectiveWeightNotPositive {
        /// Index of the control point.
        index: usize,
        /// The new weight `w·(h·P + h₀)` (the denominator row of the map
        /// applied to the point, times the point's weight).
        weight: f64,
    },
    /// An arc length `s` outside `[0, L]`, `L` the curve's length (or NaN).
    LengthOutOfRange {
        /// The length that was given.
        s: f64,
        /// The curve's length (its certified upper bound).
        length: f64,
    },
    /// Dividing a curve into zero pieces.
    ZeroPieces,
    /// Knot removal was asked for a parameter that is not an interior knot
    /// of the curve (the domain's ends cannot be removed).
    NotAnInteriorKnot {
        /// The parameter that was given.
        t: f64,
    },
    /// A 3D arc's center has a NaN or infinite coordinate, or one beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    InvalidCenter3 {
        /// The center given.
        center: [f64; 3],
    },
    /// A 3D arc's normal is zero, NaN or infinite, or its start direction
    /// is, or is parallel to the normal (nothing of it is left in the
    /// arc's plane).
    InvalidArcFrame {
        /// The normal given.
        normal: [f64; 3],
        /// The start direction given.
        start_dir: [f64; 3],
    },
    /// Interpolation at given parameters got a different number of
    /// parameters than of data points.
    ParameterCount {
        /// The number of data points.
        expected: usize,
        /// The number of parameters given.
        found: usize,
    },
    /// Degree reduction was asked for a curve of degree 0 or 1 (a line
    /// reduced would lose an end point).
    DegreeTooLowToReduce {
        /// The curve's degree.
        degree: usize,
    },
    /// No curve of one degree lower was found within the tolerance: the
    /// bound reached is given.
    ReductionInexact {
        /// The bound on the distance of the best reduction found.
        deviation: f64,
        /// The tolerance asked for.
        tolerance: f64,
    },
    /// A given interpolation parameter is NaN, infinite or beyond
    /// [`MAX_COORDINATE`], or is not above the previous one by at least
    /// `16ε` of the parameters' whole range.
    InvalidParameter {
        /// Index of the parameter.
        index: usize,
        /// Its value.
        value: f64,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NoControlPoints => {
                write!(f, "a curve needs at least one control point, got none")
            }
            Error::EmptyGrid => write!(
                f,
                "a surface needs at least one row of at least one control point, got none"
            ),
            Error::NonFiniteGridPoint { row, column } => write!(
                f,
                "the surface's control point at row {row}, column {column} has a NaN or \
                 infinite coordinate"
            ),
            Error::GridCoordinateTooLarge { row, column, value } => write!(
                f,
                "the surface's control point at row {row}, column {column} has coordinate {}, \
                 beyond the supported magnitude {}",
                Num(value),
                Num(MAX_COORDINATE)
            ),
            Error::InvalidGridWeight {
                row,
                column,
                weight,
            } => write!(
                f,
                "the surface's weight at row {row}, column {column} is {}; weights must be \
                 positive and finite",
                Num(weight)
            ),
            Error::SurfaceKnots {
                direction,
                ref error,
            } => {
                write!(f, "the surface's {direction} knots: {error}")
            }
            Error::NonFinitePoint { index } => {
                write!(f, "control point {index} has a NaN or infinite coordinate")
            }
            Error::InvalidRay { origin, dir } => write!(
                f,
                "a ray needs a finite origin and a finite, non-zero direction, not origin {:?} and direction {:?}",
                origin, dir
            ),
            Error::CoordinateTooLarge { index, value } => write!(
                f,
                "control point {index} has coordinate {}, beyond the supported magnitude {}",
                Num(value),
                Num(MAX_COORDINATE)
            ),
            Error::WeightCount { expected, found } => write!(
                f,
                "wrong weight count: expected {expected} (one per control point), found {found}"
            ),
            Error::InvalidWeight { index, weight } => write!(
                f,
                "weight {index} is {}; weights must be positive and finite",
                Num(weight)
            ),
            Error::WeightRatioTooLarge { ratio, max } => write!(
                f,
                "the largest weight is {} times the smallest, more than the supported {}",
                Num(ratio),
                Num(max)
            ),
            Error::InvalidRadius { radius } => write!(
                f,
                "radius {} is not a finite positive number at most {}",
                Num(radius),
                Num(MAX_COORDINATE)
            ),
            Error::InvalidCenter { center } => write!(
                f,
                "center ({}, {}) is not a finite point with coordinates at most {}",
                Num(center.x),
                Num(center.y),
                Num(MAX_COORDINATE)
            ),
            Error::InvalidSweep { start, end } => write!(
                f,
                "arc from {} to {} radians: the sweep end − start must be a number in (0, 2π]",
                Num(start),
                Num(end)
            ),
            Error::NonFiniteKnot { index } => write!(f, "knot {index} is NaN or infinite"),
            Error::KnotCount { expected, found } => write!(
                f,
                "wrong knot count: expected {expected} (points + degree + 1), found {found}"
            ),
            Error::KnotTooLarge { index, value } => write!(
                f,
                "knot {index} is {}, beyond the supported magnitude {}",
                Num(value),
                Num(MAX_COORDINATE)
            ),
            Error::KnotGapTooSmall { index, gap, min } => write!(
                f,
                "knots {} and {index} differ by {}, less than the smallest distinguishable gap {}; \
                 make them one repeated knot or spread them",
                index.saturating_sub(1),
                Num(gap),
                Num(min)
            ),
            Error::DecreasingKnots { index } => write!(
                f,
                "knots must be non-decreasing, but knot {index} is smaller than knot {}",
                index.saturating_sub(1)
            ),
            Error::KnotMultiplicity {
                knot,
                multiplicity,
                max,
            } => write!(
                f,
                "knot {} occurs {multiplicity} times, more than degree + 1 = {max}",
                Num(knot)
            ),
            Error::EmptyDomain { start, end } => {
                write!(
                    f,
                    "the parameter domain [{}, {}] is empty",
                    Num(start),
                    Num(end)
                )
            }
            Error::DegreeTooHigh { degree, points } => write!(
                f,
                "degree {degree} needs at least {} control points, got {points}",
                degree.saturating_add(1)
            ),
            Error::ElevationTooHigh { degree, times, max } => write!(
                f,
                "elevating degree {degree} by {times} would exceed the largest supported \
                 degree {max}"
            ),
            Error::ElevationInexact {
                degree,
                times,
                deviation,
            } => write!(
                f,
                "elevating degree {degree} by {times} would move the curve by {} of its size \
                 (rounding grows with the degree over short knot spans): not the same curve",
                Num(deviation)
            ),
            Error::ParameterOutOfDomain { t, domain } => write!(
                f,
                "parameter {} is outside the domain [{}, {}]",
                Num(t),
                Num(domain.0),
                Num(domain.1)
            ),
            Error::InvalidQueryPoint { coordinate, value } => write!(
                f,
                "query point coordinate {coordinate} is {}; it must be finite and at most {} \
                 in magnitude",
                Num(value),
                Num(MAX_COORDINATE)
            ),
            Error::DerivativeOverflow { order } => write!(
                f,
                "the derivative of order {order} could exceed {} in magnitude: spread the \
                 knots or bring the control points closer together",
                Num(MAX_DERIVATIVE)
            ),
            Error::DerivativeOrderTooHigh { order, max } => write!(
                f,
                "derivative of order {order} asked for; the highest supported order is {max}"
            ),
            Error::InvalidTolerance { tolerance } => write!(
                f,
                "tolerance must be a finite positive number, got {}",
                Num(tolerance)
            ),
            Error::ToleranceTooSmall { tolerance, min } => write!(
                f,
                "tolerance {} is below what double precision can guarantee at this \
                 object's size (tolerances are absolute, in the object's units); use at \
                 least {}",
                Num(tolerance),
                Num(min)
            ),
            Error::MeshTooLarge {
                tolerance,
                vertices,
                max,
                min,
            } => write!(
                f,
                "a mesh within tolerance {} would need at least {} vertices, more than \
                 the {max} a mesh may have; use a tolerance of at least {}",
                Num(tolerance),
                Num(vertices.round()),
                Num(min)
            ),
            Error::ToleranceTooLarge { tolerance, max } => write!(
                f,
                "tolerance {} is larger than the largest accepted, {}",
                Num(tolerance),
                Num(max)
            ),
            Error::InvalidIterations {
                max_iterations,
                max,
            } => write!(
                f,
                "iteration cap {max_iterations} is outside the accepted range 1 to {max}"
            ),
            Error::DepthTooLarge { depth, max } => write!(
                f,
                "a patch tree of depth {depth} is deeper than the {max} levels built \
                 (2^{max} leaves)"
            ),
            Error::NotPiecewisePolynomial => write!(
                f,
                "this needs a piecewise polynomial profile (Bézier spans), as Bezier and \
                 BSpline are"
            ),
            Error::NotPiecewiseRational => write!(
                f,
                "this needs a curve with rational Bézier spans (Curve::rational_bezier_spans), \
                 as Bezier, BSpline and RationalBezier are"
            ),
            Error::InvalidDomain { start, end } => write!(
                f,
                "the curve's domain ({}, {}) is not a finite interval with start < end",
                Num(start),
                Num(end)
            ),
            Error::CurveNotFinite { t } => write!(
                f,
                "the curve's point or derivative at t = {} is NaN, infinite or beyond the \
                 supported magnitude {}",
                Num(t),
                Num(MAX_COORDINATE)
            ),
            Error::SpansOutOfOrder { index } => write!(
                f,
                "the curve's Bézier spans are empty or out of order at span {index}: each \
                 needs a finite, non-empty interval starting where the previous one ends or later"
            ),
            Error::SpanPointNotFinite { span } => write!(
                f,
                "Bézier span {span} has a NaN, infinite or too large control point (beyond {})",
                Num(MAX_COORDINATE)
            ),
            Error::ProfileTooRough { pieces } => write!(
                f,
                "the profile could not be approximated by {pieces} cubic pieces: is it \
                 continuous and differentiable?"
            ),
            Error::InvalidPlacement { origin, axis } => write!(
                f,
                "cannot place a surface with its axis through ({}, {}, {}) along ({}, {}, {}): \
                 the origin must be finite and within {}, the axis a finite non-zero vector",
                Num(origin.x),
                Num(origin.y),
                Num(origin.z),
                Num(axis.x),
                Num(axis.y),
                Num(axis.z),
                Num(MAX_COORDINATE)
            ),
            Error::RaggedGrid {
                row,
                expected,
                found,
            } => write!(
                f,
                "ragged grid: row {row} has {found} entries, expected {expected} like the first row"
            ),
            Error::NoPatches => write!(
                f,
                "a model made of patches needs at least one patch, got none"
            ),
            Error::TooManySegments { segments, max } => write!(
                f,
                "{segments} segments asked for, more than the {max} a discretization can have"
            ),
            Error::BufferLength { expected, found } => write!(
                f,
                "output buffer too short: needs {expected} entries, has {found}"
            ),
            Error::AllocationFailed { bytes } => {
                write!(f, "could not allocate {bytes} bytes for the result")
            }
            Error::FlatGridLength { length, rows } => write!(
                f,
                "a flat list of {length} control values cannot be cut into {rows} rows of \
                 equal length: the length must be a non-zero multiple of the rows"
            ),
            Error::SurfaceParameterOutOfDomain {
                direction,
                t,
                domain,
            } => write!(
                f,
                "the surface's {direction} parameter {} is outside its domain [{}, {}]",
                Num(t),
                Num(domain.0),
                Num(domain.1)
            ),
            Error::SplitAtDomainEnd { t, domain } => write!(
                f,
                "cannot split at {}: at an end of the domain [{}, {}], one piece would be empty",
                Num(t),
                Num(domain.0),
                Num(domain.1)
            ),
            Error::SplitOutsideDomain {
                direction,
                t,
                domain,
            } => write!(
                f,
                "cannot split the surface in {direction} at {}: the parameter must lie strictly \
                 inside the domain ({}, {})",
                Num(t),
                Num(domain.0),
                Num(domain.1)
            ),
            Error::InvalidExtrusion { vector } => write!(
                f,
                "extrusion vector ({}, {}, {}) must be finite and non-zero",
                Num(vector.x),
                Num(vector.y),
                Num(vector.z)
            ),
            Error::NonFiniteTransform => {
                write!(f, "the affine map has a NaN or infinite entry")
            }
            Error::SpanGap {
                index,
                previous_end,
                start,
            } => write!(
                f,
                "the profile's Bézier span {index} starts at {} but the previous one ends at {}: \
                 a spline surface needs spans without gaps",
                Num(start),
                Num(previous_end)
            ),
            Error::ZeroDegree => write!(
                f,
                "interpolation, fitting and lofting need degree 1 or more, got 0"
            ),
            Error::TooFewPoints { degree, points } => write!(
                f,
                "degree {degree} needs at least {} data points, got {points}",
                degree.saturating_add(1)
            ),
            Error::CoincidentPoints { index } => write!(
                f,
                "data points {} and {index} coincide (zero chord, or too short beside \
                 the others for their parameters to differ): remove one of them",
                index.saturating_sub(1)
            ),
            Error::TooManyControlPoints {
                control_points,
                points,
            } => write!(
                f,
                "a fit with {control_points} control points needs at least as many data \
                 points, got {points}"
            ),
            Error::TooFewControlPoints {
                control_points,
                degree,
            } => write!(
                f,
                "a fit of degree {degree} needs at least {} control points, got {control_points}",
                degree.saturating_add(1)
            ),
            Error::GridTooSmall {
                direction,
                found,
                degree,
            } => write!(
                f,
                "the grid has {found} points along {direction}; degree {degree} there needs \
                 at least {}",
                degree.saturating_add(1)
            ),
            Error::CoincidentGridPoints { direction, index } => write!(
                f,
                "along {direction}, the grid's points {} and {index} coincide in every row or \
                 column: their parameters cannot differ",
                index.saturating_sub(1)
            ),
            Error::TooFewSections { sections, degree } => write!(
                f,
                "a loft of degree {degree} across its sections needs at least {} section \
                 curves, got {sections}",
                degree.saturating_add(1).max(2)
            ),
            Error::CoincidentSections { index } => write!(
                f,
                "section curves {} and {index} of the loft coincide (the same control points \
                 once made compatible): remove one of them",
                index.saturating_sub(1)
            ),
            Error::SingularSystem { column } => write!(
                f,
                "the interpolation or fitting system is singular to working precision at \
                 unknown {column}"
            ),
            Error::CurvesOverlap { a, b } => write!(
                f,
                "the curves overlap (run within the tolerance of each other) for the first \
                 curve's parameters {} to {} and the second's {} to {}: their intersections \
                 are not isolated points",
                Num(a.0),
                Num(a.1),
                Num(b.0),
                Num(b.1)
            ),
            Error::CurveOnSurface { t, u, v } => write!(
                f,
                "the curve lies on the surface (within the tolerance) for curve parameters {} \
                 to {}, surface parameters u {} to {}, v {} to {}: its intersections with the \
                 surface are not isolated points",
                Num(t.0),
                Num(t.1),
                Num(u.0),
                Num(u.1),
                Num(v.0),
                Num(v.1)
            ),
            Error::IntersectionTooLarge { coefficients, max } => write!(
                f,
                "intersecting these pieces needs {coefficients} products of control points, \
                 more than the {max} accepted: the degrees are too high"
            ),
            Error::InvalidTransform => {
                write!(f, "the transformation has a NaN or infinite entry")
            }
            Error::ProjectiveWeightNotPositive { index, weight } => write!(
                f,
                "the projective map gives control point {index} the weight {}: the curve \
                 meets the plane at infinity",
                Num(weight)
            ),
            Error::LengthOutOfRange { s, length } => write!(
                f,
                "arc length {} is outside [0, {}], the curve's length",
                Num(s),
                Num(length)
            ),
            Error::ZeroPieces => write!(f, "cannot divide a curve into zero pieces"),
            Error::NotAnInteriorKnot { t } => {
                write!(f, "{} is not an interior knot of the curve", Num(t))
            }
            Error::InvalidCenter3 { center } => write!(
                f,
                "arc center ({}, {}, {}) has a NaN, infinite or too large coordinate (limit {})",
                Num(center[0]),
                Num(center[1]),
                Num(center[2]),
                Num(MAX_COORDINATE)
            ),
            Error::InvalidArcFrame { normal, start_dir } => write!(
                f,
                "arc normal ({}, {}, {}) and start direction ({}, {}, {}) must be finite, \
                 non-zero and not parallel",
                Num(normal[0]),
                Num(normal[1]),
                Num(normal[2]),
                Num(start_dir[0]),
                Num(start_dir[1]),
                Num(start_dir[2])
            ),
            Error::DegreeTooLowToReduce { degree } => {
                write!(f, "degree reduction needs degree 2 or more, got {degree}")
            }
            Error::ReductionInexact {
                deviation,
                tolerance,
            } => write!(
                f,
                "the curve of one degree lower is only within {} of the curve, beyond the \
                 tolerance {}",
                Num(deviation),
                Num(tolerance)
            ),
            Error::ParameterCount { expected, found } => write!(
                f,
                "interpolation needs one parameter per data point ({expected}), got {found}"
            ),
            Error::InvalidParameter { index, value } => write!(
                f,
                "interpolation parameter {index} is {}: parameters must be finite, within {} \
                 and increasing by at least 16ε of their range",
                Num(value),
                Num(MAX_COORDINATE)
            ),
        }
    }
}

impl std::error::Error for Error {}

/// Formats a number readably: plain decimals for moderate magnitudes,
/// scientific notation for very large or small ones (`1e-12`, not
/// `0.000000000001`).
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() || (1e-4..1e15).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// A parameter direction of a surface: `u` (the rows of a control grid
/// follow each other along it) or `v` (along each row).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ParameterDirection {
    /// The first parameter.
    U,
    /// The second parameter.
    V,
}

impl fmt::Display for ParameterDirection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            ParameterDirection::U => "u",
            ParameterDirection::V => "v",
        })
    }
}
