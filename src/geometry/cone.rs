//! A sphere's shadow cone from a light ([`ShadowCone`]) and its part on one scanline
//! ([`RowCone`]): the points whose segment to the light certainly misses the sphere
//! (outside the cone widened), and those whose segment certainly meets it (inside the
//! cone narrowed, beyond the sphere), each decided without the exact segment test.

use super::Sphere;
use crate::Scalar;
use crate::geometry::Vec3;

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
    /// `r²`, for [`ShadowCone::clears_line`], [`ShadowCone::shadow_span`] and the umbra
    /// ([`ShadowCone::in_row`]).
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
    /// ([`RowCone`]), whose hits' segment tolerances are at most `tol`: `None` when
    /// `u.y·ly + u.z·lz` does not fit, or when a component of `u` is beyond half the
    /// format's range. Its umbra ([`RowCone::blocks`]) is kept where the tolerance's
    /// band on the sphere, `(2r + tol)·tol`, is at most `(|u|² − r²)/2`.
    pub(crate) fn in_row(&self, ly: S, lz: S, tol: S) -> Option<RowCone<S>> {
        let half = S::MAX.mul_ratio(1, 2)?;
        let u = self.u;
        (u.x.abs() <= half && u.y.abs() <= half && u.z.abs() <= half).then_some(())?;
        let yz = S::acc_add(S::acc_mul(u.y, ly)?, S::acc_mul(u.z, lz)?)?;
        Some(RowCone {
            near: self.near,
            ux: u.x,
            k: self.k,
            k_in: self.umbra(tol).unwrap_or(S::MAX),
            yz,
        })
    }

    /// The umbra's `|u|² − (7/8)·r²` ([`RowCone::blocks`]) for hits whose segment
    /// tolerance is at most `tol`: `None` where `16·|u|²` does not fit the format (the
    /// exact test's quantities are then not bounded) or the tolerance's band on the
    /// sphere, `(2r + tol)·tol`, may be more than `(|u|² − r²)/2` (checked as
    /// `(r² + 1 + tol)·tol`, no less: `2r ≤ r² + 1`). `|u|²` is `k + (9/8)r²` to a
    /// rounding, far inside the umbra's margin.
    fn umbra(&self, tol: S) -> Option<S> {
        let rr = self.rr;
        let uu = self.k.checked_add(rr.mul_ratio(9, 8)?)?;
        uu.checked_mul_int(16)?;
        let band = rr.checked_add(S::ONE)?.checked_add(tol)?.checked_mul(tol)?;
        (band <= uu.checked_sub(rr)?.mul_ratio(1, 2)?).then_some(())?;
        uu.checked_sub(rr.mul_ratio(7, 8)?)
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
    /// The interval holds the points whose line to the light passes within `r·√(5/4)` of
    /// the centre and those nearer the light than half the centre's distance, which take
    /// the exact test. The cone of `r·√(5/4)` holds the one of `r·√(9/8)` outside which
    /// [`ShadowCone::clears`] certifies a point clear with a margin of `r²/8 ≥ 512 DELTA`
    /// in squared distance from the centre: the margin `clears` keeps over the sphere
    /// itself, far more than its comparison's rounding. With `B = wy·u.y + wz·u.z`,
    /// `m = wy² + wz²` and `K = |u|² − (5/4)r²`, the first are `(s·u.x + B)² ≥ K(s² + m)`:
    /// with `A = u.x² − K < 0`, between the roots `s = (−u.x·B ± √K·√(B² + A·m))/A`; the
    /// second are `s² < |u|²/4 − m`. Their hull is widened by `(|s| + 1)/64` at each end,
    /// far more than this computation's roundings (a few `DELTA` on quantities of the
    /// scene's size). Where the cone of `r·√(9/8)` meets the line, the discriminant
    /// `B² + A·m` is at least `r²·m/8` (the two cones' `A` differ by `r²/8`), so its root
    /// is not taken near zero, where a rounding would move it most; `A` must be below
    /// `−r²/4`, so that the cone of `r·√(9/8)`, whose `A` is `r²/8` lower, is bounded on
    /// the line by a clear margin.
    pub(crate) fn shadow_span(&self, wy: S, wz: S) -> Option<Option<(S, S)>> {
        let u = self.u;
        let uu = u.dot(u)?;
        let rr = self.rr;
        let k = uu.checked_sub(rr.mul_ratio(5, 4)?)?;
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

    /// Whether the cone among `cones` of light `light` and object `object`, if there is
    /// one, clears the segment `(l, ll)` ([`ShadowCone::clears`]): where it does, that
    /// sphere's exact segment test finds the segment clear, and need not be taken.
    #[inline(always)]
    pub(crate) fn any_clears(
        cones: &[Self],
        light: usize,
        object: usize,
        l: Vec3<S>,
        ll: S,
    ) -> bool {
        cones.iter().any(|c| {
            usize::from(c.light) == light && usize::from(c.object) == object && c.clears(l, ll)
        })
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
    /// The umbra's `|u|² − (7/8)·r²` ([`RowCone::blocks`]; `S::MAX`: no umbra).
    k_in: S,
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
        let Some(lu) = self.lu(lx) else {
            return false;
        };
        lu >= S::ZERO || S::cmp_products(lu, lu, ll, self.k) == Some(core::cmp::Ordering::Less)
    }

    /// `l·u` at the row's hit with `l.x = lx`, rounded once (as [`RowCone::clears`]).
    #[inline(always)]
    fn lu(&self, lx: S) -> Option<S> {
        S::acc_mul(lx, self.ux)
            .and_then(|xx| S::acc_add(xx, self.yz))
            .and_then(S::acc_round)
    }

    /// Whether the segment from the row's hit with `l.x = lx`, `|l|² = ll` to the light
    /// certainly meets the sphere: its exact test (`Sphere::meets_segment` with the
    /// row's tolerance, [`ShadowCone::in_row`]) says so, wherever this says `true`. The
    /// mirror of [`RowCone::clears`]: the point lies inside the cone narrowed to
    /// `r·√(7/8)`, beyond the sphere.
    ///
    /// With `s = −l·u` (the centre's projection on the segment, in units of `|l|`), the
    /// exact test's terms are `b = s − ll` and `f₀ = ll − 2s + |u|² − r²`, so that
    /// `b² − ll·f₀ = s² − ll·(|u|² − r²)`. This asks `s² > ll·(|u|² − (7/8)r²)`, which
    /// leaves `ll·r²/8` over the exact test's comparison: the same margin, against the
    /// same roundings (the point at least half the centre's distance from the light,
    /// `ll ≥ |u|²/4`; `r² ≥ 4096 DELTA`), as [`ShadowCone::clears`]' (see its type). It
    /// asks `0 < s` and `17·s < 16·ll` (the segment's point nearest the centre lies
    /// inside it, by a margin of `ll/16 ≥ |u|²/64`, far beyond a rounding: `b < 0` and
    /// `−b < ll`). Every case of the exact test then meets: outside the sphere by this
    /// comparison; inside it because the light is outside (`|u|² − r² ≥ r²/8 + 1/16`);
    /// on its surface within the tolerance's band because `2s − ll = |u|² − r² − f₀` is
    /// at least half of `|u|² − r²` (the band is at most that half, [`ShadowCone::in_row`]),
    /// so `−2b < ll`. With `16·ll` and `16·|u|²` in the format (checked), every quantity
    /// of the exact test fits (`|f₁| ≤ 6 ll + 3|u|² + r²`), so it answers rather than
    /// handing the segment to the ray test.
    #[inline(always)]
    pub(crate) fn blocks(&self, lx: S, ll: S) -> bool {
        let k_in = self.k_in;
        if k_in == S::MAX || ll < self.near || ll.checked_mul_int(16).is_none() {
            return false;
        }
        let Some(s) = self.lu(lx).and_then(S::checked_neg) else {
            return false;
        };
        s > S::ZERO
            && s.checked_mul_int(17)
                .zip(ll.checked_mul_int(16))
                .is_some_and(|(s17, ll16)| s17 < ll16)
            && S::cmp_products(s, s, ll, k_in) == Some(core::cmp::Ordering::Greater)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{I16F16, I20F12, I32F32, Shape};

    use crate::num::unit_reals as uniform;

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

    /// [`RowCone::blocks`] says `true` only where the exact segment test meets the
    /// sphere, with the tolerance the row's cone was made for: points inside the sphere,
    /// on its far surface (some with a tolerance whose band is too wide for the umbra),
    /// between the light and the sphere, and on either side of the narrowed cone's edge
    /// beyond it, some lights near the sphere. Fails when the cone is the sphere's own
    /// widened (`9/8`), the check that the point lies beyond the sphere (`17·s < 16·ll`)
    /// or the band's bound is left out.
    #[test]
    fn a_blocked_shadow_segment_meets_the_sphere_in_every_fixed_format() {
        fn check<S: Scalar>() {
            let mut next = uniform(0x2026_1207);
            let (mut blocked, mut met, mut total) = (0u32, 0u32, 0u32);
            for _ in 0..60_000 {
                let mut point = || [0; 3].map(|_| 20.0 * next() - 10.0);
                let (c, mut light) = (point(), point());
                let radius = 0.25 + 2.0 * next() * next();
                if next() < 0.3 {
                    // A light near the sphere: its power `|u|² − r²` is small.
                    let d = [0; 3].map(|_| next() - 0.5);
                    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    let k = radius * (1.07 + 0.2 * next()) / n;
                    light = [0, 1, 2].map(|i| c[i] + k * d[i]);
                }
                let u = [c[0] - light[0], c[1] - light[1], c[2] - light[2]];
                let norm = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
                let off = [0; 3].map(|_| next() - 0.5);
                let pick = next();
                let p = if pick < 0.25 {
                    // On the far surface, or just off it.
                    let k = radius * (1.0 + 0.02 * (next() - 0.5)) / norm;
                    let side = [0; 3].map(|i| u[i] / norm + 1.5 * off[i]);
                    let len = (side[0] * side[0] + side[1] * side[1] + side[2] * side[2]).sqrt();
                    [0, 1, 2].map(|i| c[i] + k * norm * side[i] / len)
                } else {
                    // Along the cone: before the sphere, inside it, beyond it.
                    let s = 3.0 * next();
                    let w = 2.6 * radius * next();
                    [0, 1, 2].map(|i| light[i] + s * u[i] + s * w * off[i])
                };
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
                // Mostly a hit's tolerance; now and then one whose band is too wide.
                let tol = if next() < 0.9 {
                    S::DELTA.checked_mul_int(64).unwrap()
                } else {
                    S::from_f64(0.6 * radius * next()).unwrap()
                };
                let Some(row) = cone.in_row(l.y, l.z, tol) else {
                    continue;
                };
                total += 1;
                let exact = sphere.meets_segment(from, l, ll, tol);
                met += u32::from(exact == Some(true));
                if row.blocks(l.x, ll) {
                    blocked += 1;
                    assert_eq!(
                        exact,
                        Some(true),
                        "{}: sphere {c:?} r {radius}, light {:?}, point {p:?}, tol {}",
                        S::NAME,
                        light.to_f64(),
                        tol.to_f64()
                    );
                }
            }
            assert!(
                blocked * 2 > met && met * 8 > total,
                "{}: {blocked} blocked, {met} met, of {total}",
                S::NAME
            );
        }
        check::<I16F16>();
        check::<I20F12>();
        check::<I32F32>();
    }
}
