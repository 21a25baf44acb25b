//! A model made of many Bézier patches (Newell's teapot is 32 bicubic ones),
//! intersected through a hierarchy over the patches' pieces.

use super::patch::Patch;
use super::search::{intersect, occluded};
use super::search_pieces::SearchPieces;
use super::tessellate::tessellate_patches;
use crate::bernstein::Coefficient;
use crate::bernstein::elevate_degree;
use crate::curve::Homogeneous;
use crate::{Aabb, BezierSurface, Error, Hit, Intersect, Mesh, Ray, Tolerance};

/// A model made of Bézier patches, such as Newell's teapot: each patch a
/// [`BezierSurface`] with its own `(u, v) ∈ [0, 1]²`.
///
/// A ray does not test every patch: for the search, the patches are cut
/// once into pieces (up to 256 each, until every piece is nearly bilinear),
/// whose boxes (of their control nets, which contain them by the convex
/// hull property) are held in a bounding-volume hierarchy, built once by
/// the surface area heuristic; a ray visits only the boxes it enters,
/// nearer ones first, skipping those beyond its best hit so far, and each
/// piece it reaches gets the certified search of [`BezierSurface`]'s
/// [`Intersect`]. Patches of lower degrees are raised to the model's
/// largest degrees for the search (degree elevation changes the control
/// net, not the surface or its parameters).
///
/// [`intersect`](Intersect::intersect) gives the nearest hit over all
/// patches, with `Hit::uv` in the hit patch's parameters;
/// [`intersect_patch`](Self::intersect_patch) also says which patch.
///
/// ```
/// use revolve::{BezierPatches, BezierSurface, Intersect, Ray};
/// use revolve::nalgebra::{Point3, Vector3};
///
/// // Two unit squares side by side in the plane z = 0.
/// let square = |x0: f64| {
///     BezierSurface::new(vec![
///         vec![Point3::new(x0, 0.0, 0.0), Point3::new(x0, 1.0, 0.0)],
///         vec![Point3::new(x0 + 1.0, 0.0, 0.0), Point3::new(x0 + 1.0, 1.0, 0.0)],
///     ])
/// };
/// let model = BezierPatches::new(vec![square(0.0)?, square(1.0)?])?;
/// let ray = Ray::new(Point3::new(1.5, 0.25, 1.0), Vector3::new(0.0, 0.0, -1.0));
/// let (patch, hit) = model.intersect_patch(&ray, 0.0, f64::INFINITY).unwrap();
/// assert_eq!(patch, 1);
/// assert!((hit.t - 1.0).abs() < 1e-15);
/// assert!((hit.uv.0 - 0.5).abs() < 1e-15 && (hit.uv.1 - 0.25).abs() < 1e-15);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BezierPatches {
    surfaces: Vec<BezierSurface>,
    /// The patches' nets raised to the largest degrees, homogeneous with
    /// unit weights, cut into the ray search's pieces.
    search: SearchPieces,
    tolerance: Tolerance,
}

impl BezierPatches {
    /// The model made of `patches`.
    ///
    /// # Errors
    /// [`Error::NoPatches`] for an empty list.
    pub fn new(patches: Vec<BezierSurface>) -> Result<Self, Error> {
        if patches.is_empty() {
            return Err(Error::NoPatches);
        }
        let (degrees, nets) = raised_nets(&patches);
        Ok(BezierPatches {
            surfaces: patches,
            search: SearchPieces::new(&nets, degrees),
            tolerance: Tolerance::default(),
        })
    }

    /// The same model with the given intersection accuracy (see
    /// [`BezierSurface::with_tolerance`]).
    pub fn with_tolerance(mut self, tolerance: Tolerance) -> Self {
        self.tolerance = tolerance.clamped();
        self
    }

    /// The intersection accuracy.
    pub fn tolerance(&self) -> &Tolerance {
        &self.tolerance
    }

    /// The patches, in the order given.
    pub fn patches(&self) -> &[BezierSurface] {
        &self.surfaces
    }

