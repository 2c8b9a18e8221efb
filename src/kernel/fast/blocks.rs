//! Certified blocks: from a resync column, a run of pixels whose winner is proved the
//! search's answer at both ends (and so between them), drawn without a search.

use super::search::{FastHit, HitMemo, ahead};
use super::step::{Row, resync_pixels};
use super::{FAST_OBJECTS, Primary};
use crate::{Scalar, SceneView};

/// Where a scanline outside a certified block tries to start one: every this many
/// columns (a restart's, and half-way to the next, so that a block that fails for a
/// crossing in one half may hold in the other).
pub(super) const fn block_starts<S: Scalar>() -> u16 {
    resync_pixels::<S>() / 2
}

/// Whether format `S` draws certified blocks ([`Primary::certify_block`]) on this target:
/// its products are exact (its stepped terms are the exact ones, its comparisons exact)
/// and it is a 32-bit format (a 64-bit format's scanline would carry the block's state
/// and the lookahead row's frame on a 16 KB chip where I32F32 has a few bytes to spare),
/// on a core without a long multiply, where the search they save is dear, and on hosted
/// targets, so that the host's tests, reports and simulator take the same path (the
/// pixels are the same either way). On the Cortex-M4F and RISC-V the search is cheap
/// and the blocks cost more than they save (on RISC-V, and on both cores for the scenes
/// with spheres).
pub(crate) const fn blocks_for<S: Scalar>() -> bool {
    S::EXACT_PRODUCTS
        && core::mem::size_of::<S>() <= 4
        && cfg!(any(no_long_multiply, not(target_os = "none")))
}

/// A scanline's certified block ([`Primary::start_block`]): the column after it (0:
/// none) and the term that wins throughout ([`NO_TERM`]: the background).
#[derive(Debug, Clone, Copy)]
pub(super) struct Block {
    stop: u16,
    winner: u8,
}

impl Block {
    /// Whether the block holds no pixel (none was certified).
    pub(super) fn is_empty(&self) -> bool {
        self.stop == 0
    }

    /// The plane that wins throughout the block, if `column` is in it.
    #[inline(always)]
    pub(super) fn plane_at(&self, column: u16) -> Option<usize> {
        (column < self.stop && self.winner != NO_TERM).then_some(usize::from(self.winner))
    }
}

impl Default for Block {
    fn default() -> Self {
        Self {
            stop: 0,
            winner: NO_TERM,
        }
    }
}

/// A scanline's certified blocks ([`Primary::find`]): the block its pixels are in (empty
/// outside one) and the last pixel's winner, the guess its next resync column certifies
/// first.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Blocks {
    block: Block,
    guess: Guess,
}

impl Blocks {
    /// The plane that wins throughout the block at `column`, if it is in one.
    #[inline(always)]
    pub(crate) fn plane_at(&self, column: u16) -> Option<usize> {
        self.block.plane_at(column)
    }

    /// Leaves the block: a block holds for the pixels stepped from its start, so a
    /// restart of the scanline ends it.
    #[inline(always)]
    pub(super) fn reset(&mut self) {
        self.block = Block::default();
    }

    /// Keeps the answer at the scanline's last pixel (`found`: its winner, `Some(None)`
    /// for the background; `None` where the reference path decided) as the guess the
    /// next resync column certifies first (in the formats that draw blocks).
    #[inline(always)]
    pub(crate) fn saw<S: Scalar>(&mut self, found: Option<Option<usize>>) {
        if blocks_for::<S>() {
            self.guess = Guess::of(found);
        }
    }
}

/// No term: a block of the background (a frame has at most [`FAST_OBJECTS`] terms).
pub(super) const NO_TERM: u8 = u8::MAX;

/// The last pixel's winner, which a scanline's resync column certifies first
/// ([`Primary::start_block`]): an object's index, [`NO_TERM`] for the background, or
/// none known. One byte (an I32F32 scanline on a 16 KB chip has a few to spare).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Guess(u8);

/// No winner known ([`Guess`]).
pub(super) const UNKNOWN: u8 = u8::MAX - 1;

// An object's index is never taken for one of the two marks.
// (`as` widens a `u8`: `usize::from` is not `const`.)
const _: () = assert!(FAST_OBJECTS < UNKNOWN as usize);

impl Default for Guess {
    fn default() -> Self {
        Self(UNKNOWN)
    }
}

