//! Adaptive sampling: a frame traced at the corners of square blocks and filled between
//! them where a certificate says what the block holds ([`Sampling::Blocks`]).
//!
//! A block of `B × B` pixels (`B` = 2, 4 or 8) is traced at its four corners (each
//! corner's nearest hit as the frame's kernel finds it, or on the reference path where
//! the kernel hands the pixel on, its occluders towards each light, and on a plane its
//! colour by the diffuse model below),
//! and filled from them only where all of these hold:
//! - **no sphere's box** on the screen meets the block (the kernels' boxes, outside
//!   which no primary ray meets a sphere): a sphere smaller than the block is never
//!   missed, and a sphere's pixels are always traced;
//! - **the same surface** at the four corners: the same infinite plane, or the background
//!   at all four. The pixels where one infinite plane is the nearest hit, and where
//!   nothing is hit, are each convex on the screen (intersections of half-planes), so
//!   four corners in one of them put the whole block in it;
//! - **the same tile**, or **the tile's edge located**: a tile is convex too; where the
//!   corners lie in two tiles along an axis of a checkerboard, the edge between them is a
//!   line on the screen (`(a − A)·β`, with `a` the plane coordinate, `A` the edge's and
//!   `β = N·D`, is affine in the pixel), and each pixel takes the colour of its side's
//!   material. A pixel whose centre lies within the rounding of an edge may take the
//!   tile beyond it (`tests/sampling.rs` holds them under 0.5 % of the pixels and counts
//!   at most 0.1 % in the boing frames);
//! - **the same shadow state** for every light: either one occluder shadows all four
//!   corners (a sphere's or a plane's shadow on a plane is convex, so it covers the
//!   block), or none shadows any corner and every sphere stands clear of the segments
//!   from the light to the block (a plane's shadow is a half-plane: four corners outside
//!   it put the block outside it);
//! - **the colour's curvature is bounded**: a diffuse point light gives a plane
//!   `255·(N·L)/|L|²`, `N·L` the same at every point of it, and bilinear interpolation
//!   strays from that by at most `w²/8·|f_xx| + h²/8·|f_yy|` over `w × h` pixels,
//!   bounded from the ray's terms, which are affine in the pixel
//!   ([`Sampler::interpolation_error`]); the sum over the lit lights of `emissivity ·
//!   diffuse ·` that bound, per channel, must be at most the mode's `bound` in levels;
//!   where a channel may pass 255 (or 0) inside the block it is clamped there, and the
//!   bound grows by how far past it may go, or is the channel's whole range over the
//!   block where that is less (a block clamped to 255 everywhere strays by nothing).
//!
//! Any other block is drawn by the frame's kernel, pixel by pixel, as the exact frame
//! draws it. A filled pixel differs from the exact frame's by at most `bound` levels plus
//! the rounding of the corners' colours and of the exact pixel (`tests/sampling.rs` holds
//! every pixel off the tiles' edges within the bound plus 2 levels, and measures at most
//! 1 level in the boing frames at every bound). With `bound` 0 only blocks of one colour
//! are filled (the background, a surface every light's shadow covers) and never across a
//! tile's edge: the exact frame bit for bit, but for a corner pixel traced on the
//! reference path whose centre lies within the rounding of a tile's edge, which the
//! reference ray and a kernel may put in different tiles (none in the tests' frames).
//!
//! Only frames of the crate's rules whose objects are infinite planes (plain or tiled)
//! and spheres, lit by point lights without glints, mirrors, translucency, spotlights,
//! projectors or a light on a surface, and drawn by a kernel that knows the spheres'
//! boxes (or has no sphere), are sampled; any other frame is drawn exact
//! ([`crate::Frame::sampled`] says which).

use core::ops::Range;

use embedded_graphics_core::pixelcolor::Rgb888;
use heapless::Vec;

mod certify;
mod corners;
mod fill;

use super::fast::Primary;
use super::{Drawing, Kernel};
use crate::{Plan, Rules, Scalar, SceneView, Shape, Vec3};
use corners::{Corner, corner};
use fill::fill;

/// How a frame finds its pixels ([`crate::Frame::with_sampling`], cargo feature
/// `sampling`).
///
/// ```
/// use fixray::{BlockSize, Frame, Sampling, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(include_str!("../../../scenes/boing.scene"))?;
/// let exact: Frame<'_, I16F16> = Frame::new(&scene);
/// let blocks = Sampling::blocks(BlockSize::Four, 2);
/// let sampled: Frame<'_, I16F16> = Frame::new(&scene).with_sampling(blocks);
/// assert_eq!(exact.sampling(), Sampling::Exact);
/// assert!(sampled.sampled()); // the boing ball's kind of scene is sampled
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Sampling {
    /// Every pixel traced (the default).
    #[default]
    Exact,
    /// Blocks traced at their corners and filled where certified
    /// ([`crate::Frame::with_sampling`]).
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

/// A mode's name, as the tools and the firmware write it: `exact`, or the block's side and
/// the bound, `8x8:8`. [`Sampling`] parses it back.
///
/// ```
/// use fixray::{BlockSize, Sampling};
///
/// let mode = Sampling::blocks(BlockSize::Four, 2);
/// assert_eq!(mode.to_string(), "4x4:2");
/// assert_eq!("4x4:2".parse(), Ok(mode));
/// assert_eq!("exact".parse(), Ok(Sampling::Exact));
/// assert!("3x3:1".parse::<Sampling>().is_err());
/// ```
impl core::fmt::Display for Sampling {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Sampling::Exact => f.write_str("exact"),
            Sampling::Blocks { size, bound } => {
                let b = size.pixels();
                write!(f, "{b}x{b}:{bound}")
            }
        }
    }
}

