//! The nearest hit at a pixel: the plane test in its division-free form, a sphere's
//! near root as a fraction, the search over the terms, a row's level plane decided once,
//! and the winner's hit point (with a scanline's memo of its last still plane's hit).

use core::cmp::Ordering;

use super::step::Row;
use super::{Primary, Term, axis_of};
use crate::{Scalar, SceneView, Shape, Vec3};

/// A scanline's memo of its last still plane's hit ([`Primary::point_in`]): the key
/// (object, `|N·D|`, `D.y`) and its `t'`, `y` and `z`, and the distance bound for the
/// last `2|D|∞`. Kept by the stage sets whose scanlines keep a plane memo
/// (`KernelStages::Memo`).
#[derive(Debug, Clone)]
pub(crate) struct HitMemo<S> {
    /// Whether the last hit was a certified block's: every plane then lies out of the
    /// epsilon's margin at its pixel ([`Primary::certify_block`] checks both ends, and
    /// `|N·D|` is monotone between them).
    pub(crate) certified: bool,
    key: Option<(u8, S, S)>,
    t: S,
    y: S,
    z: S,
    bound: Option<(S, S)>,
}

impl<S: Scalar> Default for HitMemo<S> {
    fn default() -> Self {
        Self {
            certified: false,
            key: None,
            t: S::ZERO,
            y: S::ZERO,
            z: S::ZERO,
            bound: None,
        }
    }
}

/// What the fast path found at one pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastHit<S> {
    /// The object.
    pub index: usize,
    /// The hit point.
    pub point: Vec3<S>,
    /// An upper bound on the world distance `t` (for secondary-ray offsets).
    pub t_bound: S,
    /// The unnormalised ray direction `D`.
    pub dir: Vec3<S>,
    /// The hit's parameter along `D`, `t' = num/(N·D)` (the screen is at 1).
    pub param: S,
}

/// The plane test of the definition for a primary ray with unnormalised direction `D`:
/// `num = D' − N·eye`, `nd = N·D`, `eps_d2 = ε·|D|²`. Accepted unless the ray is parallel
/// within the epsilon, the plane is behind the eye, or the hit lies in front of the screen.
#[inline]
pub(crate) fn accepts<S: Scalar>(num: S, nd: S, eps: S, eps_d2: S) -> bool {
    // Parallel within the epsilon (also catches N·D = 0).
    if S::cmp_products(nd, nd, eps, eps_d2) == Some(Ordering::Less) || nd == S::ZERO {
        return false;
    }
    ahead(num, nd)
}

/// The rest of the plane test for a plane not parallel to the ray: not behind (`t' < 0`;
/// `num = 0` puts the hit at the eye, in front of the screen) and not in front of the
/// screen (`t' < 1`). `false` for `N·D = 0`.
#[inline]
pub(super) fn ahead<S: Scalar>(num: S, nd: S) -> bool {
    nd != S::ZERO && num != S::ZERO && (num > S::ZERO) == (nd > S::ZERO) && num.abs() >= nd.abs()
}

/// `ε·(ax + |dy| + |dz|)` plus two ulps: the bound of [`accepts_bounded`] for every `D`
/// with `|D.x| ≤ ax` (`‖D‖₁` is at most `ax + |dy| + |dz|` there).
pub(super) fn eps_l1_of<S: Scalar>(eps: S, ax: S, dy: S, dz: S) -> Option<S> {
    ax.checked_add(dy.abs())
        .and_then(|s| s.checked_add(dz.abs()))
        .and_then(|s| eps.checked_mul(s))
        .and_then(|b| b.checked_add(b.ulp()))
        .and_then(|b| b.checked_add(b.ulp()))
}

