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

/// How a certified block is filled.
#[derive(Debug, Clone, Copy)]
enum Fill<S> {
    /// From its corners' colours (top left, top right, bottom left, bottom right).
    Smooth([Rgb888; 4]),
    /// A tiled plane across one tile edge or two: each pixel's tile from the edges'
    /// lines located on the screen, its colour interpolated from the corners' colours in
    /// that tile's material.
    Tiles(Tiles<S>),
}

/// A block of a tiled plane that crosses a tile edge along `u`, along `v`, or both.
#[derive(Debug, Clone, Copy)]
struct Tiles<S> {
    /// The corners' colours in the plane's material and in its alternate.
    colors: [[Rgb888; 4]; 2],
    /// Per axis: the corners' `(a − A)·β` for the edge `a = A` between the block's two
    /// tiles (`β = N·D`, so that it is affine on the screen), or `None` where the block
    /// lies in one tile along that axis.
    edges: [Option<[S; 4]>; 2],
    /// The lower tile along each axis.
    first: (i32, i32),
    /// Whether `β` is negative over the block (the sides are then swapped).
    negative: bool,
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

    /// How a block with these corners (top left, top right, bottom left, bottom right)
    /// over columns `x` and rows `y` (first and last, inclusive) may be filled; `None`:
    /// it is traced.
    fn certifies(
        &self,
        scene: &SceneView<'_, S>,
        corners: [&Corner<S>; 4],
        x: (u16, u16),
        y: (u16, u16),
    ) -> Option<Fill<S>> {
        let meets = |(a, b): (u16, u16), (c, d): (u16, u16)| a <= d && c <= b;
        if self
            .spheres
            .iter()
            .any(|&(rows, columns)| meets(rows, y) && meets(columns, x))
        {
            return None;
        }
        let colors = corners.map(|c| c.color);
        let seen = corners.map(|c| c.sees);
        if seen.iter().all(|s| matches!(s, Sees::Background)) {
            return Some(Fill::Smooth(colors));
        }
        let Sees::Plane { object, .. } = seen[0] else {
            return None;
        };
        let mut points = [Vec3::new(S::ZERO, S::ZERO, S::ZERO); 4];
        let mut tiles = [(0, 0); 4];
        let (mut all, mut any) = ([u32::MAX; LIGHTS], [0; LIGHTS]);
        for ((slot, tile), seen) in points.iter_mut().zip(tiles.iter_mut()).zip(seen) {
            let Sees::Plane {
                object: o,
                tile: t,
                point,
                shadows,
            } = seen
            else {
                return None;
            };
            if o != object {
                return None;
            }
            (*slot, *tile) = (point, t);
            for ((a, n), s) in all.iter_mut().zip(any.iter_mut()).zip(shadows) {
                *a &= s;
                *n |= s;
            }
        }
        let size = (x.1 - x.0, y.1 - y.0);
        let error = self.interpolation_error(scene, object, &points, (all, any), size)?;
        if error.iter().any(|c| *c > self.bound) {
            return None;
        }
        if tiles.iter().all(|t| *t == tiles[0]) {
            return Some(Fill::Smooth(colors));
        }
        // Across a tile's edge: only with a bound (the colours are this module's own).
        let lit = core::array::from_fn(|j| all[j] == 0);
        if self.bound > S::ZERO {
            tiles_fill(scene, object, (&points, &tiles), lit, (x, y))
        } else {
            None
        }
    }

