//! The whole file: its top-level blocks, in any order, each at most once.
//!
//! ```text
//! file = ( PerspectiveCamera {…} | Lights {…} | Background {…}
//!        | Materials {…} | Group {…} | Render {…} )…
//! Background { color C  ambientLight C }     ambientLight is accepted and ignored
//! ```
//!
//! The camera is required. Without `Lights` there are none, without
//! `Background` it is black, without `Group` there are no objects, without
//! `Render` every setting is left to the renderer, and without `Materials`
//! (or with an empty one) there is one default material, grey `0.8` diffuse.

use std::path::Path;

use super::Parsed;
use super::camera::camera;
use super::cursor::{Cursor, Result};
use super::lexer::{Kind, Pos};
use super::lights::lights;
use super::materials::materials;
use super::objects::{Flat, Frame, group};
use super::render::render;
use super::resources::Resources;
use crate::scene::{Color, Material, RenderSettings, Scene};

/// The top-level block keywords.
const BLOCKS: &[&str] = &[
    "PerspectiveCamera",
    "Lights",
    "Background",
    "Materials",
    "Group",
    "Render",
];

/// The diffuse grey of the default material.
const DEFAULT_GREY: f64 = 0.8;

/// Parses the scene `text` of the file `path`.
pub(super) fn scene(text: &str, path: &Path) -> Result<Parsed> {
    let mut c = Cursor::new(text, path);
    let mut res = Resources::new(path);
    let mut seen: Vec<(&str, Pos)> = Vec::new();
    let mut camera_block = None;
    let mut light_list = Vec::new();
    let mut background_color = Color::zeros();
    let mut material_list = Vec::new();
    let mut flat = Flat::default();
    let mut settings = RenderSettings::default();
    while let Some(key) = c.peek() {
        if key.kind != Kind::Word {
            return Err(c.expected(
                "a block keyword (PerspectiveCamera, Lights, Background, Materials, Group or Render)",
            ));
        }
        c.bump();
        if let Some(&(_, first)) = seen.iter().find(|(name, _)| *name == key.text) {
            return Err(c.error(
                key.pos,
                format!("a second {} block (the first is at {first})", key.text),
            ));
        }
        match key.text {
            "PerspectiveCamera" => camera_block = Some(camera(&mut c)?),
            "Lights" => light_list = lights(&mut c)?,
            "Background" => background_color = background(&mut c)?,
            "Materials" => material_list = materials(&mut c, &mut res)?,
            "Group" => group(&mut c, &mut res, &mut flat, Frame::root())?,
            "Render" => settings = render(&mut c)?,
            _ => return Err(c.unknown(key, "the scene file", BLOCKS)),
        }
        seen.push((key.text, key.pos));
    }
    let camera = camera_block.ok_or_else(|| {
        c.error(
            Pos { line: 0, column: 0 },
            "the scene has no PerspectiveCamera block",
        )
    })?;
    let defined = material_list.len();
    if material_list.is_empty() {
        material_list.push(Material {
            diffuse: Color::repeat(DEFAULT_GREY),
            ..Default::default()
        });
    }
    if let Some(&(index, at)) = flat
        .material_uses
        .iter()
        .find(|(index, _)| *index >= material_list.len())
    {
        let message = if defined == 0 {
            format!(
                "MaterialIndex {index}, but the scene defines no materials (only the default material 0)"
            )
        } else {
            format!(
                "MaterialIndex {index}, but the scene defines {defined} material{} (indices 0 to {})",
                if defined == 1 { "" } else { "s" },
                defined - 1
            )
        };
        return Err(c.error(at, message));
    }
    let scene = Scene {
        camera,
        lights: light_list,
        background: background_color,
        materials: material_list,
        objects: flat.objects,
        render: settings,
    };
    Ok(Parsed {
        scene,
        warnings: c.take_warnings(),
    })
}

/// `Background { color C  ambientLight C }` (after its keyword); the colour
/// defaults to black and the ambient light is ignored.
fn background(c: &mut Cursor<'_>) -> Result<Color> {
    const NAME: &str = "Background";
    let open = c.open(NAME)?;
    let (mut color, mut ambient) = (None, None);
    while let Some(key) = c.key(NAME, open)? {
        match key.text {
            "color" => c.field(&mut color, key, NAME, Cursor::color)?,
            "ambientLight" => c.field(&mut ambient, key, NAME, Cursor::color)?,
            _ => return Err(c.unknown(key, NAME, &["color", "ambientLight"])),
        }
    }
    Ok(color.unwrap_or_else(Color::zeros))
}
