//! Rays, hits, the [`Intersect`] trait and the accuracy setting.
//!
//! A ray is `R(t) = origin + t·dir`. `dir` need not be unit length: `t` is
//! measured in units of `|dir|`, so `t` of a hit is the same number whatever
//! the caller's normalization convention, and `t_min`/`t_max` are in the same
//! units.

pub(crate) mod acceptance;
pub mod bvh;
pub mod newton;
pub(crate) mod slab;
pub mod wide_bvh;

pub use newton::{NewtonFinish, NewtonIntersector, NewtonReport, NewtonRun};

use crate::{Aabb, Error};
use nalgebra::{Point3, Unit, Vector3};

/// A ray `R(t) = origin + t·dir`, `t` in units of `|dir|`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts (`t = 0`).
    pub origin: Point3<f64>,
    /// The direction; need not be unit length, must not be zero.
    pub dir: Vector3<f64>,
}

impl Ray {
    /// The ray from `origin` along `dir`. Not checked: a ray whose origin is
    /// not finite or whose direction is zero or not finite misses everything
    /// ([`Ray::try_new`] says so instead).
    pub fn new(origin: Point3<f64>, dir: Vector3<f64>) -> Self {
        Ray { origin, dir }
    }

    /// The ray from `origin` along `dir`, checked.
    ///
    /// # Errors
    /// [`Error::InvalidRay`] when a coordinate of `origin` or `dir` is NaN or
    /// infinite, or `dir` is zero.
    ///
    /// ```
    /// use revolve::nalgebra::{Point3, Vector3};
    /// use revolve::{Error, Ray};
    ///
    /// let ray = Ray::try_new(Point3::origin(), Vector3::new(0.0, 0.0, 2.0))?;
    /// assert_eq!(ray.at(1.0), Point3::new(0.0, 0.0, 2.0));
    /// assert!(matches!(
    ///     Ray::try_new(Point3::origin(), Vector3::zeros()),
    ///     Err(Error::InvalidRay { .. })
    /// ));
    /// # Ok::<(), Error>(())
    /// ```
    pub fn try_new(origin: Point3<f64>, dir: Vector3<f64>) -> Result<Self, Error> {
        let finite = origin.iter().chain(dir.iter()).all(|c| c.is_finite());
        if !finite || dir == Vector3::zeros() {
            return Err(Error::InvalidRay {
                origin: origin.into(),
                dir: dir.into(),
            });
        }
        Ok(Ray { origin, dir })
    }

    /// The point `origin + t·dir`.
    #[inline]
    pub fn at(&self, t: f64) -> Point3<f64> {
        self.origin + self.dir * t
    }
}

/// A direction split into its unit vector and its length, the length as two
/// factors `|d| = largest · norm_of_scaled` (`largest` the largest absolute
/// component, `norm_of_scaled = |d / largest|` in `[1, √3]`), so that no
/// direction of finite components overflows or underflows on the way.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SplitDirection {
    pub(crate) unit: Vector3<f64>,
    pub(crate) largest: f64,
    pub(crate) norm_of_scaled: f64,
}

impl SplitDirection {
    /// `None` for a zero, NaN or infinite direction.
    pub(crate) fn new(d: &Vector3<f64>) -> Option<Self> {
        let largest = d.amax();
        if !(largest > 0.0 && largest.is_finite()) {
            return None;
        }
        let scaled = d / largest;
        let norm_of_scaled = scaled.norm();
        Some(SplitDirection {
            unit: scaled / norm_of_scaled,
            largest,
            norm_of_scaled,
        })
    }
}

