//! [`Plan`]: which stages of shading and which kernels a scene needs.

use super::{Material, Rules, Scene, SceneView};
use crate::{Scalar, Shape};

/// Which stages of shading and which kernels a scene needs ([`Scene::plan`], computed
/// from the scene whenever it is asked for, so it cannot go stale). The renderer picks a
/// shading loop compiled for the stages planned and nothing else: a scene without lights
/// never evaluates lighting, one without specular materials never computes a half
/// vector, and so on. The shapes (`tiles`, `finite_planes`, `spheres`) decide which
/// primary-ray kernels apply.
///
/// ```
/// use fixray::{Scene, I16F16};
///
/// let planes = Scene::<I16F16>::parse(include_str!("../../scenes/planes.scene"))?;
/// let plan = planes.plan();
/// assert!(plan.planes_only && !plan.lighting && !plan.shadows);
/// let lit = Scene::<I16F16>::parse(include_str!("../../scenes/default.scene"))?.plan();
/// assert!(lit.lighting && lit.shadows && !lit.spheres);
/// # Ok::<(), fixray::SceneError>(())
/// ```
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
    /// Some material is translucent (the course's `transparency`).
    pub transparency: bool,
    /// Some object is a tiled plane.
    pub tiles: bool,
    /// Some object is a finite plane.
    pub finite_planes: bool,
    /// Some object is a sphere.
    pub spheres: bool,
    /// Some object is a triangle.
    pub triangles: bool,
    /// Some object is a textured plane.
    pub textures: bool,
    /// Some object is a surface of revolution.
    pub revsurfs: bool,
    /// Every object is an infinite plane (or there is none): what the pure-geometry
    /// kernel draws.
    pub planes_only: bool,
    /// Some light is a projector.
    pub projectors: bool,
    /// Some light lies on some surface (within its tolerance): the ties of shadow rays
    /// and of a surface's own plane are resolved for it (`docs/numerics.md`, "Lights on
    /// surfaces"); without such a light those checks are not run.
    pub lights_on_surfaces: bool,
}

impl<S: Scalar, const O: usize, const M: usize, const L: usize> Scene<S, O, M, L> {
    /// What the scene needs of the renderer, worked out from its contents now (a few
    /// comparisons per object; the renderer asks once per frame or line).
    pub fn plan(&self) -> Plan {
        self.view().plan()
    }
}

impl<S: Scalar> SceneView<'_, S> {
    /// What the scene needs of the renderer ([`Scene::plan`]).
    pub fn plan(&self) -> Plan {
        let material = |i: u8| self.materials.get(usize::from(i));
        let lighting = !self.lights.is_empty();
        // Each shape's kind sets its flag: the one exhaustive match of the plan (a new
        // shape is a compile error here until it says what it needs).
        let mut plan = Plan {
            lighting,
            planes_only: true,
            ..Plan::default()
        };
        for object in self.objects {
            let flag = match object.shape {
                Shape::Plane(_) => continue,
                Shape::Sphere(_) => &mut plan.spheres,
                Shape::Tiled { .. } => &mut plan.tiles,
                Shape::Finite(_) => &mut plan.finite_planes,
                Shape::Textured(_) => &mut plan.textures,
                Shape::Triangle(_) => &mut plan.triangles,
                Shape::Revsurf(_) => &mut plan.revsurfs,
            };
            *flag = true;
            plan.planes_only = false;
        }
        let used = |f: &dyn Fn(&Material<S>) -> bool| {
            self.objects.iter().any(|o| {
                let alt = if let Shape::Tiled { alt, .. } = o.shape {
                    material(alt).is_some_and(f)
                } else {
                    false
                };
                material(o.material).is_some_and(f) || alt
            })
        };
        // Under the course rules `specular` is the mirror weight, and the glint needs a
        // `shininess` too (`COURSE-RULES.md` §7, §8).
        let course = self.rules() == Rules::Course;
        let (specular, reflection) = if course {
            (
                lighting && used(&|m| m.specular != S::ZERO && m.shininess > S::ZERO),
                used(&|m| m.specular != S::ZERO),
            )
        } else {
            (
                lighting && used(&|m| m.specular > S::ZERO),
                used(&|m| m.reflective > S::ZERO),
            )
        };
        Plan {
            shadows: lighting && (self.objects.len() > 1 || plan.spheres),
            specular,
            spotlights: self.lights.iter().any(|l| l.cone().is_some()),
            reflection,
            transparency: used(&|m| m.transparency > S::ZERO),
            projectors: self
                .lights
                .iter()
                .any(|l| matches!(l.beam, crate::Beam::Projector(_))),
            lights_on_surfaces: self.lights.iter().any(|l| {
                let tol = super::light_tolerance(self.epsilon, l.location, self.camera.viewpoint);
                self.objects.iter().any(|o| o.shape.holds(l.location, tol))
            }),
            ..plan
        }
    }
}
