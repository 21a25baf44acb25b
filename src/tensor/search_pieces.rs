//! The ray–patch search's leaves: the patches cut into pieces once, when the
//! surface is built, so that a ray does not cut them again.
//!
//! Bézier clipping ([`crate::ray::patch`]) converges fast on a nearly
//! bilinear piece and spends its first steps, on a strongly curved patch,
//! halving boxes that every ray halves the same way. So every patch is cut
//! at the middle of `u` and of `v` (de Casteljau at ½, in homogeneous
//! form), [`depth`](SearchPieces::depth) times, and the hierarchy is built
//! over the pieces; each piece keeps the parameter rectangle it covers, so
//! hits come out in the surface's own parameters.
//!
//! The depth is one for the whole surface: the least, up to
//! [`MAX_CUTS`], at which every piece is flat, its control net within
//! [`FLATNESS`] of its size from the bilinear interpolation of its
//! corners (cuts beyond the second only while the pieces stay within
//! [`PIECE_BUDGET`], the fourth only for pieces poorly served by their
//! projection certificates). One depth for all keeps neighbouring pieces' common edges
//! identical: a cut at ½ gives the two halves the same middle control
//! points, and de Casteljau at ½ gives an edge the same points whichever
//! way it runs (`a·½ + b·½` is symmetric), so patches that share an edge's
//! control points (as the teapot's do) still share them, bit for bit, after
//! cutting. Pieces are mathematically the patch restricted to a rectangle;
//! their control points carry the rounding of a few halvings and additions.

use super::patch::Patch;
use super::patch::rounding_pad;
use super::projection_certificate::ProjectionCertificate;
use super::search::PatchSet;
use crate::Aabb;
use crate::bernstein::subdivide;
use crate::curve::Homogeneous;
use crate::ray::bvh::Bvh;
use crate::ray::wide_bvh::WideBvh;

/// The most times a patch is cut in each direction (up to `4^MAX_CUTS`
/// pieces per patch).
pub(crate) const MAX_CUTS: usize = 4;
// A piece's cell index `(i, j) < 2^MAX_CUTS` is kept in a byte.
const _: () = assert!(MAX_CUTS <= 8);

/// Cuts beyond the second are made only while the surface keeps at most
/// this many pieces (the teapot's 32 patches stop at three cuts, a single
/// patch may take four; the fourth only where a piece's projection
/// certificate is missing or holds within 45° of its normal alone: the
/// benches' folded patch takes it, their gentle one does not).
pub(crate) const PIECE_BUDGET: usize = 2048;

/// A piece is flat when no control point lies farther than this fraction
/// of the piece's box diagonal from the bilinear interpolation of its four
/// corners. Flat enough that the projection certificate
/// ([`ProjectionCertificate`]) holds for most rays (the teapot is cut three
/// times: 2048 pieces; at 0.02 it was cut twice, and a random ray cost a
/// quarter more instructions with the certificates; the folded patch of
/// the benches is cut four times: a fourth cut took a third off its rays'
/// instructions).
pub(crate) const FLATNESS: f64 = 0.005;

/// The patches of a surface cut into pieces for the ray search, with the
/// hierarchy over the pieces.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SearchPieces {
    /// Degrees `(p, q)` of every piece.
    degrees: (usize, usize),
    pieces: Vec<Patch>,
    /// The index of the patch each piece was cut from.
    owners: Vec<u32>,
    /// How many times every patch was cut in each direction.
    depth: usize,
    /// Each piece's cell `(i, j)` in its patch: the rectangle
    /// `[i, i + 1]·2⁻ᵈᵉᵖᵗʰ × [j, j + 1]·2⁻ᵈᵉᵖᵗʰ` of the patch's `[0, 1]²`.
    cells: Vec<(u8, u8)>,
    tree: WideBvh,
    /// A box holding every piece's control points, padded for rounding.
    bounds: Aabb,
    /// Each piece's projection certificate (polynomial pieces).
    certificates: Vec<Option<ProjectionCertificate>>,
    /// Largest control-point coordinate: the scale of the tolerance.
    scale: f64,
}

