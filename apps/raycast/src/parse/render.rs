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
                let (samples, at) = c.whole(w, 1)?;
                if samples > MAX_SAMPLES {
                    return Err(c.error(
                        at,
                        format!("'samples' is {samples}, more than the largest, {MAX_SAMPLES}"),
                    ));
                }
                Ok(samples)
            })?,
            "maxDepth" => c.field(&mut settings.max_depth, key, BLOCK, |c, w| {
                let (depth, at) = c.whole(w, 0)?;
                if depth > MAX_DEPTH {
                    return Err(c.error(
                        at,
                        format!("'maxDepth' is {depth}, more than the largest, {MAX_DEPTH}"),
                    ));
                }
                Ok(depth)
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
