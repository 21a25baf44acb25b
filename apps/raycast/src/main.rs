//! The ray caster: `cargo run --release -p raycast -- SCENE -o OUT.png`.
//!
//! Reads a scene in the course framework's format (SCENE_FORMAT.md), decides
//! which effects it calls for ([`effects`]), renders it in parallel with the
//! Whitted ray tracer ([`whitted`]) or the path tracer ([`path`]), writes a
//! PNG and reports the effects turned on, the rays traced by kind and the
//! time spent in revolve's exact intersector. See [`cli`] for the options.

mod camera;
mod cli;
mod effects;
mod geometry;
mod image_out;
mod lights;
mod optics;
mod parse;
mod path;
mod png_file;
mod render;
mod report;
mod sampling;
mod scale;
mod scene;
mod shading;
mod stats;
mod texture;
mod tracer;
mod whitted;

#[cfg(test)]
mod render_tests;
#[cfg(test)]
mod temp_dir;

#[cfg(test)]
mod batch_tests;

#[cfg(test)]
mod golden_tests;

#[cfg(test)]
mod shadow_tests;

#[cfg(test)]
mod limits_tests;

#[cfg(test)]
mod fuzz_tests;

use std::path::Path;
use std::process::ExitCode;

/// The repository's root, two levels above this package (`apps/raycast`):
/// where the bundled `scenes/`, the docs and the default output folder
/// `out/` are.
fn repo_root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .and_then(Path::parent)
        .expect("apps/raycast lies two levels below the repository's root")
}

fn main() -> ExitCode {
    match cli::run(std::env::args().skip(1)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("raycast: {e}");
            ExitCode::from(1)
        }
    }
}
