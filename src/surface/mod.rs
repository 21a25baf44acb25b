//! Parametric surfaces: the [`Surface`] trait and surfaces of revolution.

mod mesh;
mod revolution;

pub use mesh::Mesh;
pub use revolution::Revolution;

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
    /// tangent plane exists. `None` only where no tangent plane exists.
    ///
    /// The default normalizes the cross product and returns `None` when it is
    /// zero.
    fn normal(&self, u: f64, v: f64) -> Option<Unit<Vector3<f64>>> {
        let (su, sv) = self.partials(u, v);
        Unit::try_new(su.cross(&sv), 0.0)
    }
}
