//! `Render { samples N  maxDepth N  shadows true|false  integrator whitted|path
//! toneMap clamp|reinhard }`: every key optional, each at most once;
//! `samples` at most [`MAX_SAMPLES`], `maxDepth` at most [`MAX_DEPTH`].

use super::cursor::{Cursor, Result};
use crate::effects::{MAX_DEPTH, MAX_SAMPLES};
use crate::scene::{Integrator, RenderSettings, ToneMap};

const BLOCK: &str = "Render";
const KEYS: &[&str] = &["samples", "maxDepth", "shadows", "integrator", "toneMap"];

/// Reads a `Render` block (after its keyword).
pub(super) fn render(c: &mut Cursor<'_>) -> Result<RenderSettings> {
    let open = c.open(BLOCK)?;
    let mut settings = RenderSettings::default();
    while let Some(key) = c.key(BLOCK, open)? {
        match key.text {
            "samples" => c.field(&mut settings.samples, key, BLOCK, |c, w| {
                whole_up_to(c, w, 1, MAX_SAMPLES)
            })?,
            "maxDepth" => c.field(&mut settings.max_depth, key, BLOCK, |c, w| {
                whole_up_to(c, w, 0, MAX_DEPTH)
            })?,
            "shadows" => c.field(&mut settings.shadows, key, BLOCK, |c, w| {
                c.choice(w, &[("true", true), ("false", false)])
            })?,
            "integrator" => c.field(&mut settings.integrator, key, BLOCK, |c, w| {
                c.choice(
                    w,
                    &[("whitted", Integrator::Whitted), ("path", Integrator::Path)],
                )
            })?,
            "toneMap" => c.field(&mut settings.tone_map, key, BLOCK, |c, w| {
                c.choice(
                    w,
                    &[("clamp", ToneMap::Clamp), ("reinhard", ToneMap::Reinhard)],
                )
            })?,
            _ => return Err(c.unknown(key, BLOCK, KEYS)),
        }
    }
    Ok(settings)
}

/// A whole number from `least` to `largest` (the value of the key `what`),
/// an error at the number beyond.
fn whole_up_to(c: &mut Cursor<'_>, what: &str, least: u32, largest: u32) -> Result<u32> {
    let (value, at) = c.whole(what, least)?;
    if value > largest {
        return Err(c.error(
            at,
            format!("'{what}' is {value}, more than the largest, {largest}"),
        ));
    }
    Ok(value)
}
