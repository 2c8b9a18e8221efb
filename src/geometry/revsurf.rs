//! [`Revsurf`]: the course's surface of revolution (`revsurf`, `COURSE-RULES.md` §14).
//!
//! A surface of revolution about the axis from `base` along the unit `direction`, of
//! length `height`, with radius `r(s)` at the distance `s` along the axis, open at both
//! ends. The course's profiles are built into its tracer and written down nowhere; what
//! the instructor's picture of `surfer 1` (revsurfa) shows is fitted here:
//!
//! - **`surfer 1`: a cone**, `r(s) = R₀ (1 − s / height)` with `R₀ = 4` world units, its
//!   apex at `base + height · direction`. Fitted on revsurfa's silhouette (height 6):
//!   with `R₀ = 4` every row's left and right edge matches the instructor's picture to
//!   the pixel (3, 3.5 and 4.5 are tens of pixels off); with one picture it cannot tell
//!   `R₀ = 4` from a slope of `2/3` (`r = (height − s)·2/3`), which agree at height 6.
//! - **`surfer 2` (an hourglass) and `surfer 3` (a vase)** have no public picture: their
//!   profiles are not guessed, and a scene naming them is refused
//!   ([`RevsurfError::UnknownProfile`]).
//!
//! # Intersection
//! With `w₀ = b − base`, `s₀ = w₀·a`, `s_d = d·a`, `q₀ = w₀ − s₀ a`, `q_d = d − s_d a`
//! (the parts across the axis) and the profile's slope `m = −R₀/height`, `r₀ = r(s₀)`,
//! a point `b + t d` lies on the (double) cone when `A t² + 2 B t + C = 0` with
//!
//! `A = |q_d|² − m² s_d²`, `B = q₀·q_d − m s_d r₀`, `C = |q₀|² − r₀²`.
//!
//! The roots are taken in the stable form `t₁ = Q/A`, `t₂ = C/Q` with
//! `Q = −(B + sign(B)√(B² − AC))` (no cancellation between `B` and the square root),
//! the discriminant `B² − AC` summed in one wide step; a ray along a generator line
//! (`A = 0`) keeps its one root `C/Q`. The hit is the nearest root `t > 0` whose `s`
//! lies on the profile, `0 ≤ s ≤ height` (the other nappe and the open ends miss). A
//! tangent ray (zero discriminant) meets it once; a ray along the axis meets the apex
//! only; at the apex the normal is the axis (or none, where `r` rounds to 0 exactly: lit
//! by nothing).

use super::spawn::spawn_along;
use super::{Hit, Miss, Ray, Vec3};
use crate::Scalar;

/// Why a surface of revolution cannot be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RevsurfError {
    /// A `surfer` whose profile is not known (only `1`, the cone, is).
    UnknownProfile,
    /// The direction is zero.
    ZeroDirection,
    /// The height is not positive.
    NonPositiveHeight,
    /// A derived quantity (the slope) does not fit the format.
    OutOfRange,
}

/// The cone's base radius (fitted on revsurfa, see the module documentation).
pub const CONE_BASE_RADIUS: i32 = 4;

/// A surface of revolution (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Revsurf<S> {
    base: Vec3<S>,
    axis: Vec3<S>,
    height: S,
    /// `r(0)`.
    radius: S,
    /// `−r'(s)`: `R₀ / height`.
    taper: S,
}

impl<S: Scalar> Revsurf<S> {
    /// The course's `revsurf` with profile `surfer`.
    ///
    /// # Errors
    /// [`RevsurfError`] for an unknown profile, a zero direction, a height ≤ 0 or a slope
    /// out of the format's range.
    pub fn new(
        surfer: i64,
        base: Vec3<S>,
        direction: Vec3<S>,
        height: S,
    ) -> Result<Self, RevsurfError> {
        if surfer != 1 {
            return Err(RevsurfError::UnknownProfile);
        }
        let axis = direction.unit().ok_or(RevsurfError::ZeroDirection)?;
        if height <= S::ZERO {
            return Err(RevsurfError::NonPositiveHeight);
        }
        let radius = S::from_i32(CONE_BASE_RADIUS).ok_or(RevsurfError::OutOfRange)?;
        let taper = radius.checked_div(height).ok_or(RevsurfError::OutOfRange)?;
        Ok(Self {
            base,
            axis,
            height,
            radius,
            taper,
        })
    }

    /// The base point of the axis.
    pub fn base(&self) -> Vec3<S> {
        self.base
    }

    /// The unit axis.
    pub fn axis(&self) -> Vec3<S> {
        self.axis
    }

    /// The length of the axis.
    pub fn height(&self) -> S {
        self.height
    }

    /// `r(s)`, the radius at `s` along the axis.
    fn radius_at(&self, s: S) -> Option<S> {
        self.radius.checked_sub(self.taper.checked_mul(s)?)
    }

