//! Pure-geometry plane scenes, a scanline at a time: per-pixel mode and span mode.
//!
//! A scene of infinite planes without lights, tiles or mirrors is pure geometry
//! (`docs/scene-format.md`): a pixel shows the ambient colour of the nearest plane it sees, so
//! no hit point, division or colour arithmetic is needed per pixel, only *which* plane.
//! With the eye `b`, `num_i = D'_i − N_i·b` per plane (per frame) and the unnormalised
//! direction `D = screen point − b` (as in [`super::fast`]):
//!
//! - **Per scanline**, each plane is accepted (the tests of [`super::fast`], which are
//!   those of the definition) on one interval of columns `[lo, hi)`: the accepted
//!   directions form a convex cone (`σN·D ≥ ε|D|` and `σN·D ≤ |num|`, `σ` the sign of
//!   `num`), and a scanline is a line through it. The interval's ends are estimated from
//!   `N·D`, which is linear along the scanline, and then settled by the per-pixel test
//!   itself, so the interval is exactly where that test accepts.
//! - **The nearest plane** has the largest `w = σ N·D / |num| = 1/t'` (`t'` the distance in
//!   units of `D`). On a scanline `w` is linear in the column; it is evaluated as
//!   `w̃(k) = w̃(lo) + (k − lo)·Δw̃`, scaled by `2^RATIO_SHIFT` ([`ratio_shift`]) so
//!   that the fixed formats keep their full resolution for a quantity at most 1:
//!   `w̃(lo) = σ N·D(lo) · r` and `Δw̃ = σ N.x·(WX/W) · r` with `r = 2^RATIO_SHIFT/|num|`
//!   (one division per plane per frame, none per scanline or pixel).
//!
//! **Per-pixel mode** evaluates `w̃` of every plane accepted at the pixel (a multiply and
//! an add each) and keeps the largest. **Span mode** walks the scanline from one change of
//! the nearest plane to the next: a change happens where a plane's interval starts or ends
//! or where two planes' `w̃` lines cross, each found with one estimate and settled by the
//! same per-pixel comparison. For the fixed formats `w̃(k)` is exact integer arithmetic on
//! a line, so span mode draws exactly the per-pixel mode's image (`tests/flat.rs`); for
//! floats the rounding of `w̃` can move a span's end by a pixel.
//!
//! Against the general fast path ([`super::fast`], which compares `t'` by exact
//! cross-products) the only difference is the rounding of `w̃`: pixels can differ where two
//! planes meet within that rounding (`tests/flat.rs` counts them). Any quantity that does
//! not fit the format makes [`Flat::new`] or [`Flat::row`] return `None`, and the renderer
//! traces that frame or scanline on the general path instead.

use embedded_graphics_core::pixelcolor::Rgb888;
use heapless::Vec;

use super::fast::accepts;
use crate::scene::MAX_OBJECTS;
use crate::shade::color::to_rgb888;
use crate::{Scalar, SceneView, Shape, Vec3};

/// How many bits a ratio of at most 1 is scaled up by, so that it keeps the format's full
/// resolution: half the integer bits of a fixed format (I16F16: 8, so `2^8/|num|` still
/// fits for planes 1/128 of a unit from the eye), 0 for floats (their resolution is
/// relative).
const fn ratio_shift<S: Scalar>() -> u32 {
    S::INT_BITS / 2
}

/// Columns per block of [`FlatRow::fill`]: its `w̃` buffer is this many values on the
/// stack (256 bytes in I16F16).
pub const BLOCK: usize = 64;

/// How a pure-geometry plane scene is drawn (a scene of infinite planes without lights
/// or mirrors; other scenes draw the same either way). Choose it with
/// [`Frame::with_mode`](crate::Frame::with_mode).
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb888;
/// use fixray::{Frame, PlaneMode, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(include_str!("../../scenes/planes.scene"))?;
/// let (per_pixel, spans) = (Frame::new(&scene), Frame::with_mode(&scene, PlaneMode::Spans));
/// assert_eq!(spans.mode(), PlaneMode::Spans);
/// let (mut a, mut b) = ([Rgb888::new(0, 0, 0); 160], [Rgb888::new(0, 0, 0); 160]);
/// for row in 0..scene.camera.height {
///     per_pixel.render_line(row, &mut a);
///     spans.render_line(row, &mut b);
///     assert_eq!(a, b); // the same picture in the fixed formats
/// }
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PlaneMode {
    /// Every pixel compares the planes accepted there.
    #[default]
    PerPixel,
    /// Runs of pixels that see the same plane are filled at once.
    Spans,
}

