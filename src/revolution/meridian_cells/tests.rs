//! Tests of the cells table against the per-span test and brute force.

use super::*;

use crate::test_unit::unit;

/// Random boxes in `[0, scale] × [−scale, scale]` (radius × height),
/// some touching the axis, some of zero height or zero radial width.
fn boxes(state: &mut u64, count: usize, scale: f64) -> Vec<SpanBox> {
    (0..count)
        .map(|i| {
            let (y0, r0) = (unit(state) * 2.0 - 1.0, unit(state) * 0.9);
            let dy = if i % 7 == 3 { 0.0 } else { 0.3 * unit(state) };
            let dr = if i % 5 == 2 { 0.0 } else { 0.3 * unit(state) };
            let r0 = if i % 4 == 1 { 0.0 } else { r0 };
            SpanBox {
                y: (y0 * scale, (y0 + dy) * scale),
                r: (r0 * scale, (r0 + dr).min(1.0) * scale),
            }
        })
        .collect()
}

/// The boxes the ray `o + t·d` certainly enters, by sampling: a dense
/// grid of `t` over its passage by the boxes, plus, for every box, the
/// closest approach to the axis and the parameters where the ray
/// crosses the box's heights and radii (so that touching contacts are
/// sampled where they happen). Independent of the table's cell
/// arithmetic.
fn entered(boxes: &[SpanBox], o: Vector3<f64>, d: Vector3<f64>, scale: f64) -> Vec<bool> {
    let a = d.x * d.x + d.z * d.z;
    let t_c = if a > 0.0 {
        -(o.x * d.x + o.z * d.z) / a
    } else {
        0.0
    };
    let mut ts = vec![t_c];
    let reach = 8.0 * (scale + o.amax()) / d.norm();
    ts.extend((0..=20_000).map(|i| t_c - reach + 2.0 * reach * i as f64 / 20_000.0));
    for b in boxes {
        if d.y != 0.0 {
            ts.extend([(b.y.0 - o.y) / d.y, (b.y.1 - o.y) / d.y]);
        }
        for r in [b.r.0, b.r.1] {
            let (bb, cc) = (o.x * d.x + o.z * d.z, o.x * o.x + o.z * o.z - r * r);
            let disc = bb * bb - a * cc;
            if a > 0.0 && disc >= 0.0 {
                ts.extend([(-bb - disc.sqrt()) / a, (-bb + disc.sqrt()) / a]);
            }
        }
    }
    boxes
        .iter()
        .map(|b| {
            ts.iter().any(|&t| {
                let p = o + d * t;
                let rho = (p.x * p.x + p.z * p.z).sqrt();
                (b.y.0..=b.y.1).contains(&p.y) && (b.r.0..=b.r.1).contains(&rho)
            })
        })
        .collect()
}

/// Checks one ray: a box the ray enters is in its cell's mask, and a
/// certain miss enters none. Returns what the table said, with the
/// mask's size.
fn check(
    cells: &MeridianCells,
    boxes: &[SpanBox],
    o: Vector3<f64>,
    d: Vector3<f64>,
    scale: f64,
) -> Option<usize> {
    let truth = entered(boxes, o, d, scale);
    let accept = 1e-12 * scale;
    match cells.classify(o, d, d.norm(), accept) {
        Cell::Outside => None,
        Cell::Miss => {
            assert!(
                !truth.contains(&true),
                "a miss that enters {truth:?}: o {o:?} d {d:?}"
            );
            Some(0)
        }
        Cell::Spans(words) => {
            let mask: Vec<u64> = words.map(|(listed, _)| listed).collect();
            assert_eq!(mask.len(), boxes.len().div_ceil(64));
            for (s, &inside) in truth.iter().enumerate() {
                let listed = mask[s / 64] >> (s % 64) & 1 == 1;
                assert!(
                    !inside || listed,
                    "box {s} entered but not listed: o {o:?} d {d:?}"
                );
            }
            Some(mask.iter().map(|w| w.count_ones() as usize).sum())
        }
    }
}

