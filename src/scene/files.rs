//! Texture files on a host (cargo feature `std`): a file source for
//! [`Scene::read_with`](crate::Scene::read_with) that reads the files a scene names
//! relative to the scene file's folder.
//!
//! ```no_run
//! use std::path::Path;
//! use fixray::scene::{files, LargeScene};
//!
//! let path = Path::new("course/scenes/texplane1.txt");
//! let text = std::fs::read_to_string(path)?;
//! let mut scene = LargeScene::<f64>::empty();
//! scene.read_with(&text, None, &mut files::beside(path))?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

extern crate std;

use std::boxed::Box;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock, PoisonError};
use std::vec::Vec;

/// A file source that reads a texture's `filename` relative to the folder of the scene
/// file `scene`. A name not found there is looked for by its last component in an
/// `images` folder beside the scene or in one of the folders above it (the course's
/// bundle names `../../images/X` where the file is `../images/X`, a path that was broken
/// there too). Each file is read once per program and kept for the program's life (its
/// bytes are leaked: a host tool reads a scene's few textures once): every source made
/// by `beside`, for any scene file, hands out the same bytes for the same file, so that
/// a tool that reads one scene in several number formats, or again every frame, holds
/// each texture once. A file that cannot be read is `None`, which the parser reports as
/// [`TextureProblem::NotFound`](crate::scene::TextureProblem) at its `filename`.
///
/// A file changed on disk after it was first read is not read again.
pub fn beside(scene: &Path) -> impl FnMut(&str) -> Option<&'static [u8]> + use<> {
    let folder = scene.parent().map(Path::to_path_buf).unwrap_or_default();
    move |name: &str| read_once(find(&folder, name)?)
}

/// The bytes of the file at `path`, read on the first call for that file (by its
/// canonical path) and shared by every later one.
fn read_once(path: PathBuf) -> Option<&'static [u8]> {
    static READ: OnceLock<Mutex<HashMap<PathBuf, &'static [u8]>>> = OnceLock::new();
    let path = std::fs::canonicalize(&path).unwrap_or(path);
    // A thread that panicked while holding the lock left the map whole (an insert is
    // the only change): go on with it.
    let mut read = READ
        .get_or_init(Mutex::default)
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    if let Some(bytes) = read.get(&path) {
        return Some(*bytes);
    }
    let bytes: &'static [u8] = Box::leak(std::fs::read(&path).ok()?.into_boxed_slice());
    read.insert(path, bytes);
    Some(bytes)
}

/// Where `name` is: beside the scene, else `images/<file name>` here or above.
fn find(folder: &Path, name: &str) -> Option<PathBuf> {
    let direct = folder.join(name);
    if direct.is_file() {
        return Some(direct);
    }
    let file = Path::new(name).file_name()?;
    let mut candidates: Vec<PathBuf> = Vec::new();
    let mut at = Some(folder);
    while let Some(dir) = at {
        candidates.push(dir.join("images").join(file));
        at = dir.parent().filter(|p| !p.as_os_str().is_empty());
    }
    candidates.push(Path::new("images").join(file));
    candidates.into_iter().find(|p| p.is_file())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two sources, for two scene files in one folder, hand out one copy of a texture
    /// file's bytes: a tool that reads a scene once per number format holds each
    /// texture once.
    #[test]
    fn every_source_shares_a_files_bytes() {
        let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let mut first = beside(&scenes.join("texplane.scene"));
        let mut second = beside(&scenes.join("projector.scene"));
        let a = first("textures/mike32.ppm").unwrap();
        let b = second("textures/mike32.ppm").unwrap();
        let again = first("textures/mike32.ppm").unwrap();
        assert_eq!(
            a,
            std::fs::read(scenes.join("textures/mike32.ppm")).unwrap()
        );
        assert!(core::ptr::eq(a, b) && core::ptr::eq(a, again));
        assert_eq!(first("textures/no-such-file.ppm"), None);
    }
}
