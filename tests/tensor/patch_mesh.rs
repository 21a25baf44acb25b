//! Tessellation of tensor-product surfaces: the reported deviation bound
//! holds (surface samples measured against the mesh with a point–triangle
//! distance written here), it is not absurdly loose, the meshes are
//! watertight across shared patch edges, bad tolerances are named errors,
//! and OBJ output reads back.

use revolve_testkit as common;

use common::tensor_shapes::sphere_octant;
use common::{Rng, teapot};
use revolve::nalgebra::{Point3, Vector3};
use revolve::{BSplineSurface, BezierPatches, BezierSurface, Error, Mesh, NurbsSurface, Surface};
use std::collections::HashMap;

// ---------------------------------------------------------------------------
// Distance from a point to a mesh
// ---------------------------------------------------------------------------

/// The distance from `x` to the segment `[a, b]`.
fn segment_distance(x: &Point3<f64>, a: &Point3<f64>, b: &Point3<f64>) -> f64 {
    let d = b - a;
    let len2 = d.norm_squared();
    let s = if len2 > 0.0 {
        ((x - a).dot(&d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (x - (a + d * s)).norm()
}

/// The distance from `x` to the (closed) triangle `abc`: to its plane when
/// the foot of the perpendicular falls inside (all three edge tests agree in
/// sign), else to the nearest edge. Degenerate triangles are their edges.
fn triangle_distance(x: &Point3<f64>, [a, b, c]: &[Point3<f64>; 3]) -> f64 {
    let n = (b - a).cross(&(c - a));
    let edges = segment_distance(x, a, b)
        .min(segment_distance(x, b, c))
        .min(segment_distance(x, c, a));
    let n2 = n.norm_squared();
    if n2 == 0.0 {
        return edges;
    }
    let foot = x - n * ((x - a).dot(&n) / n2);
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|(p, q)| (*q - *p).cross(&(foot - *p)).dot(&n) >= 0.0);
    if inside {
        (x - foot).norm().min(edges)
    } else {
        edges
    }
}

/// The mesh's triangles in a uniform grid of cubes: each triangle is listed
/// in every cube its box, grown by `reach`, meets, so the triangles within
/// `reach` of a point are all listed in the point's cube.
struct TriangleGrid {
    cell: f64,
    reach: f64,
    triangles: Vec<[Point3<f64>; 3]>,
    cubes: HashMap<[i64; 3], Vec<usize>>,
}

impl TriangleGrid {
    fn new(mesh: &Mesh, reach: f64) -> Self {
        let triangles: Vec<[Point3<f64>; 3]> = mesh
            .triangles
            .iter()
            .map(|t| t.map(|i| mesh.positions[i as usize]))
            .collect();
        let extent = |t: &[Point3<f64>; 3]| {
            let lo = t[0].coords.inf(&t[1].coords).inf(&t[2].coords);
            let hi = t[0].coords.sup(&t[1].coords).sup(&t[2].coords);
            (lo, hi)
        };
        let mean = triangles
            .iter()
            .map(|t| {
                let (lo, hi) = extent(t);
                (hi - lo).amax()
            })
            .sum::<f64>()
            / triangles.len().max(1) as f64;
        let cell = (2.0 * mean).max(2.0 * reach).max(1e-300);
        let mut cubes: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (k, t) in triangles.iter().enumerate() {
            let (lo, hi) = extent(t);
            let lo = (lo - Vector3::repeat(reach)).map(|c| (c / cell).floor() as i64);
            let hi = (hi + Vector3::repeat(reach)).map(|c| (c / cell).floor() as i64);
            for i in lo.x..=hi.x {
                for j in lo.y..=hi.y {
                    for l in lo.z..=hi.z {
                        cubes.entry([i, j, l]).or_default().push(k);
                    }
                }
            }
        }
        TriangleGrid {
            cell,
            reach,
            triangles,
            cubes,
        }
    }

    /// The distance from `x` to the mesh if it is at most `reach`, else
    /// infinity.
    fn distance(&self, x: &Point3<f64>) -> f64 {
        let key = x.coords.map(|c| (c / self.cell).floor() as i64);
        let nearest = self
            .cubes
            .get(&[key.x, key.y, key.z])
            .into_iter()
            .flatten()
            .map(|&k| triangle_distance(x, &self.triangles[k]))
            .fold(f64::INFINITY, f64::min);
        if nearest <= self.reach {
            nearest
        } else {
            f64::INFINITY
        }
    }
}

/// Parameters to sample: a 201 × 201 grid over the domain (edges included)
/// and 4000 random ones.
fn sample_parameters([(u0, u1), (v0, v1)]: [(f64, f64); 2], seed: u64) -> Vec<(f64, f64)> {
    let n = 200;
    let mut out = Vec::with_capacity((n + 1) * (n + 1) + 4000);
    for i in 0..=n {
        for j in 0..=n {
            let (a, b) = (i as f64 / n as f64, j as f64 / n as f64);
            out.push((u0 + (u1 - u0) * a, v0 + (v1 - v0) * b));
        }
    }
    let mut rng = Rng(seed);
    for _ in 0..4000 {
        out.push((rng.range(u0, u1), rng.range(v0, v1)));
    }
    out
}

/// The largest distance from the points to the mesh, asserting that each
/// is within the mesh's bound.
fn measured_deviation(mesh: &Mesh, points: &[Point3<f64>], name: &str) -> f64 {
    assert!(mesh.bound.is_finite() && mesh.bound > 0.0, "{name}: bound");
    let grid = TriangleGrid::new(mesh, mesh.bound);
    let mut worst = 0.0_f64;
    for x in points {
        let d = grid.distance(x);
        assert!(
            d <= mesh.bound,
            "{name}: the surface point {x:?} is farther than the bound {:e} from the mesh",
            mesh.bound
        );
        worst = worst.max(d);
    }
    worst
}

/// Structural facts every mesh must have: finite positions, unit normals,
/// uvs in the domain, valid indices, no triangle with a repeated index.
fn check_structure(mesh: &Mesh, domain: [(f64, f64); 2]) {
    let n = mesh.positions.len();
    assert_eq!(mesh.normals.len(), n);
    assert_eq!(mesh.uvs.len(), n);
    for p in &mesh.positions {
        assert!(p.coords.iter().all(|c| c.is_finite()));
    }
    for v in &mesh.normals {
        assert!((v.norm() - 1.0).abs() < 1e-12);
    }
    for &(u, v) in &mesh.uvs {
        assert!(u >= domain[0].0 && u <= domain[0].1 && v >= domain[1].0 && v <= domain[1].1);
    }
    for t in &mesh.triangles {
        assert!(t.iter().all(|&i| (i as usize) < n));
        assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "{t:?}");
    }
}

/// `Σᵢⱼ Pᵢⱼ Bᵢ(u) Bⱼ(v)` by the Bernstein sum (binomials by the
/// multiplicative formula): a second evaluator for the Bézier tests.
fn bernstein_sum(points: &[Vec<Point3<f64>>], u: f64, v: f64) -> Point3<f64> {
    let basis = |n: usize, t: f64| -> Vec<f64> {
        (0..=n)
            .map(|i| {
                let binomial = (0..i).fold(1.0, |b, k| b * (n - k) as f64 / (k + 1) as f64);
                binomial * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32)
            })
            .collect()
    };
    let bu = basis(points.len() - 1, u);
    let bv = basis(points[0].len() - 1, v);
    let mut sum = Vector3::zeros();
    for (i, row) in points.iter().enumerate() {
        for (j, p) in row.iter().enumerate() {
            sum += p.coords * (bu[i] * bv[j]);
        }
    }
    Point3::from(sum)
}

