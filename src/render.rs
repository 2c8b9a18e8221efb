//! Streaming renderer: one scanline at a time into any `embedded-graphics` [`DrawTarget`].
//!
//! # RAM
//! The library keeps no framebuffer. [`render`] hands each scanline to the target's
//! `fill_contiguous` as an iterator that traces one pixel per step, so its RAM is O(1)
//! beyond the scene: no line buffer at all. [`render_line`] fills a caller's buffer of
//! `width` pixels (O(width), the caller's RAM), for drivers that want whole lines.
//!
//! # Shading
//! A pixel shows the object with the smallest accepted `t` along its primary ray, or the
//! background. Its colour is the material's ambient colour plus, for every light not in
//! shadow, `diffuse × emissivity × max(0, N·L) / dist` (see `scene-format.md`). Lighting
//! work is done only when the scene has lights; a scene without lights costs one
//! intersection per object per pixel and nothing more.

use embedded_graphics_core::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics_core::prelude::{DrawTarget, Point, Size};
use embedded_graphics_core::primitives::Rectangle;

use crate::fast::{Primary, Row};
use crate::flat::{Flat, FlatRow, PlaneMode};
use crate::scene::Plan;
use crate::{Color, Hit, Object, Ray, Scalar, Scene, Shape, Vec3};

/// How deep mirror reflections go: a ray reflected this many times sees no further
/// reflection (its own colour only).
pub const MAX_REFLECTION_DEPTH: u8 = 4;

/// Rays and stage evaluations of a frame (or line), counted when the crate is built with
/// the `stats` feature (otherwise every count stays 0 and costs nothing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Counters {
    /// Primary rays traced.
    pub primary_rays: u32,
    /// Shadow rays traced.
    pub shadow_rays: u32,
    /// Reflected rays traced.
    pub reflection_rays: u32,
    /// Diffuse terms evaluated (per light per hit).
    pub diffuse: u32,
    /// Specular terms evaluated (per light per hit).
    pub specular: u32,
    /// Spotlight cone tests.
    pub cone_tests: u32,
    /// Checkerboard tile lookups.
    pub tile_lookups: u32,
}

#[inline(always)]
fn count(field: &mut u32) {
    if cfg!(feature = "stats") {
        *field = field.wrapping_add(1);
    }
}

/// A set of shading stages, fixed at compile time: the renderer is instantiated once per
/// set, and a stage that is `false` is not in that loop at all (no per-pixel test). The
/// plan of a scene picks the set ([`shading_for`]). Each stage is also compiled out of
/// every set when its cargo feature (`lighting`, `reflection`) is off.
pub trait Stages {
    /// Diffuse lighting.
    const LIGHTING: bool;
    /// Shadow rays.
    const SHADOWS: bool;
    /// Specular glints.
    const SPECULAR: bool;
    /// Spotlight cones.
    const CONES: bool;
    /// Mirror reflection.
    const REFLECTION: bool;
}

/// Ambient only: pure geometry.
pub struct AmbientOnly;
/// Diffuse point lights, nothing between them and the surface.
pub struct Diffuse;
/// Diffuse point lights with shadow rays.
pub struct DiffuseShadows;
/// Everything the scene format has.
pub struct Full;

impl Stages for AmbientOnly {
    const LIGHTING: bool = false;
    const SHADOWS: bool = false;
    const SPECULAR: bool = false;
    const CONES: bool = false;
    const REFLECTION: bool = false;
}
impl Stages for Diffuse {
    const LIGHTING: bool = cfg!(feature = "lighting");
    const SHADOWS: bool = false;
    const SPECULAR: bool = false;
    const CONES: bool = false;
    const REFLECTION: bool = false;
}
impl Stages for DiffuseShadows {
    const LIGHTING: bool = cfg!(feature = "lighting");
    const SHADOWS: bool = cfg!(feature = "lighting");
    const SPECULAR: bool = false;
    const CONES: bool = false;
    const REFLECTION: bool = false;
}
impl Stages for Full {
    const LIGHTING: bool = cfg!(feature = "lighting");
    const SHADOWS: bool = cfg!(feature = "lighting");
    const SPECULAR: bool = cfg!(feature = "lighting");
    const CONES: bool = cfg!(feature = "lighting");
    const REFLECTION: bool = cfg!(feature = "reflection");
}

