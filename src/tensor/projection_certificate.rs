//! A search piece settled by Newton's method alone, when the ray sees it as
//! one sheet: the certificate that a polynomial piece's projection along the
//! ray is one-to-one, and the bound that places the one root Newton finds.
//!
//! Let `G(x) = (e₁·(S(x) − o), e₂·(S(x) − o))` be the ray's two plane
//! distances on a piece, `x = (s, t)`, over a widened domain
//! `D = [−W, 1 + W]²` of the piece's parameters. For `x, y ∈ D` the mean
//! value theorem gives `G(y) − G(x) = J̄·(y − x)`, `J̄ = [P·m_s, P·m_t]`,
//! where `P` projects along the ray and `m_s`, `m_t` are averages of
//! `∂S/∂s`, `∂S/∂t` over the segment, so lie in the boxes `B_s`, `B_t`
//! that hold those derivatives on `D` (the hulls of the derivative nets).
//! `det J̄ = (m_s × m_t)·d̂`, and `m_s × m_t` lies in the interval cross
//! product `N = B_s × B_t`, built once per piece. So when `N·d̂` (an
//! interval) excludes zero:
//!
//! - `G` is one-to-one on `D`: the line meets the piece's widening at most
//!   once, whatever the curvature;
//! - every root `y ∈ D` lies within `|J̄⁻¹·G(x)|` of any `x ∈ D`, which is
//!   at most `|adj J̄|·|G(x)| / min|det J̄|`, bounded from the boxes.
//!
//! Newton's method from the piece's centre then ends at a point `x*` with a
//! residual near rounding, and the root (if any in `D`) is within a box of
//! tiny radius around `x*`. If that box lies inside the piece, `x*` is the
//! piece's one root (tested for acceptance like every hit); if it lies
//! outside the piece, the piece holds no root. Anything else (the test
//! fails, as for rays grazing the piece or pieces at a collapsed edge;
//! Newton leaves `D` or stalls; the box straddles the piece's side) is left
//! to the clipping search. Only polynomial pieces get a certificate (the
//! derivative hull of a rational piece is not its control net's).
//!
//! The boxes are kept in a frame of the piece (two tangents and the
//! normal at its centre), where they are tight, and widened for the
//! rounding of their construction.

use super::newton_polish::{Frame, accept, jet};
use super::patch::{Patch, PatchHit, polynomial_jet};
use crate::curve::Homogeneous;
use nalgebra::Vector3;

/// How far the certified domain reaches past the piece on each side, in
/// the piece's parameters: Newton may converge there on a ray that passes
/// the piece by, which then proves the piece holds no root.
const WIDEN: f64 = 0.125;

/// Newton steps before the piece is left to the clipping search.
const STEPS: usize = 12;

/// What Newton's method under the certificate made of a piece.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Settled {
    /// The piece's one root, accepted as a hit.
    Hit(PatchHit),
    /// The piece holds no hit the ray could take.
    Nothing,
    /// Not settled: the clipping search decides.
    Unknown,
}

/// The projection certificate of one polynomial piece.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ProjectionCertificate {
    /// The unit normal at the piece's centre: the axis of the cone.
    normal: Vector3<f64>,
    /// The least component along `normal` of the products `h_s × h_t` of
    /// the derivative nets' points (positive, or there is no certificate).
    along: f64,
    /// The largest part of those products across `normal`.
    across: f64,
    /// The largest `|∂S/∂s|` and `|∂S/∂t|` over the widened domain (the
    /// largest derivative net point).
    largest: (f64, f64),
    /// `S`, `∂S/∂s` and `∂S/∂t` at the centre, where Newton's method starts.
    centre: [Vector3<f64>; 3],
    /// The box of the piece's own net in the frame (tangent, cotangent,
    /// normal): rows of the frame and each axis's range.
    frame: [Vector3<f64>; 2],
    ranges: [(f64, f64); 3],
}

