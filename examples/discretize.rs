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
//! to the tolerance) and one SVG, `DIR/curves.svg`: one panel per curve, each
//! with its own axes at equal scales (profile coordinates: `x` the distance
//! from the axis of revolution, `y` along it), drawing the curve itself
//! (densely evaluated), its control polygon, the uniform samples and the
//! flattened polyline, under one legend. It prints what it wrote and the
//! flattening's certified bound.

use revolve_testkit as common;

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
    /// What kind of curve it is, for the panel's subtitle.
    kind: &'static str,
    controls: Vec<Point2<f64>>,
    /// The curve itself, densely evaluated ([`DENSE_SEGMENTS`] segments).
    dense: Vec<CurveSample<2>>,
    uniform: Vec<CurveSample<2>>,
    flat: Flattening<2>,
    tolerance: f64,
}

/// Segments of the dense evaluation drawn as "the curve".
const DENSE_SEGMENTS: usize = 1024;

/// The figure's size in pixels; each curve gets a panel `PANEL_WIDTH` wide
/// above a legend `LEGEND_HEIGHT` high.
const PANEL_WIDTH: f64 = 480.0;
const PANEL_HEIGHT: f64 = 520.0;
const LEGEND_HEIGHT: f64 = 96.0;
/// Margins of a panel's plot area: room for the title above and the tick
/// labels left and below.
const MARGIN_TOP: f64 = 66.0;
const MARGIN_LEFT: f64 = 58.0;
const MARGIN_RIGHT: f64 = 16.0;
const MARGIN_BOTTOM: f64 = 46.0;

/// The styles of the four things drawn, shared by the panels and the legend.
const CURVE_STYLE: &str = "fill=\"none\" stroke=\"#f2b705\" stroke-width=\"6\" stroke-linecap=\"round\" stroke-linejoin=\"round\" stroke-opacity=\"0.55\"";
const POLYGON_STYLE: &str =
    "fill=\"none\" stroke=\"#777\" stroke-width=\"1\" stroke-dasharray=\"5 3\"";
const FLAT_COLOR: &str = "#c03";
const SAMPLE_COLOR: &str = "#1a4fa0";

/// A step of 1, 2 or 5 times a power of ten giving about five ticks over
/// `range`.
fn tick_step(range: f64) -> f64 {
    let raw = range / 5.0;
    let magnitude = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * magnitude)
        .find(|&step| step >= raw)
        .unwrap_or(10.0 * magnitude)
}