/// Random rays through and around random boxes, at three scales: every
/// entered box is listed, and the table decides most rays with masks
/// well short of every box (else it would cull nothing).
#[test]
fn lists_every_box_a_ray_enters() {
    let mut state = 0x9E37_79B9_7F4A_7C15_u64;
    for scale in [1e-6, 1.0, 1e6] {
        let boxes = boxes(&mut state, 70, scale);
        let cells = MeridianCells::new(&boxes, scale);
        let (mut decided, mut listed, mut rays) = (0, 0, 0);
        for case in 0..600 {
            let target = Vector3::new(
                unit(&mut state) * 2.0 - 1.0,
                unit(&mut state) * 2.2 - 1.1,
                unit(&mut state) * 2.0 - 1.0,
            ) * scale;
            let mut d = Vector3::new(
                unit(&mut state) - 0.5,
                unit(&mut state) - 0.5,
                unit(&mut state) - 0.5,
            );
            match case % 6 {
                // Perpendicular to the axis.
                0 => d.y = 0.0,
                // Through the axis.
                1 => {
                    d.x = -target.x / scale;
                    d.z = -target.z / scale;
                }
                _ => {}
            }
            if d.norm() == 0.0 {
                continue;
            }
            let back = if case % 10 == 9 { 1e4 } else { 3.0 };
            let o = target - d.normalize() * back * scale;
            rays += 1;
            if let Some(n) = check(&cells, &boxes, o, d, scale) {
                decided += 1;
                listed += n;
            }
        }
        assert!(decided > rays * 9 / 10, "{decided} of {rays} decided");
        assert!(
            listed < decided * 70 / 3,
            "{listed} listed for {decided} rays"
        );
    }
}

/// Rays whose three numbers sit exactly on cell boundaries (and a
/// rounding either side): the cells' margins keep them listed.
#[test]
fn rays_on_cell_boundaries() {
    let mut state = 0x2545_F491_4F6C_DD1D_u64;
    let scale = 1.0;
    let boxes = boxes(&mut state, 40, scale);
    let cells = MeridianCells::new(&boxes, scale);
    let mut decided = 0;
    for k in 0..SLOPE_CELLS {
        let c = k as f64 * C_MAX / SLOPE_CELLS as f64;
        let (lo, per) = cells.heights[k];
        for j in 0..=HEIGHT_CELLS {
            let y_c = lo + j as f64 / per;
            for i in 0..cells.rho_cells {
                let rho = i as f64 / cells.rho_scale;
                for nudge in [-1e-15, 0.0, 1e-15] {
                    // Closest point (ρ₀, y_c, 0), direction across the
                    // radius there at cosine c with the axis.
                    let closest = Vector3::new(rho + nudge, y_c + nudge, 0.0);
                    let d = Vector3::new(0.0, c, (1.0 - c * c).sqrt());
                    let o = closest - d * 4.0;
                    if check(&cells, &boxes, o, d, scale).is_some() {
                        decided += 1;
                    }
                }
            }
        }
    }
    assert!(decided > 0);
}

/// A chain of `spans` cubic spans, as a profile's (`x` and `y`
/// coefficients, 4 a span): each control point a small random step from
/// the last, rising on the whole, radii in `[0, scale]`.
fn chain(state: &mut u64, spans: usize, scale: f64) -> (Vec<f64>, Vec<f64>) {
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    let (mut x, mut y) = (0.5 * scale, -scale);
    for i in 0..spans * 4 {
        if i % 4 != 0 || i == 0 {
            x = (x + 0.1 * scale * (2.0 * unit(state) - 1.0)).clamp(0.0, scale);
            y += 0.05 * scale * (2.0 * unit(state) - 0.4);
        }
        xs.push(x);
        ys.push(y);
    }
    (xs, ys)
}

/// The boxes of [`chain`]'s spans, by their control points.
fn chain_boxes(xs: &[f64], ys: &[f64]) -> Vec<SpanBox> {
    xs.chunks(4)
        .zip(ys.chunks(4))
        .map(|(x, y)| SpanBox {
            y: (
                y.iter().copied().fold(f64::INFINITY, f64::min),
                y.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            ),
            r: (0.0, x.iter().copied().fold(0.0, f64::max)),
        })
        .collect()
}

