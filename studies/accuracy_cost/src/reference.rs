//! The study's references, from `revolve-testkit` (shared with the
//! integration tests): the exact rational reference for surfaces of
//! revolution ([`ExactProfile`]), the certified interval reference for
//! Bézier patches ([`PatchReference`]) and the [`Certifier`] trait the
//! measurements ask them through (the closed forms of the rational sphere
//! and torus implement it too: [`crate::closed_form`]).
//!
//! The tests below check those references against closed forms and exact
//! residuals (the study's numbers are only as good as they are).

pub use crate::common::reference::Certifier;
pub use crate::common::reference::patch::PatchReference;
pub use crate::common::reference::revolution::ExactProfile;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::common::reference::exact::{Frac, round_ratio};
    use crate::common::reference::revolution::{Reference, ray, search};
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use num_traits::{Signed, Zero};
    use revolve::Ray;
    use revolve::nalgebra::Point2;
    use revolve::nalgebra::{Point3, Vector3};
    use revolve::{BSpline, Bezier, Curve};

    type Q = BigRational;

    fn q(v: f64) -> Q {
        let f = Frac::from_f64(v);
        Q::new(f.num, f.den)
    }

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(Point3::from(o), Vector3::from(d))
    }

    fn pt(x: f64, y: f64) -> Point2<f64> {
        Point2::new(x, y)
    }

    /// The neighbouring `f64`s of a finite nonzero `t`.
    fn neighbours(t: f64) -> (f64, f64) {
        let b = t.to_bits();
        let (a, c) = (f64::from_bits(b - 1), f64::from_bits(b + 1));
        if t > 0.0 { (a, c) } else { (c, a) }
    }

    /// SplitMix64 in `[0, 1)`.
    struct Rng(u64);
    impl Rng {
        fn range(&mut self, lo: f64, hi: f64) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            lo + (hi - lo) * (((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64)
        }
    }

    // -- Closed forms for a segment profile (x ≥ 0) ------------------------

    /// All hits `(t, u)` of the ray with the revolved segment `p0 → p1`, in
    /// f64 with the cancellation-free quadratic formula.
    fn segment_hits(p0: Point2<f64>, p1: Point2<f64>, r: &Ray) -> Vec<(f64, f64)> {
        let (o, d) = (r.origin, r.dir);
        if p0.y == p1.y {
            // Disk or annulus: the plane Y = p0.y.
            let t = (p0.y - o.y) / d.y;
            let rho = (o.x + t * d.x).hypot(o.z + t * d.z);
            let u = (rho - p0.x) / (p1.x - p0.x);
            return if (0.0..=1.0).contains(&u) {
                vec![(t, u)]
            } else {
                vec![]
            };
        }
        // x(Y) = x0 + k(Y − y0) = h0 + h1·t along the ray.
        let k = (p1.x - p0.x) / (p1.y - p0.y);
        let (h0, h1) = (p0.x + k * (o.y - p0.y), k * d.y);
        let qa = d.x * d.x + d.z * d.z - h1 * h1;
        let qb = o.x * d.x + o.z * d.z - h0 * h1;
        let qc = o.x * o.x + o.z * o.z - h0 * h0;
        let disc = qb * qb - qa * qc;
        let ts = if qa == 0.0 {
            vec![-qc / (2.0 * qb)]
        } else if disc < 0.0 {
            vec![]
        } else {
            let qq = -(qb + qb.signum() * disc.sqrt());
            vec![qq / qa, qc / qq]
        };
        ts.into_iter()
            .map(|t| (t, (o.y + t * d.y - p0.y) / (p1.y - p0.y)))
            .filter(|&(t, u)| t.is_finite() && (0.0..=1.0).contains(&u))
            .collect()
    }

    /// The exact residual `X² + Z² − x(Y)²` at ray parameter `t` (segment
    /// profile, not horizontal).
    fn residual(p0: Point2<f64>, p1: Point2<f64>, r: &Ray, t: f64) -> Q {
        let t = q(t);
        let at = |o: f64, d: f64| q(o) + &t * q(d);
        let (x, y, z) = (
            at(r.origin.x, r.dir.x),
            at(r.origin.y, r.dir.y),
            at(r.origin.z, r.dir.z),
        );
        let h = q(p0.x) + (q(p1.x) - q(p0.x)) / (q(p1.y) - q(p0.y)) * (y - q(p0.y));
        &x * &x + &z * &z - &h * &h
    }

    /// Checks the reference on a segment profile against the closed form:
    /// same hit or miss, `t` within `tol·(1 + |t|)`, `u` within 1e-9, and
    /// for a slanted segment the exact residual changes sign across the
    /// returned `t`'s neighbours (so `t` is within an ulp). Returns the answer.
    fn check_segment(
        p0: Point2<f64>,
        p1: Point2<f64>,
        r: Ray,
        t_min: f64,
        t_max: f64,
        tol: f64,
    ) -> Reference {
        let got = ExactProfile::from_bezier(&[p0, p1]).nearest(&r, t_min, t_max);
        let want = segment_hits(p0, p1, &r)
            .into_iter()
            .filter(|&(t, _)| t_min < t && t < t_max)
            .min_by(|a, b| a.0.total_cmp(&b.0));
        match (got, want) {
            (Reference::Hit { t, u }, Some((tc, uc))) => {
                assert!(
                    (t - tc).abs() <= tol * (1.0 + tc.abs()),
                    "t {t} vs closed form {tc}"
                );
                assert!((u - uc).abs() <= 1e-9, "u {u} vs closed form {uc}");
                if p0.y != p1.y {
                    let (a, b) = neighbours(t);
                    let (ga, gb) = (residual(p0, p1, &r, a), residual(p0, p1, &r, b));
                    assert!(
                        residual(p0, p1, &r, t).is_zero() || ga.signum() != gb.signum(),
                        "exact root not within an ulp of {t}"
                    );
                }
            }
            (Reference::Miss, None) => {}
            (g, w) => panic!("reference {g:?}, closed form {w:?}"),
        }
        got
    }

    fn is_hit(r: Reference) -> bool {
        matches!(r, Reference::Hit { .. })
    }

    const INF: f64 = f64::INFINITY;

    // -- Exact arithmetic ------------------------------------------------

    #[test]
    fn rounding_is_correct() {
        // IEEE division of integers below 2^53 is correctly rounded.
        let mut rng = Rng(1);
        for _ in 0..2000 {
            let a = rng.range(-9e15, 9e15).trunc();
            let b = rng.range(1.0, 9e15).trunc();
            let got = round_ratio(&BigInt::from(a as i64), &BigInt::from(b as i64));
            assert_eq!(got, a / b, "{a}/{b}");
        }
        let big = |e: u32| BigInt::from(1) << e;
        // Ties to even: 2^53 + 1 and 2^53 + 3 lie halfway between floats.
        assert_eq!(
            round_ratio(&(big(53) + 1), &BigInt::from(1)),
            9007199254740992.0
        );
        assert_eq!(
            round_ratio(&(big(53) + 3), &BigInt::from(1)),
            9007199254740996.0
        );
        // Just above a tie rounds up.
        assert_eq!(
            round_ratio(&(big(54) + 3), &BigInt::from(2)),
            9007199254740994.0
        );
        // Subnormals, underflow, overflow.
        assert_eq!(round_ratio(&BigInt::from(3), &big(1075)), f64::from_bits(2)); // 1.5·2^-1074 → even 2
        assert_eq!(round_ratio(&BigInt::from(1), &big(1075)), 0.0); // tie with 0 → 0
        assert_eq!(
            round_ratio(&BigInt::from(-3), &big(1076)),
            -f64::from_bits(1)
        );
        assert_eq!(round_ratio(&big(1024), &BigInt::from(1)), f64::INFINITY);
        assert_eq!(Frac::from_f64(f64::MAX).to_f64(), f64::MAX);
        for v in [0.1, -2.5e-310, 1e300, 1.0 / 3.0, -7.0] {
            assert_eq!(Frac::from_f64(v).to_f64(), v);
        }
    }

    // -- Closed forms ----------------------------------------------------

    #[test]
    fn cylinder_matches_closed_form() {
        let (p0, p1) = (pt(0.75, -1.0), pt(0.75, 1.5));
        let tol = 4.0 * f64::EPSILON;
        // Oblique from outside: the near wall.
        assert!(is_hit(check_segment(
            p0,
            p1,
            ray([3.0, 0.2, 0.4], [-1.0, 0.1, -0.13]),
            0.0,
            INF,
            tol
        )));
        // From inside: the far wall only.
        assert!(is_hit(check_segment(
            p0,
            p1,
            ray([0.1, 0.0, -0.2], [0.3, 0.7, 0.45]),
            0.0,
            INF,
            tol
        )));
        // From inside, downwards, with windows that cut the span's t range.
        let down = ray([0.1, 1.0, -0.2], [0.3, -0.7, 0.45]);
        let Reference::Hit { t: wall, .. } = check_segment(p0, p1, down, 0.0, INF, tol) else {
            panic!("the wall from inside")
        };
        assert!(is_hit(check_segment(p0, p1, down, 0.5 * wall, INF, tol)));
        assert!(is_hit(check_segment(
            p0,
            p1,
            down,
            0.5 * wall,
            1.5 * wall,
            tol
        )));
        assert_eq!(
            check_segment(p0, p1, down, 0.5 * wall, 0.9 * wall, tol),
            Reference::Miss
        );
        // Down through the open top: the inside of the wall.
        assert!(is_hit(check_segment(
            p0,
            p1,
            ray([0.1, 3.0, 0.0], [0.2, -1.0, 0.05]),
            0.0,
            INF,
            tol
        )));
        // Passing beside it, and over it.
        assert_eq!(
            check_segment(
                p0,
                p1,
                ray([3.0, 0.0, 0.8], [-1.0, 0.01, 0.0]),
                0.0,
                INF,
                tol
            ),
            Reference::Miss
        );
        assert_eq!(
            check_segment(
                p0,
                p1,
                ray([3.0, 2.0, 0.0], [-1.0, 0.1, 0.0]),
                0.0,
                INF,
                tol
            ),
            Reference::Miss
        );
        // Nearly tangent, inside and outside by 2^-20 of the radius.
        let grazing = 0.75 * (1.0 - 2f64.powi(-20));
        let near = check_segment(
            p0,
            p1,
            ray([3.0, 0.0, grazing], [-1.0, 0.01, 0.0]),
            0.0,
            INF,
            1e-9,
        );
        assert!(is_hit(near));
        let outside = 0.75 * (1.0 + 2f64.powi(-20));
        assert_eq!(
            check_segment(
                p0,
                p1,
                ray([3.0, 0.0, outside], [-1.0, 0.01, 0.0]),
                0.0,
                INF,
                tol
            ),
            Reference::Miss
        );
        // The window: t_max before the first hit, t_min past it.
        let r = ray([3.0, 0.2, 0.4], [-1.0, 0.1, -0.13]);
        let Reference::Hit { t: first, .. } = check_segment(p0, p1, r, 0.0, INF, tol) else {
            panic!("oblique ray must hit")
        };
        assert_eq!(
            check_segment(p0, p1, r, 0.0, first * 0.999, tol),
            Reference::Miss
        );
        let Reference::Hit { t: second, .. } = check_segment(p0, p1, r, first * 1.001, INF, tol)
        else {
            panic!("the far wall")
        };
        assert!(second > first + 1.0);
        // t_min exactly at the rounded first hit: the exact root is on one
        // side of it, and the answer must follow that side.
        let got = ExactProfile::from_bezier(&[p0, p1]).nearest(&r, first, INF);
        // The residual at `first` still has the outside's sign (that at t = 0)
        // iff the exact root is above `first`.
        let root_above = residual(p0, p1, &r, first).signum() == residual(p0, p1, &r, 0.0).signum();
        if root_above {
            assert!(
                matches!(got, Reference::Hit { t, .. } if t == first),
                "{got:?}"
            );
        } else {
            assert!(
                matches!(got, Reference::Hit { t, .. } if t == second),
                "{got:?}"
            );
        }
    }

    #[test]
    fn cone_and_frustum_match_closed_form() {
        let tol = 4.0 * f64::EPSILON;
        let cone = (pt(0.0, -0.5), pt(1.25, 1.0));
        let frustum = (pt(0.3, -1.0), pt(0.9, 0.7));
        let inverted = (pt(1.1, -0.2), pt(0.2, 0.9));
        let rays = [
            (ray([2.0, 0.3, 0.5], [-1.0, -0.05, -0.2]), true),
            (ray([0.05, 0.8, 0.0], [0.5, -0.3, 0.2]), true), // from inside
            (ray([0.0, -3.0, 0.0], [0.01, 1.0, 0.02]), false), // up the axis
            (ray([2.0, 3.0, 2.0], [0.1, 1.0, 0.1]), false),  // away
            (ray([-2.0, 0.35, 1.9], [1.0, 0.0001, 0.0]), false), // beside
        ];
        for (p0, p1) in [cone, frustum, inverted] {
            for &(r, hits) in &rays {
                let got = check_segment(p0, p1, r, 0.0, INF, tol);
                // The first three hit every one of these shapes.
                if hits {
                    assert!(is_hit(got), "{p0:?} {p1:?} {r:?}");
                }
            }
        }
        // Up the axis: into the cone's tip; through the others' openings.
        assert!(is_hit(check_segment(
            cone.0, cone.1, rays[2].0, 0.0, INF, tol
        )));
        assert_eq!(
            check_segment(frustum.0, frustum.1, rays[2].0, 0.0, INF, tol),
            Reference::Miss
        );
        assert!(is_hit(check_segment(
            cone.0, cone.1, rays[0].0, 1.5, 10.0, tol
        )));
    }

    #[test]
    fn disk_and_annulus_match_closed_form() {
        let disk = ExactProfile::from_bezier(&[pt(0.0, 0.5), pt(0.9, 0.5)]);
        let annulus = ExactProfile::from_bezier(&[pt(0.3, 0.5), pt(0.9, 0.5)]);
        // c − o_y = −1.5 exactly, so IEEE division gives the rounded exact t.
        let r = ray([0.1, 2.0, -0.2], [0.05, -0.7, 0.1]);
        let t = -1.5 / -0.7;
        let Reference::Hit { t: got, u } = disk.nearest(&r, 0.0, INF) else {
            panic!("disk")
        };
        assert_eq!(got, t);
        let rho = (0.1 + t * 0.05f64).hypot(-0.2 + t * 0.1);
        assert!((u - rho / 0.9).abs() < 1e-15);
        // Through the hole of the annulus: a miss; further out: a hit.
        assert_eq!(annulus.nearest(&r, 0.0, INF), Reference::Miss);
        let r2 = ray([0.5, 2.0, -0.2], [0.05, -0.7, 0.1]);
        assert!(matches!(annulus.nearest(&r2, 0.0, INF), Reference::Hit { t: g, .. } if g == t));
        // Strict window at an exactly representable t = 3 (decided exactly).
        let down = ray([0.2, 2.0, 0.0], [0.0, -0.5, 0.0]);
        assert_eq!(
            disk.nearest(&down, 0.0, INF),
            Reference::Hit {
                t: 3.0,
                u: 0.2 / 0.9
            }
        );
        assert_eq!(disk.nearest(&down, 3.0, INF), Reference::Miss);
        assert_eq!(disk.nearest(&down, 0.0, 3.0), Reference::Miss);
        for (p0, p1) in [(pt(0.0, 0.5), pt(0.9, 0.5)), (pt(0.3, 0.5), pt(0.9, 0.5))] {
            for r in [r, r2, ray([1.0, -1.0, 1.0], [-0.4, 1.0, -0.3])] {
                check_segment(p0, p1, r, 0.0, INF, 2.0 * f64::EPSILON);
            }
        }
    }

    #[test]
    fn span_boundary_hit_counted_once() {
        // Degree-1 B-spline: a cone (0,0)→(1,1) on u ∈ [0, ½], a cylinder
        // (1,1)→(1,2) on [½, 1]. The ray meets the joint ring at t = 1 and
        // the cone again at t = 5/3.
        let prof = ExactProfile::from_bspline(
            1,
            &[0.0, 0.0, 0.5, 1.0, 1.0],
            &[pt(0.0, 0.0), pt(1.0, 1.0), pt(1.0, 2.0)],
        );
        let r = ray([3.0, 2.0, 0.0], [-2.0, -1.0, 0.0]);
        assert_eq!(
            prof.nearest(&r, 0.0, INF),
            Reference::Hit { t: 1.0, u: 0.5 }
        );
        let spans = prof.spans().expect("valid");
        let data = ray::RayData::new(&r, 0.0, INF).ok().expect("supported ray");
        let roots = search::all_roots(spans, &data).expect("certain");
        assert_eq!(roots.len(), 2, "{roots:?}");
        assert_eq!(roots[0], (1.0, 0.5));
        assert_eq!(roots[1].0, 5.0 / 3.0);
        assert!((roots[1].1 - 1.0 / 6.0).abs() < 1e-15);
        assert!(matches!(prof.nearest(&r, 1.0, INF), Reference::Hit { t, .. } if t == 5.0 / 3.0));
        assert_eq!(prof.nearest(&r, 0.0, 1.0), Reference::Miss);
    }

    // -- Tangents and unsupported rays -------------------------------------

    #[test]
    fn tangent_rays_are_ambiguous_or_exact() {
        // Touching x = 1 at Z = 0, t = 3, height 0: s = ½ (dyadic) on the
        // first cylinder, s = ⅓ on the second.
        let r = ray([1.0, -3.0, -3.0], [0.0, 1.0, 1.0]);
        for top in [1.0, 2.0] {
            let cyl = ExactProfile::from_bezier(&[pt(1.0, -1.0), pt(1.0, top)]);
            let got = cyl.nearest(&r, 0.0, INF);
            let ok =
                got == Reference::Ambiguous || matches!(got, Reference::Hit { t, .. } if t == 3.0);
            assert!(ok, "top {top}: {got:?}");
        }
        let dyadic = ExactProfile::from_bezier(&[pt(1.0, -1.0), pt(1.0, 1.0)]);
        assert_eq!(
            dyadic.nearest(&r, 0.0, INF),
            Reference::Hit { t: 3.0, u: 0.5 }
        );
        let third = ExactProfile::from_bezier(&[pt(1.0, -1.0), pt(1.0, 2.0)]);
        assert_eq!(third.nearest(&r, 0.0, INF), Reference::Ambiguous);
        // A tangent beyond t_max doesn't matter.
        assert_eq!(third.nearest(&r, 0.0, 2.0), Reference::Miss);
    }

    #[test]
    fn unsupported_rays_and_profiles_are_ambiguous() {
        let cyl = ExactProfile::from_bezier(&[pt(1.0, -1.0), pt(1.0, 1.0)]);
        assert_eq!(
            cyl.nearest(&ray([3.0, 0.0, 0.0], [-1.0, 0.0, 0.0]), 0.0, INF),
            Reference::Ambiguous
        );
        assert_eq!(
            cyl.nearest(&ray([3.0, 0.0, 0.0], [0.0, 0.0, 0.0]), 0.0, INF),
            Reference::Ambiguous
        );
        assert_eq!(
            cyl.nearest(&ray([f64::NAN, 0.0, 0.0], [-1.0, 0.1, 0.0]), 0.0, INF),
            Reference::Ambiguous
        );
        let good = ray([3.0, 0.0, 0.0], [-1.0, 0.1, 0.0]);
        assert_eq!(cyl.nearest(&good, f64::NAN, INF), Reference::Ambiguous);
        assert_eq!(cyl.nearest(&good, 5.0, 5.0), Reference::Miss);
        assert!(is_hit(cyl.nearest(&good, f64::NEG_INFINITY, INF)));
        let bad = [
            ExactProfile::from_bezier(&[pt(1.0, 0.0)]),
            ExactProfile::from_bezier(&[pt(1.0, 0.0), pt(f64::INFINITY, 1.0)]),
            ExactProfile::from_bspline(
                1,
                &[0.0, 1.0, 0.5, 1.0, 1.0],
                &[pt(0.0, 0.0), pt(1.0, 1.0), pt(1.0, 2.0)],
            ),
            ExactProfile::from_bspline(3, &[0.0; 7], &[pt(0.0, 0.0), pt(1.0, 1.0), pt(1.0, 2.0)]),
            ExactProfile::from_bspline(0, &[0.0, 1.0], &[pt(0.0, 0.0)]),
        ];
        for p in bad {
            assert_eq!(p.nearest(&good, 0.0, INF), Reference::Ambiguous);
        }
    }

    // -- The study's profiles --------------------------------------------

    // The study's profiles, shared with the benches and tests
    // (`revolve-testkit`): only the checks use them, not the reference.
    use crate::common::{GLASS, VASE};

    fn points(p: &[(f64, f64)]) -> Vec<Point2<f64>> {
        p.iter().map(|&(x, y)| pt(x, y)).collect()
    }

    fn glass() -> (BSpline<2>, ExactProfile) {
        let g = BSpline::uniform(3, points(&GLASS)).expect("valid glass");
        let e = ExactProfile::from_bspline(3, g.knots(), g.points());
        (g, e)
    }

    /// Random rays from a box around the shape towards points of it.
    fn random_rays(n: usize, seed: u64) -> Vec<Ray> {
        let mut rng = Rng(seed);
        (0..n)
            .map(|_| {
                let o = [
                    rng.range(-3.0, 3.0),
                    rng.range(-3.0, 3.0),
                    rng.range(-3.0, 3.0),
                ];
                let a = [
                    rng.range(-0.8, 0.8),
                    rng.range(-1.1, 1.1),
                    rng.range(-0.8, 0.8),
                ];
                ray(o, [a[0] - o[0], a[1] - o[1], a[2] - o[2]])
            })
            .collect()
    }

    #[test]
    fn glass_hits_lie_on_the_surface() {
        let (g, e) = glass();
        let mut hits = 0;
        for r in random_rays(300, 11) {
            if let Reference::Hit { t, u } = e.nearest(&r, 0.0, INF) {
                hits += 1;
                let p = r.at(t);
                let c = g.eval(u);
                assert!(
                    (p.x.hypot(p.z) - c.x.abs()).abs() < 1e-12,
                    "radius at u {u}"
                );
                assert!((p.y - c.y).abs() < 1e-12, "height at u {u}");
            }
        }
        assert!(hits > 150, "{hits} hits");
    }

    /// A profile evaluator.
    type Eval<'a> = &'a dyn Fn(f64) -> Point2<f64>;

    /// The roots `t` along the ray, sorted, found by sampling the profile's
    /// `f(u)` on a fine grid of `u` in f64 and bisecting its sign changes
    /// (it can miss a pair of roots closer than the grid step).
    fn sampled_roots(c: Eval, (lo, hi): (f64, f64), r: &Ray) -> Vec<f64> {
        let (o, d) = (r.origin, r.dir);
        let f = |u: f64| {
            let p = c(u);
            let a = o.x * d.y + (p.y - o.y) * d.x;
            let b = o.z * d.y + (p.y - o.y) * d.z;
            a * a + b * b - d.y * d.y * p.x * p.x
        };
        let n = 20000;
        let grid = |i: usize| lo + (hi - lo) * i as f64 / n as f64;
        let mut roots = Vec::new();
        for i in 0..n {
            let (mut a, mut b) = (grid(i), grid(i + 1));
            let fa = f(a);
            if fa.signum() == f(b).signum() {
                continue;
            }
            for _ in 0..80 {
                let m = 0.5 * (a + b);
                if f(m).signum() == fa.signum() {
                    a = m
                } else {
                    b = m
                }
            }
            roots.push((c(a).y - o.y) / d.y);
        }
        roots.sort_by(f64::total_cmp);
        roots
    }

    #[test]
    fn nearest_matches_a_sampled_search() {
        let (g, e) = glass();
        let vase = Bezier::new(points(&VASE)).expect("valid vase");
        let ev = ExactProfile::from_bezier(&points(&VASE));
        let shapes: [(Eval, (f64, f64), &ExactProfile); 2] = [
            (&|u| g.eval(u), g.domain(), &e),
            (&|u| vase.eval(u), (0.0, 1.0), &ev),
        ];
        for (c, dom, exact) in shapes {
            let rays = random_rays(200, 5);
            let (mut checks, mut agree) = (0, 0);
            for r in &rays {
                let roots = sampled_roots(c, dom, r);
                // Windows: all of t > 0; past the first root; before it.
                let mut windows = vec![(0.0, INF)];
                if let Some(&t0) = roots.iter().find(|&&t| t > 0.0) {
                    windows.push((t0 + 1e-6, INF));
                    windows.push((0.0, t0 - 1e-6));
                    windows.push((-INF, t0 + 1e-6));
                    windows.push((0.5 * t0, t0 + 1e-6));
                }
                for (lo, hi) in windows {
                    let got = exact.nearest(r, lo, hi);
                    let want = roots.iter().copied().find(|&t| lo < t && t < hi);
                    checks += 1;
                    agree += usize::from(match (got, want) {
                        (Reference::Hit { t, .. }, Some(w)) => {
                            (t - w).abs() < 1e-9 * (1.0 + w.abs())
                        }
                        (Reference::Miss, None) => true,
                        _ => false,
                    });
                    // A root the sampling sees is a root: the reference can't
                    // be later, nor miss.
                    match (got, want) {
                        (Reference::Hit { t, .. }, Some(w)) => {
                            assert!(
                                t <= w + 1e-9 * (1.0 + w.abs()),
                                "reference {t} after sampled root {w}"
                            )
                        }
                        (Reference::Miss, Some(w)) => {
                            panic!("reference missed the sampled root {w} of {r:?}")
                        }
                        _ => {}
                    }
                }
            }
            assert!(
                checks > 500 && agree + 4 >= checks,
                "{agree} of {checks} agree"
            );
        }
    }

    #[test]
    fn exact_spans_match_bspline_eval() {
        let (g, e) = glass();
        let nonuniform = BSpline::new(
            2,
            vec![0.0, 0.0, 0.0, 0.3, 0.3, 0.7, 1.0, 1.0, 1.0],
            points(&[
                (0.1, 0.0),
                (0.5, 0.2),
                (0.3, 0.6),
                (0.9, 0.7),
                (0.4, 1.0),
                (0.2, 1.3),
            ]),
        )
        .expect("valid");
        let ne = ExactProfile::from_bspline(2, nonuniform.knots(), nonuniform.points());
        for (curve, exact, count) in [(&g, &e, 22), (&nonuniform, &ne, 3)] {
            let spans = exact.spans().expect("valid");
            assert_eq!(spans.len(), count);
            for w in spans.windows(2) {
                assert!(w[0].joins(&w[1]), "consecutive spans share their end point");
            }
            for span in spans {
                for s in [0.0, 0.125, 1.0 / 3.0, 0.5, 0.9, 1.0] {
                    let (x, y) = span.eval(&q(s));
                    let u = span.a.add(&span.b.sub(&span.a).mul(&Frac::from_f64(s)));
                    let u = u.to_f64();
                    let c = curve.eval(u);
                    let to = |v: &Q| Frac::new(v.numer().clone(), v.denom().clone()).to_f64();
                    assert!(
                        (to(&x) - c.x).abs() < 1e-14 && (to(&y) - c.y).abs() < 1e-14,
                        "u {u}"
                    );
                }
            }
        }
        // The Bézier profile's one span is the curve itself.
        let ev = ExactProfile::from_bezier(&points(&VASE));
        let span = &ev.spans().expect("valid")[0];
        assert_eq!(span.eval(&q(0.0)), (q(0.6), q(-1.0)));
        let three = Q::from_integer(BigInt::from(3));
        let mid = (q(0.6) + &three * q(1.6) + &three * q(-0.2) + q(0.5))
            / Q::from_integer(BigInt::from(8));
        assert_eq!(span.eval(&q(0.5)).0, mid);
    }
}

