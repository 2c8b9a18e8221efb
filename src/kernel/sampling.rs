//! Adaptive sampling: a frame traced at the corners of square blocks and filled between
//! them where a certificate says what the block holds ([`Sampling::Blocks`]).
//!
//! A block of `B × B` pixels (`B` = 2, 4 or 8) is traced at its four corners on the
//! reference path (the definition, [`crate::shade::trace_pixel`]), and filled by
//! bilinear interpolation of their colours only where all of these hold:
//! - **no sphere's box** on the screen meets the block (the kernels' boxes, outside
//!   which no primary ray meets a sphere): a sphere smaller than the block is never
//!   missed, and a sphere's pixels are always traced;
//! - **the same surface** at the four corners: the same infinite plane and the same
//!   tile of a checkerboard, or the background at all four. The pixels where one infinite
//!   plane is the nearest hit, where a tile lies, or where nothing is hit are each convex
//!   on the screen (intersections of half-planes), so four corners in one of them put
//!   the whole block in it;
//! - **the same shadow state** for every light: either one occluder shadows all four
//!   corners (a sphere's or a plane's shadow on a plane is convex, so it covers the
//!   block), or none shadows any corner and every sphere stands clear of the segments
//!   from the light to the block (a plane's shadow is a half-plane: four corners outside
//!   it put the block outside it);
//! - **the colour's range is bounded**: on a plane a diffuse point light gives
//!   `255·(N·L)/|L|²` with `N·L` the light's height above the plane, the same at every
//!   point, so over the block the term lies between its values at the largest distance
//!   (a corner) and a bound on the smallest; the sum over the lit
//!   lights of `emissivity · diffuse ·` that spread, per channel, must be at most the
//!   mode's `bound` in levels.
//!
//! Any other block is drawn by the frame's kernel, pixel by pixel, as the exact frame
//! draws it. A filled pixel lies within the colour's range over its block, as the exact
//! frame's pixel does: the two differ by at most `bound` levels plus the rounding of the
//! corners' colours and of the exact pixel (`tests/sampling.rs` measures the largest
//! difference). With `bound` 0 only blocks of one colour are filled (the background, a
//! shadowed tile under one light, an unlit surface): the exact frame bit for bit.
//!
//! Only frames of the crate's rules whose objects are infinite planes (plain or tiled)
//! and spheres, lit by point lights without glints, mirrors, translucency, spotlights,
//! projectors or a light on a surface, and drawn by a kernel that knows the spheres'
//! boxes (or has no sphere), are sampled; any other frame is drawn exact
//! ([`crate::Frame::sampled`] says which).

use core::ops::Range;

use embedded_graphics_core::pixelcolor::Rgb888;
use heapless::Vec;

use super::{Drawing, Kernel};
use crate::geometry::{Tiling, surface_tolerance};
use crate::shade::color::to_pixel;
use crate::shade::stages::Shading;
use crate::shade::trace_pixel_with;
use crate::{Plan, Rules, Scalar, SceneView, Shape, Vec3};

/// How a frame finds its pixels ([`crate::Frame::with_sampling`]).
///
/// ```
/// use fixray::{BlockSize, Frame, Sampling, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(include_str!("../../scenes/boing.scene"))?;
/// let exact: Frame<'_, I16F16> = Frame::new(&scene);
/// let sampled = Frame::new(&scene).with_sampling(Sampling::blocks(BlockSize::Four, 2));
/// assert_eq!(exact.sampling(), Sampling::Exact);
/// assert!(sampled.sampled()); // the boing ball's kind of scene is sampled
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Sampling {
    /// Every pixel traced (the default).
    #[default]
    Exact,
    /// Blocks traced at their corners and filled where certified (the module
    /// documentation of [`crate::Frame::with_sampling`]).
    Blocks {
        /// The block's side.
        size: BlockSize,
        /// How far, in levels of a channel, the colour may vary over a filled block.
        bound: u8,
    },
}

impl Sampling {
    /// Blocks of `size` filled where the colour varies by at most `bound` levels.
    pub const fn blocks(size: BlockSize, bound: u8) -> Self {
        Sampling::Blocks { size, bound }
    }
}