    /// Intersects a ray (unit direction): the nearest root `t > 0` on the profile.
    ///
    /// # Errors
    /// [`Miss::NoRoot`] when the ray misses the double cone, [`Miss::Behind`] when no
    /// root ahead lies on the profile, [`Miss::OutOfRange`] when a quantity does not fit
    /// the format; the primary-ray screen rule as for every shape.
    pub fn intersect(&self, ray: &Ray<S>) -> Result<Hit<S>, Miss> {
        let range = Miss::OutOfRange;
        let a = self.axis;
        let w0 = ray.base.diff(self.base).ok_or(range)?;
        let s0 = w0.dot(a).ok_or(range)?;
        let sd = ray.dir.dot(a).ok_or(range)?;
        let q0 = a.scale(s0).and_then(|p| w0.diff(p)).ok_or(range)?;
        let qd = a.scale(sd).and_then(|p| ray.dir.diff(p)).ok_or(range)?;
        let r0 = self.radius_at(s0).ok_or(range)?;
        // m = −taper: A = |q_d|² − taper² s_d², B = q₀·q_d + taper s_d r₀, C = |q₀|² − r₀².
        let ts = self.taper.checked_mul(sd).ok_or(range)?;
        let qa = qd.to_array();
        let big_a = S::dot3([qa[0], qa[1], qa[2]], qa)
            .and_then(|qq| S::sub_dot3(qq, [ts, S::ZERO, S::ZERO], [ts, S::ZERO, S::ZERO]))
            .ok_or(range)?;
        let q0a = q0.to_array();
        let big_b = S::dot3(q0a, qa)
            .and_then(|qq| qq.checked_add(ts.checked_mul(r0)?))
            .ok_or(range)?;
        let big_c = S::dot3(q0a, q0a)
            .and_then(|qq| S::sub_dot3(qq, [r0, S::ZERO, S::ZERO], [r0, S::ZERO, S::ZERO]))
            .ok_or(range)?;
        // B² − A C in one wide step.
        let neg_a = big_a.checked_neg().ok_or(range)?;
        let disc = S::dot3([big_b, neg_a, S::ZERO], [big_b, big_c, S::ZERO]).ok_or(range)?;
        if disc < S::ZERO {
            return Err(Miss::NoRoot);
        }
        let root = disc.checked_sqrt().ok_or(range)?;
        let q = if big_b >= S::ZERO {
            big_b.checked_add(root).and_then(S::checked_neg)
        } else {
            root.checked_sub(big_b)
        }
        .ok_or(range)?;
        let mut best: Option<S> = None;
        for t in [q.checked_div(big_a), big_c.checked_div(q)]
            .into_iter()
            .flatten()
        {
            if t <= S::ZERO || best.is_some_and(|b| b <= t) {
                continue;
            }
            let on_profile = sd
                .checked_mul(t)
                .and_then(|st| s0.checked_add(st))
                .is_some_and(|s| s >= S::ZERO && s <= self.height);
            if on_profile {
                best = Some(t);
            }
        }
        let t = best.ok_or(Miss::Behind)?;
        ray.hit_at(t)
    }

    /// The outward unit normal the course lights a point with, `unit(q + 2 r(s) taper a)`:
    /// tilted along the axis twice as far as the surface's own normal
    /// `unit(q + r(s) taper a)` (the gradient of `|q|² − r(s)²`): the tilt that draws
    /// revsurfa's shading (the fit and its figures: `docs/numerics.md`, "Surfaces of revolution"). `None` at the
    /// apex or off the format's range.
    pub fn normal_at(&self, point: Vec3<S>) -> Option<Vec3<S>> {
        let w = point.diff(self.base)?;
        let s = w.dot(self.axis)?;
        let q = w.diff(self.axis.scale(s)?)?;
        let r = self.radius_at(s)?.max(S::ZERO);
        let tilt = r.checked_mul(self.taper)?;
        q.sum(self.axis.scale(tilt.checked_add(tilt)?)?)?.unit()
    }

