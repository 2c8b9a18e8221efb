//! Shading: the colour of a hit, and tracing a ray to its nearest hit and colour.
//!
//! A pixel shows the object with the smallest accepted `t` along its primary ray, or the
//! background. Its colour is the material's ambient colour plus, for every light not in
//! shadow, `diffuse × emissivity × max(0, N·L) / dist` (see `docs/scene-format.md`), and for a
//! mirror its share of what the reflected ray sees. The stages a scene needs are compiled
//! in sets (`stages.rs`); the lights' share is `light.rs`, colour arithmetic `color.rs`.
//! Lighting work is done only when the scene has lights; a scene without lights costs one
//! intersection per object per pixel and nothing more.
//!
//! The renderer draws with the kernels; this module's functions are the definition they
//! are tested against, one ray or pixel at a time: [`trace_pixel`] and [`pixel`] (a
//! pixel's primary ray), [`trace`] (any ray), [`shade`] (a hit), the colour mappings
//! [`to_rgb888`] and [`to_pixel`], and the rule sets as types ([`Fixray`], [`Course`]).
//!
//! ```
//! use embedded_graphics::pixelcolor::Rgb888;
//! use fixray::{shade, Scene, I16F16};
//!
//! let scene = Scene::<I16F16>::parse(
//!     "rules fixray
//!      camera c { pixeldim 4 4 worlddim 4 4 viewpoint 2 2 5 }
//!      material red { ambient 1 0 0 }
//!      plane floor { material red normal 0 1 0 point 0 0.4 0 }",
//! )?;
//! assert_eq!(shade::pixel(&scene, 0, 3), Rgb888::new(255, 0, 0)); // the floor
//! assert!(shade::trace_pixel(&scene, 0, 0).hit.is_none()); // the upper half: background
//! # Ok::<(), fixray::SceneError>(())
//! ```

use embedded_graphics_core::pixelcolor::Rgb888;

pub(crate) mod color;
pub(crate) use crate::scene::light_tolerance;
pub use color::{Depth, to_pixel, to_rgb888};
#[cfg(feature = "course")]
mod course;
#[cfg(feature = "course")]
pub use course::{MAX_COURSE_BOUNCES, MAX_PATH};
mod fixray;
mod light;
pub(crate) mod rules;
#[cfg(feature = "course")]
pub use rules::Course;
pub use rules::{Fixray, RuleSet};
pub(crate) mod stages;
mod texture;

use crate::scene::PixelRay;
use crate::stats::{Counters, count};
use crate::{
    AsView, Color, Hit, Material, Object, Ray, Rules, Scalar, SceneView, Shape, Tiling, Vec3,
};
use rules::{Tracer, with_rules};
use stages::{Stages, planned, with_stages};

pub(crate) use fixray::{occluded_among, occludes_segment, shade as shade_with};
pub(crate) use light::{channel_max, diffuse_falloff, diffuse_falloff_outlined};

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

/// What the fast kernel knows of a primary hit: `D'_i − N_i·P` of every object `i`
/// at the hit point `P` (`at_hit`, one product each from the primary ray's terms) and
/// `D'_i − N_i·light_j` (`at_lights`, per frame, light by light), so that a shadow
/// segment's plane tests need no product ([`crate::Shape::meets_segment`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PlaneSides<'a, S> {
    /// `D'_i − N_i·P`, one per object.
    pub(crate) at_hit: &'a [S],
    /// `D'_i − N_i·light_j` at `j × objects + i` (a sphere's entries are place holders:
    /// its segment test does not use sides).
    pub(crate) at_lights: &'a [S],
    /// The spheres' shadow cones from the lights (per frame).
    pub(crate) cones: &'a [crate::geometry::ShadowCone<S>],
    /// Which of `at_hit` and of the first lights' `at_lights` are positive, and which
    /// objects are spheres.
    pub(crate) bits: SideBits,
}

