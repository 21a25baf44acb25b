//! A seeded, deterministic fuzz of the scene files: every bundled scene in
//! `scenes/` is mutated [`CASES`] times in all (byte flips, token deletions,
//! duplications and swaps, numbers replaced by extremes, huge counts and
//! image sizes, deep nesting, control points repeated up to a thousand
//! times, blocks and keywords spliced in, truncation, and several of these
//! at once). Each mutant is parsed; when it parses it is rendered at
//! most [`MAX_SIDE`]×[`MAX_SIDE`] pixels with one sample per pixel. Every case
//! must
//!
//! - not panic (each runs under `catch_unwind`; a panic fails the case);
//! - give finite pixels, and no camera sample that was not finite;
//! - finish within [`CASE_LIMIT`]: the cases run on a worker thread that a
//!   watchdog on the test's thread checks, failing the test with the case's
//!   seed when one runs over.
//!
//! A failure names the case's seed, the scene it came from and what was
//! done to it, and shows the mutant; `RAYCAST_FUZZ_CASE=<seed>` runs that
//! case alone.
//!
//! The mutation generator is [`Rng`] (SplitMix64) seeded from
//! [`FUZZ_SEED`] plus the case number, so every run makes the same
//! mutants.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use crate::parse::parse_str_with_warnings;
use crate::render::{Options, render};
use crate::sampling::Rng;

/// Mutants in all, spread round-robin over the bundled scenes.
const CASES: u64 = 6000;
/// The seed of case 0; case `i` uses `FUZZ_SEED + i`.
const FUZZ_SEED: u64 = 0x5eed_f022;
/// The longest a case may run before the watchdog fails the test.
const CASE_LIMIT: Duration = Duration::from_secs(10);
/// The largest image side rendered.
const MAX_SIDE: u32 = 8;

/// Numbers that stress the parser and the renderer: non-numbers, infinities,
/// the largest and smallest magnitudes, signed zero, subnormals, counts and
/// sizes around every limit, and a field of view in radians.
const EXTREMES: &[&str] = &[
    "NaN",
    "nan",
    "inf",
    "-inf",
    "1e999",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "-0",
    "0",
    "1e-320",
    "-1e-320",
    "1e-300",
    "1e100",
    "-1e100",
    "1e101",
    "1e-100",
    "4294967295",
    "4294967296",
    "18446744073709551616",
    "1e9",
    "100000",
    "16384",
    "16385",
    "101",
    "200",
    "0.7",
    "-1",
    "1",
    "0.5",
    "2",
];

/// Huge counts and sizes, for the keys that size something.
const HUGE: &[&str] = &[
    "4294967295",
    "1e9",
    "1000000000",
    "100000",
    "16384",
    "65536",
    "16385",
    "2147483648",
];

/// Keys whose value is a count or a size.
const SIZING_KEYS: &[&str] = &[
    "numObjects",
    "numLights",
    "numMaterials",
    "samples",
    "maxDepth",
    "width",
    "height",
    "MaterialIndex",
];

