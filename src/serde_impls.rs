//! `Serialize` and `Deserialize` (feature `serde`) for the curves, the
//! surfaces, rays, tolerances and boxes.
//!
//! Each type is written as its defining data, a struct of named fields:
//!
//! | type | fields |
//! | --- | --- |
//! | [`Bezier<D>`] | `points` |
//! | [`BSpline<D>`] | `degree`, `knots`, `points` |
//! | [`RationalBezier<D>`] | `points`, `weights` |
//! | [`Nurbs<D>`] | `degree`, `knots`, `points`, `weights` |
//! | [`Revolution<C>`] | `profile`, `origin`, `axis`, `tolerance`, `reversed`², `turn`³ |
//! | [`BezierSurface`] | `points` (rows along `u`), `tolerance`¹, `reversed`² |
//! | [`BezierPatches`] | `patches` (each a [`BezierSurface`]), `tolerance`¹ |
//! | [`BSplineSurface`] | `degrees`, `knots` (`u`, `v`), `points`, `tolerance`¹, `reversed`² |
//! | [`NurbsSurface`] | `degrees`, `knots`, `points`, `weights`, `tolerance`¹, `reversed`² |
//! | [`Tolerance`] | `relative`, `max_iterations` |
//! | [`Ray`] | `origin`, `dir` |
//! | [`Aabb`] | `min`, `max` |
//!
//! ¹ Written only when it is not the default; read as the default when
//! absent.
//!
//! ² The orientation flag of `reversed()`: written (`true`) only for a
//! reversed surface; absent reads as `false`, so data written before the
//! flag existed still reads.
//!
//! ³ The turn (radians) about the axis that [`Revolution::transformed`]
//! composes: written only when not 0, absent reads as 0. A moved
//! revolution reads back to rounding of its composed rotation.
//!
//! Points and vectors are sequences of their coordinates (nalgebra's own
//! serde form). Reading goes through the public constructor
//! ([`Bezier::new`], [`BSpline::new`], [`RationalBezier::new`],
//! [`Nurbs::new`], [`BezierPatches::new`], [`Tolerance::new`], [`Revolution::try_new`] then
//! [`Revolution::try_with_axis`]), so a deserialized value is exactly as
//! valid as a constructed one, and bad data (a NaN coordinate, a wrong knot
//! count, a weight that is not positive, a tolerance out of range, a zero
//! axis) is a deserialization error whose message is the crate's
//! [`Error`](crate::Error) message. Unknown fields are errors too.
//!
//! Caches are not written: a revolution's intersector tables are rebuilt
//! from the profile when it is read, a model's hierarchy from its patches. A revolution whose profile or placement
//! is broken (see [`Revolution::contract_error`]) cannot be serialized (it
//! could not be read back); neither can a [`Tolerance`] made unchecked with
//! values [`Tolerance::new`] refuses be read back. [`Ray`] and [`Aabb`] have
//! public fields and no checks, so any values round-trip (as far as the
//! format can carry them: JSON has no NaN or infinity).
//!
//! ```
//! use revolve::nalgebra::Point2;
//! use revolve::{Error, Nurbs, Revolution};
//! use std::f64::consts::FRAC_PI_2;
//!
//! // A sphere: the half circle from the south pole to the north pole, turned.
//! let arc = Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2)?;
//! let sphere = Revolution::new(arc);
//! let json = serde_json::to_string(&sphere).unwrap();
//! let back: Revolution<Nurbs<2>> = serde_json::from_str(&json).unwrap();
//! assert_eq!(back, sphere);
//!
//! // Bad data is refused with the constructor's message.
//! let bad = r#"{"degree": 1, "knots": [0, 0, 1, 1], "points": [[0, 0], [1, 1]], "weights": [1, -2]}"#;
//! let e = serde_json::from_str::<Nurbs<2>>(bad).unwrap_err();
//! let expected = Error::InvalidWeight { index: 1, weight: -2.0 };
//! assert!(e.to_string().starts_with(&expected.to_string()));
//! # Ok::<(), Error>(())
//! ```