impl ProjectionCertificate {
    /// The certificate of `piece` (degrees `(p, q)`), or `None` for a
    /// rational piece, one whose centre has no tangent plane, one whose
    /// products leave the cone's half-space, or one whose numbers are not
    /// finite.
    pub(crate) fn new(piece: &Patch, (p, q): (usize, usize)) -> Option<Self> {
        let fits = (1..SIDE).contains(&p) && (1..SIDE).contains(&q);
        if !fits || piece.net.iter().any(|h| h.w != 1.0) {
            return None;
        }
        let cols = q + 1;
        let centre = jet(piece, cols, 0.5, 0.5).map(|h| h.wp);
        let normal = centre[1].cross(&centre[2]).try_normalize(0.0)?;
        let tangent = (centre[1] - normal * normal.dot(&centre[1])).try_normalize(0.0)?;
        let cotangent = normal.cross(&tangent);
        let mut ranges = [(f64::INFINITY, f64::NEG_INFINITY); 3];
        let mut size = 0.0_f64;
        for h in &piece.net {
            for (r, axis) in ranges.iter_mut().zip([tangent, cotangent, normal]) {
                let x = axis.dot(&h.wp);
                *r = (r.0.min(x), r.1.max(x));
            }
            size = size.max(h.wp.amax());
        }
        // The projections' rounding.
        let ranges = ranges.map(|(lo, hi)| (lo - 1e-14 * size, hi + 1e-14 * size));
        // The derivative nets over the widened domain, in the piece's own
        // parameters (the widened domain is `1 + 2W` times as long).
        let net = widened(piece, (p, q));
        let at = |i: usize, j: usize| net[i * cols + j];
        let per_s = p as f64 / (1.0 + 2.0 * WIDEN);
        let per_t = q as f64 / (1.0 + 2.0 * WIDEN);
        // The derivative nets' points, kept in the frame (tangent,
        // cotangent, normal), where the normal part of a product is its
        // last coordinate; and their largest lengths.
        let in_frame = |x: &Vector3<f64>| [tangent.dot(x), cotangent.dot(x), normal.dot(x)];
        let (mut hs, mut ht) = ([[0.0; 3]; SIDE * SIDE], [[0.0; 3]; SIDE * SIDE]);
        let (mut ns, mut nt) = (0, 0);
        let (mut long_s, mut long_t) = (0.0_f64, 0.0_f64);
        let mut finite = true;
        for i in 0..=p {
            for j in 0..=q {
                if i < p {
                    let h = (at(i + 1, j) - at(i, j)) * per_s;
                    finite &= h.iter().all(|c| c.is_finite());
                    long_s = long_s.max(h.norm());
                    hs[ns] = in_frame(&h);
                    ns += 1;
                }
                if j < q {
                    let h = (at(i, j + 1) - at(i, j)) * per_t;
                    finite &= h.iter().all(|c| c.is_finite());
                    long_t = long_t.max(h.norm());
                    ht[nt] = in_frame(&h);
                    nt += 1;
                }
            }
        }
        if !finite {
            return None;
        }
        // The cone of the products: their least component along the
        // normal and their largest part across it.
        let mut along = f64::INFINITY;
        let mut across = 0.0_f64;
        for a in &hs[..ns] {
            for b in &ht[..nt] {
                let cx = a[1] * b[2] - a[2] * b[1];
                let cy = a[2] * b[0] - a[0] * b[2];
                let cz = a[0] * b[1] - a[1] * b[0];
                // Plain comparisons (the nets are finite, checked above).
                let squared = cx * cx + cy * cy;
                along = if cz < along { cz } else { along };
                across = if squared > across { squared } else { across };
            }
        }
        let across = across.sqrt();
        // Rounding of the widened nets (extrapolating de Casteljau), of the
        // differences and of the products: generous, relative to their size.
        let magnitude = net.iter().fold(0.0_f64, |m, x| m.max(x.amax()));
        let pad = 1e-11 * magnitude * per_s.max(per_t);
        // A product a × b moves by |δa||b| + |a||δb| + |δa||δb| for errors
        // δ ≤ pad in its factors, and by its own rounding.
        let fuzz = 2.0 * pad * (long_s + long_t + pad) + 1e-12 * long_s * long_t;
        let certificate = ProjectionCertificate {
            normal,
            along: along - fuzz,
            across: across + fuzz,
            largest: (long_s + pad, long_t + pad),
            centre,
            frame: [tangent, cotangent],
            ranges,
        };
        let finite = certificate.across.is_finite()
            && certificate.largest.0.is_finite()
            && certificate.largest.1.is_finite()
            && centre.iter().all(|x| x.iter().all(|c| c.is_finite()));
        (finite && certificate.along > 0.0).then_some(certificate)
    }