/// Pieces spliced in: each with the block it belongs in (inserted right
/// after that block's `{`, the block's count dropped) or `None` for
/// anywhere.
const SPLICES: &[(&str, Option<&str>)] = &[
    ("{", None),
    ("}", None),
    ("[", None),
    ("]", None),
    ("#", None),
    ("Group", None),
    ("Sphere { center 0 0 0 radius 1 }", Some("Group")),
    ("Sphere { center 1e100 0 0 radius 1e100 }", Some("Group")),
    ("Sphere { center 0 0 0 radius 1e-320 }", Some("Group")),
    ("Plane { normal 0 1e-320 0 offset 1e100 }", Some("Group")),
    ("Box { min -1e100 -1 -1 max 1e100 1 1 }", Some("Group")),
    (
        "Triangle { vertex0 0 0 0 vertex1 1e-320 0 0 vertex2 0 1e-320 0 }",
        Some("Group"),
    ),
    (
        "Disk { center 0 0 0 normal 0 0 1 radius 1e100 }",
        Some("Group"),
    ),
    (
        "Ring { center 0 0 0 normal 1 1 1 inner 1e-300 outer 1e300 }",
        Some("Group"),
    ),
    (
        "Rectangle { corner 0 0 0 edge1 1e100 0 0 edge2 0 1e-320 0 }",
        Some("Group"),
    ),
    ("MaterialIndex 7", Some("Group")),
    (
        "Transform { UniformScale 1e-300 Sphere { center 0 0 0 radius 1 } }",
        Some("Group"),
    ),
    (
        "Transform { UniformScale 1e300 Sphere { center 0 0 0 radius 1 } }",
        Some("Group"),
    ),
    (
        "Transform { Scale 1e308 1 1e-308 Box { min 0 0 0 max 1 1 1 } }",
        Some("Group"),
    ),
    (
        "Transform { Translate 1e300 0 0 Sphere { center 0 0 0 radius 1 } }",
        Some("Group"),
    ),
    (
        "Transform { Rotate { 1e-320 0 0 90 } Sphere { center 0 0 0 radius 1 } }",
        Some("Group"),
    ),
    ("UniformScale 1e-300", Some("Transform")),
    ("UniformScale 1e300", Some("Transform")),
    ("Translate 1e100 -1e100 1e100", Some("Transform")),
    (
        "RevSurface { profile BezierCurve { controls [ 1e99 0 0 ] [ -1e99 1e99 0 ] [ 1 1 0 ] } }",
        Some("Group"),
    ),
    (
        "RevSurface { profile BsplineCurve { controls [ 0 0 0 ] [ 0 0 0 ] [ 0 0 0 ] [ 0 0 0 ] } }",
        Some("Group"),
    ),
    (
        "RevSurface { profile BsplineCurve { controls [ 1e-300 0 0 ] [ 1 1e-300 0 ] [ 1e-300 2 0 ] [ 1 3 0 ] } }",
        Some("Group"),
    ),
    (
        "BezierCurve { controls [ 0 0 0 ] [ 1e100 1e100 1e100 ] }",
        Some("Group"),
    ),
    (
        "BsplineCurve { controls [ 0 0 0 ] [ 1e-300 0 0 ] [ 0 1e-300 0 ] [ 0 0 1e-300 ] }",
        Some("Group"),
    ),
    ("TriangleMesh { obj_file mesh/torus.obj }", Some("Group")),
    (
        "Transform { UniformScale 1e-300 RevSurface { profile BezierCurve { controls [ 0.5 -1 0 ] [ 1 0 0 ] [ 0.5 1 0 ] } } }",
        Some("Group"),
    ),
    (
        "Transform { UniformScale 1e300 RevSurface { profile BezierCurve { controls [ 0.5 -1 0 ] [ 1 0 0 ] [ 0.5 1 0 ] } } }",
        Some("Group"),
    ),
    (
        "Transform { Translate 1e300 0 0 RevSurface { profile BezierCurve { controls [ 0.5 -1 0 ] [ 1 0 0 ] [ 0.5 1 0 ] } } }",
        Some("Group"),
    ),
    (
        "Transform { Scale 1 1e-300 1 RevSurface { profile BsplineCurve { controls [ 0 0 0 ] [ 1 0 0 ] [ 1 1 0 ] [ 0 1 0 ] } } }",
        Some("Group"),
    ),
    (
        "RevSurface { profile BezierCurve { controls [ 1e-300 -1e-300 0 ] [ 1e-300 1e-300 0 ] } }",
        Some("Group"),
    ),
    (
        "RevSurface { profile BsplineCurve { controls [ 1e99 -1e99 0 ] [ 1e99 1e99 0 ] [ -1e99 1e99 0 ] [ 0 -1e99 0 ] } }",
        Some("Group"),
    ),
    (
        "RevSurface { profile NurbsCurve { degree 2 knots 0 0 0 1 1 1 controls [ 1e99 0 0 1e-4 ] [ 1e99 1e99 0 1e4 ] [ 0 1e99 0 ] } }",
        Some("Group"),
    ),
    (
        "RevSurface { profile NurbsCurve { degree 2 knots 0 0 0 1 1 1 controls [ 1e-300 0 0 ] [ 1 1e-300 0 1e4 ] [ 1e-300 2 0 ] } }",
        Some("Group"),
    ),
    (
        "NurbsCurve { degree 3 knots -1e100 -1e100 -1e100 -1e100 1e100 1e100 1e100 1e100 controls [ 0 0 0 ] [ 1 0 0 1e8 ] [ 1 1 1 ] [ 0 1 0 1e-300 ] }",
        Some("Group"),
    ),
    (
        "BezierSurface { rows 2 cols 2 controls [ 1e99 0 0 ] [ 0 1e99 0 1e-4 ] [ 0 0 1e99 ] [ 1e-300 1e-300 1e-300 1e4 ] }",
        Some("Group"),
    ),
    (
        "BezierSurface { rows 2 cols 2 controls [ 0 0 0 ] [ 0 0 0 ] [ 0 0 0 ] [ 0 0 0 ] }",
        Some("Group"),
    ),
    (
        "BsplineSurface { uDegree 2 vDegree 1 uKnots 0 0 0 1e-300 1e-300 1e-300 vKnots -1e100 -1e100 1e100 1e100 rows 3 cols 2 controls [ 0 0 0 ] [ 0 1 0 ] [ 1 0 1 1e8 ] [ 1 1 1 ] [ 2 0 0 ] [ 2 1 0 ] }",
        Some("Group"),
    ),
    ("BezierPatches { file data/teapot.txt }", Some("Group")),
    (
        "PointLight { position 0 0 0 color 1e100 1e100 1e100 }",
        Some("Lights"),
    ),
    (
        "PointLight { position 1e100 1e100 1e100 color 1 1 1 }",
        Some("Lights"),
    ),
    (
        "DirectionalLight { direction 0 0 1e-320 color 1 1 1 }",
        Some("Lights"),
    ),
    (
        "AreaLight { corner 0 0 0 edge1 1e-320 0 0 edge2 0 1e-320 0 color 1 1 1 }",
        Some("Lights"),
    ),
    (
        "AreaLight { corner 0 0 0 edge1 1e100 0 0 edge2 0 0 1e100 color 1e100 1 1 }",
        Some("Lights"),
    ),
    (
        "Material { transparency 1 1 1 reflectivity 1 1 1 refractionIndex 1e-300 }",
        Some("Materials"),
    ),
    (
        "Material { absorption 1e308 0 0 transparency 1 1 1 }",
        Some("Materials"),
    ),
    ("Material { emission 1e100 1e100 1e100 }", Some("Materials")),
    (
        "Material { specularColor 1 1 1 shininess 1e308 }",
        Some("Materials"),
    ),
    (
        "Material { diffuseColor 1 1 1 texture textures/tiles.png }",
        Some("Materials"),
    ),
    ("Render { integrator path maxDepth 100 }", None),
    ("Render { shadows true maxDepth 100 }", None),
];

