//! Tensor-product surfaces, intersected by revolve's certified patch search.
//!
//! ```text
//! BezierSurface  { rows m  cols n  controls [x y z] … }
//!                one Bézier patch of degrees (m − 1, n − 1)
//! BsplineSurface { uDegree p  vDegree q  uKnots k…  vKnots k…  rows m  cols n  controls [x y z] … }
//!                a B-spline surface of degrees (p, q)
//! ```
//!
//! The `m·n` control points come row by row (`m` rows of `n` points; a row
//! runs along `v`, the rows follow each other along `u`). `[x y z w]` is the
//! point `(x, y, z)` with weight `w` (not premultiplied; `[x y z]` has weight
//! 1); a surface with any four-number point is rational (revolve's
//! `NurbsSurface`; a rational `BezierSurface` is the NURBS surface on the
//! knots `0…0 1…1`). `uKnots` and `vKnots` are whole knot vectors,
//! `rows + p + 1` and `cols + q + 1` numbers. Keys come in any order; all are
//! required. `rows` and `cols` are at least 1, as revolve's constructors take
//! them (a surface of one row or column is a curve, which a ray hits only
//! where it passes through it).
//!
//! Errors are located like the curves' (see [`super::curves`]): a wrong
//! number of control points at the first extra point's `[` (too many) or at
//! `controls` (too few); revolve's own checks at the item they name — a
//! control point (its row and column) at its `[`, a weight at the
//! weight, a knot at the knot, a wrong knot count or multiplicity at
//! `uKnots` / `vKnots`, too few rows or columns for the degree at `uDegree` /
//! `vDegree` — else at the surface's keyword.
//!
//! `BezierPatches { file PATH }` is a model of bicubic Bézier patches read
//! from a file ([`super::patches`]), once per path ([`Resources`]).

use std::sync::Arc;

use revolve::nalgebra::Point3;
use revolve::{BSplineSurface, BezierSurface, Error, NurbsSurface, ParameterDirection};

use super::cursor::{Cursor, Result};
use super::curves::{Control, control_points, numbers};
use super::lexer::{Pos, Token};
use super::resources::Resources;
use crate::scene::{Shape, SurfaceBody};

/// The surface keywords written with control points.
pub(super) const SURFACES: &[&str] = &["BezierSurface", "BsplineSurface"];

/// A knot vector as written: the knots with their positions, and where its
/// keyword is.
type Knots = (Vec<(f64, Pos)>, Pos);

/// One parametric direction of a `BsplineSurface`: its degree and knots.
struct Direction {
    /// The degree and where its value is.
    degree: (usize, Pos),
    knots: Knots,
}

impl Direction {
    fn knots(&self) -> Vec<f64> {
        self.knots.0.iter().map(|&(k, _)| k).collect()
    }

    /// Where the knot error `e` of this direction points.
    fn locate(&self, e: &Error) -> Option<Pos> {
        let knot = |index: usize| self.knots.0.get(index).map(|&(_, at)| at);
        match *e {
            Error::NonFiniteKnot { index }
            | Error::KnotTooLarge { index, .. }
            | Error::KnotGapTooSmall { index, .. }
            | Error::DecreasingKnots { index } => knot(index),
            Error::KnotCount { .. }
            | Error::KnotMultiplicity { .. }
            | Error::EmptyDomain { .. } => Some(self.knots.1),
            Error::DegreeTooHigh { .. } => Some(self.degree.1),
            _ => None,
        }
    }
}

/// A surface block as written.
struct SurfaceBlock {
    /// The keyword (one of [`SURFACES`]) and where it is.
    name: &'static str,
    at: Pos,
    rows: usize,
    cols: usize,
    controls: Vec<Control>,
    /// A `BsplineSurface`'s directions `(u, v)`.
    directions: Option<(Direction, Direction)>,
}

/// Reads the surface block after its keyword (one of [`SURFACES`]).
pub(super) fn surface(c: &mut Cursor<'_>, keyword: Token<'_>) -> Result<Shape> {
    let block = surface_block(c, keyword)?;
    let body = block.build().map_err(|e| block.invalid(c, e))?;
    Ok(Shape::Surface(Arc::new(body)))
}