/// Tessellates the Bézier patch of `points` at `tolerance`, checks the
/// structure and the bound on samples (Bernstein sum), and returns
/// `(measured max deviation, bound, mesh)`.
fn check_bezier(points: Vec<Vec<Point3<f64>>>, tolerance: f64, name: &str) -> (f64, f64, Mesh) {
    let surface = BezierSurface::new(points.clone()).unwrap();
    let mesh = surface.tessellate(tolerance).unwrap();
    assert!(
        mesh.bound <= tolerance,
        "{name}: bound {} > {tolerance}",
        mesh.bound
    );
    check_structure(&mesh, surface.domain());
    for (x, &(u, v)) in mesh.positions.iter().zip(&mesh.uvs) {
        assert!(
            (x - bernstein_sum(&points, u, v)).norm() < 1e-12,
            "{name}: vertex off the surface"
        );
    }
    let samples: Vec<Point3<f64>> = sample_parameters(surface.domain(), 7)
        .into_iter()
        .map(|(u, v)| bernstein_sum(&points, u, v))
        .collect();
    let worst = measured_deviation(&mesh, &samples, name);
    eprintln!(
        "{name}: {} vertices, {} triangles, bound {:.3e}, measured {:.3e} (ratio {:.3})",
        mesh.positions.len(),
        mesh.triangles.len(),
        mesh.bound,
        worst,
        worst / mesh.bound
    );
    (worst, mesh.bound, mesh)
}

