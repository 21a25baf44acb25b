//! Spline curves: `RevSurface` profiles and curves drawn as tubes.
//!
//! ```text
//! BezierCurve  { controls [x y z] [x y z] … }   one Bézier curve of degree count − 1
//! BsplineCurve { controls [x y z] [x y z] … }   cubic B-spline, uniform knots i/(n+3)
//! NurbsCurve   { degree p  knots k0 k1 …  controls [x y z w] [x y z] … }
//!                                              rational B-spline; w the weight (1 if left out)
//! RevSurface   { profile BezierCurve {…} | profile BsplineCurve {…} | profile NurbsCurve {…} }
//! ```
//!
//! A `RevSurface` profile lies in the `z = 0` plane and turns about the `y`
//! axis; its points are used as `(x, y)`. A curve directly in a group becomes a
//! thin tube along its flattening (tolerance `10⁻³` of the control points'
//! extent, radius `10⁻²` of it but at least `0.001`).
//!
//! A `NurbsCurve`'s control point `[x y z w]` is the point `(x, y, z)` with
//! weight `w` (not premultiplied); its keys come in any order and all three
//! are required. `knots` is the whole knot vector, `points + degree + 1`
//! numbers.
//!
//! revolve's own checks (too few control points, coordinates too large, a
//! wrong knot count, decreasing knots, a weight that is not positive) are
//! reported with revolve's message, at the item the message names (the
//! control point's `[`, the weight, the knot, or the `knots` keyword for a
//! wrong count), else at the curve's keyword.

use std::sync::Arc;

use revolve::nalgebra::{Point2, Point3};
use revolve::{BSpline, Bezier, Error, Flattening, Nurbs, NurbsSurface, Revolution};

use super::cursor::{Cursor, Result};
use super::lexer::{Kind, Pos, Token};
use crate::scene::{RevolutionBody, Shape, SurfaceBody, Tube};

/// The curve keywords.
pub(super) const CURVES: &[&str] = &["BezierCurve", "BsplineCurve", "NurbsCurve"];

/// Tube flattening tolerance, relative to the control points' extent.
const TUBE_TOLERANCE: f64 = 1e-3;
/// Tube radius, relative to the control points' extent.
const TUBE_RADIUS: f64 = 1e-2;
/// The smallest tube radius.
const MIN_TUBE_RADIUS: f64 = 1e-3;

/// One control point as written (of a curve or a surface).
pub(super) struct Control {
    pub(super) point: Point3<f64>,
    /// Where its `[` is.
    pub(super) at: Pos,
    /// Its weight and where the weight is (a point written with four
    /// numbers).
    pub(super) weight: Option<(f64, Pos)>,
}

impl Control {
    /// The weight, 1 when left out.
    pub(super) fn weight(&self) -> f64 {
        self.weight.map_or(1.0, |(w, _)| w)
    }
}

/// A curve block as written.
struct CurveBlock {
    /// The curve's keyword (one of [`CURVES`]) and where it is.
    name: &'static str,
    at: Pos,
    controls: Vec<Control>,
    /// A `NurbsCurve`'s degree.
    degree: usize,
    /// A `NurbsCurve`'s knots, each with its position.
    knots: Vec<(f64, Pos)>,
    /// Where the `knots` keyword is.
    knots_at: Pos,
}

/// Reads the curve block after its keyword `keyword` (one of [`CURVES`]).
fn curve_block(c: &mut Cursor<'_>, keyword: Token<'_>) -> Result<CurveBlock> {
    let name = CURVES
        .iter()
        .copied()
        .find(|&n| n == keyword.text)
        .unwrap_or("curve");
    let nurbs = name == "NurbsCurve";
    let keys: &[&str] = if nurbs {
        &["degree", "knots", "controls"]
    } else {
        &["controls"]
    };
    let open = c.open(name)?;
    let (mut controls, mut degree, mut knots) = (None, None, None);
    while let Some(key) = c.key(name, open)? {
        match key.text {
            "controls" => c.field(&mut controls, key, name, |c, what| {
                control_points(c, what, nurbs)
            })?,
            "degree" if nurbs => c.field(&mut degree, key, name, |c, what| {
                Ok(c.whole(what, 1)?.0 as usize)
            })?,
            "knots" if nurbs => c.field(&mut knots, key, name, |c, what| {
                Ok((numbers(c, what)?, key.pos))
            })?,
            _ => return Err(c.unknown(key, name, keys)),
        }
    }
    let (degree, (knots, knots_at)) = if nurbs {
        (
            c.required(degree, "degree", name)?,
            c.required(knots, "knots", name)?,
        )
    } else {
        (0, (Vec::new(), keyword.pos))
    };
    Ok(CurveBlock {
        name,
        at: keyword.pos,
        controls: c.required(controls, "controls", name)?,
        degree,
        knots,
        knots_at,
    })
}

