//! The scene: camera, materials, lights, objects, background and precision epsilon, in
//! number format `S`, with capacities fixed in the types (no allocator).
//!
//! Scenes are read from the course's keyword-block text format with [`Scene::parse`]
//! (`parse/`: lexer, errors, schema, builder); errors carry a line and column
//! ([`SceneError`]). The camera (`camera.rs`) is the one place that maps a pixel to the
//! screen; the plan (`plan.rs`) is what the scene needs of the renderer, worked out from
//! its contents whenever it is asked for, so it cannot go stale. Displayed colours (ambient, background) are stored in
//! *channel units*: a scene colour `c` is kept as `255 c`, computed exactly from the
//! decimal text, so that the pixel value is `round(clamp(colour, 0, 255))` and a colour
//! such as 0.7 (178.5 channel units) is exact in every fixed format instead of rounding to
//! a neighbouring pixel value. A colour whose 255-fold does not fit the format (above
//! 128.5 in I16F16) is stored as the format's maximum, which displays the same (255).
//! Diffuse reflectances and emissivities stay plain reals.

use heapless::Vec;

use crate::ppm::Ppm;
use crate::{Plane, Scalar, Shape, Slide, Vec3};

mod camera;
#[cfg(feature = "std")]
pub mod files;
pub mod language;
mod parse;
mod plan;
mod rules;

pub(crate) use camera::PixelRay;
pub use camera::{Camera, PixelGrid};
pub use parse::schema;
pub use parse::{
    MAX_NUMBER, MAX_QUOTED, Quantity, Quoted, QuotedNumber, SceneError, SceneErrorKind,
    TextureProblem,
};
pub use plan::Plan;
pub use rules::{Rules, UnknownRules};

/// Maximum number of materials in a scene.
pub const MAX_MATERIALS: usize = 16;
/// Maximum number of lights (point lights and spotlights together).
pub const MAX_LIGHTS: usize = 8;
/// Maximum number of objects (planes, spheres, tiled and finite planes together).
pub const MAX_OBJECTS: usize = 32;
/// Maximum number of textures (the course's `texture` entity) in a scene: 8 with the
/// cargo feature `textures`, none without it (a scene then keeps no room for them).
pub const MAX_TEXTURES: usize = if cfg!(feature = "textures") { 8 } else { 0 };
/// Maximum number of projectors (lights that project a texture) in a scene: 2 with the
/// cargo feature `textures`, none without it.
pub const MAX_PROJECTORS: usize = if cfg!(feature = "textures") { 2 } else { 0 };
/// Largest `pixeldim` in either direction, as the scene format states.
pub const MAX_PIXELDIM: u16 = 4096;

/// The smallest scale a scene may have, in units of its number format's resolution.
/// [`Scene::parse`] refuses, with [`SceneErrorKind::BelowResolution`] at the number at
/// fault (its message names the formats that resolve every pitch and sphere of the
/// scene):
///
/// - a pixel pitch (`worlddim / pixeldim`, along either axis) below this many
///   [`Scalar::ulp`]s of the larger of the window's size and the eye's coordinate along
///   that axis (`screen − eye` is rounded there);
/// - in a fixed format, a sphere whose radius² is below [`MIN_RADIUS_SQ_DELTAS`]
///   `DELTA`s;
/// - in a float, a sphere whose radius is below this many ulps of its largest coordinate
///   (its radius² carries a relative error: no floor of its own).
///
/// In a fixed format the ulp is `DELTA` at every magnitude; in a float it is `DELTA` (the
/// machine epsilon) times the magnitude, at least 1, as the renderer's tolerances take
/// it. A `worlddim` or radius that rounds to 0 is an [`SceneErrorKind::OutOfDomain`]
/// error, and a radius² beyond the range is [`SceneErrorKind::BeyondRange`]. A scene
/// built in code is not checked.
///
/// Why 4: a screen point is rounded once, by at most ½ `DELTA`, which at a pitch of
/// 4 `DELTA` is an eighth of a pixel, below what moves an edge by a pixel; a float's
/// radius of 4 ulps of its coordinates keeps the rounding of a ray's base less its centre
/// (an ulp at that magnitude) within a quarter of the radius. Below that a picture is
/// garbage without a word (pixels more than 8 levels off f64's): the default scene scaled
/// down to a pitch of 0.33 `DELTA` draws 1.5 % of them in I16F16, to 0.2 `DELTA` 23 % in
/// I20F12, while at 2 to 3.3 `DELTA`s both draw f64's picture; a millimetre scene
/// (`worlddim 0.001 0.00075` over 160 × 120 pixels, a sphere of radius 0.0005: pitch
/// 0.4 `DELTA` and radius² 0.02 `DELTA` in I16F16) 47 %. Every shipped scene and course
/// scene is at least 41 ulps per pixel in every format that reads it.
///
/// ```
/// use fixray::{I16F16, I32F32, Scene};
///
/// let text = "camera c { pixeldim 160 120 worlddim 0.001 0.00075 viewpoint 0.0005 0.0004 0.002 }";
/// let err = Scene::<I16F16>::parse(text).unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "1:38: pixel pitch 6.25e-6 is below 4 DELTA of i16f16; i32f32, f32 or f64 resolve it"
/// );
/// assert!(Scene::<I32F32>::parse(text).is_ok());
/// ```
pub const MIN_SCALE_DELTAS: i32 = 4;