    /// Whether the products' cone is wider than 45° about the normal
    /// (rays more than 45° off the normal may then fail the cone test).
    pub(crate) fn cone_is_wide(&self) -> bool {
        self.across >= self.along
    }

    /// Settles `piece` (number `k`, `cols` control points a row) for the
    /// ray of `f`, hits in `(f.t_floor, t_best)`: see the module docs.
    pub(super) fn settle(
        &self,
        piece: &Patch,
        k: usize,
        cols: usize,
        f: &Frame,
        t_best: f64,
    ) -> Settled {
        // The ray against the piece's box in its frame: a miss is no root.
        let pad = f.acceptance.distance;
        let (mut enter, mut exit) = (f.t_floor * f.dn - pad, t_best * f.dn + pad);
        for (axis, range) in [self.frame[0], self.frame[1], self.normal]
            .iter()
            .zip(&self.ranges)
        {
            let (o, d) = (axis.dot(&f.o), axis.dot(&f.dh));
            let (lo, hi) = (range.0 - pad - o, range.1 + pad - o);
            if d == 0.0 {
                // Parallel to the side: inside the slab or a miss.
                if lo > 0.0 || hi < 0.0 {
                    return Settled::Nothing;
                }
                continue;
            }
            let (a, b) = (lo / d, hi / d);
            enter = enter.max(a.min(b));
            exit = exit.min(a.max(b));
        }
        if enter > exit {
            return Settled::Nothing;
        }
        // |det J̄| ≥ along·|d_n| − across·|d_⊥|: the products' hull, which
        // holds m_s × m_t, lies in the cone; less the rounding of this.
        let d_n = self.normal.dot(&f.dh);
        let d_across = self.normal.cross(&f.dh).norm();
        let least_det =
            self.along * d_n.abs() - self.across * d_across - 1e-12 * (self.along + self.across);
        if least_det.is_nan() || least_det <= 0.0 {
            return Settled::Unknown;
        }
        // Newton's method from the centre, within the widened domain.
        let (mut s, mut t) = (0.5, 0.5);
        let [mut x, mut xs, mut xt] = self.centre;
        let mut converged = false;
        let (mut fa, mut fb) = (f64::INFINITY, f64::INFINITY);
        // Newton stops at the target or at the rounding of the plane
        // distances themselves, whichever is larger.
        let floor = f.target.max(4.0 * f64::EPSILON * (f.o.amax() + f.scale));
        for _ in 0..STEPS {
            let r = x - f.o;
            (fa, fb) = (f.e1.dot(&r), f.e2.dot(&r));
            if fa * fa + fb * fb <= floor * floor {
                converged = true;
                break;
            }
            let (j00, j01, j10, j11) = (f.e1.dot(&xs), f.e1.dot(&xt), f.e2.dot(&xs), f.e2.dot(&xt));
            let det = j00 * j11 - j01 * j10;
            if det == 0.0 || !det.is_finite() {
                return Settled::Unknown;
            }
            let step_s = (fa * j11 - fb * j01) / det;
            let step_t = (fb * j00 - fa * j10) / det;
            s -= step_s;
            t -= step_t;
            let inside = (-WIDEN..=1.0 + WIDEN).contains(&s) && (-WIDEN..=1.0 + WIDEN).contains(&t);
            if !inside {
                return Settled::Unknown;
            }
            let Some(at) = polynomial_jet(&piece.net, cols, s, t) else {
                return Settled::Unknown;
            };
            [x, xs, xt] = at;
            if step_s.abs() <= 1e-15 && step_t.abs() <= 1e-15 {
                let r = x - f.o;
                (fa, fb) = (f.e1.dot(&r), f.e2.dot(&r));
                converged = true;
                break;
            }
        }
        if !converged {
            return Settled::Unknown;
        }
        // Where the root can be: |y − x*| ≤ |adj J̄|·|G(x*)| / min|det J̄|,
        // with G's rounding (evaluation and the plane distances).
        let noise = 64.0 * f64::EPSILON * (f.o.amax() + f.scale);
        let g = (fa.abs() + fb.abs() + 2.0 * noise) / least_det * (1.0 + 1e-9);
        let (reach_s, reach_t) = (self.largest.1 * g, self.largest.0 * g);
        if !(reach_s.is_finite() && reach_t.is_finite()) {
            return Settled::Unknown;
        }
        let within = |x: f64, r: f64| x - r >= 0.0 && x + r <= 1.0;
        let apart = |x: f64, r: f64| x + r < 0.0 || x - r > 1.0;
        if apart(s, reach_s) || apart(t, reach_t) {
            return Settled::Nothing;
        }
        if !(within(s, reach_s) && within(t, reach_t)) {
            return Settled::Unknown;
        }
        let at_root = [
            Homogeneous { wp: x, w: 1.0 },
            Homogeneous { wp: xs, w: 0.0 },
            Homogeneous { wp: xt, w: 0.0 },
        ];
        match accept(piece, k, f, s, t, &at_root) {
            Some(hit) if hit.t > f.t_floor && hit.t < t_best => Settled::Hit(hit),
            _ => Settled::Nothing,
        }
    }
}