/// The side of a sampled block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BlockSize {
    /// 2 × 2 pixels.
    Two,
    /// 4 × 4 pixels.
    Four,
    /// 8 × 8 pixels.
    Eight,
}

impl BlockSize {
    /// The side in pixels.
    pub const fn pixels(self) -> u16 {
        match self {
            BlockSize::Two => 2,
            BlockSize::Four => 4,
            BlockSize::Eight => 8,
        }
    }
}

/// The most lights a sampled frame has (a corner keeps each one's shadow state).
const LIGHTS: usize = 4;
/// The most objects a sampled frame has (a shadow state is a mask of occluders).
const OBJECTS: usize = 30;
/// A shadow state's bit for a light the surface faces away from (no occluder's index).
const FACES_AWAY: u32 = 1 << 31;
/// The most spheres a sampled frame has.
const BOXES: usize = 16;

/// What a sampled frame computes once: the spheres' boxes on the screen.
#[derive(Debug, Clone)]
pub(crate) struct Sampler<S> {
    size: u16,
    bound: S,
    /// `(rows, columns)` of every sphere, first and last inclusive.
    spheres: Vec<((u16, u16), (u16, u16)), BOXES>,
}

/// The sampler of a frame of `scene` drawn with `drawing` (`None`: the frame is drawn
/// exact, by the mode or because the scene is not of a kind the certificates cover).
pub(crate) fn sampler<S: Scalar>(
    scene: &SceneView<'_, S>,
    plan: &Plan,
    drawing: &Drawing<S>,
    sampling: Sampling,
) -> Option<Sampler<S>> {
    let Sampling::Blocks { size, bound } = sampling else {
        return None;
    };
    let plain = scene.rules == Rules::Fixray
        && !(plan.specular
            || plan.spotlights
            || plan.projectors
            || plan.reflection
            || plan.transparency
            || plan.lights_on_surfaces)
        && scene.lights.len() <= LIGHTS
        && scene.objects.len() <= OBJECTS
        && scene.objects.iter().all(|o| {
            matches!(
                o.shape,
                Shape::Plane(_) | Shape::Tiled { .. } | Shape::Sphere(_)
            )
        })
        && scene
            .lights
            .iter()
            .all(|l| matches!(l.beam, crate::scene::Beam::Everywhere));
    if !plain {
        return None;
    }
    let mut spheres = Vec::new();
    match &drawing.kernel {
        Kernel::Fast(p) | Kernel::Rows(super::rows::Rows { primary: p }) => {
            for b in p.sphere_boxes() {
                spheres.push(b).ok()?;
            }
        }
        Kernel::Flat(_) if !plan.spheres => {}
        Kernel::Flat(_) | Kernel::Reference => return None,
    }
    Some(Sampler {
        size: size.pixels(),
        bound: S::from_i32(i32::from(bound))?,
        spheres,
    })
}

/// What a block's corner sees.
#[derive(Debug, Clone, Copy)]
enum Sees<S> {
    /// Something no certificate covers (a sphere, a ray that cannot be formed).
    Other,
    /// Nothing: the background.
    Background,
    /// An infinite plane.
    Plane {
        object: u8,
        tile: (i32, i32),
        point: Vec3<S>,
        /// Per light: the occluders between the point and the light (bit `k`: object
        /// `k`), or [`FACES_AWAY`].
        shadows: [u32; LIGHTS],
    },
}

/// A traced corner: its colour and what it sees.
#[derive(Debug, Clone, Copy)]
struct Corner<S> {
    color: Rgb888,
    sees: Sees<S>,
}

/// Traces pixel (`column`, `row`) on the reference path and says what it sees.
fn corner<S: Scalar>(
    scene: &SceneView<'_, S>,
    shading: Shading,
    column: u16,
    row: u16,
) -> Corner<S> {
    let traced = trace_pixel_with(scene, shading, column, row);
    let color = to_pixel(scene.rules, traced.color);
    let formed = scene
        .camera
        .screen_y(row)
        .and_then(|y| scene.camera.pixel_ray_at(column, y))
        .is_some();
    let sees = match traced.hit {
        _ if !formed => Sees::Other,
        None => Sees::Background,
        Some((index, hit)) => plane_seen(scene, index, hit).unwrap_or(Sees::Other),
    };
    Corner { color, sees }
}

