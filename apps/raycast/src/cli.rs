//! The command line.
//!
//! ```text
//! raycast [SCENE] [-o OUT.png] [--samples N] [--seed S] [--quiet]
//! ```
//!
//! Without `SCENE` it renders the bundled showcase (`scenes/showcase.txt`
//! of the repository) to `out/showcase.png` of the repository
//! ([`crate::repo_root`]). Given a scene and no
//! `-o`, it writes `out/<scene name>.png` under the current folder. The
//! output's folder is created. Any error (bad arguments, a scene that does
//! not parse, an output that cannot be written) prints one line to stderr
//! and exits with status 1.
//!
//! The scene's warnings ([`crate::parse::ParseWarning`], e.g. a field of
//! view under 2 degrees) print to stderr before the render, one line each,
//! `raycast: FILE:LINE:COLUMN: warning: …`, also under `--quiet`: it
//! silences the progress bar and the report, not what points at a likely
//! mistake in the scene (as a compiler's warnings).

use std::io::{IsTerminal, Write};
use std::path::PathBuf;

use crate::effects::{Effects, MAX_SAMPLES};
use crate::image_out;
use crate::parse;
use crate::render::{self, Options};
use crate::report;

/// The help text.
pub const USAGE: &str = "\
usage: raycast [SCENE] [-o OUT.png] [--samples N] [--seed S] [--quiet]

Renders SCENE (default: the bundled scenes/showcase.txt) to a PNG.
  -o, --output OUT.png  where to write (default: out/<scene name>.png)
  --samples N           samples per pixel, overriding the scene's Render block
  --seed S              seed of the per-pixel random numbers (default 24301)
  -q, --quiet           no progress bar and no report (warnings still print)
  -h, --help            this text";

/// Parsed arguments.
#[derive(Debug, Clone, PartialEq)]
pub struct Args {
    pub scene: PathBuf,
    pub out: PathBuf,
    pub samples: Option<u32>,
    pub seed: Option<u64>,
    pub quiet: bool,
    pub help: bool,
}

/// Parses the arguments after the program name.
pub fn parse_args<I: IntoIterator<Item = String>>(args: I) -> Result<Args, String> {
    let mut scene = None;
    let mut out = None;
    let mut samples = None;
    let mut seed = None;
    let mut quiet = false;
    let mut help = false;
    let mut args = args.into_iter();
    while let Some(a) = args.next() {
        match a.as_str() {
            "-o" | "--output" | "--out" => {
                out = Some(PathBuf::from(
                    args.next()
                        .ok_or_else(|| format!("{a} needs a file name"))?,
                ));
            }
            "--samples" | "-s" => {
                let v = args.next().ok_or("--samples needs a number")?;
                let n: u32 = v
                    .parse()
                    .map_err(|_| format!("--samples needs a positive integer, not {v:?}"))?;
                if n == 0 {
                    return Err("--samples needs a positive integer, not 0".into());
                }
                if n > MAX_SAMPLES {
                    return Err(format!(
                        "--samples is {n}, more than the largest, {MAX_SAMPLES}"
                    ));
                }
                samples = Some(n);
            }
            "--seed" => {
                let v = args.next().ok_or("--seed needs a number")?;
                seed = Some(
                    v.parse()
                        .map_err(|_| format!("--seed needs a non-negative integer, not {v:?}"))?,
                );
            }
            "-q" | "--quiet" => quiet = true,
            "-h" | "--help" => help = true,
            s if s.starts_with('-') && s.len() > 1 => {
                return Err(format!("unknown option {s} (try --help)"));
            }
            _ => {
                if scene.is_some() {
                    return Err(format!("more than one scene given ({a}); try --help"));
                }
                scene = Some(PathBuf::from(a));
            }
        }
    }
    let root = crate::repo_root();
    let (scene, default_out) = match scene {
        Some(s) => {
            let stem = s
                .file_stem()
                .map_or_else(|| "render".into(), |n| n.to_string_lossy().into_owned());
            let out = PathBuf::from("out").join(format!("{stem}.png"));
            (s, out)
        }
        None => (
            root.join("scenes").join("showcase.txt"),
            root.join("out").join("showcase.png"),
        ),
    };
    Ok(Args {
        scene,
        out: out.unwrap_or(default_out),
        samples,
        seed,
        quiet,
        help,
    })
}

