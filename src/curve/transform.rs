//! Curves mapped by affine and projective transformations, exactly: the
//! image of a Bézier, B-spline or NURBS curve under an affine map `x ↦ Ax + b`
//! is the curve of the same kind, degree, knots and weights whose control
//! points are the images of the control points (affine invariance, Piegl &
//! Tiller, *The NURBS Book*, P2.4 and P4.7); under a projective map the image
//! of a NURBS curve is the NURBS curve of the mapped homogeneous points, as
//! long as every new weight is positive.
//!
//! The only rounding is that of mapping each control point (`Ax + b`, a
//! dot product per coordinate); the curve between them is the exact image
//! of the original's.
//!
//! Both `Transform<f64, TAffine, D>` and `Transform<f64, TProjective, D>`
//! are nalgebra's, with its bounds on `D` (`Const<D>: DimNameAdd<U1>`); they
//! hold for `D = 1, 2, 3` and beyond ([`Affine2`](nalgebra::Affine2),
//! [`Affine3`](nalgebra::Affine3), [`Projective3`](nalgebra::Projective3),
//! …).

use super::validate_points;
use crate::{BSpline, Bezier, Error, MAX_COORDINATE, Nurbs, RationalBezier};
use nalgebra::allocator::Allocator;
use nalgebra::{
    Const, DefaultAllocator, DimNameAdd, DimNameSum, Point, SVector, TAffine, TCategory,
    TProjective, Transform, U1,
};

/// The entries of a transformation's `(D + 1) × (D + 1)` matrix, by row:
/// the linear part `A = m[..D][..D]`, the translation `b = m[..D][D]`, and
/// the projective row `(h, h₀) = m[D]`.
struct Matrix<const D: usize> {
    a: [[f64; D]; D],
    b: [f64; D],
    h: [f64; D],
    h0: f64,
}

impl<const D: usize> Matrix<D> {
    /// The entries of `t`'s matrix.
    ///
    /// # Errors
    /// [`Error::InvalidTransform`] for a NaN or infinite entry.
    fn of<C: TCategory>(t: &Transform<f64, C, D>) -> Result<Self, Error>
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        let m = t.matrix();
        if !m.iter().all(|x| x.is_finite()) {
            return Err(Error::InvalidTransform);
        }
        Ok(Self::from_entries(|i, j| m[(i, j)]))
    }

    /// The entries of `t`'s matrix as they are (NaN and infinities too).
    fn of_unchecked(t: &Transform<f64, TAffine, D>) -> Self
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        let m = t.matrix();
        Self::from_entries(|i, j| m[(i, j)])
    }

    fn from_entries(m: impl Fn(usize, usize) -> f64) -> Self {
        Matrix {
            a: std::array::from_fn(|i| std::array::from_fn(|j| m(i, j))),
            b: std::array::from_fn(|i| m(i, D)),
            h: std::array::from_fn(|j| m(D, j)),
            h0: m(D, D),
        }
    }

    /// `Ax + b`.
    fn affine(&self, p: &Point<f64, D>) -> SVector<f64, D> {
        SVector::from(std::array::from_fn(|i| {
            (0..D).fold(self.b[i], |s, j| s + self.a[i][j] * p[j])
        }))
    }

    /// `h·x + h₀`.
    fn denominator(&self, p: &Point<f64, D>) -> f64 {
        (0..D).fold(self.h0, |s, j| s + self.h[j] * p[j])
    }
}

/// The images `Apᵢ + b` of the points under an affine transformation.
///
/// # Errors
/// [`Error::InvalidTransform`] for a NaN or infinite entry;
/// [`Error::NonFinitePoint`] or [`Error::CoordinateTooLarge`] for an image
/// with a coordinate that overflows or lies beyond
/// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
fn affine_images<const D: usize>(
    m: Result<Matrix<D>, Error>,
    points: &[Point<f64, D>],
) -> Result<Vec<Point<f64, D>>, Error> {
    let m = m?;
    let images: Vec<Point<f64, D>> = points.iter().map(|p| Point::from(m.affine(p))).collect();
    validate_points(&images)?;
    Ok(images)
}

/// The points with NaN coordinates set to 0 and the others clamped to
/// `±MAX_COORDINATE`: the fallback of the infallible `transformed`.
fn saturated<const D: usize>(points: &[Point<f64, D>]) -> Vec<Point<f64, D>> {
    points
        .iter()
        .map(|p| {
            p.map(|x| {
                if x.is_nan() {
                    0.0
                } else {
                    x.clamp(-MAX_COORDINATE, MAX_COORDINATE)
                }
            })
        })
        .collect()
}