/// The per-frame part of a plane.
#[derive(Debug, Clone, Copy)]
struct FramePlane<S> {
    /// The object (its normal is read from the scene: on a 16 KB chip a copy of every
    /// normal is RAM the stack needs).
    index: u8,
    /// `D' − N·eye`.
    num: S,
    /// `2^RATIO_SHIFT / |num|`, with the sign of `num` (`σ r`).
    ratio: S,
    color: Rgb888,
}

/// How many planes [`Flat`] takes: a scene with more is drawn by the general fast path.
/// The per-frame part lives for a whole frame beside the deepest shading stack, so it is
/// kept small (16 × 24 bytes in I32F32).
pub const MAX_PLANES: usize = 16;

/// The per-frame part: see [`Flat::new`].
#[derive(Debug, Clone)]
pub struct Flat<S> {
    planes: Vec<FramePlane<S>, MAX_PLANES>,
    /// `WX`, the screen window's width.
    world_width: S,
    background: Rgb888,
    width: u16,
}

/// A plane on one scanline: accepted on `lo..hi`, where `w̃(k) = start + (k − lo)·step`.
#[derive(Debug, Clone, Copy)]
struct Segment<S> {
    lo: u16,
    hi: u16,
    start: S,
    step: S,
    color: Rgb888,
}

impl<S: Scalar> Segment<S> {
    /// `w̃` at column `k` (`lo <= k < hi`); `None` when it does not fit (not for `k`
    /// inside the segment, whose ends were computed to fit).
    #[inline]
    fn weight(&self, k: u16) -> Option<S> {
        self.step
            .checked_mul_int(i32::from(k.wrapping_sub(self.lo)))?
            .checked_add(self.start)
    }

    #[inline]
    fn covers(&self, k: u16) -> bool {
        k.wrapping_sub(self.lo) < self.hi.wrapping_sub(self.lo)
    }
}

/// One scanline: the segment of every plane accepted somewhere on it (in object order).
#[derive(Debug, Clone)]
pub struct FlatRow<S> {
    segments: Vec<Segment<S>, MAX_OBJECTS>,
    background: Rgb888,
}

impl<S: Scalar> Flat<S> {
    /// Prepares a frame of a scene of infinite planes, each drawn in its ambient colour
    /// (the whole image of a pure-geometry scene: `kernel::select` decides where it
    /// applies); `None` when an object is
    /// not an infinite plane, there are more than [`MAX_PLANES`], or a per-frame quantity does not fit the format (an eye
    /// within `2^RATIO_SHIFT / MAX` of a plane, for instance).
    pub fn new(scene: &SceneView<'_, S>) -> Option<Self> {
        let camera = &scene.camera;
        let eye = camera.viewpoint;
        let scale = S::from_i32(1_i32.checked_shl(ratio_shift::<S>())?)?;
        let mut planes = Vec::new();
        for (index, object) in scene.objects.iter().enumerate() {
            let Shape::Plane(plane) = &object.shape else {
                return None;
            };
            let index = u8::try_from(index).ok()?;
            let normal = plane.normal();
            let num = S::sub_dot3(plane.offset(), normal.to_array(), eye.to_array())?;
            let material = scene.materials.get(usize::from(object.material))?;
            // num = 0: the eye lies on the plane; its every hit is at the eye, in front of
            // the screen, so it is never accepted (ratio 0 marks it, see `row`).
            let ratio = if num == S::ZERO {
                S::ZERO
            } else {
                scale.checked_div(num)?
            };
            planes
                .push(FramePlane {
                    index,
                    num,
                    ratio,
                    color: to_rgb888(material.ambient),
                })
                .ok()?;
        }
        Some(Self {
            planes,
            world_width: camera.world_width,
            background: to_rgb888(scene.background),
            width: camera.width,
        })
    }

