//! Log–log scatter plots as self-contained SVG.
//!
//! [`loglog_svg`] draws one plot, [`loglog_svg_panels`] several side by side
//! sharing their axis ranges and one legend (e.g. one panel per shape). Both
//! axes are base-10 logarithmic with a grid line and a label (`10ⁿ`, the
//! exponent as a superscript) at every decade, fainter grid lines at 2…9 ×
//! 10ⁿ when there are few decades, and ranges rounded out to whole decades.
//!
//! Every series gets a colour (Okabe–Ito, distinguishable with colour-blind
//! vision), a marker shape (filled or hollow, so series stay apart in
//! greyscale) and, when connected, a dash pattern. A series keeps its style
//! in every panel (styles are assigned by name, in order of first
//! appearance).
//!
//! Points with a non-positive or non-finite coordinate cannot be drawn on log
//! axes and are skipped; a connected series' line is broken at a skipped
//! point. Callers who want zero errors shown should clamp them to a floor
//! (e.g. `1e-17`) themselves and say so.

use std::fmt::Write as _;
use std::path::Path;

/// One series of points.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The legend entry.
    pub name: String,
    /// `(x, y)` points; those with a coordinate that is not finite and
    /// positive are skipped.
    pub points: Vec<(f64, f64)>,
    /// Whether to join consecutive points, in the order given, by a line.
    pub connect: bool,
}

/// One panel of a multi-panel plot.
#[derive(Debug, Clone, Copy)]
pub struct Panel<'a> {
    /// The panel's title, above it.
    pub title: &'a str,
    /// Its series.
    pub series: &'a [Series],
}

/// Writes `svg` to `path`, creating the parent directory if needed.
pub fn write(path: &Path, svg: &str) -> std::io::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(path, svg)
}

/// One log–log plot of `series`, 900 × 600, legend on the right.
pub fn loglog_svg(title: &str, x_label: &str, y_label: &str, series: &[Series]) -> String {
    loglog_svg_panels(title, x_label, y_label, &[Panel { title: "", series }])
}

// Layout (pixels).
const LEFT: f64 = 85.0;
const TOP: f64 = 70.0;
const BOTTOM: f64 = 70.0;
const HEIGHT: f64 = 600.0;
const GAP: f64 = 80.0;
const LEGEND: f64 = 250.0;
const RIGHT: f64 = 15.0;
const SINGLE_PLOT_WIDTH: f64 = 900.0 - LEFT - LEGEND - RIGHT;
const PANEL_PLOT_WIDTH: f64 = 480.0;

const COLOURS: [&str; 7] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000",
];
const DASHES: [&str; 5] = ["", "7 4", "2 3", "9 3 2 3", "4 2 1 2 1 2"];

#[derive(Debug, Clone, Copy)]
enum Shape {
    Circle,
    Square,
    TriangleUp,
    Diamond,
    TriangleDown,
    Cross,
    Plus,
    Star,
}

const SHAPES: [(Shape, bool); 8] = [
    (Shape::Circle, true),
    (Shape::Square, false),
    (Shape::TriangleUp, true),
    (Shape::Diamond, false),
    (Shape::TriangleDown, false),
    (Shape::Cross, false),
    (Shape::Square, true),
    (Shape::Circle, false),
];

/// The look of one series.
#[derive(Debug, Clone, Copy)]
struct Style {
    colour: &'static str,
    shape: Shape,
    filled: bool,
    dash: &'static str,
}

impl Style {
    /// The SVG `stroke-dasharray` attribute (with its leading space), or
    /// nothing for a solid line.
    fn dash_attribute(&self) -> String {
        if self.dash.is_empty() {
            String::new()
        } else {
            format!(r#" stroke-dasharray="{}""#, self.dash)
        }
    }

    fn of(index: usize) -> Self {
        // Cycle shapes and colours with coprime periods, so that the first
        // 56 series all differ in (colour, shape).
        let (shape, filled) = SHAPES[index % SHAPES.len()];
        let shape = if index >= SHAPES.len() && index % 3 == 0 {
            Shape::Star
        } else if index >= SHAPES.len() && index % 3 == 1 {
            Shape::Plus
        } else {
            shape
        };
        Style {
            colour: COLOURS[index % COLOURS.len()],
            shape,
            filled,
            dash: DASHES[index % DASHES.len()],
        }
    }
}

/// A logarithmic axis: decades `lo ..= hi` mapped linearly (in `log₁₀`) onto
/// pixels `from ..= to`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LogAxis {
    /// The lowest decade (exponent).
    pub lo: i32,
    /// The highest decade, `> lo`.
    pub hi: i32,
    /// The pixel of `10^lo`.
    pub from: f64,
    /// The pixel of `10^hi`.
    pub to: f64,
}

