//! Translational surfaces: a curve extruded along a vector
//! ([`NurbsSurface::extrude`]) or swept along a path
//! ([`NurbsSurface::sweep`]).

use super::NurbsSurface;
use crate::{Curve, Error, Nurbs};
use nalgebra::{Point3, Vector3};

impl NurbsSurface {
    /// The curve `c` extruded along `v`: `S(u, s) = C(u) + s·V` for `u` in
    /// `c`'s domain and `s ∈ [0, 1]`, exactly. Degree `(p, 1)`, knots
    /// `(c's, [0, 0, 1, 1])`, grid `points[i] = [Pᵢ, Pᵢ + V]` with weights
    /// `[wᵢ, wᵢ]`: `Σᵢ wᵢNᵢ(u)((1 − s)Pᵢ + s(Pᵢ + V)) / Σᵢ wᵢNᵢ(u)` is
    /// `C(u) + sV` since the weights do not depend on `s`. The normal is
    /// along `C′(u) × V`.
    ///
    /// # Errors
    /// [`Error::InvalidExtrusion`] when `v` has a NaN or infinite coordinate
    /// or is zero; the errors of [`NurbsSurface::new`] on the grid (e.g.
    /// [`Error::GridCoordinateTooLarge`] with the row and column of a
    /// translated point beyond [`MAX_COORDINATE`](crate::MAX_COORDINATE)).
    ///
    /// ```
    /// use revolve::{Curve, Nurbs, NurbsSurface, Surface};
    /// use revolve::nalgebra::{Point2, Point3, Vector3};
    ///
    /// // A cylinder of radius 2 and height 3: the circle in z = 0 pushed up.
    /// let c2 = Nurbs::circle(Point2::origin(), 2.0)?;
    /// let lift: Vec<Point3<f64>> = c2.points().iter().map(|p| Point3::new(p.x, p.y, 0.0)).collect();
    /// let circle = Nurbs::new(2, c2.knots().to_vec(), lift, c2.weights().to_vec())?;
    /// let s = NurbsSurface::extrude(&circle, Vector3::new(0.0, 0.0, 3.0))?;
    /// let p = s.eval(0.3, 0.5);
    /// assert!((p.x.hypot(p.y) - 2.0).abs() < 1e-14 && (p.z - 1.5).abs() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn extrude(c: &Nurbs<3>, v: Vector3<f64>) -> Result<NurbsSurface, Error> {
        if !v.iter().all(|x| x.is_finite()) || v == Vector3::zeros() {
            return Err(Error::InvalidExtrusion { vector: v });
        }
        let points = c.points().iter().map(|&p| vec![p, p + v]).collect();
        let weights = c.weights().iter().map(|&w| vec![w, w]).collect();
        NurbsSurface::new(
            (c.degree(), 1),
            (c.knots().to_vec(), vec![0.0, 0.0, 1.0, 1.0]),
            points,
            weights,
        )
    }

    /// The translational sweep of `profile` along `path`:
    /// `S(u, v) = P(u) + T(v) − T(v₀)` for `u` in the profile's domain and
    /// `v` in the path's `[v₀, v₁]`, exactly: the profile moved without
    /// turning so that its every point follows a copy of the path (at
    /// `v = v₀` the surface is the profile itself).
    ///
    /// Degrees `(p, q)` and knots of the profile and the path, grid
    /// `Qᵢⱼ = Pᵢ + Tⱼ − T(v₀)` with weights `wᵢⱼ = wᵢ·ωⱼ` (`Pᵢ`, `wᵢ` the
    /// profile's, `Tⱼ`, `ωⱼ` the path's).
    ///
    /// *Proof of exactness.* With `W(u) = Σᵢ wᵢNᵢ(u)`, `Ω(v) = Σⱼ ωⱼMⱼ(v)`
    /// (both positive), the tensor product's weight function is
    /// `Σᵢⱼ wᵢωⱼNᵢMⱼ = W·Ω`, and its numerator splits:
    /// `Σᵢⱼ wᵢωⱼNᵢMⱼ(Pᵢ + Tⱼ − T₀) = Ω·Σᵢ wᵢNᵢPᵢ + W·Σⱼ ωⱼMⱼTⱼ − WΩ·T₀`.
    /// Dividing by `WΩ` gives `Σᵢ wᵢNᵢPᵢ/W + Σⱼ ωⱼMⱼTⱼ/Ω − T₀ = P(u) + T(v) − T₀`.
    /// The product weights are what make the sums factor: with other
    /// weights on the same points the isocurves would in general be
    /// neither translated profiles nor translated paths.
    ///
    /// # Errors
    /// The errors of [`NurbsSurface::new`] on the grid:
    /// [`Error::GridCoordinateTooLarge`] (a translated point beyond
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE), its row and column),
    /// [`Error::WeightRatioTooLarge`] (the product weights spanning more
    /// than [`MAX_WEIGHT_RATIO`](crate::curve::MAX_WEIGHT_RATIO)),
    /// [`Error::DerivativeOverflow`].
    ///
    /// ```
    /// use revolve::{BSpline, Nurbs, NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// // A parabola in the xz-plane swept along a line in y.
    /// let profile = Nurbs::from(BSpline::clamped(2, vec![
    ///     Point3::new(-1.0, 0.0, 1.0), Point3::new(0.0, 0.0, -1.0), Point3::new(1.0, 0.0, 1.0),
    /// ])?);
    /// let path = Nurbs::from(BSpline::clamped(1, vec![
    ///     Point3::new(5.0, 0.0, 0.0), Point3::new(5.0, 2.0, 0.0),
    /// ])?);
    /// let s = NurbsSurface::sweep(&profile, &path)?;
    /// let p = s.eval(0.25, 0.5);
    /// assert!((p - Point3::new(-0.5, 1.0, 0.25)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn sweep(profile: &Nurbs<3>, path: &Nurbs<3>) -> Result<NurbsSurface, Error> {
        let start = path.eval(path.domain().0);
        let offsets: Vec<Vector3<f64>> = path.points().iter().map(|t| t - start).collect();
        let points: Vec<Vec<Point3<f64>>> = profile
            .points()
            .iter()
            .map(|&p| offsets.iter().map(|&d| p + d).collect())
            .collect();
        let weights = profile
            .weights()
            .iter()
            .map(|&w| path.weights().iter().map(|&z| w * z).collect())
            .collect();
        NurbsSurface::new(
            (profile.degree(), path.degree()),
            (profile.knots().to_vec(), path.knots().to_vec()),
            points,
            weights,
        )
    }
}
