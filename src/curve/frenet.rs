//! The Frenet frame of a space curve: unit tangent, principal normal and
//! binormal, curvature and torsion, from the curve's exact derivatives of
//! orders 1 to 3 (do Carmo, *Differential Geometry of Curves and
//! Surfaces*, §1.5):
//!
//! `T = C′/|C′|`, `B = (C′ × C″)/|C′ × C″|`, `N = B × T`,
//! `κ = |C′ × C″|/|C′|³`, `τ = (C′ × C″)·C‴/|C′ × C″|²`.
//!
//! # Edge rules
//! The frame is `None` where it is not defined: where `C′ = 0` (no
//! tangent), where `C′ × C″` vanishes (a straight stretch or an inflection:
//! no normal), taken as `|C′ × C″| ≤ 16ε·|C′|·|C″|` (below the rounding of
//! the cross product), and where a derivative is not finite. Parameters
//! are handled as the curve's derivatives handle them: outside the domain
//! the nearest end, NaN the start; at an interior knot the derivatives
//! from the right, at the end of the domain those from the left.

use super::scaled_norm;
use crate::{BSpline, Bezier, Nurbs, RationalBezier};
use nalgebra::{Unit, Vector3};

/// The Frenet frame of a space curve at a parameter, with its curvature
/// and torsion (see the `curve::frenet` module docs for the formulas and
/// where it is `None`).
///
/// ```
/// use revolve::Nurbs;
/// use revolve::nalgebra::{Point3, Vector3};
///
/// // A circle of radius 2: curvature 1/2, torsion 0, the normal toward the centre.
/// let circle = Nurbs::arc_3d(Point3::origin(), Vector3::z(), Vector3::x(), 2.0, 0.0, 3.0)?;
/// let f = circle.frenet_frame(0.4).unwrap();
/// assert!((f.curvature - 0.5).abs() < 1e-14 && f.torsion.abs() < 1e-14);
/// assert!((f.binormal.into_inner() - Vector3::z()).norm() < 1e-14);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrenetFrame {
    /// The unit tangent `T = C′/|C′|`, toward increasing parameter.
    pub tangent: Unit<Vector3<f64>>,
    /// The principal normal `N = B × T`, toward the centre of curvature.
    pub normal: Unit<Vector3<f64>>,
    /// The binormal `B = (C′ × C″)/|C′ × C″|`.
    pub binormal: Unit<Vector3<f64>>,
    /// The curvature `κ = |C′ × C″|/|C′|³ > 0`.
    pub curvature: f64,
    /// The torsion `τ = (C′ × C″)·C‴/|C′ × C″|²`.
    pub torsion: f64,
}

impl FrenetFrame {
    /// The frame from the first three derivatives; `None` where it is not
    /// defined (module docs).
    fn from_derivatives(d1: Vector3<f64>, d2: Vector3<f64>, d3: Vector3<f64>) -> Option<Self> {
        if !(d1
            .iter()
            .chain(d2.iter())
            .chain(d3.iter())
            .all(|x| x.is_finite()))
        {
            return None;
        }
        // Scaled so that no product over- or underflows: the frame does not
        // depend on the speed's size, κ and τ are rescaled at the end.
        let m1 = d1.amax();
        let m2 = d2.amax();
        if !(m1 > 0.0 && m2 > 0.0) {
            return None;
        }
        let (u1, u2) = (d1 / m1, d2 / m2);
        let cross = u1.cross(&u2);
        let (n1, n2, nc) = (u1.norm(), u2.norm(), scaled_norm(cross));
        if nc.is_nan() || nc <= 16.0 * f64::EPSILON * n1 * n2 {
            return None;
        }
        let tangent = Unit::new_normalize(u1);
        let binormal = Unit::new_normalize(cross);
        let normal = Unit::new_normalize(binormal.cross(&tangent));
        // κ = |d1 × d2|/|d1|³ = (m2/m1²)·|u1 × u2|/|u1|³.
        let curvature = (m2 / m1 / m1) * (nc / (n1 * n1 * n1));
        // τ = (d1 × d2)·d3/|d1 × d2|² = (u1 × u2)·d3/(m1·m2·|u1 × u2|²).
        let torsion = (cross / nc).dot(&d3) / (m1 * m2 * nc);
        (curvature.is_finite() && torsion.is_finite()).then_some(FrenetFrame {
            tangent,
            normal,
            binormal,
            curvature,
            torsion,
        })
    }
}

