//! Helpers shared by the integration tests, the benches and the examples of
//! `revolve` (a dev-dependency: `use revolve_testkit as common;`).
//!
//! - Profiles: the course wine glass ([`GLASS`], [`wine_glass`]), a cubic
//!   Bézier vase ([`VASE`], [`vase`]), a cylinder's wall ([`CYLINDER`]), and
//!   small constructors.
//! - [`Rng`]: a deterministic SplitMix64 generator.
//! - Hit checks: [`kappa`], [`t_tolerance`], [`check_hit`].
//! - [`CountingAllocator`] and [`allocations_in`]: per-thread allocation
//!   counting (the test binary that counts declares the `#[global_allocator]`
//!   itself: `tests/alloc.rs`).
//! - [`assert_close`].
//! - Rational revolutions: [`conic_profiles`] (the sphere's and the torus's
//!   NURBS profiles), [`closed_forms`] (their ray equations with exact
//!   coefficients) and [`exact_roots`] (exact real-root isolation).
//! - Tensor-product surfaces: [`tensor_shapes`] (the NURBS sphere octant and
//!   quarter cylinder with their quadratics), [`patch_shapes`] (the gently
//!   curved bicubic of the benches and the accuracy-cost study), Newell's
//!   [`teapot`] and [`patch_reference`] (every root of a ray on a Bézier
//!   patch, by interval subdivision of the power form).
//! - Random data shared by two test binaries (a test and its allocation
//!   check): [`newton_rays`] (the Newton tests' vase, generator and rays),
//!   [`random_nurbs`] (valid random NURBS) and [`random_tensors`] (control
//!   nets, weights and clamped knots).
//! - [`reference`](mod@reference): certified nearest-hit references shared with the
//!   accuracy study — surfaces of revolution in exact rational arithmetic
//!   ([`reference::revolution`]), Bézier patches by interval subdivision
//!   and Miranda's theorem ([`reference::patch`]) — and the one interval
//!   type of the references ([`interval`]).
//! - [`nearest_reference`]: the reference for nearest-point queries on
//!   surfaces (dense samples refined by Levenberg–Marquardt steps on
//!   `Surface::eval` and `partials` alone).
//! - [`camera`]: a pinhole camera's primary rays (the ray caster's formulas),
//!   for the benches.

pub mod camera;
pub mod closed_forms;
pub mod conic_profiles;
pub mod exact_roots;
pub mod interval;
pub mod nearest_reference;
pub mod newton_rays;
pub mod patch_reference;
pub mod patch_shapes;
pub mod random_nurbs;
pub mod random_tensors;
pub mod reference;
pub mod teapot;
pub mod tensor_shapes;

use revolve::nalgebra::{Point2, Point3, Vector3};
use revolve::{Aabb, BSpline, Bezier, Hit, Ray, Revolution, Surface};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

// ---------------------------------------------------------------------------
// Profiles (x = radius, y = height)
// ---------------------------------------------------------------------------

/// A wine glass as the course scene files write it: a uniform cubic B-spline
/// of 25 control points, three of them repeated on the axis at each end (the
/// foot's bottom at `y = −1` and the bowl's inside at `y = 0.15`, both flat
/// spans, so both poles have a tangent plane).
pub const GLASS: [(f64, f64); 25] = [
    (0.0, -1.0),
    (0.0, -1.0),
    (0.0, -1.0),
    (0.55, -1.0),
    (0.62, -0.97),
    (0.55, -0.92),
    (0.2, -0.88),
    (0.07, -0.8),
    (0.05, -0.6),
    (0.05, -0.3),
    (0.07, -0.1),
    (0.2, 0.0),
    (0.5, 0.1),
    (0.7, 0.35),
    (0.78, 0.7),
    (0.75, 1.0),
    (0.72, 1.06),
    (0.69, 1.0),
    (0.7, 0.7),
    (0.62, 0.38),
    (0.42, 0.22),
    (0.12, 0.15),
    (0.0, 0.15),
    (0.0, 0.15),
    (0.0, 0.15),
];

/// A vase as one cubic Bézier.
pub const VASE: [(f64, f64); 4] = [(0.6, -1.0), (1.6, -0.4), (-0.2, 0.6), (0.5, 1.0)];

