//! `Intersect::intersect_batch`: every lane gets exactly the single-ray
//! answer (hits, misses, rays along the axis and perpendicular to it, odd
//! ranges in one batch), and slices of unequal length process their common
//! prefix only.
//!
//! Issue 19 (a SIMD batch path for revolutions) adds: the batch path returns
//! bit for bit the hits of the single path
//! - on every hard case of DESIGN.md §5 (the rays of the `hard_cases` module,
//!   on the same kinds of profiles), each put into batches with random lanes
//!   that hit and miss, then again from each of its hits (a secondary ray
//!   with `t_min` at the hit) and from each hit point (a ray starting on the
//!   surface), at every offset below [`LANES`] so it falls in every lane
//!   position;
//! - on a million random rays per profile (the wine glass, the vase, the
//!   NURBS sphere), each lane's kind drawn at random: through the box in any
//!   direction, perpendicular to the axis (exactly and within `1e-12`),
//!   along the axis (on it and off it), missing, with later or shorter
//!   ranges.
//!
//! "Bit for bit": every `f64` of the hit compared by its bits (`==` would
//! let `−0` pass for `+0`), and a lane the batch leaves unwritten shows,
//! because the output starts filled with a hit no intersector returns.

use revolve_testkit as common;

use common::{Rng, bezier, points, uniform_cubic};
use revolve::nalgebra::{Point3, Vector3};
use revolve::{BSpline, BezierPatches, Curve, Hit, Intersect, Ray, Revolution};

const INF: f64 = f64::INFINITY;

/// Rays per batch of the widest SIMD path the issue asks for (8 rays; a
/// 4-ray path divides it).
const LANES: usize = 8;

/// A mixed batch through the box of `shape`: random rays, rays along the
/// y axis and perpendicular to it, rays that miss, and narrow or empty
/// ranges.
fn mixed_batch<S: Intersect + ?Sized>(
    shape: &S,
    n: usize,
    seed: u64,
) -> (Vec<Ray>, Vec<(f64, f64)>) {
    let b = shape.bounds();
    let mut rng = Rng(seed);
    let mut rays = Vec::with_capacity(n);
    let mut ranges = Vec::with_capacity(n);
    for i in 0..n {
        let target = rng.point_in(&b);
        let dir: Vector3<f64> = match i % 4 {
            0 => rng.direction(),
            1 => Vector3::new(0.0, -1.0, 0.0),
            2 => {
                let d: Vector3<f64> = rng.direction();
                Vector3::new(d.x, 0.0, d.z + 1e-3)
            }
            _ => rng.direction(),
        };
        let origin = if i % 4 == 3 {
            // Far off to the side: a miss.
            target + Vector3::new(0.0, 0.0, 10.0 * b.scale())
        } else {
            target - dir * 4.0 * b.scale()
        };
        rays.push(Ray::new(origin, dir));
        ranges.push(match i % 7 {
            0 => (0.0, 1.0),
            1 => (f64::NAN, 5.0),
            2 => (3.0, 2.0),
            _ => (0.0, f64::INFINITY),
        });
    }
    (rays, ranges)
}

fn check_lanes<S: Intersect>(shape: &S, seed: u64) {
    let (rays, ranges) = mixed_batch(shape, 512, seed);
    let mut hits: Vec<Option<Hit>> = vec![None; rays.len()];
    shape.intersect_batch(&rays, &ranges, &mut hits);
    let mut found = 0;
    for ((ray, &(lo, hi)), hit) in rays.iter().zip(&ranges).zip(&hits) {
        assert_eq!(
            *hit,
            shape.intersect(ray, lo, hi),
            "{ray:?} in ({lo}, {hi})"
        );
        found += usize::from(hit.is_some());
    }
    assert!(found > 50, "only {found} hits");
    // Unequal lengths: the common prefix only; the rest is untouched.
    let sentinel = Some(hits.iter().flatten().next().copied().unwrap());
    let mut short = vec![sentinel; 40];
    shape.intersect_batch(&rays[..30], &ranges[..35], &mut short);
    for i in 0..30 {
        assert_eq!(short[i], hits[i]);
    }
    assert!(short[30..].iter().all(|h| *h == sentinel));
    let mut none: [Option<Hit>; 0] = [];
    shape.intersect_batch(&rays, &ranges, &mut none);
}

#[test]
fn a_revolution_batch_gives_each_ray_its_own_hit() {
    check_lanes(&Revolution::new(common::wine_glass()), 1);
    check_lanes(&Revolution::new(common::vase()), 2);
}

#[test]
fn a_model_of_patches_batch_gives_each_ray_its_own_hit() {
    let model = BezierPatches::new(common::teapot::patches()).unwrap();
    check_lanes(&model, 3);
}

// ---------------------------------------------------------------------------
// Bit for bit
// ---------------------------------------------------------------------------

/// One lane of a batch: the ray and its range `(t_min, t_max)`.
type Lane = (Ray, (f64, f64));

/// The bits of every number of a hit: `t`, the point, the normal, `(u, v)`.
fn bits(hit: &Option<Hit>) -> Option<[u64; 9]> {
    hit.map(|h| {
        let n = h.normal.into_inner();
        [
            h.t, h.point.x, h.point.y, h.point.z, n.x, n.y, n.z, h.uv.0, h.uv.1,
        ]
        .map(f64::to_bits)
    })
}