/// The control points after `controls`, each `[x y z]`, or `[x y z w]` if
/// `weighted`.
pub(super) fn control_points(
    c: &mut Cursor<'_>,
    what: &str,
    weighted: bool,
) -> Result<Vec<Control>> {
    let mut points = Vec::new();
    loop {
        let at = c.here();
        if !c.open_bracket() {
            break;
        }
        let point = c.point(what)?;
        let closing = c.peek().is_some_and(|t| t.kind == Kind::CloseBracket);
        let weight = if weighted && !closing {
            Some(c.number_at("weight")?)
        } else {
            None
        };
        c.close_bracket(at)?;
        points.push(Control { point, at, weight });
    }
    Ok(points)
}

/// One or more numbers, each with its position (the value of `what`).
pub(super) fn numbers(c: &mut Cursor<'_>, what: &str) -> Result<Vec<(f64, Pos)>> {
    let mut values = vec![c.number_at(what)?];
    while c.peek().is_some_and(|t| matches!(t.kind, Kind::Number(_))) {
        values.push(c.number_at(what)?);
    }
    Ok(values)
}

impl CurveBlock {
    fn points(&self) -> Vec<Point3<f64>> {
        self.controls.iter().map(|p| p.point).collect()
    }

    fn weights(&self) -> Vec<f64> {
        self.controls.iter().map(Control::weight).collect()
    }

    fn knots(&self) -> Vec<f64> {
        self.knots.iter().map(|&(k, _)| k).collect()
    }

    /// The points as `(x, y)`: a profile lies in the `z = 0` plane.
    fn plane_points(&self, c: &Cursor<'_>) -> Result<Vec<Point2<f64>>> {
        self.controls
            .iter()
            .map(|p| {
                if p.point.z != 0.0 {
                    return Err(c.error(
                        p.at,
                        format!(
                            "a RevSurface profile lies in the z = 0 plane, but this control point has z = {}",
                            p.point.z
                        ),
                    ));
                }
                Ok(Point2::new(p.point.x, p.point.y))
            })
            .collect()
    }

    /// Where revolve's error `e` points: the control point, weight or knot
    /// it names, the `knots` keyword for a wrong count, else the keyword.
    fn locate(&self, e: &Error) -> Pos {
        let point = |index: usize| self.controls.get(index).map(|p| p.at);
        let knot = |index: usize| self.knots.get(index).map(|&(_, at)| at);
        let at = match *e {
            Error::NonFinitePoint { index } | Error::CoordinateTooLarge { index, .. } => {
                point(index)
            }
            Error::InvalidWeight { index, .. } => self
                .controls
                .get(index)
                .map(|p| p.weight.map_or(p.at, |(_, at)| at)),
            Error::NonFiniteKnot { index }
            | Error::KnotTooLarge { index, .. }
            | Error::KnotGapTooSmall { index, .. }
            | Error::DecreasingKnots { index } => knot(index),
            Error::KnotCount { .. } | Error::KnotMultiplicity { .. } => Some(self.knots_at),
            _ => None,
        };
        at.unwrap_or(self.at)
    }

    /// revolve's error `e` for this curve, located by [`Self::locate`].
    fn invalid(&self, c: &Cursor<'_>, e: Error) -> super::ParseError {
        c.error(self.locate(&e), format!("invalid {}: {e}", self.name))
    }
}