    /// The same model with the opposite orientation: every patch
    /// [reversed](BezierSurface::reversed) (the flag is the patches', so
    /// [`patches`](Self::patches) gives the reversed ones), its unit normal
    /// `−(∂S/∂u × ∂S/∂v)/|∂S/∂u × ∂S/∂v|` while points, partials, hits' `t`,
    /// `point`, `uv` and patch index are exactly the original's; the normals
    /// of [`intersect_patch`](Self::intersect_patch), [`Intersect`] and
    /// [`tessellate`](Self::tessellate) (its triangles wound the other way)
    /// are negated. `reversed().reversed()` is the original.
    pub fn reversed(&self) -> Self {
        let mut model = self.clone();
        for surface in &mut model.surfaces {
            *surface = surface.reversed();
        }
        model
    }

    /// The number of patches (at least one).
    pub fn len(&self) -> usize {
        self.surfaces.len()
    }

    /// Always `false`: a model has at least one patch.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The nearest hit with `t_min < t < t_max` and the index of the patch
    /// it is on, or `None` for a miss. The normal follows that patch's
    /// `∂S/∂u × ∂S/∂v` (its limit at collapsed edges, as on the teapot's lid;
    /// facing the ray where the patch has no tangent plane).
    pub fn intersect_patch(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(usize, Hit)> {
        let found = intersect(self.search.set(), ray, t_min, t_max, &self.tolerance)?;
        let (patch, st) = self.search.on_owner(found.patch, found.st);
        let table = self.surfaces[patch].table();
        let (point, normal) = table.point_and_normal_on(&table.patches[0], st, (found.u, found.v));
        let hit = found.to_hit(ray, point, normal)?;
        Some((patch, hit))
    }

    /// A triangle mesh within `tolerance` of every patch, each cut as in
    /// [`BezierSurface::tessellate`]; patches that share an edge with the
    /// same control points (either direction, as the teapot's do) get the
    /// same vertices along it, welded, so the mesh is open only where the
    /// model is. A vertex on a shared edge keeps the `uv` and normal of the
    /// first patch (in order) that has it. A [reversed](BezierSurface::reversed)
    /// patch's normals are negated and its triangles wound the other way.
    ///
    /// # Errors
    /// As [`BezierSurface::tessellate`].
    pub fn tessellate(&self, tolerance: f64) -> Result<Mesh, Error> {
        let (degrees, nets) = raised_nets(&self.surfaces);
        tessellate_patches(degrees, &nets, tolerance, |k| {
            self.surfaces[k].is_reversed()
        })
    }
}

/// The largest degrees `(p, q)` over `surfaces`, and each surface's net
/// raised to them, homogeneous with unit weights, on `[0, 1]²`.
fn raised_nets(surfaces: &[BezierSurface]) -> ((usize, usize), Vec<Patch>) {
    let degrees = surfaces.iter().fold((0, 0), |(p, q), s| {
        let (a, b) = s.degrees();
        (p.max(a), q.max(b))
    });
    let nets = surfaces
        .iter()
        .map(|s| Patch {
            u: (0.0, 1.0),
            v: (0.0, 1.0),
            net: raised_net(s, degrees),
        })
        .collect();
    (degrees, nets)
}

/// The homogeneous net of `surface` raised to `degrees` (each row in `v`,
/// then each column in `u`).
fn raised_net(surface: &BezierSurface, (p, q): (usize, usize)) -> Vec<Homogeneous<3>> {
    let rows: Vec<Vec<Homogeneous<3>>> = surface
        .points()
        .iter()
        .map(|row| {
            let row: Vec<Homogeneous<3>> = row.iter().map(|x| Homogeneous::new(x, 1.0)).collect();
            raise(&row, q)
        })
        .collect();
    let mut net = vec![Homogeneous::zero(); (p + 1) * (q + 1)];
    for j in 0..=q {
        let column: Vec<Homogeneous<3>> = rows.iter().map(|row| row[j]).collect();
        for (i, h) in raise(&column, p).into_iter().enumerate() {
            net[i * (q + 1) + j] = h;
        }
    }
    net
}

/// The Bézier coefficients `c` raised to `degree` (`≥ c.len() − 1`).
fn raise<T: Coefficient>(c: &[T], degree: usize) -> Vec<T> {
    elevate_degree(c, degree + 1 - c.len())
}

impl Intersect for BezierPatches {
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        self.intersect_patch(ray, t_min, t_max).map(|(_, hit)| hit)
    }

    /// Stops at the first patch piece with a hit.
    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        occluded(self.search.set(), ray, t_min, t_max, &self.tolerance)
    }

    fn bounds(&self) -> Aabb {
        self.search.bounds()
    }
}
