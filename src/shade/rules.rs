//! The rule sets as types: [`Fixray`] (the crate's rules, `fixray.rs`) and [`Course`]
//! (the course tracer's, `course.rs`), each implementing [`RuleSet`] (what a user can
//! ask of a rule set: its intersection and shadow tests) and the crate's `Tracer`
//! (tracing, and the few points where the one light loop, `light.rs`, differs).
//!
//! A frame is drawn by one of them, chosen once per ray from the scene's [`Rules`] (the
//! only `match` on the rule set in shading: `with_rules!`); everything below it (the
//! nearest hit, the light loop, the shadow tests) is compiled once per rule set, so a
//! rule set never asks at run time which one it is.

use super::light::{Lit, Passage};
use super::stages::{LightStages, Stages};
use super::{Incoming, Traced};
use crate::scene::PixelRay;
use crate::stats::Counters;
use crate::{
    Color, Hit, Light, Material, Miss, Object, PlaneFrame, Ray, Rules, Scalar, SceneView, Shape,
    Vec3,
};
use embedded_graphics_core::pixelcolor::Rgb888;

/// The crate's own rules ([`Rules::Fixray`]): pixel centres, rounding, the normal facing
/// the ray, secondary rays spawned off the surface by its error bound, the nearest root
/// of a sphere, `reflective` mirrors, glints divided by the light distance.
///
/// ```
/// use fixray::geometry::{Plane, Ray, RayKind, Shape, Vec3};
/// use fixray::shade::{Fixray, RuleSet};
/// use fixray::{Scalar, I16F16};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let wall = Shape::Plane(Plane::new(v(0.0, 0.0, 1.0), v(0.0, 0.0, -5.0)).unwrap());
/// let ray = Ray { base: v(0.0, 0.0, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Primary };
/// let hit = Fixray::intersect(&wall, &ray, I16F16::DEFAULT_EPSILON).unwrap();
/// assert_eq!(hit.t, I16F16::from_num(10));
/// assert_eq!(Fixray::RULES.name(), "fixray");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Fixray;

/// The course tracer's rules ([`Rules::Course`], `course/COURSE-RULES.md`): the screen
/// rule for plane-type hits of every ray, the near sphere root only, secondary rays that
/// start on the hit and skip its object, colours divided by the path length.
///
/// ```
/// use fixray::geometry::{Miss, Plane, Ray, RayKind, Shape, Vec3};
/// use fixray::shade::{Course, RuleSet};
/// use fixray::{Scalar, I16F16};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// // The course's screen rule holds for every ray: a shadow ray meets nothing at z > 0.01.
/// let near = Shape::Plane(Plane::new(v(0.0, 0.0, 1.0), v(0.0, 0.0, 0.5)).unwrap());
/// let ray = Ray { base: v(0.0, 0.0, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Secondary };
/// assert_eq!(Course::intersect(&near, &ray, I16F16::DEFAULT_EPSILON), Err(Miss::InFrontOfScreen));
/// ```
#[cfg(feature = "course")]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Course;

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::Fixray {}
    #[cfg(feature = "course")]
    impl Sealed for super::Course {}
}

/// A rule set as a type: what the intersection and shadow tests of a scene drawn by it
/// are. Implemented by [`Fixray`] and [`Course`] only (sealed); generic code and tests
/// take the rule set as a type parameter.
///
/// ```
/// use fixray::{Scalar, I16F16};
/// use fixray::geometry::{Miss, Plane, Ray, RayKind, Shape, Vec3};
/// use fixray::shade::{Course, Fixray, RuleSet};
///
/// let v = |x: f64, y: f64, z: f64| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// // A plane at z = 0.5, in front of the screen (z = 0), met by a shadow ray.
/// let plane = Shape::Plane(Plane::new(v(0.0, 0.0, 1.0), v(0.0, 0.0, 0.5)).unwrap());
/// let ray = Ray { base: v(0.0, 0.0, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Secondary };
/// let eps = I16F16::DEFAULT_EPSILON;
/// // The crate's screen rule is for primary rays only; the course's for every ray.
/// assert_eq!(Fixray::intersect(&plane, &ray, eps).map(|h| h.t), Ok(I16F16::from_num(4.5)));
/// assert_eq!(Course::intersect(&plane, &ray, eps), Err(Miss::InFrontOfScreen));
/// assert_eq!(Course::RULES.name(), "course");
/// ```
pub trait RuleSet: sealed::Sealed + Copy + Default + 'static {
    /// The rule set as a value (what a scene file names).
    const RULES: Rules;

    /// The intersection of a ray with a shape under these rules (`epsilon`: the plane
    /// tests' precision epsilon). The crate's: [`Shape::intersect`]. The course's
    /// (`COURSE-RULES.md` §5): planes miss at `t <= 0` and reject a plane-type hit with
    /// `z > 0.01` (triangles `z > 0`) whatever the ray; spheres take only the near root,
    /// with no screen rule.
    ///
    /// # Errors
    /// The [`Miss`] reason when the ray does not hit.
    fn intersect<S: Scalar>(shape: &Shape<S>, ray: &Ray<S>, epsilon: S) -> Result<Hit<S>, Miss>;

    /// Whether `shape` meets the shadow segment from `from` (a hit point) to the light at
    /// `from + l` (`ll = l·l`), from signs and product comparisons where the shape has a
    /// segment form. The crate's: [`Shape::meets_segment`] (`tol`: how far `from` may lie
    /// off its surface). The course's: what [`RuleSet::intersect`] with `t < dist`
    /// decides for the unit ray (the caller skips the object `from` lies on; `tol` is
    /// not used).
    fn meets_segment<S: Scalar>(
        shape: &Shape<S>,
        from: Vec3<S>,
        l: Vec3<S>,
        ll: S,
        tol: S,
        epsilon: S,
    ) -> bool;

    /// Whether `shape` meets the shadow ray `ray` (unit direction) before `dist`: the
    /// crate's [`Shape::occludes`], the course's [`RuleSet::intersect`] with `t < dist`.
    fn blocks<S: Scalar>(shape: &Shape<S>, ray: &Ray<S>, epsilon: S, dist: S) -> bool;

    /// Whether `shape` shadows a light at `light` from the shadow ray `ray` (unit
    /// direction towards the light, which is `dist` away): [`RuleSet::blocks`], except
    /// for a light lying on the surface within `tol`, the hard case where `t` and `dist`
    /// tie and the rounding would decide pixel by pixel ([`Shape::spares_light`]). So
    /// every format draws the same clean shadow as f64 (`docs/numerics.md`, "Lights on
    /// surfaces").
    fn shadows<S: Scalar>(
        shape: &Shape<S>,
        ray: &Ray<S>,
        epsilon: S,
        dist: S,
        light: Vec3<S>,
        tol: S,
    ) -> bool {
        Self::blocks(shape, ray, epsilon, dist) && !shape.spares_light(ray, light, tol)
    }
}

