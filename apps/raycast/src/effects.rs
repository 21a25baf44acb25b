//! Which effects a scene calls for, decided once from its contents.
//!
//! The rule (SCENE_FORMAT.md, "Simulate only the effects a scene calls
//! for"): an effect is simulated only when something in the scene needs it.
//! Only materials that some object uses count.
//!
//! | effect | turned on when |
//! |---|---|
//! | antialiasing (stratified jitter) | more than one sample per pixel |
//! | hard shadows | `shadows true` and a point or directional light |
//! | soft shadows | an `AreaLight` or an emissive object (off with an explicit `shadows false`) |
//! | reflection | a material with non-zero `reflectivity` |
//! | refraction (Fresnel, total internal reflection) | a material with non-zero `transparency` |
//! | absorption (Beer–Lambert) | such a transparent material with non-zero `absorption` |
//! | shadows through transparent objects | a material with non-zero `transparency` (and shadow rays) |
//! | textures | a material with a `texture` |
//! | path tracing | `integrator path`, or emissive objects and no explicit `integrator whitted` |
//! | Reinhard tone mapping | path tracing and `toneMap reinhard` |
//!
//! A scene in the base format turns on none of them and renders as the
//! course framework's ray caster: primary rays and Phong shading.

use crate::scene::{Color, Integrator, Light, Scene, ToneMap};

/// Whitted recursion depth when the Render block gives none.
pub const DEFAULT_WHITTED_DEPTH: u32 = 5;
/// Path length (bounces) when the Render block gives none.
pub const DEFAULT_PATH_DEPTH: u32 = 8;
/// The largest `maxDepth`: the parser rejects more, and a scene built in
/// code is clamped to it. The Whitted tracer recurses once per bounce, so
/// this bounds its stack (about a kilobyte a level).
pub const MAX_DEPTH: u32 = 100;
/// The most samples a pixel (2¹⁶): the parser and the command line refuse
/// more (`samples 1e9` on a 640 × 480 image would be 3·10¹⁴ rays).
pub const MAX_SAMPLES: u32 = 1 << 16;
/// Light samples per shading point and pixel: an area light gets
/// `max(1, LIGHT_SAMPLE_BUDGET / samples)` samples per shading point, so a
/// pixel gathers about this many whatever its own sample count.
pub const LIGHT_SAMPLE_BUDGET: u32 = 16;

/// The effects a render simulates, and their settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Effects {
    pub integrator: Integrator,
    /// Samples per pixel (≥ 1).
    pub samples: u32,
    /// More than one sample per pixel: stratified jitter inside the pixel.
    pub antialiasing: bool,
    /// Reflection/refraction depth (Whitted) or path length (path tracing).
    pub max_depth: u32,
    /// Shadow rays towards point and directional lights (Whitted; the path
    /// tracer always tests visibility).
    pub hard_shadows: bool,
    /// Whether the scene has point or directional lights (for the report).
    pub delta_lights: bool,
    /// The scene has `AreaLight`s: they are sampled over their area.
    pub area_lights: bool,
    /// Some used material emits: the objects are lights.
    pub emissive: bool,
    /// Shadow rays towards area lights and emitters.
    pub soft_shadows: bool,
    /// Samples per area light (or emitter) and shading point.
    pub light_samples: u32,
    pub reflection: bool,
    pub refraction: bool,
    pub absorption: bool,
    /// Shadow rays continue through transparent surfaces, attenuated by
    /// their transmission ([`crate::tracer::Tracer::transmittance`]); off,
    /// any surface blocks the light. On with refraction.
    pub transparent_shadows: bool,
    pub textures: bool,
    pub tone_map: ToneMap,
}

fn per_point(n: u32) -> String {
    format!("{n} sample{} per point", if n == 1 { "" } else { "s" })
}

fn nonzero(c: &Color) -> bool {
    c.iter().any(|v| *v != 0.0)
}