/// Which compiled stage set a plan needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shading {
    /// [`AmbientOnly`].
    AmbientOnly,
    /// [`Diffuse`].
    Diffuse,
    /// [`DiffuseShadows`].
    DiffuseShadows,
    /// [`Full`].
    Full,
}

/// The smallest stage set that covers a plan.
pub fn shading_for(plan: &Plan) -> Shading {
    if plan.reflection || plan.specular || plan.spotlights {
        Shading::Full
    } else if plan.lighting && plan.shadows {
        Shading::DiffuseShadows
    } else if plan.lighting {
        Shading::Diffuse
    } else {
        Shading::AmbientOnly
    }
}

/// The nearest accepted hit of a ray among the scene's objects, with the object's index.
pub fn nearest_hit<S: Scalar>(scene: &Scene<S>, ray: &Ray<S>) -> Option<(usize, Hit<S>)> {
    let mut best: Option<(usize, Hit<S>)> = None;
    for (i, object) in scene.objects.iter().enumerate() {
        if let Ok(hit) = object.shape.intersect(ray, scene.epsilon)
            && best.is_none_or(|(_, b)| hit.t < b.t)
        {
            best = Some((i, hit));
        }
    }
    best
}

/// Whether any object lies on the segment from `ray.base` to `ray.base + dist·ray.dir`
/// (a shadow test: the first hit is enough, and planes need no division:
/// [`Shape::occludes`]). Shadow rays start off the surface they leave
/// by its computed error bound ([`Shape::spawn`]), so that surface cannot shadow itself.
#[inline(never)] // its locals stay out of the recursive shading frames (stack: see below)
pub fn occludes<S: Scalar>(scene: &Scene<S>, ray: &Ray<S>, dist: S) -> bool {
    scene
        .objects
        .iter()
        .any(|object| object.shape.occludes(ray, scene.epsilon, dist))
}

/// Adds two non-negative colour terms; a sum beyond the format saturates (it is far above
/// 255 channel units, so the pixel is at full intensity either way).
fn add_sat<S: Scalar>(a: S, b: S) -> S {
    a.checked_add(b).unwrap_or(S::MAX)
}

/// `k × Σ` style product chain that saturates: a term too large for the format is far
/// brighter than 255.
fn term<S: Scalar>(factors: [S; 3]) -> S {
    factors
        .iter()
        .skip(1)
        .try_fold(factors[0], |acc, f| acc.checked_mul(*f))
        .unwrap_or(S::MAX)
}

/// The material index an object shows at a point (a tiled plane's odd squares show its
/// alternate material).
fn material_at<S: Scalar>(object: &Object<S>, point: Vec3<S>, counters: &mut Counters) -> u8 {
    match object.shape {
        Shape::Tiled { frame, alt } => {
            count(&mut counters.tile_lookups);
            if frame.odd_tile(point) == Some(true) {
                alt
            } else {
                object.material
            }
        }
        _ => object.material,
    }
}

