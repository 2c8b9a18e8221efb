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
        ray.hit_at(t)
    }
}

impl<S: Scalar> Plane<S> {
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
    /// it is compared exactly instead. On the Cortex-M0 a division costs about nine of
    /// these multiplications (`../shared/measurements.md`).
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
        S::cmp_products(num.abs(), S::ONE, dist, n_dot_d.abs()).is_lt()
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
        residual(hit.t, self.magnitude(ray, hit))
    }

    fn magnitude(&self, ray: &Ray<S>, hit: &Hit<S>) -> S {
        ray.base
            .max_abs()
            .max(hit.point.max_abs())
            .max(self.offset.abs())
    }

    /// A secondary ray leaving a hit on this plane in direction `dir`: its base is the hit
    /// point moved along the normal, to the side `dir` points to, by the residual bound
    /// plus [`SPAWN_MARGIN_ULPS`], so that it can never hit this plane again (pbrt's
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

/// The residual bound of [`Plane::residual_bound`] for a hit at distance `t` among values
/// of magnitude up to `m`: `(9t/16 + RESIDUAL_ULPS) × ulp(max(1, t, m))`.
fn residual<S: Scalar>(t: S, m: S) -> Option<S> {
    let m = S::ONE.max(t).max(m);
    t.mul_ratio(9, 16)?
        .checked_add(S::from_i32(RESIDUAL_ULPS)?)?
        .checked_mul(m.ulp())
}

/// Moves `point` along the unit `normal`, to the side `dir` points to, by `bound` plus
/// [`SPAWN_MARGIN_ULPS`] (at magnitude `m`): the base of a secondary ray that cannot
/// meet the surface it leaves. A `dir` tangent to the surface keeps the point.
fn offset_base<S: Scalar>(
    point: Vec3<S>,
    normal: Vec3<S>,
    dir: Vec3<S>,
    bound: S,
    m: S,
) -> Option<Vec3<S>> {
    let side = normal.dot(dir)?;
    if side == S::ZERO {
        return Some(point);
    }
    let margin = S::from_i32(SPAWN_MARGIN_ULPS)?.checked_mul(S::ONE.max(m).ulp())?;
    let mut off = bound.checked_add(margin)?;
    if side < S::ZERO {
        off = off.checked_neg()?;
    }
    point.sum(normal.scale(off)?)
}

/// Why a sphere cannot be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SphereError {
    /// The radius is not positive.
    NonPositiveRadius,
    /// `radius²` does not fit the number format.
    RadiusOutOfRange,
}

/// A sphere.
///
/// The intersection uses the numerically careful form (as in pbrt and *Ray Tracing Gems*
/// ch. 7): the discriminant is `r² − |oc − (oc·d)d|²` (the squared distance of the centre
/// from the ray's line subtracted from r², which does not cancel catastrophically for
/// far or grazing rays), and the two roots are `q = −(b + sign(b)√Δ)` and `c/q`, so
/// neither is the difference of two nearly equal numbers. Tangency is decided by the sign
/// of the discriminant (the precision epsilon belongs to the plane tests).
///
/// ```
/// use fixray::{I16F16, Ray, RayKind, Scalar, Sphere, Vec3};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let s = Sphere::new(v(0.0, 0.0, -10.0), I16F16::from_i32(2).unwrap()).unwrap();
/// let ray = Ray { base: v(0.0, 0.0, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Primary };
/// assert_eq!(s.intersect(&ray).unwrap().t.to_f64(), 13.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere<S> {
    center: Vec3<S>,
    radius: S,
    radius_sq: S,
}

impl<S: Scalar> Sphere<S> {
    /// A sphere of radius `radius` (> 0) around `center`.
    ///
    /// # Errors
    /// [`SphereError`] when the radius is not positive or its square does not fit.
    pub fn new(center: Vec3<S>, radius: S) -> Result<Self, SphereError> {
        if radius <= S::ZERO {
            return Err(SphereError::NonPositiveRadius);
        }
        let radius_sq = radius
            .checked_mul(radius)
            .ok_or(SphereError::RadiusOutOfRange)?;
        Ok(Self {
            center,
            radius,
            radius_sq,
        })
    }

    /// The centre.
    pub fn center(&self) -> Vec3<S> {
        self.center
    }