/// Reads the block's keys (in any order, each once, all required).
fn surface_block(c: &mut Cursor<'_>, keyword: Token<'_>) -> Result<SurfaceBlock> {
    let name = SURFACES
        .iter()
        .copied()
        .find(|&n| n == keyword.text)
        .unwrap_or("BezierSurface");
    let spline = name == "BsplineSurface";
    let keys: &[&str] = if spline {
        &[
            "uDegree", "vDegree", "uKnots", "vKnots", "rows", "cols", "controls",
        ]
    } else {
        &["rows", "cols", "controls"]
    };
    let open = c.open(name)?;
    let (mut rows, mut cols, mut controls) = (None, None, None);
    let (mut u_degree, mut v_degree, mut u_knots, mut v_knots) = (None, None, None, None);
    let degree = |c: &mut Cursor<'_>, what: &str| {
        let (p, at) = c.whole(what, 1)?;
        Ok((p as usize, at))
    };
    while let Some(key) = c.key(name, open)? {
        match key.text {
            "rows" => c.field(&mut rows, key, name, |c, what| c.whole(what, 1))?,
            "cols" => c.field(&mut cols, key, name, |c, what| c.whole(what, 1))?,
            "controls" => c.field(&mut controls, key, name, |c, what| {
                Ok((control_points(c, what, true)?, key.pos))
            })?,
            "uDegree" if spline => c.field(&mut u_degree, key, name, degree)?,
            "vDegree" if spline => c.field(&mut v_degree, key, name, degree)?,
            "uKnots" if spline => c.field(&mut u_knots, key, name, |c, what| {
                Ok((numbers(c, what)?, key.pos))
            })?,
            "vKnots" if spline => c.field(&mut v_knots, key, name, |c, what| {
                Ok((numbers(c, what)?, key.pos))
            })?,
            _ => return Err(c.unknown(key, name, keys)),
        }
    }
    let directions = if spline {
        Some((
            Direction {
                degree: c.required(u_degree, "uDegree", name)?,
                knots: c.required(u_knots, "uKnots", name)?,
            },
            Direction {
                degree: c.required(v_degree, "vDegree", name)?,
                knots: c.required(v_knots, "vKnots", name)?,
            },
        ))
    } else {
        None
    };
    // `whole(…, 1)` has refused 0 already.
    let rows = c.required(rows, "rows", name)?.0 as usize;
    let cols = c.required(cols, "cols", name)?.0 as usize;
    let (controls, controls_at) = c.required(controls, "controls", name)?;
    let expected = rows * cols;
    if let Some(extra) = controls.get(expected) {
        return Err(c.error(
            extra.at,
            format!(
                "{name} has rows {rows} × cols {cols} = {expected} control points, but this is \
                 control point {}",
                expected + 1
            ),
        ));
    }
    if controls.len() < expected {
        return Err(c.error(
            controls_at,
            format!(
                "{name} needs rows {rows} × cols {cols} = {expected} control points, found {}",
                controls.len()
            ),
        ));
    }
    Ok(SurfaceBlock {
        name,
        at: keyword.pos,
        rows,
        cols,
        controls,
        directions,
    })
}

impl SurfaceBlock {
    /// The points as `rows` rows of `cols`.
    fn grid(&self) -> Vec<Vec<Point3<f64>>> {
        self.controls
            .chunks(self.cols)
            .map(|row| row.iter().map(|p| p.point).collect())
            .collect()
    }

    /// The weights as `rows` rows of `cols`.
    fn weight_grid(&self) -> Vec<Vec<f64>> {
        self.controls
            .chunks(self.cols)
            .map(|row| row.iter().map(Control::weight).collect())
            .collect()
    }

    /// Whether any control point has a weight written.
    fn rational(&self) -> bool {
        self.controls.iter().any(|p| p.weight.is_some())
    }

    /// revolve's surface.
    fn build(&self) -> std::result::Result<SurfaceBody, Error> {
        let (degrees, knots) = match &self.directions {
            Some((u, v)) => ((u.degree.0, v.degree.0), (u.knots(), v.knots())),
            None if self.rational() => {
                // The rational Bézier patch: one span, knots 0…0 1…1.
                let bezier = |n: usize| [vec![0.0; n], vec![1.0; n]].concat();
                (
                    (self.rows - 1, self.cols - 1),
                    (bezier(self.rows), bezier(self.cols)),
                )
            }
            None => return BezierSurface::new(self.grid()).map(SurfaceBody::Bezier),
        };
        if self.rational() {
            NurbsSurface::new(degrees, knots, self.grid(), self.weight_grid())
                .map(SurfaceBody::Nurbs)
        } else {
            BSplineSurface::new(degrees, knots, self.grid()).map(SurfaceBody::BSpline)
        }
    }

    /// Where revolve's error `e` points (see the module docs; revolve's
    /// message names the row and column or the knot vector's direction).
    fn locate(&self, e: &Error) -> Pos {
        let control = |row: usize, column: usize| self.controls.get(row * self.cols + column);
        let at = match *e {
            Error::NonFiniteGridPoint { row, column }
            | Error::GridCoordinateTooLarge { row, column, .. } => {
                control(row, column).map(|p| p.at)
            }
            Error::InvalidGridWeight { row, column, .. } => {
                control(row, column).map(|p| p.weight.map_or(p.at, |(_, at)| at))
            }
            _ => None,
        };
        if let Some(at) = at {
            return at;
        }
        if let (Some((u, v)), Error::SurfaceKnots { direction, error }) = (&self.directions, e) {
            let knots = match direction {
                ParameterDirection::U => u,
                ParameterDirection::V => v,
            };
            if let Some(at) = knots.locate(error) {
                return at;
            }
        }
        self.at
    }

    /// revolve's error `e` for this surface, located by [`Self::locate`].
    fn invalid(&self, c: &Cursor<'_>, e: Error) -> super::ParseError {
        c.error(self.locate(&e), format!("invalid {}: {e}", self.name))
    }
}

/// `BezierPatches { file PATH }` (after its keyword).
pub(super) fn bezier_patches(c: &mut Cursor<'_>, res: &mut Resources) -> Result<Shape> {
    const NAME: &str = "BezierPatches";
    let open = c.open(NAME)?;
    let mut model = None;
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "file" => c.field(&mut model, key, NAME, |c, what| {
                let path = c.word(what)?;
                res.patches(c, path)
            })?,
            _ => return Err(c.unknown(key, NAME, &["file"])),
        }
    }
    Ok(Shape::Surface(c.required(model, "file", NAME)?))
}