impl SearchPieces {
    /// The pieces of `patches` (all of degrees `degrees`, at least one).
    pub(crate) fn new(patches: &[Patch], degrees: (usize, usize)) -> Self {
        let mut pieces: Vec<Patch> = patches.to_vec();
        let mut owners: Vec<u32> = (0..patches.len() as u32).collect();
        let mut cells: Vec<(u8, u8)> = vec![(0, 0); patches.len()];
        let mut depth = 0;
        let affordable = |depth: usize, count: usize| depth < 2 || 4 * count <= PIECE_BUDGET;
        let rough = |p: &Patch| !is_flat(p, degrees);
        let certify = |pieces: &[Patch]| -> Vec<Option<ProjectionCertificate>> {
            pieces
                .iter()
                .map(|piece| ProjectionCertificate::new(piece, degrees))
                .collect()
        };
        // The certificates of the pieces at hand, once the fourth cut's
        // decision has made them (kept if it decides against the cut).
        let mut certificates = None;
        while depth < MAX_CUTS && affordable(depth, pieces.len()) {
            // The fourth cut only for pieces that are not flat and whose
            // certificate settles too few directions.
            let cut = if depth < 3 {
                pieces.iter().any(rough)
            } else {
                // Made one by one, up to the first piece that asks for
                // the cut; all of them when none does.
                let mut made = Vec::with_capacity(pieces.len());
                for piece in &pieces {
                    let certificate = ProjectionCertificate::new(piece, degrees);
                    if rough(piece) && poorly_certified(piece, certificate.as_ref()) {
                        break;
                    }
                    made.push(certificate);
                }
                let cut = made.len() < pieces.len();
                certificates = Some(made);
                cut
            };
            if !cut {
                break;
            }
            certificates = None;
            let mut finer = Vec::with_capacity(4 * pieces.len());
            let mut finer_owners = Vec::with_capacity(4 * pieces.len());
            let mut finer_cells = Vec::with_capacity(4 * pieces.len());
            for ((piece, &owner), &(i, j)) in pieces.iter().zip(&owners).zip(&cells) {
                finer.extend(quarters(piece, degrees));
                finer_owners.extend([owner; 4]);
                // In the order `quarters` gives them.
                let (i, j) = (2 * i, 2 * j);
                finer_cells.extend([(i, j), (i, j + 1), (i + 1, j), (i + 1, j + 1)]);
            }
            (pieces, owners, cells) = (finer, finer_owners, finer_cells);
            depth += 1;
        }
        let certificates = certificates.unwrap_or_else(|| certify(&pieces));
        let mut scale = 0.0_f64;
        let boxes: Vec<Aabb> = pieces
            .iter()
            .map(|piece| {
                let b = piece.net_box();
                scale = scale.max(b.min.coords.amax()).max(b.max.coords.amax());
                b
            })
            .collect();
        let pad = rounding_pad(scale);
        let boxes: Vec<Aabb> = boxes.iter().map(|b| b.expand(pad)).collect();
        // One piece a leaf; the pieces stored in the hierarchy's order.
        let (tree, order) = Bvh::build(&boxes, 1);
        SearchPieces {
            degrees,
            bounds: tree.bounds(),
            tree: WideBvh::new(&tree),
            pieces: order.iter().map(|&k| pieces[k].clone()).collect(),
            certificates: order.iter().map(|&k| certificates[k].clone()).collect(),
            owners: order.iter().map(|&k| owners[k]).collect(),
            depth,
            cells: order.iter().map(|&k| cells[k]).collect(),
            scale,
        }
    }