/// Bits of [`PlaneSides::at_hit`], one per object (bit `i`: object `i`; the fast kernel
/// takes at most 8): the planes whose side at the hit is positive, and the spheres (whose
/// entries are place holders; a shadow segment always tests them, as it would any other
/// object without a plane, of which the fast kernel has none: `Primary::new` refuses a
/// surface of revolution). A plane can meet a shadow segment only where its sides at the
/// hit and at the light differ in sign (`sides_differ`): with these, the planes that
/// cannot are passed over without a look at their sides.
/// The first [`SIDE_BITS_LIGHTS`] lights' sides are kept the same way, per frame (a
/// shadow segment towards a later light looks at every plane). Four bytes: the struct is
/// copied into every frame that carries a hit's sides (a 16 KB chip in I32F32 has a few
/// bytes to spare).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct SideBits {
    pub(crate) positive: u8,
    pub(crate) spheres: u8,
    pub(crate) lights: [u8; SIDE_BITS_LIGHTS],
}

impl SideBits {
    /// The objects a shadow segment towards light `j` must look at: the spheres, and the
    /// planes whose sides at the hit and at the light differ in sign (every object
    /// beyond the first [`SIDE_BITS_LIGHTS`] lights).
    #[inline(always)]
    pub(crate) fn candidates(&self, j: usize) -> u8 {
        match self.lights.get(j) {
            Some(lp) => ((self.positive ^ lp) & !self.spheres) | self.spheres,
            None => u8::MAX,
        }
    }
}

/// How many lights' sides [`SideBits`] keeps.
pub(crate) const SIDE_BITS_LIGHTS: usize = 2;

/// The nearest hit of a ray by the rule set `R` ([`rules::RuleSet::intersect`]), with the
/// object's index; on equal `t` the first object in file order. A rule set whose
/// secondary rays skip the object they leave (`Tracer::SKIPS_OWN`, the course's) skips
/// `skip`. Inlined into the course's tracer (its one caller there); the crate's tracer
/// calls it out of line (`fixray::nearest`).
#[inline]
pub(crate) fn nearest<S: Scalar, R: Tracer>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    skip: Option<usize>,
) -> Option<(usize, Hit<S>)> {
    let mut best: Option<(usize, Hit<S>)> = None;
    for (i, object) in scene.objects.iter().enumerate() {
        if R::SKIPS_OWN && Some(i) == skip {
            continue;
        }
        if let Ok(hit) = R::intersect(&object.shape, ray, scene.epsilon)
            && best.is_none_or(|(_, b)| hit.t < b.t)
        {
            best = Some((i, hit));
        }
    }
    best
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
/// checkerboard anchored at the world origin (`COURSE-RULES.md` §10; `Tracer::shows_alt`).
#[inline]
pub(crate) fn material_at<S: Scalar>(
    object: &Object<S>,
    point: Vec3<S>,
    rules: Rules,
    counters: &mut Counters,
) -> u8 {
    match object.shape {
        Shape::Tiled { frame, alt, tiling } => {
            count(&mut counters.tile_lookups);
            let show_alt = match tiling {
                Tiling::WorldXz => frame.odd_tile_world_xz(point) == Some(true),
                Tiling::Frame => with_rules!(rules, shows_alt::<S>(&frame, point)),
            };
            if show_alt { alt } else { object.material }
        }
        Shape::Plane(_)
        | Shape::Sphere(_)
        | Shape::Finite(_)
        | Shape::Textured(_)
        | Shape::Triangle(_)
        | Shape::Revsurf(_) => object.material,
    }
}

fn shows_alt<S: Scalar, R: Tracer>(frame: &crate::PlaneFrame<S>, point: Vec3<S>) -> bool {
    R::shows_alt(frame, point)
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
    // Without the `textures` feature the texel lookup is not linked: a textured plane
    // (only a scene built in code can have one then: the parser refuses them) shows its
    // material as it is.
    Some(
        if cfg!(feature = "textures")
            && let Shape::Textured(slide) = &object.shape
        {
            (
                object,
                texture::textured(material, texture::texel(scene, slide, point)),
            )
        } else {
            (object, *material)
        },
    )
}

/// The colour of a hit on `objects[index]`, lit by the scene's lights, in channel units
/// (the stages the scene's plan needs), by the crate's rules (its mirrors included; the
/// course's rules divide a colour by the whole path, which only [`trace`] knows).
pub fn shade<S: Scalar>(
    scene: &impl AsView<S>,
    ray: &Ray<S>,
    index: usize,
    hit: &Hit<S>,
) -> Color<S> {
    let (scene, shading) = planned(scene);
    let scene = &scene;
    let counters = &mut Counters::default();
    let ray = &Incoming::from(ray);
    with_stages!(
        shading,
        fixray::shade::<S>(scene, ray, index, hit, counters)
    )
}

/// What a primary ray found: the nearest hit (object index and hit) and the colour.
///
/// ```
/// use fixray::shade::trace_pixel;
/// use fixray::{Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "rules fixray
///      camera c { pixeldim 4 4 worlddim 4 4 viewpoint 2 2 5 }
///      material red { ambient 1 0 0 }
///      plane floor { material red normal 0 1 0 point 0 0.4 0 }",
/// )?;
/// let floor = trace_pixel(&scene, 0, 3);
/// let (object, hit) = floor.hit.unwrap();
/// assert_eq!(object, 0);
/// assert!((hit.point.y.to_num::<f64>() - 0.4).abs() < 1e-3);
/// assert_eq!(floor.color[0].to_num::<f64>(), 255.0);
/// assert_eq!(trace_pixel(&scene, 0, 0).color, scene.background); // the sky
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Traced<S> {
    /// The nearest accepted hit, or `None` for the background.
    pub hit: Option<(usize, Hit<S>)>,
    /// The colour in channel units.
    pub color: Color<S>,
}

/// Traces a pixel's primary ray with the stages of `T` by the scene's rule set (the
/// course's takes the pixel's unnormalised direction for its textured planes' points).
pub(crate) fn trace_pixel_ray<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    pixel: &PixelRay<S>,
    counters: &mut Counters,
) -> Traced<S> {
    with_rules!(
        scene.rules(),
        trace_pixel_by::<S, T>(scene, pixel, counters)
    )
}

