//! A frame drawn band after band ([`Frame::bands`]): a sampled frame's corners kept from
//! one band to the next.

use embedded_graphics_core::pixelcolor::Rgb888;

use super::Frame;
use crate::Scalar;
use crate::stats::Counters;

impl<'a, S: Scalar, C: From<Rgb888>> Frame<'a, S, C> {
    /// The frame drawn band after band by [`Bands::render_rows`]: the pixels of
    /// [`Frame::render_rows`], and a frame sampled in blocks keeps each band's bottom
    /// corners for the next band, whose top corners they are, so that drawing a frame a
    /// band at a time (a display's strip buffer) traces each corner once, as one
    /// `render_rows` call over every row does. The corners are the frame's own: a new
    /// frame takes new bands.
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb888;
    /// use fixray::{BlockSize, Frame, Sampling, Scene, I16F16};
    ///
    /// let scene = Scene::<I16F16>::parse(include_str!("../../scenes/spheres.scene"))?;
    /// let frame: Frame<'_, I16F16> =
    ///     Frame::new(&scene).with_sampling(Sampling::blocks(BlockSize::Eight, 8));
    /// let (w, h) = (usize::from(scene.camera.width), scene.camera.height);
    /// let (mut whole, mut band) = (vec![Rgb888::new(0, 0, 0); w * usize::from(h)], vec![]);
    /// frame.render_rows(0..h, &mut whole);
    /// let mut bands = frame.bands();
    /// for top in (0..h).step_by(8) {
    ///     band.resize(w * 8, Rgb888::new(0, 0, 0));
    ///     bands.render_rows(top..(top + 8).min(h), &mut band);
    ///     let at = usize::from(top) * w;
    ///     let n = band.len().min(whole.len() - at);
    ///     assert_eq!(band[..n], whole[at..at + n]);
    /// }
    /// # Ok::<(), fixray::SceneError>(())
    /// ```
    pub fn bands(&self) -> Bands<'_, 'a, S, C> {
        Bands {
            frame: self,
            #[cfg(feature = "sampling")]
            kept: crate::kernel::sampling::Kept::default(),
        }
    }
}

/// A frame drawn band after band ([`Frame::bands`]).
pub struct Bands<'f, 'a, S: Scalar, C> {
    frame: &'f Frame<'a, S, C>,
    /// The corners of the last band's bottom row (a sampled frame's).
    #[cfg(feature = "sampling")]
    kept: crate::kernel::sampling::Kept<S>,
}

impl<S: Scalar, C: From<Rgb888>> Bands<'_, '_, S, C> {
    /// [`Frame::render_rows`], with the corners the last call kept where `rows` starts on
    /// its last row's blocks.
    pub fn render_rows(&mut self, rows: core::ops::Range<u16>, out: &mut [C]) -> usize {
        self.render_rows_counted(rows, out, &mut Counters::default())
    }

    /// [`Frame::render_rows_counted`], with the corners the last call kept.
    pub fn render_rows_counted(
        &mut self,
        rows: core::ops::Range<u16>,
        out: &mut [C],
        counters: &mut Counters,
    ) -> usize {
        let frame = self.frame;
        #[cfg(feature = "sampling")]
        if let Some(sampler) = &frame.sampler {
            return frame.render_rows_sampled(sampler, rows, out, counters, &mut self.kept);
        }
        frame.render_rows_exact(rows, out, counters)
    }
}