    /// What the ray–patch search runs over.
    pub(crate) fn set(&self) -> PatchSet<'_> {
        PatchSet {
            degrees: self.degrees,
            patches: &self.pieces,
            tree: &self.tree,
            certificates: &self.certificates,
            scale: self.scale,
        }
    }

    /// The index of the patch piece `piece` was cut from.
    pub(crate) fn owner(&self, piece: usize) -> usize {
        self.owners[piece] as usize
    }

    /// The patch piece `piece` was cut from, and the point `(s, t)` of the
    /// piece in that patch's own parameters (exact: the pieces' sides are
    /// dyadic fractions of the patch).
    pub(crate) fn on_owner(&self, piece: usize, (s, t): (f64, f64)) -> (usize, (f64, f64)) {
        let (i, j) = self.cells[piece];
        let cell = 0.5f64.powi(self.depth as i32);
        let along = |k: u8, x: f64| ((f64::from(k) + x) * cell).clamp(0.0, 1.0);
        (self.owner(piece), (along(i, s), along(j, t)))
    }

    /// How many times the patches were cut in each direction: patch 0
    /// has `4^depth` pieces.
    #[cfg(test)]
    pub(crate) fn depth(&self) -> usize {
        self.depth
    }

    /// The pieces.
    #[cfg(test)]
    pub(crate) fn pieces(&self) -> &[Patch] {
        &self.pieces
    }

    /// A box holding every piece's control points (so the whole surface),
    /// padded for rounding.
    pub(crate) fn bounds(&self) -> Aabb {
        self.bounds
    }
}

/// Whether `piece` is polynomial and its projection certificate
/// (`certificate`) is missing (a fold inside it, or a point without a
/// tangent plane) or holds only for directions within 45° of its normal
/// (its products' cone is wider than that): a piece that a fourth cut would
/// serve.
fn poorly_certified(piece: &Patch, certificate: Option<&ProjectionCertificate>) -> bool {
    let polynomial = piece.net.iter().all(|h| h.w == 1.0);
    polynomial && certificate.is_none_or(ProjectionCertificate::cone_is_wide)
}

/// Whether `patch`'s projected control points lie within [`FLATNESS`] of
/// its box diagonal from the bilinear interpolation of its corners.
fn is_flat(patch: &Patch, (p, q): (usize, usize)) -> bool {
    let w = q + 1;
    let at = |i: usize, j: usize| patch.net[i * w + j].wp / patch.net[i * w + j].w;
    let (c00, c0q, cp0, cpq) = (at(0, 0), at(0, q), at(p, 0), at(p, q));
    let mut lo = c00;
    let mut hi = c00;
    let mut deviation = 0.0_f64;
    for i in 0..=p {
        for j in 0..=q {
            let x = at(i, j);
            lo = lo.inf(&x);
            hi = hi.sup(&x);
            let (s, t) = (i as f64 / p.max(1) as f64, j as f64 / q.max(1) as f64);
            let bilinear =
                (c00 * (1.0 - t) + c0q * t) * (1.0 - s) + (cp0 * (1.0 - t) + cpq * t) * s;
            deviation = deviation.max((x - bilinear).norm());
        }
    }
    // NaN-safe: a net that is not finite is never called flat (and is not
    // cut further than MAX_CUTS either).
    deviation <= FLATNESS * (hi - lo).norm()
}

