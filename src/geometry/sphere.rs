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

/// A sphere's shadow cone from a light (the fast kernel keeps one per sphere and light,
/// per frame; shading reads them through `PlaneSides`): `u = centre − light` and
/// `k = |u|² − (9/8)r²`. A point `P` (with `l = light − P`, `ll = l·l`) can lie in the
/// sphere's shadow only if the line from the light to `P` passes within `r` of the
/// centre: `s = (P − light)·u > 0` and `s² ≥ ll·(|u|² − r²)`. [`ShadowCone::clears`]
/// tells, from three products and one exact comparison, the points whose line passes
/// farther than `r·√(9/8)` from the centre: most of a frame's pixels, which then skip
/// the sphere's exact segment test.
///
/// Why a cleared point is one the exact test finds clear: at the cone's edge the two
/// sides of `s² < ll·k` differ by `ll·r²/8`, i.e. by `r²/8` in squared distance from
/// the centre. For a point at least half the centre's distance from the light
/// (`4 ll ≥ |u|²`, checked per pixel; nearer points take the exact test) the rounding of
/// `s`, `ll` and `k` moves the comparison by about `6 DELTA` in those units, and the exact
/// test's own rounding by about `90 DELTA` (its `|from − centre|` is at most three times
/// `|l|` there); a cone is kept only for `r² ≥ 4096 DELTA` (`r ≥ 1/4` in I16F16, 1 in
/// I20F12), so `r²/8 ≥ 512 DELTA` covers both with room, and only for a light clearly
/// outside the sphere (`k ≥ 1/16`). In the float formats `DELTA` is the ulp at 1 and the
/// same argument holds relative to the magnitudes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ShadowCone<S> {
    /// The light's index.
    pub(crate) light: u8,
    /// The sphere's index.
    pub(crate) object: u8,
    u: Vec3<S>,
    k: S,
    /// `|u|²/4`, rounded down: the nearest `ll` the shortcut takes.
    near: S,
    /// `r²`, for [`ShadowCone::clears_line`].
    rr: S,
}

impl<S: Scalar> ShadowCone<S> {
    /// The cone of `sphere` from the light at `light` (index `index`), object `object`;
    /// `None` when the shortcut does not apply (see the type's documentation).
    pub(crate) fn new(
        index: usize,
        object: u8,
        sphere: &Sphere<S>,
        light: Vec3<S>,
    ) -> Option<Self> {
        let min_k = S::ONE.mul_ratio(1, 16)?;
        let min_rr = S::DELTA.checked_mul_int(4096)?;
        let u = sphere.center().diff(light)?;
        let uu = u.dot(u)?;
        let rr = sphere.radius_sq();
        let k = uu.checked_sub(rr.mul_ratio(9, 8)?)?;
        (k >= min_k && rr >= min_rr).then_some(())?;
        Some(ShadowCone {
            light: u8::try_from(index).ok()?,
            object,
            u,
            k,
            near: uu.mul_ratio(1, 4)?.checked_sub(S::DELTA)?,
            rr,
        })
    }

    /// The cone's part for one scanline whose hits share `l.y = ly` and `l.z = lz`
    /// ([`RowCone`]): `None` when `u.y·ly + u.z·lz` does not fit, or when a component of
    /// `u` is beyond half the format's range.
    pub(crate) fn in_row(&self, ly: S, lz: S) -> Option<RowCone<S>> {
        let half = S::MAX.mul_ratio(1, 2)?;
        let u = self.u;
        (u.x.abs() <= half && u.y.abs() <= half && u.z.abs() <= half).then_some(())?;
        let yz = S::acc_add(S::acc_mul(u.y, ly)?, S::acc_mul(u.z, lz)?)?;
        Some(RowCone {
            near: self.near,
            ux: u.x,
            k: self.k,
            yz,
        })
    }

