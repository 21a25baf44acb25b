//! Evaluation does not touch the heap for degrees up to 16; a surface of
//! revolution holds heap in proportion to its profile, as it reports.
//!
//! A counting global allocator wraps the system allocator and counts
//! allocations (including zeroed allocations and reallocations) per thread,
//! so the test threads running in parallel do not see each other's
//! allocations. Each check runs the operation between two readings of the
//! current thread's counter. The same allocator also keeps, per thread, the
//! bytes currently held (requested sizes): what a built value holds is the
//! change across its build ([`held_by`]).
//!
//! Every allocation check of the test suite is in this binary, so that only
//! it runs under the counting allocator: besides curves and revolutions, the
//! Newton intersector's queries ([`newton`]), NURBS evaluation ([`nurbs`])
//! and tensor-product surface evaluation ([`tensor_surfaces`]), each on the
//! data of its subject's tests (`revolve_testkit::newton_rays`,
//! `random_nurbs`, `random_tensors`).

use revolve_testkit as common;

use common::{allocations_in, allocations_so_far};
use revolve::nalgebra::{Point, SVector};
use revolve::{BSpline, Bezier, Curve, Revolution};
use std::alloc::{GlobalAlloc, Layout};
use std::cell::Cell;
use std::hint::black_box;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// [`common::CountingAllocator`] with a per-thread tally of the bytes held.
struct CountingBytes;

thread_local! {
    // `const` initialisation and no destructor, as the allocation counter.
    static HELD: Cell<isize> = const { Cell::new(0) };
}

/// Adds `bytes` to the calling thread's tally (`try_with`: during thread
/// teardown the slot may be gone).
fn hold(bytes: isize) {
    let _ = HELD.try_with(|held| held.set(held.get() + bytes));
}

