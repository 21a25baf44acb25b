//! The [`Surface`] trait every surface kind implements, and [`PatchBounds`]:
//! a surface that can box any sub-rectangle of its parameters (what the
//! generic Newton intersector needs to find starting points).

use crate::Aabb;
use nalgebra::{Point3, Unit, Vector3};

/// A parametric surface `S(u, v)` on a parameter rectangle.
///
/// Implementors provide the domain, the point and the analytic first partial
/// derivatives; [`normal`](Surface::normal) defaults to the normalized cross
/// product `∂S/∂u × ∂S/∂v`, and surfaces with degenerate points (poles)
/// override it with the limit.
pub trait Surface {
    /// The parameter rectangle `[(u₀, u₁), (v₀, v₁)]`.
    fn domain(&self) -> [(f64, f64); 2];

    /// The point `S(u, v)`.
    fn eval(&self, u: f64, v: f64) -> Point3<f64>;

    /// The partial derivatives `(∂S/∂u, ∂S/∂v)`, analytic.
    fn partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>);

    /// The unit normal along `∂S/∂u × ∂S/∂v` (the orientation of the
    /// parametrization), or its limit where the cross product vanishes but a
    /// tangent plane exists. `None` only where no tangent plane exists. A
    /// surface may take the opposite orientation throughout, along
    /// `−(∂S/∂u × ∂S/∂v)`, as the crate's surface kinds do after
    /// `reversed()`.
    ///
    /// The default normalizes the cross product and returns `None` when it is
    /// zero.
    fn normal(&self, u: f64, v: f64) -> Option<Unit<Vector3<f64>>> {
        let (su, sv) = self.partials(u, v);
        Unit::try_new(su.cross(&sv), 0.0)
    }
}

/// A [`Surface`] that can bound the image of any parameter rectangle: what
/// the generic Newton intersector ([`NewtonIntersector`]) needs to seed its
/// iterations from a tree of patches.
///
/// [`NewtonIntersector`]: crate::ray::newton::NewtonIntersector
///
/// # Contract
/// [`bound_patch`](Self::bound_patch) is *conservative*: the box contains
/// `S(u, v)` for every `(u, v)` in the rectangle (up to the rounding of
/// [`eval`](Surface::eval), which implementors pad for). A box that is too
/// large only costs time; one that is too small makes ray casters miss hits.
pub trait PatchBounds: Surface {
    /// A box containing `S([u₀, u₁] × [v₀, v₁])`, for `u = (u₀, u₁)` and
    /// `v = (v₀, v₁)` with `u₀ ≤ u₁`, `v₀ ≤ v₁` inside the
    /// [domain](Surface::domain).
    fn bound_patch(&self, u: (f64, f64), v: (f64, f64)) -> Aabb;

    /// Which parameters are periodic, `[u, v]`: a periodic parameter may
    /// leave its domain interval `(a, b)` and is taken modulo `b − a` (the
    /// angle of a surface of revolution). The default is `[false, false]`:
    /// both parameters are confined to their intervals.
    fn periodic(&self) -> [bool; 2] {
        [false, false]
    }
}

/// A reference to a surface is the same surface, so that borrowing solvers
/// (`NewtonIntersector<&S>`) work without cloning it.
impl<S: Surface + ?Sized> Surface for &S {
    fn domain(&self) -> [(f64, f64); 2] {
        (**self).domain()
    }

    fn eval(&self, u: f64, v: f64) -> Point3<f64> {
        (**self).eval(u, v)
    }

    fn partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>) {
        (**self).partials(u, v)
    }

    fn normal(&self, u: f64, v: f64) -> Option<Unit<Vector3<f64>>> {
        (**self).normal(u, v)
    }
}

impl<S: PatchBounds + ?Sized> PatchBounds for &S {
    fn bound_patch(&self, u: (f64, f64), v: (f64, f64)) -> Aabb {
        (**self).bound_patch(u, v)
    }

    fn periodic(&self) -> [bool; 2] {
        (**self).periodic()
    }
}

/// `normal`, negated when `reversed`: the orientation flag of the surface
/// kinds' `reversed()`.
#[inline]
pub(crate) fn oriented(normal: Unit<Vector3<f64>>, reversed: bool) -> Unit<Vector3<f64>> {
    if reversed { -normal } else { normal }
}