    /// Prepares scanline `row`: the interval and `w̃` line of every plane; `None` when a
    /// quantity does not fit the format (the caller traces the scanline on the general
    /// path).
    pub fn row(&self, scene: &SceneView<'_, S>, row: u16) -> Option<FlatRow<S>> {
        let camera = &scene.camera;
        let eye = camera.viewpoint;
        let dy = camera.screen_y(row)?.checked_sub(eye.y)?;
        let dz = S::ZERO.checked_sub(eye.z)?;
        let w = i32::from(self.width);
        // The direction through column k, as the per-pixel paths form it (the screen x
        // rounded once from the exact fraction).
        let dir = |k: u16| -> Option<Vec3<S>> {
            let x = camera.screen_x(k)?;
            Some(Vec3::new(x.checked_sub(eye.x)?, dy, dz))
        };
        let last = self.width.checked_sub(1)?;
        let mut segments = Vec::new();
        for plane in &self.planes {
            if plane.ratio == S::ZERO {
                continue;
            }
            let Some(Shape::Plane(p)) =
                scene.objects.get(usize::from(plane.index)).map(|o| o.shape)
            else {
                return None;
            };
            let normal = p.normal();
            // The test of the definition at column k (see `fast`), and σN·D there.
            let accepted = |k: u16| -> Option<(bool, S)> {
                let d = dir(k)?;
                let nd = normal.dot(d)?;
                let eps_d2 = scene.epsilon.checked_mul(d.dot(d)?)?;
                Some((accepts(plane.num, nd, scene.epsilon, eps_d2), nd))
            };
            let Some((lo, hi, nd)) = interval(plane, last, &accepted)? else {
                continue;
            };
            let start = nd.checked_mul(plane.ratio)?;
            // Δw̃ = N.x·(WX/W)·r, rounding the large factor first: WX/W alone would carry
            // a relative error of DELTA/(WX/W) into every column (0.1 % in I20F12).
            let step = normal
                .x
                .checked_mul(plane.ratio.checked_mul(self.world_width)?.mul_ratio(1, w)?)?;
            let segment = Segment {
                lo,
                hi,
                start,
                step,
                color: plane.color,
            };
            // Both ends fit, so every w̃ between them does (a line).
            segment.weight(hi - 1)?;
            segments.push(segment).ok()?;
        }
        Some(FlatRow {
            segments,
            background: self.background,
        })
    }
}

/// The interval `[lo, hi)` of columns `0..=last` where `accepted` holds, with `N·D` at
/// `lo`; `None` inside when there is none (`None` outside when a quantity does not fit).
///
/// The accepted columns form an interval (see the module documentation), so both ends
/// accepted means all of it. Otherwise `σ N·D`, linear in the column, gives estimates of
/// the ends from its values at the two ends of the scanline (one division), a column
/// between them that the test accepts is the seed, and each open end is moved one column
/// at a time until the per-pixel test changes there: with a good estimate two tests per
/// end.
fn interval<S: Scalar>(
    plane: &FramePlane<S>,
    last: u16,
    accepted: &dyn Fn(u16) -> Option<(bool, S)>,
) -> Option<Option<(u16, u16, S)>> {
    let (ok0, nd0) = accepted(0)?;
    let (ok1, nd1) = accepted(last)?;
    if ok0 && ok1 {
        return Some(Some((0, last + 1, nd0)));
    }
    let oriented = |v: S| {
        if plane.num > S::ZERO {
            Some(v)
        } else {
            v.checked_neg()
        }
    };
    let (e0, e1) = (oriented(nd0)?, oriented(nd1)?);
    let n = i32::from(last);
    // Columns per unit of σN·D along the line through (0, e0), (last, e1).
    let per_unit = e1
        .checked_sub(e0)
        .filter(|span| *span != S::ZERO)
        .and_then(|span| S::from_i32(n)?.checked_div(span));
    // The first column where that line exceeds `target`.
    let after = |target: S| -> Option<i32> {
        let cols = target
            .checked_sub(e0)?
            .checked_mul(per_unit?)?
            .floor_to_i32()?;
        Some(cols.saturating_add(1).clamp(0, n + 1))
    };
    let a = plane.num.abs();
    let (lo_est, hi_est) = if e1 > e0 {
        (after(S::ZERO).unwrap_or(0), after(a).unwrap_or(n + 1))
    } else if e1 < e0 {
        (after(a).unwrap_or(0), after(S::ZERO).unwrap_or(n + 1))
    } else {
        (0, n + 1)
    };
    let to_col = |k: i32| u16::try_from(k.clamp(0, n)).ok();
    // A seed: an accepted column.
    let seed = if ok0 {
        Some(0)
    } else if ok1 {
        Some(last)
    } else {
        let mid = to_col(lo_est + (hi_est - lo_est) / 2)?;
        let mut found = None;
        for k in [mid, mid.saturating_add(1).min(last), mid.saturating_sub(1)] {
            if accepted(k)?.0 {
                found = Some(k);
                break;
            }
        }
        found
    };
    let Some(seed) = seed else {
        return Some(None);
    };
    // The low end: the first accepted column at or below the seed, and N·D there.
    let (lo, nd_lo) = if ok0 {
        (0, nd0)
    } else {
        let mut lo = to_col(lo_est)?.min(seed);
        let (mut ok, mut nd) = accepted(lo)?;
        if ok {
            while lo > 0 {
                let (ok_below, nd_below) = accepted(lo - 1)?;
                if !ok_below {
                    break;
                }
                lo -= 1;
                nd = nd_below;
            }
        } else {
            while !ok {
                lo += 1;
                (ok, nd) = accepted(lo)?;
            }
        }
        (lo, nd)
    };
    // The high end: the first rejected column above the seed (or last + 1).
    let hi = if ok1 {
        last + 1
    } else {
        let mut hi = u16::try_from(hi_est.clamp(i32::from(seed) + 1, n)).ok()?;
        if accepted(hi - 1)?.0 {
            while accepted(hi)?.0 {
                hi += 1;
            }
        } else {
            while !accepted(hi - 1)?.0 {
                hi -= 1;
            }
        }
        hi
    };
    Some(Some((lo, hi, nd_lo)))
}