/// [`accepts`] with a bound first: `|N·D| ≥ ε·‖D‖₁` (`eps_l1`, with a margin of two
/// roundings) implies `(N·D)² ≥ ε²·|D|²` since `|D| ≤ ‖D‖₁`, so a plane that far from
/// parallel skips the exact squared test (two double-width products), which only planes
/// within that margin of the epsilon take (`eps_d2` computes `ε·|D|²` for them).
/// `None` when `ε·|D|²` does not fit (the reference path decides).
#[inline(always)]
pub(super) fn accepts_bounded<S: Scalar>(
    num: S,
    nd: S,
    eps: S,
    eps_l1: Option<S>,
    eps_d2: impl FnOnce() -> Option<S>,
) -> Option<bool> {
    match eps_l1 {
        Some(bound) if nd.abs() >= bound => Some(ahead(num, nd)),
        _ => eps_d2().map(|e| accepts(num, nd, eps, e)),
    }
}

/// A sphere's near root along `D` as the fraction `t' = p/q` (`q > 0`), without a
/// division: with `c = |oc|² − r² > 0` (the eye outside), `b = oc·D` and `a = D·D`, the
/// roots are `(−b ± √(b² − a·c))/a`; the ray meets the sphere ahead when `b < 0` and the
/// discriminant is not negative (compared exactly, [`Scalar::cmp_products`]), and the
/// near root is `c/q` with `q = √(b² − ac) − b` (`−b > 0`: no cancellation, as in
/// [`crate::Sphere`]). A root in front of the screen (`t' < 1`) is a miss, as on the
/// reference path. `Ok(None)` for a miss, `Err(())` when the discriminant does not fit
/// the format (the reference path decides).
#[inline]
pub(super) fn sphere_root<S: Scalar>(c: S, b: S, a: S) -> Result<Option<(S, S)>, ()> {
    if b >= S::ZERO {
        return Ok(None);
    }
    // Where products are exact, the sum's sign is the comparison's (`b² ≥ 0 ≥ −a·c`: it
    // cannot overflow), from the two products the discriminant needs anyway.
    if !S::EXACT_PRODUCTS && S::cmp_products(b, b, a, c) == Some(Ordering::Less) {
        return Ok(None);
    }
    let bb = S::acc_mul(b, b).ok_or(())?;
    let ac = S::acc_mul(a, c.checked_neg().ok_or(())?).ok_or(())?;
    let sum = S::acc_add(bb, ac).ok_or(())?;
    if S::EXACT_PRODUCTS && S::acc_negative(sum) {
        return Ok(None);
    }
    let disc = S::acc_round(sum).ok_or(())?;
    let q = disc
        .max(S::ZERO)
        .checked_sqrt()
        .and_then(|root| root.checked_sub(b))
        .ok_or(())?;
    if q <= S::ZERO || c < q {
        // t' = c/q < 1: in front of the screen.
        return Ok(None);
    }
    Ok(Some((c, q)))
}

impl<S: Scalar> Primary<S> {
    /// The nearest accepted plane at the row's current pixel: `Ok(None)` for the
    /// background, `Err(())` when the reference path must decide (the winner does not fit
    /// the format).
    #[allow(clippy::result_unit_err)]
    pub fn nearest(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
    ) -> Result<Option<FastHit<S>>, ()> {
        self.nearest_with(scene, row, None)
    }

    /// [`Primary::nearest`] with a scanline's [`HitMemo`] (the same answer).
    #[allow(clippy::result_unit_err)]
    #[inline(always)]
    pub(crate) fn nearest_with(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
        memo: Option<&mut HitMemo<S>>,
    ) -> Result<Option<FastHit<S>>, ()> {
        let mut memo = memo;
        if let Some(m) = memo.as_deref_mut() {
            m.certified = false;
        }
        match self.search(scene, row)? {
            Some((term, p, q)) => self.hit(scene, row, term, p, q, memo).map(Some).ok_or(()),
            None => Ok(None),
        }
    }

