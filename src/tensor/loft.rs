//! Lofted (skinned) surfaces: a NURBS surface through a sequence of section
//! curves (Piegl & Tiller, *The NURBS Book*, §10.3). The sections are made
//! compatible (clamped, one domain, one degree, one knot vector), then
//! their homogeneous control points are interpolated across the sections.

use super::NurbsSurface;
use crate::curve::{Interpolation, first_short_step, length, normalized_sums};
use crate::{Curve, Error, Nurbs};
use nalgebra::{Point3, Vector3, Vector4};

impl NurbsSurface {
    /// The NURBS surface through the section curves `curves`, in order:
    /// `S(u, v̄ₖ) = curves[k](u)` (after the reparametrization below), `u`
    /// along each curve and `v` across them with degree `degree_v`.
    ///
    /// # Method
    /// 1. Each curve is clamped: its domain's ends are inserted to full
    ///    multiplicity (Boehm's insertion; the curve is unchanged) and the
    ///    knots and control points beyond them dropped.
    /// 2. Each curve is reparametrized linearly onto the first curve's
    ///    domain `[a, b]`: a curve on `[c, d]` becomes
    ///    `t ↦ C(c + (t − a)(d − c)/(b − a))`, its knots mapped by the
    ///    inverse (the ends exactly). So `u` runs over `[a, b]` and the
    ///    same `u` is the same fraction of every section's domain.
    /// 3. Each curve is raised to the highest degree among them
    ///    ([`Nurbs::elevate_degree`]).
    /// 4. Each curve gets the union of the interior knots, each with the
    ///    largest multiplicity it has in any curve ([`Nurbs::insert_knot`]).
    ///    Knots of different curves closer than rounding can resolve
    ///    (`4ε ×` the domain's length) count as one, at the smallest of
    ///    them.
    /// 5. Each curve's weights are divided by its largest weight (the same
    ///    curve), so that all are 1 for polynomial sections.
    /// 6. Parameters across the sections: `dₖ`, the mean over `i` of the
    ///    distance `|Pᵢ⁽ᵏ⁾ − Pᵢ⁽ᵏ⁻¹⁾|` between the control points of
    ///    sections `k − 1` and `k`; then centripetal, `v̄₀ = 0`,
    ///    `v̄ₖ − v̄ₖ₋₁ ∝ √dₖ`, `v̄_{K−1} = 1`. Knots in `v` by averaging
    ///    (Piegl & Tiller eq. 9.8).
    /// 7. For each `i`, the homogeneous control points `(wᵢ⁽ᵏ⁾Pᵢ⁽ᵏ⁾, wᵢ⁽ᵏ⁾)`
    ///    of the sections are interpolated at the `v̄ₖ` by a spline of degree
    ///    `degree_v` (as in [`BSpline::interpolate`](crate::BSpline::interpolate)),
    ///    whose control values `(wP, w)` give row `i` of the surface's grid.
    ///
    /// The surface's grid is `points[i][j]` with `i` along `u` (the sections'
    /// control points) and `j` along `v`; its domain is `[a, b] × [0, 1]`.
    /// Equal sections apart from a translation give a translational sweep:
    /// circles of equal radius along an axis give an exact cylinder, and
    /// with `degree_v = 1` each strip between two sections is ruled
    /// (circles of linearly varying radius give a cone).
    ///
    /// # Edge rules
    /// - Sections need not be clamped, share a domain, a degree or knots;
    ///   their orientation is taken as given (reverse one with
    ///   [`Nurbs::reversed`] to flip it).
    /// - With `degree_v ≥ 2`, the interpolated weights can dip to zero or
    ///   below between sections whose weights at the same control point
    ///   differ a lot (a weight of `10⁻³` between weights 1): that is
    ///   [`Error::InvalidGridWeight`], never a surface with a pole.
    ///   Polynomial sections (weights all 1) never meet it.
    ///
    /// ```
    /// use revolve::{Nurbs, NurbsSurface, Surface};
    /// use revolve::nalgebra::Point3;
    ///
    /// // Three straight sections at heights 0, 1, 3, quadratic across them.
    /// let line = |y: f64, z: f64| {
    ///     Nurbs::new(1, vec![0.0, 0.0, 1.0, 1.0],
    ///                vec![Point3::new(0.0, y, z), Point3::new(2.0, y, z)], vec![1.0, 1.0])
    /// };
    /// let curves = [line(0.0, 0.0)?, line(0.5, 1.0)?, line(1.0, 3.0)?];
    /// let s = NurbsSurface::loft(&curves, 2)?;
    /// assert_eq!(s.degrees(), (1, 2));
    /// assert!((s.eval(0.25, 0.0) - Point3::new(0.5, 0.0, 0.0)).norm() < 1e-15);
    /// assert!((s.eval(1.0, 1.0) - Point3::new(2.0, 1.0, 3.0)).norm() < 1e-15);
    /// // Linear along u (in x), quadratic across the sections (in v).
    /// let p = s.eval(0.5, 0.5);
    /// assert!((p.x - 1.0).abs() < 1e-15 && p.z > 0.0 && p.z < 3.0);
    /// # Ok::<(), revolve::Error>(())
    /// ```
    ///
    /// # Errors
    /// In the order checked: [`Error::ZeroDegree`] (`degree_v = 0`);
    /// [`Error::TooFewSections`] (fewer than `max(2, degree_v + 1)`
    /// curves); the errors of [`Nurbs::insert_knot`],
    /// [`Nurbs::elevate_degree`] (e.g. [`Error::ElevationTooHigh`] beyond
    /// [`MAX_ELEVATED_DEGREE`](crate::curve::MAX_ELEVATED_DEGREE)) and
    /// [`Nurbs::new`] while making the curves compatible;
    /// [`Error::CoincidentSections`] (two consecutive sections with the same
    /// control points once compatible); [`Error::SingularSystem`]
    /// (rounding only); [`Error::InvalidGridWeight`] when the interpolated
    /// weights are not positive (sections whose weights differ wildly);
    /// then the errors of [`new`](Self::new) for the result.
    pub fn loft(curves: &[Nurbs<3>], degree_v: usize) -> Result<NurbsSurface, Error> {
        if degree_v == 0 {
            return Err(Error::ZeroDegree);
        }
        if curves.len() < degree_v.saturating_add(1).max(2) {
            return Err(Error::TooFewSections {
                sections: curves.len(),
                degree: degree_v,
            });
        }
        let (degree_u, knots_u, sections) = compatible(curves)?;
        let params = section_parameters(&sections)?;
        let across = Interpolation::new(degree_v, &params)?;
        let n = knots_u.len() - degree_u - 1;
        let k = sections.len();
        let mut points = vec![vec![Point3::origin(); k]; n];
        let mut weights = vec![vec![1.0; k]; n];
        for i in 0..n {
            let values: Vec<Vector4<f64>> = sections
                .iter()
                .map(|(p, w)| {
                    let wp = p[i].coords * w[i];
                    Vector4::new(wp.x, wp.y, wp.z, w[i])
                })
                .collect();
            for (j, h) in across.solve(&values).into_iter().enumerate() {
                let w = h.w;
                if !w.is_finite() || w <= 0.0 {
                    return Err(Error::InvalidGridWeight {
                        row: i,
                        column: j,
                        weight: w,
                    });
                }
                points[i][j] = Point3::from(h.xyz() / w);
                weights[i][j] = w;
            }
        }
        NurbsSurface::new(
            (degree_u, degree_v),
            (knots_u, across.knots().to_vec()),
            points,
            weights,
        )
    }
}

