//! Texel lookups (`COURSE-RULES.md` §12, §13): where a point of a [`Slide`] falls in its
//! texture, for textured planes (their material's ambient and diffuse times the texel)
//! and projectors (their emissivity times the texel).

use crate::{Material, Scalar, SceneView, Slide, TexMode, Vec3};

/// The texel of `slide` at `point` (a point of its plane inside its rectangle), each
/// channel 0 ..= 255: `mode 0` stretches the texture over the rectangle,
/// `tx = int(a / W · tw)`; `mode 1` repeats it with one texel per screen pixel's size,
/// `tx = int(a · pixels / world) mod tw` (and `ty` alike along `v`, counted from the
/// texture's bottom row), `(a, b)` the point's plane coordinates from the slide's corner.
/// `None` when the texture is not in the scene or a coordinate does not fit the format.
pub(crate) fn texel<S: Scalar>(
    scene: &SceneView<'_, S>,
    slide: &Slide<S>,
    point: Vec3<S>,
) -> Option<[u8; 3]> {
    let image = scene.textures.get(usize::from(slide.texture))?;
    let (a, b) = slide.frame.coords(point)?;
    let [w, h] = slide.frame.size();
    let (tw, th) = (image.width(), image.height());
    let camera = &scene.camera;
    let (tx, ty) = match slide.mode {
        TexMode::Fit => (fit(a, w, tw)?, fit(b, h, th)?),
        TexMode::Tile => (
            tile(a, camera.width, camera.world_width, tw)?,
            tile(b, camera.height, camera.world_height, th)?,
        ),
    };
    image.pixel(tx, th - 1 - ty)
}

/// `int(a / size · n)`, kept within `0 ..= n − 1` (the rectangle's far edge is in it).
fn fit<S: Scalar>(a: S, size: S, n: u32) -> Option<u32> {
    let n = i32::try_from(n).ok()?;
    let i = a
        .checked_div(size)?
        .checked_mul(S::from_i32(n)?)?
        .floor_to_i32()?;
    u32::try_from(i.clamp(0, n - 1)).ok()
}

/// `int(a · pixels / world) mod n`: the product first where it fits (one rounding).
fn tile<S: Scalar>(a: S, pixels: u16, world: S, n: u32) -> Option<u32> {
    let p = S::from_i32(i32::from(pixels))?;
    let cells = match a.checked_mul(p) {
        Some(ap) => ap.checked_div(world)?,
        None => a.checked_div(world)?.checked_mul(p)?,
    };
    let i = cells.floor_to_i32()?;
    u32::try_from(i.rem_euclid(i32::try_from(n).ok()?)).ok()
}

/// A material seen through a texel: ambient and diffuse times `texel / 255`, channel by
/// channel (a texel that cannot be had shows black).
pub(crate) fn textured<S: Scalar>(material: &Material<S>, texel: Option<[u8; 3]>) -> Material<S> {
    let t = texel.unwrap_or([0; 3]);
    let mut m = *material;
    for ((a, d), tk) in m.ambient.iter_mut().zip(&mut m.diffuse).zip(t) {
        let f = |c: S| c.mul_ratio(i32::from(tk), 255).unwrap_or(S::ZERO);
        *a = f(*a);
        *d = f(*d);
    }
    m
}