    /// Whether every point `P` of the line `P = light + (s, wy, wz)` (any `s`: a
    /// scanline's hits on a plane with `N.x = 0` have one `y` and one `z`) is one whose
    /// exact segment test finds the sphere clear, so that a row of such points skips the
    /// sphere (`kernel/rows/`). Every segment from the light to the line lies in the
    /// plane through the light with normal `n = (0, −wz, wy)`; the line is cleared when
    /// the centre lies farther than `r·√(3/2)` from that plane,
    /// `(wy·u.z − wz·u.y)² > (3/2)·r²·(wy² + wz²)`, and every point of the line is at
    /// least half the centre's distance from the light (`4(wy² + wz²) ≥ |u|² + 1`): then
    /// every one of its segments passes farther than `r·√(3/2)` from the centre, beyond
    /// the `r·√(9/8)` of [`ShadowCone::clears`] with a margin of `3r²/8 ≥ 1536 DELTA`
    /// (a cone has `r² ≥ 4096 DELTA`). This test's own rounding moves its comparison by
    /// a few `DELTA·|u|/|(wy, wz)|` in units of squared distance; with `|(wy, wz)| ≥ 1`
    /// and `|u|² ≤ 4096` (checked; otherwise `false`) that is at most a few hundred
    /// `DELTA`, inside the margin, and for the points the type's documentation covers,
    /// the exact test then finds them clear.
    pub(crate) fn clears_line(&self, wy: S, wz: S) -> bool {
        let check = || -> Option<bool> {
            let uu = self.u.dot(self.u)?;
            let nn = wy.checked_mul(wy)?.checked_add(wz.checked_mul(wz)?)?;
            let far_enough = nn >= S::ONE
                && uu <= S::from_i32(4096)?
                && nn.checked_mul_int(4)? >= uu.checked_add(S::ONE)?;
            if !far_enough {
                return Some(false);
            }
            let k = wy
                .checked_mul(self.u.z)?
                .checked_sub(wz.checked_mul(self.u.y)?)?;
            let rhs = self.rr.checked_mul(nn)?.mul_ratio(3, 2)?;
            Some(k.checked_mul(k)? > rhs)
        };
        check() == Some(true)
    }

    /// Where on the line `P = light + (s, wy, wz)` (every `s`, as in
    /// [`ShadowCone::clears_line`]) a point may be one whose exact segment test meets the
    /// sphere: an interval of `s` holding every such point. `Some(None)`: no point of the
    /// line; `None`: the interval is unbounded or a quantity leaves the format.
    ///
    /// The interval holds the points whose line to the light passes within `r·√(3/2)` of
    /// the centre (wider than the `r·√(9/8)` outside which [`ShadowCone::clears`]
    /// certifies a point clear) and those nearer the light than half the centre's
    /// distance, which take the exact test. With `B = wy·u.y + wz·u.z`, `m = wy² + wz²`
    /// and `K = |u|² − (3/2)r²`, the first are `(s·u.x + B)² ≥ K(s² + m)`: with
    /// `A = u.x² − K < 0`, between the roots `s = (−u.x·B ± √K·√(B² + A·m))/A`; the
    /// second are `s² < |u|²/4 − m`. Their hull is widened by `(|s| + 1)/64` at each end,
    /// far more than this computation's roundings (a few `DELTA` on quantities of the
    /// scene's size); `A` must be below `−r²/4`, so that the cone of `r·√(9/8)`, whose `A`
    /// is `3r²/8` lower, is bounded on the line by a clear margin.
    pub(crate) fn shadow_span(&self, wy: S, wz: S) -> Option<Option<(S, S)>> {
        let u = self.u;
        let uu = u.dot(u)?;
        let rr = self.rr;
        let k = uu.checked_sub(rr.mul_ratio(3, 2)?)?;
        let a = u.x.checked_mul(u.x)?.checked_sub(k)?;
        if k <= S::ZERO || a >= rr.mul_ratio(-1, 4)? {
            return None;
        }
        let b = wy.checked_mul(u.y)?.checked_add(wz.checked_mul(u.z)?)?;
        let m = wy.checked_mul(wy)?.checked_add(wz.checked_mul(wz)?)?;
        let q = b.checked_mul(b)?.checked_add(a.checked_mul(m)?)?;
        let mut span: Option<(S, S)> = None;
        let mut add = |lo: S, hi: S| {
            span = Some(span.map_or((lo, hi), |(l, h)| (l.min(lo), h.max(hi))));
        };
        if q >= S::ZERO {
            let root = k.checked_sqrt()?.checked_mul(q.checked_sqrt()?)?;
            let uxb = u.x.checked_mul(b)?.checked_neg()?;
            // `a < 0`: the root with `+ root` is the smaller.
            let lo = uxb.checked_add(root)?.checked_div(a)?;
            let hi = uxb.checked_sub(root)?.checked_div(a)?;
            add(lo, hi);
        }
        let near = uu.mul_ratio(1, 4)?.checked_sub(m)?;
        if near > S::ZERO {
            let s = near.checked_sqrt()?;
            add(s.checked_neg()?, s);
        }
        let Some((lo, hi)) = span else {
            return Some(None);
        };
        let widen = |v: S| v.abs().checked_add(S::ONE)?.mul_ratio(1, 64);
        Some(Some((
            lo.checked_sub(widen(lo)?)?,
            hi.checked_add(widen(hi)?)?,
        )))
    }