/// A hit no intersector returns (`t = −1`, outside every range): the batch's
/// output starts filled with it, so a lane left unwritten shows.
fn stale() -> Option<Hit> {
    Some(Hit {
        t: -1.0,
        point: Point3::origin(),
        normal: Vector3::y_axis(),
        uv: (-1.0, -1.0),
    })
}

/// Asserts that `intersect_batch` on `lanes` gives each lane bit for bit
/// what `intersect` gives it alone: over the whole slice and over the slice
/// from every offset below [`LANES`] (so each lane is checked in every lane
/// position of a batch, and with every remainder length). Returns the
/// number of lanes that hit.
fn assert_batch_is_single<S: Intersect + ?Sized>(what: &str, shape: &S, lanes: &[Lane]) -> usize {
    let (rays, ranges): (Vec<Ray>, Vec<(f64, f64)>) = lanes.iter().copied().unzip();
    let single: Vec<Option<Hit>> = lanes
        .iter()
        .map(|(ray, (t_min, t_max))| shape.intersect(ray, *t_min, *t_max))
        .collect();
    for offset in 0..LANES.min(lanes.len()) {
        let mut batch = vec![stale(); lanes.len() - offset];
        shape.intersect_batch(&rays[offset..], &ranges[offset..], &mut batch);
        for (i, (got, want)) in batch.iter().zip(&single[offset..]).enumerate() {
            let (ray, range) = lanes[offset + i];
            assert!(
                bits(got) == bits(want),
                "{what}: lane {i} of a batch from offset {offset}: {ray:?} in {range:?}: \
                 batch {got:?}, single {want:?}"
            );
        }
    }
    single.iter().flatten().count()
}

/// A batch path with one fault: `Nudged` moves `t` of lane 5 of every
/// batch of [`LANES`] by one ulp (a rounding difference); `Unwritten`
/// leaves the last lane of the slice as it was.
enum Faulty<'a, S> {
    Nudged(&'a S),
    Unwritten(&'a S),
}

impl<S: Intersect> Intersect for Faulty<'_, S> {
    fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
        match self {
            Faulty::Nudged(s) | Faulty::Unwritten(s) => s.intersect(ray, t_min, t_max),
        }
    }

    fn bounds(&self) -> revolve::Aabb {
        match self {
            Faulty::Nudged(s) | Faulty::Unwritten(s) => s.bounds(),
        }
    }

    fn intersect_batch(&self, rays: &[Ray], ranges: &[(f64, f64)], hits: &mut [Option<Hit>]) {
        let n = rays.len().min(ranges.len()).min(hits.len());
        for (i, hit) in hits[..n].iter_mut().enumerate() {
            let (t_min, t_max) = ranges[i];
            if matches!(self, Faulty::Unwritten(_)) && i + 1 == n {
                continue;
            }
            *hit = self.intersect(&rays[i], t_min, t_max);
            if let (Faulty::Nudged(_), Some(h), 5) = (self, hit.as_mut(), i % LANES) {
                h.t = f64::from_bits(h.t.to_bits() + 1);
            }
        }
    }
}

/// The checker itself: a batch one ulp off in one lane, or one that leaves
/// a lane unwritten, fails it; the true batch passes.
#[test]
fn the_bit_for_bit_check_catches_an_ulp_and_an_unwritten_lane() {
    let glass = Revolution::new(common::wine_glass());
    let rays: Vec<Ray> = (0..40)
        .map(|i| ray([-3.0, -0.9 + 0.045 * f64::from(i), 0.0], [1.0, 0.0, 0.0]))
        .collect();
    let lanes: Vec<Lane> = rays.iter().map(|r| (*r, (0.0, INF))).collect();
    assert_eq!(assert_batch_is_single("glass", &glass, &lanes), 40);
    for faulty in [Faulty::Nudged(&glass), Faulty::Unwritten(&glass)] {
        let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            assert_batch_is_single("faulty", &faulty, &lanes)
        }));
        assert!(caught.is_err());
    }
}

/// The lanes of the hard rays `hard` on `shape`: each ray over `(0, ∞)`,
/// then from each of its first hits (a secondary ray: `t_min` at the hit)
/// and from each hit point (a ray starting on the surface), up to four hits
/// along the ray; after each hard lane 0 to 3 random lanes through `shape`'s
/// box that hit or miss ([`mixed_batch`]), so the hard lanes fall at uneven
/// places in the batches.
fn hard_lanes<S: Intersect + ?Sized>(shape: &S, hard: &[Ray], seed: u64) -> Vec<Lane> {
    let (fill_rays, fill_ranges) = mixed_batch(shape, 4 * 5 * hard.len() + LANES, seed);
    let mut fill = fill_rays.into_iter().zip(fill_ranges);
    let mut rng = Rng(seed);
    let mut lanes = Vec::new();
    for ray in hard {
        let mut t_min = 0.0;
        for _ in 0..4 {
            let hit = shape.intersect(ray, t_min, INF);
            lanes.push((*ray, (t_min, INF)));
            lanes.extend(fill.by_ref().take(rng.below(4)));
            let Some(h) = hit else { break };
            lanes.push((Ray::new(h.point, ray.dir), (0.0, INF)));
            lanes.extend(fill.by_ref().take(rng.below(4)));
            t_min = h.t;
        }
    }
    lanes.extend(fill.take(LANES));
    lanes
}