fn grid(
    rows: usize,
    cols: usize,
    mut f: impl FnMut(f64, f64) -> Point3<f64>,
) -> Vec<Vec<Point3<f64>>> {
    (0..rows)
        .map(|i| {
            (0..cols)
                .map(|j| {
                    f(
                        i as f64 / (rows - 1) as f64,
                        j as f64 / (cols - 1).max(1) as f64,
                    )
                })
                .collect()
        })
        .collect()
}

// ---------------------------------------------------------------------------
// The bound holds
// ---------------------------------------------------------------------------

#[test]
fn planar_patch_is_within_its_bound() {
    // A bicubic whose net lies in the plane x + 2y − z = 1, unevenly spaced
    // (so its second partials do not vanish): the mesh lies in that plane.
    let points = grid(4, 4, |a, b| {
        let (x, y) = (a + 0.3 * b * b, b + 0.2 * a * a * a);
        Point3::new(x, y, x + 2.0 * y - 1.0)
    });
    let (worst, bound, mesh) = check_bezier(points, 1e-3, "planar");
    assert!(worst <= bound);
    for x in &mesh.positions {
        assert!((x.x + 2.0 * x.y - x.z - 1.0).abs() < 1e-14);
    }
}

#[test]
fn bilinear_patch_is_within_its_bound() {
    // S = (u, v, u·v): S_uv = 1, so the bound is hk/4 on an n × m grid; the
    // true deviation at a cell's centre, from the diagonal's midpoint, is
    // |S(½h, ½k) − ½(S(h, 0) + S(0, k))|·(its normal share) ≈ hk/4.
    let points = vec![
        vec![Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)],
        vec![Point3::new(1.0, 0.0, 0.0), Point3::new(1.0, 1.0, 1.0)],
    ];
    let (worst, bound, mesh) = check_bezier(points, 1e-3, "bilinear");
    // n = ⌈√(1/(4·τ))⌉ = 16 cells each way: 17² vertices, 2·16² triangles.
    assert_eq!(mesh.positions.len(), 17 * 17);
    assert_eq!(mesh.triangles.len(), 2 * 16 * 16);
    let h = 1.0 / 16.0;
    assert!((bound - h * h / 4.0).abs() < 1e-12, "bound {bound}");
    assert!(worst > bound / 4.0, "measured {worst} vs bound {bound}");
    // Each triangle follows the normal S_u × S_v = (−v, −u, 1).
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        assert!((b - a).cross(&(c - a)).z > 0.0);
    }
}

#[test]
fn random_bicubic_is_within_a_tight_bound() {
    let mut rng = Rng(18);
    let points = grid(4, 4, |_, _| rng_point(&mut Rng(rng.next_u64())));
    let (worst, bound, _) = check_bezier(points, 2e-3, "random bicubic");
    // Not absurdly loose: the second-difference bound is within a factor 50.
    assert!(
        worst >= bound / 50.0,
        "measured {worst:e} vs bound {bound:e}"
    );
}

fn rng_point(rng: &mut Rng) -> Point3<f64> {
    rng.point([0.0; 3], [1.0; 3])
}