/// Object blocks that deep nesting wraps.
const NESTED_OBJECTS: &[&str] = &[
    "Sphere { center 0 0 0 radius 1 }",
    "Box { min -1 -1 -1 max 1 1 1 }",
    "RevSurface { profile BezierCurve { controls [ 0.5 -1 0 ] [ 1 0 0 ] [ 0.5 1 0 ] } }",
];

/// How many copies of a control point the many-control-points mutation
/// inserts (a Bézier's degree grows with them).
const COPIES: &[usize] = &[10, 60, 300, 1000];

/// Nesting depths around the parser's limit and far beyond it.
const DEPTHS: &[usize] = &[50, 199, 200, 201, 1000, 17_000];

/// A bundled scene: its path (meshes and textures resolve beside it) and its
/// text with the comments removed, as tokens separated by single spaces.
struct Base {
    path: PathBuf,
    text: String,
}

/// The bundled scenes, comments stripped (so tokens can be rejoined on one
/// line without commenting out the rest of the file).
fn bases() -> Vec<Base> {
    let dir = crate::repo_root().join("scenes");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("the scenes folder")
        .map(|e| e.expect("a scenes entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "txt"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 6, "bundled scenes: {paths:?}");
    paths
        .into_iter()
        .map(|path| {
            let raw = std::fs::read_to_string(&path).expect("a readable scene");
            let text = raw
                .lines()
                .map(|l| l.split('#').next().unwrap_or(""))
                .collect::<Vec<_>>()
                .join("\n");
            Base { path, text }
        })
        .collect()
}

/// A uniform index below `n` (`n > 0`).
fn below(rng: &mut Rng, n: usize) -> usize {
    (rng.next_f64() * n as f64) as usize % n
}

/// A uniform pick from `items`.
fn pick<'a>(rng: &mut Rng, items: &[&'a str]) -> &'a str {
    items[below(rng, items.len())]
}

