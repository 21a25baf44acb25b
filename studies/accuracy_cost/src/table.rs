//! The study's results as GitHub-flavoured markdown tables.
//!
//! Numbers are compact: errors as `1.2e-15`, rates as percentages with two
//! decimals (`0` when none, `<0.01` when fewer than 0.005 %), throughput as
//! `1.23 M` / `456 k`, memory as `12.3 KiB` / `4.5 MiB`, times as `1.23 ms` /
//! `45.6 µs`. Text columns are left-aligned, numbers right-aligned; a `|` in
//! text is escaped.

use crate::curves::CurvePoint;
use crate::model::Row;
use std::fmt::Write as _;

/// The intersection table: one line per row, in the order given.
pub fn intersection_table(rows: &[Row]) -> String {
    let header = [
        ("shape", false),
        ("method", false),
        ("setting", false),
        ("median error", true),
        ("max error", true),
        ("miss %", true),
        ("false hit %", true),
        ("far hit %", true),
        ("rays/s", true),
        ("memory", true),
        ("build", true),
    ];
    let body = rows.iter().map(|r| {
        let e = &r.errors;
        vec![
            text(r.shape),
            text(&r.series),
            text(&r.knob),
            error(e.median),
            error(e.max),
            percent(e.miss_rate),
            percent(e.false_hit_rate),
            percent(e.far_hit_rate),
            per_second(r.rays_per_second),
            bytes(r.memory_bytes),
            duration(r.build_seconds),
        ]
    });
    render(&header, body)
}

/// The curve table: one line per point, in the order given.
pub fn curve_table(points: &[CurvePoint]) -> String {
    let header = [
        ("curve", false),
        ("method", false),
        ("setting", false),
        ("samples", true),
        ("time", true),
        ("certified bound", true),
        ("measured deviation", true),
        ("measured / bound", true),
    ];
    let body = points.iter().map(|p| {
        vec![
            text(p.curve),
            text(p.method),
            text(&p.knob),
            p.samples.to_string(),
            duration(p.seconds),
            p.certified.map_or_else(|| "—".to_string(), error),
            error(p.measured),
            p.certified
                .filter(|b| *b > 0.0)
                .map_or_else(|| "—".to_string(), |b| format!("{:.2}", p.measured / b)),
        ]
    });
    render(&header, body)
}

/// A table from its header (name, right-aligned) and lines of cells.
fn render(header: &[(&str, bool)], body: impl Iterator<Item = Vec<String>>) -> String {
    let mut out = String::new();
    let names: Vec<&str> = header.iter().map(|h| h.0).collect();
    let _ = writeln!(out, "| {} |", names.join(" | "));
    let rules: Vec<&str> = header
        .iter()
        .map(|h| if h.1 { "---:" } else { ":---" })
        .collect();
    let _ = writeln!(out, "|{}|", rules.join("|"));
    for cells in body {
        debug_assert_eq!(cells.len(), header.len());
        let _ = writeln!(out, "| {} |", cells.join(" | "));
    }
    out
}

/// Text for a cell: pipes escaped, line breaks flattened.
fn text(s: &str) -> String {
    s.replace('|', "\\|").replace(['\n', '\r'], " ")
}

/// `1.2e-15`; `0`; `—` if not finite (no data).
pub fn error(x: f64) -> String {
    if !x.is_finite() {
        "—".into()
    } else if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.1e}")
    }
}

/// A fraction as a percentage: `12.34`, `0`, `<0.01`.
pub fn percent(fraction: f64) -> String {
    let p = 100.0 * fraction;
    if !p.is_finite() {
        "—".into()
    } else if p == 0.0 {
        "0".into()
    } else if p.abs() < 0.005 {
        "<0.01".into()
    } else {
        format!("{p:.2}")
    }
}