#[test]
fn folded_bicubic_is_within_its_bound() {
    // The benches' folded net: alternating heights, a sheared parabola in x.
    let points: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| {
                    let (x, y) = (i as f64 / 3.0, j as f64 / 3.0);
                    let z = if (i + j) % 2 == 0 { 0.4 } else { -0.4 };
                    Point3::new(x + 0.3 * (j as f64 - 1.5).powi(2), y, z)
                })
                .collect()
        })
        .collect();
    let (worst, bound, _) = check_bezier(points, 1e-3, "folded bicubic");
    assert!(
        worst >= bound / 50.0,
        "measured {worst:e} vs bound {bound:e}"
    );
}

#[test]
fn ruled_patch_of_degrees_1_by_5_is_within_its_bound() {
    // Two quintic curves joined by lines.
    let points: Vec<Vec<Point3<f64>>> = (0..2)
        .map(|i| {
            (0..6)
                .map(|j| {
                    let t = j as f64 / 5.0;
                    let z = if i == 0 { (3.0 * t).sin() } else { t * t - 0.5 };
                    Point3::new(i as f64 + 0.2 * t, t, z)
                })
                .collect()
        })
        .collect();
    let (worst, bound, mesh) = check_bezier(points, 1e-3, "ruled 1×5");
    // Linear in u: one cell across (S_uu = 0) would do but for the twist;
    // every vertex row in v must still sample the curves.
    assert!(mesh.positions.len() >= 2);
    assert!(worst <= bound);
}

#[test]
fn bspline_with_repeated_knots_is_within_its_bound() {
    // Bicubic × biquadratic, a double interior knot in u (C¹ there) and a
    // simple one in v.
    let mut rng = Rng(5);
    let rows = 7;
    let cols = 5;
    let points: Vec<Vec<Point3<f64>>> = (0..rows)
        .map(|i| {
            (0..cols)
                .map(|j| Point3::new(i as f64, j as f64, rng.range(-1.0, 1.0)))
                .collect()
        })
        .collect();
    let ku = vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.4, 0.7, 1.0, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.5, 0.8, 1.0, 1.0, 1.0];
    let surface = BSplineSurface::new((3, 2), (ku, kv), points).unwrap();
    let tolerance = 2e-3;
    let mesh = surface.tessellate(tolerance).unwrap();
    assert!(mesh.bound <= tolerance);
    check_structure(&mesh, surface.domain());
    for (x, &(u, v)) in mesh.positions.iter().zip(&mesh.uvs) {
        assert!((x - surface.eval(u, v)).norm() < 1e-12);
    }
    let samples: Vec<Point3<f64>> = sample_parameters(surface.domain(), 11)
        .into_iter()
        .map(|(u, v)| surface.eval(u, v))
        .collect();
    let worst = measured_deviation(&mesh, &samples, "B-spline");
    eprintln!(
        "B-spline: {} vertices, bound {:.3e}, measured {:.3e} (ratio {:.3})",
        mesh.positions.len(),
        mesh.bound,
        worst,
        worst / mesh.bound
    );
    // Watertight across its 3 × 3 patches: a disk.
    let counts = edge_counts(&mesh);
    assert!(counts.values().all(|&c| c <= 2));
    let boundary: Vec<(u32, u32)> = counts
        .iter()
        .filter(|&(_, &c)| c == 1)
        .map(|(&e, _)| e)
        .collect();
    let [(u0, u1), (v0, v1)] = surface.domain();
    let on_rim = |i: u32| {
        let (u, v) = mesh.uvs[i as usize];
        u == u0 || u == u1 || v == v0 || v == v1
    };
    assert!(boundary.iter().all(|&(a, b)| on_rim(a) && on_rim(b)));
    let rim_vertices = (0..mesh.positions.len() as u32)
        .filter(|&i| on_rim(i))
        .count();
    // A closed polygon around the domain: as many edges as vertices.
    assert_eq!(boundary.len(), rim_vertices);
    let euler = mesh.positions.len() as i64 - counts.len() as i64 + mesh.triangles.len() as i64;
    assert_eq!(euler, 1, "V − E + F of a disk");
}