/// The ways of mutating a scene; each returns the new text and a short
/// description.
#[derive(Debug, Clone, Copy)]
enum Mutation {
    FlipBytes,
    DeleteToken,
    DuplicateToken,
    SwapTokens,
    ExtremeNumber,
    HugeCount,
    DeepNesting,
    ManyControlPoints,
    Splice,
    Truncate,
}

/// The mutations with their weights: the ones that keep a scene readable
/// (so that it reaches the renderer) come more often.
const MUTATIONS: [(Mutation, usize); 10] = [
    (Mutation::FlipBytes, 1),
    (Mutation::DeleteToken, 1),
    (Mutation::DuplicateToken, 1),
    (Mutation::SwapTokens, 1),
    (Mutation::ExtremeNumber, 6),
    (Mutation::HugeCount, 1),
    (Mutation::DeepNesting, 1),
    (Mutation::ManyControlPoints, 1),
    (Mutation::Splice, 3),
    (Mutation::Truncate, 1),
];

/// A mutation drawn by weight.
fn draw(rng: &mut Rng) -> Mutation {
    let total: usize = MUTATIONS.iter().map(|(_, w)| w).sum();
    let mut x = below(rng, total);
    for &(m, w) in &MUTATIONS {
        if x < w {
            return m;
        }
        x -= w;
    }
    MUTATIONS[0].0
}

/// Whether `token` reads as a number of the scene format.
fn is_number(token: &str) -> bool {
    token.parse::<f64>().is_ok() && token.bytes().any(|b| b.is_ascii_digit())
}