use std::borrow::Cow;

use nalgebra::{Point, Point3, Unit, Vector3};
use serde::{Deserialize, Deserializer, Serialize, Serializer, de, ser};

use crate::{
    Aabb, BSpline, BSplineSurface, Bezier, BezierPatches, BezierSurface, Curve, Nurbs,
    NurbsSurface, RationalBezier, Ray, Revolution, Tolerance,
};

/// A type written as its defining data and read back through its public
/// constructor. `Serialize` writes [`written`](Self::written); `Deserialize`
/// reads a [`Read`](Self::Read) and passes it to [`read`](Self::read), whose
/// error (the constructor's, as the crate's [`Error`](crate::Error) message)
/// becomes the deserializer's.
trait DefiningData: Sized {
    /// The data as written, borrowed from the value.
    type Written<'a>
    where
        Self: 'a;
    /// The data as read.
    type Read;
    /// The value's defining data, or why it cannot be written.
    fn written<E: ser::Error>(&self) -> Result<Self::Written<'_>, E>;
    /// The value built from its data by its public constructor.
    fn read<E: de::Error>(data: Self::Read) -> Result<Self, E>;
}

/// `Serialize` and `Deserialize` through [`DefiningData`], for each
/// `[generic parameters] type`.
macro_rules! serde_through_defining_data {
    ($([$($generics:tt)*] $ty:ty;)*) => {$(
        impl<$($generics)*> Serialize for $ty {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                self.written()?.serialize(serializer)
            }
        }

        impl<'de, $($generics)*> Deserialize<'de> for $ty {
            fn deserialize<De: Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
                Self::read(<$ty as DefiningData>::Read::deserialize(deserializer)?)
            }
        }
    )*};
}

serde_through_defining_data! {
    [const D: usize] Bezier<D>;
    [const D: usize] BSpline<D>;
    [const D: usize] RationalBezier<D>;
    [const D: usize] Nurbs<D>;
    [] BezierSurface;
    [] BezierPatches;
    [] BSplineSurface;
    [] NurbsSurface;
    [] Tolerance;
    [] Ray;
    [] Aabb;
}

/// The defining data of a [`Bezier`]: borrowed when written, owned when read.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Bezier", deny_unknown_fields)]
struct BezierData<'a, const D: usize> {
    points: Cow<'a, [Point<f64, D>]>,
}

impl<const D: usize> DefiningData for Bezier<D> {
    type Written<'a> = BezierData<'a, D>;
    type Read = BezierData<'static, D>;
    fn written<E: ser::Error>(&self) -> Result<BezierData<'_, D>, E> {
        Ok(BezierData {
            points: Cow::Borrowed(self.points()),
        })
    }
    fn read<E: de::Error>(data: Self::Read) -> Result<Self, E> {
        Bezier::new(data.points.into_owned()).map_err(E::custom)
    }
}

/// The defining data of a [`BSpline`].
#[derive(Serialize, Deserialize)]
#[serde(rename = "BSpline", deny_unknown_fields)]
struct BSplineData<'a, const D: usize> {
    degree: usize,
    knots: Cow<'a, [f64]>,
    points: Cow<'a, [Point<f64, D>]>,
}

impl<const D: usize> DefiningData for BSpline<D> {
    type Written<'a> = BSplineData<'a, D>;
    type Read = BSplineData<'static, D>;
    fn written<E: ser::Error>(&self) -> Result<BSplineData<'_, D>, E> {
        Ok(BSplineData {
            degree: self.degree(),
            knots: Cow::Borrowed(self.knots()),
            points: Cow::Borrowed(self.points()),
        })
    }
    fn read<E: de::Error>(data: Self::Read) -> Result<Self, E> {
        let (knots, points) = (data.knots.into_owned(), data.points.into_owned());
        BSpline::new(data.degree, knots, points).map_err(E::custom)
    }
}

