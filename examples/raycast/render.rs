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

use crate::camera::PinholeCamera;
use crate::effects::Effects;
use crate::geometry::World;
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
}

impl Default for Options {
    fn default() -> Self {
        Options {
            samples: None,
            progress: false,
            seed: 0x5eed,
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
                    for x in x0..x1 {
                        let mut rng = Rng::for_pixel(options.seed, x, y);
                        pixels.push(pixel(&tracer, &camera, x, y, &mut rng, &mut stats));
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

/// The colour of pixel `(x, y)`: the mean over its samples.
fn pixel(
    tracer: &Tracer<'_>,
    camera: &PinholeCamera,
    x: u32,
    y: u32,
    rng: &mut Rng,
    stats: &mut Stats,
) -> Color {
    let n = tracer.effects.samples.max(1);
    let mut sum = Color::zeros();
    for i in 0..n {
        let (sx, sy) = if n == 1 {
            (f64::from(x) + 0.5, f64::from(y) + 0.5)
        } else {
            let (a, b) = sampling::stratum(i, n, rng.next_2d());
            (f64::from(x) + a, f64::from(y) + b)
        };
        let ray = camera.ray(sx, sy);
        stats.rays.primary += 1;
        let c = match tracer.effects.integrator {
            Integrator::Whitted => whitted::trace(tracer, &ray, rng, stats),
            Integrator::Path => path::radiance(tracer, &ray, rng, stats),
        };
        if c.iter().all(|v| v.is_finite()) {
            sum += c;
        } else {
            stats.non_finite_samples += 1;
        }
    }
    sum / f64::from(n)
}