/// `RevSurface { profile CURVE }` (after its keyword).
pub(super) fn rev_surface(c: &mut Cursor<'_>) -> Result<Shape> {
    const NAME: &str = "RevSurface";
    let open = c.open(NAME)?;
    let mut body = None;
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "profile" => c.field(&mut body, key, NAME, |c, _| profile(c))?,
            _ => return Err(c.unknown(key, NAME, &["profile"])),
        }
    }
    let body = c.required(body, "profile", NAME)?;
    Ok(Shape::Revolution(Arc::new(body)))
}

/// The curve after `profile`, in the plane `z = 0`.
fn profile(c: &mut Cursor<'_>) -> Result<RevolutionBody> {
    let keyword = match c.peek() {
        Some(t) if CURVES.contains(&t.text) => t,
        _ => {
            return Err(c.expected("BezierCurve, BsplineCurve or NurbsCurve after 'profile'"));
        }
    };
    c.bump();
    let block = curve_block(c, keyword)?;
    let points = block.plane_points(c)?;
    let fail = |e| block.invalid(c, e);
    Ok(match keyword.text {
        "BezierCurve" => {
            RevolutionBody::Bezier(Revolution::new(Bezier::new(points).map_err(fail)?))
        }
        "BsplineCurve" => {
            RevolutionBody::BSpline(Revolution::new(BSpline::uniform(3, points).map_err(fail)?))
        }
        _ => RevolutionBody::Nurbs(Revolution::new(
            Nurbs::new(block.degree, block.knots(), points, block.weights()).map_err(fail)?,
        )),
    })
}

/// A curve directly in a group (after its keyword `curve`): a thin tube.
pub(super) fn tube(c: &mut Cursor<'_>, curve: Token<'_>) -> Result<Shape> {
    let block = curve_block(c, curve)?;
    let points = block.points();
    let fail = |e| block.invalid(c, e);
    let extent = match points.split_first() {
        Some((first, rest)) => {
            let (lo, hi) = rest
                .iter()
                .fold((first.coords, first.coords), |(lo, hi), p| {
                    (lo.inf(&p.coords), hi.sup(&p.coords))
                });
            (hi - lo).norm()
        }
        None => 0.0,
    };
    let tolerance = TUBE_TOLERANCE * extent;
    // revolve's checks first, then whether there is anything to draw.
    let flattening: std::result::Result<Flattening<3>, Error> = match curve.text {
        "BezierCurve" => {
            let bezier = Bezier::new(points).map_err(fail)?;
            check_extent(c, curve, extent)?;
            bezier.flatten(tolerance)
        }
        "BsplineCurve" => {
            let spline = BSpline::uniform(3, points).map_err(fail)?;
            check_extent(c, curve, extent)?;
            spline.flatten(tolerance)
        }
        _ => {
            let nurbs =
                Nurbs::new(block.degree, block.knots(), points, block.weights()).map_err(fail)?;
            check_extent(c, curve, extent)?;
            nurbs.flatten(tolerance)
        }
    };
    let flattening = flattening.map_err(fail)?;
    Ok(Shape::Tube(Arc::new(Tube {
        points: flattening.samples.iter().map(|s| s.point).collect(),
        radius: (TUBE_RADIUS * extent).max(MIN_TUBE_RADIUS),
    })))
}

/// A tube needs control points that do not all coincide.
fn check_extent(c: &Cursor<'_>, curve: Token<'_>, extent: f64) -> Result<()> {
    if extent > 0.0 && extent.is_finite() {
        Ok(())
    } else {
        Err(c.error(
            curve.pos,
            format!(
                "the {}'s control points all coincide: nothing to draw",
                curve.text
            ),
        ))
    }
}

impl CurveBlock {
    /// The curve as a 3D NURBS curve: a Bézier curve on the knots `0…0 1…1`,
    /// the cubic B-spline on its uniform knots, a `NurbsCurve` as written.
    fn nurbs_3d(&self) -> std::result::Result<Nurbs<3>, Error> {
        let points = self.points();
        let n = points.len();
        match self.name {
            "BezierCurve" => {
                let degree = n.saturating_sub(1);
                let knots = [vec![0.0; n], vec![1.0; n]].concat();
                Nurbs::new(degree, knots, points, vec![1.0; n])
            }
            "BsplineCurve" => {
                let knots = (0..n + 4).map(|i| i as f64 / (n + 3) as f64).collect();
                Nurbs::new(3, knots, points, vec![1.0; n])
            }
            _ => Nurbs::new(self.degree, self.knots(), points, self.weights()),
        }
    }
}