/// One section after [`compatible`]: control points and weights (largest
/// weight 1) on the common knot vector.
type Section = (Vec<Point3<f64>>, Vec<f64>);

/// The curves made compatible (steps 1–4 of [`NurbsSurface::loft`]): the
/// common degree and knot vector, and each curve's control points and
/// weights on them.
fn compatible(curves: &[Nurbs<3>]) -> Result<(usize, Vec<f64>, Vec<Section>), Error> {
    let domain = curves[0].domain();
    let degree = curves.iter().map(Nurbs::degree).max().unwrap_or(1);
    let mut prepared = Vec::with_capacity(curves.len());
    for curve in curves {
        let clamped = clamp(curve)?;
        let moved = reparametrized(&clamped, domain)?;
        prepared.push(moved.elevate_degree(degree - moved.degree())?);
    }
    let clusters = knot_union(&prepared, degree, domain);
    let mut common: Option<Vec<f64>> = None;
    let mut sections = Vec::with_capacity(prepared.len());
    for curve in prepared {
        let mut curve = curve;
        for &(value, multiplicity, tol) in &clusters {
            let (existing, own) = cluster_count(curve.knots(), value, tol);
            if multiplicity > existing {
                curve = curve.insert_knot(own.unwrap_or(value), multiplicity - existing)?;
            }
        }
        // Every knot moved onto its cluster's value: the same vector for all
        // curves (a change by rounding only).
        let knots: Vec<f64> = curve
            .knots()
            .iter()
            .map(|&t| {
                clusters
                    .iter()
                    .find(|&&(value, _, tol)| (t - value).abs() <= tol)
                    .map_or(t, |&(value, _, _)| value)
            })
            .collect();
        match &common {
            None => common = Some(knots),
            Some(c) if c.len() != knots.len() => {
                // Cannot happen (each cluster ends with the same
                // multiplicity in every curve); refuse rather than guess.
                return Err(Error::KnotCount {
                    expected: c.len(),
                    found: knots.len(),
                });
            }
            Some(_) => {}
        }
        let max_w = curve.weights().iter().fold(0.0_f64, |m, &w| m.max(w));
        let weights = curve.weights().iter().map(|&w| w / max_w).collect();
        sections.push((curve.points().to_vec(), weights));
    }
    let knots = common.unwrap_or_default();
    Ok((degree, knots, sections))
}