/// A name that is not a sampling mode (see [`Sampling`]'s `Display`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UnknownSampling;

impl core::fmt::Display for UnknownSampling {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("not a sampling mode: write `exact` or SIDExSIDE:BOUND (SIDE 2, 4 or 8, BOUND 0 to 255), e.g. `8x8:8`")
    }
}

impl core::str::FromStr for Sampling {
    type Err = UnknownSampling;

    fn from_str(name: &str) -> Result<Self, UnknownSampling> {
        if name == "exact" {
            return Ok(Sampling::Exact);
        }
        let (size, bound) = name.split_once(':').ok_or(UnknownSampling)?;
        let size = match size {
            "2x2" => BlockSize::Two,
            "4x4" => BlockSize::Four,
            "8x8" => BlockSize::Eight,
            _ => return Err(UnknownSampling),
        };
        Ok(Sampling::blocks(
            size,
            bound.parse().map_err(|_| UnknownSampling)?,
        ))
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
pub(super) const LIGHTS: usize = 4;
/// The most objects a sampled frame has (a shadow state is a mask of occluders).
const OBJECTS: usize = 30;
/// A shadow state's bit for a light the surface faces away from (no occluder's index).
pub(super) const FACES_AWAY: u32 = 1 << 31;
/// The most spheres a sampled frame has.
const BOXES: usize = 16;

/// A plane's `(|A'|, |β'|)` for one light, across a row and down a column
/// ([`plane_slopes`]).
type Slopes<S> = [(S, S); 2];

/// What a sampled frame computes once: the spheres' boxes on the screen and each plane's
/// slopes.
#[derive(Debug, Clone)]
pub(crate) struct Sampler<S> {
    size: u16,
    bound: S,
    /// `(rows, columns)` of every sphere, first and last inclusive.
    spheres: Vec<((u16, u16), (u16, u16)), BOXES>,
    /// Per object and light, for a plane: `(|A'|, |β'|)` across a row and down a column
    /// (see [`Sampler::interpolation_error`]); the same at every pixel of the frame.
    slopes: Vec<[Option<Slopes<S>>; LIGHTS], OBJECTS>,
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
            .all(|l| matches!(l.beam, crate::scene::Beam::Everywhere))
        && scene.camera.grid == crate::scene::PixelGrid::Centres
        && scene
            .objects
            .iter()
            .filter_map(|o| o.shape.plane())
            .all(|p| window_before(scene, p));
    if !plain {
        return None;
    }
    let mut spheres = Vec::new();
    match &drawing.kernel {
        Kernel::Fast(p) | Kernel::Rows(super::rows::Rows { primary: p, .. }) => {
            for b in p.sphere_boxes() {
                spheres.push(b).ok()?;
            }
        }
        Kernel::Flat(_) if !plan.spheres => {}
        Kernel::Flat(_) | Kernel::Reference => return None,
    }
    let mut slopes = Vec::new();
    for o in scene.objects {
        let mut per_light = [None; LIGHTS];
        if let Some(plane) = o.shape.plane() {
            for (slot, light) in per_light.iter_mut().zip(scene.lights) {
                *slot = plane_slopes(scene, plane, light.location);
            }
        }
        slopes.push(per_light).ok()?;
    }
    Some(Sampler {
        slopes,
        size: size.pixels(),
        bound: S::from_i32(i32::from(bound))?,
        spheres,
    })
}

/// Whether no point of the screen's window lies beyond `plane` from the eye (on it is
/// fine). A ray meets a plane before the window only from a window point beyond it; such
/// hits are not drawn (a primary ray's hits start at the window), and the pixels where
/// the plane is not drawn are then no longer a half-plane of the screen, which the
/// certificate's convexity needs.
fn window_before<S: Scalar>(scene: &SceneView<'_, S>, plane: &crate::geometry::Plane<S>) -> bool {
    let camera = &scene.camera;
    let (n, d) = (plane.normal(), plane.offset());
    let side = |p: Vec3<S>| n.dot(p).and_then(|v| v.checked_sub(d));
    let Some(eye) = side(camera.viewpoint) else {
        return false;
    };
    let (zero, wx, wy) = (S::ZERO, camera.world_width, camera.world_height);
    eye != S::ZERO
        && [(zero, zero), (wx, zero), (zero, wy), (wx, wy)]
            .into_iter()
            .all(|(x, y)| {
                side(Vec3::new(x, y, zero))
                    .is_some_and(|s| s == S::ZERO || (s > S::ZERO) == (eye > S::ZERO))
            })
}

/// A plane's `(|A'|, |β'|)` for a light at `light`, across a row and down a column: what
/// one pixel's step changes in `β = N·D` and `A = β·(L − e) − (N·P − N·e)·D`
/// ([`Sampler::interpolation_error`]). `None` where a quantity leaves the format.
fn plane_slopes<S: Scalar>(
    scene: &SceneView<'_, S>,
    plane: &crate::geometry::Plane<S>,
    light: Vec3<S>,
) -> Option<Slopes<S>> {
    let camera = &scene.camera;
    let eye = camera.viewpoint;
    let n = plane.normal();
    let sx = camera
        .world_width
        .checked_div(S::from_i32(i32::from(camera.width))?)?;
    let sy = camera
        .world_height
        .checked_div(S::from_i32(i32::from(camera.height))?)?;
    let c0 = plane.offset().checked_sub(n.dot(eye)?)?;
    let le = light.diff(eye)?;
    let slope = |step: Vec3<S>| -> Option<(S, S)> {
        let beta1 = n.dot(step)?;
        let a1 = le.scale(beta1)?.diff(step.scale(c0)?)?;
        Some((a1.dot(a1)?.checked_sqrt()?, beta1.abs()))
    };
    Some([
        slope(Vec3::new(sx, S::ZERO, S::ZERO))?,
        slope(Vec3::new(S::ZERO, sy, S::ZERO))?,
    ])
}

/// The most runs of traced blocks a band's rows are drawn with at once (more are drawn in
/// turns).
const RUNS: usize = 32;

/// The most corners of a row [`Kept`] holds: a row of blocks up to 63 blocks wide (504
/// pixels in blocks of 8); a wider one traces its bands' shared corners twice.
const KEPT: usize = 64;

/// The corners of a band's bottom row, kept for the next band, whose top row they are
/// (each corner is traced once when the bands are drawn in turn, [`sampled_rows`]).
#[derive(Debug)]
pub(crate) struct Kept<S> {
    /// The row and first column of the corners (`None`: none kept).
    at: Option<(u16, u16)>,
    corners: Vec<Corner<S>, KEPT>,
}

impl<S> Default for Kept<S> {
    fn default() -> Self {
        Self {
            at: None,
            corners: Vec::new(),
        }
    }
}

/// Draws rows `rows` (inside one band of the sampler's blocks) over columns `columns` of
/// a sampled frame into `out` (`out[(r − rows.start)·stride + (x − columns.start)]`):
/// certified blocks filled from their corners, the others by `exact` (the frame's
/// kernel: a row, its runs of columns, and the row's slice of `out`, whose first pixel is
/// column `columns.start`). Returns how many pixels were filled.
pub(crate) fn sampled_rows<S: Scalar, C: From<Rgb888>>(
    scene: &SceneView<'_, S>,
    (sampler, primary): (&Sampler<S>, Option<&Primary<S>>),
    (rows, columns): (Range<u16>, Range<u16>),
    (out, stride): (&mut [C], usize),
    exact: &mut impl FnMut(u16, &[Range<u16>], &mut [C]),
    mut kept: Option<&mut Kept<S>>,
    corners_traced: &mut u32,
) -> usize {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let b = sampler.size;
    let end = columns.end.min(w);
    if rows.start >= rows.end || rows.start >= h || columns.start >= end {
        return 0;
    }
    let mut filled = 0;
    let top = rows.start / b * b;
    let bottom = top.saturating_add(b).min(h - 1);
    let band = top..top.saturating_add(b).min(h);
    let rows = rows.start..rows.end.min(band.end);
    // Corners traced, for `Counters::corners`.
    let traced = core::cell::Cell::new(0u32);
    let trace = |x: u16, y: u16| {
        traced.set(traced.get().wrapping_add(1));
        corner(scene, primary, x, y)
    };
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
    // The top corners the band before kept (its bottom row), and this band's bottom
    // corners kept for the next.
    let mut reuse: Vec<Corner<S>, KEPT> = Vec::new();
    if let Some(k) = kept.as_deref_mut() {
        if k.at == Some((top, x0)) {
            reuse = core::mem::take(&mut k.corners);
        }
        k.at = None;
        k.corners.clear();
    }
    let mut index = 0;
    let mut corner_at = |x: u16, kept: &mut Option<&mut Kept<S>>| {
        let top = match reuse.get(index) {
            Some(c) => *c,
            None => trace(x, top),
        };
        let bottom = trace(x, bottom);
        if let Some(k) = kept.as_deref_mut()
            && k.corners.push(bottom).is_err()
        {
            *kept = None;
        }
        index += 1;
        (top, bottom)
    };
    let first = x0;
    let mut left = corner_at(x0, &mut kept);
    while x0 < end {
        let x1 = x0.saturating_add(b).min(w - 1);
        let right = corner_at(x1, &mut kept);
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
    if let Some(k) = kept {
        k.at = Some((bottom, first));
    }
    *corners_traced = corners_traced.wrapping_add(traced.get());
    filled
}