    /// The radius.
    pub fn radius(&self) -> S {
        self.radius
    }

    /// Intersects a ray (unit direction): the smallest root `t >= 0`, the far root when the
    /// base is inside; no real root is [`Miss::NoRoot`]; the primary-ray screen rule
    /// applies as for planes.
    ///
    /// # Errors
    /// The [`Miss`] reason when the ray does not hit.
    pub fn intersect(&self, ray: &Ray<S>) -> Result<Hit<S>, Miss> {
        let oc = ray.base.diff(self.center).ok_or(Miss::OutOfRange)?;
        let b = oc.dot(ray.dir).ok_or(Miss::OutOfRange)?;
        let perp = ray
            .dir
            .scale(b)
            .and_then(|p| oc.diff(p))
            .ok_or(Miss::OutOfRange)?;
        let disc = S::sub_dot3(self.radius_sq, perp.to_array(), perp.to_array())
            .ok_or(Miss::OutOfRange)?;
        if disc < S::ZERO {
            return Err(Miss::NoRoot);
        }
        let root = disc.checked_sqrt().ok_or(Miss::OutOfRange)?;
        let q = if b >= S::ZERO {
            b.checked_add(root).and_then(S::checked_neg)
        } else {
            root.checked_sub(b)
        }
        .ok_or(Miss::OutOfRange)?;
        // The other root is c/q with c = |oc|² − r² (one wide step): exact where the two
        // roots nearly cancel (the base near the surface, c ≈ 0). For a far sphere c can
        // exceed the format while t fits; then |oc| ≫ r and −b ∓ √Δ does not cancel.
        let c = S::sub_dot3(self.radius_sq, oc.to_array(), oc.to_array()).and_then(S::checked_neg);
        let other = match c {
            Some(c) if q != S::ZERO => c.checked_div(q),
            _ if b < S::ZERO => S::ZERO.checked_sub(b).and_then(|nb| nb.checked_sub(root)),
            _ => root.checked_sub(b),
        }
        .ok_or(Miss::OutOfRange)?;
        let (t0, t1) = (q, other);
        let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        let t = if near >= S::ZERO {
            near
        } else if far >= S::ZERO {
            far
        } else {
            return Err(Miss::Behind);
        };
        ray.hit_at(t)
    }

    /// The outward unit normal at a point on the surface.
    pub fn normal_at(&self, point: Vec3<S>) -> Option<Vec3<S>> {
        point.diff(self.center)?.unit()
    }

    fn magnitude(&self, ray: &Ray<S>, hit: &Hit<S>) -> S {
        ray.base
            .max_abs()
            .max(hit.point.max_abs())
            .max(self.center.max_abs())
            .max(self.radius)
    }
}

/// Why a tiled or finite plane cannot be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameError {
    /// The plane itself cannot be built.
    Plane(PlaneError),
    /// `xdir` has no component in the plane (zero, or parallel to the normal).
    XdirInvalid,
    /// A tile or side length is not positive.
    NonPositiveSize,
}

/// A plane with coordinates: the corner `point`, `u` = unit(xdir projected into the plane),
/// `v` = unit(N × u), and two lengths along them. Tiled planes (tile size) and finite
/// planes (side lengths) are built on it. The plane coordinates of a point `p` are
/// `a = (p − point)·u`, `b = (p − point)·v`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneFrame<S> {
    plane: Plane<S>,
    corner: Vec3<S>,
    u: Vec3<S>,
    v: Vec3<S>,
    size: [S; 2],
}

impl<S: Scalar> PlaneFrame<S> {
    /// Builds the frame.
    ///
    /// # Errors
    /// [`FrameError`] for a zero normal, an offset out of range, an `xdir` with no
    /// component in the plane, or a non-positive size.
    pub fn new(
        normal: Vec3<S>,
        point: Vec3<S>,
        xdir: Vec3<S>,
        size: [S; 2],
    ) -> Result<Self, FrameError> {
        let plane = Plane::new(normal, point).map_err(FrameError::Plane)?;
        if size[0] <= S::ZERO || size[1] <= S::ZERO {
            return Err(FrameError::NonPositiveSize);
        }
        let n = plane.normal();
        let along = n.dot(xdir).ok_or(FrameError::XdirInvalid)?;
        let u = n
            .scale(along)
            .and_then(|p| xdir.diff(p))
            .and_then(Vec3::unit)
            .ok_or(FrameError::XdirInvalid)?;
        let v = n
            .cross(u)
            .and_then(Vec3::unit)
            .ok_or(FrameError::XdirInvalid)?;
        Ok(Self {
            plane,
            corner: point,
            u,
            v,
            size,
        })
    }