impl Mutation {
    /// `text` mutated once with `rng`.
    fn apply(self, text: &str, rng: &mut Rng) -> (String, String) {
        let mut tokens: Vec<String> = text.split_whitespace().map(String::from).collect();
        if tokens.is_empty() {
            return (String::new(), "empty".into());
        }
        let n = tokens.len();
        let what = match self {
            Mutation::FlipBytes => {
                let mut bytes = text.as_bytes().to_vec();
                let flips = 1 + below(rng, 4);
                for _ in 0..flips {
                    let i = below(rng, bytes.len());
                    bytes[i] = match below(rng, 3) {
                        0 => bytes[i] ^ (1 << below(rng, 8)),
                        1 => b"{}[]#\n -.e0123456789"[below(rng, 20)],
                        _ => (rng.next_u64() & 0xff) as u8,
                    };
                }
                return (
                    String::from_utf8_lossy(&bytes).into_owned(),
                    format!("{flips} byte flips"),
                );
            }
            Mutation::Truncate => {
                let mut cut = below(rng, text.len() + 1);
                while !text.is_char_boundary(cut) {
                    cut -= 1;
                }
                return (text[..cut].to_string(), format!("truncated at byte {cut}"));
            }
            Mutation::DeleteToken => {
                let i = below(rng, n);
                let gone = tokens.remove(i);
                format!("deleted token {i} '{gone}'")
            }
            Mutation::DuplicateToken => {
                let (i, j) = (below(rng, n), below(rng, n + 1));
                let copy = tokens[i].clone();
                tokens.insert(j, copy.clone());
                format!("copied token {i} '{copy}' to {j}")
            }
            Mutation::SwapTokens => {
                let (i, j) = (below(rng, n), below(rng, n));
                tokens.swap(i, j);
                format!("swapped tokens {i} and {j}")
            }
            Mutation::ExtremeNumber => {
                let numbers: Vec<usize> = (0..n).filter(|&i| is_number(&tokens[i])).collect();
                if numbers.is_empty() {
                    return (tokens.join(" "), "no number to replace".into());
                }
                let count = 1 + below(rng, 2);
                let mut done = Vec::new();
                for _ in 0..count {
                    let i = numbers[below(rng, numbers.len())];
                    let value = pick(rng, EXTREMES);
                    done.push(format!("token {i} '{}' → '{value}'", tokens[i]));
                    tokens[i] = value.to_string();
                }
                done.join(", ")
            }
            Mutation::HugeCount => {
                let keys: Vec<usize> = (0..n.saturating_sub(1))
                    .filter(|&i| SIZING_KEYS.contains(&tokens[i].as_str()))
                    .collect();
                if keys.is_empty() {
                    return (tokens.join(" "), "no count to enlarge".into());
                }
                let i = keys[below(rng, keys.len())];
                let value = pick(rng, HUGE);
                let what = format!("{} '{}' → '{value}'", tokens[i], tokens[i + 1]);
                tokens[i + 1] = value.to_string();
                what
            }
            Mutation::DeepNesting => {
                let depth = DEPTHS[below(rng, DEPTHS.len())];
                let transform = below(rng, 2) == 1;
                let open = if transform {
                    "Transform { UniformScale 1.01 "
                } else {
                    "Group { "
                };
                let object = pick(rng, NESTED_OBJECTS);
                let nested = format!("{}{object}{}", open.repeat(depth), " }".repeat(depth));
                // Into the top-level group if there is one, else a new one.
                match tokens.iter().position(|t| t == "Group") {
                    Some(g) if tokens.get(g + 1).is_some_and(|t| t == "{") => {
                        tokens.insert(g + 2, nested);
                        // The group's count no longer matches; drop it.
                        if tokens.get(g + 3).is_some_and(|t| t == "numObjects") {
                            tokens.drain(g + 3..(g + 5).min(tokens.len()));
                        }
                    }
                    _ => tokens.push(format!("Group {{ {nested} }}")),
                }
                format!(
                    "{object} nested {depth} deep in {}s",
                    if transform { "Transform" } else { "Group" }
                )
            }
            Mutation::ManyControlPoints => {
                let points: Vec<usize> = (0..n.saturating_sub(4))
                    .filter(|&i| tokens[i] == "[" && tokens[i + 4] == "]")
                    .collect();
                if points.is_empty() {
                    return (tokens.join(" "), "no control point to copy".into());
                }
                let i = points[below(rng, points.len())];
                let copies = COPIES[below(rng, COPIES.len())];
                let point = tokens[i..i + 5].join(" ");
                let inserted = vec![point.clone(); copies];
                tokens.splice(i..i, inserted);
                format!("control point '{point}' at token {i} repeated {copies} more times")
            }
            Mutation::Splice => {
                let (piece, home) = SPLICES[below(rng, SPLICES.len())];
                let anchors: Vec<usize> = match home {
                    Some(block) => (0..n.saturating_sub(1))
                        .filter(|&i| tokens[i] == block && tokens[i + 1] == "{")
                        .collect(),
                    None => Vec::new(),
                };
                if anchors.is_empty() {
                    let i = below(rng, n + 1);
                    tokens.insert(i, piece.to_string());
                    format!("spliced '{piece}' at token {i}")
                } else {
                    let i = anchors[below(rng, anchors.len())] + 2;
                    // The block's count would no longer match: drop it.
                    if tokens.get(i).is_some_and(|t| {
                        ["numObjects", "numLights", "numMaterials"].contains(&t.as_str())
                    }) {
                        tokens.drain(i..(i + 2).min(tokens.len()));
                    }
                    tokens.insert(i, piece.to_string());
                    format!("spliced '{piece}' into {}", home.unwrap_or(""))
                }
            }
        };
        (tokens.join(" "), what)
    }
}