/// Checks the hard rays `hard` on `shape` ([`hard_lanes`] through
/// [`assert_batch_is_single`]); `hits_at_least` of the hard rays' own lanes
/// (over `(0, ∞)`) must hit, so the case is not all misses by mistake.
fn check_hard<S: Intersect + ?Sized>(what: &str, shape: &S, hard: &[Ray], hits_at_least: usize) {
    let hard_hits = hard
        .iter()
        .filter(|r| shape.intersect(r, 0.0, INF).is_some())
        .count();
    assert!(
        hard_hits >= hits_at_least,
        "{what}: only {hard_hits} of {} hard rays hit",
        hard.len()
    );
    let seed = what
        .bytes()
        .fold(17_u64, |h, b| h.wrapping_mul(31) ^ u64::from(b));
    let lanes = hard_lanes(shape, hard, seed);
    assert_batch_is_single(what, shape, &lanes);
}

fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
    Ray::new(Point3::from(o), Vector3::from(d))
}

/// The polyline through these points (a clamped degree-1 B-spline), revolved.
fn polyline(p: &[(f64, f64)]) -> Revolution<BSpline<2>> {
    Revolution::new(BSpline::clamped(1, points(p)).unwrap())
}

/// `n` rays from a sphere of radius `4·size` around `center` toward random
/// points of the box `center ± half`.
fn random_rays(seed: u64, n: usize, center: [f64; 3], half: [f64; 3], size: f64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    let c = Point3::from(center);
    (0..n)
        .map(|_| {
            let target = rng.point(
                [c.x - half[0], c.y - half[1], c.z - half[2]],
                [c.x + half[0], c.y + half[1], c.z + half[2]],
            );
            let origin = c + rng.direction() * 4.0 * size;
            Ray::new(origin, target - origin)
        })
        .collect()
}

/// `n` rays in random directions through the point `p`, starting `distance`
/// before it.
fn rays_through(seed: u64, n: usize, p: Point3<f64>, distance: f64) -> Vec<Ray> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let d = rng.direction();
            Ray::new(p - d * distance, d)
        })
        .collect()
}

/// The open cylinder `ρ = 1`, `0 ≤ y ≤ 2`.
fn cylinder() -> Revolution<revolve::Bezier<2>> {
    bezier(&[(1.0, 0.0), (1.0, 2.0)])
}

/// A closed body of one cubic Bézier with poles at both ends.
const CAPSULE: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];

/// The wine glass, its profile's `x` scaled by `s·m` and `y` by `s`.
fn glass(s: f64, m: f64) -> Revolution<BSpline<2>> {
    let p: Vec<(f64, f64)> = common::GLASS
        .iter()
        .map(|&(x, y)| (m * s * x, s * y))
        .collect();
    uniform_cubic(&p)
}

/// The points where the glass profile's spans join, `(x, y)`.
fn glass_joins() -> Vec<(f64, f64)> {
    let spans = common::wine_glass()
        .bezier_spans()
        .expect("polynomial spans");
    spans
        .iter()
        .skip(1)
        .map(|s| {
            let p = s.curve.points()[0];
            (p.x, p.y)
        })
        .collect()
}

/// The profile `x = 1 + u²⁰/2`, `y = u` (degree 20).
fn power20() -> Revolution<revolve::Bezier<2>> {
    let p: Vec<(f64, f64)> = (0..=20)
        .map(|i| (if i == 20 { 1.5 } else { 1.0 }, f64::from(i) / 20.0))
        .collect();
    bezier(&p)
}

/// The degree-20 bump `x = 1 + k·u¹⁰(1 − u)¹⁰`, `y = u`, widest (`ρ = 1.3`)
/// at `y = 1/2`.
fn bump20() -> Revolution<revolve::Bezier<2>> {
    let k = 0.3 * 4f64.powi(10);
    let p: Vec<(f64, f64)> = (0..=20)
        .map(|i| {
            let x = if i == 10 { 1.0 + k / 184_756.0 } else { 1.0 };
            (x, f64::from(i) / 20.0)
        })
        .collect();
    bezier(&p)
}

/// The segment `p0 → p1` degree-elevated to `n` (evenly spaced points).
fn elevated_line(p0: (f64, f64), p1: (f64, f64), n: usize) -> Vec<(f64, f64)> {
    (0..=n)
        .map(|i| {
            let s = i as f64 / n as f64;
            (p0.0 + (p1.0 - p0.0) * s, p0.1 + (p1.1 - p0.1) * s)
        })
        .collect()
}

// ---------------------------------------------------------------------------
// DESIGN.md §5, one test per group of hard cases
// ---------------------------------------------------------------------------