/// Three significant digits (for `1 ≤ v < 1000`: `1.23`, `45.6`, `789`).
fn three_digits(v: f64) -> String {
    if v >= 99.95 {
        format!("{v:.0}")
    } else if v >= 9.995 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

/// A value with a decimal prefix: `1.23 M`, `456 k`, `789`.
pub fn per_second(v: f64) -> String {
    if !v.is_finite() {
        return "—".into();
    }
    if v == 0.0 {
        return "0".into();
    }
    for (scale, unit) in [(1e9, " G"), (1e6, " M"), (1e3, " k")] {
        // Compare after rounding to three digits, so 999 999 is `1.00 M`.
        if v >= scale * 0.9995 {
            return format!("{}{unit}", three_digits(v / scale));
        }
    }
    three_digits(v)
}

/// Bytes with a binary prefix: `512 B`, `12.3 KiB`, `4.5 MiB`, `1.2 GiB`.
pub fn bytes(n: usize) -> String {
    let v = n as f64;
    for (scale, unit) in [(1u64 << 30, "GiB"), (1 << 20, "MiB"), (1 << 10, "KiB")] {
        let s = scale as f64;
        if v >= s * 0.9995 {
            return format!("{:.1} {unit}", v / s);
        }
    }
    format!("{n} B")
}

/// Seconds with a unit: `1.23 s`, `12.3 ms`, `45.6 µs`, `789 ns`; `0`.
pub fn duration(seconds: f64) -> String {
    if !seconds.is_finite() {
        return "—".into();
    }
    if seconds == 0.0 {
        return "0".into();
    }
    for (scale, unit) in [(1.0, " s"), (1e-3, " ms"), (1e-6, " µs")] {
        if seconds >= scale * 0.9995 {
            return format!("{}{unit}", three_digits(seconds / scale));
        }
    }
    format!("{} ns", three_digits(seconds * 1e9))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ErrorStats;

    /// Splits a table line into cells at unescaped pipes.
    fn cells(line: &str) -> Vec<String> {
        assert!(line.starts_with('|') && line.ends_with('|'), "{line}");
        let inner = &line[1..line.len() - 1];
        let mut out = vec![String::new()];
        let mut escaped = false;
        for c in inner.chars() {
            if c == '|' && !escaped {
                out.push(String::new());
            } else {
                out.last_mut().unwrap().push(c);
            }
            escaped = c == '\\';
        }
        out.iter().map(|c| c.trim().to_string()).collect()
    }

    fn row(shape: &'static str, series: &str, knob: &str) -> Row {
        Row {
            shape,
            series: series.into(),
            knob: knob.into(),
            errors: ErrorStats {
                rays: 1000,
                reference_hits: 600,
                median: 1.234e-15,
                max: 0.0,
                miss_rate: 0.0123,
                false_hit_rate: 0.0,
                far_hit_rate: 0.00001,
            },
            rays_per_second: 1_234_567.0,
            memory_bytes: 12_595,
            build_seconds: 4.56e-5,
            batch_mismatches: None,
        }
    }

    #[test]
    fn intersection_table_shape_and_values() {
        let rows = [
            row("vase", "exact", "tol 1e-6"),
            row("wine glass", "Newton | depth 3", "d = 3"),
        ];
        let table = intersection_table(&rows);
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines.len(), 2 + rows.len());
        let widths: Vec<usize> = lines.iter().map(|l| cells(l).len()).collect();
        assert!(widths.iter().all(|&w| w == 11), "{widths:?}");
        assert_eq!(cells(lines[0])[0], "shape");
        assert_eq!(cells(lines[0])[10], "build");
        assert!(
            cells(lines[1])
                .iter()
                .all(|c| c.starts_with(":---") || c == "---:")
        );
        let first = cells(lines[2]);
        assert_eq!(
            first,
            [
                "vase", "exact", "tol 1e-6", "1.2e-15", "0", "1.23", "0", "<0.01", "1.23 M",
                "12.3 KiB", "45.6 µs"
            ]
        );
        assert_eq!(cells(lines[3])[1], "Newton \\| depth 3");
    }

    #[test]
    fn curve_table_shape_and_values() {
        let points = [
            CurvePoint {
                curve: "vase",
                method: "adaptive",
                knob: "tol 1e-4".into(),
                samples: 17,
                seconds: 1.5e-6,
                certified: Some(8.0e-5),
                measured: 6.0e-5,
            },
            CurvePoint {
                curve: "vase",
                method: "uniform",
                knob: "n = 64".into(),
                samples: 65,
                seconds: 2.0e-3,
                certified: None,
                measured: 2.5e-4,
            },
        ];
        let table = curve_table(&points);
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines.len(), 4);
        assert!(lines.iter().all(|l| cells(l).len() == 8));
        assert_eq!(
            cells(lines[2]),
            [
                "vase", "adaptive", "tol 1e-4", "17", "1.50 µs", "8.0e-5", "6.0e-5", "0.75"
            ]
        );
        assert_eq!(
            cells(lines[3]),
            [
                "vase", "uniform", "n = 64", "65", "2.00 ms", "—", "2.5e-4", "—"
            ]
        );
    }

    #[test]
    fn number_formats() {
        assert_eq!(per_second(1_234_567.0), "1.23 M");
        assert_eq!(per_second(456_000.0), "456 k");
        assert_eq!(per_second(45_600.0), "45.6 k");
        assert_eq!(per_second(999_999.0), "1.00 M");
        assert_eq!(per_second(2.5e9), "2.50 G");
        assert_eq!(per_second(789.0), "789");
        assert_eq!(bytes(0), "0 B");
        assert_eq!(bytes(1000), "1000 B");
        assert_eq!(bytes(1024), "1.0 KiB");
        assert_eq!(bytes(12_595), "12.3 KiB");
        assert_eq!(bytes(4_718_592), "4.5 MiB");
        assert_eq!(error(1.234e-15), "1.2e-15");
        assert_eq!(error(3.0e-3), "3.0e-3");
        assert_eq!(error(0.0), "0");
        assert_eq!(error(f64::NAN), "—");
        assert_eq!(percent(0.5), "50.00");
        assert_eq!(percent(0.0), "0");
        assert_eq!(percent(1e-6), "<0.01");
        assert_eq!(duration(1.234), "1.23 s");
        assert_eq!(duration(0.0123), "12.3 ms");
        assert_eq!(duration(4.56e-5), "45.6 µs");
        assert_eq!(duration(7.89e-7), "789 ns");
        assert_eq!(duration(0.0), "0");
    }
}
