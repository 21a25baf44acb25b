//! Ruled surfaces between two NURBS curves ([`NurbsSurface::ruled`]), and
//! the curve compatibility they need (one degree, one knot vector).

use super::NurbsSurface;
use crate::{Curve, Error, Nurbs};
use nalgebra::Point3;

/// Interior knots of the second curve closer than this (relative to the
/// domain's length) to one of the first curve's are taken as that knot.
const SNAP: f64 = 64.0 * f64::EPSILON;

/// The same curve with clamped knots: the domain's ends inserted up to
/// multiplicity `p` (Boehm; exact), the control points and knots that only
/// act outside the domain dropped, and the outermost knots set to the
/// domain's ends (they only shape basis functions outside it).
pub(crate) fn clamped_curve(c: &Nurbs<3>) -> Result<Nurbs<3>, Error> {
    let p = c.degree();
    let (a, b) = c.domain();
    let multiplicity = |k: &[f64], x: f64| k.iter().filter(|&&t| t == x).count();
    let k = c.knots();
    let clamped =
        multiplicity(&k[..=p], a) == p + 1 && multiplicity(&k[k.len() - p - 1..], b) == p + 1;
    if clamped {
        return Ok(c.clone());
    }
    let mut curve = c.clone();
    for end in [a, b] {
        let times = p.saturating_sub(multiplicity(curve.knots(), end));
        if times > 0 {
            curve = curve.insert_knot(end, times)?;
        }
    }
    let k = curve.knots();
    let (Some(last_a), Some(first_b)) = (
        k.iter().rposition(|&t| t == a),
        k.iter().position(|&t| t == b),
    ) else {
        // Insertion keeps the domain's ends as knots.
        return Err(Error::EmptyDomain { start: a, end: b });
    };
    let start = last_a.saturating_sub(p);
    let mut knots = k[start..=first_b + p].to_vec();
    let n = knots.len();
    knots[0] = a;
    knots[n - 1] = b;
    let points = curve.points()[start..first_b].to_vec();
    let weights = curve.weights()[start..first_b].to_vec();
    Nurbs::new(p, knots, points, weights)
}

/// The curve with its weights divided by the largest (a polynomial curve's
/// become all 1).
fn unit_weights(c: &Nurbs<3>) -> Result<Nurbs<3>, Error> {
    let max = c.weights().iter().fold(0.0_f64, |m, &w| m.max(w));
    let weights = c.weights().iter().map(|&w| w / max).collect();
    Nurbs::new(c.degree(), c.knots().to_vec(), c.points().to_vec(), weights)
}

/// The distinct values of `knots` strictly inside `(a, b)` with their
/// multiplicities.
fn interior_knots(knots: &[f64], (a, b): (f64, f64)) -> Vec<(f64, usize)> {
    knots
        .chunk_by(|x, y| x == y)
        .filter(|run| run[0] > a && run[0] < b)
        .map(|run| (run[0], run.len()))
        .collect()
}

/// `c` with every interior knot of `other` inserted up to `other`'s
/// multiplicity of it.
fn insert_missing(c: &Nurbs<3>, other: &[f64], domain: (f64, f64)) -> Result<Nurbs<3>, Error> {
    let mut c = c.clone();
    for (x, m) in interior_knots(other, domain) {
        let have = c.knots().iter().filter(|&&t| t == x).count();
        if m > have {
            c = c.insert_knot(x, m - have)?;
        }
    }
    Ok(c)
}

/// Two curves made compatible for a tensor product (see
/// [`NurbsSurface::ruled`]): clamped, raised to the higher degree, `b`
/// reparametrized linearly onto `a`'s domain, the knots merged.
pub(crate) fn compatible(a: &Nurbs<3>, b: &Nurbs<3>) -> Result<(Nurbs<3>, Nurbs<3>), Error> {
    let (mut a, mut b) = (clamped_curve(a)?, clamped_curve(b)?);
    let p = a.degree().max(b.degree());
    if a.degree() < p {
        a = a.elevate_degree(p - a.degree())?;
    }
    if b.degree() < p {
        b = b.elevate_degree(p - b.degree())?;
    }
    let (a0, a1) = a.domain();
    let (b0, b1) = b.domain();
    let scale = (a1 - a0) / (b1 - b0);
    let snap = SNAP * (a1 - a0);
    let a_interior = interior_knots(a.knots(), (a0, a1));
    let kb = b.knots();
    let n = kb.len();
    let mapped: Vec<f64> = kb
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            if i <= p {
                a0
            } else if i >= n - p - 1 {
                a1
            } else {
                let x = (a0 + (t - b0) * scale).clamp(a0, a1);
                a_interior
                    .iter()
                    .map(|&(k, _)| k)
                    .find(|&k| (k - x).abs() <= snap)
                    .unwrap_or(x)
            }
        })
        .collect();
    let b = Nurbs::new(p, mapped, b.points().to_vec(), b.weights().to_vec())?;
    let a_merged = insert_missing(&a, b.knots(), (a0, a1))?;
    let b_merged = insert_missing(&b, a.knots(), (a0, a1))?;
    if a_merged.knots() != b_merged.knots() {
        return Err(Error::KnotCount {
            expected: a_merged.knots().len(),
            found: b_merged.knots().len(),
        });
    }
    Ok((a_merged, b_merged))
}