/// The defining data of a [`RationalBezier`].
#[derive(Serialize, Deserialize)]
#[serde(rename = "RationalBezier", deny_unknown_fields)]
struct RationalBezierData<'a, const D: usize> {
    points: Cow<'a, [Point<f64, D>]>,
    weights: Cow<'a, [f64]>,
}

impl<const D: usize> DefiningData for RationalBezier<D> {
    type Written<'a> = RationalBezierData<'a, D>;
    type Read = RationalBezierData<'static, D>;
    fn written<E: ser::Error>(&self) -> Result<RationalBezierData<'_, D>, E> {
        Ok(RationalBezierData {
            points: Cow::Borrowed(self.points()),
            weights: Cow::Borrowed(self.weights()),
        })
    }
    fn read<E: de::Error>(data: Self::Read) -> Result<Self, E> {
        RationalBezier::new(data.points.into_owned(), data.weights.into_owned()).map_err(E::custom)
    }
}

/// The defining data of a [`Nurbs`].
#[derive(Serialize, Deserialize)]
#[serde(rename = "Nurbs", deny_unknown_fields)]
struct NurbsData<'a, const D: usize> {
    degree: usize,
    knots: Cow<'a, [f64]>,
    points: Cow<'a, [Point<f64, D>]>,
    weights: Cow<'a, [f64]>,
}

impl<const D: usize> DefiningData for Nurbs<D> {
    type Written<'a> = NurbsData<'a, D>;
    type Read = NurbsData<'static, D>;
    fn written<E: ser::Error>(&self) -> Result<NurbsData<'_, D>, E> {
        Ok(NurbsData {
            degree: self.degree(),
            knots: Cow::Borrowed(self.knots()),
            points: Cow::Borrowed(self.points()),
            weights: Cow::Borrowed(self.weights()),
        })
    }
    fn read<E: de::Error>(data: Self::Read) -> Result<Self, E> {
        let (knots, points) = (data.knots.into_owned(), data.points.into_owned());
        Nurbs::new(data.degree, knots, points, data.weights.into_owned()).map_err(E::custom)
    }
}

/// Whether a tolerance is the default one (then it is not written).
fn is_default(t: &Tolerance) -> bool {
    *t == Tolerance::default()
}

/// Whether an orientation flag is the default `false` (then it is not
/// written).
fn is_false(reversed: &bool) -> bool {
    !*reversed
}

/// The defining data of a [`BezierSurface`]: its control net, rows along `u`.
#[derive(Serialize, Deserialize)]
#[serde(rename = "BezierSurface", deny_unknown_fields)]
struct BezierSurfaceData<'a> {
    points: Cow<'a, [Vec<Point3<f64>>]>,
    #[serde(default, skip_serializing_if = "is_default")]
    tolerance: Tolerance,
    #[serde(default, skip_serializing_if = "is_false")]
    reversed: bool,
}

impl DefiningData for BezierSurface {
    type Written<'a> = BezierSurfaceData<'a>;
    type Read = BezierSurfaceData<'static>;
    fn written<E: ser::Error>(&self) -> Result<BezierSurfaceData<'_>, E> {
        Ok(BezierSurfaceData {
            points: Cow::Borrowed(self.points()),
            tolerance: *self.tolerance(),
            reversed: self.is_reversed(),
        })
    }
    fn read<E: de::Error>(data: Self::Read) -> Result<Self, E> {
        BezierSurface::new(data.points.into_owned())
            .map(|s| s.with_tolerance(data.tolerance))
            .map(|s| if data.reversed { s.reversed() } else { s })
            .map_err(E::custom)
    }
}

/// The defining data of a [`BezierPatches`] model.
#[derive(Serialize, Deserialize)]
#[serde(rename = "BezierPatches", deny_unknown_fields)]
struct BezierPatchesData<'a> {
    patches: Cow<'a, [BezierSurface]>,
    #[serde(default, skip_serializing_if = "is_default")]
    tolerance: Tolerance,
}