/// The smallest radius² of a sphere in a fixed format, in `DELTA`s: [`Scene::parse`]
/// refuses a sphere whose radius² is smaller, with [`SceneErrorKind::BelowResolution`]
/// at its radius (a radius of at least ⅛ in I16F16, ½ in I20F12, 2⁻¹¹ in I32F32). In a
/// float a radius is held to [`MIN_SCALE_DELTAS`] ulps of the sphere's coordinates.
///
/// Why 1024: a hit is placed on a sphere by the discriminant `r² − dist²` (`dist` the
/// centre's distance from the ray), rounded once to `DELTA`. Where the ray meets the
/// surface at an angle of cosine `s` (the discriminant is `(s·r)²`) that rounding moves
/// the hit along the ray by `DELTA/(4sr)`, and its normal `(P − C)/r` by up to
/// `DELTA/(4sr²)`, which is more than 1/256 (a level of a light's `255·N·L`) where
/// `s < 64·DELTA/r²`: at `r² ≥ 1024 DELTA` only on the rim where `s < 1/16`, 1/256 of
/// the sphere's pixels; below, on a rim that grows as `1/r⁴`, and a light nearer than 1
/// (its falloff `N·L/|L|²`) magnifies the error further. The millimetre scene 100 times
/// larger (a sphere of radius 0.05, r² = 164 `DELTA` of I16F16, on nearly half of the
/// picture, lit from 0.27 away) draws 3.2 % of its pixels more than 2 levels off f64's in
/// I16F16; with radius 0.15 (1,475 `DELTA`) 0.02 %, and the millimetre scene itself in
/// I32F32 (1,073 `DELTA`) 0.5 %. [`crate::geometry::Sphere`] takes its normal's `1/r`
/// shortcut from the same 1024 `DELTA` on. Every shipped scene and course scene has at
/// least 2,000 `DELTA`s per radius² in every fixed format that reads it.
///
/// ```
/// use fixray::{I16F16, I32F32, Scene};
///
/// let text = "camera c { pixeldim 8 6 worlddim 8 6 viewpoint 4 3 5 }
///             material m { ambient 1 0 0 }
///             sphere s { material m center 4 3 -1 radius 0.1 }";
/// let err = Scene::<I16F16>::parse(text).unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "3:56: radius² 0.01 is below 1024 DELTA of i16f16; i32f32, f32 or f64 resolve it"
/// );
/// assert!(Scene::<I32F32>::parse(text).is_ok());
/// ```
pub const MIN_RADIUS_SQ_DELTAS: i32 = 1024;

/// An RGB colour in channel units (0 ..= 255 displays; larger values clamp).
///
/// ```
/// use fixray::scene::Color;
/// use fixray::{Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera c { pixeldim 1 1 worlddim 1 1 viewpoint 0.5 0.5 5 } background 1 0.5 0",
/// )?;
/// let sky: Color<I16F16> = scene.background; // a scene's 0 ..= 1, in channel units
/// assert_eq!(sky.map(|c| c.to_num::<f64>()), [255.0, 127.5, 0.0]);
/// # Ok::<(), fixray::SceneError>(())
/// ```
pub type Color<S> = [S; 3];