impl LogAxis {
    /// The axis covering `values` (finite, positive; others ignored), rounded
    /// out to whole decades, at least one decade wide; `1 … 10` if there are
    /// none.
    pub fn covering(values: impl IntoIterator<Item = f64>, from: f64, to: f64) -> Self {
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.into_iter().filter(|v| drawable(*v)) {
            min = min.min(v.log10());
            max = max.max(v.log10());
        }
        let (lo, hi) = if min.is_finite() {
            // A small slack so that exact powers of ten are not pushed out a
            // decade by the rounding of `log10`.
            ((min + 1e-9).floor() as i32, (max - 1e-9).ceil() as i32)
        } else {
            (0, 1)
        };
        let hi = hi.max(lo + 1);
        LogAxis { lo, hi, from, to }
    }

    /// The pixel of `v > 0`.
    pub fn map(&self, v: f64) -> f64 {
        let s = (v.log10() - f64::from(self.lo)) / f64::from(self.hi - self.lo);
        self.from + (self.to - self.from) * s
    }

    fn decades(&self) -> i32 {
        self.hi - self.lo
    }

    /// Label every `step`-th decade, so that at most about 12 are labelled.
    fn label_step(&self) -> i32 {
        ((self.decades() + 11) / 12).max(1)
    }
}