/// Runs the command line, warnings to stderr; the error is the one line to
/// print.
pub fn run<I: IntoIterator<Item = String>>(args: I) -> Result<(), String> {
    run_warning_to(args, &mut std::io::stderr())
}

/// Runs the command line, writing the scene's warnings to `warnings`.
pub fn run_warning_to<I: IntoIterator<Item = String>>(
    args: I,
    warnings: &mut dyn Write,
) -> Result<(), String> {
    let args = parse_args(args)?;
    if args.help {
        println!("{USAGE}");
        return Ok(());
    }
    let parsed = parse::parse_file_with_warnings(&args.scene).map_err(|e| e.to_string())?;
    for w in &parsed.warnings {
        // A warning that cannot be written is no reason to stop the render.
        let _ = writeln!(warnings, "raycast: {w}");
    }
    let scene = parsed.scene;
    render::check_size(scene.camera.width, scene.camera.height)
        .map_err(|e| format!("{}: {e}", args.scene.display()))?;
    image_out::check_writable(&args.out)?;

    let effects = Effects::of(&scene, args.samples);
    let mut options = Options {
        samples: args.samples,
        progress: !args.quiet && std::io::stderr().is_terminal(),
        ..Options::default()
    };
    if let Some(seed) = args.seed {
        options.seed = seed;
    }
    if !args.quiet {
        let (w, h) = (scene.camera.width as u64, scene.camera.height as u64);
        println!(
            "rendering {w} × {h} at {} sample{} a pixel: {} camera rays",
            effects.samples,
            if effects.samples == 1 { "" } else { "s" },
            w * h * u64::from(effects.samples)
        );
    }
    let (image, stats) =
        render::render(&scene, &options).map_err(|e| format!("{}: {e}", args.scene.display()))?;
    image_out::write_png(&image, effects.tone_map, &args.out)?;
    if !args.quiet {
        print!(
            "{}",
            report::summary(&args.scene, &args.out, &scene, &effects, &stats)
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn args(list: &[&str]) -> Result<Args, String> {
        parse_args(list.iter().map(|s| s.to_string()))
    }

    #[test]
    fn no_arguments_render_the_showcase_into_the_repository() {
        let a = args(&[]).unwrap();
        assert!(a.scene.ends_with("scenes/showcase.txt"));
        assert!(a.out.ends_with("out/showcase.png"));
        assert!(a.scene.is_absolute());
        assert!(a.scene.is_file(), "{} is missing", a.scene.display());
        assert_eq!(
            a.out.parent().and_then(Path::parent),
            Some(crate::repo_root())
        );
        assert_eq!(a.samples, None);
        assert!(!a.quiet);
    }

    #[test]
    fn options_are_read() {
        let a = args(&["s/x.txt", "--samples", "8", "-o", "y.png", "--quiet"]).unwrap();
        assert_eq!(a.scene, PathBuf::from("s/x.txt"));
        assert_eq!(a.out, PathBuf::from("y.png"));
        assert_eq!(a.samples, Some(8));
        assert!(a.quiet);
        assert_eq!(args(&["s/x.txt"]).unwrap().out, PathBuf::from("out/x.png"));
    }

    #[test]
    fn bad_arguments_are_errors() {
        assert!(args(&["--samples"]).is_err());
        assert!(args(&["--samples", "65536"]).is_ok());
        let e = args(&["--samples", "65537"]).expect_err("beyond the largest");
        assert!(e.contains("more than the largest, 65536"), "{e}");
        assert!(args(&["--samples", "0"]).is_err());
        assert!(args(&["--samples", "many"]).is_err());
        assert!(args(&["-o"]).is_err());
        assert!(args(&["--frobnicate"]).is_err());
        assert!(args(&["a.txt", "b.txt"]).is_err());
    }

    #[test]
    fn a_missing_scene_is_one_error_line() {
        let err = run(["/no/such/scene.txt".to_string(), "--quiet".into()]).unwrap_err();
        assert!(
            err.contains("/no/such/scene.txt") && !err.contains('\n'),
            "{err}"
        );
    }
}