impl<S: Scalar> FlatRow<S> {
    /// The nearest plane's segment at column `k` (the largest `w̃`; the first in object
    /// order on a tie, as the per-pixel paths), or `None` for the background.
    #[inline]
    fn winner(&self, k: u16) -> Option<(usize, S)> {
        let mut best: Option<(usize, S)> = None;
        for (i, s) in self.segments.iter().enumerate() {
            if s.covers(k)
                && let Some(w) = s.weight(k)
                && best.is_none_or(|(_, b)| w > b)
            {
                best = Some((i, w));
            }
        }
        best
    }

    /// The colour of column `k` (per-pixel mode): [`FlatRow::winner`]'s plane, tracked
    /// by colour.
    #[inline]
    pub fn pixel(&self, k: u16) -> Rgb888 {
        let mut color = self.background;
        // Below every accepted plane's w̃ (which is ≥ 0: σN·D > 0 and r > 0).
        let mut best = S::ONE.checked_neg().unwrap_or(S::ZERO);
        for s in &self.segments {
            if s.covers(k)
                && let Some(w) = s.weight(k)
                && w > best
            {
                best = w;
                color = s.color;
            }
        }
        color
    }

    /// Columns `from..from + out.len()` in per-pixel mode, into `out`: the same colours as
    /// [`FlatRow::pixel`] column by column, computed plane by plane over blocks of
    /// [`BLOCK`] columns (a block's `w̃` buffer on the stack): each plane steps its `w̃` by
    /// one addition per column of its interval and keeps the columns where it is the
    /// largest so far. Every accepted plane is still compared at every pixel; only the
    /// loop order differs (the fixed formats add exactly, so the values are
    /// [`FlatRow::pixel`]'s; floats round the additions instead of one product).
    pub fn fill(&self, from: u16, out: &mut [Rgb888]) {
        let mut start = from;
        for block in out.chunks_mut(BLOCK) {
            self.fill_block(start, block);
            start = start.saturating_add(u16::try_from(block.len()).unwrap_or(u16::MAX));
        }
    }

    /// Columns `0..line.len()` in per-pixel mode into a line of any colour type, block by
    /// block through [`FlatRow::fill`].
    pub fn fill_line<C: From<Rgb888>>(&self, line: &mut [C]) {
        let mut block = [Rgb888::default(); BLOCK];
        let mut at = 0u16;
        for slots in line.chunks_mut(BLOCK) {
            let colors = &mut block[..slots.len()];
            self.fill(at, colors);
            for (slot, c) in slots.iter_mut().zip(colors.iter()) {
                *slot = C::from(*c);
            }
            at = at.saturating_add(u16::try_from(slots.len()).unwrap_or(0));
        }
    }