/// Every span the table certifies monotonic for a ray's cell has, for
/// that ray, a hit function whose slope keeps one sign along the whole
/// span: `f′ = 2[(A d_x + B d_z) y′ − d_y² x x′]` from the span's own
/// point and derivative (de Casteljau) at 401 parameters, independent of
/// the certificate's coefficients and corners. Random cubic spans at
/// three scales, random rays at every slope the table covers; the table
/// must certify over ten thousand listed spans and leave some.
#[test]
fn certified_spans_are_monotonic() {
    use crate::bernstein::eval_with_derivative;
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let (mut certified, mut uncertain) = (0, 0);
    for scale in [1e-6, 1.0, 1e6] {
        for _ in 0..6 {
            let spans = 12;
            let (xs, ys) = chain(&mut state, spans, scale);
            let mut cells = MeridianCells::new(&chain_boxes(&xs, &ys), scale);
            cells.certify_monotone(SpanCurves {
                xs: &xs,
                ys: &ys,
                w: 4,
                weights: &product_weights(3),
            });
            for _ in 0..20_000 {
                let o = Vector3::new(
                    4.0 * scale * (2.0 * unit(&mut state) - 1.0),
                    4.0 * scale * (2.0 * unit(&mut state) - 1.0),
                    4.0 * scale * (2.0 * unit(&mut state) - 1.0),
                );
                let d = Vector3::new(
                    2.0 * unit(&mut state) - 1.0,
                    (2.0 * unit(&mut state) - 1.0) * [0.05, 1.0, 4.0][certified % 3],
                    2.0 * unit(&mut state) - 1.0,
                );
                let Cell::Spans(mut words) = cells.classify(o, d, d.norm(), 1e-12 * scale) else {
                    continue;
                };
                let (listed, monotone) = words.next().expect("one word");
                assert!(words.next().is_none());
                for k in 0..spans {
                    if listed >> k & 1 == 0 {
                        continue;
                    }
                    if monotone >> k & 1 == 0 {
                        uncertain += 1;
                        continue;
                    }
                    certified += 1;
                    let (sx, sy) = (&xs[4 * k..4 * k + 4], &ys[4 * k..4 * k + 4]);
                    let mut signs = (0, 0);
                    for i in 0..=400 {
                        let s = f64::from(i) / 400.0;
                        let (x, dx) = eval_with_derivative(sx, s).unwrap();
                        let (y, dy) = eval_with_derivative(sy, s).unwrap();
                        let h = y - o.y;
                        let (a, b) = (o.x * d.y + h * d.x, o.z * d.y + h * d.z);
                        let slope = (a * d.x + b * d.z) * dy - d.y * d.y * x * dx;
                        if slope > 0.0 {
                            signs.0 += 1;
                        } else if slope < 0.0 {
                            signs.1 += 1;
                        }
                    }
                    assert!(
                        signs.0 == 401 || signs.1 == 401,
                        "span {k} certified but f′ has signs {signs:?}: o {o:?} d {d:?}"
                    );
                }
            }
        }
    }
    assert!(
        certified > 10_000 && uncertain > 1000,
        "{certified} certified, {uncertain} not"
    );
}

/// The cell test the table's runs stand for: whether some line of cell
/// `(k, j, i)`, enlarged by the margins, meets the padded box `b`, by
/// the box's nearest and farthest heights from the cell's.
fn cell_meets(cells: &MeridianCells, (k, j, i): (usize, usize, usize), b: &SpanBox) -> bool {
    let (c0, c1) = slope_range(k);
    let (g0, g1) = (run_per_rise_squared(c1), run_per_rise_squared(c0));
    let (lo, per) = cells.heights[k];
    let m = cells.margin;
    let (y0, y1) = (lo + j as f64 / per - m, lo + (j + 1) as f64 / per + m);
    let rho_cell = 1.0 / cells.rho_scale;
    let rho2_margin = m * m / MARGIN;
    let a0 = ((i as f64 * rho_cell).powi(2) - rho2_margin).max(0.0);
    let a1 = ((i + 1) as f64 * rho_cell).powi(2) + rho2_margin;
    let pad = PAD / MARGIN * m;
    let (by, br) = ((b.y.0 - pad, b.y.1 + pad), (b.r.0 - pad, b.r.1 + pad));
    let near = (by.0 - y1).max(y0 - by.1).max(0.0);
    let far = (by.1 - y0).max(y1 - by.0);
    let within = a0 + g0 * near * near <= br.1 * br.1;
    let out = br.0 <= 0.0 || g1.is_infinite() || a1 + g1 * far * far >= br.0 * br.0;
    within && out
}