/// The colour of a hit on `objects[index]` in channel units, with the stages of `T`.
///
/// Per light: `255 × (diffuse × emissivity × cos + specular × emissivity × (N·H)^shininess)
/// / dist`, evaluated in overflow-free steps (the distance divides in its two parts,
/// [`crate::Normalized::divide`]); a light exactly at the hit point gives no direction and
/// lights nothing there. A reflective material mixes `(1 − K)` of that with `K` of what
/// the mirrored ray sees, to [`MAX_REFLECTION_DEPTH`].
fn shade_with<S: Scalar, T: Stages>(
    scene: &Scene<S>,
    ray: &Ray<S>,
    index: usize,
    hit: &Hit<S>,
    depth: u8,
    counters: &mut Counters,
) -> Color<S> {
    let Some(object) = scene.objects.get(index) else {
        return scene.background;
    };
    let Some(material) = scene
        .materials
        .get(usize::from(material_at(object, hit.point, counters)))
    else {
        return [S::ZERO; 3];
    };
    let mut color = material.ambient;
    let lit = T::LIGHTING && !scene.lights.is_empty();
    let mirror = T::REFLECTION && material.reflective > S::ZERO && depth < MAX_REFLECTION_DEPTH;
    if !lit && !mirror {
        return color;
    }
    let Some(surface_normal) = object.shape.normal_at(hit.point) else {
        return color;
    };
    // The normal facing the incoming ray.
    let facing = if surface_normal.dot(ray.dir).is_some_and(|d| d > S::ZERO) {
        surface_normal.checked_neg().unwrap_or(surface_normal)
    } else {
        surface_normal
    };
    if lit {
        light_with::<S, T>(
            scene, ray, object, material, hit, facing, &mut color, counters,
        );
    }
    if mirror {
        count(&mut counters.reflection_rays);
        // r = d − 2 (N·d) N
        let reflected = surface_normal
            .dot(ray.dir)
            .and_then(|nd| nd.checked_add(nd))
            .and_then(|two_nd| surface_normal.scale(two_nd))
            .and_then(|n2| ray.dir.diff(n2))
            .and_then(Vec3::unit)
            .and_then(|r| object.shape.spawn(ray, hit, r));
        let seen = match reflected {
            Some(r) => trace_with::<S, T>(scene, &r, depth + 1, counters).color,
            None => scene.background,
        };
        let k = material.reflective;
        let own = S::ONE.checked_sub(k).unwrap_or(S::ZERO);
        for (c, s) in color.iter_mut().zip(seen) {
            *c = add_sat(
                c.checked_mul(own).unwrap_or(S::MAX),
                s.checked_mul(k).unwrap_or(S::MAX),
            );
        }
    }
    color
}

/// The lights' share of a hit's colour, added to `color` (see [`shade_with`]). Not
/// inlined: its locals are not part of the recursive frames of mirror reflections (on a
/// 16 KB chip in I32F32 they decide whether four reflections fit the stack).
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn light_with<S: Scalar, T: Stages>(
    scene: &Scene<S>,
    ray: &Ray<S>,
    object: &Object<S>,
    material: &crate::Material<S>,
    hit: &Hit<S>,
    facing: Vec3<S>,
    color: &mut Color<S>,
    counters: &mut Counters,
) {
    let channel_max = S::from_i32(255).unwrap_or(S::MAX);
    let specular = T::SPECULAR && material.specular > S::ZERO;
    if material.diffuse != [S::ZERO; 3] || specular {
        for light in &scene.lights {
            let Some(to_light) = light.location.diff(hit.point).and_then(Vec3::normalize) else {
                continue;
            };
            let l = to_light.unit;
            let Some(cos) = facing.dot(l).filter(|c| *c > S::ZERO) else {
                continue;
            };
            if T::CONES
                && let Some(cone) = light.cone
            {
                count(&mut counters.cone_tests);
                // The angle between the axis and the direction light → point.
                let inside = l
                    .checked_neg()
                    .and_then(|from_light| from_light.dot(cone.axis))
                    .is_some_and(|c| c >= cone.cos_theta);
                if !inside {
                    continue;
                }
            }
            if T::SHADOWS {
                count(&mut counters.shadow_rays);
                let shadow = object.shape.spawn(ray, hit, l);
                // The distance itself may not fit (a far light): nothing lies beyond it.
                let dist = to_light.length().unwrap_or(S::MAX);
                if shadow.is_some_and(|r| occludes(scene, &r, dist)) {
                    continue;
                }
            }
            count(&mut counters.diffuse);
            // 255 cos / dist and 255 (N·H)^shininess / dist, without forming dist; scaled
            // to channel units first so that the quotient keeps the format's relative
            // precision (cos / dist alone is small: in I20F12 it would keep 10 bits).
            let diffuse_falloff = cos
                .checked_mul(channel_max)
                .and_then(|k| to_light.divide(k))
                .unwrap_or(S::MAX);
            let glint = if specular {
                count(&mut counters.specular);
                ray.dir
                    .checked_neg()
                    .and_then(|v| l.sum(v))
                    .and_then(Vec3::unit)
                    .and_then(|h| facing.dot(h))
                    .filter(|nh| *nh > S::ZERO)
                    .and_then(|nh| nh.pow_unit(material.shininess))
                    .and_then(|p| p.checked_mul(channel_max))
                    .and_then(|k| to_light.divide(k))
                    .unwrap_or(S::ZERO)
            } else {
                S::ZERO
            };
            for ((c, diffuse), emissivity) in
                color.iter_mut().zip(material.diffuse).zip(light.emissivity)
            {
                *c = add_sat(*c, term([emissivity, diffuse, diffuse_falloff]));
                if specular {
                    *c = add_sat(*c, term([emissivity, material.specular, glint]));
                }
            }
        }
    }
}

