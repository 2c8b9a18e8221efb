//! Stepping along a scanline: a row's unnormalised direction `D` and every term's `N·D`
//! (or `oc·D`), kept as unrounded sums and stepped by the per-frame `N.x × step` from
//! pixel to pixel, restarted from the exact screen coordinate every [`resync_pixels`].

use heapless::Vec;

use super::blocks::Blocks;
use super::search::eps_l1_of;
use super::{FAST_OBJECTS, Primary, axis_of};
use crate::{Scalar, SceneView, Vec3};

/// The most pixels a scanline steps `D.x` by addition before restarting from the exact
/// screen coordinate ([`resync_pixels`]; a multiple of every format's).
pub const RESYNC_PIXELS: u16 = 16;

/// How many pixels a scanline of format `S` steps `D.x` by addition before restarting
/// from the exact screen coordinate (one `mul_ratio`, a 64-bit division): the trade
/// between the drift of the stepped coordinate (≤ ½ DELTA per step), the cost of the
/// exact one, and how long a certified block can be ([`Primary::certify_block`]: at
/// most this many pixels). 16 in the formats with at least 16 fraction bits (and the
/// floats), 8 in the coarser ones (I20F12), whose drift is 16 times larger: there, 16
/// moves many more of the default scene's pixels away from f64 and the specular scene's
/// past its budget. 16 rather than 8: fewer restarts and half as many blocks to certify;
/// not 32: more blocks would hold a crossing, and fail.
pub(crate) const fn resync_pixels<S: Scalar>() -> u16 {
    // (`as` widens a `u32` here: `usize::from` is not `const`.)
    if core::mem::size_of::<S>() * 8 < S::INT_BITS as usize + 16 {
        RESYNC_PIXELS / 2
    } else {
        RESYNC_PIXELS
    }
}

/// The per-scanline part: `N·D` (planes) or `oc·D` (spheres) of every term at the
/// current pixel (rounded, and the unrounded sum it steps), `D`, and `D.y² + D.z²`.
#[derive(Debug, Clone)]
pub struct Row<S: Scalar> {
    pub(super) nd: Vec<S, FAST_OBJECTS>,
    pub(super) acc: Vec<S::Acc, FAST_OBJECTS>,
    pub(super) yz: S::Acc,
    pub(super) dir: Vec3<S>,
    pub(super) column: u16,
    pub(super) row: u16,
    /// `ε·(dx_limit + |D.y| + |D.z|)` plus two ulps, set at each restart: a bound of
    /// `accepts_bounded` valid for every pixel whose `|D.x| ≤ dx_limit` (the next
    /// [`resync_pixels`]), so that a pixel needs no product for it. When it does not
    /// fit, `dx_limit` is negative and each pixel computes its own bound.
    pub(super) eps_l1: S,
    pub(super) dx_limit: S,
}

/// A scanline's stepping flags where its lit plane hits keep a memo (`PlaneMemo`):
/// whether it steps its certified blocks' planes alone (`lazy`: until a restart, or until
/// a pixel has had to bring its terms up to date, after which a block steps them all),
/// and whether it has stepped a block's plane alone since its terms were last all up to
/// date (`stale`): a pixel that needs the others (the general shading, a shadow test)
/// brings them up to date first ([`Primary::catch_up`]), bit for bit what stepping them
/// would have given, in the formats that step so ([`Primary::steps_freely`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stepping {
    stale: bool,
    lazy: bool,
}

impl Default for Stepping {
    fn default() -> Self {
        Self {
            stale: false,
            lazy: true,
        }
    }
}