/// Rays along the axis (disks, cone apexes, the poles of closed bodies and
/// of the glass) and parallel to it off it (inside and outside cylinders,
/// on cones, disks, annuli through the hole, a cup, the capsule).
#[test]
fn hard_cases_along_and_parallel_to_the_axis_batch_equals_single() {
    let down = ray([0.0, 5.0, 0.0], [0.0, -1.0, 0.0]);
    let up = ray([0.0, -5.0, 0.0], [0.0, 2.0, 0.0]);
    let disk = bezier(&[(0.0, 0.5), (1.5, 0.5)]);
    let disk_rays = [
        down,
        up,
        ray([1.2, 3.0, 0.0], [0.0, -1.0, 0.0]),
        ray([-0.6, -1.0, 0.8], [0.0, 3.0, 0.0]),
        ray([1.6, 3.0, 0.0], [0.0, -1.0, 0.0]),
    ];
    check_hard("disk", &disk, &disk_rays, 4);
    check_hard(
        "reversed disk",
        &bezier(&[(1.5, 0.5), (0.0, 0.5)]),
        &[down, up],
        2,
    );
    check_hard(
        "cone apex",
        &bezier(&[(1.0, 0.0), (0.0, 1.0)]),
        &[down, up],
        2,
    );
    let steep = bezier(&[(0.0, -2.0), (0.25, 2.0)]);
    check_hard(
        "steep cone apex",
        &steep,
        &[ray([0.0, -6.0, 0.0], [0.0, 4.0, 0.0]), down],
        2,
    );
    let mut capsule_rays = vec![down, up];
    for rho in [0.05, 0.4, 0.7, 0.74, 0.743, 0.76] {
        for dir in [-1.0, 1.0] {
            capsule_rays.push(ray([rho, -3.0 * dir, 0.1], [0.0, dir, 0.0]));
        }
    }
    check_hard("capsule", &bezier(&CAPSULE), &capsule_rays, 12);
    let body = bezier(&[
        (0.0, 0.0),
        (1.0, 0.0),
        (2.0, 1.0),
        (2.0, 2.0),
        (1.0, 3.0),
        (0.0, 3.0),
    ]);
    check_hard(
        "degree-5 body",
        &body,
        &[down, ray([0.0, -2.0, 0.0], [0.0, 0.5, 0.0])],
        2,
    );
    let glass_axis = [
        ray([0.0, 3.0, 0.0], [0.0, -1.0, 0.0]),
        ray([0.0, -3.0, 0.0], [0.0, 1.0, 0.0]),
    ];
    check_hard("glass along its axis", &glass(1.0, 1.0), &glass_axis, 2);
    let cylinder_rays = [
        ray([0.5, -1.0, 0.3], [0.0, 1.0, 0.0]),
        ray([0.9, 3.0, -0.4], [0.0, -1.0, 0.0]),
        ray([1.5, -1.0, 0.3], [0.0, 1.0, 0.0]),
        down,
    ];
    check_hard("open cylinder", &cylinder(), &cylinder_rays, 0);
    let mut cone_rays: Vec<Ray> = [(0.7, 0.3), (0.3, 2.0), (0.999, 4.0), (0.2501, 5.5)]
        .iter()
        .map(|&(rho, phi): &(f64, f64)| {
            ray([rho * phi.cos(), 5.0, rho * phi.sin()], [0.0, -1.0, 0.0])
        })
        .collect();
    cone_rays.push(ray([1.1, 5.0, 0.0], [0.0, -1.0, 0.0]));
    check_hard(
        "frustum",
        &bezier(&[(1.0, 0.0), (0.25, 2.0)]),
        &cone_rays,
        4,
    );
    let annulus_rays = [
        ray([0.3, 3.0, 0.0], [0.0, -1.0, 0.0]),
        down,
        ray([0.6, 3.0, -0.45], [0.0, -1.0, 0.0]),
    ];
    check_hard(
        "annulus",
        &bezier(&[(0.5, 1.0), (1.0, 1.0)]),
        &annulus_rays,
        1,
    );
    let cup = polyline(&[(0.0, 0.0), (1.0, 0.0), (1.0, 2.0)]);
    check_hard(
        "cup",
        &cup,
        &[ray([0.5, 3.0, 0.2], [0.0, -1.0, 0.0]), down],
        2,
    );
}

/// Rays perpendicular to the axis, exactly and tilted by `±1e-12`,
/// `±1e-9`, `±1e-6`: cylinder, frustum, the degree-20 profile and rows
/// across the glass.
#[test]
fn hard_cases_perpendicular_to_the_axis_batch_equals_single() {
    for tilt in [0.0, 1e-12, -1e-12, 1e-9, -1e-9, 1e-6, -1e-6] {
        let mut rays = Vec::new();
        for h in [0.0, 0.3, 1.0, 1.7, 2.0] {
            for z in [0.0, 0.5, -0.9, -0.95] {
                rays.push(ray([-5.0, h, z], [1.0, tilt, 0.0]));
            }
        }
        check_hard(&format!("cylinder, tilt {tilt:e}"), &cylinder(), &rays, 12);
        let rays: Vec<Ray> = [0.1, 0.8, 1.0, 1.9]
            .iter()
            .map(|&h| ray([-5.0, h, 0.2], [1.0, tilt, 0.0]))
            .collect();
        let frustum = bezier(&[(1.0, 0.0), (0.25, 2.0)]);
        check_hard(&format!("frustum, tilt {tilt:e}"), &frustum, &rays, 4);
        let rays: Vec<Ray> = [0.0, 0.2, 0.9, 0.95, 0.99, 1.0]
            .iter()
            .map(|&h| ray([0.3, h, 4.0], [0.0, tilt, -2.0]))
            .collect();
        check_hard(&format!("degree 20, tilt {tilt:e}"), &power20(), &rays, 4);
        let rays: Vec<Ray> = (0..=60)
            .map(|i| {
                let h = -1.05 + 2.15 * f64::from(i) / 60.0;
                ray([-2.0, h, 0.026 * f64::from(i) - 0.7], [1.0, tilt, 0.0])
            })
            .collect();
        check_hard(
            &format!("glass rows, tilt {tilt:e}"),
            &glass(1.0, 1.0),
            &rays,
            30,
        );
    }
}

