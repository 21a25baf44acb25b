//! The summary printed after a render: what was simulated and what it cost.

use std::fmt::Write;
use std::path::Path;

use crate::effects::Effects;
use crate::scene::{Integrator, Scene};
use crate::stats::Stats;

/// `1234567` → `"1,234,567"`.
pub fn thousands(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, ch) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

/// The report for the render of `scene` (read from `scene_path`) written to
/// `out`.
pub fn summary(
    scene_path: &Path,
    out: &Path,
    scene: &Scene,
    effects: &Effects,
    stats: &Stats,
) -> String {
    let mut s = String::new();
    let name = scene_path.file_name().map_or_else(
        || scene_path.display().to_string(),
        |n| n.to_string_lossy().into(),
    );
    let integrator = match effects.integrator {
        Integrator::Whitted => "Whitted (Phong, recursive)",
        Integrator::Path => "path tracing",
    };
    let _ = writeln!(s, "scene       {name} ({})", scene_path.display());
    let _ = writeln!(
        s,
        "image       {}×{}, {} sample{} per pixel → {}",
        scene.camera.width,
        scene.camera.height,
        effects.samples,
        if effects.samples == 1 { "" } else { "s" },
        out.display()
    );
    if effects.integrator == Integrator::Path || effects.reflection || effects.refraction {
        let _ = writeln!(
            s,
            "integrator  {integrator}, max depth {}",
            effects.max_depth
        );
    } else {
        let _ = writeln!(s, "integrator  {integrator}");
    }
    let names = effects.names();
    if names.is_empty() {
        let _ = writeln!(
            s,
            "effects     none (base format: primary rays, Phong shading)"
        );
    } else {
        let _ = writeln!(s, "effects     {}", names.join(", "));
    }
    let r = &stats.rays;
    let _ = writeln!(
        s,
        "rays        {} total: primary {}, shadow {}, reflection {}, refraction {}, indirect {}",
        thousands(r.total()),
        thousands(r.primary),
        thousands(r.shadow),
        thousands(r.reflection),
        thousands(r.refraction),
        thousands(r.indirect)
    );
    if stats.non_finite_samples > 0 {
        let _ = writeln!(
            s,
            "warning     {} camera samples were not finite and count as black",
            thousands(stats.non_finite_samples)
        );
    }
    let secs = stats.wall.as_secs_f64();
    let _ = writeln!(
        s,
        "revolution  {} exact intersection calls, {:.3} s of thread time = {:.1}% of the render \
         (Σ time in revolve's intersector over all threads ÷ (wall time × {} threads))",
        thousands(stats.intersect.revolution_calls),
        stats.intersect.revolution_nanos as f64 * 1e-9,
        100.0 * stats.revolution_share(),
        stats.threads
    );
    let rate = if secs > 0.0 {
        r.total() as f64 / secs / 1e6
    } else {
        0.0
    };
    let _ = writeln!(
        s,
        "time        {secs:.3} s wall on {} threads ({rate:.2} M rays/s), world built in {:.3} s",
        stats.threads,
        stats.build.as_secs_f64()
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thousands_groups_digits() {
        assert_eq!(thousands(0), "0");
        assert_eq!(thousands(999), "999");
        assert_eq!(thousands(1000), "1,000");
        assert_eq!(thousands(1_234_567), "1,234,567");
    }
}
