//! Boxes of parameter rectangles of a surface of revolution
//! ([`PatchBounds`]): the profile piece's height and radius ranges from its
//! control points, swept through the angle range.

use crate::bernstein::restrict;
use crate::{Aabb, Curve, PatchBounds, Revolution};
use nalgebra::Point3;
use std::f64::consts::TAU;

/// Conservative patch bounds (for the generic Newton intersector).
///
/// The box of `S([u₀, u₁] × [θ₀, θ₁])` is built in three exact-or-outward
/// steps:
///
/// 1. **Profile ranges.** With [Bézier spans](Curve::bezier_spans) (as
///    [`Bezier`](crate::Bezier) and [`BSpline`](crate::BSpline) give), every
///    span overlapping `[u₀, u₁]` is cut to the overlap by two de Casteljau
///    subdivisions and the ranges of `x` and `y` are those of the cut
///    control points: by the convex hull property (Farin, *Curves and
///    Surfaces for CAGD*, §4.2) they contain the profile. Profiles without
///    spans are sampled at 33 points with their derivatives and the ranges
///    widened by `h·M` (`h` the sample spacing, `M` the largest sampled
///    speed `|P′|`): every point lies within `h/2·sup|P′|` of a sample, so
///    this is conservative whenever the speed on the patch is at most twice
///    its largest sampled value. No bound from samples can be unconditional
///    for an arbitrary curve; give the profile Bézier spans for a guarantee.
/// 2. **Annular sectors.** A profile point `(x, y)` at angle `θ` is
///    `(x cos θ, y, −x sin θ)`; negative `x` is `|x|` at `θ + π`. So the
///    patch lies in the union of the sector `r ∈ [max(x_min, 0), x_max]`,
///    `θ ∈ [θ₀, θ₁]` (when `x_max ≥ 0`) and the sector
///    `r ∈ [max(−x_max, 0), −x_min]`, `θ ∈ [θ₀ + π, θ₁ + π]` (when
///    `x_min < 0`). The box of a sector is exact: `r cos θ` over
///    `[r₀, r₁] × [θ₀, θ₁]` ranges over the products of the ends of
///    `[r₀, r₁]` and of the range of `cos θ`, which is the range at the ends
///    widened to `±1` where the interval contains a multiple of `π` (and
///    likewise `−r sin θ` with the odd multiples of `π/2`).
/// 3. **World frame.** The local box is moved by the rigid motion
///    [`to_world`](Revolution::to_world) by interval arithmetic
///    ([`Aabb::transformed`]: exactly the box of the rotated box). Finally the box grows by `16(n + 2)·ε` times the local
///    plus world coordinate magnitudes (`n` the profile degree), which covers
///    the rounding of subdivision, of the transform and of
///    [`eval`](crate::Surface::eval).
impl<C: Curve<2>> PatchBounds for Revolution<C> {
    fn bound_patch(&self, u: (f64, f64), v: (f64, f64)) -> Aabb {
        let (u0, u1) = (u.0.min(u.1), u.0.max(u.1));
        let (v0, v1) = (v.0.min(v.1), v.0.max(v.1));
        let (xr, yr, degree) = profile_ranges(&self.profile, u0, u1);
        if !(xr.0 <= xr.1 && yr.0 <= yr.1) {
            return Aabb::EMPTY;
        }
        // Local x and z ranges of the sector(s).
        let mut xz = (
            (f64::INFINITY, f64::NEG_INFINITY),
            (f64::INFINITY, f64::NEG_INFINITY),
        );
        let mut add = |(a, b): ((f64, f64), (f64, f64))| {
            xz.0 = (xz.0.0.min(a.0), xz.0.1.max(a.1));
            xz.1 = (xz.1.0.min(b.0), xz.1.1.max(b.1));
        };
        if xr.1 >= 0.0 {
            add(sector_box((xr.0.max(0.0), xr.1), (v0, v1)));
        }
        if xr.0 < 0.0 {
            let pi = std::f64::consts::PI;
            add(sector_box(((-xr.1).max(0.0), -xr.0), (v0 + pi, v1 + pi)));
        }
        let local = Aabb {
            min: Point3::new(xz.0.0, yr.0, xz.1.0),
            max: Point3::new(xz.0.1, yr.1, xz.1.1),
        };
        let world = local.transformed(&self.to_world);
        let world_mag = world.center().coords.amax() + (world.extent() * 0.5).amax();
        let pad = 16.0 * (degree as f64 + 2.0) * f64::EPSILON * (local.scale() + world_mag);
        world.expand(pad)
    }