#[test]
fn nurbs_sphere_octant_is_within_its_bound() {
    let r = 2.0;
    let surface = sphere_octant(r);
    let tolerance = 1e-3;
    let mesh = surface.tessellate(tolerance).unwrap();
    assert!(mesh.bound <= tolerance);
    check_structure(&mesh, surface.domain());
    // Vertices on the sphere; the triangles inside it by at most the bound
    // (there the distance to the surface is exactly r − |x|).
    // Vertex normals are the sphere's (radial), all on one side, the pole's
    // included (its limit normal).
    let side = mesh.normals[0].dot(&mesh.positions[0].coords).signum();
    for (x, n) in mesh.positions.iter().zip(&mesh.normals) {
        assert!((x.coords.norm() - r).abs() < 1e-13);
        assert!(n.dot(&x.coords) * side / r > 1.0 - 1e-9, "{x:?}: {n:?}");
    }
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let centroid = (a.coords + b.coords + c.coords) / 3.0;
        assert!(r - centroid.norm() <= mesh.bound);
        // Outward: the parametrization's normal points away from the centre
        // or into it consistently; check against the vertex normal.
        let n = (b - a).cross(&(c - a));
        let vn = mesh.normals[t[0] as usize].into_inner()
            + mesh.normals[t[1] as usize].into_inner()
            + mesh.normals[t[2] as usize].into_inner();
        assert!(n.dot(&vn) > 0.0);
    }
    // The pole (u = 0, a collapsed edge) is one vertex, with the pole's normal.
    let pole: Vec<usize> = (0..mesh.positions.len())
        .filter(|&i| (mesh.positions[i] - Point3::new(0.0, 0.0, r)).norm() < 1e-12)
        .collect();
    assert_eq!(pole.len(), 1);
    assert!(mesh.normals[pole[0]].z.abs() > 1.0 - 1e-12);
    // Exact sphere points of the octant (not the library's evaluator).
    let mut samples = Vec::new();
    let mut rng = Rng(3);
    let n = 200;
    for i in 0..=n {
        for j in 0..=n {
            let (theta, phi) = (
                std::f64::consts::FRAC_PI_2 * i as f64 / n as f64,
                std::f64::consts::FRAC_PI_2 * j as f64 / n as f64,
            );
            samples.push(sphere_point(r, theta, phi));
        }
    }
    for _ in 0..4000 {
        let theta = rng.range(0.0, std::f64::consts::FRAC_PI_2);
        let phi = rng.range(0.0, std::f64::consts::FRAC_PI_2);
        samples.push(sphere_point(r, theta, phi));
    }
    let worst = measured_deviation(&mesh, &samples, "sphere octant");
    eprintln!(
        "sphere octant: {} vertices, bound {:.3e}, measured {:.3e} (ratio {:.3})",
        mesh.positions.len(),
        mesh.bound,
        worst,
        worst / mesh.bound
    );
}

/// The point at polar angle `theta` from +z and azimuth `phi` from +x.
fn sphere_point(r: f64, theta: f64, phi: f64) -> Point3<f64> {
    Point3::new(
        r * theta.sin() * phi.cos(),
        r * theta.sin() * phi.sin(),
        r * theta.cos(),
    )
}

// ---------------------------------------------------------------------------
// Watertight meshes
// ---------------------------------------------------------------------------

/// How many triangles use each undirected edge.
fn edge_counts(mesh: &Mesh) -> HashMap<(u32, u32), usize> {
    let mut counts = HashMap::new();
    for &[a, b, c] in &mesh.triangles {
        for (x, y) in [(a, b), (b, c), (c, a)] {
            *counts.entry((x.min(y), x.max(y))).or_insert(0) += 1;
        }
    }
    counts
}

/// The loops of boundary edges (used by one triangle), each as its list of
/// vertices; asserts every boundary vertex has exactly two boundary edges
/// (the boundary is a set of closed curves).
fn boundary_loops(counts: &HashMap<(u32, u32), usize>) -> Vec<Vec<u32>> {
    let mut next: HashMap<u32, Vec<u32>> = HashMap::new();
    for (&(a, b), _) in counts.iter().filter(|&(_, &c)| c == 1) {
        next.entry(a).or_default().push(b);
        next.entry(b).or_default().push(a);
    }
    assert!(
        next.values().all(|n| n.len() == 2),
        "a boundary vertex off a simple loop"
    );
    let mut seen: HashMap<u32, ()> = HashMap::new();
    let mut loops = Vec::new();
    let mut starts: Vec<u32> = next.keys().copied().collect();
    starts.sort_unstable();
    for start in starts {
        if seen.contains_key(&start) {
            continue;
        }
        let mut cycle = vec![start];
        seen.insert(start, ());
        let (mut previous, mut at) = (start, next[&start][0]);
        while at != start {
            cycle.push(at);
            seen.insert(at, ());
            let n = &next[&at];
            let step = if n[0] == previous { n[1] } else { n[0] };
            (previous, at) = (at, step);
        }
        loops.push(cycle);
    }
    loops
}

