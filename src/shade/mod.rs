//! Shading: the colour of a hit, and tracing a ray to its nearest hit and colour.
//!
//! A pixel shows the object with the smallest accepted `t` along its primary ray, or the
//! background. Its colour is the material's ambient colour plus, for every light not in
//! shadow, `diffuse × emissivity × max(0, N·L) / dist` (see `scene-format.md`), and for a
//! mirror its share of what the reflected ray sees. The stages a scene needs are compiled
//! in sets (`stages.rs`); the lights' share is `light.rs`, colour arithmetic `color.rs`.
//! Lighting work is done only when the scene has lights; a scene without lights costs one
//! intersection per object per pixel and nothing more.

use embedded_graphics_core::pixelcolor::Rgb888;

pub(crate) mod color;
pub(crate) use crate::scene::light_tolerance;
mod course;
pub use course::{MAX_COURSE_BOUNCES, MAX_PATH};
mod light;
pub(crate) mod stages;
mod texture;

use crate::scene::PixelRay;
use crate::stats::{Counters, count};
use crate::{
    AsView, Color, Hit, Material, Object, Ray, Rules, Scalar, SceneView, Shape, Tiling, Vec3,
};
use color::{add_sat, to_pixel};
use light::light_with;
use stages::{Stages, shading_for, with_stages};

/// How deep mirror reflections go: a ray reflected this many times sees no further
/// reflection (its own colour only).
pub const MAX_REFLECTION_DEPTH: u8 = 4;

/// The ray that arrives at a hit, as shading sees it: where it came from and its
/// direction. On the reference path `dir` is the ray's unit direction; the fast
/// primary-ray kernel hands its unnormalised `screen point − eye` instead (`unit`
/// false). Diffuse light needs only the side of the surface it comes from, a mirror's
/// direction `d − 2(N·d)N` is linear in `d` and normalised after; only a specular
/// glint's half vector normalises `dir` itself, for the pixels that show one.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Incoming<'a, S> {
    /// Where the ray started (secondary rays' offsets are bounded by its magnitude).
    pub(crate) base: Vec3<S>,
    /// Its direction (see above for its length).
    pub(crate) dir: Vec3<S>,
    /// Whether `dir` is a unit vector.
    pub(crate) unit: bool,
    /// The sides of every object's plane at the hit and at the lights, where the fast
    /// kernel knows them ([`PlaneSides`]).
    pub(crate) sides: Option<PlaneSides<'a, S>>,
}

impl<S: Scalar> From<&Ray<S>> for Incoming<'_, S> {
    fn from(ray: &Ray<S>) -> Self {
        Self {
            base: ray.base,
            dir: ray.dir,
            unit: true,
            sides: None,
        }
    }
}

/// What the fast kernel knows of a hit among planes: `D'_i − N_i·P` of every object `i`
/// at the hit point `P` (`at_hit`, one product each from the primary ray's terms) and
/// `D'_i − N_i·light_j` (`at_lights`, per frame, light by light), so that a shadow
/// segment's plane tests need no product ([`crate::Shape::meets_segment`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlaneSides<'a, S> {
    /// `D'_i − N_i·P`, one per object.
    pub(crate) at_hit: &'a [S],
    /// `D'_i − N_i·light_j` at `j × objects + i`.
    pub(crate) at_lights: &'a [S],
}

/// The nearest accepted hit of a ray among the scene's objects, with the object's index.
pub fn nearest_hit<S: Scalar>(scene: &impl AsView<S>, ray: &Ray<S>) -> Option<(usize, Hit<S>)> {
    nearest(&scene.view(), ray)
}

/// Not inlined: the intersections' locals stay out of the recursive frames of mirror
/// reflections (see `own_color`).
#[inline(never)]
fn nearest<S: Scalar>(scene: &SceneView<'_, S>, ray: &Ray<S>) -> Option<(usize, Hit<S>)> {
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

/// Whether any object lies on the segment from `ray.base` to the light at `light`,
/// `dist` along `ray.dir` (a shadow test: the first hit is enough, and planes need no
/// division: [`Shape::occludes`]; a light on a surface: [`Shape::shadows`]). Under the
/// `fixray` rules shadow rays start off the surface they leave by its computed error
/// bound ([`Shape::spawn`]), so that surface cannot shadow itself; under the `course`
/// rules they start on it and skip it (`skip`), and `course_z` is the screen rule's
/// limit.
#[inline(never)] // its locals stay out of the recursive shading frames (stack: see below)
pub(crate) fn occludes<S: Scalar>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    dist: S,
    light: Vec3<S>,
    skip: Option<usize>,
    course_z: Option<S>,
) -> bool {
    let eps = scene.epsilon;
    // Only where the plan found a light on a surface, and only for a shape that blocks.
    let spared = |shape: &Shape<S>| {
        scene.lights_on_surfaces
            && shape.spares_light(
                ray,
                light,
                light_tolerance(eps, light, scene.camera.viewpoint),
            )
    };
    match course_z {
        None => scene
            .objects
            .iter()
            .any(|o| o.shape.occludes(ray, eps, dist) && !spared(&o.shape)),
        Some(z) => scene.objects.iter().enumerate().any(|(i, o)| {
            Some(i) != skip
                && o.shape
                    .intersect_course(ray, eps, z)
                    .is_ok_and(|hit| hit.t < dist)
                && !spared(&o.shape)
        }),
    }
}

