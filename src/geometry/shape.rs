//! [`Shape`]: the shapes of a scene, dispatched through an enum (no `dyn`).

use super::plane::{crossing_of_sides, crossing_point};
use super::{Hit, Miss, Plane, PlaneFrame, Ray, Revsurf, Slide, Sphere, Triangle, Vec3};
use crate::Scalar;

/// A shape of the scene. Shapes dispatch through this enum (no `dyn`).
///
/// Without the cargo feature `spheres` the sphere code is not built in: a
/// [`Shape::Sphere`] (which the parser then refuses, but code can still build one) is
/// never hit ([`Miss::NotBuiltIn`]).
///
/// ```
/// use fixray::geometry::{Plane, Ray, RayKind, Shape, Sphere, Vec3};
/// use fixray::{Scalar, I16F16};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let shapes = [
///     Shape::Plane(Plane::new(v(0.0, 0.0, 1.0), v(0.0, 0.0, -20.0)).unwrap()),
///     Shape::Sphere(Sphere::new(v(0.0, 0.0, -10.0), I16F16::ONE).unwrap()),
/// ];
/// let ray = Ray { base: v(0.0, 0.0, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Primary };
/// let nearest = shapes
///     .iter()
///     .filter_map(|s| s.intersect(&ray, I16F16::DEFAULT_EPSILON).ok())
///     .map(|hit| hit.t)
///     .min();
/// assert_eq!(nearest, Some(I16F16::from_num(14))); // the sphere, in front of the wall
/// assert!(shapes[0].plane().is_some() && shapes[1].plane().is_none());
/// ```
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
        /// How the tiles are laid out.
        tiling: super::Tiling,
    },
    /// A finite rectangle of a plane.
    Finite(PlaneFrame<S>),
    /// A finite rectangle with a texture on it (the course's `texplane`): its material's
    /// ambient and diffuse colours are multiplied by the texel.
    Textured(Slide<S>),
    /// A triangle.
    Triangle(Triangle<S>),
    /// A surface of revolution (the course's `revsurf`).
    Revsurf(Revsurf<S>),
}

/// Whether the sphere code is built in (cargo feature `spheres`).
pub(crate) const SPHERES: bool = cfg!(feature = "spheres");

impl<S: Scalar> Shape<S> {
    /// The plane of a plane-like shape (infinite, tiled, finite or a triangle); `None`
    /// for a sphere. The one place that knows which shapes are planes.
    #[inline]
    pub fn plane(&self) -> Option<&Plane<S>> {
        match self {
            Shape::Plane(p) => Some(p),
            Shape::Tiled { frame, .. } | Shape::Finite(frame) => Some(frame.plane()),
            Shape::Textured(slide) => Some(slide.frame.plane()),
            Shape::Triangle(t) => Some(t.plane()),
            Shape::Sphere(_) | Shape::Revsurf(_) => None,
        }
    }

    /// Whether a point of a plane-like shape's plane lies within its bounds: everywhere
    /// for infinite and tiled planes, inside the rectangle or the triangle for finite
    /// planes and triangles (what a kernel that found the plane's hit checks). `false`
    /// for a sphere.
    #[inline]
    pub fn bounds_contain(&self, point: Vec3<S>) -> bool {
        match self {
            Shape::Plane(_) | Shape::Tiled { .. } => true,
            Shape::Finite(frame) => frame.contains(point),
            Shape::Textured(slide) => slide.frame.contains(point),
            Shape::Triangle(t) => t.contains(point),
            Shape::Sphere(_) | Shape::Revsurf(_) => false,
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
            Shape::Finite(frame) | Shape::Textured(Slide { frame, .. }) => {
                let hit = frame.plane().intersect(ray, epsilon)?;
                if frame.contains(hit.point) {
                    Ok(hit)
                } else {
                    Err(Miss::OutsideBounds)
                }
            }
            Shape::Triangle(t) => t.intersect(ray, epsilon),
            Shape::Revsurf(r) => r.intersect(ray),
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
            Shape::Sphere(_)
            | Shape::Finite(_)
            | Shape::Textured(_)
            | Shape::Triangle(_)
            | Shape::Revsurf(_) => self.intersect(ray, epsilon).is_ok_and(|hit| hit.t < dist),
        }
    }

    /// Whether the shape meets the segment from `from` to `from + l` strictly between
    /// its ends (a shadow segment from a hit point to a light, `ll = l·l`; `tol` bounds
    /// how far `from` lies off the surface it is on, as the [`Shape::spawn`] offset).
    /// Planes and spheres decide from signs and exact product comparisons
    /// ([`Plane::crossing`], [`Sphere::meets_segment`]); finite planes and triangles
    /// divide once, for a plane they cross, to check the crossing point's bounds. The
    /// shadow test of the crate's rules: it agrees with [`Shape::occludes`] of the ray
    /// spawned off the surface towards the light, except within `tol` of the surface
    /// (where the spawned ray's offset decides) and at the rounding of the light's
    /// distance.
    #[inline]
    pub fn meets_segment(&self, from: Vec3<S>, l: Vec3<S>, ll: S, tol: S, epsilon: S) -> bool {
        self.meets_segment_with(None, from, l, ll, tol, epsilon)
    }