    /// [`Primary::nearest`]'s search: the winning term and its `t' = p/q`, without the
    /// hit point.
    // Out of line where the blocks use it too (`blocks_for`: one copy, on the Cortex-M0
    // whose flash is short; the call is cheap beside the search); elsewhere inlined into
    // `nearest`, its one caller.
    #[cfg_attr(any(no_long_multiply, not(target_os = "none")), inline(never))]
    #[cfg_attr(not(any(no_long_multiply, not(target_os = "none"))), inline(always))]
    #[allow(clippy::type_complexity)]
    pub(super) fn search(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
    ) -> Result<Option<(&Term<S>, S, S)>, ()> {
        let eps = scene.epsilon;
        let d = row.dir;
        let eps_d2 = || d.dot(d).and_then(|d2| eps.checked_mul(d2));
        let eps_l1 = if d.x.abs() <= row.dx_limit {
            Some(row.eps_l1)
        } else {
            eps_l1_of(eps, d.x.abs(), d.y, d.z)
        };
        // `D·D`, for spheres: `D.x²` added to the row's `D.y² + D.z²` (once, when a
        // sphere on this row asks for it).
        let mut dd = None;
        let mut dd = || -> Result<S, ()> {
            if let Some(v) = dd {
                return Ok(v);
            }
            let v = S::acc_round(S::acc_add(row.yz, S::acc_mul(d.x, d.x).ok_or(())?).ok_or(())?)
                .ok_or(())?;
            dd = Some(v);
            Ok(v)
        };
        // The best so far: (term, its t' as the fraction p/q with q > 0).
        let mut best: Option<(&Term<S>, S, S)> = None;
        for (term, &nd) in self.terms.iter().zip(&row.nd) {
            let (p, q) = if term.sphere {
                if row.row < term.rows.0
                    || row.row > term.rows.1
                    || row.column < term.columns.0
                    || row.column > term.columns.1
                {
                    // The row's or the column's plane of rays passes far from the
                    // sphere: `sphere_rows`, `sphere_columns`.
                    continue;
                }
                match sphere_root(term.num, nd, dd()?)? {
                    Some(pq) => pq,
                    None => continue,
                }
            } else {
                if !accepts_bounded(term.num, nd, eps, eps_l1, eps_d2).ok_or(())? {
                    continue;
                }
                (term.num.abs(), nd.abs())
            };
            if let Some((_, b_p, b_q)) = best
                && S::cmp_products(p, b_q, b_p, q) != Some(Ordering::Less)
            {
                continue;
            }
            if let Some(shape @ (Shape::Finite(_) | Shape::Textured(_) | Shape::Triangle(_))) =
                scene.objects.get(usize::from(term.index)).map(|o| &o.shape)
            {
                let (point, _, _) = self.point(scene, p, q, d).ok_or(())?;
                if !shape.bounds_contain(point) {
                    continue;
                }
            }
            best = Some((term, p, q));
        }
        Ok(best)
    }

