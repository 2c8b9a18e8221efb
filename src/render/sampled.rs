//! A frame sampled in blocks (cargo feature `sampling`): its bands of rows, its traced
//! runs, and the frame drawn into a target.

use core::ops::Range;

use embedded_graphics_core::pixelcolor::Rgb888;
use embedded_graphics_core::prelude::{DrawTarget, Point, Size};
use embedded_graphics_core::primitives::Rectangle;

use super::Frame;
use crate::Scalar;
use crate::kernel::sampling::{Kept, Sampler, sampled_rows};
use crate::kernel::{self};
use crate::shade::stages::with_stages;
use crate::stats::{Counters, count_n};

impl<S: Scalar, C: From<Rgb888>> Frame<'_, S, C> {
    /// [`Frame::render_rows`] of a frame sampled in blocks: band by band, each band's
    /// bottom corners kept for the next. Out of line: its corners live in its own stack
    /// frame, not in an exact frame's.
    /// `kept`: the corners a band before kept (a [`super::Bands`]' own, or a fresh one).
    #[inline(never)]
    pub(super) fn render_rows_sampled(
        &self,
        sampler: &Sampler<S>,
        rows: core::ops::Range<u16>,
        out: &mut [C],
        counters: &mut Counters,
        kept: &mut Kept<S>,
    ) -> usize {
        let mut filled = 0;
        let width = usize::from(self.scene.camera.width);
        let end = rows.end.min(self.scene.camera.height);
        let band = sampler.size();
        let mut corners = 0;
        let mut row = rows.start;
        while row < end {
            let next = (row / band + 1).saturating_mul(band).min(end);
            let at = usize::from(row - rows.start) * width;
            let Some(slice) = out.get_mut(at..) else {
                break;
            };
            filled += sampled_rows(
                &self.scene,
                (sampler, self.drawing.primary()),
                (row..next, 0..self.scene.camera.width),
                (slice, width),
                &mut |r, runs: &[Range<u16>], line: &mut [C]| {
                    self.exact_runs(r, runs, line, 0, counters);
                },
                Some(&mut *kept),
                &mut corners,
            );
            row = next;
        }
        count_n(&mut counters.corners, corners);
        filled
    }
    /// Columns `runs` of scanline `row` as the exact frame draws them, into `line`
    /// (`line[i]` is column `origin + i`), their rays counted in `counters`.
    pub(super) fn exact_runs(
        &self,
        row: u16,
        runs: &[Range<u16>],
        line: &mut [C],
        origin: u16,
        counters: &mut Counters,
    ) {
        let mut put = |column: u16, c: C| {
            if let Some(slot) = line.get_mut(usize::from(column - origin)) {
                *slot = c;
            }
        };
        with_stages!(
            self.shading,
            kernel::runs::<S, C>(
                &self.scene,
                &self.drawing,
                self.mode,
                row,
                runs,
                counters,
                &mut put
            )
        );
    }
}

/// A frame sampled in blocks drawn into `target`: each scanline in pieces of
/// [`SAMPLED_PIECE`] pixels (a buffer on the stack), one `fill_contiguous` call each.
pub(super) fn draw_sampled<S, D>(
    frame: &Frame<'_, S, D::Color>,
    target: &mut D,
) -> Result<(), D::Error>
where
    S: Scalar,
    D: DrawTarget,
    D::Color: From<Rgb888>,
{
    let Some(((x0, x1), rows)) = super::visible(&frame.scene.camera, target) else {
        return Ok(());
    };
    let mut piece = [D::Color::from(Rgb888::new(0, 0, 0)); SAMPLED_PIECE];
    for row in rows {
        let mut x = x0;
        while x <= x1 {
            let n = (x1 - x + 1).min(u16::try_from(SAMPLED_PIECE).unwrap_or(1));
            let out = &mut piece[..usize::from(n)];
            frame.render_columns(row, x..x + n, out);
            let at = Rectangle::new(
                Point::new(i32::from(x), i32::from(row)),
                Size::new(u32::from(n), 1),
            );
            target.fill_contiguous(&at, out.iter().copied())?;
            x += n;
        }
    }
    Ok(())
}

/// The pixels a sampled frame hands a target at once ([`Frame::draw_counted`]).
const SAMPLED_PIECE: usize = 64;
