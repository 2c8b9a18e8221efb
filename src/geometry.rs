//! Rays, hits and the plane intersection of the course notes (`plane_hits`).
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

use crate::{Scalar, Vec3};

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
}

/// Why a plane cannot be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlaneError {
    /// The normal is zero (or too short for the format to give it a direction).
    ZeroNormal,
    /// `N·point` does not fit the number format.
    OffsetOutOfRange,
}

/// An infinite plane `N·x = D'` with a unit normal.
///
/// ```
/// use fixray::{I16F16, Plane, Ray, RayKind, Scalar, Vec3};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// // The numeric example of the course notes.
/// let plane = Plane::new(v(0.0, 0.0, 1.0), v(0.0, 0.0, -7.0)).unwrap();
/// let ray = Ray { base: v(4.0, 3.0, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Primary };
/// let hit = plane.intersect(&ray, I16F16::DEFAULT_EPSILON).unwrap();
/// assert_eq!(hit.t, 12);
/// assert_eq!(hit.point, v(4.0, 3.0, -7.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane<S> {
    normal: Vec3<S>,
    offset: S,
}

impl<S: Scalar> Plane<S> {
    /// The plane through `point` with normal `normal` (any non-zero length).
    ///
    /// # Errors
    /// [`PlaneError::ZeroNormal`] for a zero normal, [`PlaneError::OffsetOutOfRange`] when
    /// `N·point` does not fit the format.
    pub fn new(normal: Vec3<S>, point: Vec3<S>) -> Result<Self, PlaneError> {
        let normal = normal.unit().ok_or(PlaneError::ZeroNormal)?;
        let offset = normal.dot(point).ok_or(PlaneError::OffsetOutOfRange)?;
        Ok(Self { normal, offset })
    }

    /// The unit normal `N`.
    pub fn normal(&self) -> Vec3<S> {
        self.normal
    }

    /// `D' = N·point`, precomputed.
    pub fn offset(&self) -> S {
        self.offset
    }

    /// Intersects a ray with the plane, as in the notes' `plane_hits()`; see the module
    /// documentation for the steps and the miss reasons.
    ///
    /// # Errors
    /// The [`Miss`] reason when the ray does not hit.
    #[inline]
    pub fn intersect(&self, ray: &Ray<S>, epsilon: S) -> Result<Hit<S>, Miss> {
        let n_dot_d = self.normal.dot(ray.dir).ok_or(Miss::OutOfRange)?;
        if n_dot_d.abs() < epsilon {
            return Err(Miss::Parallel);
        }
        // D' − N·b in one wide step: N·b alone may exceed the range when t does not.
        let t = S::sub_dot3(self.offset, self.normal.to_array(), ray.base.to_array())
            .and_then(|num| num.checked_div(n_dot_d))
            .ok_or(Miss::OutOfRange)?;
        if t < S::ZERO {
            return Err(Miss::Behind);
        }
        let point = ray
            .dir
            .scale(t)
            .and_then(|td| ray.base.sum(td))
            .ok_or(Miss::OutOfRange)?;
        if ray.kind == RayKind::Primary && point.z > S::ZERO {
            return Err(Miss::InFrontOfScreen);
        }
        Ok(Hit { t, point })
    }
}

/// Units of [`Scalar::ulp`] in the hit-point residual bound ([`Plane::residual_bound`]):
/// the constant part. For fixed formats the rounding terms are: the wide `D' − N·b`
/// (½), the division (1 × |N·d| ≤ 1), the hit point's components (√3 in total), and the
/// rounding of `N·d` (½ per unit of t: the `9t/16` part, ½ × 1/(1 − ½/8) for an epsilon
/// of at least 8 DELTAs), about 3.3 in all; floats round their three-term dot products
/// more often, so 8 covers both with margin. `tests/properties.rs` measures the largest
/// residual against this bound in every format.
pub const RESIDUAL_ULPS: i32 = 8;

/// Units of [`Scalar::ulp`] that [`Plane::spawn`] adds beyond the residual bound, for the
/// rounding of the offset base itself (√3 for its components) and of its re-evaluation
/// (½), with margin.
pub const SPAWN_MARGIN_ULPS: i32 = 4;

impl<S: Scalar> Plane<S> {
    /// A bound on how far a hit point computed by [`Plane::intersect`] lies off the plane,
    /// `|N·p − D'|` with the plane's own stored `N` and `D'`:
    /// `(9t/16 + RESIDUAL_ULPS) × ulp(m)`, `m = max(1, t, ‖b‖∞, ‖p‖∞, |D'|)`, for an epsilon
    /// of at least 8 DELTAs (the defaults are 16).
    ///
    /// `None` when the bound itself does not fit the format.
    pub fn residual_bound(&self, ray: &Ray<S>, hit: &Hit<S>) -> Option<S> {
        let m = S::ONE
            .max(hit.t)
            .max(ray.base.max_abs())
            .max(hit.point.max_abs())
            .max(self.offset.abs());
        hit.t
            .mul_ratio(9, 16)?
            .checked_add(S::from_i32(RESIDUAL_ULPS)?)?
            .checked_mul(m.ulp())
    }

    /// A secondary ray leaving a hit on this plane in direction `dir`: its base is the hit
    /// point moved along the normal, to the side `dir` points to, by the residual bound
    /// plus [`SPAWN_MARGIN_ULPS`], so that it can never hit this plane again (pbrt's
    /// offset by a computed error bound, not a magic number). A `dir` parallel to the
    /// plane keeps the hit point (such a ray cannot meet the plane).
    ///
    /// `None` when the offset base does not fit the format.
    pub fn spawn(&self, ray: &Ray<S>, hit: &Hit<S>, dir: Vec3<S>) -> Option<Ray<S>> {
        let side = self.normal.dot(dir)?;
        let base = if side == S::ZERO {
            hit.point
        } else {
            let m = S::ONE
                .max(hit.t)
                .max(ray.base.max_abs())
                .max(hit.point.max_abs())
                .max(self.offset.abs());
            let margin = S::from_i32(SPAWN_MARGIN_ULPS)?.checked_mul(m.ulp())?;
            let mut off = self.residual_bound(ray, hit)?.checked_add(margin)?;
            if side < S::ZERO {
                off = off.checked_neg()?;
            }
            hit.point.sum(self.normal.scale(off)?)?
        };
        Some(Ray {
            base,
            dir,
            kind: RayKind::Secondary,
        })
    }
}

/// A shape of the scene. Shapes dispatch through this enum (no `dyn`); the renderer draws
/// planes today, the remaining shapes of the scene format come with the effects work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape<S> {
    /// An infinite plane.
    Plane(Plane<S>),
}

impl<S: Scalar> Shape<S> {
    /// Intersects a ray with the shape.
    ///
    /// # Errors
    /// The [`Miss`] reason when the ray does not hit.
    #[inline]
    pub fn intersect(&self, ray: &Ray<S>, epsilon: S) -> Result<Hit<S>, Miss> {
        match self {
            Shape::Plane(p) => p.intersect(ray, epsilon),
        }
    }

    /// The unit surface normal at a hit point (before facing it towards the ray).
    #[inline]
    pub fn normal_at(&self, _point: Vec3<S>) -> Vec3<S> {
        match self {
            Shape::Plane(p) => p.normal(),
        }
    }
}
