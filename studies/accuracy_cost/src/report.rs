//! Runs the whole study and writes what it found: `report.md` and the plots.

use crate::curves::{self, CurvePoint};
use crate::model::Row;
use crate::patch_study::{self, PatchShape};
use crate::plot::{self, Panel, Series};
use crate::queries::{self, QueryRow};
use crate::study::{self, Cases, Plan, Shape};
use crate::table;
use indicatif::ProgressBar;
use revolve::{BezierPatches, Curve, Intersect, Revolution};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The surfaces of revolution [`collect`] measures.
pub const SHAPES: usize = 4;

/// The patch shapes [`collect`] measures.
pub const PATCH_SHAPES: usize = 3;

/// Errors below this are drawn at it on the log axis (a `t` equal to the
/// reference's rounded value has error 0).
pub const ERROR_FLOOR: f64 = 1e-17;

/// How the rays of one shape went.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeSummary {
    pub name: &'static str,
    /// A shape made of Bézier patches (plotted apart from the revolutions).
    pub patches: bool,
    /// Rays with a certified reference answer, and those hit.
    pub rays: usize,
    pub hits: usize,
    /// Rays left out (tangent contacts the reference could not certify).
    pub ambiguous: usize,
    /// Seconds the exact reference took (all cores).
    pub reference_seconds: f64,
}

/// Everything one run measured.
#[derive(Debug, Clone, PartialEq)]
pub struct Results {
    pub shapes: Vec<ShapeSummary>,
    pub rows: Vec<Row>,
    pub curves: Vec<CurvePoint>,
    /// The other queries, one row per shape.
    pub queries: Vec<QueryRow>,
}

impl Results {
    /// The intersection table.
    pub fn intersection_markdown(&self) -> String {
        table::intersection_table(&self.rows)
    }

    /// The batch rows whose hits differ from their single path's in any
    /// bit, as `"shape, method, setting: n of N rays"` (empty when all
    /// agree).
    pub fn batch_differences(&self) -> Vec<String> {
        self.rows
            .iter()
            .filter_map(|r| match r.batch_mismatches {
                Some(n) if n > 0 => Some(format!(
                    "{}, {}, {}: {n} of {} rays",
                    r.shape, r.series, r.knob, r.errors.rays
                )),
                _ => None,
            })
            .collect()
    }

    /// The shapes whose queries disagree with `intersect` on some ray, as
    /// `"shape: queries disagree on n of N rays"` (empty when none does).
    pub fn query_disagreements(&self) -> Vec<String> {
        self.queries
            .iter()
            .filter(|q| q.disagreements > 0)
            .map(|q| {
                format!(
                    "{}: queries disagree with intersect on {} of {} rays",
                    q.shape, q.disagreements, q.rays
                )
            })
            .collect()
    }
}

/// Runs the intersection study on every shape (the vase, the wine glass,
/// the rational sphere and torus; the bicubic, folded and teapot patches),
/// then the curve study, advancing `bar`.
pub fn collect(plan: &Plan, quick: bool, bar: &ProgressBar) -> Results {
    bar.set_length((SHAPES * plan.rows() + PATCH_SHAPES * plan.patch_rows()) as u64);
    let mut results = Results {
        shapes: Vec::new(),
        rows: Vec::new(),
        curves: Vec::new(),
        queries: Vec::new(),
    };
    shape(&study::vase(), plan, bar, &mut results);
    shape(&study::wine_glass(), plan, bar, &mut results);
    shape(&study::sphere(), plan, bar, &mut results);
    shape(&study::torus(), plan, bar, &mut results);
    patch_shape(&patch_study::bicubic_patch(), plan, bar, &mut results);
    patch_shape(&patch_study::folded_patch(), plan, bar, &mut results);
    patch_shape(&patch_study::teapot(), plan, bar, &mut results);
    let base = bar.position();
    bar.set_message("curves");
    results.curves = curves::study(quick, &mut |done, total| {
        bar.set_length(base + total as u64);
        bar.set_position(base + done as u64);
    });
    results
}