/// A ray–surface intersection.
///
/// - `t`: the ray parameter, in units of `|dir|`.
/// - `point`: the surface point hit, `S(uv)` but for the rounding of `uv`
///   (see `uv`); `origin + t·dir` lies within the solver's accepted
///   residual of it (`max(tolerance, 1e-9) ×` the object's scale; after
///   Newton's polish usually a few ulps).
/// - `normal`: the surface's unit normal at the hit, oriented as the surface
///   defines it ([`Surface::normal`](crate::Surface::normal)), not flipped
///   toward the ray; compare its sign with `dir` to tell front from back.
/// - `uv`: the surface parameters of the hit, rounded to `f64`: `S(uv)` lies
///   within about `ε·(|u|·|S_u| + |v|·|S_v|)` of `point`. That is a few ulps
///   of the size unless a knot span is only a few ulps of its magnitude wide
///   (a patch's `u` domain `[0.27, 0.27 + 2 ulps]` can take three values):
///   the point then comes from the patch at the exact parameters, and `uv`
///   is their nearest representable value.
///
/// Never holds NaN.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Ray parameter of the hit.
    pub t: f64,
    /// The hit point.
    pub point: Point3<f64>,
    /// Unit surface normal at the hit (orientation of the surface).
    pub normal: Unit<Vector3<f64>>,
    /// Surface parameters `(u, v)` of the hit.
    pub uv: (f64, f64),
}

/// Something a ray can hit.
pub trait Intersect {
    /// The nearest hit with `t_min < t < t_max`, or `None` for a miss.
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit>;

    /// A box containing everything the object can be hit at.
    fn bounds(&self) -> Aabb;

    /// Many rays at once: `hits[i]` receives exactly what
    /// `intersect(&rays[i], ranges[i].0, ranges[i].1)` returns
    /// (`ranges[i] = (t_min, t_max)`). Slices of unequal length: only their
    /// common prefix is processed, the rest of `hits` is left as it was.
    ///
    /// The default loops over [`intersect`](Self::intersect); a type may
    /// override it with a faster path that gives the same hits.
    ///
    /// ```
    /// use revolve::{Bezier, Intersect, Ray, Revolution};
    /// use revolve::nalgebra::{Point2, Point3, Vector3};
    ///
    /// let cylinder = Revolution::new(Bezier::new(vec![
    ///     Point2::new(1.0, 0.0), Point2::new(1.0, 2.0)])?);
    /// let rays: Vec<Ray> = (0..4)
    ///     .map(|i| Ray::new(Point3::new(-3.0, 0.5 * i as f64, 0.0), Vector3::x()))
    ///     .collect();
    /// let mut hits = vec![None; rays.len()];
    /// cylinder.intersect_batch(&rays, &[(0.0, f64::INFINITY); 4], &mut hits);
    /// for (ray, hit) in rays.iter().zip(&hits) {
    ///     assert_eq!(*hit, cylinder.intersect(ray, 0.0, f64::INFINITY));
    /// }
    /// # Ok::<(), revolve::Error>(())
    /// ```
    fn intersect_batch(&self, rays: &[Ray], ranges: &[(f64, f64)], hits: &mut [Option<Hit>]) {
        for ((ray, &(t_min, t_max)), hit) in rays.iter().zip(ranges).zip(hits.iter_mut()) {
            *hit = self.intersect(ray, t_min, t_max);
        }
    }

    /// Every hit with `t_min < t < t_max`, in increasing `t`, into `hits`
    /// (cleared first), with [`intersect`](Self::intersect)'s guarantees:
    /// no transversal crossing missed, none false, a tangential double root
    /// once. `hits.first()` is what `intersect(ray, t_min, t_max)` returns.
    ///
    /// The default walks the ray as secondary rays do
    /// ([`walk_hits`]): `intersect(ray, tₖ, t_max)`
    /// from each hit `tₖ` gives the next, since a hit within the
    /// intersector's position uncertainty past `t_min` counts as the ray's
    /// own origin. A near-tangent root may be found once more just past
    /// itself; a hit whose distance from the surface could not have changed
    /// since the previous one (`Δt·|d·n|` within twice the acceptance, see
    /// [`walk_hits`]) is that root again and is
    /// passed over. No allocation beyond `hits` growing.
    ///
    /// ```
    /// use revolve::{Bezier, Intersect, Ray, Revolution};
    /// use revolve::nalgebra::{Point2, Point3, Vector3};
    ///
    /// // A cylinder of radius 1: a ray across it crosses the wall twice.
    /// let cylinder = Revolution::new(Bezier::new(vec![
    ///     Point2::new(1.0, 0.0), Point2::new(1.0, 2.0)])?);
    /// let ray = Ray::new(Point3::new(-3.0, 1.0, 0.0), Vector3::x());
    /// let mut hits = Vec::new();
    /// cylinder.intersect_all(&ray, 0.0, f64::INFINITY, &mut hits);
    /// assert_eq!(hits.len(), 2);
    /// assert!((hits[0].t - 2.0).abs() < 1e-14 && (hits[1].t - 4.0).abs() < 1e-14);
    /// assert_eq!(hits.first().copied(), cylinder.intersect(&ray, 0.0, f64::INFINITY));
    /// # Ok::<(), revolve::Error>(())
    /// ```
    fn intersect_all(&self, ray: &Ray, t_min: f64, t_max: f64, hits: &mut Vec<Hit>) {
        let scale = self.bounds().scale().max(ray.origin.coords.amax());
        walk_hits(
            |from| self.intersect(ray, from, t_max),
            ray,
            t_min,
            acceptance::Acceptance::ROUNDING * scale,
            hits,
        );
    }

