//! What accuracy costs in time: every way to intersect a ray with a surface
//! of revolution, measured against an exact reference, and the same for
//! curve discretization.
//!
//! ```text
//! cargo run --release -p accuracy_cost [-- --quick] [--out DIR]
//! ```
//!
//! On the vase (one cubic Bézier), the wine glass (a 25-point uniform
//! cubic B-spline), and two rational revolutions, a NURBS sphere and a
//! NURBS torus (quarter arcs of `Nurbs::arc` and `Nurbs::circle`), it
//! measures
//! - revolve's exact intersector at tolerances `1e-3 … 1e-14`, one ray a
//!   call and through `Intersect::intersect_batch` in batches of 8 rays
//!   ([`batch`]; its hits must equal the single calls' bit for bit, or the
//!   run fails after writing its report), and the same profiles given as
//!   own curves (no Bézier spans: approximation + Newton);
//! - revolve's generic Newton intersector at several patch-tree depths and
//!   tolerances;
//! - the method the course teaches ([`course`]): Newton on `(t, u, v)` from
//!   the bounding-box entry, `s` random starts of `i` iterations;
//! - the profile tessellated and ray-cast as a parry3d `TriMesh`
//!   ([`mesh_baseline`]), with its build time and memory;
//!
//! against hits computed in exact rational arithmetic ([`reference`]; for
//! the sphere and the torus, their closed forms solved exactly,
//! [`closed_form`]): the
//! median and maximum error of `t` relative to the object's size, miss,
//! false-hit and wrong-root rates, rays per second on one thread (median of
//! repeated passes), heap held and build time. The curve part ([`curves`])
//! measures adaptive flattening (tolerance → samples → time → measured
//! deviation) and uniform discretization (segments → deviation).
//!
//! The same for tensor-product Bézier patches ([`patch_study`]): a gently
//! curved bicubic, a folded bicubic and Newell's teapot, with revolve's
//! certified patch intersector, the Newton intersector, the course method
//! and its tessellations in parry, against a reference certified in
//! interval arithmetic ([`reference::PatchReference`]).
//!
//! Beside the nearest hit, the other queries ([`queries`]): every hit
//! along a ray, occlusion and the nearest point, timed against
//! `intersect` on every shape.
//!
//! Writes `report.md` (the tables), `intersection.svg` (median error
//! against rays/s, log–log, one series per method, a panel per shape),
//! `intersection_max.svg` (the same for the maximum error), the same two for
//! the patches (`intersection_patches.svg`, `intersection_patches_max.svg`)
//! and `curves.svg` (deviation against samples) to `DIR` (default
//! `out/accuracy_cost`).
//! `--quick` runs every code path at a tiny size (CI).

mod batch;
mod closed_form;
mod course;
mod curves;
mod memory;
mod mesh_baseline;
mod model;
mod patch_study;
mod plot;
mod queries;
mod reference;
mod report;
mod study;
mod table;

use revolve_testkit as common;
use revolve_testkit::patch_shapes;

use indicatif::{ProgressBar, ProgressStyle};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

#[global_allocator]
static HEAP: memory::HeapCounter = memory::HeapCounter;

/// The command line.
#[derive(Debug, Clone, PartialEq)]
struct Args {
    quick: bool,
    out: PathBuf,
}

const USAGE: &str = "usage: accuracy_cost [--quick] [--out DIR]
  --quick    every code path at a tiny size (seconds, for CI)
  --out DIR  where report.md and the plots go (default out/accuracy_cost)";

fn parse_args(args: impl IntoIterator<Item = String>) -> Result<Args, String> {
    let mut parsed = Args {
        quick: false,
        out: PathBuf::from("out/accuracy_cost"),
    };
    let mut args = args.into_iter();
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--quick" => parsed.quick = true,
            "--out" => {
                parsed.out = args
                    .next()
                    .map(PathBuf::from)
                    .ok_or("--out needs a directory")?
            }
            "-h" | "--help" => return Err(USAGE.to_string()),
            other => return Err(format!("unknown argument '{other}'\n{USAGE}")),
        }
    }
    Ok(parsed)
}

fn main() -> ExitCode {
    let args = match parse_args(std::env::args().skip(1)) {
        Ok(a) => a,
        Err(message) => {
            eprintln!("{message}");
            return ExitCode::from(2);
        }
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("accuracy_cost: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> std::io::Result<()> {
    let start = Instant::now();
    let plan = if args.quick {
        study::Plan::quick()
    } else {
        study::Plan::full()
    };
    let bar = ProgressBar::new(0).with_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} [{elapsed}]")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let results = report::collect(&plan, args.quick, &bar);
    bar.finish_and_clear();
    let files = report::write(&args.out, &results, &plan)?;
    println!("{}", results.intersection_markdown());
    for f in files {
        println!("wrote {}", f.display());
    }
    println!("in {:.1} s", start.elapsed().as_secs_f64());
    let mut differences = results.batch_differences();
    differences.extend(results.query_disagreements());
    if differences.is_empty() {
        Ok(())
    } else {
        Err(std::io::Error::other(format!(
            "the batch path's hits differ from the single path's, or the queries from \
             intersect: {}",
            differences.join("; ")
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(list: &[&str]) -> Result<Args, String> {
        parse_args(list.iter().map(|s| s.to_string()))
    }

    #[test]
    fn command_line() {
        assert_eq!(
            args(&[]).unwrap(),
            Args {
                quick: false,
                out: PathBuf::from("out/accuracy_cost")
            }
        );
        let a = args(&["--quick", "--out", "x/y"]).unwrap();
        assert!(a.quick);
        assert_eq!(a.out, PathBuf::from("x/y"));
        assert!(args(&["--out"]).unwrap_err().contains("needs a directory"));
        assert!(
            args(&["--fast"])
                .unwrap_err()
                .contains("unknown argument '--fast'")
        );
    }
}