/// The images of the points under an affine map, [`saturated`] (the
/// fallback of the infallible `transformed`).
fn saturated_images<const D: usize>(m: Matrix<D>, points: &[Point<f64, D>]) -> Vec<Point<f64, D>> {
    let images: Vec<Point<f64, D>> = points.iter().map(|p| Point::from(m.affine(p))).collect();
    saturated(&images)
}

/// Shared docs of the fallback, referred to by each `transformed`.
macro_rules! fallback_doc {
    () => {
        "Never fails, never panics: when the image is not a valid curve (a \
         transformation with a NaN or infinite entry, or an image coordinate \
         beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE)), the image points \
         are saturated (NaN to 0, the others clamped to `±MAX_COORDINATE`), \
         and if even that curve is refused (its derivatives would overflow) \
         the result is a copy of `self`. Use `try_transformed` to get the \
         error instead."
    };
}

impl<const D: usize> Bezier<D> {
    /// The image of the curve under the affine map `x ↦ Ax + b`: the Bézier
    /// curve of the mapped control points, so `C′(s) = T(C(s))` for every
    /// `s` (exact, but for the rounding of mapping each control point).
    ///
    #[doc = fallback_doc!()]
    ///
    /// ```
    /// use revolve::{Bezier, Curve};
    /// use revolve::nalgebra::{Affine2, Matrix3, Point2};
    ///
    /// let c = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 0.0)])?;
    /// // Scale x by 2, shear, translate by (1, −1).
    /// let t = Affine2::from_matrix_unchecked(Matrix3::new(2.0, 0.5, 1.0, 0.0, 1.0, -1.0, 0.0, 0.0, 1.0));
    /// let image = c.transformed(&t);
    /// assert!((image.eval(0.3) - t * c.eval(0.3)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn transformed(&self, t: &Transform<f64, TAffine, D>) -> Self
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        self.try_transformed(t).unwrap_or_else(|_| {
            Bezier::new(saturated_images(Matrix::of_unchecked(t), self.points()))
                .unwrap_or_else(|_| self.clone())
        })
    }

    /// As [`transformed`](Self::transformed), with the errors reported.
    ///
    /// ```
    /// use revolve::{Bezier, Error};
    /// use revolve::nalgebra::{Affine2, Matrix3, Point2};
    ///
    /// let c = Bezier::new(vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0)])?;
    /// let huge = Affine2::from_matrix_unchecked(Matrix3::new(1e300, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0));
    /// assert!(matches!(c.try_transformed(&huge), Err(Error::CoordinateTooLarge { index: 1, .. })));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTransform`] for a NaN or infinite matrix entry;
    /// [`Error::NonFinitePoint`] or [`Error::CoordinateTooLarge`] for an
    /// image point that overflows or lies beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE); the other errors of
    /// [`new`](Self::new) for the image.
    pub fn try_transformed(&self, t: &Transform<f64, TAffine, D>) -> Result<Self, Error>
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        Bezier::new(affine_images(Matrix::of(t), self.points())?)
    }
}

impl<const D: usize> RationalBezier<D> {
    /// The image of the curve under the affine map `x ↦ Ax + b`: the mapped
    /// control points with the same weights (affine maps commute with the
    /// rational combination, whose coefficients sum to one), so
    /// `C′(s) = T(C(s))` for every `s`.
    ///
    #[doc = fallback_doc!()]
    ///
    /// ```
    /// use revolve::{Curve, RationalBezier};
    /// use revolve::nalgebra::{Affine2, Matrix3, Point2};
    ///
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let quarter = RationalBezier::new(vec![Point2::new(1.0, 0.0), Point2::new(1.0, 1.0), Point2::new(0.0, 1.0)], vec![1.0, h, 1.0])?;
    /// // Stretch into a quarter ellipse with semi-axes 3 and 2.
    /// let t = Affine2::from_matrix_unchecked(Matrix3::new(3.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0));
    /// let p = quarter.transformed(&t).eval(0.4);
    /// assert!(((p.x / 3.0).powi(2) + (p.y / 2.0).powi(2) - 1.0).abs() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn transformed(&self, t: &Transform<f64, TAffine, D>) -> Self
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        self.try_transformed(t).unwrap_or_else(|_| {
            RationalBezier::new(
                saturated_images(Matrix::of_unchecked(t), self.points()),
                self.weights().to_vec(),
            )
            .unwrap_or_else(|_| self.clone())
        })
    }

    /// As [`transformed`](Self::transformed), with the errors reported.
    ///
    /// ```
    /// use revolve::{Error, RationalBezier};
    /// use revolve::nalgebra::{Affine2, Matrix3, Point2};
    ///
    /// let c = RationalBezier::new(vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0)], vec![1.0, 2.0])?;
    /// let bad = Affine2::from_matrix_unchecked(Matrix3::new(f64::NAN, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0));
    /// assert_eq!(c.try_transformed(&bad), Err(Error::InvalidTransform));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Bezier::try_transformed`].
    pub fn try_transformed(&self, t: &Transform<f64, TAffine, D>) -> Result<Self, Error>
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        RationalBezier::new(
            affine_images(Matrix::of(t), self.points())?,
            self.weights().to_vec(),
        )
    }
}