impl Guess {
    /// The guess of a pixel's answer (`None`: not known; `Some(None)`: the background).
    pub(super) fn of(found: Option<Option<usize>>) -> Self {
        Self(match found {
            Some(Some(i)) => u8::try_from(i)
                .ok()
                .filter(|i| *i < UNKNOWN)
                .unwrap_or(UNKNOWN),
            Some(None) => NO_TERM,
            None => UNKNOWN,
        })
    }

    /// The guessed winner (`Some(None)`: the background), if one is known.
    pub(super) fn winner(self) -> Option<Option<usize>> {
        match self.0 {
            UNKNOWN => None,
            NO_TERM => Some(None),
            i => Some(Some(usize::from(i))),
        }
    }
}

impl<S: Scalar> Primary<S> {
    /// The nearest hit at the row's current pixel, `column` of a scanline whose last
    /// column is `last` (`None`: the reference path decides): [`Primary::nearest_with`]'s
    /// answer, bit for bit, from the scanline's certified block where the pixel is in one
    /// (no search). A resync column certifies the last pixel's winner first (no search
    /// where it holds), else the searched one (unless that was the guess); a restart's
    /// block that does not hold to the next restart may hold for its first half (the
    /// second half tries its own, [`block_starts`]). Only in the formats that draw blocks
    /// ([`blocks_for`]: compiled out of the others).
    #[inline(always)]
    pub(crate) fn find(
        &self,
        scene: &SceneView<'_, S>,
        r: &Row<S>,
        (column, last): (u16, u16),
        blocks: &mut Blocks,
        hits: Option<&mut HitMemo<S>>,
    ) -> Option<Option<FastHit<S>>> {
        let mut hits = hits;
        if !blocks_for::<S>() {
            return self.nearest_with(scene, r, hits).ok();
        }
        let (block, guess) = (&mut blocks.block, blocks.guess);
        if let Some(hit) = self.block_hit(scene, r, block, hits.as_deref_mut()) {
            return hit.ok();
        }
        if column % block_starts::<S>() != 0 {
            return self.nearest_with(scene, r, hits).ok();
        }
        if let Some(w) = guess.winner() {
            self.start_block(r, w, last, block);
            if let Some(hit) = self.block_hit(scene, r, block, hits.as_deref_mut()) {
                return hit.ok();
            }
        }
        let hit = self.nearest_with(scene, r, hits).ok()?;
        let winner = hit.as_ref().map(|h| h.index);
        if guess.winner() != Some(winner) {
            self.start_block(r, winner, last, block);
        }
        if block.is_empty() && column % resync_pixels::<S>() == 0 {
            let half = last.min(column.saturating_add(block_starts::<S>() - 1));
            self.start_block(r, winner, half, block);
        }
        Some(hit)
    }

