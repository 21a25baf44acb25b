//! The analytic shapes in their own frame: sphere, plane, triangle, box,
//! disk and ring (one annulus type), and rectangle (a parallelogram).
//!
//! Every `intersect` takes a ray whose direction need not be unit length
//! (`t` in units of `|dir|`) and returns the nearest hit with
//! `t_min < t < t_max`. Comparisons are written so that a NaN never passes as
//! a hit. Degenerate input (zero radius, zero-area triangle or rectangle, zero
//! normal, non-finite numbers) makes the constructor return `None`: such a
//! shape never hits.
//!
//! Normals are returned unnormalized (the caller transforms, then normalizes
//! once): outward for the closed shapes (sphere, box); for the open ones, the
//! given plane or disk normal, `edge1 × edge2` for a rectangle and
//! `(v1 − v0) × (v2 − v0)` for a triangle. UVs lie in `[0, 1]²`.

use std::f64::consts::{PI, TAU};

use revolve::nalgebra::{Point3, Vector3};
use revolve::{Aabb, Ray};

/// A hit in a shape's own frame.
#[derive(Debug, Clone, Copy)]
pub struct LocalHit {
    pub t: f64,
    pub point: Point3<f64>,
    /// Not necessarily unit; oriented as the module docs say.
    pub normal: Vector3<f64>,
    /// Spheres, planes, disks and rings leave this `(0, 0)` and compute it
    /// with their `uv` method, for the nearest hit only (it takes
    /// trigonometry or a floating-point remainder).
    pub uv: (f64, f64),
}

/// Whether every coordinate is finite.
pub fn finite(v: &Vector3<f64>) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// Whether `t_min < t < t_max` (false for NaN).
#[inline(always)]
pub fn in_range(t: f64, t_min: f64, t_max: f64) -> bool {
    t > t_min && t < t_max
}