/// An open cylinder's wall, radius 1 and height 2, as a degree-1 profile
/// (the benches' and the profiler's floor: it has a closed form).
pub const CYLINDER: [(f64, f64); 2] = [(1.0, 0.0), (1.0, 2.0)];

/// The points `(x, y)` as `Point2`s.
pub fn points(p: &[(f64, f64)]) -> Vec<Point2<f64>> {
    p.iter().map(|&(x, y)| Point2::new(x, y)).collect()
}

/// The Bézier profile on these control points, revolved.
pub fn bezier(p: &[(f64, f64)]) -> Revolution<Bezier<2>> {
    Revolution::new(Bezier::new(points(p)).unwrap())
}

/// The course framework's uniform cubic B-spline on these points (knots
/// `i/(n + 3)`), revolved.
pub fn uniform_cubic(p: &[(f64, f64)]) -> Revolution<BSpline<2>> {
    Revolution::new(BSpline::uniform(3, points(p)).unwrap())
}

/// The wine-glass profile [`GLASS`] as the course's uniform cubic B-spline.
pub fn wine_glass() -> BSpline<2> {
    BSpline::uniform(3, points(&GLASS)).expect("valid wine glass")
}

/// The vase profile [`VASE`] as a cubic Bézier.
pub fn vase() -> Bezier<2> {
    Bezier::new(points(&VASE)).expect("valid vase")
}

// ---------------------------------------------------------------------------
// Random numbers
// ---------------------------------------------------------------------------

/// SplitMix64: a small deterministic generator, so random rays and points are
/// the same on every run without a `rand` dependency.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)` (53 random bits).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// An index in `0..n`.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// A point uniform in the box `lo..hi`.
    pub fn point(&mut self, lo: [f64; 3], hi: [f64; 3]) -> Point3<f64> {
        Point3::new(
            self.range(lo[0], hi[0]),
            self.range(lo[1], hi[1]),
            self.range(lo[2], hi[2]),
        )
    }

    /// A point uniform in the box `b`.
    pub fn point_in(&mut self, b: &Aabb) -> Point3<f64> {
        self.point(b.min.into(), b.max.into())
    }

    /// A unit vector, uniform on the sphere.
    pub fn direction(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let n = v.norm();
            if n > 0.1 && n <= 1.0 {
                return v / n;
            }
        }
    }
}

/// `count` deterministic control points: a wobbly helix-like walk with
/// coordinates of order 1.
pub fn helix_points(count: usize, seed: u64) -> Vec<Point3<f64>> {
    let mut rng = Rng(seed);
    (0..count)
        .map(|i| {
            let s = i as f64 / count.max(2).saturating_sub(1) as f64;
            Point3::new(
                (6.0 * s).cos() + rng.range(-0.3, 0.3),
                (6.0 * s).sin() + rng.range(-0.3, 0.3),
                2.0 * s - 1.0 + rng.range(-0.1, 0.1),
            )
        })
        .collect()
}

// ---------------------------------------------------------------------------
// Checks on hits
// ---------------------------------------------------------------------------

/// Backward error allowed of a hit, relative to the scene scale.
pub const REL: f64 = 1e-12;

/// Condition number of a hit of direction `d` on a surface with unit normal
/// `n`: how much `t·|d|` moves per unit of backward error.
pub fn kappa(d: &Vector3<f64>, n: &Vector3<f64>) -> f64 {
    let c = d.normalize().dot(&n.normalize()).abs();
    if c > 0.0 {
        (1.0 / c).max(1.0)
    } else {
        f64::INFINITY
    }
}

/// Allowed `|t − t_ref|`: `(1e-12 + 16ε·κ)·scale / |d|`, the backward error of
/// [`REL`] plus 16 ulps of the scene amplified by the condition number.
pub fn t_tolerance(scale: f64, kappa: f64, d: &Vector3<f64>) -> f64 {
    (REL + 16.0 * f64::EPSILON * kappa) * scale / d.norm()
}

