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
//! - **`surfer 2`: an hourglass**, `r(s) = 1 + cos(s)/2`, and **`surfer 3`: a vase**,
//!   `r(s) = 1 + sin(s)/2`, `s` in world units (the course's files give them
//!   `height 6.28`, one period). Fitted on revsurfe's silhouettes: every row's edges of
//!   both shapes match the instructor's picture to the pixel but one (of 30 rows
//!   checked); lit with their true normal `unit(q − r(s) r'(s) a)` (0.19 % of revsurfe's
//!   sampled pixels beyond 2 levels; 32 % with the cone's doubled tilt). Other numbers
//!   are refused ([`RevsurfError::UnknownProfile`]).
//!
//! # Intersection
//! ## The cone
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
//!
//! ## The hourglass and the vase
//! Not quadrics: the hit is the first sign change of `F(t) = |q₀ + q_d t|² − r(s₀ + s_d t)²`
//! on the part of the ray inside the bounding cylinder (radius 25/16, the profiles'
//! largest radius 3/2 with a margin, so that no root lies where the ray enters it) and
//! between the end planes (`0 ≤ s ≤ height`), found by stepping and then bisecting. On
//! that part `|F'(t)| ≤ (25/8)|q_d| + (3/2)|s_d| < 4`, so a step of `|F(t)|/4`
//! cannot pass a root; a step is at least [`MIN_STEP`] (a ray that grazes the surface for
//! less than that may pass it: the silhouette's last sliver), at most [`MAX_STEPS`] steps
//! (a longer search is a documented miss, [`Miss::Behind`]). The bisection halves the
//! bracket until its midpoint rounds to an end, and the hit is the end past the surface.
//! The profile's cosine and sine are the format's own (`crate::num::series::cos`).

use super::spawn::spawn_along;
use super::{Hit, Miss, Ray, Vec3};
use crate::Scalar;
use crate::num::series::cos::{cos_any, sin_any};

/// Why a surface of revolution cannot be built.
///
/// ```
/// use fixray::geometry::{Revsurf, RevsurfError, Vec3};
/// use fixray::{Scalar, I16F16};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// let (base, up, one) = (v(0.0, 0.0, -10.0), v(0.0, 1.0, 0.0), I16F16::ONE);
/// assert_eq!(Revsurf::new(7, base, up, one), Err(RevsurfError::UnknownProfile));
/// assert_eq!(Revsurf::new(1, base, v(0.0, 0.0, 0.0), one), Err(RevsurfError::ZeroDirection));
/// assert_eq!(Revsurf::new(1, base, up, I16F16::ZERO), Err(RevsurfError::NonPositiveHeight));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RevsurfError {
    /// A `surfer` whose profile is not known (`1`, `2` and `3` are).
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

/// The shortest step of the hourglass's and the vase's root search, in world units along
/// the (unit) ray: 1/64.
pub const MIN_STEP: (i32, i32) = (1, 64);

/// The most steps of one root search (at [`MIN_STEP`], 8 world units of grazing path).
pub const MAX_STEPS: u32 = 512;

/// A radius profile `r(s)` (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Profile<S> {
    /// `surfer 1`: `r(s) = radius − taper · s`.
    Cone {
        /// `r(0)`.
        radius: S,
        /// `−r'(s)`: `R₀ / height`.
        taper: S,
    },
    /// `surfer 2`: `r(s) = 1 + cos(s)/2`.
    Hourglass,
    /// `surfer 3`: `r(s) = 1 + sin(s)/2`.
    Vase,
}

/// A ray in the axis' terms: `s(t) = s0 + sd t` along the axis, `q(t) = q0 + qd t`
/// across it.
struct Axial<S> {
    s0: S,
    sd: S,
    q0: Vec3<S>,
    qd: Vec3<S>,
}