    /// The underlying infinite plane.
    pub fn plane(&self) -> &Plane<S> {
        &self.plane
    }

    /// The tile or side lengths along `u` and `v`.
    pub fn size(&self) -> [S; 2] {
        self.size
    }

    /// The plane coordinates `(a, b)` of a point.
    pub fn coords(&self, p: Vec3<S>) -> Option<(S, S)> {
        let q = p.diff(self.corner)?;
        Some((q.dot(self.u)?, q.dot(self.v)?))
    }

    /// Whether a point lies on the checkerboard's odd squares:
    /// `floor(a / W) + floor(b / H)` odd.
    pub fn odd_tile(&self, p: Vec3<S>) -> Option<bool> {
        let (a, b) = self.coords(p)?;
        let i = a.checked_div(self.size[0])?.floor_to_i32()?;
        let j = b.checked_div(self.size[1])?.floor_to_i32()?;
        Some((i.wrapping_add(j)) & 1 == 1)
    }

    /// Whether a point lies inside the rectangle `0 <= a <= W`, `0 <= b <= H`.
    pub fn contains(&self, p: Vec3<S>) -> bool {
        self.coords(p).is_some_and(|(a, b)| {
            a >= S::ZERO && a <= self.size[0] && b >= S::ZERO && b <= self.size[1]
        })
    }
}

/// A shape of the scene. Shapes dispatch through this enum (no `dyn`).
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

impl<S: Scalar> Shape<S> {
    /// Intersects a ray with the shape (`epsilon` is the plane tests' precision epsilon).
    ///
    /// # Errors
    /// The [`Miss`] reason when the ray does not hit.
    #[inline]
    pub fn intersect(&self, ray: &Ray<S>, epsilon: S) -> Result<Hit<S>, Miss> {
        match self {
            Shape::Plane(p) => p.intersect(ray, epsilon),
            Shape::Sphere(s) => s.intersect(ray),
            Shape::Tiled { frame, .. } => frame.plane.intersect(ray, epsilon),
            Shape::Finite(frame) => {
                let hit = frame.plane.intersect(ray, epsilon)?;
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
            Shape::Tiled { frame, .. } => frame.plane.occludes(ray, epsilon, dist),
            Shape::Sphere(_) | Shape::Finite(_) => {
                self.intersect(ray, epsilon).is_ok_and(|hit| hit.t < dist)
            }
        }
    }

    /// The unit surface normal at a hit point (before facing it towards the ray).
    #[inline]
    pub fn normal_at(&self, point: Vec3<S>) -> Option<Vec3<S>> {
        match self {
            Shape::Plane(p) => Some(p.normal()),
            Shape::Sphere(s) => s.normal_at(point),
            Shape::Tiled { frame, .. } | Shape::Finite(frame) => Some(frame.plane.normal()),
        }
    }

    /// A secondary ray leaving `hit` in direction `dir`, based off the surface by its
    /// computed error bound so that it cannot meet the surface it leaves
    /// ([`Plane::spawn`]; for spheres the same bound along the sphere's normal).
    pub fn spawn(&self, ray: &Ray<S>, hit: &Hit<S>, dir: Vec3<S>) -> Option<Ray<S>> {
        match self {
            Shape::Plane(p) => p.spawn(ray, hit, dir),
            Shape::Tiled { frame, .. } | Shape::Finite(frame) => frame.plane.spawn(ray, hit, dir),
            Shape::Sphere(s) => {
                let m = s.magnitude(ray, hit);
                let bound = residual(hit.t, m)?;
                let base = offset_base(hit.point, s.normal_at(hit.point)?, dir, bound, m)?;
                Some(Ray {
                    base,
                    dir,
                    kind: RayKind::Secondary,
                })
            }
        }
    }
}