    /// The row's current pixel (a resync column, just restarted) and the pixels after it
    /// up to `last` and the next restart ([`resync_pixels`]), if [`Primary::nearest`] answers
    /// `winner` (an object's index, `None`: the background) at every one of them: that
    /// block (the column after it, and the term that wins throughout or [`NO_TERM`]).
    /// `None` where that is not certain. `winner` may be a guess (the last pixel's): the
    /// checks below are `nearest`'s own tests at both ends, so a block is certified only
    /// where it is that pixel's answer too.
    ///
    /// Why it holds: inside the block `D.x` steps by a constant, so every plane's unrounded
    /// `N·D` is linear in the column and its rounded `N·D` monotone. The block's last
    /// pixel is formed as the scanline would step to it (`advance_by`: the same steps, the
    /// terms rounded once at the end). Every plane must keep one side of zero and stay
    /// at least the epsilon bound away from it at both ends (so that no pixel between
    /// takes the exact parallel test, and its acceptance, monotone, is the same
    /// throughout). The winner must beat every other accepted plane at both ends by a
    /// margin that the roundings of `N·D` cannot eat (`KernelArith::products_clearly_greater`:
    /// the comparison with unrounded terms is linear, so it holds between the ends too).
    #[inline(never)]
    pub(super) fn certify_block(
        &self,
        a: &Row<S>,
        winner: Option<usize>,
        last: u16,
    ) -> Option<Block> {
        // Up to the scanline's next restart (the stepped terms hold until then).
        let m = last
            .checked_sub(a.column)?
            .min(resync_pixels::<S>() - 1 - a.column % resync_pixels::<S>());
        if m == 0 || a.nd.len() != self.terms.len() {
            return None;
        }
        let mut e = a.clone();
        self.advance_by(&mut e, m)?;
        // No search at the block's end: the checks below are its tests there (every
        // plane beyond the epsilon bound, so accepted by `ahead` alone; the winner
        // accepted; every other accepted plane clearly farther, so that neither order
        // of the tie rule lets it win), so they imply its answer.
        // Both ends (and so every pixel between: |D.x| is largest at an end) take the
        // row's epsilon bound.
        let bound = a.eps_l1;
        if a.dx_limit < a.dir.x.abs() || a.dx_limit < e.dir.x.abs() {
            return None;
        }
        // A term's position is its object's index (every object is a term). The winner
        // must be accepted (at the start; the loop below makes both ends agree): a guess
        // may name a plane behind the eye, whose `|t'|` would win the comparisons.
        let w = match winner {
            Some(i) => {
                let (num, na) = (self.terms.get(i)?.num, *a.nd.get(i)?);
                if !ahead(num, na) {
                    return None;
                }
                Some((i, num.abs(), na, *e.nd.get(i)?))
            }
            None => None,
        };
        for (k, (term, (&na, &ne))) in self.terms.iter().zip(a.nd.iter().zip(&e.nd)).enumerate() {
            // (Not zero either: a caller may give the view a negative epsilon.)
            if na.abs() < bound
                || ne.abs() < bound
                || na == S::ZERO
                || ne == S::ZERO
                || (na > S::ZERO) != (ne > S::ZERO)
            {
                return None;
            }
            let accepted = ahead(term.num, na);
            if accepted != ahead(term.num, ne) {
                return None;
            }
            match w {
                Some((i, pw, wa, we)) if accepted && k != i => {
                    let pb = term.num.abs();
                    let clear = S::products_clearly_greater(pb, wa.abs(), pw, na.abs())
                        && S::products_clearly_greater(pb, we.abs(), pw, ne.abs());
                    if !clear {
                        return None;
                    }
                }
                // The background at both ends, yet a plane accepted: cannot be.
                None if accepted => return None,
                _ => {}
            }
        }
        Some(Block {
            stop: e.column.checked_add(1)?,
            winner: match winner {
                Some(k) => u8::try_from(k).ok()?,
                None => NO_TERM,
            },
        })
    }

    /// The pixels of a scanline from a resync column (just restarted there) as a
    /// certified block of `winner` ([`Primary::certify_block`]) into `block` where they
    /// can be one (else an empty block); `last`: the scanline's last column. Inside the
    /// block [`Primary::block_hit`] answers for [`Primary::nearest`].
    #[inline(never)]
    pub(super) fn start_block(
        &self,
        row: &Row<S>,
        winner: Option<usize>,
        last: u16,
        block: &mut Block,
    ) {
        *block = if self.blocks {
            self.certify_block(row, winner, last).unwrap_or_default()
        } else {
            Block::default()
        };
    }

    /// The frame without certified blocks: every pixel searched (the tests' oracle).
    #[cfg(test)]
    pub(super) fn without_blocks(mut self) -> Self {
        self.blocks = false;
        self
    }

    /// [`Primary::nearest`]'s answer at a pixel of the certified block `block`, bit for bit
    /// (`None`: the pixel is not in the block). Reset `block` at every restart of the
    /// scanline: a block holds for the pixels stepped from its start.
    #[inline(always)]
    pub(super) fn block_hit(
        &self,
        scene: &SceneView<'_, S>,
        row: &Row<S>,
        block: &Block,
        memo: Option<&mut HitMemo<S>>,
    ) -> Option<Result<Option<FastHit<S>>, ()>> {
        if row.column >= block.stop {
            return None;
        }
        let mut memo = memo;
        if let Some(m) = memo.as_deref_mut() {
            m.certified = true;
        }
        Some(match block.winner {
            NO_TERM => Ok(None),
            // A plane's `t'` as `search` forms it: `|num| / |N·D|`.
            k => {
                let k = usize::from(k);
                match (self.terms.get(k), row.nd.get(k)) {
                    (Some(term), Some(nd)) => self
                        .hit(scene, row, term, term.num.abs(), nd.abs(), memo)
                        .map(Some)
                        .ok_or(()),
                    _ => Err(()),
                }
            }
        })
    }
}
