//! Rendering a whole image: pixels, samples, tiles and threads.
//!
//! The image is cut into [`TILE`]×[`TILE`] tiles (smaller at the right and
//! bottom edges) that rayon renders in parallel. Pixel `(x, y)` draws its
//! random numbers from its own generator, seeded from `(seed, x, y)`
//! ([`Rng::for_pixel`]), so the image does not depend on the thread count or
//! the order in which tiles run. With one sample per pixel the ray goes
//! through the pixel centre; with `n > 1`, sample `i` is jittered inside
//! stratum `i` of a `⌈√n⌉`-column grid over the pixel and the pixel is the
//! mean of the samples (antialiasing). A sample whose value is not finite
//! counts as black instead of poisoning the pixel.
//!
//! Camera rays go through the scene in batches: runs of up to
//! [`Options::lanes`] pixels of a row, sample `i` of each at a time
//! ([`Tracer::nearest_batch`]); the image is the same as one ray at a time.
//!
//! Each tile counts its rays in its own [`Stats`]; they are merged when the
//! image is done, and the wall time and thread count are filled in.
//!
//! # Size
//! An image is at most [`MAX_IMAGE_SIDE`] pixels on a side and
//! [`MAX_IMAGE_PIXELS`] in all ([`check_size`]; the parser reports a larger
//! `width`/`height` at its value). The framebuffer is allocated fallibly
//! before any ray is traced, so a size the machine cannot hold is an error,
//! not an abort.

use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use revolve::Ray;
use revolve::nalgebra::{Point3, Vector3};

use crate::camera::PinholeCamera;
use crate::effects::Effects;
use crate::geometry::{LANES, World};
use crate::path;
use crate::sampling::{self, Rng};
use crate::scene::{Color, Integrator, Scene};
use crate::stats::Stats;
use crate::tracer::Tracer;
use crate::whitted;

/// Tile side in pixels.
pub const TILE: u32 = 16;

/// Tiles rendered in parallel before their pixels are copied into the
/// framebuffer (a batch holds at most 256 × 256 pixels besides it).
const TILE_BATCH: usize = 256;

/// The longest image side, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// The most pixels in an image: 2²⁵, e.g. 8192 × 4096 (8K UHD, 7680 × 4320,
/// fits); its framebuffer takes 768 MiB.
pub const MAX_IMAGE_PIXELS: u64 = 1 << 25;

/// Whether a `width × height` image is within [`MAX_IMAGE_SIDE`] and
/// [`MAX_IMAGE_PIXELS`] and not empty; the error says which bound it breaks.
pub fn check_size(width: u32, height: u32) -> Result<(), String> {
    if width == 0 || height == 0 {
        return Err(format!("the image is empty ({width}×{height} pixels)"));
    }
    if width.max(height) > MAX_IMAGE_SIDE {
        return Err(format!(
            "the image is {width}×{height} pixels; a side may be at most {MAX_IMAGE_SIDE}"
        ));
    }
    let pixels = u64::from(width) * u64::from(height);
    if pixels > MAX_IMAGE_PIXELS {
        return Err(format!(
            "the image is {width}×{height} = {pixels} pixels, more than the largest, \
             {MAX_IMAGE_PIXELS} (e.g. 8192×4096)"
        ));
    }
    Ok(())
}

/// A vector of `len` copies of `value`, or an error naming `what` when the
/// memory cannot be had.
pub fn try_filled<T: Clone>(len: usize, value: T, what: &str) -> Result<Vec<T>, String> {
    let mut v = Vec::new();
    v.try_reserve_exact(len).map_err(|e| {
        format!(
            "cannot allocate {what} ({len} × {} bytes): {e}",
            std::mem::size_of::<T>()
        )
    })?;
    v.resize(len, value);
    Ok(v)
}

/// How to render, beyond what the scene says.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Overrides the Render block's samples per pixel.
    pub samples: Option<u32>,
    /// Shows a progress bar (on a terminal).
    pub progress: bool,
    /// The seed of every pixel's random numbers.
    pub seed: u64,
    /// Camera rays traced together, in `1..=`[`LANES`] (clamped): a run of
    /// up to that many pixels of a row, one sample of each at a time. 1
    /// traces every camera ray alone with the single-ray query; the image is
    /// the same.
    pub lanes: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            samples: None,
            progress: false,
            seed: 0x5eed,
            lanes: LANES,
        }
    }
}

/// A rendered image: linear radiance per pixel, row 0 at the top, before
/// tone mapping.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<Color>,
}

impl Image {
    /// The pixel in column `x` and row `y` (for tests).
    #[cfg(test)]
    pub fn get(&self, x: u32, y: u32) -> Color {
        self.pixels[y as usize * self.width as usize + x as usize]
    }
}

/// Renders `scene` with the effects it calls for; builds the world first.
/// An error when the image is too large ([`check_size`]) or its memory
/// cannot be had.
pub fn render(scene: &Scene, options: &Options) -> Result<(Image, Stats), String> {
    let effects = Effects::of(scene, options.samples);
    let started = Instant::now();
    let world = World::new(scene);
    let build = started.elapsed();
    let (image, mut stats) = render_world(scene, &world, effects, options)?;
    stats.build = build;
    Ok((image, stats))
}

