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
//!   block), or none shadows any corner and no sphere's shadow box on the plane meets the
//!   block's box (a plane's shadow is a half-plane: four corners outside it put the block
//!   outside it);
//! - **the colour's range is bounded**: on a plane a diffuse point light gives
//!   `255·(N·L)/|L|²` with `N·L` the light's height above the plane, the same at every
//!   point, so over the block the term lies between its values at the largest distance
//!   (a corner) and the smallest (no nearer than the block's box); the sum over the lit
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
/// The most sphere boxes and shadow boxes a sampled frame keeps.
const BOXES: usize = 48;

/// A box of world space, `(low, high)` corners.
type Aabb<S> = (Vec3<S>, Vec3<S>);

/// What a sampled frame computes once: the spheres' screen boxes and their shadows'
/// boxes on every plane.
#[derive(Debug, Clone)]
pub(crate) struct Sampler<S> {
    size: u16,
    bound: S,
    /// `(rows, columns)` of every sphere, first and last inclusive.
    spheres: Vec<((u16, u16), (u16, u16)), BOXES>,
    /// `(sphere, light, plane)` and the box that holds the sphere's shadow from the
    /// light on the plane (`None`: it may fall anywhere on it).
    shadows: Vec<((u8, u8, u8), Option<Aabb<S>>), BOXES>,
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
    let mut shadows = Vec::new();
    for (k, sphere) in scene.objects.iter().enumerate() {
        let Shape::Sphere(sphere) = &sphere.shape else {
            continue;
        };
        for (j, light) in scene.lights.iter().enumerate() {
            for (i, plane) in scene.objects.iter().enumerate() {
                let Some(plane) = plane.shape.plane() else {
                    continue;
                };
                let b = shadow_box(plane, sphere, light.location);
                let key = (
                    u8::try_from(k).ok()?,
                    u8::try_from(j).ok()?,
                    u8::try_from(i).ok()?,
                );
                shadows.push((key, b)).ok()?;
            }
        }
    }
    Some(Sampler {
        size: size.pixels(),
        bound: S::from_i32(i32::from(bound))?,
        spheres,
        shadows,
    })
}