/// A surface of revolution (see the module documentation).
///
/// ```
/// use fixray::geometry::{Ray, RayKind, Revsurf, Vec3};
/// use fixray::{Scalar, I16F16};
///
/// let v = |x, y, z| Vec3::<I16F16>::from_f64([x, y, z]).unwrap();
/// // The hourglass (`surfer 2`: radius 1 + cos(s)/2 at `s` along the axis), 3 units tall.
/// let glass = Revsurf::new(2, v(0.0, 0.0, -10.0), v(0.0, 1.0, 0.0), I16F16::from_num(3)).unwrap();
/// // At 1.5 up the axis its radius is 1 + cos(1.5)/2 ≈ 1.0354.
/// let ray = Ray { base: v(0.0, 1.5, 5.0), dir: v(0.0, 0.0, -1.0), kind: RayKind::Primary };
/// let hit = glass.intersect(&ray).unwrap();
/// assert!((hit.t.to_f64() - (15.0 - 1.0354)).abs() < 0.01);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Revsurf<S> {
    base: Vec3<S>,
    axis: Vec3<S>,
    height: S,
    profile: Profile<S>,
}

/// `Q = −(B + sign(B)√disc)` of the stable root pair `Q/A`, `C/Q` (no cancellation
/// between `B` and the square root `root`).
fn stable_q<S: Scalar>(big_b: S, root: S) -> Option<S> {
    if big_b >= S::ZERO {
        big_b.checked_add(root).and_then(S::checked_neg)
    } else {
        root.checked_sub(big_b)
    }
}

