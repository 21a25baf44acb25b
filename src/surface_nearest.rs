//! [`SurfaceNearest`]: the answer of a surface's nearest-point query, shared
//! by every surface kind (`nearest_point` on [`Revolution`](crate::Revolution),
//! [`BezierSurface`](crate::BezierSurface), [`BSplineSurface`](crate::BSplineSurface),
//! [`NurbsSurface`](crate::NurbsSurface) and [`BezierPatches`](crate::BezierPatches)).

use nalgebra::Point3;

/// The point of a surface nearest to a query point `P`:
/// `distance = |point − P|`, the least `|S(u, v) − P|` over the whole
/// parameter domain, its edges included.
///
/// `point` is the surface's own evaluation at `uv` (`Surface::eval(uv)`,
/// for [`BezierPatches`](crate::BezierPatches) that of patch `patch`), and
/// `distance` is `|point − P|` as computed from it. When several points are
/// equally near (the centre of a sphere) any of them is a right answer.
///
/// What `certified` promises depends on the kind; each kind's
/// `nearest_point` states it. In short: `true` means no point of the
/// surface is nearer to `P` than `distance` minus a documented rounding
/// allowance (for a revolution, that of the profile's
/// [`CurveProjector`](crate::CurveProjector); for the tensor-product kinds a
/// few hundred units in the last place of the problem's size).
///
/// ```
/// use revolve::{Revolution, Surface};
/// use revolve::nalgebra::{Point2, Point3};
/// use revolve::Nurbs;
/// use std::f64::consts::FRAC_PI_2;
///
/// // A unit sphere about the origin: from outside, the nearest point is on
/// // the ray from the centre through the query point.
/// let sphere = Revolution::new(Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2)?);
/// let p = Point3::new(2.0, 1.0, -2.0);
/// let near = sphere.nearest_point(&p)?;
/// assert!((near.point - p / 3.0).norm() < 1e-15);
/// assert!((near.distance - 2.0).abs() < 1e-15 && near.certified);
/// assert!((sphere.eval(near.uv.0, near.uv.1) - near.point).norm() < 1e-15);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceNearest {
    /// The parameters `(u, v)` of the nearest point, in the surface's own
    /// domain (for a revolution `(u, θ)` as in [`Hit::uv`](crate::Hit::uv):
    /// the profile's parameter and the angle in `[0, 2π]`; for
    /// [`BezierPatches`](crate::BezierPatches) the patch's own `[0, 1]²`).
    pub uv: (f64, f64),
    /// The nearest point `S(u, v)`, but for the rounding of `uv` (as a
    /// hit's point: see [`Hit::uv`](crate::Hit::uv)).
    pub point: Point3<f64>,
    /// Its distance `|point − P|` from the query point.
    pub distance: f64,
    /// `true` when the answer is certified global (see the kind's
    /// `nearest_point`); `false` for a revolution whose profile has no
    /// Bézier spans (a sampled answer), and when a tensor-product search
    /// reached its cap on the pieces it examines.
    pub certified: bool,
    /// The index of the patch the point is on, for
    /// [`BezierPatches`](crate::BezierPatches) (as
    /// [`BezierPatches::intersect_patch`](crate::BezierPatches::intersect_patch)
    /// numbers them: the order given); `0` for the single-surface kinds.
    pub patch: usize,
}

/// `|a − b|`: the plain norm where its squares can neither underflow nor
/// overflow, else scaled by the largest component first.
pub(crate) fn distance(a: &Point3<f64>, b: &Point3<f64>) -> f64 {
    let d = a - b;
    if (1e-150..=1e150).contains(&d.amax()) {
        d.norm()
    } else {
        crate::curve::scaled_norm(d)
    }
}