fn drawable(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

/// Several log–log panels side by side, sharing axis ranges, labels and one
/// legend on the right. 600 px high; 900 px wide for one panel, about 560 px
/// more per extra panel.
pub fn loglog_svg_panels(
    title: &str,
    x_label: &str,
    y_label: &str,
    panels: &[Panel<'_>],
) -> String {
    let count = panels.len().max(1);
    let plot_w = if count == 1 {
        SINGLE_PLOT_WIDTH
    } else {
        PANEL_PLOT_WIDTH
    };
    let width = LEFT + count as f64 * plot_w + (count - 1) as f64 * GAP + RIGHT + LEGEND;
    let plot_h = HEIGHT - TOP - BOTTOM;
    let all_points = || {
        panels
            .iter()
            .flat_map(|p| p.series.iter())
            .flat_map(|s| s.points.iter().copied())
            .filter(|&(x, y)| drawable(x) && drawable(y))
    };
    let x_range = LogAxis::covering(all_points().map(|p| p.0), 0.0, plot_w);
    let y_range = LogAxis::covering(all_points().map(|p| p.1), 0.0, plot_h);

    // Styles by name, in order of first appearance.
    let mut names: Vec<&str> = Vec::new();
    for s in panels.iter().flat_map(|p| p.series.iter()) {
        if !names.contains(&s.name.as_str()) {
            names.push(&s.name);
        }
    }
    let style_of = |name: &str| Style::of(names.iter().position(|n| *n == name).unwrap_or(0));

    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{HEIGHT:.0}" viewBox="0 0 {width:.0} {HEIGHT:.0}" font-family="Helvetica, Arial, sans-serif">"#
    );
    let _ = writeln!(svg, "<title>{}</title>", escape(title));
    let _ = writeln!(
        svg,
        r##"<rect x="0" y="0" width="{width:.0}" height="{HEIGHT:.0}" fill="#ffffff"/>"##
    );
    let _ = writeln!(
        svg,
        r#"<text x="{:.1}" y="28" font-size="19" font-weight="bold" text-anchor="middle">{}</text>"#,
        (LEFT + width - LEGEND - RIGHT) / 2.0,
        escape(title)
    );

    for (k, panel) in panels.iter().enumerate() {
        let x0 = LEFT + k as f64 * (plot_w + GAP);
        let x_axis = LogAxis {
            from: x0,
            to: x0 + plot_w,
            ..x_range
        };
        let y_axis = LogAxis {
            from: TOP + plot_h,
            to: TOP,
            ..y_range
        };
        draw_panel(
            &mut svg, panel, &x_axis, &y_axis, x_label, y_label, &style_of,
        );
    }
    draw_legend(&mut svg, &names, &style_of, width - LEGEND - RIGHT + 20.0);
    svg.push_str("</svg>\n");
    svg
}

fn draw_panel(
    svg: &mut String,
    panel: &Panel<'_>,
    x: &LogAxis,
    y: &LogAxis,
    x_label: &str,
    y_label: &str,
    style_of: &dyn Fn(&str) -> Style,
) {
    let (left, right, top, bottom) = (x.from, x.to, y.to, y.from);
    let _ = writeln!(svg, "<g>");
    if !panel.title.is_empty() {
        let _ = writeln!(
            svg,
            r#"<text x="{:.1}" y="{:.1}" font-size="15" text-anchor="middle">{}</text>"#,
            (left + right) / 2.0,
            top - 14.0,
            escape(panel.title)
        );
    }
    // Minor grid at 2…9 × 10ⁿ when the decades are wide enough to show it.
    let minor = |axis: &LogAxis| axis.decades() <= 8;
    let mut grid = |axis: &LogAxis, vertical: bool| {
        for d in axis.lo..=axis.hi {
            let p = axis.map(10f64.powi(d));
            let (class, x1, y1, x2, y2) = if vertical {
                ("gx", p, top, p, bottom)
            } else {
                ("gy", left, p, right, p)
            };
            let _ = writeln!(
                svg,
                r##"<line class="{class}" data-decade="{d}" x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}" stroke="#c8c8c8" stroke-width="1"/>"##
            );
            if minor(axis) && d < axis.hi {
                for m in 2..=9 {
                    let p = axis.map(f64::from(m) * 10f64.powi(d));
                    let (x1, y1, x2, y2) = if vertical {
                        (p, top, p, bottom)
                    } else {
                        (left, p, right, p)
                    };
                    let _ = writeln!(
                        svg,
                        r##"<line x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}" stroke="#ececec" stroke-width="1"/>"##
                    );
                }
            }
        }
    };
    grid(x, true);
    grid(y, false);
    let _ = writeln!(
        svg,
        r##"<rect x="{left:.2}" y="{top:.2}" width="{:.2}" height="{:.2}" fill="none" stroke="#333333" stroke-width="1.2"/>"##,
        right - left,
        bottom - top
    );
    // Decade labels.
    for d in (x.lo..=x.hi).filter(|d| (d - x.lo) % x.label_step() == 0) {
        let p = x.map(10f64.powi(d));
        let _ = writeln!(
            svg,
            r##"<line x1="{p:.2}" y1="{bottom:.2}" x2="{p:.2}" y2="{:.2}" stroke="#333333"/>"##,
            bottom + 5.0
        );
        let _ = writeln!(
            svg,
            r#"<text x="{p:.2}" y="{:.2}" font-size="13" text-anchor="middle">{}</text>"#,
            bottom + 22.0,
            power_of_ten(d)
        );
    }
    for d in (y.lo..=y.hi).filter(|d| (d - y.lo) % y.label_step() == 0) {
        let p = y.map(10f64.powi(d));
        let _ = writeln!(
            svg,
            r##"<line x1="{:.2}" y1="{p:.2}" x2="{left:.2}" y2="{p:.2}" stroke="#333333"/>"##,
            left - 5.0
        );
        let _ = writeln!(
            svg,
            r#"<text x="{:.2}" y="{:.2}" font-size="13" text-anchor="end">{}</text>"#,
            left - 8.0,
            p + 5.0,
            power_of_ten(d)
        );
    }
    let _ = writeln!(
        svg,
        r#"<text x="{:.2}" y="{:.2}" font-size="14" text-anchor="middle">{}</text>"#,
        (left + right) / 2.0,
        bottom + 50.0,
        escape(x_label)
    );
    let (ly, lx) = ((top + bottom) / 2.0, left - 58.0);
    let _ = writeln!(
        svg,
        r#"<text x="{lx:.2}" y="{ly:.2}" font-size="14" text-anchor="middle" transform="rotate(-90 {lx:.2} {ly:.2})">{}</text>"#,
        escape(y_label)
    );

    // Lines first, then markers on top.
    for s in panel.series {
        let style = style_of(&s.name);
        if !s.connect {
            continue;
        }
        let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        for &(px, py) in &s.points {
            if drawable(px) && drawable(py) {
                runs.last_mut()
                    .expect("non-empty")
                    .push((x.map(px), y.map(py)));
            } else if !runs.last().expect("non-empty").is_empty() {
                runs.push(Vec::new());
            }
        }
        for run in runs.iter().filter(|r| r.len() >= 2) {
            let coords: Vec<String> = run.iter().map(|(a, b)| format!("{a:.2},{b:.2}")).collect();
            let dash = style.dash_attribute();
            let _ = writeln!(
                svg,
                r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="1.6"{dash}/>"#,
                coords.join(" "),
                style.colour
            );
        }
    }
    for s in panel.series {
        let style = style_of(&s.name);
        let _ = writeln!(svg, "<g><title>{}</title>", escape(&s.name));
        for &(px, py) in s
            .points
            .iter()
            .filter(|(a, b)| drawable(*a) && drawable(*b))
        {
            svg.push_str(&marker(&style, x.map(px), y.map(py)));
        }
        let _ = writeln!(svg, "</g>");
    }
    let _ = writeln!(svg, "</g>");
}

fn draw_legend(svg: &mut String, names: &[&str], style_of: &dyn Fn(&str) -> Style, x: f64) {
    let _ = writeln!(svg, "<g>");
    for (i, name) in names.iter().enumerate() {
        let style = style_of(name);
        let y = TOP + 10.0 + 24.0 * i as f64;
        let dash = style.dash_attribute();
        let _ = writeln!(
            svg,
            r#"<line x1="{x:.2}" y1="{y:.2}" x2="{:.2}" y2="{y:.2}" stroke="{}" stroke-width="1.6"{dash}/>"#,
            x + 30.0,
            style.colour
        );
        svg.push_str(&marker(&style, x + 15.0, y));
        let _ = writeln!(
            svg,
            r#"<text x="{:.2}" y="{:.2}" font-size="13">{}</text>"#,
            x + 38.0,
            y + 4.5,
            escape(name)
        );
    }
    let _ = writeln!(svg, "</g>");
}

/// The SVG element of a marker centred on `(x, y)`.
fn marker(style: &Style, x: f64, y: f64) -> String {
    const R: f64 = 4.5;
    let fill = if style.filled {
        style.colour
    } else {
        "#ffffff"
    };
    let paint = format!(
        r#"fill="{fill}" stroke="{}" stroke-width="1.5""#,
        style.colour
    );
    let polygon = |pts: &[(f64, f64)]| {
        let p: Vec<String> = pts
            .iter()
            .map(|(dx, dy)| format!("{:.2},{:.2}", x + dx * R, y + dy * R))
            .collect();
        format!("<polygon points=\"{}\" {paint}/>\n", p.join(" "))
    };
    match style.shape {
        Shape::Circle => format!("<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"{R}\" {paint}/>\n"),
        Shape::Square => polygon(&[(-0.9, -0.9), (0.9, -0.9), (0.9, 0.9), (-0.9, 0.9)]),
        Shape::TriangleUp => polygon(&[(0.0, -1.2), (1.1, 0.8), (-1.1, 0.8)]),
        Shape::TriangleDown => polygon(&[(0.0, 1.2), (1.1, -0.8), (-1.1, -0.8)]),
        Shape::Diamond => polygon(&[(0.0, -1.25), (1.0, 0.0), (0.0, 1.25), (-1.0, 0.0)]),
        Shape::Star => {
            let pts: Vec<(f64, f64)> = (0..10)
                .map(|k| {
                    let a = std::f64::consts::PI * (k as f64 / 5.0 - 0.5);
                    let r = if k % 2 == 0 { 1.3 } else { 0.55 };
                    (r * a.cos(), r * a.sin())
                })
                .collect();
            polygon(&pts)
        }
        Shape::Cross | Shape::Plus => {
            let d = if matches!(style.shape, Shape::Cross) {
                [(-1.0, -1.0, 1.0, 1.0), (-1.0, 1.0, 1.0, -1.0)]
            } else {
                [(-1.2, 0.0, 1.2, 0.0), (0.0, -1.2, 0.0, 1.2)]
            };
            d.iter()
                .map(|(a, b, c, e)| {
                    format!(
                        "<line x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\" stroke=\"{}\" stroke-width=\"2\"/>\n",
                        x + a * R,
                        y + b * R,
                        x + c * R,
                        y + e * R,
                        style.colour
                    )
                })
                .collect()
        }
    }
}

/// `10ⁿ` as SVG text content: the exponent as a raised, smaller `tspan`,
/// with a true minus sign.
fn power_of_ten(d: i32) -> String {
    let exponent = if d < 0 {
        format!("\u{2212}{}", -d)
    } else {
        d.to_string()
    };
    format!(r#"10<tspan dy="-7" font-size="10">{exponent}</tspan>"#)
}

/// `s` with the XML special characters replaced by entities.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks that every tag is closed in order (a crude well-formedness
    /// check: no attribute values containing `>`, which `escape` ensures).
    fn assert_well_formed(svg: &str) {
        let mut stack: Vec<&str> = Vec::new();
        let mut rest = svg;
        while let Some(open) = rest.find('<') {
            let close = rest[open..].find('>').expect("unterminated tag") + open;
            let tag = &rest[open + 1..close];
            assert!(!tag.contains('<'), "'<' inside a tag: {tag}");
            if let Some(name) = tag.strip_prefix('/') {
                assert_eq!(stack.pop(), Some(name.trim()), "mismatched </{name}>");
            } else if !tag.ends_with('/') && !tag.starts_with('?') && !tag.starts_with('!') {
                let name = tag.split_whitespace().next().expect("tag name");
                stack.push(name);
            }
            rest = &rest[close + 1..];
        }
        assert!(stack.is_empty(), "unclosed tags: {stack:?}");
        // Text between tags holds no raw '&' other than entities.
        for (i, _) in svg.match_indices('&') {
            let entity = &svg[i..svg[i..].find(';').map_or(svg.len(), |j| i + j + 1)];
            assert!(
                ["&amp;", "&lt;", "&gt;", "&quot;", "&apos;"].contains(&entity),
                "raw '&': {entity}"
            );
        }
    }

    fn sample() -> Vec<Series> {
        vec![
            Series {
                name: "exact <tol> & \"friends\"".into(),
                points: vec![(1e5, 1e-15), (2e5, 3e-14), (1e6, 2e-12)],
                connect: true,
            },
            Series {
                name: "Newton depth 3".into(),
                points: vec![
                    (3e6, 1e-9),
                    (0.0, 1e-3),
                    (4e6, -1.0),
                    (5e6, f64::NAN),
                    (7e6, 1e-6),
                ],
                connect: true,
            },
            Series {
                name: "parry TriMesh".into(),
                points: vec![(2e7, 1e-4), (f64::INFINITY, 1e-2)],
                connect: false,
            },
        ]
    }

    /// The `x1` of every decade grid line of class `class`, by decade.
    fn grid_positions(svg: &str, class: &str) -> Vec<(i32, f64)> {
        let needle = format!(r#"class="{class}" data-decade=""#);
        svg.match_indices(&needle)
            .map(|(i, _)| {
                let rest = &svg[i + needle.len()..];
                let decade: i32 = rest[..rest.find('"').unwrap()].parse().unwrap();
                let key = if class == "gx" { "x1=\"" } else { "y1=\"" };
                let at = rest.find(key).unwrap() + key.len();
                let value: f64 = rest[at..at + rest[at..].find('"').unwrap()]
                    .parse()
                    .unwrap();
                (decade, value)
            })
            .collect()
    }

    #[test]
    fn single_plot_is_well_formed_and_complete() {
        let svg = loglog_svg("Cost <vs> accuracy", "rays/s", "median |Δt|", &sample());
        assert_well_formed(&svg);
        assert_eq!(svg.matches("<svg").count(), 1);
        assert_eq!(svg.matches("</svg>").count(), 1);
        assert!(svg.contains(r#"viewBox="0 0 900 600""#));
        assert!(svg.contains("Cost &lt;vs&gt; accuracy"));
        for s in sample() {
            assert!(svg.contains(&escape(&s.name)), "missing {}", s.name);
        }
        assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
        // 3 + 2 + 1 drawable points, plus one legend marker per series.
        // (The first three styles are circle, square and triangle.)
        let markers = svg.matches("<circle").count() + svg.matches("<polygon").count();
        assert_eq!(markers, 6 + 3);
    }

    #[test]
    fn decades_have_equal_lengths() {
        let svg = loglog_svg("t", "x", "y", &sample());
        let xs = grid_positions(&svg, "gx");
        // x spans 1e5 … 2e7 → decades 5 … 8.
        assert_eq!(xs.iter().map(|p| p.0).collect::<Vec<_>>(), vec![5, 6, 7, 8]);
        let ys = grid_positions(&svg, "gy");
        assert_eq!(ys.first().unwrap().0, -15);
        assert_eq!(ys.last().unwrap().0, -4);
        for grid in [xs, ys] {
            let step = grid[1].1 - grid[0].1;
            assert!(step.abs() > 10.0);
            for w in grid.windows(2) {
                assert!((w[1].1 - w[0].1 - step).abs() <= 0.011, "{grid:?}");
            }
        }
    }

    #[test]
    fn axis_maps_logarithmically() {
        let axis = LogAxis::covering([1e-3, 5e-1, 0.0, -2.0, f64::NAN], 100.0, 500.0);
        assert_eq!((axis.lo, axis.hi), (-3, 0));
        assert_eq!(axis.map(1e-3), 100.0);
        assert!((axis.map(1.0) - 500.0).abs() < 1e-9);
        let decade = axis.map(1e-1) - axis.map(1e-2);
        assert!((decade - 400.0 / 3.0).abs() < 1e-9);
        // An exact power of ten is a decade boundary, not one decade beyond.
        let exact = LogAxis::covering([1e-3, 1e3], 0.0, 1.0);
        assert_eq!((exact.lo, exact.hi), (-3, 3));
        let single = LogAxis::covering([7.0], 0.0, 1.0);
        assert_eq!((single.lo, single.hi), (0, 1));
        let none = LogAxis::covering([0.0], 0.0, 1.0);
        assert_eq!((none.lo, none.hi), (0, 1));
    }

    #[test]
    fn connected_line_breaks_at_skipped_points() {
        let series = [Series {
            name: "a".into(),
            points: vec![
                (1.0, 1.0),
                (2.0, 2.0),
                (3.0, 0.0),
                (4.0, 4.0),
                (5.0, 5.0),
                (6.0, 6.0),
            ],
            connect: true,
        }];
        let svg = loglog_svg("t", "x", "y", &series);
        assert_eq!(svg.matches("<polyline").count(), 2);
        let unconnected = [Series {
            connect: false,
            ..series[0].clone()
        }];
        let svg = loglog_svg("t", "x", "y", &unconnected);
        assert_eq!(svg.matches("<polyline").count(), 0);
    }

    #[test]
    fn panels_share_styles_and_ranges() {
        let a = sample();
        let b = vec![sample()[1].clone(), sample()[0].clone()];
        let svg = loglog_svg_panels(
            "two",
            "x",
            "y",
            &[
                Panel {
                    title: "vase",
                    series: &a,
                },
                Panel {
                    title: "wine glass",
                    series: &b,
                },
            ],
        );
        assert_well_formed(&svg);
        assert!(svg.contains(">vase<") && svg.contains(">wine glass<"));
        // One legend entry per distinct name.
        assert_eq!(svg.matches(">Newton depth 3</text>").count(), 1);
        // Both panels have the same decades, one panel-width apart.
        let xs = grid_positions(&svg, "gx");
        assert_eq!(xs.len(), 8);
        let shift = xs[4].1 - xs[0].1;
        assert!((shift - (PANEL_PLOT_WIDTH + GAP)).abs() < 0.011);
        for i in 0..4 {
            assert_eq!(xs[i].0, xs[i + 4].0);
            assert!((xs[i + 4].1 - xs[i].1 - shift).abs() < 0.011);
        }
    }

    #[test]
    fn styles_differ() {
        for i in 0..20 {
            for j in 0..i {
                let (a, b) = (Style::of(i), Style::of(j));
                let same_shape = std::mem::discriminant(&a.shape)
                    == std::mem::discriminant(&b.shape)
                    && a.filled == b.filled;
                assert!(!(a.colour == b.colour && same_shape), "styles {i} and {j}");
            }
        }
        for i in 0..8 {
            for j in 0..i {
                assert!(
                    std::mem::discriminant(&Style::of(i).shape)
                        != std::mem::discriminant(&Style::of(j).shape)
                        || Style::of(i).filled != Style::of(j).filled,
                    "greyscale: styles {i} and {j}"
                );
            }
        }
    }
}
