//! Discretizes a profile curve and writes what it computed.
//!
//! ```text
//! cargo run --release --example discretize -- [--out DIR] [--segments N] [--tolerance TOL]
//! ```
//!
//! The profile is the wine glass of the course scene files: a uniform cubic
//! B-spline (the course framework's knots `i/(n + 3)`), plus a cubic Bézier
//! vase. For each curve the example writes `DIR/<name>_uniform.csv` (uniform
//! samples: t, point, derivative), `DIR/<name>_flat.csv` (adaptive flattening
//! to the tolerance) and one SVG, `DIR/curves.svg`, showing the control
//! polygons, the uniform samples and the flattened polylines. It prints what it
//! wrote and the flattening's certified bound.

#[path = "../tests/common/mod.rs"]
mod common;

use common::{vase, wine_glass};
use revolve::nalgebra::Point2;
use revolve::{Curve, CurveSample, Flattening};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

/// Command-line options.
struct Options {
    out: PathBuf,
    segments: usize,
    tolerance: f64,
}

fn parse_args() -> Result<Options, String> {
    let mut options = Options {
        out: PathBuf::from("out"),
        segments: 32,
        tolerance: 1e-3,
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let mut value = || args.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--out" => options.out = PathBuf::from(value()?),
            "--segments" => {
                let v = value()?;
                options.segments = v
                    .parse()
                    .map_err(|_| format!("--segments: not a count: {v}"))?;
            }
            "--tolerance" => {
                let v = value()?;
                options.tolerance = v
                    .parse()
                    .map_err(|_| format!("--tolerance: not a number: {v}"))?;
            }
            "-h" | "--help" => {
                return Err(
                    "usage: discretize [--out DIR] [--segments N] [--tolerance TOL]".to_string(),
                );
            }
            other => return Err(format!("unknown argument {other}; try --help")),
        }
    }
    Ok(options)
}

fn samples_csv(samples: &[CurveSample<2>]) -> String {
    let mut csv = String::from("t,x,y,dx,dy\n");
    for s in samples {
        let _ = writeln!(
            csv,
            "{},{},{},{},{}",
            s.t, s.point.x, s.point.y, s.derivative.x, s.derivative.y
        );
    }
    csv
}

/// One curve's outputs, for the SVG.
struct Drawn {
    name: &'static str,
    color: &'static str,
    controls: Vec<Point2<f64>>,
    uniform: Vec<CurveSample<2>>,
    flat: Flattening<2>,
}

fn svg(curves: &[Drawn]) -> String {
    // World window [-1.2, 1.8] × [-1.2, 1.2] mapped to 600 × 480 pixels, y up.
    let map = |p: &Point2<f64>| ((p.x + 1.2) * 200.0, (1.2 - p.y) * 200.0);
    let polyline = |pts: &mut dyn Iterator<Item = Point2<f64>>| {
        pts.map(|p| {
            let (x, y) = map(&p);
            format!("{x:.2},{y:.2}")
        })
        .collect::<Vec<_>>()
        .join(" ")
    };
    let mut out = String::from(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"600\" height=\"480\" viewBox=\"0 0 600 480\">\n\
         <rect width=\"600\" height=\"480\" fill=\"white\"/>\n\
         <line x1=\"240\" y1=\"0\" x2=\"240\" y2=\"480\" stroke=\"#bbb\" stroke-dasharray=\"4 4\"/>\n",
    );
    for c in curves {
        let _ = writeln!(
            out,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"#999\" stroke-width=\"1\"/>",
            polyline(&mut c.controls.iter().copied())
        );
        let _ = writeln!(
            out,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>",
            polyline(&mut c.flat.samples.iter().map(|s| s.point)),
            c.color
        );
        for s in &c.uniform {
            let (x, y) = map(&s.point);
            let _ = writeln!(
                out,
                "<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"2\" fill=\"{}\"/>",
                c.color
            );
        }
        let (x, y) = map(&c.controls[0]);
        let _ = writeln!(
            out,
            "<text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\">{}</text>",
            x + 6.0,
            y + 14.0,
            c.name
        );
    }
    out.push_str("</svg>\n");
    out
}

fn run(options: &Options) -> Result<(), String> {
    let glass = wine_glass();
    let vase = vase();
    let curves = [
        Drawn {
            name: "wine_glass",
            color: "#c03",
            controls: glass.points().to_vec(),
            uniform: glass.discretize(options.segments),
            flat: glass
                .flatten(options.tolerance)
                .map_err(|e| format!("wine glass: {e}"))?,
        },
        Drawn {
            name: "vase",
            color: "#06c",
            controls: vase.points().to_vec(),
            uniform: vase.discretize(options.segments),
            flat: vase
                .flatten(options.tolerance)
                .map_err(|e| format!("vase: {e}"))?,
        },
    ];
    std::fs::create_dir_all(&options.out)
        .map_err(|e| format!("cannot create {}: {e}", options.out.display()))?;
    let write = |name: String, text: String| {
        let path = options.out.join(name);
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        println!("wrote {}", path.display());
        Ok::<(), String>(())
    };
    for c in &curves {
        write(format!("{}_uniform.csv", c.name), samples_csv(&c.uniform))?;
        write(format!("{}_flat.csv", c.name), samples_csv(&c.flat.samples))?;
        println!(
            "{:>10}: {} uniform samples; flattened to {} samples, certified deviation ≤ {:.3e} (asked {:.0e})",
            c.name,
            c.uniform.len(),
            c.flat.samples.len(),
            c.flat.bound,
            options.tolerance
        );
    }
    write("curves.svg".to_string(), svg(&curves))
}

fn main() -> ExitCode {
    let result = parse_args().and_then(|options| run(&options));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("discretize: {message}");
            ExitCode::FAILURE
        }
    }
}