/// Traces a ray with the stages of `T`.
fn trace_with<S: Scalar, T: Stages>(
    scene: &Scene<S>,
    ray: &Ray<S>,
    depth: u8,
    counters: &mut Counters,
) -> Traced<S> {
    let hit = nearest_hit(scene, ray);
    let color = match &hit {
        Some((i, h)) => shade_with::<S, T>(scene, ray, *i, h, depth, counters),
        None => scene.background,
    };
    Traced { hit, color }
}

/// The colour of a hit on `objects[index]`, lit by the scene's lights, in channel units
/// (the stages the scene's plan needs).
pub fn shade<S: Scalar>(scene: &Scene<S>, ray: &Ray<S>, index: usize, hit: &Hit<S>) -> Color<S> {
    let counters = &mut Counters::default();
    match shading_for(&scene.plan) {
        Shading::AmbientOnly => shade_with::<S, AmbientOnly>(scene, ray, index, hit, 0, counters),
        Shading::Diffuse => shade_with::<S, Diffuse>(scene, ray, index, hit, 0, counters),
        Shading::DiffuseShadows => {
            shade_with::<S, DiffuseShadows>(scene, ray, index, hit, 0, counters)
        }
        Shading::Full => shade_with::<S, Full>(scene, ray, index, hit, 0, counters),
    }
}

/// Converts a colour in channel units to a pixel: `round(clamp(c, 0, 255))` per channel,
/// ties away from zero.
pub fn to_rgb888<S: Scalar>(c: Color<S>) -> Rgb888 {
    let channel = |v: S| -> u8 {
        let max = S::from_i32(255).unwrap_or(S::MAX);
        let v = v.max(S::ZERO).min(max);
        v.round_to_i32()
            .and_then(|i| u8::try_from(i).ok())
            .unwrap_or(u8::MAX)
    };
    Rgb888::new(channel(c[0]), channel(c[1]), channel(c[2]))
}

/// What a primary ray found: the nearest hit (object index and hit) and the colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Traced<S> {
    /// The nearest accepted hit, or `None` for the background.
    pub hit: Option<(usize, Hit<S>)>,
    /// The colour in channel units.
    pub color: Color<S>,
}

/// Traces one ray: its nearest hit and colour, with the stages the scene's plan needs.
pub fn trace<S: Scalar>(scene: &Scene<S>, ray: &Ray<S>) -> Traced<S> {
    let counters = &mut Counters::default();
    match shading_for(&scene.plan) {
        Shading::AmbientOnly => trace_with::<S, AmbientOnly>(scene, ray, 0, counters),
        Shading::Diffuse => trace_with::<S, Diffuse>(scene, ray, 0, counters),
        Shading::DiffuseShadows => trace_with::<S, DiffuseShadows>(scene, ray, 0, counters),
        Shading::Full => trace_with::<S, Full>(scene, ray, 0, counters),
    }
}

/// Traces the primary ray of pixel (`column`, `row`), row 0 at the top. A ray that cannot
/// be formed in the format (see [`crate::Camera::primary_ray`]) sees the background.
pub fn trace_pixel<S: Scalar>(scene: &Scene<S>, column: u16, row: u16) -> Traced<S> {
    match scene.camera.primary_ray(column, row) {
        Some(ray) => trace(scene, &ray),
        None => Traced {
            hit: None,
            color: scene.background,
        },
    }
}