/// Whether a light lies in the plane of a plane-like surface (within
/// [`light_tolerance`]): it lights nothing of that surface, since `N·L` is 0 there by
/// geometry (the rounded `N·L` would light it, or not, pixel by pixel, and near the light
/// `1/dist` magnifies that). Run only where the plan found a light on a surface.
pub(crate) fn in_own_plane<S: Scalar>(shape: &Shape<S>, light: Vec3<S>, tol: S) -> bool {
    shape.plane().is_some() && shape.holds(light, tol)
}

/// The material index an object shows at a point: a tiled plane shows its alternate
/// material on its odd squares, under the course rules on the even squares of the
/// checkerboard anchored at the world origin (`COURSE-RULES.md` §10).
pub(crate) fn material_at<S: Scalar>(
    object: &Object<S>,
    point: Vec3<S>,
    rules: Rules,
    counters: &mut Counters,
) -> u8 {
    match object.shape {
        Shape::Tiled { frame, alt, tiling } => {
            count(&mut counters.tile_lookups);
            let show_alt = match (tiling, rules) {
                (Tiling::WorldXz, _) => frame.odd_tile_world_xz(point) == Some(true),
                (Tiling::Frame, Rules::Fixray) => frame.odd_tile(point) == Some(true),
                (Tiling::Frame, Rules::Course) => frame.odd_tile_from_origin(point) == Some(false),
            };
            if show_alt { alt } else { object.material }
        }
        _ => object.material,
    }
}

/// The object `objects[index]` and the material it shows at `point` (both rule sets): a
/// tiled plane's tile's, a textured plane's times its texel; `None` for an index or
/// material out of the scene.
pub(crate) fn surface<'a, S: Scalar>(
    scene: &'a SceneView<'_, S>,
    index: usize,
    point: Vec3<S>,
    counters: &mut Counters,
) -> Option<(&'a Object<S>, Material<S>)> {
    let object = scene.objects.get(index)?;
    let material = material_at(object, point, scene.rules(), counters);
    let material = scene.materials.get(usize::from(material))?;
    Some(match &object.shape {
        Shape::Textured(slide) => (
            object,
            texture::textured(material, texture::texel(scene, slide, point)),
        ),
        _ => (object, *material),
    })
}

/// The colour of a hit on `objects[index]` in channel units, with the stages of `T`.
///
/// Per light: `255 × (diffuse × emissivity × cos + specular × emissivity × (N·H)^shininess)
/// / dist`, evaluated in overflow-free steps (the distance divides in its two parts,
/// [`crate::Normalized::divide`]); a light exactly at the hit point gives no direction and
/// lights nothing there. A reflective material mixes `(1 − K)` of that with `K` of what
/// the mirrored ray sees, to [`MAX_REFLECTION_DEPTH`].
pub(crate) fn shade_with<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Incoming<'_, S>,
    index: usize,
    hit: &Hit<S>,
    depth: u8,
    counters: &mut Counters,
) -> Color<S> {
    let (mut color, mirror) = own_color::<S, T>(scene, ray, index, hit, depth, counters);
    if let Some((reflected, k)) = mirror {
        let seen = match reflected {
            Some(r) => trace_with::<S, T>(scene, &r, depth + 1, counters).color,
            None => scene.background,
        };
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

/// A hit's own colour (ambient and lights) and, for a mirror, the reflected ray (`None`
/// when it does not fit the format: the mirror then shows the background) and its
/// weight `K`. Not inlined: its locals (the normal, the lights' terms) stay out of the
/// recursive frames of mirror reflections, which hold only a colour and a ray (on a
/// 16 KB chip in I32F32 that is what lets four reflections fit the stack).
#[inline(never)]
#[allow(clippy::type_complexity)]
fn own_color<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Incoming<'_, S>,
    index: usize,
    hit: &Hit<S>,
    depth: u8,
    counters: &mut Counters,
) -> (Color<S>, Option<(Option<Ray<S>>, S)>) {
    // An index comes from a hit; a material index out of the scene shows black.
    let Some((object, material)) = surface(scene, index, hit.point, counters) else {
        return ([S::ZERO; 3], None);
    };
    let mut color = material.ambient;
    let lit = T::LIGHTING && !scene.lights.is_empty();
    let mirror = T::REFLECTION && material.reflective > S::ZERO && depth < MAX_REFLECTION_DEPTH;
    if !lit && !mirror {
        return (color, None);
    }
    let Some(surface_normal) = object.shape.normal_at(hit.point) else {
        return (color, None);
    };
    // The normal facing the incoming ray.
    let facing = if surface_normal.dot(ray.dir).is_some_and(|d| d > S::ZERO) {
        surface_normal.checked_neg().unwrap_or(surface_normal)
    } else {
        surface_normal
    };
    if lit {
        let stages = stages::LightStages::of::<T>();
        light_with(
            scene, ray, object, &material, hit, facing, None, stages, &mut color, counters, None,
        );
    }
    if !mirror {
        return (color, None);
    }
    count(&mut counters.reflection_rays);
    // r = d − 2 (N·d) N
    let reflected = surface_normal
        .dot(ray.dir)
        .and_then(|nd| nd.checked_add(nd))
        .and_then(|two_nd| surface_normal.scale(two_nd))
        .and_then(|n2| ray.dir.diff(n2))
        .and_then(Vec3::unit)
        .and_then(|r| object.shape.spawn_from(ray.base, hit, r));
    (color, Some((reflected, material.reflective)))
}

/// Traces a ray with the stages of `T`, by the scene's rules.
pub(crate) fn trace_with<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    depth: u8,
    counters: &mut Counters,
) -> Traced<S> {
    if scene.rules() == Rules::Course {
        return course::trace_course::<S, T>(scene, ray, None, counters);
    }
    let hit = nearest(scene, ray);
    let color = match &hit {
        Some((i, h)) => shade_with::<S, T>(scene, &Incoming::from(ray), *i, h, depth, counters),
        None => scene.background,
    };
    Traced { hit, color }
}

