//! The scene: camera, materials, lights, objects, background and precision epsilon, in
//! number format `S`, with capacities fixed in the types (no allocator).
//!
//! Scenes are read from the course's keyword-block text format with [`Scene::parse`]; see
//! [`crate::parse`] for the errors. Displayed colours (ambient, background) are stored in
//! *channel units*: a scene colour `c` is kept as `255 c`, computed exactly from the
//! decimal text, so that the pixel value is `round(clamp(colour, 0, 255))` and a colour
//! such as 0.7 (178.5 channel units) is exact in every fixed format instead of rounding to
//! a neighbouring pixel value. A colour whose 255-fold does not fit the format (above
//! 128.5 in I16F16) is stored as the format's maximum, which displays the same (255).
//! Diffuse reflectances and emissivities stay plain reals.

use heapless::Vec;

use crate::{Plane, Ray, RayKind, Scalar, Shape, Vec3};

/// Maximum number of materials in a scene.
pub const MAX_MATERIALS: usize = 16;
/// Maximum number of lights (point lights and spotlights together).
pub const MAX_LIGHTS: usize = 8;
/// Maximum number of objects (planes, spheres, tiled and finite planes together).
pub const MAX_OBJECTS: usize = 32;
/// Largest `pixeldim` in either direction, as the scene format states.
pub const MAX_PIXELDIM: u16 = 4096;

/// An RGB colour in channel units (0 ..= 255 displays; larger values clamp).
pub type Color<S> = [S; 3];

/// The camera: image size, screen window and eye.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera<S> {
    /// Image width in pixels, `1..=4096`.
    pub width: u16,
    /// Image height in pixels, `1..=4096`.
    pub height: u16,
    /// Width of the screen window `[0, WX]` on the plane z = 0, in world units.
    pub world_width: S,
    /// Height of the screen window `[0, WY]`, in world units.
    pub world_height: S,
    /// The eye, `z > 0`.
    pub viewpoint: Vec3<S>,
}

impl<S: Scalar> Camera<S> {
    /// The primary ray through the centre of pixel (`column`, `row`), row 0 at the top:
    /// base = viewpoint, direction = unit(screen point − viewpoint) with the screen point
    /// `(WX (i + ½) / W, WY (1 − (j + ½) / H), 0)`.
    ///
    /// `None` when the direction cannot be formed in the format (the pixel then shows the
    /// background); never for a scene that [`Scene::parse`] accepted with an eye within
    /// the format's range of the screen.
    pub fn primary_ray(&self, column: u16, row: u16) -> Option<Ray<S>> {
        let y = self.screen_y(row)?;
        self.primary_ray_at(column, y)
    }

    /// The screen y coordinate of a pixel row (constant along a scanline).
    pub fn screen_y(&self, row: u16) -> Option<S> {
        let h = i32::from(self.height);
        let j = i32::from(row);
        self.world_height.mul_ratio(2 * (h - j) - 1, 2 * h)
    }

    /// The primary ray through pixel `column` of the scanline whose screen y is `y`.
    pub fn primary_ray_at(&self, column: u16, y: S) -> Option<Ray<S>> {
        let w = i32::from(self.width);
        let x = self
            .world_width
            .mul_ratio(2 * i32::from(column) + 1, 2 * w)?;
        let dir = Vec3::new(x, y, S::ZERO).diff(self.viewpoint)?.unit()?;
        Some(Ray {
            base: self.viewpoint,
            dir,
            kind: RayKind::Primary,
        })
    }
}

/// A surface material.
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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone<S> {
    /// Unit vector from the light towards the point it is aimed at.
    pub axis: Vec3<S>,
    /// cos θ.
    pub cos_theta: S,
}

/// A point light, or a spotlight when it has a cone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light<S> {
    /// Position.
    pub location: Vec3<S>,
    /// Emissivity per channel (plain reals, not channel units).
    pub emissivity: Color<S>,
    /// The spotlight's cone; `None` for a point light.
    pub cone: Option<Cone<S>>,
}

/// Which stages of shading a scene needs, worked out once when the scene is built
/// ([`Scene::plan`]). The renderer picks a shading loop compiled for the stages planned
/// and nothing else: a scene without lights never evaluates lighting, one without
/// specular materials never computes a half vector, and so on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Plan {
    /// Any light at all (diffuse term).
    pub lighting: bool,
    /// Shadow rays: lights and something that can stand between a point and a light
    /// (two objects, or any sphere).
    pub shadows: bool,
    /// Some material has a specular glint (and there are lights).
    pub specular: bool,
    /// Some light is a spotlight.
    pub spotlights: bool,
    /// Some material is reflective.
    pub reflection: bool,
    /// Some object is a tiled plane.
    pub tiles: bool,
    /// Some object is a finite plane.
    pub finite_planes: bool,
    /// Some object is a sphere.
    pub spheres: bool,
}