/// The colour of pixel (`column`, `row`), row 0 at the top.
pub fn pixel<S: Scalar>(scene: &Scene<S>, column: u16, row: u16) -> Rgb888 {
    to_rgb888(trace_pixel(scene, column, row).color)
}

/// The pixels of a scanline traced with the stage set `T`, one per step, as the caller
/// (a `fill_contiguous` or a line buffer) pulls them. With a fast-path frame (`primary`,
/// plane scenes without specular or reflection) primary rays take [`crate::fast`];
/// otherwise, and for any pixel the fast path hands back, the reference path.
fn scanline_with<'a, S: Scalar, T: Stages, C: From<Rgb888>>(
    scene: &'a Scene<S>,
    primary: Option<&'a Primary<S>>,
    row: u16,
    columns: core::ops::Range<u16>,
    counters: &'a mut Counters,
) -> impl Iterator<Item = C> + 'a {
    let y = scene.camera.screen_y(row);
    let mut state: Option<Row<S>> = None;
    columns.map(move |column| {
        count(&mut counters.primary_rays);
        let fast = primary.and_then(|p| {
            match state.as_mut() {
                Some(r)
                    if Primary::column(r).checked_add(1) == Some(column)
                        && column % crate::fast::RESYNC_PIXELS != 0 =>
                {
                    p.advance(scene, r)?
                }
                _ => state = Some(p.row(scene, row, column)?),
            }
            p.nearest(scene, state.as_ref()?).ok()
        });
        let color = match fast {
            Some(Some(h)) => {
                let ray = Ray {
                    base: scene.camera.viewpoint,
                    dir: h.dir,
                    kind: crate::RayKind::Primary,
                };
                let hit = Hit {
                    t: h.t_bound,
                    point: h.point,
                };
                shade_with::<S, T>(scene, &ray, h.index, &hit, 0, counters)
            }
            Some(None) => scene.background,
            None => match y.and_then(|y| scene.camera.primary_ray_at(column, y)) {
                Some(ray) => trace_with::<S, T>(scene, &ray, 0, counters).color,
                None => scene.background,
            },
        };
        C::from(to_rgb888(color))
    })
}

/// The fast-path frame for stage set `T`: only where the unnormalised primary direction is
/// all shading needs (no specular half vector, no mirror direction).
fn primary_for<S: Scalar, T: Stages>(scene: &Scene<S>) -> Option<Primary<S>> {
    if T::SPECULAR || T::REFLECTION {
        return None;
    }
    Primary::new(scene)
}

/// Calls `$f::<S, Stage set>(args)` for the stage set the scene's plan needs: the plan is
/// looked at once per call, never per pixel.
macro_rules! with_stages {
    ($scene:expr, $f:ident::<$s:ty>($($arg:expr),*)) => {
        match shading_for(&$scene.plan) {
            Shading::AmbientOnly => $f::<$s, AmbientOnly, _>($($arg),*),
            Shading::Diffuse => $f::<$s, Diffuse, _>($($arg),*),
            Shading::DiffuseShadows => $f::<$s, DiffuseShadows, _>($($arg),*),
            Shading::Full => $f::<$s, Full, _>($($arg),*),
        }
    };
}

/// Renders scanline `row` with an explicit stage set `T` instead of the one the scene's
/// plan picks: for benchmarks (what a stage costs) and for firmware that knows its scenes
/// in advance. Stages the scene needs but `T` lacks are simply not drawn.
pub fn render_line_stages<S: Scalar, T: Stages, C: From<Rgb888>>(
    scene: &Scene<S>,
    row: u16,
    line: &mut [C],
    counters: &mut Counters,
) {
    if row < scene.camera.height {
        line_with::<S, T, C>(scene, row, line, counters);
    }
}

/// The pure-geometry kernel ([`crate::flat`]) for stage set `T`: plane scenes drawn
/// without lighting or mirrors.
fn flat_for<S: Scalar, T: Stages>(scene: &Scene<S>) -> Option<Flat<S>> {
    if T::LIGHTING || T::REFLECTION {
        return None;
    }
    Flat::new(scene)
}