/// Renders `scene`, whose `world` is built, with `effects` (errors as
/// [`render`]).
pub fn render_world(
    scene: &Scene,
    world: &World,
    effects: Effects,
    options: &Options,
) -> Result<(Image, Stats), String> {
    let (width, height) = (scene.camera.width, scene.camera.height);
    check_size(width, height)?;
    let mut image = Image {
        width,
        height,
        pixels: try_filled(
            width as usize * height as usize,
            Color::zeros(),
            "the framebuffer",
        )?,
    };
    let tracer = Tracer::new(scene, world, effects);
    let camera = PinholeCamera::new(&scene.camera);
    let tiles: Vec<(u32, u32)> = (0..height.div_ceil(TILE))
        .flat_map(|ty| (0..width.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
        .collect();
    let bar = if options.progress {
        let bar = ProgressBar::new(tiles.len() as u64);
        if let Ok(style) = ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {wide_bar} {pos}/{len} tiles (eta {eta})",
        ) {
            bar.set_style(style);
        }
        bar
    } else {
        ProgressBar::hidden()
    };

    let (lanes, seed) = (options.lanes.clamp(1, LANES), options.seed);
    let started = Instant::now();
    let mut stats = Stats::default();
    // Tiles render in parallel a batch at a time and are copied into the
    // framebuffer, so the tiles' own pixels never hold more than a batch.
    for batch in tiles.chunks(TILE_BATCH) {
        let done: Vec<(Vec<Color>, Stats)> = batch
            .par_iter()
            .map(|&(x0, y0)| {
                let (x1, y1) = ((x0 + TILE).min(width), (y0 + TILE).min(height));
                let mut stats = Stats::default();
                let mut pixels = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
                for y in y0..y1 {
                    for x in (x0..x1).step_by(lanes) {
                        let run = (x, (x + lanes as u32).min(x1));
                        pixel_run(&tracer, &camera, run, y, seed, &mut stats, &mut pixels);
                    }
                }
                bar.inc(1);
                (pixels, stats)
            })
            .collect();
        for (&(x0, y0), (pixels, tile_stats)) in batch.iter().zip(&done) {
            let w = (x0 + TILE).min(width) - x0;
            for (i, c) in pixels.iter().enumerate() {
                let (x, y) = (x0 + i as u32 % w, y0 + i as u32 / w);
                image.pixels[y as usize * width as usize + x as usize] = *c;
            }
            stats.merge(tile_stats);
        }
    }
    let wall = started.elapsed();
    bar.finish_and_clear();

    stats.wall = wall;
    stats.threads = rayon::current_num_threads().min(tiles.len()).max(1);
    Ok((image, stats))
}

/// The colours of pixels `x0..x1` (at most [`LANES`]) of row `y`, appended
/// to `out`: each the mean over its samples. Sample `i` of every pixel goes
/// through the scene in one batch ([`Tracer::nearest_batch`]; one pixel
/// alone takes the single-ray query). Each pixel draws from its own
/// generator in the same order as if it were traced alone, so the image does
/// not depend on the batching.
fn pixel_run(
    tracer: &Tracer<'_>,
    camera: &PinholeCamera,
    (x0, x1): (u32, u32),
    y: u32,
    seed: u64,
    stats: &mut Stats,
    out: &mut Vec<Color>,
) {
    let w = (x1 - x0).clamp(1, LANES as u32) as usize;
    let n = tracer.effects.samples.max(1);
    let mut rngs: [Rng; LANES] =
        std::array::from_fn(|j| Rng::for_pixel(seed, x0 + j.min(w - 1) as u32, y));
    let mut sums = [Color::zeros(); LANES];
    let mut rays = [Ray::new(Point3::origin(), Vector3::zeros()); LANES];
    let mut hits = [None; LANES];
    for i in 0..n {
        for (j, (ray, rng)) in rays.iter_mut().zip(&mut rngs).take(w).enumerate() {
            let x = f64::from(x0 + j as u32);
            let (sx, sy) = if n == 1 {
                (x + 0.5, f64::from(y) + 0.5)
            } else {
                let (a, b) = sampling::stratum(i, n, rng.next_2d());
                (x + a, f64::from(y) + b)
            };
            *ray = camera.ray(sx, sy);
        }
        stats.rays.primary += w as u64;
        if w == 1 {
            hits[0] = tracer.nearest(&rays[0], 0.0, stats);
        } else {
            tracer.nearest_batch(&rays[..w], 0.0, &mut hits[..w], stats);
        }
        for j in 0..w {
            let (ray, hit, rng) = (&rays[j], hits[j], &mut rngs[j]);
            let c = match tracer.effects.integrator {
                Integrator::Whitted => whitted::trace(tracer, ray, hit, rng, stats),
                Integrator::Path => path::radiance(tracer, ray, hit, rng, stats),
            };
            if c.iter().all(|v| v.is_finite()) {
                sums[j] += c;
            } else {
                stats.non_finite_samples += 1;
            }
        }
    }
    out.extend(sums[..w].iter().map(|s| s / f64::from(n)));
}
