//! The infinite plane `N·x = D'`: the intersection of the course notes, the division-free
//! shadow test, and the offset of rays that leave it.

use super::spawn::{offset_base, residual};
use super::{Hit, Miss, Ray, RayKind, Vec3};
use crate::Scalar;

/// Why a plane cannot be built.
///
/// ```
/// use fixray::geometry::{Plane, PlaneError, Vec3};
/// use fixray::I16F16;
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// assert_eq!(Plane::new(v(0.0, 0.0, 0.0), v(0.0, 0.0, 0.0)), Err(PlaneError::ZeroNormal));
/// // N·point = 30000·√3 ≈ 51962 does not fit I16F16.
/// let far = v(30000.0, 30000.0, 30000.0);
/// assert_eq!(Plane::new(v(1.0, 1.0, 1.0), far), Err(PlaneError::OffsetOutOfRange));
/// ```
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
/// use fixray::{I16F16, Scalar};
/// use fixray::geometry::{Plane, Ray, RayKind, Vec3};
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
        ray.hit_at(t)
    }
}

impl<S: Scalar> Plane<S> {
    /// Where the line from `base` along `dir` of any length meets the plane,
    /// `base + s·dir` with `s = (D' − N·base)/(N·dir)`. [`Plane::intersect`]'s point
    /// carries the rounding of its unit direction, times `t/|N·d|` (at a grazing angle
    /// far more than `t`); with the unnormalised direction of a pixel's primary ray
    /// (exact to one rounding of the screen point) it keeps that precision. `None` when
    /// `N·dir = 0` or a quantity does not fit.
    pub fn crossing_along(&self, base: Vec3<S>, dir: Vec3<S>) -> Option<Vec3<S>> {
        let s = S::sub_dot3(self.offset, self.normal.to_array(), base.to_array())?
            .checked_div(self.normal.dot(dir)?)?;
        base.sum(dir.scale(s)?)
    }

    /// Whether the plane meets the ray at some `0 <= t < dist` (a shadow test, pbrt's
    /// `BasicIntersect`): the tests of [`Plane::intersect`] without its division.
    /// `t = num / (N·d)` with `num = D' − N·b`, so
    ///
    /// - parallel: `|N·d| < epsilon`, as in `intersect`;
    /// - `t >= 0`  ⇔  `num` is zero or has the sign of `N·d`;
    /// - `t < dist`  ⇔  `|num| < dist·|N·d|`, compared exactly
    ///   ([`Scalar::cmp_products`]).
    ///
    /// It agrees with `intersect(..).is_ok_and(|h| h.t < dist)` except where the rounded
    /// quotient `t` and the exact one fall on different sides of `dist` (a plane through
    /// the light itself, within one rounding) and where `intersect` finds `t` or the hit
    /// point out of range: such a `t` exceeds every `dist` that fits the format, and here
    /// it is compared exactly instead. On the Cortex-M0 a division costs several of
    /// these multiplications (`docs/performance.md`).
    #[inline]
    pub fn occludes(&self, ray: &Ray<S>, epsilon: S, dist: S) -> bool {
        let Some(n_dot_d) = self.normal.dot(ray.dir) else {
            return false;
        };
        if n_dot_d.abs() < epsilon {
            return false;
        }
        let Some(num) = S::sub_dot3(self.offset, self.normal.to_array(), ray.base.to_array())
        else {
            // `D' − N·b` out of range: so is `t`, beyond any distance that fits.
            return false;
        };
        if num != S::ZERO && (num > S::ZERO) != (n_dot_d > S::ZERO) {
            return false;
        }
        S::cmp_products(num.abs(), S::ONE, dist, n_dot_d.abs()) == Some(core::cmp::Ordering::Less)
    }
}

impl<S: Scalar> Plane<S> {
    /// Whether the segment from `from` to `from + l` crosses the plane strictly between
    /// its ends (a shadow segment from a lit point to its light, `ll = l·l`), without a
    /// division or a square root: with `a₀ = D' − N·from` and `a₁ = a₀ − N·l` (the ends'
    /// signed distances, negated) it crosses when they have strictly opposite signs. As
    /// in [`Plane::intersect`] a segment within `epsilon` of parallel misses
    /// (`|N·l| < ε·|l|`, compared squared: `(N·l)² < ε·(ε·|l|²)`), and an end within
    /// `tol` of the plane does not count as crossing it: `from` is a hit point on or next
    /// to this plane (a ray leaving a plane cannot meet it again), and a light within
    /// `tol` lies on it. `tol` is the caller's bound on `from`'s distance from a surface
    /// it lies on (the [`Plane::spawn`] offset: residual bound plus margin).
    ///
    /// `Some((a₀, N·l))` when it crosses (the crossing is at `u = a₀/(N·l)` along `l`),
    /// `None` when it does not or a quantity does not fit (then `a₀` or `N·l` exceeds the
    /// range: the plane is beyond any light that fits).
    #[inline]
    pub fn crossing(&self, from: Vec3<S>, l: Vec3<S>, ll: S, tol: S, epsilon: S) -> Option<(S, S)> {
        let a0 = S::sub_dot3(self.offset, self.normal.to_array(), from.to_array())?;
        if a0.abs() <= tol {
            return None;
        }
        let a1 = a0.checked_sub(self.normal.dot(l)?)?;
        crossing_of_sides(a0, a1, ll, tol, epsilon)
    }
}

