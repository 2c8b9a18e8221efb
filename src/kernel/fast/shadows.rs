//! What shadow segments from a plane hit need of the frame: every plane's side at the
//! hit (one product each), and the quiet planes of a scanline, which no shadow segment
//! from a hit on it can be stopped by.

use heapless::Vec;

use super::step::Row;
use super::{FAST_OBJECTS, Primary};
use crate::shade::SideBits;
use crate::{Scalar, SceneView, Shape};

/// The quiet planes of a scanline ([`Primary::quiet_planes`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Quiet<S> {
    /// The objects that are not quiet, as bits (one per object; all of them, `u8::MAX`,
    /// where the frame has another object than planes).
    pub(crate) loud: u8,
    /// Up to which `t'` the others are.
    pub(crate) t_max: S,
}

impl<S: Scalar> Default for Quiet<S> {
    fn default() -> Self {
        Self {
            loud: u8::MAX,
            t_max: S::ZERO,
        }
    }
}

impl<S: Scalar> Primary<S> {
    /// `D'_i − N_i·P` of every plane at the hit `P = eye + t'·D` of the row's current
    /// pixel: `num_i − t'·(N_i·D)`, one product each. `None` when one does not fit (the
    /// shadow segments then compute them). Written into `sides` (a buffer the scanline
    /// keeps: a returned one would be copied whole, capacity and all, per pixel); returned:
    /// which sides are positive and which objects are spheres, as bits
    /// ([`SideBits`]).
    pub(crate) fn sides_at(
        &self,
        row: &Row<S>,
        param: S,
        sides: &mut Vec<S, FAST_OBJECTS>,
    ) -> Option<SideBits> {
        self.sides_but(row, param, usize::MAX, sides)
    }

    /// [`Primary::sides_at`] but for object `own` (the hit's own plane), whose side is
    /// left zero without its product (and its bit clear) where it fits for certain
    /// (`|num| < MAX/2`: `t'·(N·D)` lies within a few DELTAs of `num`, so that
    /// `sides_at` would not have failed on it): for a caller that leaves the hit's own
    /// plane out of its shadow tests (`kernel::shading`).
    #[inline(always)]
    pub(crate) fn sides_but(
        &self,
        row: &Row<S>,
        param: S,
        own: usize,
        sides: &mut Vec<S, FAST_OBJECTS>,
    ) -> Option<SideBits> {
        sides.clear();
        let mut positive = 0u8;
        for (i, (term, &nd)) in self.terms.iter().zip(&row.nd).enumerate() {
            let side = if term.sphere {
                // Not read for a sphere (see `Primary::new`).
                S::ZERO
            } else if i == own && S::MAX.checked_sub(term.num.abs())? > term.num.abs() {
                S::ZERO
            } else {
                term.num.checked_sub(param.checked_mul(nd)?)?
            };
            if side > S::ZERO {
                positive |= 1 << i;
            }
            sides.push(side).ok()?;
        }
        Some(SideBits {
            positive,
            spheres: self.sphere_bits,
            lights: self.light_positive,
        })
    }

    /// The planes that no shadow segment from a plane hit on this scanline can be
    /// stopped by (`Quiet::loud`: the others, as bits), and the largest `t'` for which that holds
    /// (`Quiet::t_max`), where the row's pixels keep every plane out of the epsilon's
    /// margin ([`Primary::clear_of_margin`]); `Quiet::default()` (none) where the frame
    /// has another object than plain and tiled planes, or a quantity does not fit.
    ///
    /// A plane is quiet when the eye and every light lie strictly on one side of it and
    /// so do the screen points of the row's rays (its two ends, the stepped drift
    /// included, by at least 2 DELTAs: `num − N·D` is affine in `D`). Then a ray of the
    /// row does not cross the plane between the eye and the screen; beyond the screen it
    /// would cross it only as an accepted plane (out of the margin the search accepts by
    /// `ahead` alone), at or beyond the hit, the nearest. So the plane's exact side at
    /// the hit (`numᵢ − t'·(N·D)ᵢ` with the hit's exact `t'`) has the eye's sign, the
    /// lights'; the formed one (`sides_at`'s) lies within `(|N·D|ᵢ + 1)·DELTA` of it
    /// (an exact quotient, `KernelArith::EXACT_QUOTIENTS`), inside the segments' tolerance;
    /// so `sides_differ` passes the plane over towards every light, as it does the hit's
    /// own plane (`kernel::shading`). `t_max`: up to it, `t'·(N·D)ᵢ` and the
    /// side fit the format (`sides_at` would not have failed): `|numᵢ| ≤ MAX/4` and
    /// `t'·|N·D|ᵢ ≤ MAX/4`.
    pub(crate) fn quiet_planes(&self, scene: &SceneView<'_, S>, row: &Row<S>) -> Quiet<S> {
        let quiet = || -> Option<Quiet<S>> {
            let quarter = S::MAX.mul_ratio(1, 4)?;
            let margin = S::DELTA.checked_mul_int(2)?;
            let (lo, hi) = self.dx_range(scene, scene.camera.width)?;
            let mut planes = 0u8;
            let mut widest = S::DELTA;
            for (i, term) in self.terms.iter().enumerate() {
                let object = scene.objects.get(usize::from(term.index))?;
                if !matches!(object.shape, Shape::Plane(_) | Shape::Tiled { .. }) {
                    return None;
                }
                let num = term.num;
                if num == S::ZERO || num.abs() > quarter {
                    continue;
                }
                let plane = object.shape.plane()?;
                let n = plane.normal().to_array();
                let lights_aside = scene.lights.iter().all(|l| {
                    S::sub_dot3(plane.offset(), n, l.location.to_array())
                        .is_some_and(|a| a != S::ZERO && (a > S::ZERO) == (num > S::ZERO))
                });
                let mut screen_aside = true;
                for dx in [lo, hi] {
                    let d = [dx, row.dir.y, self.dz];
                    match S::sub_dot3(num, n, d) {
                        Some(v) if (v > S::ZERO) == (num > S::ZERO) && v.abs() >= margin => {
                            // |N·D| at this end: |num − v|.
                            widest = widest.max(num.checked_sub(v)?.abs());
                        }
                        _ => screen_aside = false,
                    }
                }
                if lights_aside && screen_aside {
                    planes |= 1 << i;
                }
            }
            // Every object is a term (at most eight: `FAST_OBJECTS`).
            let all = u8::MAX.checked_shr(u32::try_from(8 - self.terms.len()).ok()?)?;
            Some(Quiet {
                loud: all & !planes,
                t_max: quarter.checked_div(widest)?,
            })
        };
        quiet().unwrap_or_default()
    }

    /// Whether every plane but `own` lies out of the epsilon's margin at the row's
    /// current pixel (`|N·D| ≥` the bound by which the search accepts it by `ahead`
    /// alone, the row's, where it holds).
    #[inline(always)]
    pub(crate) fn clear_of_margin(row: &Row<S>, own: usize) -> bool {
        if row.dir.x.abs() > row.dx_limit {
            return false;
        }
        row.nd
            .iter()
            .enumerate()
            .all(|(i, nd)| i == own || nd.abs() >= row.eps_l1)
    }
}