/// A shape with its material.
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
#[derive(Debug, Clone, PartialEq)]
pub struct Scene<S> {
    /// The camera.
    pub camera: Camera<S>,
    /// Materials, indexed by [`Object::material`].
    pub materials: Vec<Material<S>, MAX_MATERIALS>,
    /// Point lights.
    pub lights: Vec<Light<S>, MAX_LIGHTS>,
    /// Objects.
    pub objects: Vec<Object<S>, MAX_OBJECTS>,
    /// Colour where no object is hit.
    pub background: Color<S>,
    /// The precision epsilon of every intersection test in this scene: the scene's
    /// `precision`, or [`Scalar::DEFAULT_EPSILON`].
    pub epsilon: S,
    /// The stages this scene needs; kept up to date by [`Scene::parse`] and the `push_`
    /// methods. After changing the public vectors directly, call [`Scene::replan`].
    pub plan: Plan,
    /// How a pure-geometry plane scene is drawn ([`crate::flat`]): per pixel (the default)
    /// or in spans. A drawing option, not part of the scene text: [`Scene::clear`] and
    /// [`Scene::read`] keep it.
    pub mode: crate::PlaneMode,
}

impl<S: Scalar> Scene<S> {
    /// A scene with a camera and nothing in it: black background, default epsilon.
    pub fn new(camera: Camera<S>) -> Self {
        Self {
            camera,
            materials: Vec::new(),
            lights: Vec::new(),
            objects: Vec::new(),
            background: [S::ZERO; 3],
            epsilon: S::DEFAULT_EPSILON,
            plan: Plan::default(),
            mode: crate::PlaneMode::PerPixel,
        }
    }

    /// Works out the [`Plan`] from the scene's contents (called by the parser and the
    /// `push_` methods).
    pub fn replan(&mut self) {
        let material = |i: u8| self.materials.get(usize::from(i));
        let lighting = !self.lights.is_empty();
        let spheres = self
            .objects
            .iter()
            .any(|o| matches!(o.shape, Shape::Sphere(_)));
        let used = |f: &dyn Fn(&Material<S>) -> bool| {
            self.objects.iter().any(|o| {
                let alt = match o.shape {
                    Shape::Tiled { alt, .. } => material(alt).is_some_and(f),
                    _ => false,
                };
                material(o.material).is_some_and(f) || alt
            })
        };
        self.plan = Plan {
            lighting,
            shadows: lighting && (self.objects.len() > 1 || spheres),
            specular: lighting && used(&|m| m.specular > S::ZERO),
            spotlights: self.lights.iter().any(|l| l.cone.is_some()),
            reflection: used(&|m| m.reflective > S::ZERO),
            tiles: self
                .objects
                .iter()
                .any(|o| matches!(o.shape, Shape::Tiled { .. })),
            finite_planes: self
                .objects
                .iter()
                .any(|o| matches!(o.shape, Shape::Finite(_))),
            spheres,
        };
    }

    /// Adds a plane object; hands the object back when the scene is full.
    ///
    /// # Errors
    /// The object, when [`MAX_OBJECTS`] are already there.
    pub fn push_plane(&mut self, plane: Plane<S>, material: u8) -> Result<(), Object<S>> {
        self.push_object(Object {
            shape: Shape::Plane(plane),
            material,
        })
    }

    /// Adds any object; hands it back when the scene is full.
    ///
    /// # Errors
    /// The object, when [`MAX_OBJECTS`] are already there.
    pub fn push_object(&mut self, object: Object<S>) -> Result<(), Object<S>> {
        self.objects.push(object)?;
        self.replan();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I32F32};

    /// The RAM a scene takes, as the README states it (update both together).
    #[test]
    fn scene_sizes_are_as_documented() {
        std::println!(
            "Scene<I16F16>: {} bytes, Scene<I32F32>: {} bytes, Scene<f32>: {} bytes",
            core::mem::size_of::<Scene<I16F16>>(),
            core::mem::size_of::<Scene<I32F32>>(),
            core::mem::size_of::<Scene<f32>>()
        );
        assert_eq!(core::mem::size_of::<Scene<I16F16>>(), 3184);
        assert_eq!(core::mem::size_of::<Scene<I32F32>>(), 6328);
    }
}