#[test]
fn teapot_is_watertight_but_where_the_model_is_open() {
    let model = BezierPatches::new(teapot::patches()).unwrap();
    let mesh = model.tessellate(1e-2).unwrap();
    assert!(mesh.bound <= 1e-2);
    check_structure(&mesh, [(0.0, 1.0), (0.0, 1.0)]);
    let counts = edge_counts(&mesh);
    assert!(
        counts.values().all(|&c| c <= 2),
        "an edge of three triangles"
    );
    // The model is open in six places, each a simple loop of boundary
    // edges: the rim's inner edge (r = 1.4) and the lid's outer edge
    // (r = 1.3) leave a gap at z = 2.4; the handle's two ends and the
    // spout's base end on the body without being stitched to it (their end
    // curves are not edges of the body's patches); the spout's tip is open.
    // Every other edge has exactly two triangles. (Boxes of the loops'
    // vertices, x, y, z lows then highs.)
    let expected: [([f64; 3], [f64; 3], &str); 6] = [
        ([-1.4, -1.4, 2.4], [1.4, 1.4, 2.4], "rim"),
        ([-1.3, -1.3, 2.4], [1.3, 1.3, 2.4], "lid"),
        ([-2.0, -0.225, 0.6], [-1.9, 0.225, 0.9], "handle, lower end"),
        (
            [-1.6, -0.225, 2.025],
            [-1.5, 0.225, 2.25],
            "handle, upper end",
        ),
        ([1.7, -0.495, 0.6], [1.7, 0.495, 1.425], "spout, base"),
        ([2.8, -0.1125, 2.4], [3.2, 0.1125, 2.4], "spout, tip"),
    ];
    let loops = boundary_loops(&counts);
    assert_eq!(loops.len(), expected.len());
    let boundary_edges = counts.values().filter(|&&c| c == 1).count();
    assert_eq!(loops.iter().map(Vec::len).sum::<usize>(), boundary_edges);
    for (lo_want, hi_want, name) in expected {
        let found = loops.iter().any(|l| {
            let (lo, hi) = l.iter().fold(
                (
                    Vector3::repeat(f64::INFINITY),
                    Vector3::repeat(f64::NEG_INFINITY),
                ),
                |(lo, hi), &i| {
                    let x = mesh.positions[i as usize].coords;
                    (lo.inf(&x), hi.sup(&x))
                },
            );
            (lo - Vector3::from(lo_want)).amax() < 1e-2
                && (hi - Vector3::from(hi_want)).amax() < 1e-2
        });
        assert!(found, "no open loop at the {name}");
    }
    eprintln!(
        "teapot: {} vertices, {} triangles, {} edges ({boundary_edges} boundary)",
        mesh.positions.len(),
        mesh.triangles.len(),
        counts.len(),
    );
    // Every surface point of every patch is within the bound.
    let mut samples = Vec::new();
    for (k, patch) in model.patches().iter().enumerate() {
        for (u, v) in sample_parameters(patch.domain(), k as u64)
            .into_iter()
            .step_by(4)
        {
            samples.push(patch.eval(u, v));
        }
    }
    let worst = measured_deviation(&mesh, &samples, "teapot");
    eprintln!(
        "teapot: bound {:.3e}, measured {worst:.3e} (ratio {:.3})",
        mesh.bound,
        worst / mesh.bound
    );
}