/// What shading asks of a rule set beyond [`RuleSet`]: tracing a ray, and the points
/// where the one light loop (`light.rs`) differs.
pub(crate) trait Tracer: RuleSet {
    /// Whether the nearest-hit search skips the object a secondary ray leaves (the
    /// course's; the crate's rays start off the surface instead).
    const SKIPS_OWN: bool;
    /// Whether a spotlight's cone is strict (`cos > cos θ`, the course's) or takes its
    /// edge (`≥`, the crate's).
    const STRICT_CONE: bool;
    /// Whether a glint is divided by the light distance (the crate's).
    const GLINT_FALLOFF: bool;

    /// Traces a pixel's primary ray with the stages of `T`.
    fn trace_pixel<S: Scalar, T: Stages>(
        scene: &SceneView<'_, S>,
        pixel: &PixelRay<S>,
        counters: &mut Counters,
    ) -> Traced<S>;

    /// Traces a ray with the stages of `T`.
    fn trace<S: Scalar, T: Stages>(
        scene: &SceneView<'_, S>,
        ray: &Ray<S>,
        counters: &mut Counters,
    ) -> Traced<S>;

    /// A colour in channel units as a pixel.
    fn to_pixel<S: Scalar>(c: Color<S>) -> Rgb888;

    /// Whether a frame-tiled plane shows its alternate material at `point` (the rule
    /// sets anchor and colour the checkerboard differently).
    fn shows_alt<S: Scalar>(frame: &PlaneFrame<S>, point: Vec3<S>) -> bool;

    /// Whether `material` shows a specular glint.
    fn glints<S: Scalar>(material: &Material<S>) -> bool;

    /// The segment tests' tolerance at a hit (how far it may lie off its surface); `None`
    /// when the shadow segments cannot be used there (every light then takes the ray
    /// path).
    fn segment_tolerance<S: Scalar>(
        stages: LightStages,
        ray: &Incoming<'_, S>,
        hit: &Hit<S>,
    ) -> Option<S>;

    /// The shadow along the segment from the hit to light `index` at `hit + to_light`
    /// (`ll = |to_light|²`).
    fn segment_shadow<S: Scalar>(
        at: &Lit<'_, '_, S>,
        light: (usize, &Light<S>),
        to_light: Vec3<S>,
        ll: S,
        tol: S,
    ) -> Passage<S>;

    /// The shadow along the ray from the hit towards the light (unit direction `l`, the
    /// light `dist` away), for a light whose `|L|²` does not fit the format.
    fn ray_shadow<S: Scalar>(
        at: &Lit<'_, '_, S>,
        light: &Light<S>,
        l: Vec3<S>,
        dist: S,
    ) -> Passage<S>;

    /// Where a hit on `object` at `point` moved after a shadow ray towards the light at
    /// `light` went on past a translucent occluder ([`Passage::continues`]); `None`: it
    /// stays (the crate's hits never move).
    fn moved_hit<S: Scalar>(
        _object: &Object<S>,
        _point: Vec3<S>,
        _light: Vec3<S>,
    ) -> Option<(Vec3<S>, Vec3<S>)> {
        None
    }
}

/// `with_rules!(rules, f::<S, More…>(args))` calls `f::<S, Set, More…>(args)` for the
/// rule set `Set` that `rules` (a [`Rules`]) names.
macro_rules! with_rules {
    ($rules:expr, $($f:ident)::+::<$s:ty $(, $more:ty)*>($($arg:expr),*)) => {
        match $rules {
            $crate::Rules::Fixray => {
                $($f)::+::<$s, $crate::shade::rules::Fixray $(, $more)*>($($arg),*)
            }
            #[cfg(feature = "course")]
            $crate::Rules::Course => {
                $($f)::+::<$s, $crate::shade::rules::Course $(, $more)*>($($arg),*)
            }
            // Without the cargo feature `course` no file is read by the course's rules
            // (the parser refuses them); a scene set to them in code is drawn by the
            // crate's, so that the course's tracer is not linked.
            #[cfg(not(feature = "course"))]
            $crate::Rules::Course => {
                $($f)::+::<$s, $crate::shade::rules::Fixray $(, $more)*>($($arg),*)
            }
        }
    };
}
pub(crate) use with_rules;