/// Counts `n` primary rays at once (the pure-geometry kernel's scanlines).
fn count_primary(counters: &mut Counters, n: u16) {
    if cfg!(feature = "stats") {
        counters.primary_rays = counters.primary_rays.wrapping_add(u32::from(n));
    }
}

/// Fills `line` with columns `0..line.len()` of a pure-geometry scanline.
fn flat_line<S: Scalar, C: From<Rgb888>>(row: &FlatRow<S>, mode: PlaneMode, line: &mut [C]) {
    let width = u16::try_from(line.len()).unwrap_or(u16::MAX);
    match mode {
        PlaneMode::PerPixel => {
            let mut block = [Rgb888::default(); crate::flat::BLOCK];
            let mut at = 0u16;
            for slots in line.chunks_mut(crate::flat::BLOCK) {
                let colors = &mut block[..slots.len()];
                row.fill(at, colors);
                for (slot, c) in slots.iter_mut().zip(colors.iter()) {
                    *slot = C::from(*c);
                }
                at = at.saturating_add(u16::try_from(slots.len()).unwrap_or(0));
            }
        }
        PlaneMode::Spans => {
            let mut rest = line;
            for (n, color) in row.spans(0, width) {
                let (run, tail) = rest.split_at_mut(usize::from(n).min(rest.len()));
                for slot in run {
                    *slot = C::from(color);
                }
                rest = tail;
            }
        }
    }
}

fn line_with<S: Scalar, T: Stages, C: From<Rgb888>>(
    scene: &Scene<S>,
    row: u16,
    line: &mut [C],
    counters: &mut Counters,
) {
    let width = line_width(scene, line);
    if !T::LIGHTING && !T::REFLECTION && flat_line_with(scene, None, row, &mut line[..width]) {
        count_primary(
            counters,
            scene.camera.width.min(u16::try_from(width).unwrap_or(0)),
        );
        return;
    }
    let primary = primary_for::<S, T>(scene);
    primary_line_with::<S, T, C>(scene, primary.as_ref(), row, line, counters);
}

/// How many pixels of `line` a scanline fills: its length, at most the camera's width.
fn line_width<S: Scalar, C>(scene: &Scene<S>, line: &[C]) -> usize {
    line.len().min(usize::from(scene.camera.width))
}

/// A scanline of the pure-geometry kernel (with the frame's part if the caller has it),
/// `false` when it does not apply or hands the scanline back. Not inlined: its frame (the
/// kernel's per-scanline data) and the general path's are never on the stack together
/// (on a 16 KB chip in I32F32 that is the difference between fitting and not).
#[inline(never)]
fn flat_line_with<S: Scalar, C: From<Rgb888>>(
    scene: &Scene<S>,
    flat: Option<&Flat<S>>,
    row: u16,
    line: &mut [C],
) -> bool {
    let flat_row = match flat {
        Some(f) => f.row(scene, row),
        None => Flat::new(scene).and_then(|f| f.row(scene, row)),
    };
    match flat_row {
        Some(flat_row) => {
            flat_line(&flat_row, scene.mode, line);
            true
        }
        None => false,
    }
}

/// A scanline of the general path: fast primary rays with the frame's part `primary`,
/// the reference path without it.
#[inline(never)]
fn primary_line_with<S: Scalar, T: Stages, C: From<Rgb888>>(
    scene: &Scene<S>,
    primary: Option<&Primary<S>>,
    row: u16,
    line: &mut [C],
    counters: &mut Counters,
) {
    let width = u16::try_from(line_width(scene, line)).unwrap_or(0);
    let pixels = scanline_with::<S, T, C>(scene, primary, row, 0..width, counters);
    for (slot, c) in line.iter_mut().zip(pixels) {
        *slot = c;
    }
}

/// What a frame computes once for all its scanlines.
#[derive(Debug, Clone)]
enum Kernel<S> {
    /// The pure-geometry kernel's per-frame part.
    Flat(Flat<S>),
    /// The fast primary-ray path's per-frame part, if it applies.
    Primary(Option<Primary<S>>),
}