/// An orthonormal pair `(e1, e2)` with `e1 × e2 = n` for a unit `n`
/// (Duff et al., "Building an orthonormal basis, revisited", 2017: no
/// branch on a threshold, continuous except across `n_z = 0`).
pub fn basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let sign = 1.0f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vector3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vector3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// `x / y` clamped to `[0, 1]` (0 when `y` is 0).
#[inline]
fn fraction(x: f64, y: f64) -> f64 {
    if y > 0.0 {
        (x / y).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The angle of `(x, y)` as a fraction of a turn in `[0, 1]`.
#[inline]
pub fn turn(y: f64, x: f64) -> f64 {
    (y.atan2(x).rem_euclid(TAU) / TAU).clamp(0.0, 1.0)
}

/// The two roots of `|f + t·g|² = r²`, smaller first; `None` when the line
/// misses (or `g = 0`). A sphere is `f = o − center`, `g = d`; an infinite
/// cylinder about the line through `a` along `b` is `f = (o − a) × b`,
/// `g = d × b`, `r·|b|`.
///
/// With `a = g·g` and `b = −f·g` the roots are `(b ± √D)/a`, and the
/// discriminant is computed as `D = a·(r − |l|)(r + |l|)` with
/// `l = f + (b/a)·g` the closest approach, which does not cancel for small
/// spheres far away (Haines et al., *Ray Tracing Gems*, ch. 7). The root of
/// smaller magnitude comes from the product of the roots `c/a`
/// (`c = |f|² − r²`), avoiding the cancellation in `b ∓ √D`.
#[inline]
pub fn norm_roots(f: &Vector3<f64>, g: &Vector3<f64>, r: f64) -> Option<(f64, f64)> {
    let a = g.norm_squared();
    if a.is_nan() || a <= 0.0 {
        return None;
    }
    let b = -f.dot(g);
    let ln = (f + g * (b / a)).norm();
    let disc = a * (r - ln) * (r + ln);
    if disc.is_nan() || disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let q = if b >= 0.0 { b + s } else { b - s };
    if q == 0.0 {
        // b = 0 and D = 0: tangent at the closest approach, t = 0.
        return Some((0.0, 0.0));
    }
    let fl = f.norm();
    let (t0, t1) = (q / a, (fl - r) * (fl + r) / q);
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

/// A sphere. UV: `u` the longitude `atan2(−z, x)/2π` about the `y` axis
/// (the angle of revolve's revolutions), `v = ½ + asin(y)/π` the latitude
/// (0 at the bottom pole, 1 at the top), of the unit vector from the centre.
#[derive(Debug, Clone)]
pub struct Sphere {
    center: Point3<f64>,
    radius: f64,
}

impl Sphere {
    pub fn new(center: Point3<f64>, radius: f64) -> Option<Sphere> {
        (radius > 0.0 && radius.is_finite() && finite(&center.coords))
            .then_some(Sphere { center, radius })
    }

    pub fn bounds(&self) -> Aabb {
        let r = Vector3::repeat(self.radius);
        Aabb::new(self.center - r, self.center + r)
    }

    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        let (t0, t1) = norm_roots(&(ray.origin - self.center), &ray.dir, self.radius)?;
        let t = if in_range(t0, t_min, t_max) {
            t0
        } else if in_range(t1, t_min, t_max) {
            t1
        } else {
            return None;
        };
        let point = ray.at(t);
        Some(LocalHit {
            t,
            point,
            normal: (point - self.center) / self.radius,
            uv: (0.0, 0.0),
        })
    }

    /// The UV of a hit from [`intersect`](Self::intersect).
    pub fn uv(&self, hit: &LocalHit) -> (f64, f64) {
        let n = hit.normal;
        (
            turn(-n.z, n.x),
            (0.5 + n.y.clamp(-1.0, 1.0).asin() / PI).clamp(0.0, 1.0),
        )
    }
}

/// An infinite plane `n·p = offset`, stored with a unit normal. UV: the
/// fractional parts of the coordinates along an in-plane orthonormal pair
/// (a texture tiles with period 1).
#[derive(Debug, Clone)]
pub struct Plane {
    normal: Vector3<f64>,
    offset: f64,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
}

impl Plane {
    pub fn new(normal: Vector3<f64>, offset: f64) -> Option<Plane> {
        let len = normal.norm();
        if !(len > 0.0 && len.is_finite() && offset.is_finite()) {
            return None;
        }
        let n = normal / len;
        let (e1, e2) = basis(&n);
        Some(Plane {
            normal: n,
            offset: offset / len,
            e1,
            e2,
        })
    }

    /// Everything: a plane is unbounded.
    pub fn bounds(&self) -> Aabb {
        let inf = Vector3::repeat(f64::INFINITY);
        Aabb {
            min: Point3::from(-inf),
            max: Point3::from(inf),
        }
    }

    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        let denom = self.normal.dot(&ray.dir);
        let t = (self.offset - self.normal.dot(&ray.origin.coords)) / denom;
        if !in_range(t, t_min, t_max) {
            return None;
        }
        Some(LocalHit {
            t,
            point: ray.at(t),
            normal: self.normal,
            uv: (0.0, 0.0),
        })
    }

    /// The UV of a hit from [`intersect`](Self::intersect).
    pub fn uv(&self, hit: &LocalHit) -> (f64, f64) {
        let p = hit.point.coords;
        let (a, b) = (self.e1.dot(&p), self.e2.dot(&p));
        (a.rem_euclid(1.0).min(1.0), b.rem_euclid(1.0).min(1.0))
    }
}

/// A triangle `v0 + b1·e1 + b2·e2` (`e1 = v1 − v0`, `e2 = v2 − v0`,
/// `b1, b2 ≥ 0`, `b1 + b2 ≤ 1`, edges included). Normal `e1 × e2`; UV the
/// barycentric `(b1, b2)`.
#[derive(Debug, Clone, Copy)]
pub struct Triangle {
    v0: Point3<f64>,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
}

impl Triangle {
    /// `None` for zero area or non-finite vertices.
    pub fn new(v: [Point3<f64>; 3]) -> Option<Triangle> {
        let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
        let n = e1.cross(&e2);
        (finite(&v[0].coords) && finite(&e1) && finite(&e2) && n.norm_squared() > 0.0)
            .then_some(Triangle { v0: v[0], e1, e2 })
    }

    pub fn bounds(&self) -> Aabb {
        let (a, b, c) = (self.v0, self.v0 + self.e1, self.v0 + self.e2);
        Aabb::new(a, b).include(&c)
    }

    /// `(v0, e1, e2)`.
    pub fn parts(&self) -> (Point3<f64>, Vector3<f64>, Vector3<f64>) {
        (self.v0, self.e1, self.e2)
    }

    /// `e1 × e2`.
    pub fn normal(&self) -> Vector3<f64> {
        self.e1.cross(&self.e2)
    }

    /// Möller–Trumbore: `(t, b1, b2)` of the hit with `t_min < t < t_max`.
    ///
    /// Solves `o + t·d = v0 + b1·e1 + b2·e2` by Cramer's rule with
    /// `det = e1·(d × e2)`; a ray parallel to the plane (`det = 0`) misses.
    /// Both faces are hit (no culling).
    #[inline(always)]
    pub fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, f64, f64)> {
        let p = ray.dir.cross(&self.e2);
        let det = self.e1.dot(&p);
        if det == 0.0 {
            return None;
        }
        let inv = 1.0 / det;
        let s = ray.origin - self.v0;
        let b1 = s.dot(&p) * inv;
        if !(0.0..=1.0).contains(&b1) {
            return None;
        }
        let q = s.cross(&self.e1);
        let b2 = ray.dir.dot(&q) * inv;
        if !(b2 >= 0.0 && b1 + b2 <= 1.0) {
            return None;
        }
        let t = self.e2.dot(&q) * inv;
        in_range(t, t_min, t_max).then_some((t, b1, b2))
    }

    /// The full hit from [`hit`](Self::hit)'s result.
    pub fn local_hit(&self, ray: &Ray, (t, b1, b2): (f64, f64, f64)) -> LocalHit {
        LocalHit {
            t,
            point: ray.at(t),
            normal: self.normal(),
            uv: (b1, b2),
        }
    }

    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        self.hit(ray, t_min, t_max).map(|h| self.local_hit(ray, h))
    }
}

