//! `Materials { numMaterials N  material… }`, each material
//! `PhongMaterial { … }` or `Material { … }` with any of
//!
//! ```text
//! diffuseColor C  specularColor C  shininess S
//! reflectivity C  transparency C  refractionIndex N  absorption C  emission C
//! texture PATH            (a PNG, relative to the scene file)
//! ```
//!
//! Missing keys are zero (`refractionIndex` is 1). `numMaterials`, when given,
//! must equal the number of materials. The four reflectances (`diffuseColor`,
//! `specularColor`, `reflectivity`, `transparency`) are fractions of the
//! light, each component in `[0, 1]`; `emission` is a radiance, at most
//! `1e100`; `absorption` is any finite rate `≥ 0`.

use super::counted::Counter;
use super::cursor::{Cursor, Result};
use super::resources::Resources;
use crate::scene::Material;

const BLOCK: &str = "Materials";

/// The keys of a material block.
const KEYS: &[&str] = &[
    "diffuseColor",
    "specularColor",
    "shininess",
    "reflectivity",
    "transparency",
    "refractionIndex",
    "absorption",
    "emission",
    "texture",
];

/// Reads a `Materials` block (after its keyword).
pub(super) fn materials(c: &mut Cursor<'_>, res: &mut Resources) -> Result<Vec<Material>> {
    let open = c.open(BLOCK)?;
    let mut materials = Vec::new();
    let mut count = Counter::new("numMaterials", "the block", "material");
    while let Some(key) = c.key(BLOCK, open)? {
        match key.text {
            "numMaterials" => count.read(c, key)?,
            "PhongMaterial" | "Material" => materials.push(material(c, res, key.text)?),
            _ => {
                return Err(c.unknown(key, BLOCK, &["numMaterials", "PhongMaterial", "Material"]));
            }
        }
    }
    count.check(c, materials.len())?;
    Ok(materials)
}

/// One material block named `name` (after its keyword).
fn material(c: &mut Cursor<'_>, res: &mut Resources, name: &str) -> Result<Material> {
    let open = c.open(name)?;
    let (mut diffuse, mut specular, mut shininess) = (None, None, None);
    let (mut reflectivity, mut transparency, mut refraction_index) = (None, None, None);
    let (mut absorption, mut emission, mut texture) = (None, None, None);
    while let Some(key) = c.key(name, open)? {
        match key.text {
            "diffuseColor" => c.field(&mut diffuse, key, name, Cursor::reflectance)?,
            "specularColor" => c.field(&mut specular, key, name, Cursor::reflectance)?,
            "shininess" => c.field(&mut shininess, key, name, Cursor::non_negative)?,
            "reflectivity" => c.field(&mut reflectivity, key, name, Cursor::reflectance)?,
            "transparency" => c.field(&mut transparency, key, name, Cursor::reflectance)?,
            "refractionIndex" => c.field(&mut refraction_index, key, name, Cursor::positive)?,
            "absorption" => c.field(&mut absorption, key, name, Cursor::rates)?,
            "emission" => c.field(&mut emission, key, name, Cursor::color)?,
            "texture" => c.field(&mut texture, key, name, |c, what| {
                let path = c.word(what)?;
                res.texture(c, path)
            })?,
            _ => return Err(c.unknown(key, name, KEYS)),
        }
    }
    let default = Material::default();
    Ok(Material {
        diffuse: diffuse.unwrap_or(default.diffuse),
        specular: specular.unwrap_or(default.specular),
        shininess: shininess.unwrap_or(default.shininess),
        reflectivity: reflectivity.unwrap_or(default.reflectivity),
        transparency: transparency.unwrap_or(default.transparency),
        refraction_index: refraction_index.unwrap_or(default.refraction_index),
        absorption: absorption.unwrap_or(default.absorption),
        emission: emission.unwrap_or(default.emission),
        texture,
    })
}