fn shape<C: Curve<2> + Clone>(
    shape: &Shape<C>,
    plan: &Plan,
    bar: &ProgressBar,
    results: &mut Results,
) {
    bar.set_message(format!("{}: exact reference", shape.name));
    let bounds = Revolution::new(shape.profile.clone()).bounds();
    let rays = study::random_rays(&bounds, plan.rays, 0xACC0 + results.shapes.len() as u64);
    let start = Instant::now();
    let cases: Cases = study::reference_cases(shape.reference.as_ref(), &rays, bounds.scale());
    summarize(shape.name, false, &cases, start, results);
    let rows = study::run_shape(shape, &cases, plan, &mut |row| {
        bar.set_message(format!("{}: {} {}", row.shape, row.series, row.knob));
        bar.inc(1);
    });
    results.rows.extend(rows);
    bar.set_message(format!("{}: queries", shape.name));
    let surface = Revolution::new(shape.profile.clone());
    let seed = 0xACC0 + results.queries.len() as u64;
    results.queries.push(queries::measure(
        shape.name,
        &surface,
        &|p| surface.nearest_point(p),
        (&rays, plan.rays),
        plan.repeats,
        seed,
    ));
}

fn patch_shape(shape: &PatchShape, plan: &Plan, bar: &ProgressBar, results: &mut Results) {
    bar.set_message(format!("{}: certified reference", shape.name));
    let bounds = shape.bounds();
    let rays = study::random_rays(&bounds, plan.rays, 0xACC0 + results.shapes.len() as u64);
    let start = Instant::now();
    let cases = study::reference_cases(&shape.reference(), &rays, bounds.scale());
    summarize(shape.name, true, &cases, start, results);
    let rows = patch_study::run_patch_shape(shape, &cases, plan, &mut |row| {
        bar.set_message(format!("{}: {} {}", row.shape, row.series, row.knob));
        bar.inc(1);
    });
    results.rows.extend(rows);
    bar.set_message(format!("{}: queries", shape.name));
    let seed = 0xACC0 + results.queries.len() as u64;
    let sizes = (rays.as_slice(), plan.rays);
    // One patch as a `BezierSurface`, a model as `BezierPatches`.
    let row = match shape.patches.as_slice() {
        [one] => queries::measure(
            shape.name,
            one,
            &|p| one.nearest_point(p),
            sizes,
            plan.repeats,
            seed,
        ),
        many => {
            let model =
                BezierPatches::new(many.to_vec()).expect("the study's patches form a model");
            queries::measure(
                shape.name,
                &model,
                &|p| model.nearest_point(p),
                sizes,
                plan.repeats,
                seed,
            )
        }
    };
    results.queries.push(row);
}

/// Records how a shape's rays went.
fn summarize(
    name: &'static str,
    patches: bool,
    cases: &Cases,
    start: Instant,
    results: &mut Results,
) {
    results.shapes.push(ShapeSummary {
        name,
        patches,
        rays: cases.cases.len(),
        hits: cases.cases.iter().filter(|c| c.t.is_some()).count(),
        ambiguous: cases.ambiguous,
        reference_seconds: start.elapsed().as_secs_f64(),
    });
}

/// The plot series of one shape's rows: one per method series, points
/// `(rays/s, error)` in the rows' order, errors floored at [`ERROR_FLOOR`].
pub fn series_of(rows: &[Row], shape: &str, error: impl Fn(&Row) -> f64) -> Vec<Series> {
    grouped(rows.iter().filter(|r| r.shape == shape).map(|row| {
        // The course method's settings are not an ordered sweep.
        let connect = !row.series.starts_with("course");
        let point = (row.rays_per_second, error(row).max(ERROR_FLOOR));
        (row.series.clone(), point, connect)
    }))
}

/// Points `(series name, point, connect)` gathered into one series per
/// name, in order of first appearance, points in the order given.
fn grouped(points: impl Iterator<Item = (String, (f64, f64), bool)>) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    for (name, point, connect) in points {
        match out.iter_mut().find(|s| s.name == name) {
            Some(s) => s.points.push(point),
            None => out.push(Series {
                name,
                points: vec![point],
                connect,
            }),
        }
    }
    out
}