impl Effects {
    /// Decides the effects of `scene`; `samples` overrides the Render
    /// block's sample count (the `--samples` option).
    pub fn of(scene: &Scene, samples: Option<u32>) -> Effects {
        let mut used = vec![false; scene.materials.len()];
        for object in &scene.objects {
            if let Some(u) = used.get_mut(object.material) {
                *u = true;
            }
        }
        let materials = || {
            scene
                .materials
                .iter()
                .zip(&used)
                .filter(|(_, u)| **u)
                .map(|(m, _)| m)
        };
        let emissive = materials().any(|m| nonzero(&m.emission));
        let refraction = materials().any(|m| nonzero(&m.transparency));
        let absorption = materials().any(|m| nonzero(&m.transparency) && nonzero(&m.absorption));
        let reflection = materials().any(|m| nonzero(&m.reflectivity));
        let textures = materials().any(|m| m.texture.is_some());

        let settings = &scene.render;
        let integrator = match settings.integrator {
            Some(i) => i,
            None if emissive => Integrator::Path,
            None => Integrator::Whitted,
        };
        let samples = samples.or(settings.samples).unwrap_or(1).max(1);
        let max_depth = settings
            .max_depth
            .unwrap_or(match integrator {
                Integrator::Whitted => DEFAULT_WHITTED_DEPTH,
                Integrator::Path => DEFAULT_PATH_DEPTH,
            })
            .min(MAX_DEPTH);
        let delta_lights = scene
            .lights
            .iter()
            .any(|l| matches!(l, Light::Point { .. } | Light::Directional { .. }));
        let area_lights = scene.lights.iter().any(|l| matches!(l, Light::Area { .. }));
        let tone_map = match integrator {
            Integrator::Path => settings.tone_map.unwrap_or(ToneMap::Clamp),
            Integrator::Whitted => ToneMap::Clamp,
        };
        Effects {
            integrator,
            samples,
            antialiasing: samples > 1,
            max_depth,
            hard_shadows: settings.shadows == Some(true),
            delta_lights,
            area_lights,
            emissive,
            soft_shadows: (area_lights || emissive) && settings.shadows != Some(false),
            light_samples: (LIGHT_SAMPLE_BUDGET / samples).max(1),
            reflection,
            refraction,
            absorption,
            transparent_shadows: refraction,
            textures,
            tone_map,
        }
    }

    /// Whether some shadow ray may pass through a transparent surface: with
    /// transparent shadows on, the Whitted tracer's hard and soft shadow
    /// rays, and the path tracer's shadow rays towards point and directional
    /// lights (towards area lights and emitters the path tracer keeps
    /// surfaces opaque: its paths through the glass already bring that light).
    pub fn shadows_through_transparency(&self) -> bool {
        self.transparent_shadows
            && match self.integrator {
                Integrator::Whitted => {
                    (self.delta_lights && self.hard_shadows)
                        || ((self.area_lights || self.emissive) && self.soft_shadows)
                }
                Integrator::Path => self.delta_lights,
            }
    }

    /// The names of the effects turned on, for the report; empty for a
    /// scene in the base format.
    pub fn names(&self) -> Vec<String> {
        let mut names = Vec::new();
        if self.integrator == Integrator::Path {
            names.push(format!(
                "path tracing (next-event estimation, Russian roulette, {} bounces)",
                self.max_depth
            ));
        }
        if self.antialiasing {
            names.push(format!(
                "antialiasing ({} stratified samples)",
                self.samples
            ));
        }
        let visibility_always = self.integrator == Integrator::Path;
        if self.delta_lights && (self.hard_shadows || visibility_always) {
            names.push("hard shadows".into());
        }
        if self.area_lights || self.emissive {
            let what = match (self.area_lights, self.emissive) {
                (true, true) => "area lights and emissive objects",
                (true, false) => "area lights",
                _ => "emissive objects",
            };
            if self.soft_shadows || visibility_always {
                names.push(format!(
                    "soft shadows ({what}, {})",
                    per_point(self.light_samples)
                ));
            } else {
                names.push(format!(
                    "{what} sampled without shadows ({})",
                    per_point(self.light_samples)
                ));
            }
        }
        if self.reflection {
            names.push("reflection".into());
        }
        if self.refraction {
            names.push("refraction (exact Fresnel, total internal reflection)".into());
        }
        if self.absorption {
            names.push("absorption (Beer–Lambert)".into());
        }
        if self.shadows_through_transparency() {
            names.push("shadows through transparent objects".into());
        }
        if self.textures {
            names.push("textures (bilinear)".into());
        }
        if self.tone_map == ToneMap::Reinhard {
            names.push("Reinhard tone mapping + sRGB".into());
        }
        names
    }
}