/// What a corner whose ray met `objects[index]` at `hit` sees, if it is a plane.
fn plane_seen<S: Scalar>(
    scene: &SceneView<'_, S>,
    index: usize,
    hit: crate::Hit<S>,
) -> Option<Sees<S>> {
    let shape = &scene.objects.get(index)?.shape;
    let tile = match shape {
        Shape::Plane(_) => (0, 0),
        Shape::Tiled { frame, tiling, .. } => match tiling {
            Tiling::Frame => frame.tile(hit.point)?,
            Tiling::WorldXz => frame.tile_world_xz(hit.point)?,
        },
        _ => return None,
    };
    let plane = shape.plane()?;
    let point = hit.point;
    // The side the eye sees: a light lights the point only from that side.
    let eye_side = plane.normal().dot(scene.camera.viewpoint.diff(point)?)?;
    let tol = surface_tolerance(hit.t, point.max_abs())?;
    let mut shadows = [0; LIGHTS];
    for (state, light) in shadows.iter_mut().zip(scene.lights) {
        let l = light.location.diff(point)?;
        let nl = plane.normal().dot(l)?;
        if nl == S::ZERO || (nl > S::ZERO) != (eye_side > S::ZERO) {
            *state = FACES_AWAY;
            continue;
        }
        let ll = l.dot(l)?;
        for (k, o) in scene.objects.iter().enumerate() {
            if k != index && o.shape.meets_segment(point, l, ll, tol, scene.epsilon) {
                *state |= 1 << k;
            }
        }
    }
    Some(Sees::Plane {
        object: u8::try_from(index).ok()?,
        tile,
        point,
        shadows,
    })
}

impl<S: Scalar> Sampler<S> {
    /// The block side.
    pub(crate) fn size(&self) -> u16 {
        self.size
    }

    /// Whether a block with these corners (top left, top right, bottom left, bottom
    /// right) over columns `x` and rows `y` (first and last, inclusive) may be filled.
    fn certifies(
        &self,
        scene: &SceneView<'_, S>,
        corners: [&Corner<S>; 4],
        x: (u16, u16),
        y: (u16, u16),
    ) -> bool {
        let meets = |(a, b): (u16, u16), (c, d): (u16, u16)| a <= d && c <= b;
        if self
            .spheres
            .iter()
            .any(|&(rows, columns)| meets(rows, y) && meets(columns, x))
        {
            return false;
        }
        match corners.map(|c| c.sees) {
            [
                Sees::Background,
                Sees::Background,
                Sees::Background,
                Sees::Background,
            ] => true,
            [
                Sees::Plane {
                    object,
                    tile,
                    point: p0,
                    shadows: s0,
                },
                b,
                c,
                d,
            ] => {
                let mut points = [p0; 4];
                let (mut all, mut any) = (s0, s0);
                for (slot, seen) in points[1..].iter_mut().zip([b, c, d]) {
                    let Sees::Plane {
                        object: o,
                        tile: t,
                        point,
                        shadows,
                    } = seen
                    else {
                        return false;
                    };
                    if o != object || t != tile {
                        return false;
                    }
                    *slot = point;
                    for ((a, n), s) in all.iter_mut().zip(any.iter_mut()).zip(shadows) {
                        *a &= s;
                        *n |= s;
                    }
                }
                self.spread(scene, object, &points, all, any)
                    .is_some_and(|spread| spread.iter().all(|c| *c <= self.bound))
            }
            _ => false,
        }
    }