#[test]
fn patches_joined_across_directions_are_welded() {
    // Patch B's column j = 0 (a curve in u) is patch A's row i = 3 (a curve
    // in v) reversed, and A needs many more cells across than B would
    // alone: the counts must agree, and the two meshes join into a disk.
    let mut rng = Rng(99);
    let a: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| Point3::new(i as f64, j as f64, rng.range(-1.0, 1.0)))
                .collect()
        })
        .collect();
    let shared: Vec<Point3<f64>> = a[3].iter().rev().copied().collect();
    let b: Vec<Vec<Point3<f64>>> = (0..4)
        .map(|i| {
            (0..3)
                .map(|j| {
                    let x = shared[i];
                    if j == 0 {
                        x
                    } else {
                        Point3::new(x.x + j as f64, x.y + 0.1 * j as f64, x.z)
                    }
                })
                .collect()
        })
        .collect();
    let model = BezierPatches::new(vec![
        BezierSurface::new(a).unwrap(),
        BezierSurface::new(b).unwrap(),
    ])
    .unwrap();
    let mesh = model.tessellate(1e-3).unwrap();
    let counts = edge_counts(&mesh);
    assert!(counts.values().all(|&c| c <= 2));
    assert_eq!(
        boundary_loops(&counts).len(),
        1,
        "one outline: the seam is closed"
    );
    let euler = mesh.positions.len() as i64 - counts.len() as i64 + mesh.triangles.len() as i64;
    assert_eq!(euler, 1, "V − E + F of a disk");
}

#[test]
fn closed_bspline_tube_is_watertight() {
    // A cylinder closed in v by repeating the first control column at the
    // end (clamped knots, the seam is a shared patch edge of equal control
    // points), open at its two ends: several spans both ways.
    let ring = [
        (1.0, 0.0),
        (1.0, 1.0),
        (-1.0, 1.0),
        (-1.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
    ];
    let points: Vec<Vec<Point3<f64>>> = (0..5)
        .map(|i| {
            ring.iter()
                .map(|&(x, y)| Point3::new(x, y, i as f64 * 0.5))
                .collect()
        })
        .collect();
    let ku = vec![0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0];
    let kv = vec![0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0];
    let surface = BSplineSurface::new((2, 2), (ku, kv), points).unwrap();
    let mesh = surface.tessellate(1e-3).unwrap();
    check_structure(&mesh, surface.domain());
    let counts = edge_counts(&mesh);
    assert!(counts.values().all(|&c| c <= 2));
    // Open only at the two ends u = 0 and u = 1: boundary edges join
    // vertices there, and each end is a closed loop (as many edges as
    // vertices).
    let (u0, u1) = surface.domain()[0];
    let boundary: Vec<(u32, u32)> = counts
        .iter()
        .filter(|&(_, &c)| c == 1)
        .map(|(&e, _)| e)
        .collect();
    let end = |i: u32| mesh.uvs[i as usize].0;
    assert!(
        boundary
            .iter()
            .all(|&(a, b)| end(a) == end(b) && (end(a) == u0 || end(a) == u1))
    );
    let end_vertices = mesh
        .uvs
        .iter()
        .filter(|&&(u, _)| u == u0 || u == u1)
        .count();
    assert_eq!(boundary.len(), end_vertices);
    // An annulus: V − E + F = 0.
    let euler = mesh.positions.len() as i64 - counts.len() as i64 + mesh.triangles.len() as i64;
    assert_eq!(euler, 0);
}

// ---------------------------------------------------------------------------
// Bad input
// ---------------------------------------------------------------------------

#[test]
fn bad_tolerances_are_named_errors() {
    let octant = sphere_octant(1.0);
    let bezier = BezierSurface::new(grid(3, 3, |a, b| Point3::new(a, b, a * b))).unwrap();
    let bspline = BSplineSurface::new(
        (1, 1),
        (vec![0.0, 0.0, 1.0, 1.0], vec![0.0, 0.0, 1.0, 1.0]),
        grid(2, 2, |a, b| Point3::new(a, b, 0.0)),
    )
    .unwrap();
    let all: [&dyn Fn(f64) -> Result<Mesh, Error>; 3] =
        [&|t| octant.tessellate(t), &|t| bezier.tessellate(t), &|t| {
            bspline.tessellate(t)
        }];
    for tessellate in all {
        for bad in [0.0, -1e-3, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            match tessellate(bad) {
                Err(Error::InvalidTolerance { tolerance }) => {
                    assert!(tolerance.to_bits() == bad.to_bits())
                }
                other => panic!("{bad}: {other:?}"),
            }
        }
        for small in [1e-300, 1e-12] {
            match tessellate(small) {
                Err(
                    Error::ToleranceTooSmall { tolerance, min }
                    | Error::MeshTooLarge { tolerance, min, .. },
                ) => {
                    assert_eq!(tolerance, small);
                    assert!(min > small && min.is_finite());
                }
                other => panic!("{small}: {other:?}"),
            }
        }
    }
    // The budget's `min` is honest: just below the vertex cap, the next
    // tolerance up still works (bilinear: n² vertices for τ = 1/(4n²)).
    let flat = BezierSurface::new(grid(2, 2, |a, b| Point3::new(a, b, a * b))).unwrap();
    let err = flat.tessellate(1e-9).unwrap_err();
    let Error::MeshTooLarge {
        tolerance,
        vertices,
        max,
        min,
    } = err
    else {
        panic!("{err:?}")
    };
    assert!(min > 1e-9 && min < 1e-7, "min {min}");
    assert_eq!((tolerance, max), (1e-9, Mesh::MAX_VERTICES));
    assert!(vertices > max as f64, "{vertices}");
    assert!(flat.tessellate(min).is_ok());
    assert!(err.to_string().contains("vertices"), "{err}");
}

#[test]
fn huge_tolerance_gives_one_cell() {
    let s = BezierSurface::new(grid(4, 4, |a, b| Point3::new(a, b, (a - b).powi(2)))).unwrap();
    let mesh = s.tessellate(1e6).unwrap();
    assert_eq!(mesh.positions.len(), 4);
    assert_eq!(mesh.triangles.len(), 2);
    assert!(mesh.bound <= 1e6);
}

#[test]
fn degenerate_patches_give_finite_meshes() {
    // Degree 0 in u (a curve, every cell's image a segment) and a patch
    // collapsed to one point: no panic, no NaN, unit normals, and the
    // surface still within the bound (collapsed triangles are kept where
    // nothing else covers their segment).
    let curve = vec![vec![
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 2.0, 0.0),
        Point3::new(2.0, 0.0, 1.0),
    ]];
    let point = vec![vec![Point3::new(1.0, 2.0, 3.0); 3]; 3];
    for points in [curve, point] {
        let surface = BezierSurface::new(points.clone()).unwrap();
        let mesh = surface.tessellate(1e-3).unwrap();
        assert!(!mesh.triangles.is_empty());
        for (x, n) in mesh.positions.iter().zip(&mesh.normals) {
            assert!(x.coords.iter().all(|c| c.is_finite()));
            assert!((n.norm() - 1.0).abs() < 1e-12);
        }
        let samples: Vec<Point3<f64>> = sample_parameters(surface.domain(), 1)
            .into_iter()
            .step_by(16)
            .map(|(u, v)| bernstein_sum(&points, u, v))
            .collect();
        measured_deviation(&mesh, &samples, "degenerate");
    }
}