/// The mutant of case `seed`: the scene it comes from, its text and what
/// was done. Mostly one mutation, sometimes two to four in a row.
fn mutant(seed: u64, bases: &[Base]) -> (usize, String, String) {
    let mut rng = Rng::new(seed);
    let scene = (seed.wrapping_sub(FUZZ_SEED) % bases.len() as u64) as usize;
    let mut text = bases[scene].text.clone();
    let rounds = if below(&mut rng, 4) == 0 {
        2 + below(&mut rng, 3)
    } else {
        1
    };
    let mut done = Vec::new();
    for _ in 0..rounds {
        let m = draw(&mut rng);
        let (next, what) = m.apply(&text, &mut rng);
        text = next;
        done.push(format!("{m:?}: {what}"));
    }
    (scene, text, done.join("; "))
}

/// Runs case `seed`: whether its mutant parsed (and so was rendered), or
/// the failure.
fn check_case(seed: u64, bases: &[Base]) -> Result<bool, String> {
    let (scene, text, what) = mutant(seed, bases);
    let base = &bases[scene];
    let described = format!("case seed {seed:#x} ({}; {what})", base.path.display());
    guarded(&described, &text, || {
        let Ok(parsed) = parse_str_with_warnings(&text, &base.path) else {
            return Ok(false);
        };
        let mut scene = parsed.scene;
        scene.camera.width = scene.camera.width.min(MAX_SIDE);
        scene.camera.height = scene.camera.height.min(MAX_SIDE);
        scene.render.samples = Some(1);
        let options = Options {
            samples: Some(1),
            ..Options::default()
        };
        let (image, stats) = render(&scene, &options)?;
        if let Some(p) = image
            .pixels
            .iter()
            .find(|p| !p.iter().all(|c| c.is_finite()))
        {
            return Err(format!("a pixel is not finite: {p:?}"));
        }
        if stats.non_finite_samples > 0 {
            return Err(format!(
                "{} camera samples were not finite",
                stats.non_finite_samples
            ));
        }
        Ok(true)
    })
}

/// Runs `body` under `catch_unwind`: its result, or its error or panic as a
/// failure of the case `described` (whose mutant is `text`).
fn guarded(
    described: &str,
    text: &str,
    body: impl FnOnce() -> Result<bool, String>,
) -> Result<bool, String> {
    let failure = match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(parsed)) => return Ok(parsed),
        Ok(Err(e)) => e,
        Err(panic) => {
            let message = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            format!("panicked: {message}")
        }
    };
    let shown: String = text.chars().take(1500).collect();
    Err(format!(
        "{described}: {failure}\n--- mutant (first 1500 characters) ---\n{shown}"
    ))
}

/// The fuzz's outcome: cases run, how many parsed, and the failures.
struct Summary {
    cases: u64,
    parsed: u64,
    failures: Vec<String>,
}

/// Runs `case` for every seed of `seeds` on a worker thread under the
/// watchdog, which panics naming the seed of a case that runs over `limit`.
fn run_cases(
    seeds: Vec<u64>,
    limit: Duration,
    case: fn(u64, &[Base]) -> Result<bool, String>,
) -> Summary {
    let bases = Arc::new(bases());
    let current = Arc::new(AtomicU64::new(u64::MAX));
    let started_ms = Arc::new(AtomicU64::new(0));
    let clock = Instant::now();
    let worker = {
        let (bases, current, started_ms) = (bases.clone(), current.clone(), started_ms.clone());
        std::thread::Builder::new()
            .name("scene fuzz".into())
            .spawn(move || {
                let mut summary = Summary {
                    cases: 0,
                    parsed: 0,
                    failures: Vec::new(),
                };
                for seed in seeds {
                    started_ms.store(clock.elapsed().as_millis() as u64, Ordering::SeqCst);
                    current.store(seed, Ordering::SeqCst);
                    match case(seed, &bases) {
                        Ok(parsed) => summary.parsed += u64::from(parsed),
                        Err(failure) => summary.failures.push(failure),
                    }
                    summary.cases += 1;
                }
                summary
            })
            .expect("spawn the fuzz worker")
    };
    while !worker.is_finished() {
        std::thread::sleep(Duration::from_millis(20));
        let seed = current.load(Ordering::SeqCst);
        let since = clock.elapsed().as_millis() as u64 - started_ms.load(Ordering::SeqCst);
        if seed != u64::MAX && since > limit.as_millis() as u64 && !worker.is_finished() {
            let (scene, text, what) = mutant(seed, &bases);
            let shown: String = text.chars().take(1500).collect();
            panic!(
                "case seed {seed:#x} ({}; {what}) has run {since} ms, over {limit:?}: a hang\n\
                 --- mutant (first 1500 characters) ---\n{shown}",
                bases[scene].path.display()
            );
        }
    }
    worker.join().expect("the fuzz worker does not panic")
}