    /// Whether anything lies on the ray with `t_min < t < t_max`: exactly
    /// `intersect(ray, t_min, t_max).is_some()` (a shadow ray's question).
    /// An implementor may stop at the first certified root it finds rather
    /// than the nearest; the default asks [`intersect`](Self::intersect).
    fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        self.intersect(ray, t_min, t_max).is_some()
    }
}

/// Consecutive finds of one root that [`walk_hits`] passes over before it
/// stops: only a ray lying in the surface (every point a root) comes near.
const MAX_REPEATS: usize = 8;

/// The walk behind [`Intersect::intersect_all`]: `next(from)` is the
/// nearest hit past `from` (an intersector's `intersect(ray, from, t_max)`),
/// called from `t_min` and then from each hit, into `hits` (cleared first).
///
/// A hit `h′` after `h` is the same root found again when the ray crosses
/// the surface the same way at both (`d·n·d·n′ ≥ 0`) and
/// `(t′ − t)·max(|d·n|, |d·n′|) ≤ 2·accept`: both ray points lie within
/// `accept` (the intersector's acceptance distance) of the surface, and the
/// ray's distance from a surface of normal `n` changes by `Δt·|d·n|`
/// between them, so nothing beyond the acceptance separates them. (The two
/// roots of a ray grazing a surface, however close, cross it opposite ways
/// and are both kept.) Such a repeat is passed over and the walk goes on
/// from it; after `MAX_REPEATS` in a row (a ray lying in the surface) it
/// stops. A `t` that does not increase (an
/// intersector breaking its contract) stops it too, so it always ends.
pub fn walk_hits(
    mut next: impl FnMut(f64) -> Option<Hit>,
    ray: &Ray,
    t_min: f64,
    accept: f64,
    hits: &mut Vec<Hit>,
) {
    hits.clear();
    let mut from = t_min;
    let mut repeats = 0;
    while let Some(hit) = next(from) {
        // NaN-safe: a t that is NaN or not past `from` ends the walk.
        let advances = hit.t > from;
        if !advances {
            break;
        }
        from = hit.t;
        let again = hits.last().is_some_and(|last: &Hit| {
            let (a, b) = (ray.dir.dot(&last.normal), ray.dir.dot(&hit.normal));
            a * b >= 0.0 && (hit.t - last.t) * a.abs().max(b.abs()) <= 2.0 * accept
        });
        if again {
            repeats += 1;
            if repeats >= MAX_REPEATS {
                break;
            }
            continue;
        }
        repeats = 0;
        hits.push(hit);
    }
}

