//! Rays, hits and the shapes: one file per shape (`plane.rs`, `sphere.rs`, `frame.rs` for
//! tiled and finite planes, `triangle.rs`), the [`Shape`] enum they dispatch through (`shape.rs`), and the
//! offsets of secondary rays (`spawn.rs`). This file: rays, hits, misses, and the plane
//! intersection of the course notes (`plane_hits`).
//!
//! # The plane test
//! With `N` the unit normal and `D' = N·P` precomputed when the plane is built, a ray with
//! base `b` and unit direction `d`:
//!
//! 1. misses when `|N·d| < epsilon` (it runs parallel to the plane within the precision
//!    epsilon) — [`Miss::Parallel`];
//! 2. otherwise `t = (D' − N·b) / (N·d)`;
//! 3. misses when `t < 0` (the plane is behind the base) — [`Miss::Behind`];
//! 4. hits at `b + t·d`, unless the ray is a primary ray and the hit has `z > 0`: it lies in
//!    front of the screen — [`Miss::InFrontOfScreen`].
//!
//! # Overflow
//! When `t` or the hit point does not fit the number format, the result is
//! [`Miss::OutOfRange`]: a documented miss, never a wrapped value and never a panic, in
//! debug and in release builds. Such a hit is beyond what the format can address (for
//! I16F16: 32768 world units), so the pixel shows whatever else it sees. `D' − N·b` is
//! computed in one wide step, so a large `N·b` alone (a far eye) does not cause a miss.
//!
//! # Error bound (first order, fixed formats)
//! With δ the format's `DELTA`: `N` and `d` carry ≤ 2δ per component from normalisation
//! and each wide dot product rounds once (≤ ½δ), so `N·d` is off by ≤ 2(‖N‖₁ + ‖d‖₁)δ + ½δ
//! ≤ 7.5δ and `D' − N·b` by ≤ ΔD' + 2‖b‖₁δ + ½δ, where ΔD' is the error of the stored
//! offset. Then
//!
//! `|Δt| ≤ (ΔD' + (2‖b‖₁ + ½)δ + 7.5 t δ) / |N·d| + δ`
//!
//! (the last δ for the division): small for steep rays, large near the epsilon.
//! `tests/precision.rs` checks every pixel of the shipped scenes against it.

mod cone;
mod frame;
mod plane;
mod revsurf;
mod shape;
mod spawn;
mod sphere;
mod triangle;
mod vec3;

pub(crate) use cone::{RowCone, ShadowCone};
pub(crate) use frame::RowTiles;
pub use frame::{PlaneFrame, PlaneFrameError, Slide, TexMode, Tiling};
#[cfg(feature = "course")]
pub(crate) use plane::crossing_point;
pub(crate) use plane::sides_differ;
pub use plane::{Plane, PlaneError};
pub use revsurf::{CONE_BASE_RADIUS, Revsurf, RevsurfError};
pub use shape::Shape;
#[cfg(feature = "course")]
pub(crate) use shape::{SPHERES, unit_ray};
pub use spawn::{RESIDUAL_ULPS, SPAWN_MARGIN_ULPS};
pub(crate) use spawn::{surface_tolerance, surface_tolerance_fits};
pub use sphere::{Sphere, SphereError};
pub use triangle::{EDGE_SLACK_ULPS, Triangle, TriangleError};
pub use vec3::{Normalized, Vec3};

use crate::Scalar;

/// What a ray is for: primary rays (eye through pixel) reject hits in front of the screen.
///
/// ```
/// use fixray::geometry::{Plane, Ray, RayKind, Vec3};
/// use fixray::{Scalar, I16F16};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// // A plane at z = 1, between the screen (z = 0) and the eye.
/// let plane = Plane::new(v(0.0, 0.0, 1.0), v(0.0, 0.0, 1.0)).unwrap();
/// let ray = |kind| Ray { base: v(0.0, 0.0, 5.0), dir: v(0.0, 0.0, -1.0), kind };
/// let eps = I16F16::DEFAULT_EPSILON;
/// assert!(plane.intersect(&ray(RayKind::Primary), eps).is_err()); // in front of the screen
/// assert!(plane.intersect(&ray(RayKind::Secondary), eps).is_ok());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RayKind {
    /// From the eye through a pixel: hits with `z > 0` are rejected.
    Primary,
    /// Any other ray (towards a light, ...): every hit with `t >= 0` counts.
    Secondary,
}