/// Writes `report.md`, `intersection.svg`, `intersection_max.svg` (the
/// revolutions), `intersection_patches.svg`, `intersection_patches_max.svg`
/// (the patch shapes) and `curves.svg` into `dir`; returns their paths.
pub fn write(dir: &Path, results: &Results, plan: &Plan) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut files = Vec::new();
    let median = (|r: &Row| r.errors.median) as fn(&Row) -> f64;
    let max = (|r: &Row| r.errors.max) as fn(&Row) -> f64;
    for (file, patches, what, error) in [
        ("intersection.svg", false, "median", median),
        ("intersection_max.svg", false, "maximum", max),
        ("intersection_patches.svg", true, "median", median),
        ("intersection_patches_max.svg", true, "maximum", max),
    ] {
        let names: Vec<&str> = results
            .shapes
            .iter()
            .filter(|s| s.patches == patches)
            .map(|s| s.name)
            .collect();
        let series: Vec<Vec<Series>> = names
            .iter()
            .map(|n| series_of(&results.rows, n, error))
            .collect();
        let panels: Vec<Panel<'_>> = names
            .iter()
            .zip(&series)
            .map(|(n, s)| Panel {
                title: n,
                series: s,
            })
            .collect();
        let svg = plot::loglog_svg_panels(
            &format!("What accuracy costs: {what} error of t against rays per second"),
            "rays per second (one thread)",
            &format!("{what} |t − t_exact| / object size"),
            &panels,
        );
        let path = dir.join(file);
        plot::write(&path, &svg)?;
        files.push(path);
    }
    let curve_series = curve_series(&results.curves);
    let svg = plot::loglog_svg(
        "Curve discretization: measured deviation against samples",
        "samples",
        "max deviation of the curve from the polyline",
        &curve_series,
    );
    let path = dir.join("curves.svg");
    plot::write(&path, &svg)?;
    files.push(path);
    let path = dir.join("report.md");
    std::fs::write(&path, markdown(results, plan))?;
    files.push(path);
    Ok(files)
}

/// One series per curve and method: `(samples, measured deviation)`.
fn curve_series(points: &[CurvePoint]) -> Vec<Series> {
    grouped(points.iter().map(|p| {
        let name = format!("{}, {}", p.curve, p.method);
        (name, (p.samples as f64, p.measured.max(ERROR_FLOOR)), true)
    }))
}