/// How accurately a solver works: an explicit setting, no hidden epsilon.
///
/// `relative` is the target error of a hit (in `t`, and in the distance of the
/// hit point from the surface) relative to the object's scale (the largest
/// absolute coordinate of its bounding box). The default, `4ε ≈ 8.9e-16`, is
/// full double precision: solvers iterate until rounding stops them.
///
/// # Valid settings
/// `relative` in [`MIN_RELATIVE`](Self::MIN_RELATIVE) `..=`
/// [`MAX_RELATIVE`](Self::MAX_RELATIVE) and `max_iterations` in
/// `1..=`[`MAX_ITERATIONS`](Self::MAX_ITERATIONS). [`Tolerance::new`] checks
/// them; the fields are public, so every solver uses
/// [`clamped`](Self::clamped), which moves any setting (NaN, infinite,
/// negative, zero iterations) into that range. No setting can make a solver
/// hang or return NaN.
///
/// ```
/// use revolve::{Error, Tolerance};
///
/// let tol = Tolerance::new(1e-9, 16)?;
/// assert_eq!(tol.relative, 1e-9);
/// assert!(matches!(Tolerance::new(f64::NAN, 16), Err(Error::InvalidTolerance { .. })));
/// assert!(matches!(Tolerance::new(0.5, 16), Err(Error::ToleranceTooLarge { .. })));
/// // An unchecked setting is clamped where it is used.
/// assert_eq!(Tolerance::relative(10.0).clamped().relative, Tolerance::MAX_RELATIVE);
/// # Ok::<(), revolve::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Target error relative to the object's scale.
    pub relative: f64,
    /// Cap on the iterations of any one Newton refinement.
    pub max_iterations: u32,
}

impl Default for Tolerance {
    fn default() -> Self {
        Tolerance {
            relative: 4.0 * f64::EPSILON,
            max_iterations: 32,
        }
    }
}

impl Tolerance {
    /// The smallest relative target, `ε`: below it no double-precision
    /// solver can go.
    pub const MIN_RELATIVE: f64 = f64::EPSILON;
    /// The largest relative target, `1e-3`: a looser one would let the
    /// secondary-ray margin (hits within the tolerance of the ray's start
    /// are the start itself) swallow real hits.
    pub const MAX_RELATIVE: f64 = 1e-3;
    /// The largest iteration cap.
    pub const MAX_ITERATIONS: u32 = 1000;

    /// A checked tolerance.
    ///
    /// # Errors
    /// [`Error::InvalidTolerance`] for a `relative` that is NaN, infinite or
    /// not positive; [`Error::ToleranceTooSmall`] below
    /// [`MIN_RELATIVE`](Self::MIN_RELATIVE); [`Error::ToleranceTooLarge`]
    /// above [`MAX_RELATIVE`](Self::MAX_RELATIVE);
    /// [`Error::InvalidIterations`] for `max_iterations` of 0 or above
    /// [`MAX_ITERATIONS`](Self::MAX_ITERATIONS).
    pub fn new(relative: f64, max_iterations: u32) -> Result<Self, Error> {
        if !(relative.is_finite() && relative > 0.0) {
            return Err(Error::InvalidTolerance {
                tolerance: relative,
            });
        }
        if relative < Self::MIN_RELATIVE {
            return Err(Error::ToleranceTooSmall {
                tolerance: relative,
                min: Self::MIN_RELATIVE,
            });
        }
        if relative > Self::MAX_RELATIVE {
            return Err(Error::ToleranceTooLarge {
                tolerance: relative,
                max: Self::MAX_RELATIVE,
            });
        }
        if max_iterations == 0 || max_iterations > Self::MAX_ITERATIONS {
            return Err(Error::InvalidIterations {
                max_iterations,
                max: Self::MAX_ITERATIONS,
            });
        }
        Ok(Tolerance {
            relative,
            max_iterations,
        })
    }

    /// A tolerance with the given relative target and the default cap,
    /// unchecked: solvers use it [`clamped`](Self::clamped). Use
    /// [`Tolerance::new`] to have a bad value reported.
    pub fn relative(relative: f64) -> Self {
        Tolerance {
            relative,
            ..Self::default()
        }
    }

    /// The setting every solver actually uses: `relative` clamped into
    /// `[MIN_RELATIVE, MAX_RELATIVE]` (NaN becomes the default `4ε`), and
    /// `max_iterations` into `1..=MAX_ITERATIONS`. A valid tolerance is
    /// returned unchanged.
    pub fn clamped(self) -> Self {
        let relative = if self.relative.is_nan() {
            Self::default().relative
        } else {
            self.relative.clamp(Self::MIN_RELATIVE, Self::MAX_RELATIVE)
        };
        Tolerance {
            relative,
            max_iterations: self.max_iterations.clamp(1, Self::MAX_ITERATIONS),
        }
    }
}