/// A surface material.
///
/// ```
/// use fixray::scene::Material;
/// use fixray::{Scalar, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "rules fixray
///      camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
///      material shiny { ambient 0.2 0 0 diffuse 0.8 0.1 0.1 specular 0.5 shininess 20 }",
/// )?;
/// let m = scene.materials[0];
/// assert!((m.ambient[0].to_f64() - 0.2 * 255.0).abs() < 1e-3); // in channel units
/// assert_eq!(m.shininess, I16F16::from_num(20));
/// assert_eq!(Material::<I16F16>::new().reflective, I16F16::ZERO); // the defaults: matte
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material<S> {
    /// Ambient colour, in channel units (see the module documentation).
    pub ambient: Color<S>,
    /// Diffuse reflectance per channel, a plain real as in the scene (it multiplies the
    /// light's emissivity; the product is brought to channel units when shading).
    pub diffuse: [S; 3],
    /// Specular reflectance (0: no glint).
    pub specular: S,
    /// Specular exponent, ≥ 1.
    pub shininess: S,
    /// Mirror share K in [0, 1] (0: not reflective).
    pub reflective: S,
    /// The course's `transparency` T in [0, 1] (0: opaque): a translucent surface shows
    /// `(1 − T)` of its own colour and filters what lies behind it and the light through
    /// it (`COURSE-RULES.md` §11).
    pub transparency: S,
}

impl<S: Scalar> Material<S> {
    /// A material with every attribute at the scene format's default (black, matte).
    pub fn new() -> Self {
        Self {
            ambient: [S::ZERO; 3],
            diffuse: [S::ZERO; 3],
            specular: S::ZERO,
            shininess: S::ONE,
            reflective: S::ZERO,
            transparency: S::ZERO,
        }
    }
}

impl<S: Scalar> Default for Material<S> {
    fn default() -> Self {
        Self::new()
    }
}

/// A spotlight's cone: it lights a point only when the angle between its axis and the
/// direction to the point is at most θ, i.e. `(point − location)·axis ≥ cos θ × |…|`.
///
/// ```
/// use fixray::{Scalar, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "rules fixray
///      camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
///      spotlight spot { location 0 5 0 emissivity 1 1 1 point 0 0 0 theta 60 }",
/// )?;
/// let cone = scene.lights[0].cone().unwrap();
/// assert_eq!(cone.axis.y, -I16F16::ONE); // straight down
/// assert!((cone.cos_theta.to_f64() - 0.5).abs() < 1e-4);
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone<S> {
    /// Unit vector from the light towards the point it is aimed at.
    pub axis: Vec3<S>,
    /// cos θ.
    pub cos_theta: S,
}

/// Where a light shines.
///
/// ```
/// use fixray::scene::Beam;
/// use fixray::{Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "rules fixray
///      camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
///      light bulb { location 0 5 0 emissivity 1 1 1 }
///      spotlight spot { location 0 5 0 emissivity 1 1 1 point 0 0 0 theta 30 }",
/// )?;
/// assert_eq!(scene.lights[0].beam, Beam::Everywhere);
/// assert!(matches!(scene.lights[1].beam, Beam::Cone(_)));
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Beam<S> {
    /// Everywhere: a point light.
    Everywhere,
    /// Within a cone: a spotlight.
    Cone(Cone<S>),
    /// Through a slide: a projector (the course's `projector`), which lights a point only
    /// through the slide's rectangle, with its emissivity times the texel there. The
    /// index is into [`Scene::projectors`].
    Projector(u8),
}

/// A point light, a spotlight or a projector.
///
/// ```
/// use fixray::geometry::Vec3;
/// use fixray::scene::{Beam, Light};
/// use fixray::{Scene, I16F16};
///
/// let mut scene = Scene::<I16F16>::parse(
///     "rules fixray
///      camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
///      light lamp { location 1 4 -2 emissivity 2 2 2 }",
/// )?;
/// assert_eq!(scene.lights[0].location, Vec3::from_f64([1.0, 4.0, -2.0]).unwrap());
/// // Built in code: a second, red, point light.
/// let red = Light {
///     location: Vec3::from_f64([3.0, 4.0, -2.0]).unwrap(),
///     emissivity: [I16F16::from_num(2), I16F16::from_num(0), I16F16::from_num(0)],
///     beam: Beam::Everywhere,
/// };
/// scene.lights.push(red).unwrap();
/// assert!(scene.plan().lighting);
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light<S> {
    /// Position.
    pub location: Vec3<S>,
    /// Emissivity per channel (plain reals, not channel units).
    pub emissivity: Color<S>,
    /// Where it shines.
    pub beam: Beam<S>,
}