/// A frame drawn line by line, for display drivers fed a scanline at a time (no
/// framebuffer): what is constant for the frame (per-plane terms, reciprocals, colours) is
/// computed once in [`Frame::new`] instead of once per [`render_line`] call. The pictures
/// are those of [`render_line`].
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use fixray::{render::Frame, render_line, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(include_str!("../scenes/planes.scene")).unwrap();
/// let frame = Frame::new(&scene);
/// let (mut a, mut b) = ([Rgb565::new(0, 0, 0); 160], [Rgb565::new(0, 0, 0); 160]);
/// for row in 0..scene.camera.height {
///     frame.render_line(row, &mut a); // send `a` to the display here
///     render_line(&scene, row, &mut b);
///     assert_eq!(a, b);
/// }
/// ```
#[derive(Debug, Clone)]
pub struct Frame<'a, S> {
    scene: &'a Scene<S>,
    kernel: Kernel<S>,
}

impl<'a, S: Scalar> Frame<'a, S> {
    /// Prepares a frame of `scene` (for the stages its plan needs).
    pub fn new(scene: &'a Scene<S>) -> Self {
        let kernel = match shading_for(&scene.plan) {
            Shading::AmbientOnly => match Flat::new(scene) {
                Some(flat) => Kernel::Flat(flat),
                None => Kernel::Primary(primary_for::<S, AmbientOnly>(scene)),
            },
            Shading::Diffuse => Kernel::Primary(primary_for::<S, Diffuse>(scene)),
            Shading::DiffuseShadows => Kernel::Primary(primary_for::<S, DiffuseShadows>(scene)),
            Shading::Full => Kernel::Primary(primary_for::<S, Full>(scene)),
        };
        Self { scene, kernel }
    }

    /// [`render_line`] with this frame's precomputation.
    pub fn render_line<C: From<Rgb888>>(&self, row: u16, line: &mut [C]) {
        self.render_line_counted(row, line, &mut Counters::default());
    }

    /// [`render_line_counted`] with this frame's precomputation.
    pub fn render_line_counted<C: From<Rgb888>>(
        &self,
        row: u16,
        line: &mut [C],
        counters: &mut Counters,
    ) {
        let scene = self.scene;
        if row >= scene.camera.height {
            return;
        }
        let primary = match &self.kernel {
            Kernel::Flat(flat) => {
                let width = line_width(scene, line);
                if flat_line_with(scene, Some(flat), row, &mut line[..width]) {
                    count_primary(counters, u16::try_from(width).unwrap_or(0));
                    return;
                }
                None
            }
            Kernel::Primary(p) => p.as_ref(),
        };
        with_stages!(
            scene,
            primary_line_with::<S>(scene, primary, row, line, counters)
        );
    }
}

/// Renders scanline `row` into `line`: pixel `i` of `line` is column `i`. Columns beyond
/// the camera's width (or beyond `line`) are left untouched; a row beyond the camera's
/// height leaves `line` untouched.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use fixray::{render_line, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera c { pixeldim 4 2 worlddim 4 2 viewpoint 2 1 5 } background 0 0 1",
/// )
/// .unwrap();
/// let mut line = [Rgb565::new(0, 0, 0); 4];
/// render_line(&scene, 0, &mut line);
/// assert_eq!(line, [Rgb565::new(0, 0, 31); 4]);
/// ```
pub fn render_line<S: Scalar, C: From<Rgb888>>(scene: &Scene<S>, row: u16, line: &mut [C]) {
    render_line_counted(scene, row, line, &mut Counters::default());
}

/// [`render_line`], adding the line's rays and stage evaluations to `counters` (counted
/// with the `stats` feature; without it they stay 0).
pub fn render_line_counted<S: Scalar, C: From<Rgb888>>(
    scene: &Scene<S>,
    row: u16,
    line: &mut [C],
    counters: &mut Counters,
) {
    Frame::new(scene).render_line_counted(row, line, counters);
}