/// The whole report as markdown.
pub fn markdown(results: &Results, plan: &Plan) -> String {
    let mut md = String::from("# What accuracy costs in time\n\n");
    let _ = writeln!(
        md,
        "Written by `cargo run --release -p accuracy_cost`. Random rays through \
         each shape's bounding box, {} per shape; errors are `|t − t_exact| / object size` \
         against hits computed in exact arithmetic (the spline profiles' own hits in \
         rational arithmetic; for the NURBS sphere and torus, the exact sphere and torus: \
         the ray–sphere quadratic and ray–torus quartic solved exactly, which the NURBS \
         profiles match to about 1e-16 of their size; for the Bézier patches, an interval \
         reference, below); rays/s is the median of {} \
         passes on one thread; memory is the heap each method holds per object.\n",
        plan.rays, plan.repeats
    );
    for s in &results.shapes {
        let _ = writeln!(
            md,
            "- {}: {} rays certified ({} hit), {} left out as tangent contacts; \
             reference in {:.1} s.",
            s.name, s.rays, s.hits, s.ambiguous, s.reference_seconds
        );
    }
    let batch_rows = results
        .rows
        .iter()
        .filter(|r| r.batch_mismatches.is_some())
        .count();
    let differences = results.batch_differences();
    let agreement = if differences.is_empty() {
        format!("equal on every ray of all {batch_rows} batch rows")
    } else {
        format!("**DIFFERENT** (the run fails): {}", differences.join("; "))
    };
    let _ = writeln!(
        md,
        "\n## Intersection\n\nA far hit is one farther than {:.0e} of the object's size \
         from the exact nearest hit: another root, a near miss accepted within a loose \
         tolerance, or a grazing hit on a coarse mesh. A method named \"…, batches of {}\" \
         is the row above it called through `Intersect::intersect_batch` on {} consecutive \
         rays of the set at a time (the last batch shorter), built and measured the same \
         way; its hits (t, point, normal, u, v) are compared with the single calls' bit \
         for bit: {agreement}.\n",
        crate::model::FAR_HIT,
        crate::batch::BATCH,
        crate::batch::BATCH,
    );
    let of_kind = |patches: bool| -> Vec<Row> {
        let names: Vec<&str> = results
            .shapes
            .iter()
            .filter(|s| s.patches == patches)
            .map(|s| s.name)
            .collect();
        results
            .rows
            .iter()
            .filter(|r| names.contains(&r.shape))
            .cloned()
            .collect()
    };
    md.push_str(&table::intersection_table(&of_kind(false)));
    md.push_str("\n![median error against rays/s](intersection.svg)\n\n");
    md.push_str("![maximum error against rays/s](intersection_max.svg)\n\n");
    let _ = writeln!(
        md,
        "## Bézier patches\n\n\
         A gently curved bicubic patch, a folded bicubic (rays cross it up to several \
         times) and Newell's teapot (32 bicubic patches, `scenes/data/teapot.txt`). The \
         reference is `revolve_testkit::reference::patch`: subdivision of the ray's two plane distances \
         in interval arithmetic rounded outward, a root proven by Miranda's theorem on a \
         small box around Newton's point inside a box where the preconditioned Jacobian \
         proves the map injective (at most one root), its `t` narrowed by a mean-value \
         step; it shares no code with revolve's intersectors (only the control points), \
         and its `t` lies in an interval about 5e-14 of the object's size wide (at most \
         1e-12, checked by its tests), the floor of the errors measured against it. \
         revolve's certified \
         patch intersector runs at each tolerance of the sweep (`with_tolerance`: how far \
         a near miss may be accepted; every hit is polished to full precision); it ray-casts \
         the teapot as a `BezierPatches` (a hierarchy over the patches' boxes), Newton \
         and the course method as a loop over its 32 patches, each behind a test of its \
         box. The meshes are revolve's `tessellate` (a uniform \
         grid per patch within the absolute tolerance by a second-derivative bound, \
         welded along shared edges) as one parry `TriMesh`; meshes predicted to exceed \
         {} triangles are not built. The course method \
         starts `u` and `v` uniformly (a patch has no axis) and never accepts hits within \
         1e-6 of a patch edge.\n",
        crate::patch_study::MAX_TRIANGLES
    );
    md.push_str(&table::intersection_table(&of_kind(true)));
    md.push_str("\n![median error against rays/s](intersection_patches.svg)\n\n");
    md.push_str("![maximum error against rays/s](intersection_patches_max.svg)\n\n");
    md.push_str(&queries_section(&results.queries));
    md.push_str("## Curves\n\n");
    md.push_str(&table::curve_table(&results.curves));
    md.push_str("\n![deviation against samples](curves.svg)\n");
    md
}