    /// A secondary ray leaving a hit in direction `dir`, based off the surface along its
    /// normal by the plane's and sphere's residual bound (the crate's rules; the course
    /// starts on the hit and skips the object).
    pub fn spawn(&self, ray: &Ray<S>, hit: &Hit<S>, dir: Vec3<S>) -> Option<Ray<S>> {
        let m = ray
            .base
            .max_abs()
            .max(hit.point.max_abs())
            .max(self.base.max_abs())
            .max(self.height)
            .max(self.radius);
        spawn_along(hit, self.normal_at(hit.point)?, dir, m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I32F32};

    fn cone<S: Scalar>() -> Revsurf<S> {
        let v = |x, y, z| Vec3::<S>::from_f64([x, y, z]).unwrap();
        Revsurf::new(
            1,
            v(4.0, 0.0, -4.0),
            v(0.0, 1.0, 0.0),
            S::from_i32(6).unwrap(),
        )
        .unwrap()
    }

    fn ray<S: Scalar>(base: [f64; 3], dir: [f64; 3]) -> Ray<S> {
        Ray {
            base: Vec3::from_f64(base).unwrap(),
            dir: Vec3::from_f64(dir).unwrap().unit().unwrap(),
            kind: crate::RayKind::Secondary,
        }
    }

    fn cases<S: Scalar>(tol: f64) {
        let c = cone::<S>();
        // Horizontally at height 3 (radius 2) through the axis: the near side, t = 8 − 2.
        let h = c
            .intersect(&ray([4.0, 3.0, 4.0], [0.0, 0.0, -1.0]))
            .unwrap();
        assert!(
            (h.t.to_f64() - 6.0).abs() < tol,
            "{} {}",
            S::NAME,
            h.t.to_f64()
        );
        let n = c.normal_at(h.point).unwrap();
        // Outward and up, twice the surface's tilt: (0, 8/3, 2) normalised.
        let want = [0.0, 0.8, 0.6];
        for (g, w) in n.to_array().iter().zip(want) {
            assert!((g.to_f64() - w).abs() < 1e-3, "{} normal", S::NAME);
        }
        // Tangent at height 3: x = 6 is the silhouette; x = 6.01 misses.
        assert!(
            c.intersect(&ray([6.01, 3.0, 4.0], [0.0, 0.0, -1.0]))
                .is_err()
        );
        // Above the apex along the other nappe: misses (s > height).
        assert!(
            c.intersect(&ray([4.0, 7.0, 4.0], [0.0, 0.0, -1.0]))
                .is_err()
        );
        // Down beside the axis from above: just below the apex, t = 1 + 0.01 / taper.
        let h = c
            .intersect(&ray([4.01, 7.0, -4.0], [0.0, -1.0, 0.0]))
            .unwrap();
        assert!(
            (h.t.to_f64() - 1.015).abs() < tol,
            "{} {}",
            S::NAME,
            h.t.to_f64()
        );
        // The apex: a normal along the axis (the rounding of r(height)) or none.
        let apex = Vec3::from_f64([4.0, 6.0, -4.0]).unwrap();
        if let Some(n) = c.normal_at(apex) {
            assert!((n.y.to_f64() - 1.0).abs() < 1e-3, "{}", S::NAME);
        }
        // Up through the open base from below: meets the inside, just below the apex. The
        // two roots coalesce at the apex (0.03 apart): the discriminant cancels, and `t`
        // is good to a few √DELTA there (the axis is the hard case, `docs/numerics.md`).
        let h = c
            .intersect(&ray([4.01, -1.0, -4.0], [0.0, 1.0, 0.0]))
            .unwrap();
        let near_apex = tol.max(8.0 * S::DELTA.to_f64().sqrt());
        assert!(
            (h.t.to_f64() - 6.985).abs() < near_apex,
            "{} {}",
            S::NAME,
            h.t.to_f64()
        );
        // Below the base rim: misses (s < 0); a ray from inside meets the wall.
        assert!(
            c.intersect(&ray([4.0, -0.5, 4.0], [0.0, 0.0, -1.0]))
                .is_err()
        );
        let h = c
            .intersect(&ray([4.0, 1.5, -4.0], [1.0, 0.0, 0.0]))
            .unwrap();
        assert!((h.t.to_f64() - 3.0).abs() < tol);
        // Along a generator line (A = 0): from the apex's side, one root.
        let g = c
            .intersect(&ray([4.0 + 8.0, 6.0 - 12.0, -4.0], [-2.0, 3.0, 0.0]))
            .map(|h| h.t.to_f64());
        assert!(g.is_ok() || g == Err(Miss::Behind), "{} {g:?}", S::NAME);
    }

    #[test]
    fn the_cone_in_every_format() {
        cases::<f64>(1e-9);
        cases::<f32>(1e-4);
        cases::<I32F32>(1e-6);
        cases::<I16F16>(2e-3);
    }

    #[test]
    fn unknown_profiles_and_bad_axes_are_errors() {
        let v = |x, y, z| Vec3::<f64>::from_f64([x, y, z]).unwrap();
        assert_eq!(
            Revsurf::new(2, v(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0), 6.0),
            Err(RevsurfError::UnknownProfile)
        );
        assert_eq!(
            Revsurf::new(1, v(0.0, 0.0, 0.0), v(0.0, 0.0, 0.0), 6.0),
            Err(RevsurfError::ZeroDirection)
        );
        assert_eq!(
            Revsurf::new(1, v(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0), 0.0),
            Err(RevsurfError::NonPositiveHeight)
        );
    }
}