impl<S> Light<S> {
    /// The spotlight's cone; `None` for a point light or a projector.
    #[inline]
    pub fn cone(&self) -> Option<&Cone<S>> {
        match &self.beam {
            Beam::Cone(c) => Some(c),
            _ => None,
        }
    }
}

/// A shape with its material.
///
/// ```
/// use fixray::geometry::Shape;
/// use fixray::{Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
///      material grey { ambient 0.5 0.5 0.5 }  material red { ambient 1 0 0 }
///      sphere ball { material red center 2 1.5 -5 radius 1 }",
/// )?;
/// let ball = &scene.objects[0];
/// assert!(matches!(ball.shape, Shape::Sphere(_)));
/// assert_eq!(ball.material, 1); // `red`, the second material
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Object<S> {
    /// The geometry.
    pub shape: Shape<S>,
    /// Index into [`Scene::materials`].
    pub material: u8,
}

/// A scene in number format `S`.
///
/// ```
/// use fixray::{Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera cam { pixeldim 4 3 worlddim 8 6 viewpoint 4 3 5 }
///      material grey { ambient 0.5 0.5 0.5 }
///      plane floor { material grey normal 0 1 0 point 0 -1 0 }",
/// )
/// .unwrap();
/// assert_eq!(scene.objects.len(), 1);
/// assert_eq!((scene.camera.width, scene.camera.height), (4, 3));
/// ```
///
/// The capacities are part of the type: `OBJECTS` objects, `MATERIALS` materials and
/// `LIGHTS` lights, today's [`MAX_OBJECTS`], [`MAX_MATERIALS`] and [`MAX_LIGHTS`] by
/// default (what a 16 KB chip holds). A host or a big chip picks larger ones; a file over
/// capacity is a [`SceneErrorKind::TooMany`] error that names the parameter to raise.
///
/// ```
/// use fixray::{Scene, I16F16};
/// use fixray::scene::SceneErrorKind;
///
/// let mut text = String::from("camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }");
/// text += "material m { ambient 1 1 1 }";
/// for i in 0..100 {
///     text += &format!("sphere s{i} {{ material m center {i} 0 -10 radius 0.5 }}");
/// }
/// let err = Scene::<I16F16>::parse(&text).unwrap_err();
/// assert!(matches!(err.kind, SceneErrorKind::TooMany { capacity: 32, parameter: "OBJECTS", .. }));
/// let big = Scene::<I16F16, 128>::parse(&text).unwrap();
/// assert_eq!(big.objects.len(), 100);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Scene<
    S,
    const OBJECTS: usize = MAX_OBJECTS,
    const MATERIALS: usize = MAX_MATERIALS,
    const LIGHTS: usize = MAX_LIGHTS,
> {
    /// The camera.
    pub camera: Camera<S>,
    /// Materials, indexed by [`Object::material`] (at most 256 of them can be named).
    pub materials: Vec<Material<S>, MATERIALS>,
    /// Point lights.
    pub lights: Vec<Light<S>, LIGHTS>,
    /// Objects.
    pub objects: Vec<Object<S>, OBJECTS>,
    /// Textures, indexed by [`Slide::texture`]: binary PPM images borrowed for the
    /// program's life (flash on a chip, e.g. `include_bytes!`; see [`Scene::read_with`]).
    pub textures: Vec<Ppm<'static>, MAX_TEXTURES>,
    /// Projectors' slides, indexed by [`Beam::Projector`].
    pub projectors: Vec<Slide<S>, MAX_PROJECTORS>,
    /// Colour where no object is hit.
    pub background: Color<S>,
    /// The precision epsilon of every intersection test in this scene: the scene's
    /// `precision`, or [`Scalar::DEFAULT_EPSILON`].
    pub epsilon: S,
    /// The rule set ([`Scene::rules`]).
    rules: Rules,
}

/// Capacities for a host or a big chip: every real course file fits (the largest has 178
/// objects).
///
/// ```
/// use fixray::scene::LargeScene;
/// use fixray::{Scene, I16F16};
///
/// let mut text = String::from("camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }");
/// text += "material m { ambient 1 1 1 }";
/// for i in 0..100 {
///     text += &format!("sphere s{i} {{ material m center {i} 0 -10 radius 0.5 }}");
/// }
/// assert!(Scene::<I16F16>::parse(&text).is_err()); // 32 objects at most
/// assert_eq!(LargeScene::<I16F16>::parse(&text).unwrap().objects.len(), 100);
/// ```
pub type LargeScene<S> = Scene<S, 1024, 256, 64>;