impl Bezier<3> {
    /// The [`FrenetFrame`] at `t` from the exact hodographs of orders 1–3;
    /// `None` where `C′ = 0` or `C′ × C″ = 0` (straight: no normal), as the
    /// `curve::frenet` module docs say.
    ///
    /// ```
    /// use revolve::Bezier;
    /// use revolve::nalgebra::Point3;
    ///
    /// let c = Bezier::new(vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 0.0), Point3::new(1.0, 1.0, 1.0)])?;
    /// let f = c.frenet_frame(0.5).unwrap();
    /// assert!(f.curvature > 0.0 && f.torsion != 0.0);
    /// let line = Bezier::new(vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 2.0, 3.0)])?;
    /// assert!(line.frenet_frame(0.5).is_none());
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn frenet_frame(&self, t: f64) -> Option<FrenetFrame> {
        let d = |k| self.nth_derivative(t, k).ok();
        FrenetFrame::from_derivatives(d(1)?, d(2)?, d(3)?)
    }
}

impl BSpline<3> {
    /// The [`FrenetFrame`] at `t` from the exact derivatives of orders 1–3
    /// ([`nth_derivative`](Self::nth_derivative)); `None` where `C′ = 0` or
    /// `C′ × C″ = 0` (module `curve::frenet`).
    ///
    /// ```
    /// use revolve::BSpline;
    /// use revolve::nalgebra::Point3;
    ///
    /// let c = BSpline::clamped(3, vec![Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 0.0), Point3::new(1.0, 1.0, 1.0), Point3::new(0.0, 2.0, 1.0)])?;
    /// assert!(c.frenet_frame(0.3).unwrap().curvature > 0.0);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn frenet_frame(&self, t: f64) -> Option<FrenetFrame> {
        let d = |k| self.nth_derivative(t, k).ok();
        FrenetFrame::from_derivatives(d(1)?, d(2)?, d(3)?)
    }
}

impl Nurbs<3> {
    /// The [`FrenetFrame`] at `t` from the exact derivatives of orders 1–3
    /// ([`derivatives`](Self::derivatives), the quotient rule on the
    /// homogeneous ones); `None` where `C′ = 0` or `C′ × C″ = 0` (module
    /// `curve::frenet`).
    ///
    /// ```
    /// use revolve::Nurbs;
    /// use revolve::nalgebra::{Point3, Vector3};
    ///
    /// let arc = Nurbs::arc_3d(Point3::origin(), Vector3::new(1.0, 1.0, 0.0), Vector3::z(), 4.0, 0.0, 2.0)?;
    /// assert!((arc.frenet_frame(0.7).unwrap().curvature - 0.25).abs() < 1e-14);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn frenet_frame(&self, t: f64) -> Option<FrenetFrame> {
        let mut d = [Vector3::zeros(); 4];
        self.derivatives(t, &mut d).ok()?;
        FrenetFrame::from_derivatives(d[1], d[2], d[3])
    }
}

impl RationalBezier<3> {
    /// The [`FrenetFrame`] at `t` from the exact derivatives of orders 1–3
    /// ([`derivatives`](Self::derivatives)); `None` where `C′ = 0` or
    /// `C′ × C″ = 0` (module `curve::frenet`).
    ///
    /// ```
    /// use revolve::RationalBezier;
    /// use revolve::nalgebra::Point3;
    ///
    /// // A quarter of the unit circle in the plane z = 1: curvature 1.
    /// let h = std::f64::consts::FRAC_1_SQRT_2;
    /// let q = RationalBezier::new(vec![Point3::new(1.0, 0.0, 1.0), Point3::new(1.0, 1.0, 1.0), Point3::new(0.0, 1.0, 1.0)], vec![1.0, h, 1.0])?;
    /// let f = q.frenet_frame(0.2).unwrap();
    /// assert!((f.curvature - 1.0).abs() < 1e-14 && f.torsion.abs() < 1e-14);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn frenet_frame(&self, t: f64) -> Option<FrenetFrame> {
        let mut d = [Vector3::zeros(); 4];
        self.derivatives(t, &mut d).ok()?;
        FrenetFrame::from_derivatives(d[1], d[2], d[3])
    }
}