    /// [`Primary::nearest`] at a pixel of a row whose planes [`Primary::level_row`]
    /// decided once: `level`, the row's plane (its object, `t' = p/q` and `t'`), or
    /// `None` when no plane is accepted on the row. Only the spheres are tested; the
    /// level plane takes its place among the terms with its fraction (the other planes
    /// are farther, or as far and later: never `nearest`'s winner, nor do they change
    /// which of the others wins), so the winner is `nearest`'s. `Ok(None)`: the
    /// background; `Ok(Some(None))`: the level plane, whose point `nearest` forms and
    /// this checks fits without forming it (its `y` and `z` are the row's); `Err(())`
    /// where `nearest` says `Err`.
    #[allow(clippy::result_unit_err, clippy::type_complexity)]
    pub(crate) fn nearest_over_level(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
        level: Option<(usize, (S, S), S)>,
    ) -> Result<Option<Option<FastHit<S>>>, ()> {
        let d = row.dir;
        let mut dd = None;
        let mut dd = || -> Result<S, ()> {
            if let Some(v) = dd {
                return Ok(v);
            }
            let v = S::acc_round(S::acc_add(row.yz, S::acc_mul(d.x, d.x).ok_or(())?).ok_or(())?)
                .ok_or(())?;
            dd = Some(v);
            Ok(v)
        };
        // The best so far: (its term, or `None` for the level plane; its t' = p/q).
        let mut best: Option<(Option<&Term<S>>, S, S)> = None;
        for (term, &nd) in self.terms.iter().zip(&row.nd) {
            let (candidate, p, q) = if term.sphere {
                if row.row < term.rows.0
                    || row.row > term.rows.1
                    || row.column < term.columns.0
                    || row.column > term.columns.1
                {
                    continue;
                }
                match sphere_root(term.num, nd, dd()?)? {
                    Some((p, q)) => (Some(term), p, q),
                    None => continue,
                }
            } else {
                match level {
                    Some((index, (p, q), _)) if index == usize::from(term.index) => (None, p, q),
                    _ => continue,
                }
            };
            if let Some((_, b_p, b_q)) = best
                && S::cmp_products(p, b_q, b_p, q) != Some(Ordering::Less)
            {
                continue;
            }
            best = Some((candidate, p, q));
        }
        match best {
            None => Ok(None),
            Some((Some(term), p, q)) => self
                .hit(scene, row, term, p, q, None)
                .map(|h| Some(Some(h)))
                .ok_or(()),
            Some((None, _, _)) => {
                // As `Primary::point` forms it: `x = eye.x + t'·D.x` and `t'·2|D|∞`.
                let t = level.map(|(_, _, t)| t).ok_or(())?;
                let x = t
                    .checked_mul(d.x)
                    .and_then(|v| scene.camera.viewpoint.x.checked_add(v));
                let bound = d
                    .max_abs()
                    .checked_add(d.max_abs())
                    .and_then(|m| t.checked_mul(m));
                match (x, bound) {
                    (Some(_), Some(_)) => Ok(Some(None)),
                    _ => Err(()),
                }
            }
        }
    }

    /// The nearest plane of scanline `row` when every plane's `N·D` is the same at each
    /// of its pixels (`N.x = 0`: the row's `N·D` steps by `N.x × step = 0`) and every
    /// plane's test decides the same at each of them: `Some((object, p, q))` with the
    /// winner's `t' = p/q`, `Some` of `None` when no plane is accepted, and `None` when the
    /// row cannot be decided once (a plane with `N.x ≠ 0`, or one within the margin of the
    /// epsilon at some pixel of the row, `N·D = 0` included: [`nearest`](Self::nearest)
    /// then decides each pixel). `first` is the row started at column 0, `width` its
    /// pixels. Spheres are left out: the caller tests them inside their screen boxes, or
    /// their chords of the row ([`Self::sphere_chords_on_row`]). The same tests and the same tie rule as
    /// `nearest`, so that a pixel's plane is `nearest`'s (`kernel/rows/`).
    pub(crate) fn level_row(
        &self,
        scene: &SceneView<'_, S>,
        first: &Row<S>,
        width: u16,
    ) -> Option<Option<(usize, S, S)>> {
        let eps = scene.epsilon;
        let eye_x = scene.camera.viewpoint.x;
        // The largest |D.x| of the row, with the drift of the stepped coordinate.
        let last = scene
            .camera
            .screen_x(width.checked_sub(1)?)?
            .checked_sub(eye_x)?;
        let widest = first.dir.x.abs().max(last.abs());
        let widest = self.resync_span.and_then(|m| m.checked_add(widest))?;
        let bound = eps_l1_of(eps, widest, first.dir.y, first.dir.z)?;
        let mut best: Option<(&Term<S>, S, S)> = None;
        for (term, &nd) in self.terms.iter().zip(&first.nd) {
            if term.sphere {
                continue;
            }
            if axis_of(scene, term.index)?.x != S::ZERO {
                return None;
            }
            // Accepted at every pixel, or at none (`N·D = 0`); otherwise each pixel decides.
            // (`N·D = 0` too: a pixel rejects it only after forming `ε·|D|²`, which may
            // not fit and hand the pixel to the reference path.)
            if nd.abs() < bound {
                return None;
            }
            if !ahead(term.num, nd) {
                continue;
            }
            let (p, q) = (term.num.abs(), nd.abs());
            if let Some((_, b_p, b_q)) = best
                && S::cmp_products(p, b_q, b_p, q) != Some(Ordering::Less)
            {
                continue;
            }
            if !matches!(
                scene.objects.get(usize::from(term.index)).map(|o| &o.shape),
                Some(Shape::Plane(_) | Shape::Tiled { .. })
            ) {
                return None;
            }
            best = Some((term, p, q));
        }
        Some(best.map(|(term, p, q)| (usize::from(term.index), p, q)))
    }