    /// Whether the segment from a point to the light (`l = light − point`, `ll = l·l`)
    /// clearly misses the sphere: the point lies outside its shadow cone. A point
    /// nearer to the light than half the centre's distance (`ll < |u|²/4`) takes the
    /// exact test. Out of line: its products' temporaries stay out of the shadow loop's
    /// frame (the stack of an I32F32 frame on a 16 KB chip).
    #[inline(never)]
    pub(crate) fn clears(&self, l: Vec3<S>, ll: S) -> bool {
        if ll < self.near {
            return false;
        }
        let Some(lu) = l.dot(self.u) else {
            return false;
        };
        // s = −l·u ≤ 0: the nearest point of the segment to the centre is the light.
        lu >= S::ZERO || S::cmp_products(lu, lu, ll, self.k) == Some(core::cmp::Ordering::Less)
    }
}

/// A [`ShadowCone`] on one scanline whose hits share `l.y` and `l.z`
/// ([`ShadowCone::in_row`]): what [`RowCone::clears`] needs, the row's part of `l·u`
/// unrounded (`u.y·l.y + u.z·l.z`) included, and nothing else (a lean row keeps one per
/// cone: an I32F32 scanline's frame on a 16 KB chip).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RowCone<S: Scalar> {
    near: S,
    ux: S,
    k: S,
    yz: S::Acc,
}

impl<S: Scalar> RowCone<S> {
    /// [`ShadowCone::clears`] at the row's hit with `l.x = lx` and `|l|² = ll`: `l·u`
    /// from `l.x` and the row's part, one product. The same answer bit for bit in the
    /// formats whose sums are exact, for `|l.x|` and the row's `|l.y|`, `|l.z|` at most
    /// half the format's range (no partial sum of `l·u` then leaves the double width, in
    /// any order; callers check).
    #[inline(always)]
    pub(crate) fn clears(&self, lx: S, ll: S) -> bool {
        if ll < self.near {
            return false;
        }
        let Some(lu) = S::acc_mul(lx, self.ux)
            .and_then(|xx| S::acc_add(xx, self.yz))
            .and_then(S::acc_round)
        else {
            return false;
        };
        lu >= S::ZERO || S::cmp_products(lu, lu, ll, self.k) == Some(core::cmp::Ordering::Less)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I20F12, I32F32, Shape};