/// Renders the scene into `target`, one `fill_contiguous` call per scanline, top to bottom.
///
/// The image covers the rectangle `(0, 0)`–`(width, height)` of the camera's `pixeldim`,
/// cut to the target's bounding box: only visible pixels are traced, each written once.
///
/// # Errors
/// The target's own error, from the first scanline it refused.
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb888};
/// use fixray::{render, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera c { pixeldim 3 2 worlddim 3 2 viewpoint 1.5 1 5 } background 1 0 0",
/// )
/// .unwrap();
/// let mut display = MockDisplay::<Rgb888>::new();
/// render(&scene, &mut display).unwrap();
/// display.assert_pattern(&["RRR", "RRR"]);
/// ```
pub fn render<S, D>(scene: &Scene<S>, target: &mut D) -> Result<(), D::Error>
where
    S: Scalar,
    D: DrawTarget,
    D::Color: PixelColor + From<Rgb888>,
{
    render_counted(scene, target, &mut Counters::default())
}

/// [`render`], adding the frame's rays and stage evaluations to `counters` (counted with
/// the `stats` feature; without it they stay 0).
///
/// # Errors
/// The target's own error, from the first scanline it refused.
pub fn render_counted<S, D>(
    scene: &Scene<S>,
    target: &mut D,
    counters: &mut Counters,
) -> Result<(), D::Error>
where
    S: Scalar,
    D: DrawTarget,
    D::Color: PixelColor + From<Rgb888>,
{
    with_stages!(scene, frame_with::<S>(scene, target, counters))
}

fn frame_with<S, T, D>(
    scene: &Scene<S>,
    target: &mut D,
    counters: &mut Counters,
) -> Result<(), D::Error>
where
    S: Scalar,
    T: Stages,
    D: DrawTarget,
    D::Color: PixelColor + From<Rgb888>,
{
    let full = Rectangle::new(
        Point::zero(),
        Size::new(
            u32::from(scene.camera.width),
            u32::from(scene.camera.height),
        ),
    );
    let area = full.intersection(&target.bounding_box());
    let Some(bottom_right) = area.bottom_right() else {
        return Ok(());
    };
    // Both corners lie inside `full`, whose coordinates fit u16.
    let to_u16 = |v: i32| u16::try_from(v).unwrap_or(0);
    let (x0, x1) = (to_u16(area.top_left.x), to_u16(bottom_right.x));
    // What is constant for the frame is computed once.
    let flat = flat_for::<S, T>(scene);
    let primary = match flat {
        Some(_) => None,
        None => primary_for::<S, T>(scene),
    };
    for row in to_u16(area.top_left.y)..=to_u16(bottom_right.y) {
        let line = Rectangle::new(
            Point::new(area.top_left.x, i32::from(row)),
            Size::new(area.size.width, 1),
        );
        if let Some(r) = flat.as_ref().and_then(|f| f.row(scene, row)) {
            count_primary(counters, x1 - x0 + 1);
            match scene.mode {
                PlaneMode::PerPixel => {
                    // Block by block, as `render_line` fills its buffer.
                    let blocks = (x0..=x1).step_by(crate::flat::BLOCK).flat_map(|start| {
                        let n = usize::from(x1 - start + 1).min(crate::flat::BLOCK);
                        let mut colors = [Rgb888::default(); crate::flat::BLOCK];
                        r.fill(start, &mut colors[..n]);
                        colors.into_iter().take(n)
                    });
                    target.fill_contiguous(&line, blocks.map(D::Color::from))?;
                }
                PlaneMode::Spans => target.fill_contiguous(
                    &line,
                    r.spans(x0, x1 + 1)
                        .flat_map(|(n, c)| core::iter::repeat_n(D::Color::from(c), n.into())),
                )?,
            }
            continue;
        }
        // A scanline the pure-geometry kernel handed back takes the general fast path.
        let fallback = flat.as_ref().and_then(|_| primary_for::<S, T>(scene));
        let primary = fallback.as_ref().or(primary.as_ref());
        target.fill_contiguous(
            &line,
            scanline_with::<S, T, D::Color>(scene, primary, row, x0..x1 + 1, counters),
        )?;
    }
    Ok(())
}
