//! Spline curves: `RevSurface` profiles and curves drawn as tubes.
//!
//! ```text
//! BezierCurve  { controls [x y z] [x y z] … }   one Bézier curve of degree count − 1
//! BsplineCurve { controls [x y z] [x y z] … }   cubic B-spline, uniform knots i/(n+3)
//! RevSurface   { profile BezierCurve {…} | profile BsplineCurve {…} }
//! ```
//!
//! A `RevSurface` profile lies in the `z = 0` plane and turns about the `y`
//! axis; its points are used as `(x, y)`. A curve directly in a group becomes a
//! thin tube along its flattening (tolerance `10⁻³` of the control points'
//! extent, radius `10⁻²` of it but at least `0.001`). revolve's own checks
//! (too few control points, coordinates too large) are reported at the curve's
//! keyword with revolve's message.

use std::sync::Arc;

use revolve::nalgebra::{Point2, Point3};
use revolve::{BSpline, Bezier, Revolution};

use super::cursor::{Cursor, Result};
use super::lexer::{Pos, Token};
use crate::scene::{RevolutionBody, Shape, Tube};

/// The two curve keywords.
pub(super) const CURVES: &[&str] = &["BezierCurve", "BsplineCurve"];

/// Tube flattening tolerance, relative to the control points' extent.
const TUBE_TOLERANCE: f64 = 1e-3;
/// Tube radius, relative to the control points' extent.
const TUBE_RADIUS: f64 = 1e-2;
/// The smallest tube radius.
const MIN_TUBE_RADIUS: f64 = 1e-3;

/// The control points of a curve block (after its keyword `name`), each
/// with the position of its `[`.
fn controls(c: &mut Cursor<'_>, name: &str) -> Result<Vec<(Point3<f64>, Pos)>> {
    let open = c.open(name)?;
    let mut points = None;
    while let Some(key) = c.key(name, open)? {
        match key.text {
            "controls" => c.field(&mut points, key, name, |c, what| {
                let mut points = Vec::new();
                loop {
                    let at = c.here();
                    if !c.open_bracket() {
                        break;
                    }
                    let p = c.point(what)?;
                    c.close_bracket(at)?;
                    points.push((p, at));
                }
                Ok(points)
            })?,
            _ => return Err(c.unknown(key, name, &["controls"])),
        }
    }
    c.required(points, "controls", name)
}

/// revolve's error for the curve `name` at `at`.
fn invalid(c: &Cursor<'_>, name: &str, at: Pos, e: revolve::Error) -> super::ParseError {
    c.error(at, format!("invalid {name}: {e}"))
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
    let curve = match c.peek() {
        Some(t) if CURVES.contains(&t.text) => t,
        _ => return Err(c.expected("BezierCurve or BsplineCurve after 'profile'")),
    };
    c.bump();
    let mut points = Vec::new();
    for (p, at) in controls(c, curve.text)? {
        if p.z != 0.0 {
            return Err(c.error(
                at,
                format!(
                    "a RevSurface profile lies in the z = 0 plane, but this control point has z = {}",
                    p.z
                ),
            ));
        }
        points.push(Point2::new(p.x, p.y));
    }
    let fail = |e| invalid(c, curve.text, curve.pos, e);
    Ok(if curve.text == "BezierCurve" {
        RevolutionBody::Bezier(Revolution::new(Bezier::new(points).map_err(fail)?))
    } else {
        RevolutionBody::BSpline(Revolution::new(BSpline::uniform(3, points).map_err(fail)?))
    })
}

/// A curve directly in a group (after its keyword `curve`): a thin tube.
pub(super) fn tube(c: &mut Cursor<'_>, curve: Token<'_>) -> Result<Shape> {
    let points: Vec<Point3<f64>> = controls(c, curve.text)?
        .into_iter()
        .map(|(p, _)| p)
        .collect();
    let fail = |e| invalid(c, curve.text, curve.pos, e);
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
    let flattening = if curve.text == "BezierCurve" {
        let bezier = Bezier::new(points).map_err(fail)?;
        check_extent(c, curve, extent)?;
        bezier.flatten(tolerance).map_err(fail)?
    } else {
        let spline = BSpline::uniform(3, points).map_err(fail)?;
        check_extent(c, curve, extent)?;
        spline.flatten(tolerance).map_err(fail)?
    };
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
