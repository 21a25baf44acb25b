//! Files a scene refers to (OBJ meshes, PNG textures, Bézier patch
//! models): paths resolved relative to the scene file, each file read once
//! and shared.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::cursor::{Cursor, Result};
use super::lexer::Token;
use super::obj::{ObjError, read_obj};
use super::patches::{PatchFileError, read_patches};
use super::texture::read_texture;
use crate::scene::{SurfaceBody, Texture, TriangleMesh};

/// The scene file's directory and the meshes, textures and patch models
/// read so far.
pub(super) struct Resources {
    base: PathBuf,
    meshes: HashMap<PathBuf, Arc<TriangleMesh>>,
    textures: HashMap<PathBuf, Arc<Texture>>,
    patches: HashMap<PathBuf, Arc<SurfaceBody>>,
}

impl Resources {
    /// Resources of the scene file `scene`.
    pub(super) fn new(scene: &Path) -> Self {
        Resources {
            base: scene.parent().map(Path::to_path_buf).unwrap_or_default(),
            meshes: HashMap::new(),
            textures: HashMap::new(),
            patches: HashMap::new(),
        }
    }

    /// The mesh named by the path token `path`; errors point at it.
    pub(super) fn mesh(&mut self, c: &Cursor<'_>, path: Token<'_>) -> Result<Arc<TriangleMesh>> {
        let full = self.base.join(path.text);
        if let Some(mesh) = self.meshes.get(&full) {
            return Ok(Arc::clone(mesh));
        }
        let mesh = Arc::new(read_obj(&full).map_err(|e| {
            let message = match e {
                ObjError::Io(e) => format!("cannot read mesh '{}': {e}", path.text),
                e => format!("mesh '{}': {e}", path.text),
            };
            c.error(path.pos, message)
        })?);
        self.meshes.insert(full, Arc::clone(&mesh));
        Ok(mesh)
    }

    /// The texture named by the path token `path`; errors point at it.
    pub(super) fn texture(&mut self, c: &Cursor<'_>, path: Token<'_>) -> Result<Arc<Texture>> {
        let full = self.base.join(path.text);
        if let Some(texture) = self.textures.get(&full) {
            return Ok(Arc::clone(texture));
        }
        let texture = Arc::new(read_texture(&full).map_err(|e| {
            c.error(
                path.pos,
                format!("cannot read texture '{}': {e}", path.text),
            )
        })?);
        self.textures.insert(full, Arc::clone(&texture));
        Ok(texture)
    }

    /// The Bézier patch model named by the path token `path`; errors point
    /// at it and name the file (and its line).
    pub(super) fn patches(&mut self, c: &Cursor<'_>, path: Token<'_>) -> Result<Arc<SurfaceBody>> {
        let full = self.base.join(path.text);
        if let Some(model) = self.patches.get(&full) {
            return Ok(Arc::clone(model));
        }
        let model = read_patches(&full).map_err(|e| {
            let message = match e {
                PatchFileError::Io(e) => format!("cannot read patches file '{}': {e}", path.text),
                e => format!("patches file '{}': {e}", path.text),
            };
            c.error(path.pos, message)
        })?;
        let model = Arc::new(SurfaceBody::Patches(model));
        self.patches.insert(full, Arc::clone(&model));
        Ok(model)
    }
}