#[cfg(test)]
mod interval_tests {
    use crate::common::interval::{Interval, down, up};

    #[test]
    fn operations_enclose_the_exact_results() {
        // 0.1 + 0.2 is not 0.3 in binary; the exact sum of the two doubles
        // lies strictly inside the rounded-outward interval.
        let s = Interval::point(0.1).add(Interval::point(0.2));
        assert!(s.lo < 0.1 + 0.2 && 0.1 + 0.2 < s.hi);
        assert!(s.hi - s.lo <= 4.0 * f64::EPSILON);
        let p = Interval { lo: -2.0, hi: 3.0 }.mul(Interval { lo: -5.0, hi: 1.0 });
        assert!(p.lo <= -15.0 && p.hi >= 10.0 && p.lo > -15.0 - 1e-13);
        let q = Interval { lo: 1.0, hi: 2.0 }.div_point(-4.0);
        assert!(q.lo <= -0.5 && q.hi >= -0.25);
        assert_eq!(up(0.0), f64::from_bits(1));
        assert_eq!(down(0.0), -f64::from_bits(1));
        assert_eq!(up(-1.0), -1.0 + f64::EPSILON / 2.0);
        assert_eq!(down(1.0), 1.0 - f64::EPSILON / 2.0);
        let l = Interval::lerp(Interval::point(1.0), Interval::point(3.0), 0.25);
        assert!(l.lo <= 1.5 && 1.5 <= l.hi);
        assert!(
            Interval {
                lo: 1e-300,
                hi: 1.0
            }
            .positive()
        );
        assert!(!Interval { lo: 0.0, hi: 1.0 }.positive());
    }
}
