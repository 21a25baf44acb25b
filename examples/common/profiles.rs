//! The bundled profiles shared by the examples (x = radius, y = height).

use revolve::nalgebra::Point2;
use revolve::{BSpline, Bezier, Error};

/// The wine glass of the course scene files: a uniform cubic B-spline (the
/// course framework's knots `i/(n + 3)`) touching the axis at both ends with
/// repeated control points there.
pub fn wine_glass() -> Result<BSpline<2>, Error> {
    let controls = [
        (0.0, -1.0),
        (0.0, -1.0),
        (0.0, -1.0),
        (0.6, -1.0),
        (0.7, -0.95),
        (0.3, -0.9),
        (0.08, -0.8),
        (0.06, -0.5),
        (0.06, -0.1),
        (0.1, 0.0),
        (0.5, 0.1),
        (0.7, 0.4),
        (0.75, 0.8),
        (0.72, 1.0),
        (0.7, 1.02),
        (0.68, 0.8),
        (0.6, 0.45),
        (0.35, 0.25),
        (0.1, 0.2),
        (0.0, 0.2),
        (0.0, 0.2),
        (0.0, 0.2),
    ];
    BSpline::uniform(
        3,
        controls.iter().map(|&(x, y)| Point2::new(x, y)).collect(),
    )
}

/// A vase as one cubic Bézier.
pub fn vase() -> Result<Bezier<2>, Error> {
    Bezier::new(vec![
        Point2::new(0.6, -1.0),
        Point2::new(1.6, -0.4),
        Point2::new(-0.2, 0.6),
        Point2::new(0.5, 1.0),
    ])
}