/// The point where the segment from `from` along `l` crosses a plane, from what
/// [`Plane::crossing`] returned: `from + l·a₀/(N·l)` (one division, for a shape whose
/// bounds need the point). `None` when it does not fit the format.
pub(crate) fn crossing_point<S: Scalar>(
    from: Vec3<S>,
    l: Vec3<S>,
    (a0, nl): (S, S),
) -> Option<Vec3<S>> {
    from.sum(l.scale(a0.checked_div(nl)?)?)
}

/// Whether the ends' sides `a₀` and `a₁` of a segment lie strictly on the two sides of
/// a plane, each farther than `tol` from it: where [`crossing_of_sides`] goes on to
/// its products (a shadow test that knows the sides asks this first, without calls).
#[inline]
pub(crate) fn sides_differ<S: Scalar>(a0: S, a1: S, tol: S) -> bool {
    a0.abs() > tol && a1.abs() > tol && (a0 > S::ZERO) != (a1 > S::ZERO)
}

/// [`Plane::crossing`] from the two ends' sides `a₀ = D' − N·from` and `a₁ = D' − N·to`
/// (what a kernel that knows them per frame and per pixel passes: no products), with
/// `N·l = a₀ − a₁`.
#[inline]
pub(crate) fn crossing_of_sides<S: Scalar>(
    a0: S,
    a1: S,
    ll: S,
    tol: S,
    epsilon: S,
) -> Option<(S, S)> {
    if !sides_differ(a0, a1, tol) {
        return None;
    }
    let nl = a0.checked_sub(a1)?;
    let eps_ll = epsilon.checked_mul(ll).unwrap_or(S::MAX);
    if S::cmp_products(nl, nl, epsilon, eps_ll) == Some(core::cmp::Ordering::Less) {
        return None;
    }
    Some((a0, nl))
}

impl<S: Scalar> Plane<S> {}

impl<S: Scalar> Plane<S> {
    /// A bound on how far a hit point computed by [`Plane::intersect`] lies off the plane,
    /// `|N·p − D'|` with the plane's own stored `N` and `D'`:
    /// `(9t/16 + RESIDUAL_ULPS) × ulp(m)`, `m = max(1, t, ‖b‖∞, ‖p‖∞, |D'|)`, for an epsilon
    /// of at least 8 DELTAs (the defaults are 16).
    ///
    /// `None` when the bound itself does not fit the format.
    pub fn residual_bound(&self, ray: &Ray<S>, hit: &Hit<S>) -> Option<S> {
        residual(hit.t, self.magnitude(ray, hit))
    }

    pub(crate) fn magnitude(&self, ray: &Ray<S>, hit: &Hit<S>) -> S {
        ray.base
            .max_abs()
            .max(hit.point.max_abs())
            .max(self.offset.abs())
    }

    /// A secondary ray leaving a hit on this plane in direction `dir`: its base is the hit
    /// point moved along the normal, to the side `dir` points to, by the residual bound
    /// plus [`SPAWN_MARGIN_ULPS`](super::SPAWN_MARGIN_ULPS), so that it can never hit this plane again (pbrt's
    /// offset by a computed error bound, not a magic number). A `dir` parallel to the
    /// plane keeps the hit point (such a ray cannot meet the plane).
    ///
    /// `None` when the offset base does not fit the format.
    pub fn spawn(&self, ray: &Ray<S>, hit: &Hit<S>, dir: Vec3<S>) -> Option<Ray<S>> {
        let m = self.magnitude(ray, hit);
        let base = offset_base(
            hit.point,
            self.normal,
            dir,
            self.residual_bound(ray, hit)?,
            m,
        )?;
        Some(Ray {
            base,
            dir,
            kind: RayKind::Secondary,
        })
    }
}