/// A ray: `base + t·dir` for `t >= 0`. `dir` is expected to be a unit vector (as made by
/// [`Vec3::unit`]); the precision epsilon is defined for unit directions.
///
/// ```
/// use fixray::geometry::{Ray, RayKind, Vec3};
/// use fixray::I16F16;
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let ray = Ray { base: v(1.0, 2.0, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Secondary };
/// let hit = ray.hit_at(I16F16::from_num(8)).unwrap(); // base + 8·dir
/// assert_eq!(hit.point, v(1.0, 2.0, -3.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray<S> {
    /// Where the ray starts.
    pub base: Vec3<S>,
    /// Unit direction.
    pub dir: Vec3<S>,
    /// Primary or secondary.
    pub kind: RayKind,
}

impl<S: Scalar> Ray<S> {
    /// The hit at distance `t` (≥ 0): the point `base + t·dir`, `OutOfRange` when it does
    /// not fit, and the primary-ray screen rule (`z > 0` is in front of the screen).
    ///
    /// # Errors
    /// [`Miss::OutOfRange`] or [`Miss::InFrontOfScreen`].
    #[inline]
    pub fn hit_at(&self, t: S) -> Result<Hit<S>, Miss> {
        let point = self
            .dir
            .scale(t)
            .and_then(|td| self.base.sum(td))
            .ok_or(Miss::OutOfRange)?;
        if self.kind == RayKind::Primary && point.z > S::ZERO {
            return Err(Miss::InFrontOfScreen);
        }
        Ok(Hit { t, point })
    }
}

/// An accepted intersection.
///
/// ```
/// use fixray::geometry::{Ray, RayKind, Sphere, Vec3};
/// use fixray::{Scalar, I16F16};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let ball = Sphere::new(v(0.0, 0.0, -10.0), I16F16::ONE).unwrap();
/// let ray = Ray { base: v(0.0, 0.0, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Primary };
/// let hit = ball.intersect(&ray).unwrap();
/// assert_eq!((hit.t, hit.point), (I16F16::from_num(14), v(0.0, 0.0, -9.0)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit<S> {
    /// Distance along the ray (in units of `dir`, i.e. world units for a unit `dir`).
    pub t: S,
    /// `base + t·dir`.
    pub point: Vec3<S>,
}

/// Why a ray missed.
///
/// ```
/// use fixray::geometry::{Miss, Plane, Ray, RayKind, Vec3};
/// use fixray::{Scalar, I16F16};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let floor = Plane::new(v(0.0, 1.0, 0.0), v(0.0, 0.0, 0.0)).unwrap();
/// let ray = |dir| Ray { base: v(0.0, 1.0, 5.0), dir, kind: RayKind::Primary };
/// let eps = I16F16::DEFAULT_EPSILON;
/// assert_eq!(floor.intersect(&ray(v(0.0, 0.0, -1.0)), eps), Err(Miss::Parallel));
/// assert_eq!(floor.intersect(&ray(v(0.0, 0.6, -0.8)), eps), Err(Miss::Behind));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Miss {
    /// `|N·d| < epsilon`: the ray is parallel to the plane within the precision epsilon.
    Parallel,
    /// `t < 0`: the plane is behind the ray's base.
    Behind,
    /// A primary ray's hit with `z > 0` lies in front of the screen.
    InFrontOfScreen,
    /// `t` or the hit point does not fit the number format.
    OutOfRange,
    /// The ray passes a sphere by: the discriminant is negative.
    NoRoot,
    /// The ray meets a finite plane's plane outside its rectangle.
    OutsideBounds,
    /// The shape's code is not built into this program (a sphere without the cargo
    /// feature `spheres`).
    NotBuiltIn,
}