/// A scene of any capacities seen through slices ([`Scene::view`]): what the renderer
/// reads, so that its code is the same for every capacity.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use fixray::scene::LargeScene;
/// use fixray::{render_line, Scene, I16F16};
///
/// let text = "camera c { pixeldim 4 1 worlddim 4 1 viewpoint 2 0.5 5 } background 0 0 1";
/// let (small, large) = (Scene::<I16F16>::parse(text)?, LargeScene::<I16F16>::parse(text)?);
/// // Two capacities, one view type: what the renderer reads.
/// assert_eq!(small.view().objects.len(), large.view().objects.len());
/// let (mut a, mut b) = ([Rgb888::new(0, 0, 0); 4], [Rgb888::new(0, 0, 0); 4]);
/// render_line(&small.view(), 0, &mut a);
/// render_line(&large, 0, &mut b);
/// assert_eq!(a, b);
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct SceneView<'a, S> {
    /// The camera.
    pub camera: Camera<S>,
    /// Materials, indexed by [`Object::material`].
    pub materials: &'a [Material<S>],
    /// Lights.
    pub lights: &'a [Light<S>],
    /// Objects.
    pub objects: &'a [Object<S>],
    /// Textures.
    pub textures: &'a [Ppm<'static>],
    /// Projectors' slides.
    pub projectors: &'a [Slide<S>],
    /// Colour where no object is hit.
    pub background: Color<S>,
    /// The precision epsilon.
    pub epsilon: S,
    /// The rule set.
    pub rules: Rules,
    /// Whether the tie checks of lights lying on surfaces run: always for a view of a
    /// scene ([`Scene::view`]); a frame sets it from its plan ([`Plan`]'s
    /// `lights_on_surfaces`), so that a scene without such a light pays nothing for them.
    pub(crate) lights_on_surfaces: bool,
    /// Whether the light loop casts shadows: the stage set's, set where a set is chosen
    /// for the view (`shade::stages::stage`); `true` for a view of a scene (the compiled
    /// set then decides alone). A build with one compiled set (cargo feature `kernels`
    /// off) draws every scene with it and asks this instead.
    pub(crate) shadows: bool,
}

/// How close to a surface a light counts as lying on it ([`crate::Shape::shadows`]): the
/// scene's epsilon in units of the larger of 1 and the light's and the eye's coordinates
/// (the rounding of the light's, the surface's and the hit points' positions grows with
/// the scene's magnitude). One value per light and frame, so that the plan can tell in
/// advance whether any light lies on any surface.
pub(crate) fn light_tolerance<S: Scalar>(epsilon: S, light: Vec3<S>, eye: Vec3<S>) -> S {
    let m = S::ONE.max(light.max_abs()).max(eye.max_abs());
    epsilon.checked_mul(m).unwrap_or(S::MAX)
}

/// What the renderer's functions take: a [`Scene`] of any capacities, or a
/// [`SceneView`] of one.
///
/// ```
/// use fixray::scene::{AsView, LargeScene};
/// use fixray::{Scalar, Scene, I16F16};
///
/// // One function for scenes of every capacity.
/// fn objects<S: Scalar>(scene: &impl AsView<S>) -> usize {
///     scene.view().objects.len()
/// }
/// let text = "camera c { pixeldim 4 3 worlddim 4 3 viewpoint 2 1.5 5 }
///             material m { ambient 1 1 1 }  plane p { material m normal 0 1 0 point 0 0 0 }";
/// assert_eq!(objects(&Scene::<I16F16>::parse(text)?), 1);
/// assert_eq!(objects(&LargeScene::<I16F16>::parse(text)?), 1);
/// # Ok::<(), fixray::SceneError>(())
/// ```
pub trait AsView<S> {
    /// The scene through slices.
    fn view(&self) -> SceneView<'_, S>;
}

impl<S: Scalar, const O: usize, const M: usize, const L: usize> AsView<S> for Scene<S, O, M, L> {
    fn view(&self) -> SceneView<'_, S> {
        Scene::view(self)
    }
}

impl<S: Scalar> AsView<S> for SceneView<'_, S> {
    fn view(&self) -> SceneView<'_, S> {
        *self
    }
}

impl<S: Scalar> SceneView<'_, S> {
    /// The rule set the scene is drawn by.
    #[inline]
    pub fn rules(&self) -> Rules {
        self.rules
    }
}

