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
/// - `point`: the surface point `S(uv)`; `origin + t·dir` lies within the
///   solver's accepted residual of it (`max(tolerance, 1e-9) ×` the object's
///   scale; after Newton's polish usually a few ulps).
/// - `normal`: the surface's unit normal at the hit, oriented as the surface
///   defines it ([`Surface::normal`](crate::Surface::normal)), not flipped
///   toward the ray; compare its sign with `dir` to tell front from back.
/// - `uv`: the surface parameters of the hit.
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
