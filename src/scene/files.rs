//! Texture files on a host (cargo feature `std`): a file source for
//! [`Scene::read_with`](crate::Scene::read_with) that reads the files a scene names
//! relative to the scene file's folder.
//!
//! ```no_run
//! use std::path::Path;
//! use fixray::{LargeScene, scene::files};
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
use std::vec::Vec;

/// A file source that reads a texture's `filename` relative to the folder of the scene
/// file `scene`. A name not found there is looked for by its last component in an
/// `images` folder beside the scene or in one of the folders above it (the course's
/// bundle names `../../images/X` where the file is `../images/X`, a path that was broken
/// there too). Each file is read once and kept for the program's life (its bytes are
/// leaked: a host tool reads a scene's few textures once); a file that cannot be read is
/// `None`, which the parser reports as [`TextureProblem::NotFound`](crate::scene::TextureProblem)
/// at its `filename`.
pub fn beside(scene: &Path) -> impl FnMut(&str) -> Option<&'static [u8]> + use<> {
    let folder = scene.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut read: HashMap<PathBuf, &'static [u8]> = HashMap::new();
    move |name: &str| {
        let path = find(&folder, name)?;
        if let Some(bytes) = read.get(&path) {
            return Some(*bytes);
        }
        let bytes: &'static [u8] = Box::leak(std::fs::read(&path).ok()?.into_boxed_slice());
        read.insert(path, bytes);
        Some(bytes)
    }
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