/// `patch` cut at the middle of its `u` and `v` intervals into four pieces,
/// in the order (low u, low v), (low u, high v), (high u, low v),
/// (high u, high v).
fn quarters(patch: &Patch, (p, q): (usize, usize)) -> [Patch; 4] {
    let w = q + 1;
    let zero = Homogeneous::zero();
    // In u: each column (fixed j) is a curve in i.
    let mut halves = [vec![zero; patch.net.len()], vec![zero; patch.net.len()]];
    let (mut left, mut right) = (vec![zero; p + 1], vec![zero; p + 1]);
    let mut column = vec![zero; p + 1];
    for j in 0..w {
        for (i, c) in column.iter_mut().enumerate() {
            *c = patch.net[i * w + j];
        }
        subdivide(&column, 0.5, &mut left, &mut right);
        for i in 0..=p {
            halves[0][i * w + j] = left[i];
            halves[1][i * w + j] = right[i];
        }
    }
    // In v: each row of each half.
    let (mut left, mut right) = (vec![zero; w], vec![zero; w]);
    let mid = |(a, b): (f64, f64)| 0.5 * (a + b);
    let (um, vm) = (mid(patch.u), mid(patch.v));
    let u_ranges = [(patch.u.0, um), (um, patch.u.1)];
    let cut_v =
        |half: &Vec<Homogeneous<3>>, left: &mut [Homogeneous<3>], right: &mut [Homogeneous<3>]| {
            let (mut low, mut high) = (vec![zero; half.len()], vec![zero; half.len()]);
            for i in 0..=p {
                let row = i * w..(i + 1) * w;
                subdivide(&half[row.clone()], 0.5, left, right);
                low[row.clone()].copy_from_slice(left);
                high[row].copy_from_slice(right);
            }
            (low, high)
        };
    let (a_low, a_high) = cut_v(&halves[0], &mut left, &mut right);
    let (b_low, b_high) = cut_v(&halves[1], &mut left, &mut right);
    let piece = |u: (f64, f64), v: (f64, f64), net: Vec<Homogeneous<3>>| Patch { u, v, net };
    [
        piece(u_ranges[0], (patch.v.0, vm), a_low),
        piece(u_ranges[0], (vm, patch.v.1), a_high),
        piece(u_ranges[1], (patch.v.0, vm), b_low),
        piece(u_ranges[1], (vm, patch.v.1), b_high),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tensor::patch::Patch;
    use nalgebra::{Point3, Vector3};

    /// The point of a homogeneous net at `(s, t)` by the tensor Bernstein
    /// sum (a second algorithm to de Casteljau).
    fn point(patch: &Patch, (p, q): (usize, usize), s: f64, t: f64) -> Vector3<f64> {
        let mut h = Homogeneous::<3>::zero();
        for i in 0..=p {
            for j in 0..=q {
                let b = crate::bernstein::bernstein(p, i, s) * crate::bernstein::bernstein(q, j, t);
                h = h + patch.net[i * (q + 1) + j] * b;
            }
        }
        h.wp / h.w
    }

    fn wavy(p: usize, q: usize, bend: f64) -> Patch {
        let mut net = Vec::new();
        for i in 0..=p {
            for j in 0..=q {
                let (x, y) = (i as f64 / p as f64, j as f64 / q as f64);
                let z = bend * ((3.0 * x).sin() + (2.0 * y).cos() * x);
                let w = 1.0 + 0.3 * ((i + 2 * j) % 3) as f64;
                net.push(Homogeneous::new(&Point3::new(x, y, z), w));
            }
        }
        Patch {
            u: (2.0, 3.0),
            v: (-1.0, 0.5),
            net,
        }
    }

    #[test]
    fn pieces_are_the_patch_on_their_rectangles() {
        let degrees = (3, 2);
        let patch = wavy(3, 2, 0.8);
        let pieces = SearchPieces::new(std::slice::from_ref(&patch), degrees);
        // Three cuts: a fourth serves projection certificates, which a
        // rational piece does not get.
        assert_eq!(pieces.depth(), 3, "a strongly bent rational patch is cut");
        assert_eq!(pieces.pieces().len(), 64);
        let (du, dv) = (patch.u.1 - patch.u.0, patch.v.1 - patch.v.0);
        let mut area = 0.0;
        for (k, piece) in pieces.pieces().iter().enumerate() {
            assert_eq!(pieces.owner(k), 0);
            area += (piece.u.1 - piece.u.0) * (piece.v.1 - piece.v.0);
            for (a, b) in [(0.0, 0.0), (0.3, 0.9), (1.0, 0.5), (0.71, 0.13), (1.0, 1.0)] {
                let u = piece.u.0 + (piece.u.1 - piece.u.0) * a;
                let v = piece.v.0 + (piece.v.1 - piece.v.0) * b;
                let whole = point(&patch, degrees, (u - patch.u.0) / du, (v - patch.v.0) / dv);
                let part = point(piece, degrees, a, b);
                assert!((whole - part).norm() < 1e-14, "{k} {a} {b}: {whole} {part}");
            }
        }
        assert!(
            (area - du * dv).abs() < 1e-15,
            "the pieces tile the rectangle"
        );
    }

    /// A polynomial bicubic height field `z = bend·sin(3x)·cos(2y)`.
    fn height_field(bend: f64) -> Patch {
        let mut net = Vec::new();
        for i in 0..=3 {
            for j in 0..=3 {
                let (x, y) = (i as f64 / 3.0, j as f64 / 3.0);
                let z = bend * (3.0 * x).sin() * (2.0 * y).cos();
                net.push(Homogeneous::new(&Point3::new(x, y, z), 1.0));
            }
        }
        Patch {
            u: (0.0, 1.0),
            v: (0.0, 1.0),
            net,
        }
    }

    /// The fourth cut is made for a polynomial patch whose pieces after
    /// three are poorly served by their certificates (a steep fold), not
    /// for a gently curved one.
    #[test]
    fn the_fourth_cut_serves_poorly_certified_pieces_only() {
        let steep = SearchPieces::new(&[height_field(4.0)], (3, 3));
        assert_eq!(steep.depth(), 4);
        let gentle = SearchPieces::new(&[height_field(0.3)], (3, 3));
        assert!(gentle.depth() <= 3, "{}", gentle.depth());
    }

    #[test]
    fn neighbouring_pieces_share_their_edges_bit_for_bit() {
        let degrees = (3, 3);
        let patch = wavy(3, 3, 0.8);
        let pieces = SearchPieces::new(std::slice::from_ref(&patch), degrees);
        let w = 4;
        let mut shared = 0;
        for a in pieces.pieces() {
            for b in pieces.pieces() {
                // b above a in u: a's last row is b's first.
                if a.u.1 == b.u.0 && a.v == b.v {
                    for j in 0..w {
                        assert_eq!(a.net[3 * w + j], b.net[j]);
                    }
                    shared += 1;
                }
                // b beside a in v: a's last column is b's first.
                if a.v.1 == b.v.0 && a.u == b.u {
                    for i in 0..w {
                        assert_eq!(a.net[i * w + 3], b.net[i * w]);
                    }
                    shared += 1;
                }
            }
        }
        // 2^depth pieces a side, so 2^depth − 1 inner edges between rows
        // (and columns) of them.
        let side = 1 << pieces.depth();
        assert!(side > 1, "the wavy patch is cut");
        assert_eq!(
            shared,
            2 * side * (side - 1),
            "every inner edge of the pieces"
        );
    }

    #[test]
    fn an_edge_cut_either_way_gives_the_same_points() {
        // b is a with v reversed, b(s, t) = a(s, 1 − t): the two share the
        // edge u = u₀ run in opposite directions (as the teapot's patches
        // share edges), and still share it after cutting.
        let degrees = (3, 3);
        let a = wavy(3, 3, 0.5);
        let mut b = a.clone();
        for i in 0..4 {
            for j in 0..4 {
                b.net[i * 4 + j] = a.net[i * 4 + (3 - j)];
            }
        }
        let (pa, pb) = (
            SearchPieces::new(std::slice::from_ref(&a), degrees),
            SearchPieces::new(std::slice::from_ref(&b), degrees),
        );
        assert!(pa.depth() > 0 && pa.depth() == pb.depth());
        let (v0, dv) = (a.v.0, a.v.1 - a.v.0);
        let mut compared = 0;
        for x in pa.pieces().iter().filter(|x| x.u.0 == a.u.0) {
            let (lo, hi) = ((x.v.0 - v0) / dv, (x.v.1 - v0) / dv);
            let y = pb
                .pieces()
                .iter()
                .find(|y| {
                    y.u.0 == b.u.0 && (y.v.0 - v0) / dv == 1.0 - hi && (y.v.1 - v0) / dv == 1.0 - lo
                })
                .expect("the mirrored piece");
            let mut edge = y.net[..4].to_vec();
            edge.reverse();
            assert_eq!(x.net[..4].to_vec(), edge);
            compared += 1;
        }
        assert_eq!(compared, 1 << pa.depth());
    }

    #[test]
    fn flat_patches_are_not_cut() {
        let degrees = (2, 3);
        let patch = wavy(2, 3, 0.0);
        let pieces = SearchPieces::new(std::slice::from_ref(&patch), degrees);
        assert_eq!(pieces.depth(), 0);
        assert_eq!(pieces.pieces(), std::slice::from_ref(&patch));
    }
}