/// `n / d`, or the format's largest magnitude of the quotient's sign where it does not
/// fit (a bound of the search interval that lies beyond the format's range).
fn div_or_far<S: Scalar>(n: S, d: S) -> S {
    n.checked_div(d).unwrap_or_else(|| {
        if (n < S::ZERO) == (d < S::ZERO) {
            S::MAX
        } else {
            S::MAX.checked_neg().unwrap_or(S::ZERO)
        }
    })
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
        if !(1..=3).contains(&surfer) {
            return Err(RevsurfError::UnknownProfile);
        }
        let axis = direction.unit().ok_or(RevsurfError::ZeroDirection)?;
        if height <= S::ZERO {
            return Err(RevsurfError::NonPositiveHeight);
        }
        let profile = match surfer {
            1 => {
                let radius = S::from_i32(CONE_BASE_RADIUS).ok_or(RevsurfError::OutOfRange)?;
                let taper = radius.checked_div(height).ok_or(RevsurfError::OutOfRange)?;
                Profile::Cone { radius, taper }
            }
            2 => Profile::Hourglass,
            _ => Profile::Vase,
        };
        Ok(Self {
            base,
            axis,
            height,
            profile,
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

    /// The profile's number (`surfer`): 1 the cone, 2 the hourglass, 3 the vase.
    pub fn surfer(&self) -> u8 {
        match self.profile {
            Profile::Cone { .. } => 1,
            Profile::Hourglass => 2,
            Profile::Vase => 3,
        }
    }

    /// The largest radius of the profile (the hourglass's and the vase's with a margin
    /// of 1/16: their bounding cylinder, which then meets the surface nowhere, so that
    /// `F` at a side entry is clearly positive and no root lies at the search's start).
    fn max_radius(&self) -> Option<S> {
        match self.profile {
            Profile::Cone { radius, .. } => Some(radius),
            Profile::Hourglass | Profile::Vase => S::from_i32(25)?.mul_ratio(1, 16),
        }
    }

    /// `r(s)`, the radius at `s` along the axis.
    fn radius_at(&self, s: S) -> Option<S> {
        match self.profile {
            Profile::Cone { radius, taper } => radius.checked_sub(taper.checked_mul(s)?),
            Profile::Hourglass => S::ONE.checked_add(cos_any(s)?.mul_ratio(1, 2)?),
            Profile::Vase => S::ONE.checked_add(sin_any(s)?.mul_ratio(1, 2)?),
        }
    }

    /// The ray in the axis' terms.
    fn axial(&self, ray: &Ray<S>) -> Option<Axial<S>> {
        let a = self.axis;
        let w0 = ray.base.diff(self.base)?;
        let s0 = w0.dot(a)?;
        let sd = ray.dir.dot(a)?;
        let q0 = w0.diff(a.scale(s0)?)?;
        let qd = ray.dir.diff(a.scale(sd)?)?;
        Some(Axial { s0, sd, q0, qd })
    }

    /// Intersects a ray (unit direction): the nearest root `t > 0` on the profile.
    ///
    /// # Errors
    /// [`Miss::NoRoot`] when the ray misses the surface (the cone's double cone, the
    /// other profiles' bounding cylinder), [`Miss::Behind`] when no root ahead lies on
    /// the profile (or the root search ran out of steps), [`Miss::OutOfRange`] when a
    /// quantity does not fit the format; the primary-ray screen rule as for every shape.
    pub fn intersect(&self, ray: &Ray<S>) -> Result<Hit<S>, Miss> {
        let w = self.axial(ray).ok_or(Miss::OutOfRange)?;
        let t = match self.profile {
            Profile::Cone { radius, taper } => self.cone_root(&w, radius, taper)?,
            Profile::Hourglass | Profile::Vase => self.search_root(&w)?,
        };
        ray.hit_at(t)
    }

    /// The cone's nearest root on the profile (the stable quadratic, module
    /// documentation).
    fn cone_root(&self, w: &Axial<S>, radius: S, taper: S) -> Result<S, Miss> {
        let range = Miss::OutOfRange;
        let Axial { s0, sd, q0, qd } = *w;
        let r0 = radius
            .checked_sub(taper.checked_mul(s0).ok_or(range)?)
            .ok_or(range)?;
        // m = −taper: A = |q_d|² − taper² s_d², B = q₀·q_d + taper s_d r₀, C = |q₀|² − r₀².
        let ts = taper.checked_mul(sd).ok_or(range)?;
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
        let q = stable_q(big_b, root).ok_or(range)?;
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
        best.ok_or(Miss::Behind)
    }

    /// `F(t) = |q(t)|² − r(s(t))²`: positive outside the surface, negative inside.
    fn excess(&self, w: &Axial<S>, t: S) -> Option<S> {
        let q = w.q0.sum(w.qd.scale(t)?)?.to_array();
        let r = self.radius_at(w.s0.checked_add(w.sd.checked_mul(t)?)?)?;
        S::sub_dot3(S::dot3(q, q)?, [r, S::ZERO, S::ZERO], [r, S::ZERO, S::ZERO])
    }

    /// The part `(lo, hi)` of the ray ahead (`lo ≥ 0`) inside the bounding cylinder and
    /// between the end planes.
    fn search_interval(&self, w: &Axial<S>) -> Result<(S, S), Miss> {
        let range = Miss::OutOfRange;
        let (mut lo, mut hi) = (S::ZERO, S::MAX);
        // The end planes: 0 ≤ s0 + sd t ≤ height.
        if w.sd == S::ZERO {
            if w.s0 < S::ZERO || w.s0 > self.height {
                return Err(Miss::NoRoot);
            }
        } else {
            let neg_s0 = w.s0.checked_neg().ok_or(range)?;
            let ta = div_or_far(neg_s0, w.sd);
            let tb = div_or_far(self.height.checked_sub(w.s0).ok_or(range)?, w.sd);
            lo = lo.max(ta.min(tb));
            hi = hi.min(ta.max(tb));
        }
        // The bounding cylinder: A t² + 2 B t + C ≤ 0.
        let rmax = self.max_radius().ok_or(range)?;
        let qd = w.qd.to_array();
        let q0 = w.q0.to_array();
        let big_a = S::dot3(qd, qd).ok_or(range)?;
        let big_b = S::dot3(q0, qd).ok_or(range)?;
        let big_c = S::dot3(q0, q0)
            .and_then(|qq| S::sub_dot3(qq, [rmax, S::ZERO, S::ZERO], [rmax, S::ZERO, S::ZERO]))
            .ok_or(range)?;
        if big_a == S::ZERO {
            if big_c > S::ZERO {
                return Err(Miss::NoRoot);
            }
        } else {
            let neg_a = big_a.checked_neg().ok_or(range)?;
            let disc = S::dot3([big_b, neg_a, S::ZERO], [big_b, big_c, S::ZERO]).ok_or(range)?;
            if disc <= S::ZERO {
                return Err(Miss::NoRoot);
            }
            let root = disc.checked_sqrt().ok_or(range)?;
            let q = stable_q(big_b, root).ok_or(range)?;
            let (t1, t2) = (div_or_far(q, big_a), div_or_far(big_c, q));
            lo = lo.max(t1.min(t2));
            hi = hi.min(t1.max(t2));
        }
        if hi <= lo {
            return Err(Miss::NoRoot);
        }
        Ok((lo, hi))
    }

    /// The first sign change of [`Self::excess`] on the search interval (module
    /// documentation).
    fn search_root(&self, w: &Axial<S>) -> Result<S, Miss> {
        let range = Miss::OutOfRange;
        let (lo, hi) = self.search_interval(w)?;
        let min_step = S::ONE.mul_ratio(MIN_STEP.0, MIN_STEP.1).ok_or(range)?;
        let mut t = lo;
        let mut f = self.excess(w, t).ok_or(range)?;
        if f == S::ZERO && t > S::ZERO {
            return Ok(t);
        }
        for _ in 0..MAX_STEPS {
            if t >= hi {
                return Err(Miss::Behind);
            }
            // |F'| < 4 on the interval: no root within |F|/4.
            let step = f.abs().mul_ratio(1, 4).ok_or(range)?.max(min_step);
            let next = t.checked_add(step).map_or(hi, |n| n.min(hi));
            let g = self.excess(w, next).ok_or(range)?;
            if g == S::ZERO || (g < S::ZERO) != (f < S::ZERO) {
                return self.bisect(w, t, next, f < S::ZERO);
            }
            t = next;
            f = g;
        }
        Err(Miss::Behind)
    }

    /// Halves the bracket `[a, b]` (`F(a)` negative when `inside`, `F(b)` of the other sign
    /// or zero) until its midpoint rounds to an end; the end past the surface.
    fn bisect(&self, w: &Axial<S>, mut a: S, mut b: S, inside: bool) -> Result<S, Miss> {
        let range = Miss::OutOfRange;
        for _ in 0..128 {
            let m = b
                .checked_sub(a)
                .and_then(|d| d.mul_ratio(1, 2))
                .and_then(|h| a.checked_add(h))
                .ok_or(range)?;
            if m <= a || m >= b {
                break;
            }
            let fm = self.excess(w, m).ok_or(range)?;
            if fm != S::ZERO && (fm < S::ZERO) == inside {
                a = m;
            } else {
                b = m;
            }
        }
        if b > S::ZERO {
            Ok(b)
        } else {
            Err(Miss::Behind)
        }
    }

    /// The outward unit normal the course lights a point with. The cone's,
    /// `unit(q + 2 r(s) taper a)`, is tilted along the axis twice as far as the surface's
    /// own normal `unit(q + r(s) taper a)` (the gradient of `|q|² − r(s)²`): the tilt that
    /// draws revsurfa's shading. The hourglass and the vase take their true normal,
    /// `unit(q − r(s) r'(s) a)` (the fits and their figures: `docs/numerics.md`,
    /// "Surfaces of revolution"). `None` at the cone's apex or off the format's range.
    pub fn normal_at(&self, point: Vec3<S>) -> Option<Vec3<S>> {
        let w = point.diff(self.base)?;
        let s = w.dot(self.axis)?;
        let q = w.diff(self.axis.scale(s)?)?;
        // The normal's part along the axis, −r r' (doubled for the cone).
        let along = match self.profile {
            Profile::Cone { taper, .. } => {
                let r = self.radius_at(s)?.max(S::ZERO);
                let tilt = r.checked_mul(taper)?;
                tilt.checked_add(tilt)?
            }
            Profile::Hourglass => {
                // r r' = −(1 + cos s / 2) sin s / 2
                let r = self.radius_at(s)?;
                r.checked_mul(sin_any(s)?.mul_ratio(1, 2)?)?
            }
            Profile::Vase => {
                // r r' = (1 + sin s / 2) cos s / 2
                let r = self.radius_at(s)?;
                r.checked_mul(cos_any(s)?.mul_ratio(1, 2)?)?.checked_neg()?
            }
        };
        q.sum(self.axis.scale(along)?)?.unit()
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
            .max(self.max_radius()?);
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
        for k in [0, 4, -1] {
            assert_eq!(
                Revsurf::new(k, v(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0), 6.0),
                Err(RevsurfError::UnknownProfile)
            );
        }
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
