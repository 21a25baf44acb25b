//! The finish of the patch search: Newton's method on the ray's two plane
//! distances from a box, and the test that its point is a hit.

use super::patch::{Patch, PatchHit, first_jet, tensor_jet};
use crate::curve::{Homogeneous, power_of_two_near, scaled_norm};
use crate::ray::acceptance::Acceptance;
use crate::{Ray, Tolerance};
use nalgebra::Vector3;

/// How far outside its patch (in the patch's parameters) Newton may land and
/// still count: rounding only.
pub(super) const SLACK: f64 = 1e-9;

/// The ray in the frame the search uses, and the Newton settings.
pub(super) struct Frame {
    pub(super) o: Vector3<f64>,
    pub(super) dn: f64,
    pub(super) e1: Vector3<f64>,
    pub(super) e2: Vector3<f64>,
    pub(super) dh: Vector3<f64>,
    /// The residual within which a hit is accepted.
    pub(super) acceptance: Acceptance,
    pub(super) target: f64,
    pub(super) iterations: u32,
    /// Hits at or below this ray parameter are the origin's own.
    pub(super) t_floor: f64,
    /// The ray parameter searched from.
    pub(super) t_min: f64,
    /// Largest control-point coordinate of the surface.
    pub(super) scale: f64,
    /// The inverse of a power of two near `scale` (within the range of
    /// `f64`): Newton's quantities are taken in units of that power.
    pub(super) per_unit: f64,
}

impl Frame {
    /// The frame of `ray` searched from `t_min` on a surface of largest
    /// control-point coordinate `scale`, at the tolerance `tol`; `None`
    /// for a ray whose origin or direction is not finite or whose
    /// direction is zero.
    pub(super) fn new(ray: &Ray, t_min: f64, scale: f64, tol: &Tolerance) -> Option<Frame> {
        let tol = tol.clamped();
        let (o, d) = (ray.origin.coords, ray.dir);
        let m = d.amax();
        let usable = m > 0.0 && m.is_finite() && o.iter().all(|c| c.is_finite());
        if !usable {
            return None;
        }
        let dn = m * (d / m).norm();
        let dh = d / dn;
        // Two unit normals of planes through the ray.
        let helper = if dh.x.abs() <= dh.y.abs() && dh.x.abs() <= dh.z.abs() {
            Vector3::x()
        } else if dh.y.abs() <= dh.z.abs() {
            Vector3::y()
        } else {
            Vector3::z()
        };
        let e1 = dh.cross(&helper).normalize();
        let e2 = dh.cross(&e1);
        let scale = scale.max(f64::MIN_POSITIVE);
        let acceptance = Acceptance::certified(&tol, scale, &o);
        Some(Frame {
            o,
            dn,
            e1,
            e2,
            dh,
            acceptance,
            // Every hit is polished to full precision, whatever the tolerance.
            target: Tolerance::default().relative * scale,
            iterations: tol.max_iterations,
            // Hits within the position uncertainty of the origin are the
            // origin's.
            t_floor: acceptance.t_floor(t_min, dn),
            t_min,
            scale,
            per_unit: 1.0 / power_of_two_near(scale.clamp(1e-300, 1e300)),
        })
    }
}