impl DefiningData for BezierPatches {
    type Written<'a> = BezierPatchesData<'a>;
    type Read = BezierPatchesData<'static>;
    fn written<E: ser::Error>(&self) -> Result<BezierPatchesData<'_>, E> {
        Ok(BezierPatchesData {
            patches: Cow::Borrowed(self.patches()),
            tolerance: *self.tolerance(),
        })
    }
    fn read<E: de::Error>(data: Self::Read) -> Result<Self, E> {
        BezierPatches::new(data.patches.into_owned())
            .map(|m| m.with_tolerance(data.tolerance))
            .map_err(E::custom)
    }
}

/// The defining data of a [`BSplineSurface`] or, with weights, a
/// [`NurbsSurface`].
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct TensorSplineData<'a> {
    degrees: (usize, usize),
    knots: (Cow<'a, [f64]>, Cow<'a, [f64]>),
    points: Cow<'a, [Vec<Point3<f64>>]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weights: Option<Cow<'a, [Vec<f64>]>>,
    #[serde(default, skip_serializing_if = "is_default")]
    tolerance: Tolerance,
    #[serde(default, skip_serializing_if = "is_false")]
    reversed: bool,
}

impl DefiningData for BSplineSurface {
    type Written<'a> = TensorSplineData<'a>;
    type Read = TensorSplineData<'static>;
    fn written<E: ser::Error>(&self) -> Result<TensorSplineData<'_>, E> {
        let (ku, kv) = self.knots();
        Ok(TensorSplineData {
            degrees: self.degrees(),
            knots: (Cow::Borrowed(ku), Cow::Borrowed(kv)),
            points: Cow::Borrowed(self.points()),
            weights: None,
            tolerance: *self.tolerance(),
            reversed: self.is_reversed(),
        })
    }
    fn read<E: de::Error>(data: Self::Read) -> Result<Self, E> {
        if data.weights.is_some() {
            return Err(E::custom(
                "a B-spline surface has no weights (read it as a NurbsSurface)",
            ));
        }
        let knots = (data.knots.0.into_owned(), data.knots.1.into_owned());
        BSplineSurface::new(data.degrees, knots, data.points.into_owned())
            .map(|s| s.with_tolerance(data.tolerance))
            .map(|s| if data.reversed { s.reversed() } else { s })
            .map_err(E::custom)
    }
}

impl DefiningData for NurbsSurface {
    type Written<'a> = TensorSplineData<'a>;
    type Read = TensorSplineData<'static>;
    fn written<E: ser::Error>(&self) -> Result<TensorSplineData<'_>, E> {
        let (ku, kv) = self.knots();
        Ok(TensorSplineData {
            degrees: self.degrees(),
            knots: (Cow::Borrowed(ku), Cow::Borrowed(kv)),
            points: Cow::Borrowed(self.points()),
            weights: Some(Cow::Borrowed(self.weights())),
            tolerance: *self.tolerance(),
            reversed: self.is_reversed(),
        })
    }
    fn read<E: de::Error>(data: Self::Read) -> Result<Self, E> {
        let Some(weights) = data.weights else {
            return Err(E::missing_field("weights"));
        };
        let knots = (data.knots.0.into_owned(), data.knots.1.into_owned());
        let (points, weights) = (data.points.into_owned(), weights.into_owned());
        NurbsSurface::new(data.degrees, knots, points, weights)
            .map(|s| s.with_tolerance(data.tolerance))
            .map(|s| if data.reversed { s.reversed() } else { s })
            .map_err(E::custom)
    }
}

/// The defining data of a [`Tolerance`].
#[derive(Serialize, Deserialize)]
#[serde(rename = "Tolerance", deny_unknown_fields)]
struct ToleranceData {
    relative: f64,
    max_iterations: u32,
}

impl DefiningData for Tolerance {
    type Written<'a> = ToleranceData;
    type Read = ToleranceData;
    fn written<E: ser::Error>(&self) -> Result<ToleranceData, E> {
        Ok(ToleranceData {
            relative: self.relative,
            max_iterations: self.max_iterations,
        })
    }
    fn read<E: de::Error>(data: ToleranceData) -> Result<Self, E> {
        Tolerance::new(data.relative, data.max_iterations).map_err(E::custom)
    }
}

