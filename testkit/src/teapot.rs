//! Newell's teapot from `scenes/data/teapot.txt` (the classic layout: the
//! patch count, 16 one-based indices per patch, the vertex count, the
//! vertices; `#` starts a comment line), as 32 bicubic [`BezierSurface`]s.

use revolve::BezierSurface;
use revolve::nalgebra::Point3;

/// The teapot data file's text.
pub const TEXT: &str = include_str!("../../scenes/data/teapot.txt");

/// The patches of a model in the classic layout `text` (panics on bad data:
/// the file is the repository's own).
pub fn patches_from(text: &str) -> Vec<BezierSurface> {
    let mut numbers = text
        .lines()
        .filter(|l| !l.trim_start().starts_with('#'))
        .flat_map(|l| l.split_whitespace())
        .map(|w| w.parse::<f64>().expect("a number"));
    let mut next = || numbers.next().expect("more numbers");
    let count = next() as usize;
    let indices: Vec<[usize; 16]> = (0..count)
        .map(|_| std::array::from_fn(|_| next() as usize - 1))
        .collect();
    let vertex_count = next() as usize;
    let vertices: Vec<Point3<f64>> = (0..vertex_count)
        .map(|_| Point3::new(next(), next(), next()))
        .collect();
    indices
        .iter()
        .map(|ix| {
            let rows = (0..4)
                .map(|i| (0..4).map(|j| vertices[ix[4 * i + j]]).collect())
                .collect();
            BezierSurface::new(rows).expect("a valid patch")
        })
        .collect()
}

/// The teapot's 32 patches.
pub fn patches() -> Vec<BezierSurface> {
    patches_from(TEXT)
}