    /// Columns `columns` in per-pixel mode as an iterator, computed a block at a time
    /// through [`FlatRow::fill`] as it is pulled (for a streaming `fill_contiguous`).
    pub fn blocks(&self, columns: core::ops::Range<u16>) -> impl Iterator<Item = Rgb888> + '_ {
        let end = columns.end;
        columns.step_by(BLOCK).flat_map(move |start| {
            let n = usize::from(end - start).min(BLOCK);
            let mut colors = [Rgb888::default(); BLOCK];
            self.fill(start, &mut colors[..n]);
            colors.into_iter().take(n)
        })
    }

    /// One block of [`FlatRow::fill`] (`out.len() <= BLOCK`).
    fn fill_block(&self, from: u16, out: &mut [Rgb888]) {
        // Below every accepted plane's w̃ (which is ≥ 0: σN·D > 0 and r > 0).
        let floor = S::ONE.checked_neg().unwrap_or(S::ZERO);
        let mut best = [floor; BLOCK];
        out.fill(self.background);
        let len = u16::try_from(out.len().min(BLOCK)).unwrap_or(0);
        let to = from.saturating_add(len);
        for s in &self.segments {
            let (a, b) = (s.lo.max(from), s.hi.min(to));
            if a >= b {
                continue;
            }
            let Some(mut w) = s.weight(a) else {
                continue;
            };
            let range = usize::from(a - from)..usize::from(b - from);
            for (best, pixel) in best[range.clone()].iter_mut().zip(&mut out[range]) {
                if w > *best {
                    *best = w;
                    *pixel = s.color;
                }
                // Inside the segment every w̃ fits (both ends were checked); past its
                // last column the value is not used.
                w = w.checked_add(s.step).unwrap_or(w);
            }
        }
    }

    /// Whether segment `j` wins over segment `p` at column `k` (both cover `k`).
    fn beats(&self, j: usize, p: usize, k: u16) -> bool {
        let (sj, sp) = (&self.segments[j], &self.segments[p]);
        match (sj.weight(k), sp.weight(k)) {
            (Some(wj), Some(wp)) => wj > wp || (wj == wp && j < p),
            _ => false,
        }
    }

    /// The first column in `from..to` where segment `j` wins over `p` (which covers the
    /// whole range), if any. `w̃_j − w̃_p` is linear: estimated, then settled.
    fn overtake(&self, j: usize, p: usize, from: u16, to: u16) -> Option<u16> {
        if from >= to {
            return None;
        }
        if self.beats(j, p, from) {
            return Some(from);
        }
        if !self.beats(j, p, to - 1) {
            // A line below at both ends is below in between.
            return None;
        }
        // w̃_j − w̃_p rises from ≤ 0 at `from` to > 0 at `to − 1`: estimate the crossing.
        let (sj, sp) = (&self.segments[j], &self.segments[p]);
        let estimate = (|| {
            let gap = sp.weight(from)?.checked_sub(sj.weight(from)?)?;
            let rate = sj.step.checked_sub(sp.step)?;
            let cols = gap.checked_div(rate)?.floor_to_i32()?;
            let k = i64::from(from) + i64::from(cols) + 1;
            u16::try_from(k.clamp(i64::from(from) + 1, i64::from(to) - 1)).ok()
        })()
        .unwrap_or(to - 1);
        let mut k = estimate;
        while k > from + 1 && self.beats(j, p, k - 1) {
            k -= 1;
        }
        while k < to - 1 && !self.beats(j, p, k) {
            k += 1;
        }
        Some(k)
    }

    /// The scanline from column `from` to `to` as runs `(length, colour)` (span mode):
    /// each run ends where the nearest plane changes.
    pub fn spans(&self, from: u16, to: u16) -> Spans<'_, S> {
        Spans {
            row: self,
            at: from,
            to,
        }
    }

    /// Where the run starting at `k` (seen by `winner`) ends, at most `to`.
    fn run_end(&self, k: u16, winner: Option<usize>, to: u16) -> u16 {
        let mut end = to;
        match winner {
            None => {
                for s in &self.segments {
                    if s.lo > k && s.lo < end && s.hi > s.lo {
                        end = s.lo;
                    }
                }
            }
            Some(p) => {
                end = end.min(self.segments[p].hi);
                for (j, s) in self.segments.iter().enumerate() {
                    if j == p {
                        continue;
                    }
                    if let Some(at) = self.overtake(j, p, s.lo.max(k + 1), s.hi.min(end)) {
                        end = end.min(at);
                    }
                }
            }
        }
        end
    }
}

/// The runs of a scanline: see [`FlatRow::spans`].
#[derive(Debug)]
pub struct Spans<'a, S> {
    row: &'a FlatRow<S>,
    at: u16,
    to: u16,
}

impl<S: Scalar> Iterator for Spans<'_, S> {
    type Item = (u16, Rgb888);

    fn next(&mut self) -> Option<Self::Item> {
        if self.at >= self.to {
            return None;
        }
        let k = self.at;
        let winner = self.row.winner(k).map(|(i, _)| i);
        let end = self.row.run_end(k, winner, self.to).max(k + 1);
        self.at = end;
        let color = winner.map_or(self.row.background, |i| self.row.segments[i].color);
        Some((end - k, color))
    }
}
