//! Tessellates a surface of revolution, or Newell's teapot, and writes it as
//! OBJ.
//!
//! ```text
//! cargo run --release --example tessellate -- [PROFILE] [-o OUT.obj] [--tolerance TOL]
//! ```
//!
//! `PROFILE` is `wine_glass` (default), `vase`, `teapot` (its 32 bicubic
//! Bézier patches, `scenes/data/teapot.txt`, meshed watertight across their
//! shared edges), or a text file of control
//! points, one `x y` pair per line (`#` starts a comment), read as the course
//! framework's uniform cubic B-spline (`--bezier` reads it as one Bézier
//! curve instead). The mesh is within the tolerance of the surface; the bound
//! it achieved is printed and written into the OBJ header.

use revolve_testkit as common;

use revolve::nalgebra::Point2;
use revolve::{BSpline, Bezier, BezierPatches, Mesh, Revolution};
use std::path::PathBuf;
use std::process::ExitCode;

struct Options {
    profile: String,
    out: PathBuf,
    tolerance: f64,
    bezier: bool,
}

fn parse_args() -> Result<Options, String> {
    let mut o = Options {
        profile: "wine_glass".into(),
        out: PathBuf::from("out/surface.obj"),
        tolerance: 1e-3,
        bezier: false,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "-o" | "--out" => o.out = args.next().ok_or("-o needs a path")?.into(),
            "--tolerance" => {
                let v = args.next().ok_or("--tolerance needs a value")?;
                o.tolerance = v
                    .parse()
                    .map_err(|_| format!("--tolerance: not a number: {v}"))?;
            }
            "--bezier" => o.bezier = true,
            "-h" | "--help" => {
                return Err("usage: tessellate [wine_glass|vase|teapot|FILE] [-o OUT.obj] [--tolerance TOL] [--bezier]".into());
            }
            flag if flag.starts_with('-') => {
                return Err(format!("unknown flag {flag}; try --help"));
            }
            name => o.profile = name.to_string(),
        }
    }
    Ok(o)
}

/// Control points from a text file: `x y` per line, `#` comments.
fn read_points(path: &str) -> Result<Vec<Point2<f64>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read {path}: {e}"))?;
    let mut points = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let nums: Vec<f64> = line
            .split_whitespace()
            .map(|w| {
                w.parse::<f64>()
                    .map_err(|_| format!("{path}:{}: not a number: {w}", n + 1))
            })
            .collect::<Result<_, _>>()?;
        match nums[..] {
            [x, y] => points.push(Point2::new(x, y)),
            _ => {
                return Err(format!(
                    "{path}:{}: expected two numbers `x y`, got {}",
                    n + 1,
                    nums.len()
                ));
            }
        }
    }
    Ok(points)
}

fn mesh_of(o: &Options) -> Result<Mesh, String> {
    let err = |e: revolve::Error| format!("{}: {e}", o.profile);
    match o.profile.as_str() {
        "wine_glass" => Revolution::new(common::wine_glass()).tessellate(o.tolerance),
        "vase" => Revolution::new(common::vase()).tessellate(o.tolerance),
        "teapot" => BezierPatches::new(common::teapot::patches())
            .and_then(|model| model.tessellate(o.tolerance)),
        path => {
            let points = read_points(path)?;
            if o.bezier {
                Revolution::new(Bezier::new(points).map_err(err)?).tessellate(o.tolerance)
            } else {
                Revolution::new(BSpline::uniform(3, points).map_err(err)?).tessellate(o.tolerance)
            }
        }
    }
    .map_err(err)
}

fn run(o: &Options) -> Result<(), String> {
    let mesh = mesh_of(o)?;
    if let Some(dir) = o.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    let file = std::fs::File::create(&o.out)
        .map_err(|e| format!("cannot write {}: {e}", o.out.display()))?;
    let mut w = std::io::BufWriter::new(file);
    mesh.write_obj(&mut w)
        .map_err(|e| format!("cannot write {}: {e}", o.out.display()))?;
    println!(
        "wrote {}: {} vertices, {} triangles, deviation ≤ {:.3e} (asked {:.0e})",
        o.out.display(),
        mesh.positions.len(),
        mesh.triangles.len(),
        mesh.bound,
        o.tolerance
    );
    Ok(())
}

fn main() -> ExitCode {
    match parse_args().and_then(|o| run(&o)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(m) => {
            eprintln!("tessellate: {m}");
            ExitCode::FAILURE
        }
    }
}
