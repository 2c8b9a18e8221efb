//! Spans of a quick run: pixels drawn from the two ends of a span where both ends
//! convert to one colour of the frame's depth ([`crate::Depth`]) and nothing between can
//! differ from them there.
//!
//! Along a lean row with one light, between two restarts of the stepping, a quick pixel's
//! colour is a function of its tile and `|L|²` alone where no sphere can shadow the row
//! from the light (the row keeps no cone for it, or the pixels lie outside the columns
//! where one may, `changes::shadow_columns`): `D.x` grows by one step a pixel, the
//! hit's `x = eye.x + t'·D.x` (`t'` the row's) is monotone in it, and so are its tile
//! column (a difference and a floored quotient), `L.x = light.x − x` and, on one side of
//! `L.x = 0`, `|L|² = L.x² + (L.y² + L.z²)` (one rounding of a sum that grows with
//! `|L.x|`). Each channel of the colour is then monotone in `|L|²`: the ambient part is
//! the tile's, the light's term `w·(255·N·L)/|L|²` (with `N·L` the row's) is a truncated
//! quotient times a weight, added saturating, rounded and clamped to a channel, and a
//! depth's channel `round(v·max/255)` is monotone in `v`. So where two pixels of one tile
//! column with `L.x` of one sign have one key in the depth, every pixel between them has
//! it too, whichever path would have drawn it (the quick pixel where it settles, the
//! exact term where it does not): the pixels between are drawn as the left end.
//!
//! A span is the run's next pixels up to the column before the next restart; its far
//! end is drawn first, then it is halved where its ends differ, the left half first, so
//! that every pixel is drawn at most once. In the exact depth a pixel so drawn is the
//! exact pixel itself; in a shallower one it converts to the exact pixel's colour
//! (`tests/depth.rs`, and the quick runs' invariant, `invariants.rs`).

use embedded_graphics_core::pixelcolor::Rgb888;

use super::super::fast::{Primary, Row};
use super::RUN;
use super::lean::{LeanLight, LeanRow, Side, quick_at};
use super::level::Level;
use crate::{Depth, Scalar, SceneView};

/// A quick run's spans so far ([`Span::draw`]).
pub(super) struct Span {
    /// What the pixels must be exact in.
    pub(super) depth: Depth,
    /// The run's own pixel's column (`run[0]` is the next one's).
    pub(super) from: u16,
    /// The last column drawn (the row's state is there): its pixel and its [`class`].
    pub(super) at: (u16, Rgb888, Option<i32>),
    /// The pixels drawn ahead so far: `run[..n]` (every one lit).
    pub(super) n: u8,
}

/// The most pixels a span covers: those after a restart of the stepping, up to the next.
const SPAN: usize = super::super::fast::RESYNC_PIXELS as usize - 1;

/// A drawn pixel's [`Side`] as one number (`2·tile + left`), `None` where its tile is
/// not known or so far out that the number would not tell two tiles apart.
#[inline(always)]
pub(super) fn class(side: Side) -> Option<i32> {
    let tile = side.tile.filter(|t| t.unsigned_abs() < 1 << 29)?;
    Some(2 * tile + i32::from(side.left))
}

/// What [`Span::draw`] drew.
pub(super) enum Drew {
    /// Every pixel up to the span's end.
    All,
    /// The pixels up to one before this column, at most (the column's pixel is not a
    /// quick pixel: a quick run ends before it).
    Before(u16),
    /// Nothing (a quantity out of range: the caller steps one pixel).
    Not,
}

/// A drawn column of a span: its offset from the span's start, its key in the depth, its
/// [`class`] (`UNKNOWN` where it has none) and its pixel.
#[derive(Clone, Copy)]
struct End {
    k: u8,
    key: u32,
    class: i32,
    pixel: Rgb888,
}

/// The class of a column whose [`class`] is `None`: never [`End::alike`] any other (a
/// known class lies within `±2³⁰`).
const UNKNOWN: i32 = i32::MIN;

impl End {
    fn new(k: usize, depth: Depth, pixel: Rgb888, class: Option<i32>) -> Self {
        Self {
            // (`k` is at most a span, below 256.)
            k: k as u8,
            key: depth.key(pixel),
            class: class.unwrap_or(UNKNOWN),
            pixel,
        }
    }

    /// Whether the two columns have one key and one known class: every column between
    /// them is then drawn as the left one (the module's certificate).
    #[inline(always)]
    fn alike(&self, other: &Self) -> bool {
        self.class != UNKNOWN && self.class == other.class && self.key == other.key
    }

    fn class(&self) -> Option<i32> {
        (self.class != UNKNOWN).then_some(self.class)
    }
}