/// Everything every hit must satisfy: finite, inside `(t_min, t_max)`, its
/// point on the ray and on the surface (`eval(uv)`) to `REL·scale`, `uv` in
/// the domain, a unit normal equal to the surface's normal there and
/// perpendicular to the partials.
pub fn check_hit<S: Surface>(s: &S, r: &Ray, h: &Hit, t_min: f64, t_max: f64, scale: f64) {
    let finite = h.t.is_finite()
        && h.point.iter().all(|c| c.is_finite())
        && h.normal.iter().all(|c| c.is_finite())
        && h.uv.0.is_finite()
        && h.uv.1.is_finite();
    assert!(finite, "non-finite hit {h:?} for {r:?}");
    assert!(
        h.t > t_min && h.t < t_max,
        "t = {} outside ({t_min}, {t_max}) for {r:?}",
        h.t
    );
    let on_ray = (r.at(h.t) - h.point).norm();
    assert!(
        on_ray <= REL * scale,
        "hit point {on_ray:e} off the ray: {h:?} {r:?}"
    );
    let on_surface = (s.eval(h.uv.0, h.uv.1) - h.point).norm();
    assert!(
        on_surface <= REL * scale,
        "hit point {on_surface:e} off S(uv): {h:?} {r:?}"
    );
    let [(u0, u1), (v0, v1)] = s.domain();
    assert!(
        h.uv.0 >= u0 && h.uv.0 <= u1 && h.uv.1 >= v0 && h.uv.1 <= v1,
        "uv outside the domain: {h:?}"
    );
    let n = h.normal.into_inner();
    assert!((n.norm() - 1.0).abs() <= 1e-12, "normal not unit: {h:?}");
    if let Some(sn) = s.normal(h.uv.0, h.uv.1) {
        assert!(
            (sn.into_inner() - n).norm() <= 1e-12,
            "hit normal {n:?} differs from Surface::normal {sn:?}"
        );
        let (su, sv) = s.partials(h.uv.0, h.uv.1);
        for p in [su, sv] {
            if p.norm() > 0.0 {
                assert!(
                    n.dot(&p).abs() <= 1e-12 * p.norm(),
                    "normal {n:?} not perpendicular to partial {p:?}: {h:?}"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Allocation counting
// ---------------------------------------------------------------------------

/// A global allocator that forwards to `System` and counts allocations
/// (including zeroed allocations and reallocations) per thread, so test
/// threads running in parallel do not see each other's allocations. A test
/// binary enables it with
/// `#[global_allocator] static GLOBAL: common::CountingAllocator = common::CountingAllocator;`
/// (or wraps it, as `tests/alloc.rs` does).
pub struct CountingAllocator;

thread_local! {
    // `const` initialisation and a type without a destructor: reading or
    // bumping the counter never allocates or registers anything.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count_one() {
    // `try_with`: during thread teardown the slot may be gone; not counting
    // there is harmless.
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

// SAFETY: every method forwards to `System` with the caller's arguments
// unchanged, so `System`'s guarantees carry over; counting has no effect on
// the memory handed out.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count_one();
        // SAFETY: forwarded contract of `GlobalAlloc::alloc`.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count_one();
        // SAFETY: forwarded contract of `GlobalAlloc::alloc_zeroed`.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count_one();
        // SAFETY: forwarded contract of `GlobalAlloc::realloc`; `ptr` came
        // from this allocator, i.e. from `System`.
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded contract of `GlobalAlloc::dealloc`.
        unsafe { System.dealloc(ptr, layout) }
    }
}

/// The number of heap allocations the current thread has made so far (counted
/// only where [`CountingAllocator`] is the global allocator).
pub fn allocations_so_far() -> usize {
    ALLOCATIONS.with(Cell::get)
}

/// The number of heap allocations the current thread makes while running `f`.
pub fn allocations_in<R>(f: impl FnOnce() -> R) -> usize {
    let before = allocations_so_far();
    std::hint::black_box(f());
    allocations_so_far() - before
}

// ---------------------------------------------------------------------------
// Assertions
// ---------------------------------------------------------------------------

/// Asserts `|got − want| ≤ tol`, naming `what` on failure.
pub fn assert_close(got: f64, want: f64, tol: f64, what: &str) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got:e}, want {want:e}, |diff| = {:e} > {tol:e}",
        (got - want).abs()
    );
}