/// An axis-aligned box (corners sorted per axis at construction). The hit
/// is where the ray enters, or, from inside (entry `≤ t_min`), where it
/// leaves; the normal is the outward normal of that face. UV on a face
/// perpendicular to axis `k`: the coordinates along the next two axes in
/// cyclic order, `(k + 1, k + 2) mod 3`, as fractions of the box's extent.
#[derive(Debug, Clone)]
pub struct BoxShape {
    min: Point3<f64>,
    max: Point3<f64>,
}

impl BoxShape {
    pub fn new(a: Point3<f64>, b: Point3<f64>) -> Option<BoxShape> {
        (finite(&a.coords) && finite(&b.coords)).then(|| BoxShape {
            min: a.inf(&b),
            max: a.sup(&b),
        })
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.min, self.max)
    }

    /// The slab test, remembering which slab set each end of the interval.
    /// A zero direction component is handled without dividing: the ray is
    /// then inside that slab always or never.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        let (o, d) = (ray.origin, ray.dir);
        let (mut t_in, mut t_out) = (f64::NEG_INFINITY, f64::INFINITY);
        let (mut axis_in, mut axis_out) = (3, 3);
        for i in 0..3 {
            if d[i] == 0.0 {
                if o[i] < self.min[i] || o[i] > self.max[i] {
                    return None;
                }
                continue;
            }
            let inv = 1.0 / d[i];
            let (t0, t1) = ((self.min[i] - o[i]) * inv, (self.max[i] - o[i]) * inv);
            let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
            if near > t_in {
                t_in = near;
                axis_in = i;
            }
            if far < t_out {
                t_out = far;
                axis_out = i;
            }
        }
        // Neither is ever NaN: a NaN candidate fails its comparison.
        if t_in > t_out {
            return None;
        }
        let (t, axis, sign) = if axis_in < 3 && in_range(t_in, t_min, t_max) {
            (t_in, axis_in, -d[axis_in].signum())
        } else if axis_out < 3 && in_range(t_out, t_min, t_max) {
            (t_out, axis_out, d[axis_out].signum())
        } else {
            return None;
        };
        let point = ray.at(t);
        let mut normal = Vector3::zeros();
        normal[axis] = sign;
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        let ext = self.max - self.min;
        Some(LocalHit {
            t,
            point,
            normal,
            uv: (
                fraction(point[i] - self.min[i], ext[i]),
                fraction(point[j] - self.min[j], ext[j]),
            ),
        })
    }
}

/// A disk (`inner = 0`) or ring: the points of the plane through `center`
/// perpendicular to `normal` with `inner ≤ |p − center| ≤ outer`. Normal as
/// given; UV polar: `u` the angle in the plane's basis over `2π`, `v` the
/// radius fraction `(ρ − inner)/(outer − inner)` (so `ρ/r` for a disk).
#[derive(Debug, Clone)]
pub struct Annulus {
    center: Point3<f64>,
    normal: Vector3<f64>,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
    inner: f64,
    outer: f64,
}