impl NurbsSurface {
    /// The ruled surface between the curves `a` (at `v = 0`) and `b` (at
    /// `v = 1`): degree 1 in `v` on the knots `[0, 0, 1, 1]`, each isocurve
    /// `u = const` the straight segment from `A(u)` to `B(u)`.
    ///
    /// The curves are first made compatible (Piegl & Tiller, *The NURBS
    /// Book*, §8.4), each step exact: both clamped (their domain ends
    /// inserted up to multiplicity `p`, the control points outside
    /// dropped), the lower degree raised to the higher
    /// ([`Nurbs::elevate_degree`]), `b` reparametrized linearly onto `a`'s
    /// domain (its knots mapped by `t ↦ a₀ + (t − b₀)(a₁ − a₀)/(b₁ − b₀)`,
    /// which is `B` at the mapped parameter; an interior knot that lands
    /// within `64ε` of the domain's length of one of `a`'s is taken as
    /// that knot), then each curve gets the other's interior knots
    /// ([`Nurbs::insert_knot`]). Each curve's weights are divided by its
    /// largest. The grid is `points[i] = [Aᵢ, Bᵢ]` with weights
    /// `[wᴬᵢ, wᴮᵢ]`, so `u` is `a`'s parameter and
    ///
    /// `S(u, v) = ((1 − v)W_A A(u) + v W_B B(φ(u))) / ((1 − v)W_A + v W_B)`
    ///
    /// with `W_A`, `W_B` the curves' weight functions and `φ` the linear
    /// map of `a`'s domain onto `b`'s. That is `A + ρ(B − A)` with
    /// `ρ = vW_B/((1 − v)W_A + vW_B)`: on the segment, and linear in `v`
    /// (`ρ = v`, `S = (1 − v)A(u) + vB(φ(u))`) where the weights agree,
    /// as for polynomial curves (all weights 1 after the division).
    ///
    /// # Errors
    /// The errors of [`Nurbs::insert_knot`], [`Nurbs::elevate_degree`]
    /// ([`Error::ElevationTooHigh`], [`Error::ElevationInexact`]) and
    /// [`Nurbs::new`] on the compatible curves, then those of
    /// [`NurbsSurface::new`] on the grid (e.g. [`Error::WeightRatioTooLarge`]
    /// when the two curves' weights together span too wide a range).
    ///
    /// ```
    /// use revolve::{BSpline, Nurbs, NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// // Two skew lines: the hyperbolic paraboloid z = x·y.
    /// let line = |p: Point3<f64>, q: Point3<f64>| -> Result<Nurbs<3>, revolve::Error> {
    ///     Ok(Nurbs::from(BSpline::clamped(1, vec![p, q])?))
    /// };
    /// let a = line(Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0))?;
    /// let b = line(Point3::new(0.0, 1.0, 0.0), Point3::new(1.0, 1.0, 1.0))?;
    /// let s = NurbsSurface::ruled(&a, &b)?;
    /// let p = s.eval(0.3, 0.6);
    /// assert!((p - Point3::new(0.3, 0.6, 0.18)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    pub fn ruled(a: &Nurbs<3>, b: &Nurbs<3>) -> Result<NurbsSurface, Error> {
        let (a, b) = compatible(a, b)?;
        let (a, b) = (unit_weights(&a)?, unit_weights(&b)?);
        let points: Vec<Vec<Point3<f64>>> = a
            .points()
            .iter()
            .zip(b.points())
            .map(|(&p, &q)| vec![p, q])
            .collect();
        let weights = a
            .weights()
            .iter()
            .zip(b.weights())
            .map(|(&w, &z)| vec![w, z])
            .collect();
        NurbsSurface::new(
            (a.degree(), 1),
            (a.knots().to_vec(), vec![0.0, 0.0, 1.0, 1.0]),
            points,
            weights,
        )
    }

    /// The bilinear patch through four corners (the "four-point surface"):
    /// `S(u, v) = (1 − u)(1 − v)·p00 + u(1 − v)·p10 + (1 − u)v·p01 + uv·p11`
    /// on `[0, 1]²`, degree 1 in both parameters, weights 1. It is the
    /// ruled surface between the segments `p00 p10` and `p01 p11`; four
    /// coplanar corners give a flat quadrilateral, otherwise a hyperbolic
    /// paraboloid.
    ///
    /// ```
    /// use revolve::{NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// let s = NurbsSurface::bilinear(
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(1.0, 0.0, 0.0),
    ///     Point3::new(0.0, 1.0, 0.0), Point3::new(1.0, 1.0, 1.0),
    /// )?;
    /// assert!((s.eval(0.3, 0.6) - Point3::new(0.3, 0.6, 0.18)).norm() < 1e-15);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// The errors of [`NurbsSurface::new`] for the corners
    /// ([`Error::NonFiniteGridPoint`], [`Error::GridCoordinateTooLarge`]).
    pub fn bilinear(
        p00: Point3<f64>,
        p10: Point3<f64>,
        p01: Point3<f64>,
        p11: Point3<f64>,
    ) -> Result<NurbsSurface, Error> {
        let ends = vec![0.0, 0.0, 1.0, 1.0];
        NurbsSurface::new(
            (1, 1),
            (ends.clone(), ends),
            vec![vec![p00, p01], vec![p10, p11]],
            vec![vec![1.0; 2]; 2],
        )
    }
}