#[test]
fn mutated_scene_files_neither_panic_nor_hang_nor_make_nan() {
    let seeds: Vec<u64> = match std::env::var("RAYCAST_FUZZ_CASE") {
        Ok(s) => {
            let s = s.trim_start_matches("0x");
            vec![u64::from_str_radix(s, 16).expect("RAYCAST_FUZZ_CASE: a hexadecimal seed")]
        }
        Err(_) => (0..CASES).map(|i| FUZZ_SEED + i).collect(),
    };
    let started = Instant::now();
    let summary = run_cases(seeds, CASE_LIMIT, check_case);
    eprintln!(
        "scene fuzz: {} cases, {} parsed and rendered, {} failures, {:.1} s",
        summary.cases,
        summary.parsed,
        summary.failures.len(),
        started.elapsed().as_secs_f64()
    );
    assert!(
        summary.failures.is_empty(),
        "{} of {} cases failed; the first:\n{}",
        summary.failures.len(),
        summary.cases,
        summary.failures[..summary.failures.len().min(5)].join("\n\n")
    );
    // The mutants must exercise the renderer, not only the parser's errors.
    if summary.cases == CASES {
        assert!(
            summary.parsed > CASES / 5,
            "only {} of {CASES} mutants parsed",
            summary.parsed
        );
    }
}

#[test]
fn the_watchdog_names_the_seed_of_a_hanging_case() {
    // A stand-in case that "hangs" (sleeps past the limit) on one seed.
    fn sleepy(seed: u64, _: &[Base]) -> Result<bool, String> {
        if seed == FUZZ_SEED + 2 {
            std::thread::sleep(Duration::from_millis(1500));
        }
        Ok(true)
    }
    let seeds = (0..4).map(|i| FUZZ_SEED + i).collect();
    let outcome = catch_unwind(|| run_cases(seeds, Duration::from_millis(300), sleepy));
    let panic = outcome.err().expect("the watchdog fires");
    let message = panic.downcast_ref::<String>().cloned().unwrap_or_default();
    assert!(
        message.contains(&format!("case seed {:#x}", FUZZ_SEED + 2)) && message.contains("a hang"),
        "{message}"
    );
}

#[test]
fn a_panicking_or_nan_case_is_reported_with_its_seed() {
    fn faulty(seed: u64, _: &[Base]) -> Result<bool, String> {
        match seed - FUZZ_SEED {
            1 => Err(format!("case seed {seed:#x}: a pixel is not finite")),
            _ => Ok(false),
        }
    }
    let summary = run_cases((0..3).map(|i| FUZZ_SEED + i).collect(), CASE_LIMIT, faulty);
    assert_eq!((summary.cases, summary.parsed), (3, 0));
    assert_eq!(summary.failures.len(), 1);
    assert!(summary.failures[0].contains(&format!("{:#x}", FUZZ_SEED + 1)));
}

#[test]
fn a_panic_on_a_render_thread_is_caught_and_named() {
    // The renderer runs tiles on rayon's threads; a panic there must come
    // back to the case as a failure naming it, not end the fuzz.
    use rayon::prelude::*;
    let outcome = guarded("case seed 0x7", "the mutant", || {
        (0..4).into_par_iter().for_each(|i| {
            assert!(i != 3, "boom at {i}");
        });
        Ok(true)
    });
    let failure = outcome.unwrap_err();
    assert!(
        failure.starts_with("case seed 0x7: panicked: boom at 3") && failure.contains("the mutant"),
        "{failure}"
    );
    assert_eq!(guarded("case", "", || Ok(true)), Ok(true));
    assert!(
        guarded("case", "", || Err("NaN".into()))
            .unwrap_err()
            .contains("case: NaN")
    );
}