fn trace_pixel_by<S: Scalar, R: Tracer, T: Stages>(
    scene: &SceneView<'_, S>,
    pixel: &PixelRay<S>,
    counters: &mut Counters,
) -> Traced<S> {
    R::trace_pixel::<S, T>(scene, pixel, counters)
}

/// Traces one ray: its nearest hit and colour, with the stages the scene's plan needs.
pub fn trace<S: Scalar>(scene: &impl AsView<S>, ray: &Ray<S>) -> Traced<S> {
    let (scene, shading) = planned(scene);
    let scene = &scene;
    let counters = &mut Counters::default();
    with_stages!(shading, trace_one::<S>(scene, ray, counters))
}

fn trace_one<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    counters: &mut Counters,
) -> Traced<S> {
    with_rules!(scene.rules(), trace_by::<S, T>(scene, ray, counters))
}

fn trace_by<S: Scalar, R: Tracer, T: Stages>(
    scene: &SceneView<'_, S>,
    ray: &Ray<S>,
    counters: &mut Counters,
) -> Traced<S> {
    R::trace::<S, T>(scene, ray, counters)
}

/// Traces the primary ray of pixel (`column`, `row`), row 0 at the top, on the reference
/// path. A ray that cannot be formed in the format (see [`crate::Camera::primary_ray`])
/// sees the background. It works out the scene's plan on every call: for many pixels,
/// [`crate::Frame::trace_pixel`] does that once per frame.
pub fn trace_pixel<S: Scalar>(scene: &impl AsView<S>, column: u16, row: u16) -> Traced<S> {
    let (scene, shading) = planned(scene);
    trace_pixel_with(&scene, shading, column, row)
}

/// [`trace_pixel`] with the stage set already chosen (`scene` set up for it,
/// [`stages::stage`]).
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