/// Points per side of a net that gets a certificate (degree 7).
const SIDE: usize = 8;

/// A net of at most `SIDE × SIDE` points, row-major, on the stack.
type Net = [Vector3<f64>; SIDE * SIDE];

/// The points of `piece`'s net (unit weights, at most [`SIDE`] a side)
/// reparametrised to the widened domain `[−W, 1 + W]²`: each column and
/// then each row restricted by two de Casteljau passes at parameters
/// outside `[0, 1]` (extrapolation): to `[0, 1 + W]`, then to its part
/// from `−W`.
fn widened(piece: &Patch, (p, q): (usize, usize)) -> Net {
    let cols = q + 1;
    let mut net: Net = [Vector3::zeros(); SIDE * SIDE];
    for (x, h) in net.iter_mut().zip(&piece.net) {
        *x = h.wp;
    }
    let widen = |line: &mut [Vector3<f64>; SIDE], n: usize| {
        for (b, t) in [(1.0 + WIDEN, false), (-WIDEN / (1.0 + WIDEN), true)] {
            // de Casteljau at b: the left part's points are the first of
            // each level, the right part's the last.
            let mut work = *line;
            for level in 0..n {
                if t {
                    line[n - 1 - level] = work[n - 1 - level];
                } else {
                    line[level] = work[0];
                }
                for k in 0..n - 1 - level {
                    work[k] = work[k] + (work[k + 1] - work[k]) * b;
                }
            }
        }
    };
    let mut line = [Vector3::zeros(); SIDE];
    for j in 0..cols {
        for i in 0..=p {
            line[i] = net[i * cols + j];
        }
        widen(&mut line, p + 1);
        for i in 0..=p {
            net[i * cols + j] = line[i];
        }
    }
    for i in 0..=p {
        line[..cols].copy_from_slice(&net[i * cols..(i + 1) * cols]);
        widen(&mut line, cols);
        net[i * cols..(i + 1) * cols].copy_from_slice(&line[..cols]);
    }
    net
}

#[cfg(test)]
mod tests {
    use super::super::newton_polish::Frame;
    use super::super::patch::Patch;
    use super::super::search::clip_search;
    use super::super::search_pieces::SearchPieces;
    use super::{ProjectionCertificate, Settled};
    use crate::curve::Homogeneous;
    use crate::{Ray, Tolerance};
    use nalgebra::{Point3, Vector3};

