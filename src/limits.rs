//! The numeric limits on accepted input, which the error messages quote.

/// The largest control-point coordinate or knot magnitude accepted (`1e100`).
///
/// Far beyond any geometry, and small enough that differences, hodographs and
/// squared distances of accepted values cannot overflow.
pub const MAX_COORDINATE: f64 = 1e100;

/// The largest derivative magnitude a [`Bezier`](crate::Bezier) or
/// [`BSpline`](crate::BSpline) may have (`1e300`): constructors refuse curves
/// whose derivatives of some order could exceed it
/// ([`Error::DerivativeOverflow`](crate::Error::DerivativeOverflow)), so that
/// every derivative of an accepted curve, of any order, is finite.
pub const MAX_DERIVATIVE: f64 = 1e300;