/// The queries' section: the table and how it was measured.
fn queries_section(rows: &[QueryRow]) -> String {
    let mut md = String::from(
        "## Every hit, occlusion, the nearest point\n\n\
         The shape's own rays (the default tolerance, `t` in `(0, 100)`): `intersect_all` \
         (every hit, in order) and `occluded` (is there a hit) per ray, against \
         `intersect`; their answers are checked against `intersect`'s on every ray (the \
         first of every hit is the nearest, `occluded` is whether there is one; a \
         disagreement fails the run). `nearest_point` from random points in the shape's \
         box grown by half its size on every side. Times are medians of the passes, on \
         one thread.\n\n\
         | shape | `intersect` | `intersect_all` | hits a ray | `occluded` | disagreements | \
         `nearest_point` | certified |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for q in rows {
        let micro = |s: f64| format!("{:.2} µs", s * 1e6);
        let ratio = |s: f64| format!("{} ({:.2}×)", micro(s), s / q.intersect);
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.2} | {} | {} | {} | {} of {} |",
            q.shape,
            micro(q.intersect),
            ratio(q.all),
            q.hits as f64 / q.rays.max(1) as f64,
            ratio(q.occluded),
            q.disagreements,
            micro(q.nearest),
            q.certified,
            q.points
        );
    }
    md.push('\n');
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every code path of the study at its quick size, written to disk.
    #[test]
    fn quick_study_writes_tables_and_plots() {
        let plan = Plan::quick();
        let results = collect(&plan, true, &ProgressBar::hidden());
        assert_eq!(
            results.rows.len(),
            SHAPES * plan.rows() + PATCH_SHAPES * plan.patch_rows()
        );
        assert_eq!(results.shapes.len(), SHAPES + PATCH_SHAPES);
        for s in &results.shapes {
            assert_eq!(s.rays + s.ambiguous, plan.rays, "{}", s.name);
        }
        // Every exact or certified row is followed by its batch row, with
        // the same hits, so the same error figures.
        let mut batch_rows = 0;
        for pair in results.rows.windows(2) {
            let (single, batched) = (&pair[0], &pair[1]);
            if single.series.ends_with(", batches of 8") {
                continue;
            }
            if !matches!(
                single.series.as_str(),
                "revolve exact" | "revolve certified"
            ) {
                assert_eq!(single.batch_mismatches, None, "{}", single.series);
                continue;
            }
            batch_rows += 1;
            assert_eq!(batched.series, format!("{}, batches of 8", single.series));
            assert_eq!((batched.shape, &batched.knob), (single.shape, &single.knob));
            assert_eq!(batched.batch_mismatches, Some(0), "{}", single.shape);
            assert_eq!(batched.errors, single.errors, "{}", single.shape);
        }
        assert_eq!(
            batch_rows,
            (SHAPES + PATCH_SHAPES) * plan.exact_tolerances.len()
        );
        assert!(results.batch_differences().is_empty());
        // The exact intersector at full precision: nothing missed.
        for row in results.rows.iter().filter(|r| r.knob == "tol 1e-14") {
            assert_eq!(row.errors.miss_rate, 0.0, "{}", row.shape);
            assert!(
                row.errors.max < 1e-12,
                "{}: {:e}",
                row.shape,
                row.errors.max
            );
        }
        // The mesh's error is its tessellation's, far above rounding.
        for row in results.rows.iter().filter(|r| r.series == "parry TriMesh") {
            assert!(row.errors.median > 1e-6, "{}", row.shape);
            // At least its vertices (24 bytes) and a few triangles.
            assert!(row.memory_bytes > 100, "{}", row.shape);
        }
        let dir = std::env::temp_dir().join(format!("accuracy_cost_test_{}", std::process::id()));
        let files = write(&dir, &results, &plan).unwrap();
        assert_eq!(files.len(), 6);
        let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
        assert!(md.contains("| vase | revolve exact | tol 1e-3 |"));
        assert!(md.contains("| vase | revolve exact, batches of 8 | tol 1e-3 |"));
        assert!(md.contains("| teapot | revolve certified, batches of 8 | tol 1e-14, BVH"));
        assert!(md.contains(&format!(
            "equal on every ray of all {batch_rows} batch rows"
        )));
        assert!(md.contains("| wine glass | parry TriMesh |"));
        assert!(md.contains("| NURBS sphere | revolve exact | tol 1e-14 |"));
        assert!(md.contains("| NURBS torus | parry TriMesh |"));
        assert!(md.contains("| teapot | revolve certified | tol 1e-14, BVH over 32 patches |"));
        assert!(md.contains("| folded patch | parry TriMesh | tess 1e-2"));
        let svg = std::fs::read_to_string(dir.join("intersection_patches.svg")).unwrap();
        assert!(svg.contains("teapot") && !svg.contains("NaN"));
        assert!(md.contains("## Curves"));
        // The queries: one row per shape, every answer agreeing with
        // `intersect`, a nearest point for every query point.
        assert_eq!(results.queries.len(), SHAPES + PATCH_SHAPES);
        for q in &results.queries {
            assert_eq!(
                (q.rays, q.points, q.disagreements),
                (plan.rays, plan.rays, 0),
                "{q:?}"
            );
            assert!(q.intersect > 0.0 && q.all > 0.0 && q.occluded > 0.0 && q.nearest > 0.0);
            assert_eq!(q.certified, q.points, "{q:?}");
        }
        assert!(results.query_disagreements().is_empty());
        assert!(md.contains("| teapot | "));
        assert!(md.contains("## Every hit, occlusion, the nearest point"));
        let svg = std::fs::read_to_string(dir.join("intersection.svg")).unwrap();
        assert!(svg.contains("course Newton") && !svg.contains("NaN"));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A batch row that differs from its single path is named, with its
    /// count, in the report (and by `main`, which then fails).
    #[test]
    fn batch_differences_are_reported() {
        let row = |series: &str, mismatches: Option<usize>| Row {
            shape: "vase",
            series: series.to_string(),
            knob: "tol 1e-6".to_string(),
            errors: crate::model::ErrorStats {
                rays: 2000,
                ..Default::default()
            },
            rays_per_second: 1e6,
            memory_bytes: 0,
            build_seconds: 0.0,
            batch_mismatches: mismatches,
        };
        let mut results = Results {
            shapes: Vec::new(),
            rows: vec![
                row("revolve exact", None),
                row("revolve exact, batches of 8", Some(0)),
            ],
            curves: Vec::new(),
            queries: Vec::new(),
        };
        assert!(results.batch_differences().is_empty());
        let md = markdown(&results, &Plan::quick());
        assert!(md.contains("bit for bit: equal on every ray of all 1 batch rows."));
        results.rows[1].batch_mismatches = Some(3);
        assert_eq!(
            results.batch_differences(),
            ["vase, revolve exact, batches of 8, tol 1e-6: 3 of 2000 rays"]
        );
        let md = markdown(&results, &Plan::quick());
        assert!(md.contains(
            "bit for bit: **DIFFERENT** (the run fails): vase, revolve exact, batches of 8, \
             tol 1e-6: 3 of 2000 rays."
        ));
    }

    /// A shape whose queries disagree with `intersect` is named (and
    /// `main` then fails).
    #[test]
    fn query_disagreements_are_reported() {
        let row = QueryRow {
            shape: "teapot",
            rays: 2000,
            hits: 2500,
            intersect: 1e-6,
            all: 2e-6,
            occluded: 0.9e-6,
            disagreements: 0,
            points: 2000,
            nearest: 2e-5,
            certified: 2000,
        };
        let mut results = Results {
            shapes: Vec::new(),
            rows: Vec::new(),
            curves: Vec::new(),
            queries: vec![row],
        };
        assert!(results.query_disagreements().is_empty());
        let md = markdown(&results, &Plan::quick());
        assert!(md.contains("| teapot | 1.00 µs | 2.00 µs (2.00×) | 1.25 | 0.90 µs (0.90×) | 0 |"));
        results.queries[0].disagreements = 2;
        assert_eq!(
            results.query_disagreements(),
            ["teapot: queries disagree with intersect on 2 of 2000 rays"]
        );
    }

    #[test]
    fn series_group_rows_by_method_and_floor_zero_errors() {
        let row = |series: &str, rate: f64, median: f64| Row {
            shape: "vase",
            series: series.to_string(),
            knob: String::new(),
            errors: crate::model::ErrorStats {
                median,
                ..Default::default()
            },
            rays_per_second: rate,
            memory_bytes: 0,
            build_seconds: 0.0,
            batch_mismatches: None,
        };
        let rows = [
            row("exact", 1e6, 0.0),
            row("course Newton", 1e5, 1e-9),
            row("exact", 2e6, 1e-3),
        ];
        let s = series_of(&rows, "vase", |r| r.errors.median);
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].points, vec![(1e6, ERROR_FLOOR), (2e6, 1e-3)]);
        assert!(s[0].connect && !s[1].connect);
        assert!(series_of(&rows, "wine glass", |r| r.errors.median).is_empty());
    }
}