impl<S: Scalar> Primary<S> {
    /// Moves a scanline's row `state` to pixel `column` of scanline `row` and returns it:
    /// a step from the last column ([`Primary::advance`]; inside a certified block, with
    /// a memo's `stepping`, the block's plane alone, [`Primary::advance_one`]), else a
    /// restart from the exact screen point (every [`resync_pixels`], or after a step that
    /// failed), which leaves the scanline's block. `None` where the row cannot be formed
    /// (the pixel takes the reference path; the next pixel restarts).
    #[inline(always)]
    pub(crate) fn step_to<'r>(
        &self,
        scene: &SceneView<'_, S>,
        (row, column): (u16, u16),
        state: &'r mut Option<Row<S>>,
        blocks: &mut Blocks,
        stepping: Option<&mut Stepping>,
    ) -> Option<&'r Row<S>> {
        match state.as_mut() {
            Some(r)
                if r.column.checked_add(1) == Some(column)
                    && column % resync_pixels::<S>() != 0 =>
            {
                match (stepping, blocks.plane_at(column)) {
                    (Some(m), Some(w)) if m.lazy && self.steps_freely() => {
                        self.advance_one(r, w)?;
                        m.stale = true;
                    }
                    (m, _) => {
                        if let Some(m) = m.filter(|m| m.stale) {
                            self.refresh(scene, r)?;
                            m.stale = false;
                        }
                        self.advance(r)?
                    }
                }
            }
            Some(r) => {
                blocks.reset();
                if let Some(m) = stepping {
                    *m = Stepping::default();
                }
                if self.restart(scene, row, column, r).is_none() {
                    *state = None;
                    return None;
                }
            }
            None => {
                blocks.reset();
                if let Some(m) = stepping {
                    *m = Stepping::default();
                }
                *state = Some(self.row_resumed(scene, row, column)?);
            }
        }
        state.as_ref()
    }

    /// Brings the terms of a row stepped by its block's plane alone up to date
    /// ([`Stepping`]) for a pixel that needs them all, and steps every term from then on
    /// (until a restart). `None` where a term does not fit (the row's terms are then
    /// not all usable: the caller shades the pixel the general way).
    #[inline(always)]
    pub(crate) fn catch_up(
        &self,
        scene: &SceneView<'_, S>,
        r: &mut Row<S>,
        stepping: &mut Stepping,
    ) -> Option<()> {
        if stepping.stale {
            if self.refresh(scene, r).is_none() {
                stepping.lazy = false;
                return None;
            }
            (stepping.stale, stepping.lazy) = (false, false);
        }
        Some(())
    }

    /// Starts scanline `row` at column `column`.
    pub fn row(&self, scene: &SceneView<'_, S>, row: u16, column: u16) -> Option<Row<S>> {
        let mut r = Row {
            nd: Vec::new(),
            acc: Vec::new(),
            yz: S::acc_mul(S::ZERO, S::ZERO)?,
            dir: Vec3::new(S::ZERO, S::ZERO, S::ZERO),
            column,
            // No row yet (rows are below `u16::MAX`): `restart` forms its `D.y`.
            row: u16::MAX,
            eps_l1: S::ZERO,
            dx_limit: S::ZERO,
        };
        self.restart(scene, row, column, &mut r)?;
        Some(r)
    }

    /// Scanline `row` at column `column` as a scanline started at column 0 reaches it, so
    /// that a scanline drawn from any column has the whole scanline's pixels: the steps
    /// from the last [`resync_pixels`] column at or before it replayed as
    /// [`Primary::step_to`] takes them (a restart there, then a step a pixel; after a step
    /// that fails, a restart at the next pixel; after a restart that fails, a restart at
    /// each next pixel until one holds). `None` where the whole scanline's step to
    /// `column` fails too (its pixel then takes the reference path).
    pub(crate) fn row_resumed(
        &self,
        scene: &SceneView<'_, S>,
        row: u16,
        column: u16,
    ) -> Option<Row<S>> {
        let anchor = column - column % resync_pixels::<S>();
        let mut state: Option<Row<S>> = None;
        let mut held = false;
        for c in anchor..=column {
            held = match state.as_mut() {
                Some(r) if r.column.checked_add(1) == Some(c) && c % resync_pixels::<S>() != 0 => {
                    self.advance(r).is_some()
                }
                Some(r) => {
                    let restarted = self.restart(scene, row, c, r).is_some();
                    if !restarted {
                        state = None;
                    }
                    restarted
                }
                None => {
                    state = self.row(scene, row, c);
                    state.is_some()
                }
            };
        }
        state.filter(|_| held)
    }

    /// [`Primary::row`] into an existing row (in place: a row is hundreds of bytes, and
    /// a scanline restarts every [`resync_pixels`]). On `None` the row is unusable.
    pub(crate) fn restart(
        &self,
        scene: &SceneView<'_, S>,
        row: u16,
        column: u16,
        r: &mut Row<S>,
    ) -> Option<()> {
        // The same scanline with every term in place: its still terms stay as they are
        // (bit for bit what they would be recomputed to: `0·D.x` adds nothing). Otherwise
        // the terms are cleared first, so that a restart that fails leaves fewer of them
        // (and the next one recomputes them all); a kept restart that fails has left the
        // still terms as they were.
        let keep = r.row == row && r.nd.len() == self.terms.len();
        if !keep {
            r.nd.clear();
            r.acc.clear();
        }
        // The same scanline keeps its `D.y` (`restart_dir_in_row` sets `D` and the row
        // together): no division for it.
        if r.row == row {
            self.restart_dir_in_row(scene, row, r.dir.y, column, r)?;
        } else {
            self.restart_dir(scene, row, column, r)?;
        }
        if self.spheres && !keep {
            r.yz = S::acc_add(S::acc_mul(r.dir.y, r.dir.y)?, S::acc_mul(r.dir.z, r.dir.z)?)?;
        }
        self.terms_at(scene, r, keep)
    }

    /// The part of [`Primary::restart`] that is not the terms: `D` from the exact screen
    /// point, the column and row, the epsilon bound. A scanline whose terms are not
    /// needed at this pixel (`kernel/rows/`, outside the spheres' columns) restarts
    /// with this alone and brings its terms up to date with [`Primary::refresh`] where
    /// it needs them.
    pub(crate) fn restart_dir(
        &self,
        scene: &SceneView<'_, S>,
        row: u16,
        column: u16,
        r: &mut Row<S>,
    ) -> Option<()> {
        let dy = scene
            .camera
            .screen_y(row)?
            .checked_sub(scene.camera.viewpoint.y)?;
        self.restart_dir_in_row(scene, row, dy, column, r)
    }

    /// [`Primary::restart_dir`] with the row's `D.y` (`screen_y(row) − eye.y`, the same at
    /// every pixel of the row) given: a scanline that keeps it restarts without its
    /// division (`kernel/rows/`, every [`resync_pixels`]).
    #[inline]
    pub(crate) fn restart_dir_in_row(
        &self,
        scene: &SceneView<'_, S>,
        row: u16,
        dy: S,
        column: u16,
        r: &mut Row<S>,
    ) -> Option<()> {
        let eye = scene.camera.viewpoint;
        let unit = (self.x_unit > S::ZERO).then_some(self.x_unit);
        let x = scene.camera.screen_x_in(unit, column)?;
        r.dir = Vec3::new(x.checked_sub(eye.x)?, dy, self.dz);
        r.column = column;
        r.row = row;
        // The epsilon bound for this pixel and the next `resync_pixels` (|D.x| grows by at
        // most a step each; a larger bound only sends more planes to the exact test).
        let limit = self.resync_span.and_then(|m| m.checked_add(r.dir.x.abs()));
        let bound = limit.and_then(|m| Some((m, eps_l1_of(scene.epsilon, m, r.dir.y, r.dir.z)?)));
        (r.dx_limit, r.eps_l1) = bound.unwrap_or((S::ONE.checked_neg()?, S::ZERO));
        Some(())
    }

    /// Every term's `N·D` (and its unrounded sum) for the row's current `D`, the still
    /// ones only when not `keep`.
    pub(super) fn terms_at(
        &self,
        scene: &SceneView<'_, S>,
        r: &mut Row<S>,
        keep: bool,
    ) -> Option<()> {
        for (i, term) in self.terms.iter().enumerate() {
            let still = self.still & (1 << i) != 0;
            if keep && still {
                continue;
            }
            let sum = S::acc_dot3(axis_of(scene, term.index)?.to_array(), r.dir.to_array())?;
            let nd = S::acc_round(sum)?;
            match (r.nd.get_mut(i), r.acc.get_mut(i)) {
                (Some(n), Some(a)) if keep => (*n, *a) = (nd, sum),
                _ => {
                    r.nd.push(nd).ok()?;
                    r.acc.push(sum).ok()?;
                }
            }
        }
        Some(())
    }

    /// Brings a scanline's terms up to date with its `D` after [`Primary::advance_dir`]
    /// or [`Primary::restart_dir`]: in the formats whose products are exact
    /// (`KernelArith::EXACT_PRODUCTS`) bit for bit what [`Primary::advance`] would have stepped
    /// them to (both are the exact `N·D` of the same `D`). `None` where a term does not
    /// fit, or the row does not hold every term (it must be restarted whole).
    pub(crate) fn refresh(&self, scene: &SceneView<'_, S>, r: &mut Row<S>) -> Option<()> {
        if r.nd.len() != self.terms.len() {
            return None;
        }
        self.terms_at(scene, r, true)
    }

    /// The `D.x` [`Primary::advance_dir`] would step the row to, without stepping it.
    #[inline(always)]
    pub(crate) fn next_dx(&self, row: &Row<S>) -> Option<S> {
        self.next_dx_after(row.dir.x)
    }

    /// The `D.x` one [`Primary::advance_dir`] takes `D.x = dx` to.
    #[inline(always)]
    pub(crate) fn next_dx_after(&self, dx: S) -> Option<S> {
        dx.checked_add(self.step_x)
    }

    /// [`Primary::advance`] `m` times in one go, bit for bit in the fixed formats: `D.x`
    /// and the unrounded terms move by `m` steps, the terms are rounded once at the end
    /// (`None` where a step does not fit).
    pub(super) fn advance_by(&self, row: &mut Row<S>, m: u16) -> Option<()> {
        // `m` steps as `m·step` (`D.x`) and as the sum of `step`'s doublings picked by
        // `m`'s bits (the terms): the same integers in the fixed formats, whose sums are
        // exact, where the blocks are drawn (`blocks_for`). A product or a doubling that
        // does not fit says `None`: the block is then not certified.
        row.dir.x = row
            .dir
            .x
            .checked_add(self.step_x.checked_mul_int(i32::from(m))?)?;
        let terms = row.nd.iter_mut().zip(row.acc.iter_mut()).zip(&self.steps);
        for (i, ((nd, acc), step)) in terms.enumerate() {
            if self.still & (1 << i) == 0 {
                let (mut a, mut power, mut bits) = (*acc, *step, m);
                while bits != 0 {
                    if bits & 1 != 0 {
                        a = S::acc_add(a, power)?;
                    }
                    bits >>= 1;
                    if bits != 0 {
                        power = S::acc_add(power, power)?;
                    }
                }
                *acc = a;
                *nd = S::acc_round(a)?;
            }
        }
        row.column = row.column.checked_add(m)?;
        Some(())
    }

    /// Whether a scanline may step one term alone and bring the others up to date later
    /// ([`Primary::advance_one`], [`Primary::refresh`], bit for bit): the format's sums
    /// and products are exact, and every term fits throughout the frame (so that the
    /// refresh cannot fail where the steps would not have).
    #[inline(always)]
    pub(super) fn steps_freely(&self) -> bool {
        S::EXACT_SUMS && S::EXACT_PRODUCTS && self.fits
    }

    /// [`Primary::advance`] of `D.x` and the term of object `index` alone (the others are
    /// then stale until [`Primary::refresh`]): for a pixel of a certified block, whose
    /// hit needs only its plane's `N·D`.
    #[inline(always)]
    pub(super) fn advance_one(&self, row: &mut Row<S>, index: usize) -> Option<()> {
        row.dir.x = row.dir.x.checked_add(self.step_x)?;
        if self.still & 1u8.checked_shl(u32::try_from(index).ok()?)? == 0 {
            let (acc, nd) = (row.acc.get_mut(index)?, row.nd.get_mut(index)?);
            let step = *self.steps.get(index)?;
            if S::EXACT_SUMS && self.fits {
                (*acc, *nd) = S::acc_step_fitting(*acc, step);
            } else {
                *acc = S::acc_add(*acc, step)?;
                *nd = S::acc_round(*acc)?;
            }
        }
        row.column = row.column.checked_add(1)?;
        Some(())
    }

    /// [`Primary::advance`] without the terms: `D.x` and the column only (the terms are
    /// then stale until [`Primary::refresh`]).
    pub(crate) fn advance_dir(&self, row: &mut Row<S>) -> Option<()> {
        row.dir.x = row.dir.x.checked_add(self.step_x)?;
        row.column = row.column.checked_add(1)?;
        Some(())
    }

    /// [`Primary::advance_dir`] `m` times in one go, to `dx`: the `D.x` the caller
    /// stepped to by `m` sums of [`Primary::next_dx_after`].
    #[inline(always)]
    pub(crate) fn advance_dir_to(&self, row: &mut Row<S>, m: u16, dx: S) {
        row.column = row.column.saturating_add(m);
        row.dir.x = dx;
    }

    /// Whether every term of scanline `first` (started at column 0, holding every term)
    /// fits the format at every `D.x` its pixels can take (the first and last column's,
    /// widened by the drift of the stepped coordinate): a term is linear in `D.x`, so it
    /// fits between two values that fit. Then a pixel whose terms are skipped
    /// ([`Primary::advance_dir`]) is one where [`Primary::advance`] would not have failed.
    pub(crate) fn terms_fit_row(
        &self,
        scene: &SceneView<'_, S>,
        first: &Row<S>,
        width: u16,
    ) -> bool {
        let fits = || -> Option<()> {
            if first.nd.len() != self.terms.len() {
                return None;
            }
            let (lo, hi) = self.dx_range(scene, width)?;
            for x in [lo, hi] {
                let d = Vec3::new(x, first.dir.y, first.dir.z);
                for (i, term) in self.terms.iter().enumerate() {
                    if self.still & (1 << i) == 0 {
                        let axis = axis_of(scene, term.index)?;
                        S::acc_round(S::acc_dot3(axis.to_array(), d.to_array())?)?;
                    }
                }
            }
            Some(())
        };
        fits().is_some()
    }

    /// The least and greatest `D.x` a scanline can take at its `width` pixels: the first
    /// and last column's (`screen_x − eye.x`, as a restart forms them), widened by the
    /// drift of the stepped coordinate (`resync_pixels·|step_x|`). `None` when that does
    /// not fit.
    pub(crate) fn dx_range(&self, scene: &SceneView<'_, S>, width: u16) -> Option<(S, S)> {
        let camera = &scene.camera;
        let dx = |column: u16| camera.screen_x(column)?.checked_sub(camera.viewpoint.x);
        let (first, last) = (dx(0)?, dx(width.checked_sub(1)?)?);
        let span = self.resync_span?;
        let (lo, hi) = if first <= last {
            (first, last)
        } else {
            (last, first)
        };
        Some((lo.checked_sub(span)?, hi.checked_add(span)?))
    }

    /// The column the row is at.
    pub fn column(row: &Row<S>) -> u16 {
        row.column
    }

    /// The row's current unnormalised direction `D`.
    pub(crate) fn dir(row: &Row<S>) -> Vec3<S> {
        row.dir
    }

    /// The scanline a row is on.
    #[inline(always)]
    pub(crate) fn row_index(row: &Row<S>) -> u16 {
        row.row
    }

    /// The row's `N·D` of object `index` at its current pixel (its term's position is
    /// its index: every object is a term).
    #[inline(always)]
    pub(crate) fn nd(row: &Row<S>, index: usize) -> Option<S> {
        row.nd.get(index).copied()
    }

    /// Moves a scanline to its next pixel: `D.x` grows by the pixel step (rounded once
    /// per frame; callers restart the row from the exact screen x every
    /// `resync_pixels` pixels, so the drift stays below half as many DELTAs), and
    /// `N·D` grows by the unrounded `N.x × step` (`KernelArith::Acc`): in the fixed formats
    /// bit for bit the wide dot product of the new `D` (consistent with `D`, so the hit
    /// point lies on the ray through that screen point), with no product per pixel.
    pub fn advance(&self, row: &mut Row<S>) -> Option<()> {
        row.dir.x = row.dir.x.checked_add(self.step_x)?;
        let terms = row.nd.iter_mut().zip(row.acc.iter_mut()).zip(&self.steps);
        for (i, ((nd, acc), step)) in terms.enumerate() {
            // A still term's step is zero: it stays as it is.
            if self.still & (1 << i) == 0 {
                if S::EXACT_SUMS && self.fits {
                    // Within the frame's checked range (`frame_fits`), in a format whose
                    // sums are exact: no test.
                    (*acc, *nd) = S::acc_step_fitting(*acc, *step);
                } else {
                    *acc = S::acc_add(*acc, *step)?;
                    *nd = S::acc_round(*acc)?;
                }
            }
        }
        row.column = row.column.checked_add(1)?;
        Some(())
    }
}