    /// The most the colour of plane `object` can vary, per channel, over the block whose
    /// corners hit it at `points`, given each light's occluders common to all corners
    /// (`all`) and found at any (`any`); `None` where the shadow state may change inside
    /// the block or a quantity leaves the format.
    ///
    /// The block's points lie within `ρ` of the corners' centroid `m` (the largest
    /// distance from it to a corner: the block is their convex hull). A segment from the
    /// light to such a point lies within `ρ` of the segment to `m` (point for point), so
    /// a sphere farther than `r·17/16 + ρ` from that segment shadows none of them (the
    /// sixteenth: the shadow test's rounding at its edge). The distance to the light
    /// lies between `|L − m| − ρ` and the largest at a corner (a convex function on a
    /// convex set peaks at a vertex).
    fn spread(
        &self,
        scene: &SceneView<'_, S>,
        object: u8,
        points: &[Vec3<S>; 4],
        all: [u32; LIGHTS],
        any: [u32; LIGHTS],
    ) -> Option<[S; 3]> {
        let o = scene.objects.get(usize::from(object))?;
        let n = o.shape.plane()?.normal();
        let mut m = points[0];
        for p in &points[1..] {
            m = m.sum(*p)?;
        }
        let m = Vec3::new(
            m.x.mul_ratio(1, 4)?,
            m.y.mul_ratio(1, 4)?,
            m.z.mul_ratio(1, 4)?,
        );
        let mut rho_sq = S::ZERO;
        for p in points {
            let d = p.diff(m)?;
            rho_sq = rho_sq.max(d.dot(d)?);
        }
        let rho = rho_sq.checked_sqrt()?.checked_add(S::DELTA)?;
        let diffuse = diffuse_bound(scene, o)?;
        let k = S::from_i32(255)?;
        let mut spread = [S::ZERO; 3];
        for (j, light) in scene.lights.iter().enumerate() {
            if all[j] != 0 {
                continue; // shadowed (or facing away) everywhere in the block
            }
            if any[j] != 0 {
                return None; // shadowed at some corners only
            }
            let to_m = m.diff(light.location)?;
            for sphere in scene.objects.iter().filter_map(|o| match &o.shape {
                Shape::Sphere(s) => Some(s),
                _ => None,
            }) {
                let margin = sphere.radius().mul_ratio(17, 16)?.checked_add(rho)?;
                let d = distance_sq_to_segment(sphere.center(), light.location, to_m)?;
                if d <= margin.checked_mul(margin)? {
                    return None;
                }
            }
            let (mut nl_lo, mut nl_hi, mut ll_hi) = (S::MAX, S::ZERO, S::ZERO);
            for p in points {
                let l = light.location.diff(*p)?;
                let nl = n.dot(l)?.abs();
                nl_lo = nl_lo.min(nl);
                nl_hi = nl_hi.max(nl);
                ll_hi = ll_hi.max(l.dot(l)?);
            }
            let near = to_m.dot(to_m)?.checked_sqrt()?.checked_sub(rho)?;
            if near <= S::ZERO {
                return None;
            }
            let ll_lo = near.checked_mul(near)?;
            let top = nl_hi.checked_mul(k)?.checked_div(ll_lo)?;
            let bottom = nl_lo.checked_mul(k)?.checked_div(ll_hi)?;
            let range = top.checked_sub(bottom)?;
            for ((s, e), d) in spread.iter_mut().zip(light.emissivity).zip(diffuse) {
                *s = s.checked_add(e.abs().checked_mul(d)?.checked_mul(range)?)?;
            }
        }
        Some(spread)
    }
}

/// The larger per-channel diffuse of an object's materials (a tiled plane has two, and
/// which one a block's tile has is not kept).
fn diffuse_bound<S: Scalar>(scene: &SceneView<'_, S>, o: &crate::Object<S>) -> Option<[S; 3]> {
    let mut d = scene
        .materials
        .get(usize::from(o.material))?
        .diffuse
        .map(S::abs);
    if let Shape::Tiled { alt, .. } = o.shape {
        let a = scene.materials.get(usize::from(alt))?;
        for (x, y) in d.iter_mut().zip(a.diffuse) {
            *x = x.max(y.abs());
        }
    }
    Some(d)
}

/// The squared distance from `c` to the segment from `a` to `a + v`.
fn distance_sq_to_segment<S: Scalar>(c: Vec3<S>, a: Vec3<S>, v: Vec3<S>) -> Option<S> {
    let w = c.diff(a)?;
    let wv = w.dot(v)?;
    let vv = v.dot(v)?;
    let s = if wv <= S::ZERO || vv <= S::ZERO {
        S::ZERO
    } else if wv >= vv {
        S::ONE
    } else {
        wv.checked_div(vv)?
    };
    let d = w.diff(v.scale(s)?)?;
    d.dot(d)
}