    /// The hit of `term` at the row's current pixel, its `t' = p/q`: the point, its
    /// distance bound and `t'` ([`Primary::nearest`]'s, and a certified block's winner's).
    /// `None` where they do not fit (`nearest` then says `Err`).
    #[inline(always)]
    pub(super) fn hit(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
        term: &Term<S>,
        p: S,
        q: S,
        memo: Option<&mut HitMemo<S>>,
    ) -> Option<FastHit<S>> {
        let d = row.dir;
        let still = self.still & 1u8.checked_shl(u32::from(term.index)).unwrap_or(0) != 0;
        let (point, t_bound, param) = match memo {
            Some(m) if still => self.point_in(scene, term.index, p, q, d, m)?,
            _ => self.point(scene, p, q, d)?,
        };
        Some(FastHit {
            index: usize::from(term.index),
            point,
            t_bound,
            dir: d,
            param,
        })
    }

    /// [`Primary::point`] for a still term (`N.x = 0`, object `index`), with a scanline's
    /// memo of the last one: the same operations, bit for bit, where the memo holds
    /// this term's `t' = p/q` for this `q` and `D.y` (along a scanline a still plane's
    /// `N·D` does not change, a back wall's nowhere in the frame): its `t'` and the
    /// hit's `y` and `z` are kept, and the distance bound for the last `2|D|∞`; a pixel
    /// forms its hit's `x` alone.
    #[inline(never)]
    pub(super) fn point_in(
        &self,
        scene: &SceneView<'_, S>,
        index: u8,
        p: S,
        q: S,
        d: Vec3<S>,
        memo: &mut HitMemo<S>,
    ) -> Option<(Vec3<S>, S, S)> {
        let eye = scene.camera.viewpoint;
        if memo.key != Some((index, q, d.y)) {
            memo.key = None;
            let t = p.checked_div(q)?;
            memo.y = eye.y.checked_add(t.checked_mul(d.y)?)?;
            memo.z = eye.z.checked_add(t.checked_mul(d.z)?)?;
            memo.t = t;
            memo.bound = None;
            memo.key = Some((index, q, d.y));
        }
        let t = memo.t;
        let x = eye.x.checked_add(t.checked_mul(d.x)?)?;
        let twice = d.max_abs().checked_add(d.max_abs())?;
        let t_bound = match memo.bound {
            Some((k, b)) if k == twice => b,
            _ => {
                let b = t.checked_mul(twice)?;
                memo.bound = Some((twice, b));
                b
            }
        };
        Some((Vec3::new(x, memo.y, memo.z), t_bound, t))
    }

    /// The hit point `eye + t'·D` of a term, a bound on its world distance, and `t'`.
    pub(super) fn point(
        &self,
        scene: &SceneView<'_, S>,
        p: S,
        q: S,
        d: Vec3<S>,
    ) -> Option<(Vec3<S>, S, S)> {
        let t = p.checked_div(q)?;
        let point = scene.camera.viewpoint.sum(d.scale(t)?)?;
        // |D| ≤ √3 |D|∞ < 2 |D|∞: the world distance t'·|D| is below t'·2|D|∞.
        let t_bound = t.checked_mul(d.max_abs().checked_add(d.max_abs())?)?;
        Some((point, t_bound, t))
    }
}