    /// A bound, per channel, on how far the colour of plane `object` strays from the
    /// bilinear interpolation of its values at the corners over a block of `size` pixels
    /// whose corners hit it at `points`, given each light's occluders common to all
    /// corners (`all`) and found at any (`any`); `None` where the shadow state may change
    /// inside the block, a channel may reach 255 (where it is clamped, the colour is not
    /// smooth) or a quantity leaves the format.
    ///
    /// **Shadows.** The block's points lie within `ρ` of the corners' centroid `m` (the
    /// largest distance from it to a corner: the block is their convex hull). A segment
    /// from the light to such a point lies within `ρ` of the segment to `m` (point for
    /// point), so a sphere farther than `r·17/16 + ρ` from that segment shadows none of
    /// them (the sixteenth: the shadow test's rounding at its edge).
    ///
    /// **Colour.** A light's term is `f = K/ρ²` with `K = 255·(N·L)`, the same at every
    /// point of a plane, and `ρ = |L − P|`. Along a scanline the ray's `β = N·D` and
    /// `A = β·(L − P) = β·(L − e) − (N·P − N·e)·D` are affine in the column (and likewise
    /// down a column), so with `a = |A'|/|β|`, `b = |β'|/|β|` (per pixel), the relative
    /// derivatives of `ρ²` obey `|(ρ²)'|/ρ² ≤ 2a/ρ + 2b` and `|(ρ²)''|/ρ² ≤ 2a²/ρ² +
    /// 8ab/ρ + 6b²`, and `|f''| ≤ f·(2p² + q)` for those two bounds `p`, `q`. Bilinear
    /// interpolation over `w × h` pixels strays by at most `w²/8·|f_xx| + h²/8·|f_yy|`.
    /// The bounds take `|β|` at its smallest (a corner: `β` is affine and does not
    /// change sign over the block) and `ρ` at its smallest (`|L − m| − ρ`).
    fn interpolation_error(
        &self,
        scene: &SceneView<'_, S>,
        object: u8,
        points: &[Vec3<S>; 4],
        (all, any): ([u32; LIGHTS], [u32; LIGHTS]),
        (w, h): (u16, u16),
    ) -> Option<[S; 3]> {
        let o = scene.objects.get(usize::from(object))?;
        let plane = o.shape.plane()?;
        let n = plane.normal();
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
        let (diffuse, ambient) = materials_bound(scene, o)?;
        let camera = &scene.camera;
        let eye = camera.viewpoint;
        // What a pixel's step moves `D` by, across and down.
        let (sx, sy) = (
            camera
                .world_width
                .checked_div(S::from_i32(i32::from(camera.width))?)?,
            camera
                .world_height
                .checked_div(S::from_i32(i32::from(camera.height))?)?,
        );
        let steps = [
            Vec3::new(sx, S::ZERO, S::ZERO),
            Vec3::new(S::ZERO, sy, S::ZERO),
        ];
        let c0 = plane.offset().checked_sub(n.dot(eye)?)?;
        let mut beta = S::MAX;
        for p in points {
            beta = beta.min(n.dot(p.diff(eye)?)?.abs());
        }
        if beta <= S::ZERO {
            return None;
        }
        let k = S::from_i32(255)?;
        let (w, h) = (S::from_i32(i32::from(w))?, S::from_i32(i32::from(h))?);
        let sizes = [
            w.checked_mul(w)?.mul_ratio(1, 8)?,
            h.checked_mul(h)?.mul_ratio(1, 8)?,
        ];
        let mut error = [S::ZERO; 3];
        let mut top = ambient;
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
            let near = to_m.dot(to_m)?.checked_sqrt()?.checked_sub(rho)?;
            if near <= S::ZERO {
                return None;
            }
            let mut nl = S::ZERO;
            for p in points {
                nl = nl.max(n.dot(light.location.diff(*p)?)?.abs());
            }
            // The term at its largest.
            let f = nl.checked_mul(k)?.checked_div(near.checked_mul(near)?)?;
            let le = light.location.diff(eye)?;
            let mut curvature = S::ZERO;
            for (step, size) in steps.iter().zip(sizes) {
                let beta1 = n.dot(*step)?;
                let a1 = le.scale(beta1)?.diff(step.scale(c0)?)?;
                let a = a1.dot(a1)?.checked_sqrt()?.checked_div(beta)?;
                let b = beta1.abs().checked_div(beta)?;
                let an = a.checked_div(near)?;
                let p = an.checked_add(b)?.checked_mul_int(2)?;
                let q = an
                    .checked_mul(an)?
                    .checked_mul_int(2)?
                    .checked_add(an.checked_mul(b)?.checked_mul_int(8)?)?
                    .checked_add(b.checked_mul(b)?.checked_mul_int(6)?)?;
                let second = p.checked_mul(p)?.checked_mul_int(2)?.checked_add(q)?;
                // Each rounding above is at most a DELTA: a few more keep the bound one.
                let second = second.checked_add(S::DELTA.checked_mul_int(4)?)?;
                curvature = curvature.checked_add(size.checked_mul(second)?)?;
            }
            let stray = f.checked_mul(curvature)?;
            for (((e, t), c), d) in error
                .iter_mut()
                .zip(top.iter_mut())
                .zip(light.emissivity)
                .zip(diffuse)
            {
                let weight = c.abs().checked_mul(d)?;
                *e = e.checked_add(weight.checked_mul(stray)?)?;
                *t = t.checked_add(weight.checked_mul(f)?)?;
            }
        }
        if top.iter().any(|t| *t >= k) {
            return None;
        }
        Some(error)
    }
}