impl<S: Scalar, const O: usize, const M: usize, const L: usize> Scene<S, O, M, L> {
    /// The scene through slices, for the renderer.
    #[inline]
    pub fn view(&self) -> SceneView<'_, S> {
        SceneView {
            camera: self.camera,
            materials: &self.materials,
            lights: &self.lights,
            objects: &self.objects,
            textures: &self.textures,
            projectors: &self.projectors,
            background: self.background,
            epsilon: self.epsilon,
            rules: self.rules,
            lights_on_surfaces: true,
            shadows: true,
        }
    }

    /// A scene with a camera and nothing in it: black background, default epsilon, the
    /// crate's own rules ([`Rules::Fixray`]; the camera's grid is set to match).
    pub fn new(camera: Camera<S>) -> Self {
        let mut scene = Self {
            camera,
            materials: Vec::new(),
            lights: Vec::new(),
            objects: Vec::new(),
            textures: Vec::new(),
            projectors: Vec::new(),
            background: [S::ZERO; 3],
            epsilon: S::DEFAULT_EPSILON,
            rules: Rules::Fixray,
        };
        scene.set_rules(Rules::Fixray);
        scene
    }

    /// The rule set the scene is drawn by: the file's `rules` statement, [`Rules::Course`]
    /// for a file without one, [`Rules::Fixray`] for a scene built in code.
    pub fn rules(&self) -> Rules {
        self.rules
    }

    /// Draws the scene by `rules` from now on (a tool's `--rules` override). The camera's
    /// pixel grid follows: pixel centres for `fixray`, the window's corners for `course`.
    ///
    /// Without the cargo feature `course` the course's rules are not built in: the scene
    /// is then drawn by the crate's (`Rules::Course` is taken as `Rules::Fixray`, grid
    /// and plan included).
    pub fn set_rules(&mut self, rules: Rules) {
        let rules = if cfg!(feature = "course") {
            rules
        } else {
            Rules::Fixray
        };
        self.rules = rules;
        self.camera.grid = match rules {
            Rules::Course => PixelGrid::Corners,
            Rules::Fixray => PixelGrid::Centres,
        };
    }

    /// Adds a plane object; hands the object back when the scene is full.
    ///
    /// # Errors
    /// The object, when `OBJECTS` are already there.
    pub fn push_plane(&mut self, plane: Plane<S>, material: u8) -> Result<(), Object<S>> {
        self.push_object(Object {
            shape: Shape::Plane(plane),
            material,
        })
    }

    /// Adds any object; hands it back when the scene is full.
    ///
    /// # Errors
    /// The object, when `OBJECTS` are already there.
    pub fn push_object(&mut self, object: Object<S>) -> Result<(), Object<S>> {
        self.objects.push(object)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I32F32};

    /// What the README states (update both together): without the `textures` feature,
    /// and what its room for textures and projectors adds.
    const SIZE_I16F16: usize = 3384;
    const SIZE_I32F32: usize = 6720;
    const TEXTURES_I16F16: usize = 384;
    const TEXTURES_I32F32: usize = 512;

    /// The RAM a scene takes, as the README states it (update both together). The host
    /// tests always build the `textures` feature: the size without it is the size less
    /// the two lists' room.
    #[test]
    fn scene_sizes_are_as_documented() {
        fn room<S>() -> usize {
            core::mem::size_of::<Vec<Ppm<'static>, MAX_TEXTURES>>()
                + core::mem::size_of::<Vec<Slide<S>, MAX_PROJECTORS>>()
                - 2 * core::mem::size_of::<Vec<u8, 0>>()
        }
        let (a, b) = (
            core::mem::size_of::<Scene<I16F16>>(),
            core::mem::size_of::<Scene<I32F32>>(),
        );
        std::println!(
            "Scene<I16F16>: {a} bytes ({} of it textures), Scene<I32F32>: {b} bytes ({}), Scene<f32>: {} bytes",
            room::<I16F16>(),
            room::<I32F32>(),
            core::mem::size_of::<Scene<f32>>()
        );
        assert_eq!(a - room::<I16F16>(), SIZE_I16F16);
        assert_eq!(b - room::<I32F32>(), SIZE_I32F32);
        if cfg!(feature = "textures") {
            assert_eq!(room::<I16F16>(), TEXTURES_I16F16);
            assert_eq!(room::<I32F32>(), TEXTURES_I32F32);
        }
    }
}