/// Rays through the axis: oblique through a closed cylinder, the capsule and
/// the glass's stem (also starting on the axis inside), through cone apexes
/// and disk centres; profiles touching the axis with repeated control points
/// (the course's vase: poles, its flat bottom hit vertically at radii down
/// to `1e-300`, oblique rays through the poles).
#[test]
fn hard_cases_through_the_axis_and_the_poles_batch_equals_single() {
    let closed = polyline(&[(0.0, 0.0), (1.0, 0.0), (1.0, 2.0), (0.0, 2.0)]);
    let mut rays = Vec::new();
    for (i, y) in [0.05, 0.7, 1.3, 1.95].into_iter().enumerate() {
        let through = Point3::new(0.0, y, 0.0);
        rays.extend(rays_through(10 + i as u64, 8, through, 3.0));
        rays.extend(rays_through(20 + i as u64, 4, through, 0.0));
    }
    check_hard("closed cylinder through its axis", &closed, &rays, 40);
    let mut rays = Vec::new();
    for y in [0.02, 0.5, 0.98] {
        rays.extend(rays_through(30, 8, Point3::new(0.0, y, 0.0), 3.0));
        rays.extend(rays_through(31, 4, Point3::new(0.0, y, 0.0), 0.0));
    }
    check_hard("capsule through its axis", &bezier(&CAPSULE), &rays, 30);
    let mut rays = Vec::new();
    for y in [-0.75, -0.4, -0.15] {
        rays.extend(rays_through(40, 8, Point3::new(0.0, y, 0.0), 3.0));
        rays.extend(rays_through(41, 4, Point3::new(0.0, y, 0.0), 0.0));
    }
    check_hard("glass stem through its axis", &glass(1.0, 1.0), &rays, 30);
    let apex: Vec<Ray> = [[-0.5, -1.0, 0.2], [0.3, -2.0, -0.6], [0.0, -1.0, 0.9]]
        .iter()
        .map(|&d| {
            let d = Vector3::from(d);
            Ray::new(Point3::new(0.0, 1.0, 0.0) - d * 2.0, d)
        })
        .collect();
    check_hard(
        "cone apex, obliquely",
        &bezier(&[(1.0, 0.0), (0.0, 1.0)]),
        &apex,
        3,
    );
    let mut centre = Vec::new();
    for a in (1..10).step_by(2) {
        for b in (1..10).step_by(2) {
            for c in (1..10).step_by(4) {
                let d = Vector3::new(f64::from(a), -f64::from(b), f64::from(c)) / 10.0;
                centre.push(Ray::new(Point3::origin() - d * 3.0, d));
            }
        }
    }
    check_hard(
        "disk centre, obliquely",
        &bezier(&[(0.0, 0.0), (1.0, 0.0)]),
        &centre,
        75,
    );
    // The course's closed vase: the first three and last three control
    // points equal and on the axis (flat pole spans).
    let vase = uniform_cubic(&[
        (0.0, 0.0),
        (0.0, 0.0),
        (0.0, 0.0),
        (0.9, 0.0),
        (1.0, 0.5),
        (0.5, 1.2),
        (0.8, 2.0),
        (0.0, 2.0),
        (0.0, 2.0),
        (0.0, 2.0),
    ]);
    let mut rays = vec![ray([0.0, 5.0, 0.0], [0.0, -1.0, 0.0])];
    for rho in [1e-300, 1e-12, 1e-6, 0.01, 0.1, 0.149] {
        for phi in [0.0_f64, 2.5] {
            rays.push(ray(
                [rho * phi.cos(), -1.0, rho * phi.sin()],
                [0.0, 1.0, 0.0],
            ));
        }
    }
    for pole in [Point3::origin(), Point3::new(0.0, 2.0, 0.0)] {
        for distance in [0.5, 3.0] {
            rays.extend(rays_through(50, 12, pole, distance));
        }
    }
    rays.extend(random_rays(51, 40, [0.0, 1.0, 0.0], [1.0, 1.1, 1.0], 1.5));
    check_hard("vase with repeated pole points", &vase, &rays, 40);
}

/// Tangent and grazing rays on silhouettes, both sides of tangency: a
/// cylinder missed or cut by `1e-6`, `1e-9`, `1e-12` of its radius (level
/// and tilted), the degree-20 bump's curved silhouette (vertical and
/// perpendicular rays), and rays along the glass's surface tangents.
#[test]
fn hard_cases_grazing_silhouettes_batch_equals_single() {
    let mut rays = Vec::new();
    for delta in [1e-6, 1e-9, 1e-12, -1e-6, -1e-9, -1e-12, 0.0] {
        for tilt in [0.0, 1e-3] {
            rays.push(ray([-5.0, 0.7, 1.0 - delta], [1.0, tilt, 0.0]));
        }
    }
    check_hard("cylinder silhouette", &cylinder(), &rays, 6);
    let mut rays = Vec::new();
    for delta in [1e-6, 1e-9, -1e-6, -1e-9, 1e-12, 0.0] {
        let rho = 1.3 * (1.0 - delta);
        rays.push(ray([rho * 0.6, 3.0, -rho * 0.8], [0.0, -1.0, 0.0]));
        rays.push(ray([rho, 3.0, 0.0], [0.0, -1.0, 0.0]));
        rays.push(ray([-4.0, 0.5, rho], [1.0, 0.0, 0.0]));
    }
    check_hard("bump silhouette", &bump20(), &rays, 6);
    // Along the tangent of the glass profile at many points, in the
    // meridian plane and turned out of it: tangent to the surface.
    let g = glass(1.0, 1.0);
    let profile = common::wine_glass();
    let (u0, u1) = profile.domain();
    let mut rays = Vec::new();
    for i in 0..=60 {
        let u = u0 + (u1 - u0) * f64::from(i) / 60.0;
        let (p, d) = profile.eval_with_derivative(u);
        let surface_point = Point3::new(p.x, p.y, 0.0);
        for dir in [Vector3::new(d.x, d.y, 0.0), Vector3::new(0.0, 0.0, 1.0)] {
            rays.push(Ray::new(surface_point - dir * 2.0, dir));
        }
    }
    check_hard("glass tangents", &g, &rays, 60);
}

