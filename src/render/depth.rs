//! A frame's pixels exact in a display's colour depth ([`Frame::with_depth`]).

use super::Frame;
use crate::kernel::Kernel;
use crate::{Depth, Scalar};

impl<S: Scalar, C> Frame<'_, S, C> {
    /// The frame drawn for a display of colour depth `depth`: each pixel converts to the
    /// colour the exact pixel converts to in that depth (channel by channel, as
    /// `embedded-graphics` converts `Rgb888` to its colour types), and may differ from
    /// the exact pixel only where they convert alike. The default, [`Depth::RGB888`],
    /// draws the exact pixels.
    ///
    /// What it buys: the level-plane kernel (a floor, a back wall, spheres; the boing
    /// ball) draws a run of plane pixels between two restarts of its stepping from the
    /// run's two ends where they convert to one colour and lie in one tile on one side of
    /// the light (every pixel between then does too: its colour is monotone along the
    /// run), so the shallower the depth, the fewer pixels it traces. Other kernels draw
    /// every pixel exact, and so does every kernel without the cargo feature `depth`
    /// (the runs' code is then not linked).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
    /// use fixray::{Depth, Frame, Scene, I16F16};
    ///
    /// let scene = Scene::<I16F16>::parse(include_str!("../../scenes/boing-240x240.scene"))?;
    /// let n = 240 * 16;
    /// let (mut exact, mut panel) = (vec![Rgb888::new(0, 0, 0); n], vec![Rgb888::new(0, 0, 0); n]);
    /// Frame::<_, Rgb888>::new(&scene).render_rows(100..116, &mut exact);
    /// Frame::<_, Rgb888>::new(&scene)
    ///     .with_depth(Depth::of::<Rgb565>())
    ///     .render_rows(100..116, &mut panel);
    /// // On an Rgb565 panel, the same picture (with the `depth` feature, though not the
    /// // same Rgb888 pixels):
    /// assert!(exact.iter().zip(&panel).all(|(a, b)| Rgb565::from(*a) == Rgb565::from(*b)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_depth(mut self, depth: Depth) -> Self {
        if let Kernel::Rows(rows) = &mut self.drawing.kernel {
            rows.depth = depth;
        }
        self
    }
}