    /// A seeded xorshift stream of values in `[0, 1)` (the same on every run).
    fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut x = seed;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        }
    }

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

    /// `ShadowCone::clears_line` clears only lines whose every point's exact segment
    /// test misses the sphere: on seeded random spheres, lights and lines along x (a third
    /// of them aimed at the sphere's edge as seen from the light, in y and z), for every
    /// cleared line, points along it from far left to far right (every 1/8 unit, and its
    /// nearest point to the light), the exact test says no. It clears a good share.
    #[test]
    fn a_cleared_line_misses_the_sphere_at_every_point_in_every_format() {
        fn check<S: Scalar>() {
            let mut next = uniform(0x2026_1204);
            let (mut cleared, mut total) = (0u32, 0u32);
            for _ in 0..3_000 {
                let mut point = || [0; 3].map(|_| 16.0 * next() - 8.0);
                let (c, light) = (point(), point());
                let radius = 0.05 + 2.0 * next() * next();
                let (mut wy, mut wz) = (16.0 * next() - 8.0, 16.0 * next() - 8.0);
                if next() < 1.0 / 3.0 {
                    // Beyond the sphere, just off its edge in y and z.
                    let s = 1.0 + 2.0 * next();
                    let a = std::f64::consts::TAU * next();
                    let r = radius * (1.0 + 0.6 * next());
                    wy = s * (c[1] - light[1] + r * a.cos());
                    wz = s * (c[2] - light[2] + r * a.sin());
                }
                let v = |a: [f64; 3]| Vec3::<S>::from_f64(a).unwrap();
                let Ok(sphere) = Sphere::new(v(c), S::from_f64(radius).unwrap()) else {
                    continue;
                };
                let light = v(light);
                let Some(cone) = ShadowCone::new(0, 0, &sphere, light) else {
                    continue;
                };
                let (Some(wy), Some(wz)) = (S::from_f64(wy), S::from_f64(wz)) else {
                    continue;
                };
                total += 1;
                if !cone.clears_line(wy, wz) {
                    continue;
                }
                cleared += 1;
                let shape = Shape::Sphere(sphere);
                let tol = S::DELTA.checked_mul_int(64).unwrap();
                let lx = light.x.to_f64();
                for k in -160..=160 {
                    let px = lx + f64::from(k) / 8.0;
                    let Some(px) = S::from_f64(px) else { continue };
                    let Some(from) = light.sum(Vec3::new(px.checked_sub(light.x).unwrap(), wy, wz))
                    else {
                        continue;
                    };
                    let from = Vec3::new(px, from.y, from.z);
                    let Some(l) = light.diff(from) else { continue };
                    let Some(ll) = l.dot(l) else { continue };
                    assert!(
                        !shape.meets_segment(from, l, ll, tol, S::DEFAULT_EPSILON),
                        "{}: sphere {c:?} r {radius}, light {:?}, point {:?}",
                        S::NAME,
                        light.to_f64(),
                        from.to_f64()
                    );
                }
            }
            assert!(
                cleared * 4 > total,
                "{}: {cleared} of {total} cleared",
                S::NAME
            );
        }
        check::<I16F16>();
        check::<I20F12>();
        check::<I32F32>();
        check::<f32>();
        check::<f64>();
    }

    /// `ShadowCone::clears` never passes over a sphere its exact segment test finds in
    /// the way (`Shape::meets_segment`, its fallback for quantities out of range
    /// included): on seeded random spheres (radii 0.01 to 2: the small ones get no cone),
    /// lights and points, a third of them aimed near the cone's edge and a sixth near the
    /// light, whenever it clears, the exact test says no. And it clears a good share of a
    /// wide field (it is worth its products).
    #[test]
    fn a_cleared_shadow_segment_misses_the_sphere_in_every_format() {
        fn check<S: Scalar>() {
            let mut next = uniform(0x2026_1203);
            let (mut cleared, mut total) = (0u32, 0u32);
            for _ in 0..30_000 {
                let mut point = || [0; 3].map(|_| 20.0 * next() - 10.0);
                let (c, light, mut p) = (point(), point(), point());
                let radius = 0.01 + 2.0 * next() * next();
                let pick = next();
                let u = [c[0] - light[0], c[1] - light[1], c[2] - light[2]];
                let off = [next() - 0.5, next() - 0.5, next() - 0.5];
                if pick < 1.0 / 3.0 {
                    // Near the cone's edge: beyond the sphere, just off its tangent line.
                    let s = 1.0 + 2.0 * next();
                    for i in 0..3 {
                        p[i] = light[i] + s * (u[i] + radius * 2.0 * off[i]);
                    }
                } else if pick < 0.5 {
                    // Near the light: short segments, some at half the centre's distance.
                    let s = next();
                    for i in 0..3 {
                        p[i] = light[i] + s * u[i] + off[i];
                    }
                }
                let v = |a: [f64; 3]| Vec3::<S>::from_f64(a).unwrap();
                let Ok(sphere) = Sphere::new(v(c), S::from_f64(radius).unwrap()) else {
                    continue;
                };
                let (light, from) = (v(light), v(p));
                let Some(l) = light.diff(from) else { continue };
                let Some(ll) = l.dot(l) else { continue };
                let Some(cone) = ShadowCone::new(0, 0, &sphere, light) else {
                    continue;
                };
                total += 1;
                if cone.clears(l, ll) {
                    cleared += 1;
                    let tol = S::DELTA.checked_mul_int(64).unwrap();
                    let shape = Shape::Sphere(sphere);
                    assert!(
                        !shape.meets_segment(from, l, ll, tol, S::DEFAULT_EPSILON),
                        "{}: sphere {c:?} r {radius}, light {:?}, point {p:?}",
                        S::NAME,
                        light.to_f64()
                    );
                }
            }
            assert!(
                cleared * 4 > total,
                "{}: {cleared} of {total} cleared",
                S::NAME
            );
        }
        check::<I16F16>();
        check::<I20F12>();
        check::<I32F32>();
        check::<f32>();
        check::<f64>();
    }
}