impl<const D: usize> BSpline<D> {
    /// The image of the curve under the affine map `x ↦ Ax + b`: the same
    /// degree and knots, the mapped control points (the basis functions sum
    /// to one on the domain), so `C′(s) = T(C(s))` for every `s`.
    ///
    #[doc = fallback_doc!()]
    ///
    /// ```
    /// use revolve::{BSpline, Curve};
    /// use revolve::nalgebra::{Isometry2, Point2, Vector2, convert};
    ///
    /// let c = BSpline::clamped(2, vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0), Point2::new(3.0, 2.0), Point2::new(4.0, 0.0)])?;
    /// // A rotation by 0.3 rad and a translation, as an affine transform.
    /// let t = convert(Isometry2::new(Vector2::new(1.0, -2.0), 0.3));
    /// let image = c.transformed(&t);
    /// assert_eq!(image.knots(), c.knots());
    /// assert!((image.eval(0.6) - t * c.eval(0.6)).norm() < 1e-14);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn transformed(&self, t: &Transform<f64, TAffine, D>) -> Self
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        self.try_transformed(t).unwrap_or_else(|_| {
            let points = saturated_images(Matrix::of_unchecked(t), self.points());
            BSpline::new(self.degree(), self.knots().to_vec(), points)
                .unwrap_or_else(|_| self.clone())
        })
    }

    /// As [`transformed`](Self::transformed), with the errors reported.
    ///
    /// ```
    /// use revolve::{BSpline, Error};
    /// use revolve::nalgebra::{Affine2, Matrix3, Point2};
    ///
    /// let c = BSpline::clamped(1, vec![Point2::new(0.0, 0.0), Point2::new(1.0, 2.0)])?;
    /// let huge = Affine2::from_matrix_unchecked(Matrix3::new(1.0, 0.0, 1e200, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0));
    /// assert!(matches!(c.try_transformed(&huge), Err(Error::CoordinateTooLarge { index: 0, .. })));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Bezier::try_transformed`], with the errors of
    /// [`BSpline::new`] for the image.
    pub fn try_transformed(&self, t: &Transform<f64, TAffine, D>) -> Result<Self, Error>
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        BSpline::new(
            self.degree(),
            self.knots().to_vec(),
            affine_images(Matrix::of(t), self.points())?,
        )
    }
}