    /// The angle `θ` is periodic (period `2π`); the profile parameter is not.
    fn periodic(&self) -> [bool; 2] {
        [false, true]
    }
}
/// Conservative ranges of the profile's `x` and `y` over `[u0, u1]`, and the
/// profile degree used for the rounding pad (see the `PatchBounds` impl).
fn profile_ranges<C: Curve<2>>(profile: &C, u0: f64, u1: f64) -> ((f64, f64), (f64, f64), usize) {
    let empty = (f64::INFINITY, f64::NEG_INFINITY);
    let widen = |r: (f64, f64), x: f64| (r.0.min(x), r.1.max(x));
    let (mut xr, mut yr) = (empty, empty);
    if let Some(spans) = profile.rational_bezier_spans() {
        let mut degree = 0;
        for span in &spans {
            let (a, b) = span.knots;
            if b < u0 || a > u1 || b <= a {
                continue;
            }
            let curve = &span.curve;
            degree = degree.max(curve.degree());
            let s0 = ((u0 - a) / (b - a)).clamp(0.0, 1.0);
            let s1 = ((u1 - a) / (b - a)).clamp(0.0, 1.0);
            // A rational piece is cut in homogeneous coordinates (wx, wy, w);
            // the cut control points (divided back) bound it as well.
            let pts = curve.points().iter().zip(curve.weights());
            let cut = if curve.is_polynomial() {
                cut_piece(pts.map(|(p, _)| p.coords).collect(), (s0, s1))
            } else {
                let h = pts.map(|(p, &w)| nalgebra::Vector3::new(p.x * w, p.y * w, w));
                cut_piece(h.collect(), (s0, s1))
                    .into_iter()
                    .map(|h| nalgebra::Vector2::new(h.x / h.z, h.y / h.z))
                    .collect()
            };
            for q in cut.iter() {
                xr = widen(xr, q.x);
                yr = widen(yr, q.y);
            }
        }
        if xr.0 <= xr.1 {
            return (xr, yr, degree);
        }
    }
    // No spans: 33 samples, widened by h·M (see the impl's docs).
    const SAMPLES: usize = 32;
    let h = (u1 - u0) / SAMPLES as f64;
    let mut speed = 0.0_f64;
    for i in 0..=SAMPLES {
        let t = if i == SAMPLES { u1 } else { u0 + h * i as f64 };
        let (p, d) = profile.eval_with_derivative(t);
        xr = widen(xr, p.x);
        yr = widen(yr, p.y);
        speed = speed.max(d.norm());
    }
    let m = h * speed;
    ((xr.0 - m, xr.1 + m), (yr.0 - m, yr.1 + m), 3)
}
/// The exact local `(x, z)` ranges of the sector `{(r cos θ, −r sin θ)}`,
/// `r ∈ [r0, r1]` (`0 ≤ r0 ≤ r1`), `θ ∈ [θ0, θ1]`.
fn sector_box((r0, r1): (f64, f64), (t0, t1): (f64, f64)) -> ((f64, f64), (f64, f64)) {
    use std::f64::consts::{FRAC_PI_2, PI};
    // Whether [t0, t1] contains α + 2kπ for some k; a hair of slack keeps
    // extremes that rounding might put just outside (a larger box is safe).
    let contains = |alpha: f64| {
        if t1 - t0 >= TAU {
            return true;
        }
        let slack = 1e-12 * (1.0 + t0.abs().max(t1.abs()));
        let k = ((t0 - slack - alpha) / TAU).ceil();
        alpha + k * TAU <= t1 + slack
    };
    let ((s0, c0), (s1, c1)) = (t0.sin_cos(), t1.sin_cos());
    let cos_max = if contains(0.0) { 1.0 } else { c0.max(c1) };
    let cos_min = if contains(PI) { -1.0 } else { c0.min(c1) };
    let sin_max = if contains(FRAC_PI_2) { 1.0 } else { s0.max(s1) };
    let sin_min = if contains(-FRAC_PI_2) {
        -1.0
    } else {
        s0.min(s1)
    };
    // The range of r·w over [r0, r1] × [w0, w1] is that of the corners.
    let product = |w0: f64, w1: f64| {
        let c = [r0 * w0, r0 * w1, r1 * w0, r1 * w1];
        (
            c.iter().fold(f64::INFINITY, |m, &x| m.min(x)),
            c.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x)),
        )
    };
    (product(cos_min, cos_max), product(-sin_max, -sin_min))
}

/// The Bézier coefficients `c` of a piece restricted to `[s0, s1]`.
fn cut_piece<T: crate::bernstein::Coefficient>(mut c: Vec<T>, range: (f64, f64)) -> Vec<T> {
    restrict(&mut c, range);
    c
}