/// Newton's method on `(e₁·(S − o), e₂·(S − o)) = 0` over `patch` (number
/// `k`, with `cols` control points a row) from the
/// centre of the box `bs × bt` (then its corners); the hit if a start converges to a
/// point of the patch within the acceptance (else the first start that
/// stopped within the acceptance without converging).
pub(super) fn polish(
    patch: &Patch,
    k: usize,
    cols: usize,
    f: &Frame,
    (bs, bt): ((f64, f64), (f64, f64)),
) -> Option<PatchHit> {
    let starts = [
        (0.5 * (bs.0 + bs.1), 0.5 * (bt.0 + bt.1)),
        (bs.0, bt.0),
        (bs.1, bt.1),
        (bs.0, bt.1),
        (bs.1, bt.0),
    ];
    let mut fallback = None;
    for (s0, t0) in starts {
        let (mut s, mut t) = (s0, t0);
        // The jet at the last point evaluated, if Newton stopped there.
        let mut last = None;
        let mut previous = f64::INFINITY;
        let mut rising = 0;
        let mut converged = false;
        for _ in 0..f.iterations.max(8) {
            let (sc, tc) = (s.clamp(-0.5, 1.5), t.clamp(-0.5, 1.5));
            let jet = jet(patch, cols, sc, tc);
            let [h, hs, ht] = jet;
            let x = h.wp / h.w;
            let xs = (hs.wp - x * hs.w) / h.w;
            let xt = (ht.wp - x * ht.w) / h.w;
            let r = x - f.o;
            // In units of a power of two near the surface's scale (exact),
            // so that the residual and the determinant neither underflow on
            // tiny surfaces nor overflow on huge ones.
            let k = f.per_unit;
            let (fa, fb) = (f.e1.dot(&r) * k, f.e2.dot(&r) * k);
            let (j00, j01, j10, j11) = (
                f.e1.dot(&xs) * k,
                f.e1.dot(&xt) * k,
                f.e2.dot(&xs) * k,
                f.e2.dot(&xt) * k,
            );
            let det = j00 * j11 - j01 * j10;
            let residual = fa.hypot(fb);
            if residual <= f.target * k || det == 0.0 || !det.is_finite() {
                converged = residual <= f.target;
                last = Some((sc, tc, jet));
                break;
            }
            // Clamped to the domain's margin, or rising twice running:
            // this start is not converging.
            rising = if residual >= previous { rising + 1 } else { 0 };
            if (sc, tc) != (s, t) || rising >= 2 {
                break;
            }
            previous = residual;
            let ds = (fa * j11 - fb * j01) / det;
            let dt = (fb * j00 - fa * j10) / det;
            s -= ds;
            t -= dt;
            if !(s.is_finite() && t.is_finite()) || (ds.abs() < 1e-17 && dt.abs() < 1e-17) {
                break;
            }
        }
        // Past the sides by more than rounding: another piece's root,
        // unless Newton converged there and the side's point is within the
        // acceptance too (at a pole, where a side is one point, or a root
        // just inside the neighbouring piece): then kept as past the side.
        let within = |x: f64| (-SLACK..=1.0 + SLACK).contains(&x);
        if !(converged || (within(s) && within(t))) {
            continue;
        }
        let past_side = !((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t));
        let (s, t) = (s.clamp(0.0, 1.0), t.clamp(0.0, 1.0));
        let jet = match last {
            Some((sc, tc, jet)) if (sc, tc) == (s, t) => jet,
            _ => jet(patch, cols, s, t),
        };
        if let Some(hit) = accept(patch, k, f, s, t, &jet) {
            let hit = PatchHit { past_side, ..hit };
            // A start that converged is at full precision; one that stopped
            // within the acceptance (a singular Jacobian, as at a pole) is
            // kept in case no other start converges.
            if converged {
                return Some(hit);
            }
            // Marked as unfinished, as a hit past the side is: the pieces
            // beside it are polished for the converged root.
            fallback = fallback.or(Some(PatchHit {
                past_side: true,
                ..hit
            }));
        }
    }
    fallback
}

/// The hit at `(s, t)` of `patch` (number `k`), from the jet there, if the
/// surface point is within the acceptance of the ray and is not the ray's
/// own origin.
pub(super) fn accept(
    patch: &Patch,
    k: usize,
    f: &Frame,
    s: f64,
    t: f64,
    &[h, hs, ht]: &[Homogeneous<3>; 3],
) -> Option<PatchHit> {
    let x = h.wp / h.w;
    let r = x - f.o;
    let along = f.dh.dot(&r);
    // Scaled before squaring: a tiny surface's distances would underflow.
    let off = scaled_norm(r - f.dh * along);
    // The point is uncertain by `accept` off the surface, so its ray
    // parameter by `accept/(|d|·cos)` for the angle of incidence: a
    // root that close to `t_min` is the ray's own start (a secondary
    // ray's origin on the surface), however grazing.
    let normal = ((hs.wp - x * hs.w) / h.w).cross(&((ht.wp - x * ht.w) / h.w));
    let cos = (f.dh.dot(&normal).abs() / normal.norm()).clamp(1e-6, 1.0);
    let own = along / f.dn - f.t_min
        <= f.acceptance.distance / (f.dn * if cos.is_nan() { 1.0 } else { cos });
    (f.acceptance.accepts(off) && !own).then(|| PatchHit {
        patch: k,
        t: along / f.dn,
        u: patch.u.0 + (patch.u.1 - patch.u.0) * s,
        v: patch.v.0 + (patch.v.1 - patch.v.0) * t,
        st: (s, t),
        past_side: false,
    })
}

/// `(A, ∂A/∂s, ∂A/∂t)` of `patch` at `(s, t)`: by the Bernstein bases, or
/// by de Casteljau at degrees they do not take.
#[inline]
pub(super) fn jet(patch: &Patch, cols: usize, s: f64, t: f64) -> [Homogeneous<3>; 3] {
    first_jet(&patch.net, cols, s, t).unwrap_or_else(|| {
        let jet = tensor_jet(&patch.net, cols, s, t, 1);
        [jet[0][0], jet[1][0], jet[0][1]]
    })
}