/// The runs of height cells the table is built from give the cells the
/// cell test passes: every one of them (the table is a superset), and
/// beyond them only cells at a run's end within its rounding slack
/// (none in practice). Random boxes at three scales.
#[test]
fn runs_are_the_cells_the_cell_test_passes() {
    let mut state = 0x1234_5678_9ABC_DEF1_u64;
    for scale in [1e-6, 1.0, 1e6] {
        let boxes = boxes(&mut state, 70, scale);
        let cells = MeridianCells::new(&boxes, scale);
        let (mut passed, mut extra) = (0, 0);
        for k in 0..SLOPE_CELLS {
            for j in 0..HEIGHT_CELLS {
                for i in 0..cells.rho_cells {
                    let at = ((k * HEIGHT_CELLS + j) * cells.rho_cells + i) * cells.width;
                    for (s, b) in boxes.iter().enumerate() {
                        let set = cells.masks[at + s / 8] >> (s % 8) & 1 == 1;
                        let meets = cell_meets(&cells, (k, j, i), b);
                        assert!(set || !meets, "cell {:?} box {s} left out", (k, j, i));
                        passed += usize::from(meets);
                        extra += usize::from(set && !meets);
                    }
                }
            }
        }
        assert!(passed > 10_000, "{passed} cells passed");
        assert!(extra <= passed / 1000, "{extra} cells beyond {passed}");
    }
}

/// The height cells certified monotonic per slope cell and span (from
/// the closed-form heights) pass the corner test [`Monotone::holds`] on
/// the cell enlarged by the margins, and miss few of the cells that
/// test passes (the closed form asks twice its tolerance). Random cubic
/// chains at three scales.
#[test]
fn certified_cells_pass_the_corner_test() {
    let mut state = 0x0F1E_2D3C_4B5A_6978_u64;
    let (mut certified, mut missed) = (0, 0);
    for scale in [1e-6, 1.0, 1e6] {
        let (xs, ys) = chain(&mut state, 12, scale);
        let mut cells = MeridianCells::new(&chain_boxes(&xs, &ys), scale);
        let weights = product_weights(3);
        cells.certify_monotone(SpanCurves {
            xs: &xs,
            ys: &ys,
            w: 4,
            weights: &weights,
        });
        let certificates = Monotone::new(SpanCurves {
            xs: &xs,
            ys: &ys,
            w: 4,
            weights: &weights,
        });
        for k in 0..SLOPE_CELLS {
            let (lo, per) = cells.heights[k];
            let m = cells.margin;
            for j in 0..HEIGHT_CELLS {
                let y = (lo + j as f64 / per - m, lo + (j + 1) as f64 / per + m);
                for s in 0..12 {
                    let at = (k * HEIGHT_CELLS + j) * cells.width;
                    let set = cells.monotone[at + s / 8] >> (s % 8) & 1 == 1;
                    let holds = certificates.holds(s, slope_range(k), y);
                    assert!(holds || !set, "slope {k} height {j} span {s}: certified");
                    certified += usize::from(set);
                    missed += usize::from(holds && !set);
                }
            }
        }
    }
    assert!(certified > 2000, "{certified} certified");
    assert!(missed <= certified / 100, "{missed} missed of {certified}");
}

/// Lines steeper than `C_MAX`, far origins and loose tolerances are
/// left to the full test; a line that stays outside every box's radius
/// is a certain miss.
#[test]
fn outside_and_certain_misses() {
    let boxes = [SpanBox {
        y: (0.0, 1.0),
        r: (0.2, 0.5),
    }];
    let cells = MeridianCells::new(&boxes, 1.0);
    let o = Vector3::new(0.1, -2.0, 0.0);
    let steep = Vector3::new(0.0, 1.0, 0.01);
    assert!(matches!(
        cells.classify(o, steep, steep.norm(), 1e-12),
        Cell::Outside
    ));
    let d = Vector3::new(0.0, 0.5, 1.0);
    assert!(matches!(
        cells.classify(o, d, d.norm(), 1e-3),
        Cell::Outside
    ));
    let far = Vector3::new(2e5, 0.5, 0.0);
    assert!(matches!(
        cells.classify(far, d, d.norm(), 1e-12),
        Cell::Outside
    ));
    let wide = Vector3::new(0.6, 0.5, -3.0);
    let along_z = Vector3::new(0.0, 0.0, 1.0);
    assert!(matches!(
        cells.classify(wide, along_z, 1.0, 1e-12),
        Cell::Miss
    ));
    let near = Vector3::new(0.4, 0.5, -3.0);
    let Cell::Spans(words) = cells.classify(near, along_z, 1.0, 1e-12) else {
        panic!("a line through the box is not listed");
    };
    assert_eq!(words.map(|(listed, _)| listed).collect::<Vec<_>>(), [1]);
}
