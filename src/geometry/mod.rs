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

mod frame;
mod plane;
mod revsurf;
mod shape;
mod spawn;
mod sphere;
mod triangle;
mod vec3;

pub(crate) use frame::RowTiles;
pub use frame::{FrameError, PlaneFrame, Slide, TexMode, Tiling};
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
pub(crate) use sphere::{RowCone, ShadowCone};
pub use sphere::{Sphere, SphereError};
pub use triangle::{EDGE_SLACK_ULPS, Triangle, TriangleError};
pub use vec3::{Normalized, Vec3};

use crate::Scalar;

/// What a ray is for: primary rays (eye through pixel) reject hits in front of the screen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RayKind {
    /// From the eye through a pixel: hits with `z > 0` are rejected.
    Primary,
    /// Any other ray (towards a light, ...): every hit with `t >= 0` counts.
    Secondary,
}

/// A ray: `base + t·dir` for `t >= 0`. `dir` is expected to be a unit vector (as made by
/// [`Vec3::unit`]); the precision epsilon is defined for unit directions.
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
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit<S> {
    /// Distance along the ray (in units of `dir`, i.e. world units for a unit `dir`).
    pub t: S,
    /// `base + t·dir`.
    pub point: Vec3<S>,
}

/// Why a ray missed.
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