// SAFETY: every method forwards to `common::CountingAllocator` (which
// forwards to `System`) with the caller's arguments unchanged; the tally
// only reads sizes and touches a destructor-free thread-local.
unsafe impl GlobalAlloc for CountingBytes {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded contract of `GlobalAlloc::alloc`.
        let p = unsafe { common::CountingAllocator.alloc(layout) };
        if !p.is_null() {
            hold(layout.size() as isize);
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: forwarded contract of `GlobalAlloc::alloc_zeroed`.
        let p = unsafe { common::CountingAllocator.alloc_zeroed(layout) };
        if !p.is_null() {
            hold(layout.size() as isize);
        }
        p
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: forwarded contract of `GlobalAlloc::realloc`; `ptr` came
        // from this allocator.
        let p = unsafe { common::CountingAllocator.realloc(ptr, layout, new_size) };
        // On failure the old block stays allocated: nothing changes.
        if !p.is_null() {
            hold(new_size as isize - layout.size() as isize);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded contract of `GlobalAlloc::dealloc`.
        unsafe { common::CountingAllocator.dealloc(ptr, layout) };
        hold(-(layout.size() as isize));
    }
}

#[global_allocator]
static GLOBAL: CountingBytes = CountingBytes;

/// `build`'s value and the heap bytes it holds: the calling thread's bytes
/// held after the build minus before (temporaries freed during the build
/// do not count).
fn held_by<T>(build: impl FnOnce() -> T) -> (T, usize) {
    let before = HELD.with(Cell::get);
    let value = build();
    let held = HELD.with(Cell::get) - before;
    (
        value,
        usize::try_from(held).expect("a build does not free more than it allocates"),
    )
}

/// `n` control points in `D` dimensions with distinct coordinates.
fn points<const D: usize>(n: usize) -> Vec<Point<f64, D>> {
    (0..n)
        .map(|i| {
            let v = SVector::<f64, D>::from_fn(|r, _| ((i * 7 + r * 3) % 11) as f64 - 5.0);
            Point::from(v)
        })
        .collect()
}

const PARAMS: [f64; 9] = [
    0.0,
    1e-9,
    0.25,
    0.5,
    0.7,
    1.0,
    f64::NAN,
    -3.0,
    f64::INFINITY,
];

/// Asserts that every evaluation entry point of a degree-`degree` Bézier in
/// `D` dimensions runs without allocating.
fn check_bezier<const D: usize>(degree: usize) {
    let c = Bezier::new(points::<D>(degree + 1)).unwrap();
    for t in PARAMS {
        let t = black_box(t);
        let what = format!("Bezier<{D}> degree {degree} t={t}");
        assert_eq!(allocations_in(|| c.eval(t)), 0, "eval: {what}");
        assert_eq!(allocations_in(|| c.derivative(t)), 0, "derivative: {what}");
        assert_eq!(
            allocations_in(|| c.eval_with_derivative(t)),
            0,
            "eval_with_derivative: {what}"
        );
        for order in 0..=degree + 1 {
            assert_eq!(
                allocations_in(|| c.nth_derivative(t, order).unwrap()),
                0,
                "nth_derivative({order}): {what}"
            );
        }
    }
}

/// Splines of degree `p` in `D` dimensions: framework uniform, clamped, and
/// one with a repeated interior knot.
fn splines<const D: usize>(p: usize) -> Vec<BSpline<D>> {
    let n = p + 4;
    let mut knots: Vec<f64> = (0..=n + p).map(|i| i as f64).collect();
    // Repeat the knot at the middle of the domain p times (allowed up to p + 1).
    let mid = (p + n) / 2;
    for k in knots.iter_mut().skip(mid).take(p) {
        *k = mid as f64;
    }
    knots.sort_by(f64::total_cmp);
    vec![
        BSpline::uniform(p, points::<D>(n)).unwrap(),
        BSpline::clamped(p, points::<D>(n)).unwrap(),
        BSpline::new(p, knots, points::<D>(n)).unwrap(),
    ]
}

/// Asserts that every evaluation entry point of degree-`p` B-splines in `D`
/// dimensions runs without allocating.
fn check_bspline<const D: usize>(p: usize) {
    for c in splines::<D>(p) {
        let (a, b) = c.domain();
        let mut basis = vec![0.0; p + 1];
        let mut derivs = vec![0.0; (p + 2) * (p + 1)];
        let interior = c.knots()[p + 1..c.points().len()].to_vec();
        let ts = PARAMS
            .iter()
            .map(|&s| a + (b - a) * s)
            .chain(interior)
            .chain([a, b, f64::NAN]);
        for t in ts.collect::<Vec<_>>() {
            let t = black_box(t);
            let what = format!("BSpline<{D}> degree {p} knots {:?} t={t}", c.knots());
            assert_eq!(allocations_in(|| c.eval(t)), 0, "eval: {what}");
            assert_eq!(allocations_in(|| c.derivative(t)), 0, "derivative: {what}");
            assert_eq!(
                allocations_in(|| c.eval_with_derivative(t)),
                0,
                "eval_with_derivative: {what}"
            );
            for order in 0..=p + 1 {
                assert_eq!(
                    allocations_in(|| c.nth_derivative(t, order).unwrap()),
                    0,
                    "nth_derivative({order}): {what}"
                );
            }
            assert_eq!(allocations_in(|| c.span(t)), 0, "span: {what}");
            assert_eq!(
                allocations_in(|| c.basis_functions(t, &mut basis).unwrap()),
                0,
                "basis_functions: {what}"
            );
            for order in 0..=p + 1 {
                assert_eq!(
                    allocations_in(|| c.basis_derivatives(t, order, &mut derivs).unwrap()),
                    0,
                    "basis_derivatives({order}): {what}"
                );
            }
        }
    }
}

#[test]
fn bezier_evaluation_does_not_allocate_up_to_degree_16_in_1d() {
    (0..=16).for_each(check_bezier::<1>);
}

#[test]
fn bezier_evaluation_does_not_allocate_up_to_degree_16_in_2d() {
    (0..=16).for_each(check_bezier::<2>);
}

#[test]
fn bezier_evaluation_does_not_allocate_up_to_degree_16_in_3d() {
    (0..=16).for_each(check_bezier::<3>);
}

#[test]
fn bspline_evaluation_and_basis_do_not_allocate_up_to_degree_16_in_1d() {
    (0..=16).for_each(check_bspline::<1>);
}

#[test]
fn bspline_evaluation_and_basis_do_not_allocate_up_to_degree_16_in_2d() {
    (0..=16).for_each(check_bspline::<2>);
}

#[test]
fn bspline_evaluation_and_basis_do_not_allocate_up_to_degree_16_in_3d() {
    (0..=16).for_each(check_bspline::<3>);
}

// -------------------------------------- the counter can see allocations ----

#[test]
fn counter_sees_a_plain_allocation() {
    assert_eq!(allocations_in(|| Vec::<u64>::with_capacity(4)), 1);
    assert_eq!(allocations_in(|| Box::new(7u32)), 1);
    assert_eq!(allocations_in(|| String::from("spline")), 1);
    assert_eq!(allocations_in(|| 2 + 2), 0);
}

#[test]
fn very_high_degree_bezier_eval_allocates() {
    // Scratch beyond the stack buffers comes from the heap. (Degree 30 still
    // fits the crate's largest stack buffer, 102 entries, so it does not
    // allocate; 110 does not fit. Much higher degrees have derivatives too
    // large for a double and are refused: `Error::DerivativeOverflow`.)
    let c = Bezier::new(points::<2>(111)).unwrap();
    let t = black_box(0.3);
    assert!(allocations_in(|| c.eval(t)) >= 1);
    assert!(allocations_in(|| c.nth_derivative(t, 2).unwrap()) >= 1);
    let s = BSpline::clamped(110, points::<2>(111)).unwrap();
    let u = black_box(s.domain().0);
    assert!(allocations_in(|| s.eval(u)) >= 1);
}

#[test]
fn operations_that_return_collections_allocate() {
    let c = Bezier::new(points::<2>(4)).unwrap();
    assert!(allocations_in(|| c.discretize(8)) >= 1);
    assert!(allocations_in(|| c.subdivide(0.5).unwrap()) >= 1);
    assert!(allocations_in(|| c.hodograph()) >= 1);
    let s = BSpline::clamped(3, points::<2>(7)).unwrap();
    assert!(allocations_in(|| s.discretize(8)) >= 1);
    assert!(allocations_in(|| s.to_bezier_spans()) >= 1);
    assert!(allocations_in(|| s.derivative_spline()) >= 1);
}

#[test]
fn counts_are_per_thread() {
    // Another thread allocates continuously while this one evaluates; this
    // thread's count must stay at zero, and the other thread's must grow.
    let stop = Arc::new(AtomicBool::new(false));
    let churned = Arc::new(AtomicUsize::new(0));
    let worker = {
        let (stop, churned) = (Arc::clone(&stop), Arc::clone(&churned));
        std::thread::spawn(move || {
            let start = allocations_so_far();
            while !stop.load(Ordering::Relaxed) {
                black_box(vec![0u8; 64]);
                churned.store(allocations_so_far() - start, Ordering::Relaxed);
            }
        })
    };
    let c = BSpline::uniform(3, points::<3>(10)).unwrap();
    let mut spins = 0u64;
    let during = allocations_in(|| {
        // Evaluate until the other thread has made many allocations.
        while churned.load(Ordering::Relaxed) < 10_000 {
            black_box(c.eval(black_box(0.5)));
            spins += 1;
        }
    });
    stop.store(true, Ordering::Relaxed);
    worker.join().unwrap();
    assert!(churned.load(Ordering::Relaxed) >= 10_000);
    assert_eq!(during, 0, "after {spins} evaluations");
}

// ------------------------------------------------ surfaces' heap bytes ----

/// Builds the surface of `profile` (itself built by `profile`) and checks
/// what it holds: [`Revolution::heap_bytes`] agrees with the allocator's
/// count of what the surface's construction kept (to a word per table:
/// they should be equal), and the whole surface, profile included, holds
/// at most `limit` bytes. Returns the surface's heap bytes.
fn check_heap<C: Curve<2>>(what: &str, profile: impl FnOnce() -> C, limit: usize) -> usize {
    let (profile, profile_bytes) = held_by(profile);
    let (surface, surface_bytes) = held_by(|| Revolution::new(profile));
    assert!(surface.has_exact_intersector(), "{what}");
    let reported = surface.heap_bytes();
    assert!(
        reported.abs_diff(surface_bytes) <= 64,
        "{what}: heap_bytes {reported}, the allocator counted {surface_bytes}"
    );
    assert!(
        profile_bytes + surface_bytes <= limit,
        "{what}: profile {profile_bytes} and surface {surface_bytes} bytes, limit {limit}"
    );
    reported
}

/// The one-cubic vase (cut into 8 spans) holds at most 4 KiB, the 25-point
/// wine glass (22 spans) at most 16 KiB, profile included, and the glass
/// more than the vase.
#[test]
fn surfaces_hold_heap_in_proportion_to_their_profiles() {
    let vase = check_heap("vase", common::vase, 4 * 1024);
    let glass = check_heap("wine glass", common::wine_glass, 16 * 1024);
    assert!(vase < glass, "vase {vase}, glass {glass}");
}

/// Rational revolutions (a NURBS half circle: the unit sphere; a NURBS
/// circle off the axis: a torus) hold little heap, and intersecting a ray
/// with them allocates nothing (nor do every hit, into a vector with room,
/// and occlusion).
#[test]
fn rational_revolutions_are_small_and_do_not_allocate_per_ray() {
    use revolve::nalgebra::{Point2, Vector3};
    use revolve::{Intersect, Nurbs, Ray};
    use std::f64::consts::FRAC_PI_2;
    let half = || Nurbs::arc(Point2::origin(), 1.0, -FRAC_PI_2, FRAC_PI_2).unwrap();
    let ring = || Nurbs::circle(Point2::new(1.0, 0.0), 0.25).unwrap();
    check_heap("NURBS sphere", half, 5 * 1024);
    check_heap("NURBS torus", ring, 6 * 1024);
    let mut rng = common::Rng(23);
    for surface in [Revolution::new(half()), Revolution::new(ring())] {
        let bounds = surface.bounds();
        let mut hits = 0;
        // Every hit into the caller's vector: no allocation once it has room.
        let mut all = Vec::with_capacity(16);
        for _ in 0..500 {
            let dir: Vector3<f64> = rng.direction();
            let ray = Ray::new(rng.point_in(&bounds) - dir * 4.0, dir);
            let mut hit = None;
            let count = allocations_in(|| hit = surface.intersect(&ray, 0.0, f64::INFINITY));
            assert_eq!(count, 0, "{ray:?}");
            hits += usize::from(hit.is_some());
            let count =
                allocations_in(|| surface.intersect_all(&ray, 0.0, f64::INFINITY, &mut all));
            assert_eq!((count, all.first().copied()), (0, hit), "{ray:?}");
            let count = allocations_in(|| black_box(surface.occluded(&ray, 0.0, f64::INFINITY)));
            assert_eq!(count, 0, "{ray:?}");
        }
        assert!(hits > 100, "only {hits} hits");
    }
}

/// Newell's teapot as a [`BezierPatches`](revolve::BezierPatches) model:
/// the 32 bicubic patches, cut for the ray search into 64 pieces each (2048
/// nets of 16 homogeneous points with their projection certificates, about
/// 0.8 KiB each with their share of the hierarchy), hold at most 2 MiB
/// (the budget the speed work set itself; 1.7 MB today), and a ray through
/// the model allocates nothing (nor do every hit, into a vector with room,
/// and occlusion).
#[test]
fn the_teapot_model_is_small_and_does_not_allocate_per_ray() {
    use revolve::nalgebra::Vector3;
    use revolve::{BezierPatches, Intersect, Ray};
    let patches = common::teapot::patches();
    let (model, bytes) = held_by(|| BezierPatches::new(patches).unwrap());
    assert!(bytes <= 2 * 1024 * 1024, "teapot model holds {bytes} bytes");
    let bounds = model.bounds();
    let mut rng = common::Rng(31);
    let mut hits = 0;
    let mut all = Vec::with_capacity(16);
    for _ in 0..500 {
        let dir: Vector3<f64> = rng.direction();
        let ray = Ray::new(rng.point_in(&bounds) - dir * 10.0, dir);
        let mut hit = None;
        let count = allocations_in(|| hit = model.intersect(&ray, 0.0, f64::INFINITY));
        assert_eq!(count, 0, "{ray:?}");
        hits += usize::from(hit.is_some());
        let count = allocations_in(|| model.intersect_all(&ray, 0.0, f64::INFINITY, &mut all));
        assert_eq!((count, all.first().copied()), (0, hit), "{ray:?}");
        let count = allocations_in(|| black_box(model.occluded(&ray, 0.0, f64::INFINITY)));
        assert_eq!(count, 0, "{ray:?}");
    }
    assert!(hits > 100, "only {hits} hits");
}

// ---------------------------------------- the other layers' hot paths ----

/// The generic Newton intersector (the tests of `tests/revolution/newton.rs`).
mod newton {
    use super::common;
    use common::newton_rays::{Xorshift64 as Rng, pole_vase as vase, random_ray};
    use common::{GLASS, allocations_in, uniform_cubic};
    use revolve::{Intersect, NewtonIntersector};