/// Hits exactly at span joins and within `1e-10`, `1e-13` of them (level
/// and tilted by `±1e-9`, `±1e-12`): a stepped polyline, a bellows of 40
/// cones (more spans entered than are sorted), the glass's joins.
#[test]
fn hard_cases_at_span_joins_batch_equals_single() {
    let stepped = [(1.0, 0.0), (1.0, 1.0), (0.5, 1.5), (0.5, 2.0), (0.0, 2.0)];
    let mut rays = Vec::new();
    for (h, z) in [(1.0, 0.3), (1.5, 0.1), (1.0, 0.0), (1.5, -0.45), (2.0, 0.2)] {
        rays.push(ray([-5.0, h, z], [1.0, 0.0, 0.0]));
    }
    let mut rng = Rng(3);
    for &(x, y) in &stepped[1..4] {
        for _ in 0..12 {
            let theta = rng.range(0.0, std::f64::consts::TAU);
            let join = Point3::new(x * theta.cos(), y, -x * theta.sin());
            let d = rng.direction();
            rays.push(Ray::new(join - d * 2.5, d));
        }
    }
    for offset in [1e-10, -1e-10, 1e-13, -1e-13] {
        for tilt in [0.0, 1e-9, -1e-9, 1e-12, -1e-12] {
            for h in [1.0, 1.5] {
                rays.push(ray([-5.0, h + offset, 0.2], [1.0, tilt, 0.0]));
            }
        }
    }
    check_hard("stepped polyline joins", &polyline(&stepped), &rays, 60);
    let bellows: Vec<(f64, f64)> = (0..=40)
        .map(|i| (if i % 2 == 0 { 0.9 } else { 1.1 }, 0.1 * f64::from(i)))
        .collect();
    let rays = [
        ray([1.0, -1.0, 0.0], [0.001, 1.0, 0.0005]),
        ray([0.0, 5.0, 1.0], [-0.0005, -1.0, 0.001]),
        ray([0.7, -0.5, 0.7], [0.0003, 1.0, 0.0002]),
    ];
    check_hard("bellows", &polyline(&bellows), &rays, 3);
    let mut rays = Vec::new();
    let mut rng = Rng(8);
    for (x, y) in glass_joins() {
        rays.push(ray([-2.0, y, 0.37 * x], [1.0, 0.0, 0.0]));
        for _ in 0..(if x > 0.0 { 3 } else { 0 }) {
            let theta = rng.range(0.0, std::f64::consts::TAU);
            let join = Point3::new(x * theta.cos(), y, -x * theta.sin());
            let d = rng.direction();
            rays.push(Ray::new(join - d * 2.5, d));
        }
    }
    check_hard("glass joins", &glass(1.0, 1.0), &rays, 40);
}

/// Rays lying in the surface or starting just before it: in a cylinder's
/// wall and just off it, in a flat annulus's plane and just off it, tilted
/// through that plane by `2⁻⁴⁰`, in the plane of the glass's flat foot, and
/// hits `1e-10` after the origin.
#[test]
fn hard_cases_rays_in_the_surface_batch_equals_single() {
    let mut rays = vec![
        ray([1.0, -1.0, 0.0], [0.0, 1.0, 0.0]),
        ray([0.0, 3.0, -1.0], [0.0, -2.0, 0.0]),
        ray([0.6, 1.0, 0.8], [0.0, 1.0, 0.0]),
    ];
    for delta in [1e-6, 1e-9, 1e-12, -1e-6, -1e-9, -1e-12] {
        rays.push(ray([1.0 + delta, -1.0, 0.0], [0.0, 1.0, 0.0]));
        rays.push(ray([0.0, 3.0, 1.0 + delta], [0.0, -1.0, 0.0]));
    }
    for gap in [1e-10, 1e-11] {
        rays.push(ray([-1.0 - gap, 0.7, 0.0], [1.0, 0.0, 0.0]));
    }
    check_hard("cylinder wall", &cylinder(), &rays, 3);
    let cup = polyline(&[(0.0, 0.0), (1.0, 0.0), (1.0, 2.0)]);
    let rays = [
        ray([1.0 - 1e-6, 3.0, 0.0], [0.0, -1.0, 0.0]),
        ray([1.0 - 1e-9, 3.0, 0.0], [0.0, -1.0, 0.0]),
    ];
    check_hard("cup wall", &cup, &rays, 2);
    let tiny = 2f64.powi(-40);
    let mut rays: Vec<Ray> = [
        [-3.0, 1.0, 0.0],
        [-3.0, 1.0, 0.3],
        [-3.0, 1.0, 0.7],
        [0.0, 1.0, 0.75],
    ]
    .iter()
    .map(|&o| ray(o, [1.0, 0.0, 0.0]))
    .collect();
    for delta in [1e-6, 1e-9, 1e-12, -1e-6, -1e-9, -1e-12] {
        rays.push(ray([-3.0, 1.0 + delta, 0.0], [1.0, 0.0, 0.0]));
    }
    rays.push(ray([-2.75, 1.0 - 2.0 * tiny, 0.0], [1.0, tiny, 0.0]));
    check_hard(
        "annulus plane",
        &bezier(&[(0.5, 1.0), (1.0, 1.0)]),
        &rays,
        2,
    );
    let rays = [
        ray([-2.0, -1.0, 0.0], [1.0, 0.0, 0.0]),
        ray([-2.0, -1.0, 0.3], [1.0, 0.0, 0.2]),
    ];
    check_hard("glass foot plane", &glass(1.0, 1.0), &rays, 1);
}