/// The fill of a block of tiled plane `object` whose corners (at `points`, in `tiles`)
/// lie in at most two tiles along each axis, under the lights `lit` (lit everywhere in
/// the block; the others light none of it), over columns `x` and rows `y`.
fn tiles_fill<S: Scalar>(
    scene: &SceneView<'_, S>,
    object: u8,
    (points, tiles): (&[Vec3<S>; 4], &[(i32, i32); 4]),
    lit: [bool; LIGHTS],
    (x, y): ((u16, u16), (u16, u16)),
) -> Option<Fill<S>> {
    let o = scene.objects.get(usize::from(object))?;
    let Shape::Tiled {
        frame,
        alt,
        tiling: Tiling::Frame,
    } = &o.shape
    else {
        return None;
    };
    let first = (
        tiles.iter().map(|t| t.0).min()?,
        tiles.iter().map(|t| t.1).min()?,
    );
    let last = (
        tiles.iter().map(|t| t.0).max()?,
        tiles.iter().map(|t| t.1).max()?,
    );
    if last.0 - first.0 > 1 || last.1 - first.1 > 1 {
        return None;
    }
    let camera = &scene.camera;
    let eye = camera.viewpoint;
    let n = frame.plane().normal();
    let at = [(x.0, y.0), (x.1, y.0), (x.0, y.1), (x.1, y.1)];
    let mut beta = [S::ZERO; 4];
    for (b, (c, r)) in beta.iter_mut().zip(at) {
        let d = Vec3::new(camera.screen_x(c)?, camera.screen_y(r)?, S::ZERO).diff(eye)?;
        *b = n.dot(d)?;
    }
    let negative = beta[0] < S::ZERO;
    if beta
        .iter()
        .any(|b| (*b < S::ZERO) != negative || *b == S::ZERO)
    {
        return None;
    }
    let size = frame.size();
    let mut edges = [None; 2];
    for (axis, edge) in edges.iter_mut().enumerate() {
        let (lo, hi) = if axis == 0 {
            (first.0, last.0)
        } else {
            (first.1, last.1)
        };
        if lo == hi {
            continue;
        }
        let bound = size[axis].checked_mul(S::from_i32(hi)?)?;
        let mut values = [S::ZERO; 4];
        for ((v, p), b) in values.iter_mut().zip(points).zip(beta) {
            let (a, c) = frame.coords(*p)?;
            let coord = if axis == 0 { a } else { c };
            *v = coord.checked_sub(bound)?.checked_mul(b)?;
        }
        *edge = Some(values);
    }
    let own = scene.materials.get(usize::from(o.material))?;
    let other = scene.materials.get(usize::from(*alt))?;
    let mut colors = [[Rgb888::new(0, 0, 0); 4]; 2];
    for (material, out) in [own, other].into_iter().zip(colors.iter_mut()) {
        for (slot, p) in out.iter_mut().zip(points) {
            let mut c = material.ambient;
            for (light, _) in scene.lights.iter().zip(lit).filter(|(_, l)| *l) {
                let l = light.location.diff(*p)?;
                let f = n
                    .dot(l)?
                    .abs()
                    .checked_mul(S::from_i32(255)?)?
                    .checked_div(l.dot(l)?)?;
                for ((c, e), d) in c.iter_mut().zip(light.emissivity).zip(material.diffuse) {
                    *c = c.checked_add(e.checked_mul(d)?.checked_mul(f)?)?;
                }
            }
            *slot = to_pixel(scene.rules, c);
        }
    }
    Some(Fill::Tiles(Tiles {
        colors,
        edges,
        first,
        negative,
    }))
}

