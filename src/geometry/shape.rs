//! [`Shape`]: the shapes of a scene, dispatched through an enum (no `dyn`).

use super::{Hit, Miss, Plane, PlaneFrame, Ray, Sphere, Vec3};
use crate::Scalar;

/// A shape of the scene. Shapes dispatch through this enum (no `dyn`).
///
/// Without the cargo feature `spheres` the sphere code is not built in: a
/// [`Shape::Sphere`] (which the parser then refuses, but code can still build one) is
/// never hit ([`Miss::NotBuiltIn`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape<S> {
    /// An infinite plane.
    Plane(Plane<S>),
    /// A sphere.
    Sphere(Sphere<S>),
    /// An infinite plane tiled in a checkerboard of the object's material and `alt`.
    Tiled {
        /// The plane and its tile coordinates.
        frame: PlaneFrame<S>,
        /// The material of the odd tiles (index into the scene's materials).
        alt: u8,
    },
    /// A finite rectangle of a plane.
    Finite(PlaneFrame<S>),
}

/// Whether the sphere code is built in (cargo feature `spheres`).
const SPHERES: bool = cfg!(feature = "spheres");

impl<S: Scalar> Shape<S> {
    /// The plane of a plane-like shape (infinite, tiled or finite); `None` for a sphere.
    /// The one place that knows which shapes are planes.
    #[inline]
    pub fn plane(&self) -> Option<&Plane<S>> {
        match self {
            Shape::Plane(p) => Some(p),
            Shape::Tiled { frame, .. } | Shape::Finite(frame) => Some(frame.plane()),
            Shape::Sphere(_) => None,
        }
    }

    /// Intersects a ray with the shape (`epsilon` is the plane tests' precision epsilon).
    ///
    /// # Errors
    /// The [`Miss`] reason when the ray does not hit.
    #[inline]
    pub fn intersect(&self, ray: &Ray<S>, epsilon: S) -> Result<Hit<S>, Miss> {
        match self {
            Shape::Plane(p) => p.intersect(ray, epsilon),
            Shape::Sphere(s) if SPHERES => s.intersect(ray),
            Shape::Sphere(_) => Err(Miss::NotBuiltIn),
            Shape::Tiled { frame, .. } => frame.plane().intersect(ray, epsilon),
            Shape::Finite(frame) => {
                let hit = frame.plane().intersect(ray, epsilon)?;
                if frame.contains(hit.point) {
                    Ok(hit)
                } else {
                    Err(Miss::OutsideBounds)
                }
            }
        }
    }

    /// Whether the shape meets the ray at some `0 <= t < dist` (shadow rays). Infinite and
    /// tiled planes use the division-free [`Plane::occludes`]; spheres and finite planes
    /// (whose bounds need the hit point) intersect in full.
    #[inline]
    pub fn occludes(&self, ray: &Ray<S>, epsilon: S, dist: S) -> bool {
        match self {
            Shape::Plane(p) => p.occludes(ray, epsilon, dist),
            Shape::Tiled { frame, .. } => frame.plane().occludes(ray, epsilon, dist),
            Shape::Sphere(_) | Shape::Finite(_) => {
                self.intersect(ray, epsilon).is_ok_and(|hit| hit.t < dist)
            }
        }
    }

    /// The unit surface normal at a hit point (before facing it towards the ray).
    #[inline]
    pub fn normal_at(&self, point: Vec3<S>) -> Option<Vec3<S>> {
        match self {
            Shape::Sphere(s) if SPHERES => s.normal_at(point),
            Shape::Sphere(_) => None,
            _ => self.plane().map(Plane::normal),
        }
    }

    /// A secondary ray leaving `hit` in direction `dir`, based off the surface by its
    /// computed error bound so that it cannot meet the surface it leaves
    /// ([`Plane::spawn`], [`Sphere::spawn`]).
    pub fn spawn(&self, ray: &Ray<S>, hit: &Hit<S>, dir: Vec3<S>) -> Option<Ray<S>> {
        match self {
            Shape::Sphere(s) if SPHERES => s.spawn(ray, hit, dir),
            Shape::Sphere(_) => None,
            _ => self.plane()?.spawn(ray, hit, dir),
        }
    }
}

impl<S: Scalar> Shape<S> {
    /// [`Shape::spawn`] for a ray that started at `base`: the offset needs nothing else of
    /// the incoming ray (its direction may be unnormalised, see `shade::Incoming`).
    #[inline]
    pub(crate) fn spawn_from(&self, base: Vec3<S>, hit: &Hit<S>, dir: Vec3<S>) -> Option<Ray<S>> {
        let from = Ray {
            base,
            dir,
            kind: crate::RayKind::Secondary,
        };
        self.spawn(&from, hit, dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, RayKind};

    /// Regression: the `spheres` feature gated only the parser, so a firmware built
    /// without it still carried (and ran) the sphere intersection for spheres built in
    /// code. Without the feature a sphere is never hit.
    #[test]
    fn spheres_are_hit_exactly_when_built_in() {
        let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
        let sphere = Shape::Sphere(Sphere::new(v(0.0, 0.0, -10.0), I16F16::ONE).unwrap());
        let ray = Ray {
            base: v(0.0, 0.0, 5.0),
            dir: v(0.0, 0.0, -1.0),
            kind: RayKind::Primary,
        };
        let hit = sphere.intersect(&ray, I16F16::DEFAULT_EPSILON);
        if cfg!(feature = "spheres") {
            assert_eq!(hit.map(|h| h.t), Ok(I16F16::from_num(14)));
        } else {
            assert_eq!(hit, Err(Miss::NotBuiltIn));
            assert!(!sphere.occludes(&ray, I16F16::DEFAULT_EPSILON, I16F16::MAX));
        }
        assert!(sphere.plane().is_none());
    }
}
