//! The sphere, with the numerically careful intersection.

use super::spawn::spawn_along;
use super::{Hit, Miss, Ray, Vec3};
use crate::Scalar;

/// Why a sphere cannot be built.
///
/// ```
/// use fixray::geometry::{Sphere, SphereError, Vec3};
/// use fixray::I16F16;
///
/// let center = Vec3::<I16F16>::from_f64([0.0, 0.0, -10.0]).unwrap();
/// assert_eq!(Sphere::new(center, I16F16::from_num(0)), Err(SphereError::NonPositiveRadius));
/// // 200² = 40000 does not fit I16F16.
/// assert_eq!(Sphere::new(center, I16F16::from_num(200)), Err(SphereError::RadiusOutOfRange));
/// ```
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
/// use fixray::{I16F16, Scalar};
/// use fixray::geometry::{Ray, RayKind, Sphere, Vec3};
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
    /// `1/radius` for the normal, where it has at least 8 significant bits (`1/r ≥
    /// 256·DELTA`) and `r²` at least 10 (`r² ≥ 1024·DELTA`: the normal's surface check,
    /// `r²/64`, is then well above its roundings); zero where not (the normal is then
    /// normalised).
    inv_radius: S,
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
            inv_radius: S::ONE
                .checked_div(radius)
                .filter(|k| S::DELTA.checked_mul_int(256).is_some_and(|min| *k >= min))
                .filter(|_| {
                    S::DELTA
                        .checked_mul_int(1024)
                        .is_some_and(|m| radius_sq >= m)
                })
                .unwrap_or(S::ZERO),
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

    /// `radius²`, precomputed.
    pub fn radius_sq(&self) -> S {
        self.radius_sq
    }

    /// Intersects a ray (unit direction): the smallest root `t >= 0`, the far root when the
    /// base is inside; no real root is [`Miss::NoRoot`]; the primary-ray screen rule
    /// applies as for planes.
    ///
    /// # Errors
    /// The [`Miss`] reason when the ray does not hit.
    pub fn intersect(&self, ray: &Ray<S>) -> Result<Hit<S>, Miss> {
        let (near, far) = self.roots(ray)?;
        let t = if near >= S::ZERO {
            near
        } else if far >= S::ZERO {
            far
        } else {
            return Err(Miss::Behind);
        };
        ray.hit_at(t)
    }

    /// The two roots `(near, far)` of a ray (unit direction), either of which may be
    /// negative: the near one by `q = −(b ± √Δ)`, the other as `c/q` (no cancellation);
    /// a tangent ray (zero discriminant) gives one double root, no real root is
    /// [`Miss::NoRoot`].
    ///
    /// # Errors
    /// [`Miss::NoRoot`], or [`Miss::OutOfRange`] when a quantity does not fit the format.
    pub fn roots(&self, ray: &Ray<S>) -> Result<(S, S), Miss> {
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
        Ok((near, far))
    }

    /// Whether the segment from `from` to `from + l` (a shadow segment, `ll = l·l`)
    /// meets the sphere strictly between its ends, from signs and exact product
    /// comparisons only: no square root, no division. With `oc = from − centre`,
    /// `f(u) = |oc + u·l|² − r² = ll·u² + 2b·u + f₀` (`b = oc·l`, `f₀ = |oc|² − r²`,
    /// `f₁ = f(1) = f₀ + 2b + ll`):
    ///
    /// - `from` inside (`f₀ < −band`): it meets the sphere when the light is outside
    ///   (`f₁ > 0`);
    /// - `from` outside (`f₀ > band`): when the light is inside (`f₁ < 0`), or both ends
    ///   are outside and the vertex `u* = −b/ll` lies in (0, 1) with `f(u*) < 0`:
    ///   `b < 0`, `−b < ll` and `b² > ll·f₀`;
    /// - `from` on the surface (`|f₀| ≤ band`, `band = tol·(2r + tol)`: within `tol` of
    ///   it, a hit point on this sphere): the root at 0 is the point itself, the other
    ///   is `−2b/ll`, and it meets the sphere when that lies in (0, 1): `b < 0`,
    ///   `−2b < ll` (the segment goes through the sphere, as from the inside of a
    ///   sphere the eye is in).
    ///
    /// `None` when a quantity does not fit the format (a sphere far from `from`): the
    /// caller then decides by intersecting the ray.
    pub fn meets_segment(&self, from: Vec3<S>, l: Vec3<S>, ll: S, tol: S) -> Option<bool> {
        let (b, f0) = self.segment_terms(from, l)?;
        let band = self
            .radius
            .checked_add(self.radius)?
            .checked_add(tol)?
            .checked_mul(tol)?;
        if f0.abs() <= band {
            return Some(b < S::ZERO && b.checked_add(b)?.checked_neg()? < ll);
        }
        let f1 = f0.checked_add(b)?.checked_add(b)?.checked_add(ll)?;
        if f0 < S::ZERO {
            return Some(f1 > S::ZERO);
        }
        if f1 < S::ZERO {
            return Some(true);
        }
        Some(
            b < S::ZERO
                && b.checked_neg()? < ll
                && S::cmp_products(b, b, ll, f0) == Some(core::cmp::Ordering::Greater),
        )
    }

    /// The segment's terms of both segment tests: `b = (from − c)·l` and
    /// `f₀ = |from − c|² − r²` (one wide step).
    fn segment_terms(&self, from: Vec3<S>, l: Vec3<S>) -> Option<(S, S)> {
        let oc = from.diff(self.center)?;
        let b = oc.dot(l)?;
        let f0 = S::sub_dot3(self.radius_sq, oc.to_array(), oc.to_array())?.checked_neg()?;
        Some((b, f0))
    }

    /// Whether the near root of the ray from `from` towards `from + l` lies in `[0, 1)`
    /// with a positive discriminant (the course's shadow test, `COURSE-RULES.md` §5, §7:
    /// the near root of [`Sphere::roots`] ahead and before the light), from signs and
    /// exact product comparisons: with `b`, `f₀`, `f₁` as in [`Sphere::meets_segment`],
    /// the near root is not negative when `b ≤ 0` and `f₀ ≥ 0` (`from` not inside), and
    /// it lies before the light when `−b < ll` or the light is inside (`f₁ < 0`). `None`
    /// when a quantity does not fit the format.
    pub fn meets_segment_near(&self, from: Vec3<S>, l: Vec3<S>, ll: S) -> Option<bool> {
        let (b, f0) = self.segment_terms(from, l)?;
        if b > S::ZERO
            || f0 < S::ZERO
            || S::cmp_products(b, b, ll, f0) != Some(core::cmp::Ordering::Greater)
        {
            return Some(false);
        }
        if b.checked_neg()? < ll {
            return Some(true);
        }
        Some(f0.checked_add(b)?.checked_add(b)?.checked_add(ll)? < S::ZERO)
    }

    /// Where the segment from `from` to `from + l` (`ll = l·l`) enters the sphere, as a
    /// share `s` of the segment (`from + s l` is the entry point): the near root
    /// `f₀ / (√(b² − ll f₀) − b)` with `b = (from − c)·l` and `f₀ = |from − c|² − r²`
    /// (no cancellation: it is asked of a segment that meets the sphere, `b < 0`).
    /// `None` when the segment does not enter it ahead of `from` or a quantity does not
    /// fit the format.
    pub fn segment_entry(&self, from: Vec3<S>, l: Vec3<S>, ll: S) -> Option<S> {
        let (b, f0) = self.segment_terms(from, l)?;
        if b >= S::ZERO || f0 < S::ZERO {
            return None;
        }
        let disc = b.checked_mul(b)?.checked_sub(ll.checked_mul(f0)?)?;
        let root = disc.checked_sqrt()?.checked_sub(b)?;
        f0.checked_div(root)
    }

    /// Where the line through `from` along the unit direction `u` crosses the sphere at
    /// its near root `s = −(b + √(b² − f₀))` (`b = (from − c)·u`, `f₀ = |from − c|² − r²`),
    /// which may lie behind `from`: for a point on the surface and a direction leaving
    /// it (`b > 0`), the line's other crossing. The two terms of the sum have one sign
    /// (no cancellation). `None` when the line misses or a quantity does not fit.
    pub fn near_crossing(&self, from: Vec3<S>, u: Vec3<S>) -> Option<Vec3<S>> {
        let (b, f0) = self.segment_terms(from, u)?;
        let disc = b.checked_mul(b)?.checked_sub(f0)?;
        if disc < S::ZERO {
            return None;
        }
        let s = b.checked_add(disc.checked_sqrt()?)?.checked_neg()?;
        from.sum(u.scale(s)?)
    }

    /// The outward unit normal at a point on the surface: `(P − C)·(1/r)` (three
    /// products: `1/r` is kept with the sphere), components clamped to [−1, 1], where
    /// `|P − C|²` is within `r²/64` of `r²` (the point is on the surface to within about
    /// 1 % of the radius, as hits are: its length is then 1 within about 1 %, plus
    /// `1/r`'s rounding); otherwise, or when `1/r` or `r²` has too few significant bits
    /// in the format (a radius beyond 256 or below ⅛ in I16F16, beyond 16 or below ½ in
    /// I20F12), `(P − C)` normalised ([`Vec3::unit`]: a square root and three to six
    /// divisions, which on a Cortex-M0 cost about twenty times as much). Either way the
    /// direction carries the point's error divided by `r`.
    pub fn normal_at(&self, point: Vec3<S>) -> Option<Vec3<S>> {
        self.normal_and_excess(point).map(|(normal, _)| normal)
    }

    /// [`Sphere::normal_at`], with `r² − |P − C|²` (one rounding) where the normal is
    /// the three products' (`1/r` kept, the point on the surface): then `1/r ≥ 256·DELTA`,
    /// `r² ≥ 1024·DELTA` and `|P − C| ≤ 1.0093·r`, so that each component of the normal
    /// lies within `1/64` of `(P − C)/r` in a fixed format (`1/r`'s truncation at most
    /// `1.0093/256`, the product's rounding a DELTA, the clamp at most `0.0093` and a
    /// DELTA: the fast kernel's own-sphere shadow test rests on it, `kernel/shading.rs`).
    /// Out of line: one copy for both (flash).
    #[inline(never)]
    pub(crate) fn normal_and_excess(&self, point: Vec3<S>) -> Option<(Vec3<S>, Option<S>)> {
        let (d, k) = (point.diff(self.center)?, self.inv_radius);
        if k <= S::ZERO {
            return Some((d.unit()?, None));
        }
        // |d|² within r²/64 of r² (one rounding): the point is on the surface.
        let excess = S::sub_dot3(self.radius_sq, d.to_array(), d.to_array());
        let on_surface = excess
            .and_then(|e| e.abs().checked_mul_int(64))
            .is_some_and(|e| e <= self.radius_sq);
        if !on_surface {
            return Some((d.unit()?, None));
        }
        let (one, minus_one) = (S::ONE, S::ONE.checked_neg()?);
        let c = |v: S| -> Option<S> { Some(v.checked_mul(k)?.min(one).max(minus_one)) };
        Some((Vec3::new(c(d.x)?, c(d.y)?, c(d.z)?), excess))
    }

    fn magnitude(&self, ray: &Ray<S>, hit: &Hit<S>) -> S {
        ray.base
            .max_abs()
            .max(hit.point.max_abs())
            .max(self.center.max_abs())
            .max(self.radius)
    }

    /// A secondary ray leaving a hit on the sphere in direction `dir`: based off the
    /// surface along the sphere's normal by the bound of [`super::Plane::spawn`], the
    /// normal normalised (the bound is along a unit vector; [`Sphere::normal_at`] is one
    /// only to about 1 %). `None` when the offset base does not fit the format.
    pub fn spawn(&self, ray: &Ray<S>, hit: &Hit<S>, dir: Vec3<S>) -> Option<Ray<S>> {
        spawn_along(
            hit,
            hit.point.diff(self.center)?.unit()?,
            dir,
            self.magnitude(ray, hit),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I20F12, I32F32};

    use crate::num::unit_reals as uniform;

    /// The normal by `1/r` is the normalised one's within a few DELTAs (relative to the
    /// error the point's rounding carries, `DELTA/r` a component) at points on the
    /// surface, and a point off the surface (where `(P − C)/r` is not a unit vector)
    /// takes the normalised one: unit length either way, for radii from 1/64 (below
    /// the formats' floors for the product: normalised) to 3¼.
    #[test]
    fn the_normal_by_the_reciprocal_radius_is_unit_on_and_off_the_surface() {
        fn check<S: Scalar>() {
            let mut next = uniform(0x2026_1205);
            let ulp = S::DELTA.to_f64().max(f64::from(f32::EPSILON));
            let mut worst = 0.0f64;
            for case in 0..2_000 {
                let c = [0; 3].map(|_| 8.0 * next() - 4.0);
                let r = if case % 3 == 0 {
                    1.0 / 64.0 + 0.5 * next()
                } else {
                    0.25 + 3.0 * next()
                };
                let dir = [0; 3].map(|_| next() - 0.5);
                let len = dir.iter().map(|v| v * v).sum::<f64>().sqrt();
                // On the surface, or (every fourth case) at twice the radius.
                let k = if case % 4 == 0 { 2.0 } else { 1.0 };
                let p = [0, 1, 2].map(|i| c[i] + k * r * dir[i] / len);
                let to = |v: [f64; 3]| {
                    Vec3::new(
                        S::from_f64(v[0]).unwrap(),
                        S::from_f64(v[1]).unwrap(),
                        S::from_f64(v[2]).unwrap(),
                    )
                };
                let sphere = Sphere::new(to(c), S::from_f64(r).unwrap()).unwrap();
                let n = sphere.normal_at(to(p)).unwrap();
                let n = [n.x.to_f64(), n.y.to_f64(), n.z.to_f64()];
                let length = n.iter().map(|v| v * v).sum::<f64>().sqrt();
                assert!(
                    (length - 1.0).abs() <= 16.0 * ulp / r.min(1.0),
                    "{} case {case}: |n| = {length}",
                    S::NAME
                );
                for i in 0..3 {
                    let err = (n[i] - dir[i] / len).abs();
                    assert!(
                        err <= 16.0 * ulp / r.min(1.0),
                        "{} case {case}: component {i} off by {err:e}",
                        S::NAME
                    );
                    worst = worst.max(err / ulp);
                }
            }
            std::println!("{}: worst normal component error {worst:.1} ulps", S::NAME);
        }
        check::<I16F16>();
        check::<I20F12>();
        check::<I32F32>();
        check::<f32>();
        // Small spheres, points a little off the surface and one DELTA from the centre:
        // where `r²` has few bits its rounding would pass points far off the surface, so
        // those spheres' normals are normalised (unit length within 2⁻⁶).
        fn small<S: Scalar>() {
            for r in [1.0 / 1024.0, 1.0 / 256.0, 0.05, 0.1, 0.3] {
                let c = Vec3::new(S::ONE, S::ONE, S::ONE);
                let sphere = Sphere::new(c, S::from_f64(r).unwrap()).unwrap();
                for k in [0.0, 0.96, 1.0, 1.04] {
                    for dir in [[1.0, 0.0, 0.0], [0.6, -0.8, 0.0], [0.48, 0.6, 0.64]] {
                        let off = dir.map(|v: f64| S::from_f64(k * r * v).unwrap());
                        let off = if k == 0.0 {
                            Vec3::new(S::DELTA, S::ZERO, S::ZERO)
                        } else {
                            Vec3::new(off[0], off[1], off[2])
                        };
                        let Some(n) = sphere.normal_at(c.sum(off).unwrap()) else {
                            continue;
                        };
                        let len = [n.x, n.y, n.z]
                            .map(|v| v.to_f64() * v.to_f64())
                            .iter()
                            .sum::<f64>()
                            .sqrt();
                        assert!(
                            (len - 1.0).abs() < 1.0 / 64.0,
                            "{} r = {r}, {k}·r along {dir:?}: |n| = {len}",
                            S::NAME
                        );
                    }
                }
            }
        }
        small::<I16F16>();
        small::<I20F12>();
        small::<I32F32>();
    }
}