    /// A bicubic height field `z = bend·(sin 3x + x·cos 2y)` on the unit
    /// square; with `weight`, its control points get unequal weights.
    fn wavy(bend: f64, weight: bool) -> Patch {
        let mut net = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                let (x, y) = (i as f64 / 3.0, j as f64 / 3.0);
                let z = bend * ((3.0 * x).sin() + (2.0 * y).cos() * x);
                let w = if weight {
                    1.0 + 0.25 * ((i + j) % 2) as f64
                } else {
                    1.0
                };
                net.push(Homogeneous::new(&Point3::new(x, y, z), w));
            }
        }
        Patch {
            u: (0.0, 1.0),
            v: (0.0, 1.0),
            net,
        }
    }

    /// Every verdict of the certificate agrees with Bézier clipping (a
    /// second algorithm, run on the same piece): a hit is clipping's hit
    /// (the same root, to rounding), "nothing" is no hit for clipping. Rays
    /// from all sides, aimed at points on and around the patch; and the
    /// certificate settles most of the pieces the rays hit, so the clipping
    /// search is the exception.
    #[test]
    fn verdicts_agree_with_clipping_and_settle_most_hits() {
        for bend in [0.6, 2.5] {
            agree_with_clipping(bend);
        }
    }

    /// The check of [`verdicts_agree_with_clipping_and_settle_most_hits`]
    /// on the patch `wavy(bend)`.
    fn agree_with_clipping(bend: f64) {
        let patch = wavy(bend, false);
        let pieces = SearchPieces::new(std::slice::from_ref(&patch), (3, 3));
        let set = pieces.set();
        let tol = Tolerance::default();
        let mut buf = [[0.0; 4]; 48];
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || crate::test_unit::unit(&mut state);
        let (mut hits, mut settled_hits, mut unknown) = (0, 0, 0);
        for _ in 0..3000 {
            let aim = Point3::new(
                1.2 * next() - 0.1,
                1.2 * next() - 0.1,
                bend * (2.0 * next() - 0.5),
            );
            let (a, b) = (std::f64::consts::TAU * next(), 2.0 * next() - 1.0);
            let r = (1.0 - b * b).sqrt();
            let dir = Vector3::new(r * a.cos(), r * a.sin(), b);
            let ray = Ray::new(aim - dir * 3.0, dir);
            let frame = Frame::new(&ray, 0.0, set.scale, &tol).unwrap();
            for (k, piece) in set.patches.iter().enumerate() {
                let certificate = set.certificates[k].as_ref().expect("polynomial pieces");
                let verdict = certificate.settle(piece, k, 4, &frame, f64::INFINITY);
                let clipped = clip_search(set, k, &frame, &mut buf, f64::INFINITY);
                hits += usize::from(clipped.is_some());
                match (verdict, clipped) {
                    (Settled::Hit(a), Some(b)) => {
                        settled_hits += 1;
                        assert!((a.t - b.t).abs() <= 1e-12, "{ray:?} piece {k}: {a:?} {b:?}");
                        assert!((a.u - b.u).abs() + (a.v - b.v).abs() <= 1e-9, "{a:?} {b:?}");
                    }
                    (Settled::Nothing, None) => {}
                    (Settled::Unknown, _) => unknown += 1,
                    (verdict, clipped) => {
                        panic!("{ray:?} piece {k}: certificate {verdict:?}, clipping {clipped:?}")
                    }
                }
            }
        }
        assert!(hits > 1000, "only {hits} hits");
        assert!(
            settled_hits * 10 >= hits * 8,
            "{settled_hits} of {hits} hits settled ({unknown} pieces unknown)"
        );
    }

    /// A ray grazing a piece (in its tangent plane) is not settled: the
    /// projection along it is not one-to-one.
    #[test]
    fn a_grazing_ray_is_left_to_clipping() {
        let patch = wavy(0.0, false);
        let certificate = ProjectionCertificate::new(&patch, (3, 3)).unwrap();
        let ray = Ray::new(Point3::new(-1.0, 0.5, 0.0), Vector3::new(1.0, 0.1, 0.0));
        let frame = Frame::new(&ray, 0.0, 1.0, &Tolerance::default()).unwrap();
        let verdict = certificate.settle(&patch, 0, 4, &frame, f64::INFINITY);
        assert_eq!(verdict, Settled::Unknown);
        // Tilted by a degree, it crosses the flat patch once: settled.
        let ray = Ray::new(
            Point3::new(-0.5, 0.5, 0.01745),
            Vector3::new(1.0, 0.0, -0.01745),
        );
        let frame = Frame::new(&ray, 0.0, 1.0, &Tolerance::default()).unwrap();
        match certificate.settle(&patch, 0, 4, &frame, f64::INFINITY) {
            Settled::Hit(hit) => assert!((ray.at(hit.t).z).abs() < 1e-12, "{hit:?}"),
            other => panic!("{other:?}"),
        }
    }

    /// Rational pieces, and pieces whose centre has no tangent plane (a
    /// patch collapsed to a curve), get no certificate.
    #[test]
    fn rational_and_degenerate_pieces_have_no_certificate() {
        assert!(ProjectionCertificate::new(&wavy(0.6, true), (3, 3)).is_none());
        let mut line = wavy(0.0, false);
        for h in &mut line.net {
            h.wp.y = 0.0;
        }
        assert!(ProjectionCertificate::new(&line, (3, 3)).is_none());
        assert!(ProjectionCertificate::new(&wavy(0.6, false), (3, 3)).is_some());
    }
}