impl Annulus {
    /// `None` for a zero normal, `outer ≤ 0`, or non-finite input. A
    /// negative `inner` counts as 0, and `inner > outer` are swapped.
    pub fn new(
        center: Point3<f64>,
        normal: Vector3<f64>,
        inner: f64,
        outer: f64,
    ) -> Option<Annulus> {
        let (inner, outer) = (inner.min(outer).max(0.0), inner.max(outer));
        let len = normal.norm();
        if !(len > 0.0
            && len.is_finite()
            && outer > 0.0
            && outer.is_finite()
            && finite(&center.coords))
        {
            return None;
        }
        let n = normal / len;
        let (e1, e2) = basis(&n);
        Some(Annulus {
            center,
            normal: n,
            e1,
            e2,
            inner,
            outer,
        })
    }

    /// Per axis `i` the disk reaches `outer·√(1 − n_i²)` from its centre.
    pub fn bounds(&self) -> Aabb {
        let half = self
            .normal
            .map(|c| self.outer * (1.0 - c * c).max(0.0).sqrt());
        Aabb::new(self.center - half, self.center + half)
    }

    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        let denom = self.normal.dot(&ray.dir);
        let t = self.normal.dot(&(self.center - ray.origin)) / denom;
        if !in_range(t, t_min, t_max) {
            return None;
        }
        let point = ray.at(t);
        let w = point - self.center;
        let (a, b) = (self.e1.dot(&w), self.e2.dot(&w));
        let rho = (a * a + b * b).sqrt();
        if !(rho >= self.inner && rho <= self.outer) {
            return None;
        }
        Some(LocalHit {
            t,
            point,
            normal: self.normal,
            uv: (0.0, 0.0),
        })
    }

    /// The UV of a hit from [`intersect`](Self::intersect).
    pub fn uv(&self, hit: &LocalHit) -> (f64, f64) {
        let w = hit.point - self.center;
        let (a, b) = (self.e1.dot(&w), self.e2.dot(&w));
        let rho = (a * a + b * b).sqrt();
        (
            turn(b, a),
            fraction(rho - self.inner, self.outer - self.inner),
        )
    }
}

/// A parallelogram `corner + a·edge1 + b·edge2`, `a, b ∈ [0, 1]` (edges
/// included). Normal `edge1 × edge2`; UV `(a, b)`.
///
/// With `n = e1 × e2` and `w = p − corner = a·e1 + b·e2`, the coordinates
/// come from the dual basis: `a = w·(e2 × n)/|n|²`, `b = w·(n × e1)/|n|²`
/// (since `(e2 × n)·e1 = n·(e1 × e2) = |n|²` and `(e2 × n)·e2 = 0`), exact for
/// non-orthogonal edges.
#[derive(Debug, Clone)]
pub struct Parallelogram {
    corner: Point3<f64>,
    e1: Vector3<f64>,
    e2: Vector3<f64>,
    normal: Vector3<f64>,
    dual_a: Vector3<f64>,
    dual_b: Vector3<f64>,
}

impl Parallelogram {
    /// `None` for zero area or non-finite input.
    pub fn new(corner: Point3<f64>, e1: Vector3<f64>, e2: Vector3<f64>) -> Option<Parallelogram> {
        let n = e1.cross(&e2);
        let n2 = n.norm_squared();
        if !(n2 > 0.0 && n2.is_finite() && finite(&corner.coords)) {
            return None;
        }
        Some(Parallelogram {
            corner,
            e1,
            e2,
            normal: n,
            dual_a: e2.cross(&n) / n2,
            dual_b: n.cross(&e1) / n2,
        })
    }

    pub fn bounds(&self) -> Aabb {
        let c = self.corner;
        Aabb::new(c, c + self.e1)
            .include(&(c + self.e2))
            .include(&(c + self.e1 + self.e2))
    }

    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<LocalHit> {
        let denom = self.normal.dot(&ray.dir);
        let t = self.normal.dot(&(self.corner - ray.origin)) / denom;
        if !in_range(t, t_min, t_max) {
            return None;
        }
        let point = ray.at(t);
        let w = point - self.corner;
        let (a, b) = (self.dual_a.dot(&w), self.dual_b.dot(&w));
        if !((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)) {
            return None;
        }
        Some(LocalHit {
            t,
            point,
            normal: self.normal,
            uv: (a, b),
        })
    }
}