/// The defining data of a [`Revolution`]: the profile (by reference when
/// written), the placement and the accuracy.
#[derive(Serialize, Deserialize)]
#[serde(rename = "Revolution", deny_unknown_fields)]
struct RevolutionData<P> {
    profile: P,
    origin: Point3<f64>,
    axis: Vector3<f64>,
    tolerance: Tolerance,
    #[serde(default, skip_serializing_if = "is_false")]
    reversed: bool,
    /// The turn about the axis of a revolution moved by
    /// [`Revolution::transformed`] (radians; written only when not 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    turn: f64,
}

/// Whether an angle is zero (not written).
fn is_zero(angle: &f64) -> bool {
    *angle == 0.0
}

impl<C: Curve<2>> DefiningData for Revolution<C> {
    type Written<'a>
        = RevolutionData<&'a C>
    where
        C: 'a;
    type Read = RevolutionData<C>;
    fn written<E: ser::Error>(&self) -> Result<RevolutionData<&C>, E> {
        if let Some(e) = self.contract_error() {
            return Err(E::custom(format_args!(
                "a broken revolution cannot be written: {e}"
            )));
        }
        Ok(RevolutionData {
            profile: self.profile(),
            origin: Point3::from(self.to_world().translation.vector),
            axis: *self.scaled_axis(),
            tolerance: *self.tolerance(),
            reversed: self.reversed,
            turn: self.turn(),
        })
    }
    fn read<E: de::Error>(data: RevolutionData<C>) -> Result<Self, E> {
        if !data.turn.is_finite() {
            return Err(E::custom(format_args!(
                "a revolution's turn about its axis must be a finite angle, not {}",
                data.turn
            )));
        }
        // `try_with_axis` checks the axis itself (finite, not zero) and
        // brings it to unit length.
        Revolution::try_new(data.profile)
            .and_then(|r| r.try_with_axis(data.origin, Unit::new_unchecked(data.axis)))
            .map(|r| r.with_tolerance(data.tolerance).with_turn(data.turn))
            .map(|mut r| {
                r.reversed = data.reversed;
                r
            })
            .map_err(E::custom)
    }
}

impl<C: Curve<2> + Serialize> Serialize for Revolution<C> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.written()?.serialize(serializer)
    }
}

impl<'de, C: Curve<2> + Deserialize<'de>> Deserialize<'de> for Revolution<C> {
    fn deserialize<De: Deserializer<'de>>(deserializer: De) -> Result<Self, De::Error> {
        Self::read(RevolutionData::<C>::deserialize(deserializer)?)
    }
}

/// The fields of a [`Ray`].
#[derive(Serialize, Deserialize)]
#[serde(rename = "Ray", deny_unknown_fields)]
struct RayData {
    origin: Point3<f64>,
    dir: Vector3<f64>,
}

impl DefiningData for Ray {
    type Written<'a> = RayData;
    type Read = RayData;
    fn written<E: ser::Error>(&self) -> Result<RayData, E> {
        Ok(RayData {
            origin: self.origin,
            dir: self.dir,
        })
    }
    fn read<E: de::Error>(data: RayData) -> Result<Self, E> {
        Ok(Ray::new(data.origin, data.dir))
    }
}

/// The fields of an [`Aabb`] (read as given: any corners make a box, an
/// inverted one is empty).
#[derive(Serialize, Deserialize)]
#[serde(rename = "Aabb", deny_unknown_fields)]
struct AabbData {
    min: Point3<f64>,
    max: Point3<f64>,
}

impl DefiningData for Aabb {
    type Written<'a> = AabbData;
    type Read = AabbData;
    fn written<E: ser::Error>(&self) -> Result<AabbData, E> {
        Ok(AabbData {
            min: self.min,
            max: self.max,
        })
    }
    fn read<E: de::Error>(data: AabbData) -> Result<Self, E> {
        Ok(Aabb {
            min: data.min,
            max: data.max,
        })
    }
}