/// Profiles with negative `x` (the cylinder and the glass mirrored) and
/// profiles crossing the axis (the double cone `ρ = |y − 1|` through its
/// apex and along its axis; a cubic crossing the axis three times).
#[test]
fn hard_cases_negative_x_and_crossing_the_axis_batch_equals_single() {
    let rays = random_rays(31, 60, [0.0, 0.5, 0.0], [1.2, 0.7, 1.2], 1.0);
    check_hard(
        "cylinder of negative x",
        &bezier(&[(-1.0, 0.0), (-1.0, 1.0)]),
        &rays,
        20,
    );
    let rays = random_rays(32, 60, [0.0, 0.0, 0.0], [0.8, 1.1, 0.8], 1.0);
    check_hard("glass of negative x", &glass(1.0, -1.0), &rays, 20);
    let double_cone = bezier(&[(-1.0, 0.0), (1.0, 2.0)]);
    let mut rays = rays_through(41, 30, Point3::new(0.0, 1.0, 0.0), 3.0);
    rays.extend(random_rays(42, 30, [0.0, 1.0, 0.0], [1.0, 1.0, 1.0], 1.0));
    rays.push(ray([0.0, 5.0, 0.0], [0.0, -1.0, 0.0]));
    check_hard("double cone", &double_cone, &rays, 40);
    let wave = bezier(&[(-1.0, 0.0), (1.0, 0.5), (-1.0, 1.5), (1.0, 2.0)]);
    let mut rays = random_rays(43, 40, [0.0, 1.0, 0.0], [0.6, 1.0, 0.6], 1.0);
    for i in 0..=40 {
        rays.push(ray([-2.0, 0.05 * f64::from(i), 0.1], [1.0, 0.0, 0.0]));
    }
    check_hard("profile crossing the axis", &wave, &rays, 30);
}

/// Degrees 1 to 20 (a frustum, a cylinder, an annulus and a disk as
/// degree-elevated lines; the degree-20 power and bump profiles; a parabola
/// elevated to degree 20) and scenes scaled by `1e-6` and `1e6` (cylinder,
/// frustum, glass).
#[test]
fn hard_cases_degrees_1_to_20_and_scales_batch_equals_single() {
    let down = ray([0.0, 2.0, 0.0], [0.0, -1.0, 0.0]);
    let segments = [
        ((1.2, -0.5), (0.3, 1.5)),
        ((0.8, -1.0), (0.8, 1.0)),
        ((0.3, 0.25), (1.1, 0.25)),
        ((0.0, 0.25), (1.1, 0.25)),
    ];
    for n in [1, 2, 3, 5, 8, 13, 20] {
        for (k, (p0, p1)) in segments.into_iter().enumerate() {
            let mut rays = random_rays(60 + k as u64, 16, [0.0, 0.5, 0.0], [1.3, 1.1, 1.3], 1.2);
            rays.push(down);
            let s = bezier(&elevated_line(p0, p1, n));
            check_hard(&format!("line {k} elevated to degree {n}"), &s, &rays, 4);
        }
    }
    let mut rays = random_rays(61, 30, [0.0, 0.5, 0.0], [1.4, 0.6, 1.4], 1.5);
    for rho in [1.0001, 1.1, 1.3, 1.49] {
        rays.push(ray([0.0, 3.0, rho], [0.0, -1.0, 0.0]));
    }
    check_hard("degree-20 power", &power20(), &rays, 10);
    let mut rays = random_rays(62, 30, [0.0, 0.5, 0.0], [1.2, 0.6, 1.2], 1.3);
    for rho in [1.001, 1.1, 1.25] {
        rays.push(ray([rho, 3.0, 0.0], [0.0, -1.0, 0.0]));
    }
    check_hard("degree-20 bump", &bump20(), &rays, 10);
    let n = 20.0;
    let parabola: Vec<(f64, f64)> = (0..=20)
        .map(|i| {
            let i = f64::from(i);
            (
                0.5 + 2.0 * i / n - 2.0 * i * (i - 1.0) / (n * (n - 1.0)),
                2.0 * i / n,
            )
        })
        .collect();
    let mut rays = random_rays(63, 30, [0.0, 1.0, 0.0], [1.0, 1.1, 1.0], 1.0);
    for rho in [0.6, 0.8, 0.99] {
        rays.push(ray([0.0, 3.0, rho], [0.0, -1.0, 0.0]));
    }
    check_hard(
        "parabola elevated to degree 20",
        &bezier(&parabola),
        &rays,
        10,
    );
    for s in [1e-6, 1e6] {
        let mut rays: Vec<Ray> = [0.0, 0.6, -0.99]
            .iter()
            .flat_map(|&z| {
                [
                    ray([-5.0 * s, 0.7 * s, z * s], [1.0, 0.0, 0.0]),
                    ray([-5.0 * s, 0.7 * s, z * s], [s, 0.0, 0.0]),
                ]
            })
            .collect();
        rays.extend(random_rays(
            64,
            20,
            [0.0, s, 0.0],
            [1.2 * s, 1.1 * s, 1.2 * s],
            s,
        ));
        check_hard(
            &format!("cylinder at {s:e}"),
            &bezier(&[(s, 0.0), (s, 2.0 * s)]),
            &rays,
            6,
        );
        let frustum = bezier(&[(s, 0.0), (0.25 * s, 2.0 * s)]);
        check_hard(&format!("frustum at {s:e}"), &frustum, &rays, 6);
        let rays = random_rays(65, 40, [0.0, 0.0, 0.0], [0.8 * s, 1.1 * s, 0.8 * s], s);
        check_hard(&format!("glass at {s:e}"), &glass(s, 1.0), &rays, 10);
    }
}