/// The multiples of `step` in `[lo, hi]`.
fn ticks(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// The map from profile coordinates to one panel's pixels: equal scales on
/// both axes (the profile is not distorted), the data box centred in the
/// plot area.
struct Frame {
    /// Pixels per unit.
    scale: f64,
    /// The pixel of the profile point (0, 0).
    origin: (f64, f64),
    /// The data box shown, `(x_min, x_max, y_min, y_max)`.
    window: (f64, f64, f64, f64),
    /// The plot area in pixels, `(left, top, right, bottom)`.
    area: (f64, f64, f64, f64),
}

impl Frame {
    /// The frame of the panel whose left edge is at `left` showing all of
    /// `points` and the axis of revolution `x = 0`.
    fn new(left: f64, points: impl Iterator<Item = Point2<f64>>) -> Frame {
        let (mut x0, mut x1, mut y0, mut y1) = (0.0f64, 0.0f64, f64::INFINITY, -f64::INFINITY);
        for p in points {
            (x0, x1) = (x0.min(p.x), x1.max(p.x));
            (y0, y1) = (y0.min(p.y), y1.max(p.y));
        }
        let pad = 0.06 * (x1 - x0).max(y1 - y0);
        let window = (x0 - pad, x1 + pad, y0 - pad, y1 + pad);
        let area = (
            left + MARGIN_LEFT,
            MARGIN_TOP,
            left + PANEL_WIDTH - MARGIN_RIGHT,
            PANEL_HEIGHT - MARGIN_BOTTOM,
        );
        let scale = ((area.2 - area.0) / (window.1 - window.0))
            .min((area.3 - area.1) / (window.3 - window.2));
        // Centre the data box in the plot area.
        let cx = 0.5 * (area.0 + area.2) - scale * 0.5 * (window.0 + window.1);
        let cy = 0.5 * (area.1 + area.3) + scale * 0.5 * (window.2 + window.3);
        Frame {
            scale,
            origin: (cx, cy),
            window,
            area,
        }
    }

    /// The pixel of the profile point `p` (y up).
    fn map(&self, p: &Point2<f64>) -> (f64, f64) {
        (
            self.origin.0 + self.scale * p.x,
            self.origin.1 - self.scale * p.y,
        )
    }

    /// `points` as an SVG `points` attribute.
    fn polyline(&self, points: impl Iterator<Item = Point2<f64>>) -> String {
        points
            .map(|p| {
                let (x, y) = self.map(&p);
                format!("{x:.2},{y:.2}")
            })
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// The text of a tick label: no more decimals than the step needs.
fn tick_label(value: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    format!("{value:.decimals$}")
}

/// The axes of one panel: frame, grid, tick labels, axis titles and the
/// axis of revolution.
fn axes(out: &mut String, f: &Frame) {
    let (left, top, right, bottom) = f.area;
    let (x0, x1, y0, y1) = f.window;
    let step = tick_step((x1 - x0).max(y1 - y0));
    for x in ticks(x0, x1, step) {
        let (px, _) = f.map(&Point2::new(x, 0.0));
        if px < left || px > right {
            continue;
        }
        let _ = writeln!(
            out,
            "<line x1=\"{px:.2}\" y1=\"{top}\" x2=\"{px:.2}\" y2=\"{bottom}\" stroke=\"#eee\"/>\n\
             <text x=\"{px:.2}\" y=\"{:.1}\" font-size=\"11\" text-anchor=\"middle\">{}</text>",
            bottom + 15.0,
            tick_label(x, step)
        );
    }
    for y in ticks(y0, y1, step) {
        let (_, py) = f.map(&Point2::new(0.0, y));
        if py < top || py > bottom {
            continue;
        }
        let _ = writeln!(
            out,
            "<line x1=\"{left}\" y1=\"{py:.2}\" x2=\"{right}\" y2=\"{py:.2}\" stroke=\"#eee\"/>\n\
             <text x=\"{:.1}\" y=\"{:.2}\" font-size=\"11\" text-anchor=\"end\">{}</text>",
            left - 6.0,
            py + 4.0,
            tick_label(y, step)
        );
    }
    let _ = writeln!(
        out,
        "<rect x=\"{left}\" y=\"{top}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>\n\
         <text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\" text-anchor=\"middle\">x (distance from the axis)</text>\n\
         <text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\" text-anchor=\"middle\" transform=\"rotate(-90 {:.1} {:.1})\">y (along the axis)</text>",
        right - left,
        bottom - top,
        0.5 * (left + right),
        bottom + 34.0,
        left - 42.0,
        0.5 * (top + bottom),
        left - 42.0,
        0.5 * (top + bottom),
    );
    let (ax, _) = f.map(&Point2::new(0.0, 0.0));
    let _ = writeln!(
        out,
        "<line x1=\"{ax:.2}\" y1=\"{top}\" x2=\"{ax:.2}\" y2=\"{bottom}\" stroke=\"#999\" stroke-dasharray=\"2 4\"/>\n\
         <text x=\"{:.2}\" y=\"{:.1}\" font-size=\"10\" fill=\"#777\">axis of revolution</text>",
        ax + 4.0,
        top + 12.0
    );
}

/// One panel (left edge at `left`): title, axes and the four drawings of
/// the curve `c`.
fn panel(out: &mut String, left: f64, c: &Drawn) {
    let f = Frame::new(
        left,
        c.controls
            .iter()
            .copied()
            .chain(c.dense.iter().map(|s| s.point)),
    );
    let centre = left + PANEL_WIDTH / 2.0;
    let _ = writeln!(
        out,
        "<text x=\"{centre:.1}\" y=\"20\" font-size=\"15\" font-weight=\"bold\" text-anchor=\"middle\">{}</text>\n\
         <text x=\"{centre:.1}\" y=\"37\" font-size=\"11\" text-anchor=\"middle\" fill=\"#444\">{}, {} control points</text>\n\
         <text x=\"{centre:.1}\" y=\"52\" font-size=\"11\" text-anchor=\"middle\" fill=\"#444\">{} uniform samples; \
         flattened to {} vertices, deviation ≤ {:.1e} (asked {:.0e})</text>",
        c.name,
        c.kind,
        c.controls.len(),
        c.uniform.len(),
        c.flat.samples.len(),
        c.flat.bound,
        c.tolerance
    );
    axes(out, &f);
    let _ = writeln!(
        out,
        "<polyline points=\"{}\" {CURVE_STYLE}/>",
        f.polyline(c.dense.iter().map(|s| s.point))
    );
    let _ = writeln!(
        out,
        "<polyline points=\"{}\" {POLYGON_STYLE}/>",
        f.polyline(c.controls.iter().copied())
    );
    for p in &c.controls {
        let (x, y) = f.map(p);
        let _ = writeln!(out, "{}", control_marker(x, y));
    }
    let _ = writeln!(
        out,
        "<polyline points=\"{}\" fill=\"none\" stroke=\"{FLAT_COLOR}\" stroke-width=\"1.2\"/>",
        f.polyline(c.flat.samples.iter().map(|s| s.point))
    );
    for s in &c.flat.samples {
        let (x, y) = f.map(&s.point);
        let _ = writeln!(out, "{}", flat_marker(x, y));
    }
    for s in &c.uniform {
        let (x, y) = f.map(&s.point);
        let _ = writeln!(out, "{}", sample_marker(x, y));
    }
}

/// A control point: a small grey square.
fn control_marker(x: f64, y: f64) -> String {
    format!(
        "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"6\" height=\"6\" fill=\"white\" stroke=\"#777\"/>",
        x - 3.0,
        y - 3.0
    )
}

/// A vertex of the flattening: a small open circle.
fn flat_marker(x: f64, y: f64) -> String {
    format!(
        "<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"2.5\" fill=\"white\" stroke=\"{FLAT_COLOR}\" stroke-width=\"1\"/>"
    )
}

/// A uniform sample: a small filled dot.
fn sample_marker(x: f64, y: f64) -> String {
    format!("<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"2\" fill=\"{SAMPLE_COLOR}\"/>")
}

/// The legend under the panels: one entry per thing drawn.
fn legend(out: &mut String, width: f64, segments: usize) {
    let top = PANEL_HEIGHT + 8.0;
    let _ = writeln!(
        out,
        "<rect x=\"10\" y=\"{top}\" width=\"{:.0}\" height=\"{:.0}\" fill=\"#fafafa\" stroke=\"#ccc\"/>",
        width - 20.0,
        LEGEND_HEIGHT - 16.0
    );
    let entries: [(String, String); 4] = [
        (
            format!("<line x1=\"0\" y1=\"0\" x2=\"36\" y2=\"0\" {CURVE_STYLE}/>"),
            format!("the curve ({DENSE_SEGMENTS} evaluations)"),
        ),
        (
            format!(
                "<line x1=\"0\" y1=\"0\" x2=\"36\" y2=\"0\" {POLYGON_STYLE}/>{}",
                control_marker(18.0, 0.0)
            ),
            "control polygon and control points".to_string(),
        ),
        (
            sample_marker(18.0, 0.0),
            format!("uniform samples ({segments} segments of the parameter)"),
        ),
        (
            format!(
                "<line x1=\"0\" y1=\"0\" x2=\"36\" y2=\"0\" stroke=\"{FLAT_COLOR}\" stroke-width=\"1.2\"/>{}",
                flat_marker(18.0, 0.0)
            ),
            "adaptive flattening (polyline and vertices)".to_string(),
        ),
    ];
    for (i, (symbol, label)) in entries.iter().enumerate() {
        let (col, row) = (i % 2, i / 2);
        let x = 30.0 + col as f64 * (width / 2.0);
        let y = top + 26.0 + row as f64 * 28.0;
        let _ = writeln!(
            out,
            "<g transform=\"translate({x:.1} {y:.1})\">{symbol}</g>\n\
             <text x=\"{:.1}\" y=\"{:.1}\" font-size=\"12\">{label}</text>",
            x + 48.0,
            y + 4.0
        );
    }
}

/// The figure: one panel per curve, side by side, each with its own axes
/// (equal scales), and the legend under them.
fn svg(curves: &[Drawn], segments: usize) -> String {
    let width = PANEL_WIDTH * curves.len() as f64;
    let height = PANEL_HEIGHT + LEGEND_HEIGHT;
    let mut out = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" \
         viewBox=\"0 0 {width:.0} {height:.0}\" font-family=\"sans-serif\">\n\
         <rect width=\"{width:.0}\" height=\"{height:.0}\" fill=\"white\"/>\n"
    );
    for (i, c) in curves.iter().enumerate() {
        panel(&mut out, i as f64 * PANEL_WIDTH, c);
    }
    legend(&mut out, width, segments);
    out.push_str("</svg>\n");
    out
}

fn run(options: &Options) -> Result<(), String> {
    let glass = wine_glass();
    let vase = vase();
    let curves = [
        Drawn {
            name: "wine_glass",
            kind: "uniform cubic B-spline",
            controls: glass.points().to_vec(),
            dense: glass.discretize(DENSE_SEGMENTS),
            uniform: glass.discretize(options.segments),
            flat: glass
                .flatten(options.tolerance)
                .map_err(|e| format!("wine glass: {e}"))?,
            tolerance: options.tolerance,
        },
        Drawn {
            name: "vase",
            kind: "cubic Bézier",
            controls: vase.points().to_vec(),
            dense: vase.discretize(DENSE_SEGMENTS),
            uniform: vase.discretize(options.segments),
            flat: vase
                .flatten(options.tolerance)
                .map_err(|e| format!("vase: {e}"))?,
            tolerance: options.tolerance,
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
    write("curves.svg".to_string(), svg(&curves, options.segments))
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