/// A box holding the shadow of `sphere` from a light at `light` on `plane`: the central
/// projection from the light onto the plane of the corners of a cube a quarter wider
/// than the sphere (the projection of a convex set lies in the hull of its corners'
/// projections while every corner is nearer the plane than the light is). `None` where
/// the shadow is not bounded (a corner level with the light or beyond it, or the light
/// in the plane) or a quantity leaves the format.
fn shadow_box<S: Scalar>(
    plane: &crate::geometry::Plane<S>,
    sphere: &crate::geometry::Sphere<S>,
    light: Vec3<S>,
) -> Option<Aabb<S>> {
    let (mut n, mut d) = (plane.normal(), plane.offset());
    let mut h = n.dot(light)?.checked_sub(d)?;
    if h < S::ZERO {
        (n, d, h) = (n.checked_neg()?, d.checked_neg()?, h.checked_neg()?);
    }
    if h <= S::ZERO {
        return None;
    }
    let nl = d.checked_add(h)?;
    let half = sphere.radius().mul_ratio(5, 4)?;
    let c = sphere.center();
    let mut lo = Vec3::new(S::MAX, S::MAX, S::MAX);
    let low = S::MAX.checked_neg()?;
    let mut hi = Vec3::new(low, low, low);
    for corner in 0..8u8 {
        let pick = |bit: u8, v: S| -> Option<S> {
            if corner & bit == 0 {
                v.checked_sub(half)
            } else {
                v.checked_add(half)
            }
        };
        let v = Vec3::new(pick(1, c.x)?, pick(2, c.y)?, pick(4, c.z)?);
        let den = nl.checked_sub(n.dot(v)?)?;
        if den <= S::ZERO {
            return None;
        }
        let s = h.checked_div(den)?;
        let x = light.sum(v.diff(light)?.scale(s)?)?;
        lo = Vec3::new(lo.x.min(x.x), lo.y.min(x.y), lo.z.min(x.z));
        hi = Vec3::new(hi.x.max(x.x), hi.y.max(x.y), hi.z.max(x.z));
    }
    Some((lo, hi))
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
    fn spread(
        &self,
        scene: &SceneView<'_, S>,
        object: u8,
        points: &[Vec3<S>; 4],
        all: [u32; LIGHTS],
        any: [u32; LIGHTS],
    ) -> Option<[S; 3]> {
        let o = scene.objects.get(usize::from(object))?;
        let material = scene.materials.get(usize::from(o.material));
        let n = o.shape.plane()?.normal();
        let (mut lo, mut hi) = (points[0], points[0]);
        for p in &points[1..] {
            lo = Vec3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z));
            hi = Vec3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z));
        }
        let mut spread = [S::ZERO; 3];
        for (j, light) in scene.lights.iter().enumerate() {
            if all[j] != 0 {
                continue; // shadowed (or facing away) everywhere in the block
            }
            if any[j] != 0 {
                return None; // shadowed at some corners only
            }
            let clear = self.shadows.iter().all(|&((_, l, plane), b)| {
                usize::from(l) != j
                    || plane != object
                    || b.is_some_and(|(slo, shi)| !boxes_meet((lo, hi), (slo, shi)))
            });
            if !clear {
                return None;
            }
            // Which of a tiled plane's two materials the block's tile has is not
            // kept: the larger diffuse of the two bounds it.
            let diffuse = diffuse_bound(scene, o, material)?;
            let (mut nl_lo, mut nl_hi, mut ll_hi) = (S::MAX, S::ZERO, S::ZERO);
            for p in points {
                let l = light.location.diff(*p)?;
                let nl = n.dot(l)?.abs();
                nl_lo = nl_lo.min(nl);
                nl_hi = nl_hi.max(nl);
                ll_hi = ll_hi.max(l.dot(l)?);
            }
            let ll_lo = distance_sq_to_box(light.location, (lo, hi))?;
            let k = S::from_i32(255)?;
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

/// The larger per-channel diffuse of an object's materials (a tiled plane has two).
fn diffuse_bound<S: Scalar>(
    scene: &SceneView<'_, S>,
    o: &crate::Object<S>,
    material: Option<&crate::Material<S>>,
) -> Option<[S; 3]> {
    let mut d = material?.diffuse.map(S::abs);
    if let Shape::Tiled { alt, .. } = o.shape {
        let a = scene.materials.get(usize::from(alt))?;
        for (x, y) in d.iter_mut().zip(a.diffuse) {
            *x = x.max(y.abs());
        }
    }
    Some(d)
}

/// Whether two boxes share a point.
fn boxes_meet<S: Scalar>(a: Aabb<S>, b: Aabb<S>) -> bool {
    let axes = |v: Vec3<S>| [v.x, v.y, v.z];
    let (alo, ahi, blo, bhi) = (axes(a.0), axes(a.1), axes(b.0), axes(b.1));
    (0..3).all(|i| alo[i] <= bhi[i] && blo[i] <= ahi[i])
}

/// The squared distance from `p` to a box (0 inside it), no larger than the squared
/// distance to any point of the box; `None` when it is 0 (no bound on `1/|L|²`) or out of
/// range.
fn distance_sq_to_box<S: Scalar>(p: Vec3<S>, (lo, hi): Aabb<S>) -> Option<S> {
    let gap = |v: S, a: S, b: S| -> Option<S> {
        if v < a {
            a.checked_sub(v)
        } else if v > b {
            v.checked_sub(b)
        } else {
            Some(S::ZERO)
        }
    };
    let g = [
        gap(p.x, lo.x, hi.x)?,
        gap(p.y, lo.y, hi.y)?,
        gap(p.z, lo.z, hi.z)?,
    ];
    let mut sum = S::ZERO;
    for g in g {
        sum = sum.checked_add(g.checked_mul(g)?)?;
    }
    (sum > S::ZERO).then_some(sum)
}

/// Draws rows `rows` (inside one band of the sampler's blocks) over columns `columns` of
/// a sampled frame into `out` (`out[(r − rows.start)·stride + (x − columns.start)]`):
/// certified blocks filled from their corners, the others by `exact` (the frame's
/// kernel: row, columns, the slice they go to).
pub(crate) fn sampled_rows<S: Scalar, C: From<Rgb888>>(
    scene: &SceneView<'_, S>,
    shading: Shading,
    sampler: &Sampler<S>,
    (rows, columns): (Range<u16>, Range<u16>),
    (out, stride): (&mut [C], usize),
    exact: &mut impl FnMut(u16, Range<u16>, &mut [C]),
) {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let b = sampler.size;
    let end = columns.end.min(w);
    if rows.start >= rows.end || columns.start >= end {
        return;
    }
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
            fill(
                (corners.map(|c| c.color), (x0, x1), (top, bottom)),
                (rows.clone(), x0.max(columns.start)..next.min(end)),
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