// ---------------------------------------------------------------------------
// A million random rays per profile
// ---------------------------------------------------------------------------

/// The kinds of lane in [`million_mixed_lanes`].
const KINDS: [&str; 7] = [
    "through the box",
    "perpendicular to the axis",
    "within 1e-12 of perpendicular",
    "along the axis, on it",
    "along the axis, off it",
    "missing the box",
    "through the box, later or shorter range",
];

/// The index of the rays on the axis in [`KINDS`].
const ON_AXIS: usize = 3;

/// The index of the kind that misses in [`KINDS`].
const MISSING: usize = 5;

/// A million random rays on `shape` (a surface of revolution about the y
/// axis), in slices of 4096 − (0..8) lanes so the batches end at every
/// remainder, each lane of a kind of [`KINDS`] drawn at random; each lane
/// bit for bit its single-ray answer. Every kind but the misses must hit
/// often, except rays on the axis when the profile does not reach it
/// (`reaches_axis` false): those never hit.
fn million_mixed_lanes<S: Intersect>(name: &str, shape: &S, reaches_axis: bool, seed: u64) {
    const RAYS: usize = 1_000_000;
    let b = shape.bounds();
    let reach = 4.0 * b.extent().norm();
    let mut rng = Rng(seed);
    let mut done = 0;
    let mut hits_of_kind = [0_usize; KINDS.len()];
    let mut slice = 0;
    while done < RAYS {
        let n = (4096 - slice % LANES).min(RAYS - done);
        slice += 1;
        let mut kinds = Vec::with_capacity(n);
        let mut lanes: Vec<Lane> = Vec::with_capacity(n);
        for _ in 0..n {
            let kind = rng.below(KINDS.len());
            let target = rng.point_in(&b);
            let mut range = (0.0, INF);
            let dir: Vector3<f64> = match kind {
                1 | 2 => {
                    let d = rng.direction();
                    let tilt = if kind == 2 {
                        1e-12 * rng.range(-1.0, 1.0)
                    } else {
                        0.0
                    };
                    Vector3::new(d.x, tilt, d.z + 1e-3)
                }
                3 | 4 => Vector3::new(0.0, if rng.below(2) == 0 { -1.0 } else { 2.5 }, 0.0),
                _ => rng.direction(),
            };
            let mut origin = target - dir * (reach / dir.norm());
            let mut dir = dir;
            match kind {
                ON_AXIS => {
                    origin.x = 0.0;
                    origin.z = 0.0;
                }
                MISSING => {
                    // Beyond the box in z, heading further away.
                    origin = target + Vector3::new(0.0, 0.0, 2.0 * reach);
                    dir.z = dir.z.abs() + 0.1;
                }
                6 => {
                    let t = rng.range(0.0, 2.0 * reach);
                    range = if rng.below(2) == 0 {
                        (t, INF)
                    } else {
                        (0.0, t)
                    };
                }
                _ => {}
            }
            lanes.push((Ray::new(origin, dir), range));
            kinds.push(kind);
        }
        let (rays, ranges): (Vec<Ray>, Vec<(f64, f64)>) = lanes.iter().copied().unzip();
        let mut batch = vec![stale(); n];
        shape.intersect_batch(&rays, &ranges, &mut batch);
        for (i, ((ray, (t_min, t_max)), got)) in lanes.iter().zip(&batch).enumerate() {
            let want = shape.intersect(ray, *t_min, *t_max);
            assert!(
                bits(got) == bits(&want),
                "{name}: lane {i} ({}): {ray:?} in ({t_min}, {t_max}): batch {got:?}, \
                 single {want:?}",
                KINDS[kinds[i]]
            );
            hits_of_kind[kinds[i]] += usize::from(want.is_some());
        }
        done += n;
    }
    for (k, (kind, hits)) in KINDS.iter().zip(hits_of_kind).enumerate() {
        eprintln!("{name}: {hits} hits {kind}");
        let never = k == MISSING || (k == ON_AXIS && !reaches_axis);
        assert!(
            if never { hits == 0 } else { hits > 1000 },
            "{name}: {hits} hits {kind}"
        );
    }
}

#[test]
fn a_million_mixed_lanes_on_the_wine_glass_batch_equals_single() {
    million_mixed_lanes(
        "wine glass",
        &Revolution::new(common::wine_glass()),
        true,
        101,
    );
}

#[test]
fn a_million_mixed_lanes_on_the_vase_batch_equals_single() {
    million_mixed_lanes("vase", &Revolution::new(common::vase()), false, 102);
}

#[test]
fn a_million_mixed_lanes_on_the_nurbs_sphere_batch_equals_single() {
    let sphere = Revolution::new(common::conic_profiles::sphere_profile(1.0));
    million_mixed_lanes("NURBS sphere", &sphere, true, 103);
}