impl<const D: usize> Nurbs<D> {
    /// The image of the curve under the affine map `x ↦ Ax + b`: the same
    /// degree, knots and weights, the mapped control points, so
    /// `C′(s) = T(C(s))` for every `s`.
    ///
    #[doc = fallback_doc!()]
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::{Affine2, Matrix3, Point2};
    ///
    /// let circle = Nurbs::circle(Point2::origin(), 1.0)?;
    /// let t = Affine2::from_matrix_unchecked(Matrix3::new(3.0, 0.0, 1.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0));
    /// let ellipse = circle.transformed(&t);
    /// assert_eq!(ellipse.weights(), circle.weights());
    /// let p = ellipse.eval(0.3);
    /// assert!((((p.x - 1.0) / 3.0).powi(2) + (p.y / 2.0).powi(2) - 1.0).abs() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn transformed(&self, t: &Transform<f64, TAffine, D>) -> Self
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        self.try_transformed(t).unwrap_or_else(|_| {
            let points = saturated_images(Matrix::of_unchecked(t), self.points());
            Nurbs::new(
                self.degree(),
                self.knots().to_vec(),
                points,
                self.weights().to_vec(),
            )
            .unwrap_or_else(|_| self.clone())
        })
    }

    /// As [`transformed`](Self::transformed), with the errors reported.
    ///
    /// ```
    /// use revolve::{Error, Nurbs};
    /// use revolve::nalgebra::{Affine2, Matrix3, Point2};
    ///
    /// let circle = Nurbs::circle(Point2::origin(), 1.0)?;
    /// let bad = Affine2::from_matrix_unchecked(Matrix3::new(1.0, f64::INFINITY, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0));
    /// assert_eq!(circle.try_transformed(&bad), Err(Error::InvalidTransform));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// As [`Bezier::try_transformed`], with the errors of
    /// [`Nurbs::new`] for the image.
    pub fn try_transformed(&self, t: &Transform<f64, TAffine, D>) -> Result<Self, Error>
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        let points = affine_images(Matrix::of(t), self.points())?;
        Nurbs::new(
            self.degree(),
            self.knots().to_vec(),
            points,
            self.weights().to_vec(),
        )
    }

    /// The image of the curve under the projective map with matrix
    /// `M = [[A, b], [hᵀ, h₀]]`, `x ↦ (Ax + b)/(h·x + h₀)`, as a NURBS curve:
    /// the homogeneous control points `wᵢ(Pᵢ, 1)` are mapped by `M`, giving
    /// the points `Qᵢ = (APᵢ + b)/dᵢ` with `dᵢ = h·Pᵢ + h₀` and the weights
    /// `wᵢ·dᵢ`; same degree and knots. Then `C′(s) = T(C(s))` for every `s`
    /// (exact, but for the rounding of mapping each point).
    ///
    /// The image is a curve with positive weights when every `dᵢ > 0`; since
    /// `M` and `−M` are the same projective map, every `dᵢ < 0` is accepted
    /// too (`M` is negated). Then the curve's own denominator `h·C + h₀` is a
    /// positive combination of the `dᵢ` and never vanishes: the curve stays
    /// away from the plane at infinity. An affine `M` gives
    /// [`transformed`](Self::transformed)'s curve.
    ///
    /// ```
    /// use revolve::{Curve, Nurbs};
    /// use revolve::nalgebra::{Matrix3, Point2, Projective2};
    ///
    /// let circle = Nurbs::circle(Point2::new(0.0, 0.0), 1.0)?;
    /// // A perspective map x ↦ x / (0.2·x + 2): the circle goes to an ellipse.
    /// let m = Projective2::from_matrix_unchecked(Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.2, 0.0, 2.0));
    /// let image = circle.transformed_projective(&m)?;
    /// for k in 0..=10 {
    ///     let s = k as f64 / 10.0;
    ///     assert!((image.eval(s) - m * circle.eval(s)).norm() < 1e-15);
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidTransform`] for a NaN or infinite matrix entry;
    /// [`Error::ProjectiveWeightNotPositive`] when the `dᵢ` are not all of
    /// one sign (or one is zero): the control polygon meets the plane at
    /// infinity; [`Error::NonFinitePoint`] or [`Error::CoordinateTooLarge`]
    /// for an image point that overflows or lies beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE); the other errors of
    /// [`Nurbs::new`] for the image (the weights' ratio beyond
    /// [`MAX_WEIGHT_RATIO`](crate::curve::MAX_WEIGHT_RATIO), derivative
    /// overflow).
    pub fn transformed_projective(&self, t: &Transform<f64, TProjective, D>) -> Result<Self, Error>
    where
        Const<D>: DimNameAdd<U1>,
        DefaultAllocator: Allocator<DimNameSum<Const<D>, U1>, DimNameSum<Const<D>, U1>>,
    {
        let m = Matrix::of(t)?;
        projective_image(&m, self)
    }
}

/// The points `(APᵢ + b)/dᵢ` and weights `wᵢdᵢ`, `dᵢ = h·Pᵢ + h₀`, of the
/// projective image (all `dᵢ` negated when all are negative).
///
/// # Errors
/// [`Error::ProjectiveWeightNotPositive`] for a weight that is not positive.
#[allow(clippy::type_complexity)]
fn projective_parts<const D: usize>(
    m: &Matrix<D>,
    points: &[Point<f64, D>],
    weights: &[f64],
) -> Result<(Vec<Point<f64, D>>, Vec<f64>), Error> {
    let denominators: Vec<f64> = points.iter().map(|p| m.denominator(p)).collect();
    let sign = if denominators.iter().all(|&d| d < 0.0) {
        -1.0
    } else {
        1.0
    };
    let mut images = Vec::with_capacity(denominators.len());
    let mut new_weights = Vec::with_capacity(denominators.len());
    for (index, ((p, &w), &d)) in points.iter().zip(weights).zip(&denominators).enumerate() {
        let d = sign * d;
        let weight = w * d;
        if weight.is_nan() || weight <= 0.0 {
            return Err(Error::ProjectiveWeightNotPositive { index, weight });
        }
        images.push(Point::from(m.affine(p) * sign / d));
        new_weights.push(weight);
    }
    Ok((images, new_weights))
}

/// The NURBS of the projective image, with the curve's degree and knots.
fn projective_image<const D: usize>(m: &Matrix<D>, curve: &Nurbs<D>) -> Result<Nurbs<D>, Error> {
    let (points, weights) = projective_parts(m, curve.points(), curve.weights())?;
    validate_points(&points)?;
    Nurbs::new(curve.degree(), curve.knots().to_vec(), points, weights)
}