    /// [`Shape::meets_segment`] with, for a plane-like shape, the ends' sides
    /// `(D' − N·from, D' − N·to)` already known (`sides`: a kernel's per-frame and
    /// per-pixel terms), so that the test needs no product.
    #[inline]
    pub(crate) fn meets_segment_with(
        &self,
        sides: Option<(S, S)>,
        from: Vec3<S>,
        l: Vec3<S>,
        ll: S,
        tol: S,
        epsilon: S,
    ) -> bool {
        let crossing = |p: &Plane<S>| match sides {
            Some((a0, a1)) => crossing_of_sides(a0, a1, ll, tol, epsilon),
            None => p.crossing(from, l, ll, tol, epsilon),
        };
        match self {
            Shape::Plane(p) => crossing(p).is_some(),
            Shape::Tiled { frame, .. } => crossing(frame.plane()).is_some(),
            Shape::Finite(_) | Shape::Textured(_) | Shape::Triangle(_) => self
                .plane()
                .and_then(crossing)
                .and_then(|c| crossing_point(from, l, c))
                .is_some_and(|x| self.bounds_contain(x)),
            Shape::Sphere(s) if SPHERES => s.meets_segment(from, l, ll, tol).unwrap_or_else(|| {
                // Far from `from` (a quantity out of range): the ray's own test.
                unit_ray(from, l).is_some_and(|(r, dist)| self.occludes(&r, epsilon, dist))
            }),
            Shape::Sphere(_) => false,
            // No segment form: the unit ray's own test.
            Shape::Revsurf(_) => {
                unit_ray(from, l).is_some_and(|(r, dist)| self.occludes(&r, epsilon, dist))
            }
        }
    }

    /// Whether a point lies on the surface within `tol` (world units): on the plane of a
    /// plane-like shape (its bounds aside), or on a sphere's surface.
    pub fn holds(&self, point: Vec3<S>, tol: S) -> bool {
        match self {
            Shape::Sphere(s) => {
                // |p − c|² − r² = (|p − c| − r)(|p − c| + r): within tol·(2r + tol).
                let Some(pc) = point.diff(s.center()) else {
                    return false;
                };
                let excess = S::sub_dot3(s.radius_sq(), pc.to_array(), pc.to_array());
                let band = s
                    .radius()
                    .checked_add(s.radius())
                    .and_then(|d| d.checked_add(tol))
                    .and_then(|d| d.checked_mul(tol));
                matches!((excess, band), (Some(e), Some(b)) if e.abs() <= b)
            }
            // Not resolved for surfaces of revolution: a light on one is not treated
            // as the tie (`docs/numerics.md`, "Lights on surfaces").
            Shape::Revsurf(_) => false,
            Shape::Plane(_)
            | Shape::Tiled { .. }
            | Shape::Finite(_)
            | Shape::Textured(_)
            | Shape::Triangle(_) => self.plane().is_some_and(|p| {
                S::sub_dot3(p.offset(), p.normal().to_array(), point.to_array())
                    .is_some_and(|d| d.abs() <= tol)
            }),
        }
    }

    /// For a shape that blocks the shadow ray `ray`: whether that is only the tie of a
    /// light lying on it (within `tol`), which it then does not shadow
    /// ([`crate::shade::RuleSet::shadows`]): a plane never shadows it (the segment to a point
    /// on a plane meets the plane only at that point), a sphere only when the ray
    /// leaves the sphere at the light (it went through the sphere first). Asked only of
    /// blocking shapes: it costs a dot product.
    #[inline]
    pub fn spares_light(&self, ray: &Ray<S>, light: Vec3<S>, tol: S) -> bool {
        if !self.holds(light, tol) {
            return false;
        }
        match self {
            // Spared unless the ray leaves the sphere at the light.
            Shape::Sphere(s) if SPHERES => !light
                .diff(s.center())
                .and_then(|out| out.dot(ray.dir))
                .is_some_and(|d| d > S::ZERO),
            Shape::Sphere(_)
            | Shape::Plane(_)
            | Shape::Tiled { .. }
            | Shape::Finite(_)
            | Shape::Textured(_)
            | Shape::Triangle(_)
            | Shape::Revsurf(_) => true,
        }
    }

    /// The unit surface normal at a hit point (before facing it towards the ray).
    #[inline]
    pub fn normal_at(&self, point: Vec3<S>) -> Option<Vec3<S>> {
        match self {
            Shape::Sphere(s) if SPHERES => s.normal_at(point),
            Shape::Sphere(_) => None,
            Shape::Revsurf(r) => r.normal_at(point),
            Shape::Plane(_)
            | Shape::Tiled { .. }
            | Shape::Finite(_)
            | Shape::Textured(_)
            | Shape::Triangle(_) => self.plane().map(Plane::normal),
        }
    }

    /// A secondary ray leaving `hit` in direction `dir`, based off the surface by its
    /// computed error bound so that it cannot meet the surface it leaves
    /// ([`Plane::spawn`], [`Sphere::spawn`]).
    pub fn spawn(&self, ray: &Ray<S>, hit: &Hit<S>, dir: Vec3<S>) -> Option<Ray<S>> {
        match self {
            Shape::Sphere(s) if SPHERES => s.spawn(ray, hit, dir),
            Shape::Sphere(_) => None,
            Shape::Revsurf(r) => r.spawn(ray, hit, dir),
            Shape::Plane(_)
            | Shape::Tiled { .. }
            | Shape::Finite(_)
            | Shape::Textured(_)
            | Shape::Triangle(_) => self.plane()?.spawn(ray, hit, dir),
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

/// The secondary ray from `from` along `l` with a unit direction, and the segment's
/// length (what the segment tests fall back to when a quantity does not fit the format).
pub(crate) fn unit_ray<S: Scalar>(from: Vec3<S>, l: Vec3<S>) -> Option<(Ray<S>, S)> {
    let n = l.normalize()?;
    let ray = Ray {
        base: from,
        dir: n.unit,
        kind: super::RayKind::Secondary,
    };
    Some((ray, n.length()?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, RayKind};

    /// The `spheres` feature gates the sphere intersection, not only the parser: without
    /// it a firmware carries none, and a sphere built in code is never hit.
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
