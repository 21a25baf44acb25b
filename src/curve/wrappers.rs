//! [`Curve`] for references and smart pointers: `&C`, `&mut C`, `Box<C>`,
//! `Rc<C>` and `Arc<C>`, for any `C: Curve<D> + ?Sized`, so also
//! `Box<dyn Curve<D>>`, `Arc<dyn Curve<D> + Send + Sync>` and the like.
//!
//! Every method of the trait is forwarded to the pointee, the ones with
//! default implementations too ([`bezier_spans`](Curve::bezier_spans),
//! [`rational_bezier_spans`](Curve::rational_bezier_spans),
//! [`tangent`](Curve::tangent), [`nearest_point`](Curve::nearest_point),
//! [`arc_length`](Curve::arc_length), …): a wrapped curve is the same curve,
//! bit for bit, and keeps whatever its concrete type overrides. In
//! particular a [`Revolution`](crate::Revolution) of a wrapped profile with
//! Bézier spans keeps the exact intersector.
//!
//! ```
//! use revolve::{Bezier, Curve, Revolution};
//! use revolve::nalgebra::Point2;
//! use std::sync::Arc;
//!
//! let profile = Bezier::new(vec![Point2::new(1.0, 0.0), Point2::new(2.0, 1.0), Point2::new(1.0, 2.0)])?;
//! let boxed: Box<dyn Curve<2>> = Box::new(profile.clone());
//! assert_eq!(boxed.eval(0.3), profile.eval(0.3));
//! assert!(boxed.bezier_spans().is_some());
//! assert!(Revolution::new(boxed).has_exact_intersector());
//! assert!(Revolution::new(&profile).has_exact_intersector());
//! assert!(Revolution::new(Arc::new(profile)).has_exact_intersector());
//! # Ok::<(), revolve::Error>(())
//! ```

use super::{ArcLength, BezierSpan, Curve, CurveSample, NearestPoint, RationalBezierSpan};
use crate::Error;
use nalgebra::{Point, SVector, Unit};
use std::rc::Rc;
use std::sync::Arc;

/// `impl Curve<D>` for a pointer type whose target is `C`, forwarding every
/// method to `**self`.
macro_rules! forward_curve {
    ($($pointer:ty),* $(,)?) => {$(
        impl<C: Curve<D> + ?Sized, const D: usize> Curve<D> for $pointer {
            #[inline]
            fn domain(&self) -> (f64, f64) {
                (**self).domain()
            }
            #[inline]
            fn eval(&self, t: f64) -> Point<f64, D> {
                (**self).eval(t)
            }
            #[inline]
            fn derivative(&self, t: f64) -> SVector<f64, D> {
                (**self).derivative(t)
            }
            #[inline]
            fn eval_with_derivative(&self, t: f64) -> (Point<f64, D>, SVector<f64, D>) {
                (**self).eval_with_derivative(t)
            }
            #[inline]
            fn tangent(&self, t: f64) -> Option<Unit<SVector<f64, D>>> {
                (**self).tangent(t)
            }
            #[inline]
            fn bezier_spans(&self) -> Option<Vec<BezierSpan<D>>> {
                (**self).bezier_spans()
            }
            #[inline]
            fn rational_bezier_spans(&self) -> Option<Vec<RationalBezierSpan<D>>> {
                (**self).rational_bezier_spans()
            }
            #[inline]
            fn nearest_point(&self, p: &Point<f64, D>) -> Result<NearestPoint<D>, Error> {
                (**self).nearest_point(p)
            }
            #[inline]
            fn arc_length(&self, tolerance: f64) -> Result<ArcLength, Error> {
                (**self).arc_length(tolerance)
            }
            #[inline]
            fn parameter_at_length(&self, s: f64, tolerance: f64) -> Result<f64, Error> {
                (**self).parameter_at_length(s, tolerance)
            }
            #[inline]
            fn divide_by_length(&self, pieces: usize, tolerance: f64) -> Result<Vec<f64>, Error> {
                (**self).divide_by_length(pieces, tolerance)
            }
            #[inline]
            fn discretize(&self, segments: usize) -> Vec<CurveSample<D>> {
                (**self).discretize(segments)
            }
            #[inline]
            fn try_discretize(&self, segments: usize) -> Result<Vec<CurveSample<D>>, Error> {
                (**self).try_discretize(segments)
            }
        }
    )*};
}

forward_curve!(&C, &mut C, Box<C>, Rc<C>, Arc<C>);
