//! Where secondary rays start: off the surface they leave by a computed bound on how far
//! a hit point lies off it (pbrt's offset by an error bound, not a magic number).

use super::{Hit, Ray, RayKind, Vec3};
use crate::Scalar;

/// Units of [`Scalar::ulp`] in the hit-point residual bound ([`super::Plane::residual_bound`]):
/// the constant part. For fixed formats the rounding terms are: the wide `D' − N·b`
/// (½), the division (1 × |N·d| ≤ 1), the hit point's components (√3 in total), and the
/// rounding of `N·d` (½ per unit of t: the `9t/16` part, ½ × 1/(1 − ½/8) for an epsilon
/// of at least 8 DELTAs), about 3.3 in all; floats round their three-term dot products
/// more often, so 8 covers both with margin. `tests/properties.rs` measures the largest
/// residual against this bound in every format.
pub const RESIDUAL_ULPS: i32 = 8;

/// Units of [`Scalar::ulp`] that [`super::Plane::spawn`] adds beyond the residual bound, for the
/// rounding of the offset base itself (√3 for its components) and of its re-evaluation
/// (½), with margin.
pub const SPAWN_MARGIN_ULPS: i32 = 4;

/// The residual bound of [`super::Plane::residual_bound`] for a hit at distance `t` among values
/// of magnitude up to `m`: `(9t/16 + RESIDUAL_ULPS) × ulp(max(1, t, m))`.
pub(crate) fn residual<S: Scalar>(t: S, m: S) -> Option<S> {
    let m = S::ONE.max(t).max(m);
    t.mul_ratio(9, 16)?
        .checked_add(S::from_i32(RESIDUAL_ULPS)?)?
        .checked_mul(m.ulp())
}

/// How far a hit point at distance `t` among values of magnitude up to `m` may lie off
/// its surface, with the margin of a spawned ray: `(t + RESIDUAL_ULPS +
/// SPAWN_MARGIN_ULPS) × ulp(max(1, t, m))`, at least [`residual`] plus the margin
/// [`offset_base`] adds (`t` for its `9t/16`: no division, a per-pixel one on a chip
/// without a divide instruction). The tolerance of the segment shadow tests
/// ([`super::Shape::meets_segment`]).
pub(crate) fn surface_tolerance<S: Scalar>(t: S, m: S) -> Option<S> {
    let m = S::ONE.max(t).max(m);
    t.checked_add(S::from_i32(RESIDUAL_ULPS + SPAWN_MARGIN_ULPS)?)?
        .checked_mul(m.ulp())
}

/// Whether [`surface_tolerance`]`(t, m)` fits the format, without forming it, in the
/// fixed formats (`KernelArith::EXACT_SUMS`; `false` in the others: form it), whose `ulp` is
/// `DELTA` at every magnitude: the tolerance is then `(t + c)·DELTA`, no larger than
/// `t + c` for `t ≥ 0`, and fits wherever that sum does.
#[inline]
pub(crate) fn surface_tolerance_fits<S: Scalar>(t: S) -> bool {
    S::EXACT_SUMS
        && t >= S::ZERO
        && S::from_i32(RESIDUAL_ULPS + SPAWN_MARGIN_ULPS)
            .and_then(|c| t.checked_add(c))
            .is_some()
}

/// Moves `point` along the unit `normal`, to the side `dir` points to, by `bound` plus
/// [`SPAWN_MARGIN_ULPS`] (at magnitude `m`): the base of a secondary ray that cannot
/// meet the surface it leaves. A `dir` tangent to the surface keeps the point.
pub(crate) fn offset_base<S: Scalar>(
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

/// A secondary ray leaving `hit` of a curved surface in direction `dir`, based off it
/// along its unit `normal` there by [`residual`] at magnitude `m` (spheres and surfaces of
/// revolution); `None` when the offset base does not fit the format.
pub(crate) fn spawn_along<S: Scalar>(
    hit: &Hit<S>,
    normal: Vec3<S>,
    dir: Vec3<S>,
    m: S,
) -> Option<Ray<S>> {
    let bound = residual(hit.t, m)?;
    let base = offset_base(hit.point, normal, dir, bound, m)?;
    Some(Ray {
        base,
        dir,
        kind: RayKind::Secondary,
    })
}