/// The larger per-channel diffuse and ambient of an object's materials (a tiled plane
/// has two).
fn materials_bound<S: Scalar>(
    scene: &SceneView<'_, S>,
    o: &crate::Object<S>,
) -> Option<([S; 3], [S; 3])> {
    let first = scene.materials.get(usize::from(o.material))?;
    let (mut d, mut a) = (first.diffuse.map(S::abs), first.ambient.map(S::abs));
    if let Shape::Tiled { alt, .. } = o.shape {
        let alt = scene.materials.get(usize::from(alt))?;
        for (x, y) in d.iter_mut().zip(alt.diffuse) {
            *x = x.max(y.abs());
        }
        for (x, y) in a.iter_mut().zip(alt.ambient) {
            *x = x.max(y.abs());
        }
    }
    Some((d, a))
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

/// The most runs of traced blocks a band's rows are drawn with at once (more are drawn in
/// turns).
const RUNS: usize = 32;

/// Draws rows `rows` (inside one band of the sampler's blocks) over columns `columns` of
/// a sampled frame into `out` (`out[(r − rows.start)·stride + (x − columns.start)]`):
/// certified blocks filled from their corners, the others by `exact` (the frame's
/// kernel: a row, its runs of columns, and the row's slice of `out`, whose first pixel is
/// column `columns.start`). Returns how many pixels were filled.
pub(crate) fn sampled_rows<S: Scalar, C: From<Rgb888>>(
    scene: &SceneView<'_, S>,
    shading: Shading,
    sampler: &Sampler<S>,
    (rows, columns): (Range<u16>, Range<u16>),
    (out, stride): (&mut [C], usize),
    exact: &mut impl FnMut(u16, &[Range<u16>], &mut [C]),
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
    // The traced blocks' runs of columns, drawn row by row when the list is full and at
    // the end.
    let mut runs: Vec<Range<u16>, RUNS> = Vec::new();
    let mut draw = |runs: &mut Vec<Range<u16>, RUNS>, out: &mut [C]| {
        if runs.is_empty() {
            return;
        }
        for r in rows.clone() {
            let at = usize::from(r - rows.start) * stride;
            if let Some(line) = out.get_mut(at..) {
                exact(r, runs, line);
            }
        }
        runs.clear();
    };
    let mut x0 = columns.start / b * b;
    let mut left = (trace(x0, top), trace(x0, bottom));
    while x0 < end {
        let x1 = x0.saturating_add(b).min(w - 1);
        let right = (trace(x1, top), trace(x1, bottom));
        let corners = [&left.0, &right.0, &left.1, &right.1];
        let next = x0.saturating_add(b).min(w);
        let span = x0.max(columns.start)..next.min(end);
        if let Some(how) = sampler.certifies(scene, corners, (x0, x1), (top, bottom)) {
            filled += rows.len() * span.len();
            fill(
                (&how, (x0, x1), (top, bottom)),
                (rows.clone(), span),
                (out, stride, (rows.start, columns.start)),
            );
        } else {
            match runs.last_mut() {
                Some(run) if run.end == span.start => run.end = span.end,
                _ => {
                    if runs.is_full() {
                        draw(&mut runs, out);
                    }
                    let _ = runs.push(span);
                }
            }
        }
        left = right;
        x0 = next;
    }
    draw(&mut runs, out);
    filled
}

/// Fills the pixels `rows × columns` of a block over columns `x` and rows `y` (its
/// corners') as `how` says: each pixel the bilinear interpolation of four corner colours
/// (rounded to nearest), in a tiled block those of the pixel's tile's material.
fn fill<S: Scalar, C: From<Rgb888>>(
    (how, x, y): (&Fill<S>, (u16, u16), (u16, u16)),
    (rows, columns): (Range<u16>, Range<u16>),
    (out, stride, origin): (&mut [C], usize, (u16, u16)),
) {
    use embedded_graphics_core::pixelcolor::RgbColor;
    let w = u32::from(x.1 - x.0).max(1);
    let h = u32::from(y.1 - y.0).max(1);
    let area = w * h;
    let channels = |c: Rgb888| [u32::from(c.r()), u32::from(c.g()), u32::from(c.b())];
    let (smooth, tiles) = match how {
        Fill::Smooth(colors) => (colors.map(channels), None),
        Fill::Tiles(t) => (
            t.colors[0].map(channels),
            Some((t, t.colors[1].map(channels))),
        ),
    };
    for r in rows {
        let v = u32::from(r - y.0).min(h);
        let row = usize::from(r - origin.0) * stride;
        for col in columns.clone() {
            let u = u32::from(col - x.0).min(w);
            let weights = [(w - u) * (h - v), u * (h - v), (w - u) * v, u * v];
            let corners = match &tiles {
                Some((t, other)) if odd_tile(t, weights) => other,
                _ => &smooth,
            };
            let mut c = [0u8; 3];
            for (i, slot) in c.iter_mut().enumerate() {
                let sum: u32 = corners.iter().zip(weights).map(|(k, wt)| k[i] * wt).sum();
                *slot = u8::try_from((sum + area / 2) / area).unwrap_or(u8::MAX);
            }
            if let Some(p) = out.get_mut(row + usize::from(col - origin.1)) {
                *p = C::from(Rgb888::new(c[0], c[1], c[2]));
            }
        }
    }
}

/// Whether the pixel with these corner weights lies on an odd tile of the block's tiled
/// plane: on each axis the block crosses, the side of the edge's line its interpolated
/// `(a − A)·β` gives (exact for a function affine on the screen).
fn odd_tile<S: Scalar>(t: &Tiles<S>, weights: [u32; 4]) -> bool {
    let mut tile = [t.first.0, t.first.1];
    for (index, edge) in tile.iter_mut().zip(t.edges) {
        let Some(values) = edge else {
            continue;
        };
        let mut sum = S::ZERO;
        for (v, wt) in values.iter().zip(weights) {
            let term = i32::try_from(wt).ok().and_then(|wt| v.checked_mul_int(wt));
            sum = match term.and_then(|term| sum.checked_add(term)) {
                Some(s) => s,
                None => return false,
            };
        }
        // `a ≥ A` (the upper tile, as `floor` puts a point on the edge): `(a − A)·β`
        // has `β`'s sign there, or is zero.
        let upper = if t.negative {
            sum <= S::ZERO
        } else {
            sum >= S::ZERO
        };
        if upper {
            *index += 1;
        }
    }
    (tile[0].wrapping_add(tile[1])) & 1 == 1
}