/// The surfaces built from curves.
pub(super) const CONSTRUCTED: &[&str] = &["RuledSurface", "ExtrudedSurface", "LoftedSurface"];

/// `RuledSurface { curves CURVE CURVE }`, `ExtrudedSurface { curve CURVE
/// direction x y z }` or `LoftedSurface { degree q  curves CURVE CURVE … }`
/// (after its keyword): revolve's `NurbsSurface::ruled`, `::extrude` and
/// `::loft` of the curves (each a `BezierCurve`, `BsplineCurve` or
/// `NurbsCurve` block, in 3D).
pub(super) fn constructed_surface(c: &mut Cursor<'_>, keyword: Token<'_>) -> Result<Shape> {
    let name = CONSTRUCTED
        .iter()
        .copied()
        .find(|&n| n == keyword.text)
        .unwrap_or("RuledSurface");
    let keys: &[&str] = match name {
        "ExtrudedSurface" => &["curve", "direction"],
        "LoftedSurface" => &["degree", "curves"],
        _ => &["curves"],
    };
    let open = c.open(name)?;
    let (mut curves, mut direction, mut degree) = (None, None, None);
    while let Some(key) = c.key(name, open)? {
        match key.text {
            "curves" if name != "ExtrudedSurface" => {
                c.field(&mut curves, key, name, |c, _| curve_blocks(c))?
            }
            "curve" if name == "ExtrudedSurface" => {
                c.field(&mut curves, key, name, |c, _| Ok(vec![one_curve(c)?]))?
            }
            "direction" if name == "ExtrudedSurface" => {
                c.field(&mut direction, key, name, |c, what| c.vector(what))?
            }
            "degree" if name == "LoftedSurface" => c.field(&mut degree, key, name, |c, what| {
                Ok(c.whole(what, 1)?.0 as usize)
            })?,
            _ => return Err(c.unknown(key, name, keys)),
        }
    }
    let blocks = c.required(curves, keys[0], name)?;
    let mut sections = Vec::with_capacity(blocks.len());
    for block in &blocks {
        sections.push(block.nurbs_3d().map_err(|e| block.invalid(c, e))?);
    }
    let built = match name {
        "ExtrudedSurface" => {
            let direction = c.required(direction, "direction", name)?;
            NurbsSurface::extrude(&sections[0], direction)
        }
        "LoftedSurface" => {
            let degree = c.required(degree, "degree", name)?;
            NurbsSurface::loft(&sections, degree)
        }
        _ if sections.len() != 2 => {
            return Err(c.error(
                keyword.pos,
                format!(
                    "a RuledSurface takes exactly two curves, got {}",
                    sections.len()
                ),
            ));
        }
        _ => NurbsSurface::ruled(&sections[0], &sections[1]),
    };
    let surface = built.map_err(|e| c.error(keyword.pos, format!("invalid {name}: {e}")))?;
    Ok(Shape::Surface(Arc::new(SurfaceBody::Nurbs(surface))))
}

/// One curve block (its keyword first).
fn one_curve(c: &mut Cursor<'_>) -> Result<CurveBlock> {
    match c.peek() {
        Some(t) if CURVES.contains(&t.text) => {
            c.bump();
            curve_block(c, t)
        }
        _ => Err(c.expected("BezierCurve, BsplineCurve or NurbsCurve")),
    }
}

/// One or more curve blocks.
fn curve_blocks(c: &mut Cursor<'_>) -> Result<Vec<CurveBlock>> {
    let mut blocks = vec![one_curve(c)?];
    while c.peek().is_some_and(|t| CURVES.contains(&t.text)) {
        blocks.push(one_curve(c)?);
    }
    Ok(blocks)
}