/// The curve with its domain's ends at full multiplicity and nothing
/// beyond them (the same curve).
fn clamp(curve: &Nurbs<3>) -> Result<Nurbs<3>, Error> {
    let p = curve.degree();
    let (a, b) = curve.domain();
    let mut c = curve.clone();
    for end in [a, b] {
        let count = c.knots().iter().filter(|&&t| t == end).count();
        if count < p + 1 {
            c = c.insert_knot(end, p + 1 - count)?;
        }
    }
    let knots = c.knots();
    let first = knots.iter().position(|&t| t == a).unwrap_or(0);
    let last = knots
        .iter()
        .rposition(|&t| t == b)
        .unwrap_or(knots.len() - 1);
    if first == 0 && last == knots.len() - 1 {
        return Ok(c);
    }
    // Basis functions 0 … first − 1 vanish on [a, b] (a has multiplicity
    // p + 1), and so do the last (len − 1 − last) ones.
    let dropped_end = knots.len() - 1 - last;
    let n = c.points().len();
    Nurbs::new(
        p,
        knots[first..=last].to_vec(),
        c.points()[first..n - dropped_end].to_vec(),
        c.weights()[first..n - dropped_end].to_vec(),
    )
}

/// The clamped curve on `[a, b]`, reparametrized linearly from its domain
/// `[c, d]`: knot `t ↦ a + (t − c)(b − a)/(d − c)`, the ends exactly.
fn reparametrized(curve: &Nurbs<3>, (a, b): (f64, f64)) -> Result<Nurbs<3>, Error> {
    let (c, d) = curve.domain();
    if (c, d) == (a, b) {
        return Ok(curve.clone());
    }
    let knots = curve
        .knots()
        .iter()
        .map(|&t| {
            if t <= c {
                a
            } else if t >= d {
                b
            } else {
                let s = (t - c) / (d - c);
                (a + s * (b - a)).clamp(a, b)
            }
        })
        .collect();
    Nurbs::new(
        curve.degree(),
        knots,
        curve.points().to_vec(),
        curve.weights().to_vec(),
    )
}

/// The union of the interior knots of `curves` (all on the domain
/// `(a, b)`): `(value, multiplicity, tolerance)` per cluster of knots
/// closer than `4ε (b − a)` to the cluster's smallest value, with the
/// largest multiplicity any curve gives the cluster.
fn knot_union(curves: &[Nurbs<3>], degree: usize, (a, b): (f64, f64)) -> Vec<(f64, usize, f64)> {
    let tol = 4.0 * f64::EPSILON * (b - a);
    let mut all: Vec<f64> = curves
        .iter()
        .flat_map(|c| c.knots().iter().copied())
        .filter(|&t| t > a && t < b)
        .collect();
    all.sort_by(f64::total_cmp);
    let mut clusters: Vec<(f64, usize, f64)> = Vec::new();
    for t in all {
        match clusters.last() {
            Some(&(value, _, _)) if t - value <= tol => {}
            _ => clusters.push((t, 0, tol)),
        }
    }
    for cluster in &mut clusters {
        let most = curves
            .iter()
            .map(|c| cluster_count(c.knots(), cluster.0, tol).0)
            .max()
            .unwrap_or(0);
        cluster.1 = most.min(degree + 1);
    }
    clusters
}

/// How many of `knots` lie within `tol` of `value`, and one of them.
fn cluster_count(knots: &[f64], value: f64, tol: f64) -> (usize, Option<f64>) {
    let mut count = 0;
    let mut own = None;
    for &t in knots {
        if (t - value).abs() <= tol {
            count += 1;
            own = Some(t);
        }
    }
    (count, own)
}

/// The centripetal parameters across the sections: steps `√dₖ`, `dₖ` the
/// mean distance between corresponding control points.
fn section_parameters(sections: &[Section]) -> Result<Vec<f64>, Error> {
    let mut steps = Vec::with_capacity(sections.len() - 1);
    for (k, pair) in sections.windows(2).enumerate() {
        let (before, after) = (&pair[0].0, &pair[1].0);
        let mean = before
            .iter()
            .zip(after)
            .map(|(p, q)| length::<3>(&Vector3::from(q - p)))
            .sum::<f64>()
            / before.len() as f64;
        if mean.is_nan() || mean <= 0.0 {
            return Err(Error::CoincidentSections { index: k + 1 });
        }
        steps.push(mean.sqrt());
    }
    let params = normalized_sums(&steps).ok_or(Error::CoincidentSections { index: 1 })?;
    match first_short_step(&params) {
        Some(index) => Err(Error::CoincidentSections { index }),
        None => Ok(params),
    }
}