    #[test]
    fn queries_do_not_allocate() {
        let vase = vase();
        let glass = uniform_cubic(&GLASS);
        let newton_vase = NewtonIntersector::new(&vase, 8);
        let newton_glass = NewtonIntersector::new(&glass, 10);
        let mut rng = Rng::new(17);
        for _ in 0..200 {
            let ray = random_ray(&mut rng, &newton_glass.bounds());
            let t = f64::INFINITY;
            assert_eq!(allocations_in(|| newton_glass.intersect(&ray, 0.0, t)), 0);
            assert_eq!(
                allocations_in(|| newton_glass.intersect_with_report(&ray, 0.0, t)),
                0
            );
            let ray = random_ray(&mut rng, &newton_vase.bounds());
            assert_eq!(allocations_in(|| newton_vase.intersect(&ray, 0.0, t)), 0);
        }
    }
}

/// NURBS curves (the tests of `tests/curves/nurbs.rs`).
mod nurbs {
    use super::common;
    use common::random_nurbs::{parameters, random_parts};
    use common::{Rng, allocations_in};
    use revolve::nalgebra::{Point2, Vector2};
    use revolve::{Curve, Nurbs};

    #[test]
    fn evaluation_does_not_allocate_up_to_degree_16() {
        let mut rng = Rng(43);
        for degree in [1, 2, 3, 7, 16] {
            let parts = random_parts(&mut rng, degree, 0.1, 10.0);
            let c = parts.nurbs();
            let circle = Nurbs::circle(Point2::new(1.0, 2.0), 3.0).unwrap();
            let ts = parameters(&mut rng, &c, 10);
            let count = allocations_in(|| {
                let mut out = [Vector2::zeros(); 4];
                let mut sum = Vector2::zeros();
                for &t in &ts {
                    sum += c.eval(t).coords + c.derivative(t) + circle.eval(t).coords;
                    let (p, d) = c.eval_with_derivative(t);
                    sum += p.coords + d;
                    c.derivatives(t, &mut out).unwrap();
                    sum += out[3] + c.nth_derivative(t, 2).unwrap();
                    sum += c.tangent(t).map_or(Vector2::zeros(), |u| u.into_inner());
                }
                sum
            });
            assert_eq!(count, 0, "degree {degree}");
        }
    }
}

/// Tensor-product surfaces (the tests of `tests/tensor/tensor_surfaces.rs`).
mod tensor_surfaces {
    use super::common;
    use common::allocations_in;
    use common::random_tensors::{Xorshift64Star as Rng, clamped_knots};
    use revolve::{BSplineSurface, BezierSurface, NurbsSurface, Surface};

    #[test]
    fn bicubic_evaluation_does_not_allocate() {
        let mut rng = Rng(59);
        let bezier = BezierSurface::new(rng.grid(4, 4)).unwrap();
        let knots = (clamped_knots(&mut rng, 3, 7), clamped_knots(&mut rng, 3, 6));
        let bspline = BSplineSurface::new((3, 3), knots.clone(), rng.grid(7, 6)).unwrap();
        let nurbs = NurbsSurface::new((3, 3), knots, rng.grid(7, 6), rng.weights(7, 6)).unwrap();
        let surfaces: [&dyn Surface; 3] = [&bezier, &bspline, &nurbs];
        for s in surfaces {
            let (u, v) = (rng.next(), rng.next());
            assert_eq!(allocations_in(|| s.eval(u, v)), 0);
            assert_eq!(allocations_in(|| s.partials(u, v)), 0);
            assert_eq!(allocations_in(|| s.normal(u, v)), 0);
        }
        assert_eq!(allocations_in(|| bezier.second_partials(0.3, 0.7)), 0);
    }
}