impl Span {
    /// Draws the pixels after the last one drawn up to column `b` (no restart of the
    /// stepping after the last one, up to `b`; at least two pixels, and a row whose light
    /// no sphere can shadow: every quick pixel is lit) into `run`, and steps the row's
    /// `state` to the last pixel drawn ([`Drew`]). Where a pixel is not a quick pixel
    /// (`quick_at` says `None`) the pixels drawn before it (all of them left of it) are
    /// kept.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn draw<S: Scalar>(
        &mut self,
        scene: &SceneView<'_, S>,
        p: &Primary<S>,
        lean: (&Level<S>, &LeanRow<S>, &LeanLight<S>),
        state: &mut Row<S>,
        dy: S,
        b: u16,
        run: &mut [Rgb888; RUN],
    ) -> Drew {
        let a = self.at.0;
        let len = usize::from(b.saturating_sub(a));
        // `run[base + k − 1]` is column `a + k`'s (`k ≥ 1`). (Indices are masked to the
        // arrays' sizes, powers of two, which they stay within.)
        let base = usize::from(a.saturating_sub(self.from));
        if !(2..=SPAN).contains(&len) || base + len > RUN {
            return Drew::Not;
        }
        let slot = |k: usize| (base + k - 1) & (RUN - 1);
        // `D.x` at column `a + k`: `k` sums of the step (`advance_dir`'s, bit for bit: the
        // fixed formats' sums are exact), as `D.x` plus the step's doublings picked by `k`.
        let Some(step) = p.next_dx_after(S::ZERO) else {
            return Drew::Not;
        };
        let mut doublings = [step; 5];
        for i in 1..doublings.len() {
            let Some(d) = doublings[i - 1].checked_add(doublings[i - 1]) else {
                return Drew::Not;
            };
            doublings[i] = d;
        }
        let dx0 = Primary::dir(state).x;
        let dx = |k: usize| -> Option<S> {
            let mut d = dx0;
            for (i, step) in doublings.iter().enumerate() {
                if k & (1 << i) != 0 {
                    d = d.checked_add(*step)?;
                }
            }
            Some(d)
        };
        // (No pixel of a span lies in a sphere's shadow: its cones are not tested.)
        let eval = |k: usize| quick_at(scene, p, lean, (dx(k)?, dy), false);
        let colors = self.depth;
        let Some((pixel, _, side)) = eval(len) else {
            return Drew::Before(b);
        };
        run[slot(len)] = pixel;
        // The last column drawn with every one left of it drawn (`left`), and the drawn
        // columns right of it still to reach (`right[..depth]`, the nearest last; masked
        // to the array's size, a power of two, within which `depth` stays): each gap
        // between two is halved where its ends are not alike, its left half first.
        let mut left = End::new(0, colors, self.at.1, self.at.2);
        let mut right = [left; 8];
        right[0] = End::new(len, colors, pixel, class(side));
        let mut depth = 1usize;
        while depth > 0 {
            let r = right[(depth - 1) & 7];
            let (lo, hi) = (usize::from(left.k), usize::from(r.k));
            if hi - lo < 2 || left.alike(&r) {
                for k in lo + 1..hi {
                    run[slot(k)] = left.pixel;
                }
                left = r;
                depth -= 1;
                continue;
            }
            let m = lo + (hi - lo) / 2;
            let Some((pixel, _, side)) = eval(m) else {
                // Every column up to `lo` is drawn (the left halves go first).
                let Some(dx) = dx(lo) else {
                    return Drew::Not;
                };
                self.keep(state, p, (lo, dx), left.pixel, left.class());
                return Drew::Before(a + m as u16);
            };
            run[slot(m)] = pixel;
            if depth == right.len() {
                return Drew::Not;
            }
            right[depth & 7] = End::new(m, colors, pixel, class(side));
            depth += 1;
        }
        let Some(dx) = dx(len) else {
            return Drew::Not;
        };
        self.keep(state, p, (len, dx), left.pixel, left.class());
        Drew::All
    }

    /// Keeps the pixels drawn up to `k` columns after the last one (the one there is
    /// `pixel`, of class `class`; every one lit), and steps the row's state there (to `D.x = dx`).
    fn keep<S: Scalar>(
        &mut self,
        state: &mut Row<S>,
        p: &Primary<S>,
        (k, dx): (usize, S),
        pixel: Rgb888,
        class: Option<i32>,
    ) {
        // (`k` is at most a span, within the run: `draw` checked.)
        let k = k as u16;
        if k == 0 {
            return;
        }
        p.advance_dir_to(state, k, dx);
        let c = self.at.0 + k;
        self.n = (c - self.from) as u8;
        self.at = (c, pixel, class);
    }
}