/// The colour of a hit on `objects[index]`, lit by the scene's lights, in channel units
/// (the stages the scene's plan needs).
pub fn shade<S: Scalar>(
    scene: &impl AsView<S>,
    ray: &Ray<S>,
    index: usize,
    hit: &Hit<S>,
) -> Color<S> {
    let scene = &scene.view();
    let counters = &mut Counters::default();
    let ray = &Incoming::from(ray);
    with_stages!(
        shading_for(&scene.plan()),
        shade_one::<S>(scene, ray, index, hit, counters)
    )
}

fn shade_one<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Incoming<'_, S>,
    index: usize,
    hit: &Hit<S>,
    counters: &mut Counters,
) -> Color<S> {
    shade_with::<S, T>(scene, ray, index, hit, 0, counters)
}

/// What a primary ray found: the nearest hit (object index and hit) and the colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Traced<S> {
    /// The nearest accepted hit, or `None` for the background.
    pub hit: Option<(usize, Hit<S>)>,
    /// The colour in channel units.
    pub color: Color<S>,
}

/// Traces a pixel's primary ray with the stages of `T`: [`trace_with`], and under the
/// course rules with the pixel's unnormalised direction for its textured planes' points
/// (see [`course::trace_course`]).
pub(crate) fn trace_pixel_ray<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    pixel: &PixelRay<S>,
    counters: &mut Counters,
) -> Traced<S> {
    if scene.rules() == Rules::Course {
        return course::trace_course::<S, T>(scene, &pixel.ray, Some(pixel.toward), counters);
    }
    trace_with::<S, T>(scene, &pixel.ray, 0, counters)
}

/// Traces one ray: its nearest hit and colour, with the stages the scene's plan needs.
pub fn trace<S: Scalar>(scene: &impl AsView<S>, ray: &Ray<S>) -> Traced<S> {
    let scene = &scene.view();
    let counters = &mut Counters::default();
    with_stages!(
        shading_for(&scene.plan()),
        trace_one::<S>(scene, ray, counters)
    )
}

fn trace_one<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    counters: &mut Counters,
) -> Traced<S> {
    trace_with::<S, T>(scene, ray, 0, counters)
}

/// Traces the primary ray of pixel (`column`, `row`), row 0 at the top, on the reference
/// path. A ray that cannot be formed in the format (see [`crate::Camera::primary_ray`])
/// sees the background. It works out the scene's plan on every call: for many pixels,
/// [`crate::Frame::trace_pixel`] does that once per frame.
pub fn trace_pixel<S: Scalar>(scene: &impl AsView<S>, column: u16, row: u16) -> Traced<S> {
    let scene = &scene.view();
    trace_pixel_with(scene, shading_for(&scene.plan()), column, row)
}

/// [`trace_pixel`] with the stage set already chosen.
pub(crate) fn trace_pixel_with<S: Scalar>(
    scene: &SceneView<'_, S>,
    shading: stages::Shading,
    column: u16,
    row: u16,
) -> Traced<S> {
    let pixel = scene
        .camera
        .screen_y(row)
        .and_then(|y| scene.camera.pixel_ray_at(column, y));
    match pixel {
        Some(pixel) => with_stages!(
            shading,
            trace_pixel_ray::<S>(scene, &pixel, &mut Counters::default())
        ),
        None => Traced {
            hit: None,
            color: scene.background,
        },
    }
}

/// The colour of pixel (`column`, `row`), row 0 at the top.
pub fn pixel<S: Scalar>(scene: &impl AsView<S>, column: u16, row: u16) -> Rgb888 {
    let scene = &scene.view();
    to_pixel(scene.rules(), trace_pixel(scene, column, row).color)
}