/// Draws rows `rows` (inside one band of the sampler's blocks) over columns `columns` of
/// a sampled frame into `out` (`out[(r − rows.start)·stride + (x − columns.start)]`):
/// certified blocks filled from their corners, the others by `exact` (the frame's
/// kernel: row, columns, the slice they go to). Returns how many pixels were filled.
pub(crate) fn sampled_rows<S: Scalar, C: From<Rgb888>>(
    scene: &SceneView<'_, S>,
    shading: Shading,
    sampler: &Sampler<S>,
    (rows, columns): (Range<u16>, Range<u16>),
    (out, stride): (&mut [C], usize),
    exact: &mut impl FnMut(u16, Range<u16>, &mut [C]),
) -> usize {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let b = sampler.size;
    let end = columns.end.min(w);
    if rows.start >= rows.end || columns.start >= end {
        return 0;
    }
    let mut filled = 0;
    let top = rows.start / b * b;
    let bottom = top.saturating_add(b).min(h - 1);
    let band = top..top.saturating_add(b).min(h);
    let rows = rows.start..rows.end.min(band.end);
    let trace = |x: u16, y: u16| corner(scene, shading, x, y);
    let mut x0 = columns.start / b * b;
    let mut left = (trace(x0, top), trace(x0, bottom));
    let mut pending: Option<u16> = None;
    let mut flush = |from: u16, to: u16, out: &mut [C]| {
        let (from, to) = (from.max(columns.start), to.min(end));
        if from >= to {
            return;
        }
        for r in rows.clone() {
            let at = usize::from(r - rows.start) * stride + usize::from(from - columns.start);
            if let Some(slot) = out.get_mut(at..at + usize::from(to - from)) {
                exact(r, from..to, slot);
            }
        }
    };
    while x0 < end {
        let x1 = x0.saturating_add(b).min(w - 1);
        let right = (trace(x1, top), trace(x1, bottom));
        let corners = [&left.0, &right.0, &left.1, &right.1];
        let next = x0.saturating_add(b).min(w);
        if sampler.certifies(scene, corners, (x0, x1), (top, bottom)) {
            if let Some(from) = pending.take() {
                flush(from, x0, out);
            }
            let span = x0.max(columns.start)..next.min(end);
            filled += rows.len() * span.len();
            fill(
                (corners.map(|c| c.color), (x0, x1), (top, bottom)),
                (rows.clone(), span),
                (out, stride, (rows.start, columns.start)),
            );
        } else if pending.is_none() {
            pending = Some(x0);
        }
        left = right;
        x0 = next;
    }
    if let Some(from) = pending {
        flush(from, end, out);
    }
    filled
}

/// Fills the pixels `rows × columns` of a block by bilinear interpolation of its corner
/// colours (top left, top right, bottom left, bottom right at columns `x` and rows `y`),
/// each channel rounded to nearest.
fn fill<C: From<Rgb888>>(
    (colors, x, y): ([Rgb888; 4], (u16, u16), (u16, u16)),
    (rows, columns): (Range<u16>, Range<u16>),
    (out, stride, origin): (&mut [C], usize, (u16, u16)),
) {
    use embedded_graphics_core::pixelcolor::RgbColor;
    let w = u32::from(x.1 - x.0).max(1);
    let h = u32::from(y.1 - y.0).max(1);
    let channels = |c: Rgb888| [u32::from(c.r()), u32::from(c.g()), u32::from(c.b())];
    let [c00, c10, c01, c11] = colors.map(channels);
    let area = w * h;
    for r in rows {
        let v = u32::from(r - y.0).min(h);
        let row = usize::from(r - origin.0) * stride;
        for col in columns.clone() {
            let u = u32::from(col - x.0).min(w);
            let mut c = [0u8; 3];
            for (i, slot) in c.iter_mut().enumerate() {
                let sum = c00[i] * (w - u) * (h - v)
                    + c10[i] * u * (h - v)
                    + c01[i] * (w - u) * v
                    + c11[i] * u * v;
                *slot = u8::try_from((sum + area / 2) / area).unwrap_or(u8::MAX);
            }
            if let Some(p) = out.get_mut(row + usize::from(col - origin.1)) {
                *p = C::from(Rgb888::new(c[0], c[1], c[2]));
            }
        }
    }
}