// ---------------------------------------------------------------------------
// OBJ
// ---------------------------------------------------------------------------

#[test]
fn obj_reads_back() {
    let surface = NurbsSurface::from(
        BSplineSurface::new(
            (2, 2),
            (
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            ),
            grid(3, 3, |a, b| Point3::new(a, b, (a * 3.0).sin() * b)),
        )
        .unwrap(),
    );
    let mesh = surface.tessellate(1e-3).unwrap();
    let mut out = Vec::new();
    mesh.write_obj(&mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    let (mut normals, mut uvs) = (0, 0);
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let c: Vec<f64> = words.map(|w| w.parse().unwrap()).collect();
                positions.push(Point3::new(c[0], c[1], c[2]));
            }
            Some("vn") => normals += 1,
            Some("vt") => uvs += 1,
            Some("f") => {
                let idx: Vec<u32> = words
                    .map(|w| w.split('/').next().unwrap().parse::<u32>().unwrap() - 1)
                    .collect();
                faces.push([idx[0], idx[1], idx[2]]);
            }
            _ => {}
        }
    }
    assert_eq!(positions, mesh.positions, "shortest round-trip digits");
    assert_eq!(faces, mesh.triangles);
    assert_eq!(normals, mesh.normals.len());
    assert_eq!(uvs, mesh.uvs.len());
}
