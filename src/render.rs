//! Streaming renderer: one scanline at a time into any `embedded-graphics` [`DrawTarget`].
//!
//! Every entry point goes through a [`Frame`]: the plan and the kernel are chosen once
//! ([`crate::kernel`]'s `select`), then each scanline is drawn with them, so [`render`],
//! [`render_line`], [`Frame::render_line`] and the frame drawn as an `embedded-graphics`
//! [`Drawable`] draw the same pixels.
//!
//! # Colour
//! The shading computes [`Rgb888`] pixels; a frame converts each to its colour type `C`
//! (`From<Rgb888>`, as every colour of `embedded-graphics` has) as it hands it on. `C` is
//! a type parameter of [`Frame`] because [`Drawable`] names one colour per type; it is
//! inferred from the target drawn into or the line filled, and is [`Rgb888`] where a
//! type is written without it.
//!
//! # RAM
//! The library keeps no framebuffer. [`render`] hands each scanline to the target's
//! `fill_contiguous` as an iterator that computes the pixels as the target pulls them
//! (the pure-geometry kernel a block of 64 at a time), so its RAM is O(1) beyond the scene
//! and the frame's per-plane terms. [`render_line`] fills a caller's buffer of `width`
//! pixels (O(width), the caller's RAM), for drivers that want whole lines.

use core::marker::PhantomData;
#[cfg(feature = "sampling")]
use core::ops::Range;

use embedded_graphics_core::Drawable;
use embedded_graphics_core::pixelcolor::{PixelColor, Rgb888};
use embedded_graphics_core::prelude::{DrawTarget, Point, Size};
use embedded_graphics_core::primitives::Rectangle;

use crate::kernel::KernelStages;
use crate::kernel::flat::PlaneMode;
#[cfg(feature = "sampling")]
use crate::kernel::sampling::{Sampler, Sampling, sampled_rows, sampler};

mod bands;
mod depth;
pub use bands::Bands;
#[cfg(feature = "sampling")]
mod sampled;
use crate::kernel::{self, Drawing, KernelKind, RowSink};
use crate::shade::stages::{Shading, shading_for, stage, with_stages};
use crate::stats::Counters;
use crate::{AsView, Scalar, SceneView, Traced};

/// A frame of a scene: what is constant for the frame (the plan, the kernel, its
/// per-plane terms and reciprocals) computed once in [`Frame::new`], then drawn line by
/// line ([`Frame::render_line`], for display drivers fed a scanline at a time) or
/// streamed into a target as an `embedded-graphics` [`Drawable`] (`frame.draw(&mut
/// display)`, or [`Frame::draw_counted`] to count its rays). [`render_line`] and
/// [`render`] build one per call.
///
/// `C` is the colour the frame draws in: the display's, inferred from the target it draws
/// into or the line it fills (the shading's [`Rgb888`] converted by `From`, as
/// `embedded-graphics`' image decoders do), [`Rgb888`] where the type is written without
/// it.
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb565, prelude::*};
/// use fixray::{Frame, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera c { pixeldim 3 2 worlddim 3 2 viewpoint 1.5 1 5 } background 1 0 0",
/// )?;
/// let mut display = MockDisplay::<Rgb565>::new();
/// let frame = Frame::new(&scene); // a Frame<'_, I16F16, Rgb565>: the display's colour
/// frame.draw(&mut display)?; // one fill_contiguous per scanline
/// display.assert_pattern(&["RRR", "RRR"]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// Line by line, into a driver's buffer:
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use fixray::{Frame, PlaneMode, Scene, I16F16, render_line};
///
/// let scene = Scene::<I16F16>::parse(include_str!("../scenes/planes.scene")).unwrap();
/// let frame = Frame::new(&scene);
/// let spans = Frame::with_mode(&scene, PlaneMode::Spans);
/// let black = Rgb565::new(0, 0, 0);
/// let (mut a, mut b, mut c) = ([black; 160], [black; 160], [black; 160]);
/// for row in 0..scene.camera.height {
///     frame.render_line(row, &mut a); // send `a` to the display here
///     render_line(&scene, row, &mut b);
///     spans.render_line(row, &mut c);
///     assert_eq!(a, b);
///     assert_eq!(a, c); // span mode draws the per-pixel image in the fixed formats
/// }
/// ```
#[derive(Debug, Clone)]
pub struct Frame<'a, S: Scalar, C = Rgb888> {
    scene: SceneView<'a, S>,
    shading: Shading,
    drawing: Drawing<S>,
    mode: PlaneMode,
    #[cfg(feature = "sampling")]
    sampling: Sampling,
    /// The blocks' per-frame part, for a frame sampled in blocks (`None`: exact).
    #[cfg(feature = "sampling")]
    sampler: Option<Sampler<S>>,
    /// The colour drawn in (no value: `fn() -> C` keeps the frame `Send` and `Sync`
    /// whatever `C` is).
    color: PhantomData<fn() -> C>,
}

impl<'a, S: Scalar, C> Frame<'a, S, C> {
    /// Prepares a frame of `scene` (for the stages its plan needs), pure-geometry plane
    /// scenes drawn per pixel.
    pub fn new(scene: &'a impl AsView<S>) -> Self {
        Self::with_mode(scene, PlaneMode::PerPixel)
    }

    /// [`Frame::new`] with pure-geometry plane scenes drawn in `mode` (a drawing option:
    /// other scenes draw the same either way).
    pub fn with_mode(scene: &'a impl AsView<S>, mode: PlaneMode) -> Self {
        let mut scene = scene.view();
        let plan = scene.plan();
        scene.lights_on_surfaces = plan.lights_on_surfaces;
        let shading = shading_for(&plan);
        stage(&mut scene, shading);
        let drawing = with_stages!(shading, kernel::select::<S>(&scene, &plan));
        Self {
            scene,
            shading,
            drawing,
            mode,
            #[cfg(feature = "sampling")]
            sampling: Sampling::Exact,
            #[cfg(feature = "sampling")]
            sampler: None,
            color: PhantomData,
        }
    }

    /// The frame drawn with `sampling` (cargo feature `sampling`; [`Sampling::Exact`],
    /// every pixel traced, is the default): in [`Sampling::Blocks`], blocks traced at
    /// their corners (by the frame's kernel) and filled between them where a certificate
    /// holds (same surface, tile, shadow state; no sphere's box; spread within the bound),
    /// every other block drawn as the exact frame draws it. Every entry point draws the
    /// same pixels; [`Frame::render_rows`] traces each band of blocks' corners once, the
    /// others once per scanline. Frames of a kind the certificates do not cover are drawn
    /// exact ([`Frame::sampled`]).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb888;
    /// use fixray::{BlockSize, Frame, Sampling, Scene, I16F16};
    ///
    /// let scene = Scene::<I16F16>::parse(include_str!("../scenes/boing.scene"))?;
    /// let exact = Frame::new(&scene);
    /// let zero = Frame::new(&scene).with_sampling(Sampling::blocks(BlockSize::Eight, 0));
    /// let loose = Frame::new(&scene).with_sampling(Sampling::blocks(BlockSize::Eight, 3));
    /// let black = Rgb888::new(0, 0, 0);
    /// let (mut a, mut b, mut c) = ([black; 128 * 64], [black; 128 * 64], [black; 128 * 64]);
    /// exact.render_rows(0..64, &mut a);
    /// zero.render_rows(0..64, &mut b);
    /// loose.render_rows(0..64, &mut c);
    /// assert_eq!(a, b); // a zero bound fills only blocks of one colour: the exact frame
    /// let off = a.iter().zip(&c).filter(|(x, y)| x != y).count();
    /// assert!(off > 0 && off < 128 * 64 / 4);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[cfg(feature = "sampling")]
    pub fn with_sampling(mut self, sampling: Sampling) -> Self {
        let plan = self.scene.plan();
        self.sampler = sampler(&self.scene, &plan, &self.drawing, sampling);
        self.sampling = sampling;
        self
    }

    /// How this frame samples its pixels ([`Frame::with_sampling`]).
    #[cfg(feature = "sampling")]
    pub fn sampling(&self) -> Sampling {
        self.sampling
    }

    /// Whether this frame is drawn in blocks: its sampling is [`Sampling::Blocks`] and
    /// the scene is of the kind the blocks' certificates cover (the crate's rules,
    /// infinite planes and spheres, point lights without glints, mirrors, translucency or
    /// a light on a surface); `false`: every pixel is traced.
    #[cfg(feature = "sampling")]
    pub fn sampled(&self) -> bool {
        self.sampler.is_some()
    }

    /// Which primary-ray kernel draws this frame, chosen once in [`Frame::new`] (the
    /// renderer's only choice of kernel): the flat kernel for pure geometry of infinite
    /// planes, the fast kernel for other scenes under the crate's rules, the reference
    /// path for the course's rules (and where a fast kernel's per-frame quantity does
    /// not fit the format). Always the reference path in a build without the cargo
    /// feature `kernels` (on by default).
    ///
    /// ```
    /// use fixray::{Frame, KernelKind, Scene, I16F16};
    ///
    /// let planes = Scene::<I16F16>::parse(include_str!("../scenes/planes.scene")).unwrap();
    /// // The kernel does not depend on the colour; a frame that draws nothing names one.
    /// let frame: Frame<'_, I16F16> = Frame::new(&planes);
    /// assert_eq!(frame.kernel(), KernelKind::Flat);
    /// let lit = Scene::<I16F16>::parse(include_str!("../scenes/default.scene")).unwrap();
    /// assert_eq!(Frame::<_>::new(&lit).kernel(), KernelKind::Fast);
    /// ```
    pub fn kernel(&self) -> KernelKind {
        self.drawing.kind()
    }

    /// Which kernel draws scanline `row`: [`Frame::kernel`], except for a scanline the
    /// flat kernel hands back (a per-row quantity out of the format's range), which the
    /// next kernel of the chain draws (fast, or the reference path), and one the
    /// level-plane kernel cannot decide once (a plane near edge-on to the row), which the
    /// fast kernel draws.
    pub fn row_kernel(&self, row: u16) -> KernelKind {
        self.drawing.row_kind(&self.scene, row)
    }

    /// The primary ray of pixel (`column`, `row`) traced on the reference path (the
    /// definition, a normalised ray), with the stage set this frame chose:
    /// [`crate::shade::trace_pixel`] without working out the plan again.
    pub fn trace_pixel(&self, column: u16, row: u16) -> Traced<S> {
        crate::shade::trace_pixel_with(&self.scene, self.shading, column, row)
    }

    /// How pure-geometry plane scenes are drawn in this frame.
    pub fn mode(&self) -> PlaneMode {
        self.mode
    }

    /// Which pixels of this frame may differ from `before` (the frame shown before it):
    /// what an animation redraws on a display that keeps its picture. See [`Changes`].
    pub fn changes_since<'f, D>(&'f self, before: &'f Frame<'_, S, D>) -> Changes<'f, S> {
        // A block filled in one frame may be traced in the other: a sampled frame may
        // change anywhere.
        #[cfg(feature = "sampling")]
        let exact = self.sampler.is_none() && before.sampler.is_none();
        #[cfg(not(feature = "sampling"))]
        let exact = true;
        let moved = kernel::moved_spheres(&before.scene, &self.scene).filter(|_| exact);
        let moved = moved.map(|objects| Moved {
            objects,
            before: (&before.scene, &before.drawing),
            after: (&self.scene, &self.drawing),
        });
        Changes {
            width: self.scene.camera.width,
            height: self.scene.camera.height,
            moved,
        }
    }
}

/// Which pixels of a frame may differ from the frame before it ([`Frame::changes_since`]):
/// what an animation redraws on a display that keeps its picture, such as an SPI panel's
/// own memory.
///
/// When the two scenes differ only in where some spheres are (the frames of an
/// [`crate::anim::Bounce`]) and the level-plane kernel draws both ([`KernelKind::Rows`]:
/// lit level planes and spheres, the boing ball's kind), a scanline changes only inside
/// the moved spheres' boxes on the screen, old and new, unless their shadows can fall on
/// it (then it changes whole). Two exact frames of the same scene change nowhere; any
/// other pair (a frame sampled in blocks among them) changes everywhere. The columns are certified, not estimated: a pixel outside them is
/// drawn from nothing that differs between the two frames (the level-plane kernel tests a
/// sphere only inside its box, and casts its shadow only on the rows its shadow cone
/// meets), so drawing them over the frame before ([`Frame::render_columns`]) gives the
/// frame bit for bit.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use fixray::anim::Bounce;
/// use fixray::{Frame, Scene, I16F16};
///
/// let mut scene = Scene::<I16F16>::parse(include_str!("../scenes/boing.scene"))?;
/// let mut next = scene.clone();
/// let bounce = Bounce::boing(&scene.objects)?;
/// bounce.apply(&mut next, 1)?;
/// let (before, after) = (Frame::new(&scene), Frame::new(&next));
/// let changes = after.changes_since(&before);
/// let mut shown = [[Rgb565::new(0, 0, 0); 128]; 64]; // the display's memory: frame 0
/// for (row, line) in (0..).zip(shown.iter_mut()) {
///     before.render_line(row, line);
/// }
/// let mut redrawn = 0;
/// for (row, line) in (0..).zip(shown.iter_mut()) {
///     if let Some(columns) = changes.columns(row) {
///         let span = usize::from(columns.start)..usize::from(columns.end);
///         redrawn += span.len();
///         after.render_columns(row, columns, &mut line[span]);
///     }
/// }
/// let mut whole = [Rgb565::new(0, 0, 0); 128];
/// for (row, line) in (0..).zip(shown.iter()) {
///     after.render_line(row, &mut whole);
///     assert_eq!(line, &whole); // frame 1, bit for bit
/// }
/// assert!(redrawn < 128 * 64 / 2);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Changes<'f, S: Scalar> {
    width: u16,
    height: u16,
    /// The moved spheres and both frames (`None`: the scenes differ in more).
    moved: Option<Moved<'f, S>>,
}

/// Two frames whose scenes differ only in the centres of the spheres `objects`.
#[derive(Debug, Clone, Copy)]
struct Moved<'f, S: Scalar> {
    objects: u8,
    before: (&'f SceneView<'f, S>, &'f Drawing<S>),
    after: (&'f SceneView<'f, S>, &'f Drawing<S>),
}

impl<S: Scalar> Changes<'_, S> {
    /// The columns of scanline `row` to redraw; `None`: the row is the frame before's.
    pub fn columns(&self, row: u16) -> Option<core::ops::Range<u16>> {
        if row >= self.height {
            return None;
        }
        match &self.moved {
            None => Some(0..self.width),
            Some(m) if m.objects == 0 => None,
            Some(m) => kernel::changed_columns(m.before, m.after, m.objects, row),
        }
    }

    /// Whether every pixel may differ (the scenes differ in more than where spheres are).
    pub fn everywhere(&self) -> bool {
        self.moved.is_none()
    }
}

impl<S: Scalar, C: From<Rgb888>> Frame<'_, S, C> {
    /// Renders scanline `row` into `line`: pixel `i` of `line` is column `i`. Columns
    /// beyond the camera's width (or beyond `line`) are left untouched; a row beyond the
    /// camera's height leaves `line` untouched.
    pub fn render_line(&self, row: u16, line: &mut [C]) {
        self.render_line_counted(row, line, &mut Counters::default());
    }

    /// [`Frame::render_line`], adding the line's rays and stage evaluations to `counters`
    /// (counted with the `stats` feature; without it they stay 0; a frame sampled in
    /// blocks counts none).
    ///
    /// ```
    /// use embedded_graphics::pixelcolor::Rgb888;
    /// use fixray::stats::Counters;
    /// use fixray::{Frame, Scene, I16F16};
    ///
    /// let scene = Scene::<I16F16>::parse(include_str!("../scenes/default.scene"))?;
    /// let mut line = [Rgb888::new(0, 0, 0); 160];
    /// let mut counters = Counters::default();
    /// Frame::new(&scene).render_line_counted(60, &mut line, &mut counters);
    /// // Counted with the `stats` feature (the crate's tests turn it on): one primary
    /// // ray a pixel.
    /// assert!(counters.primary_rays == 160 || counters.primary_rays == 0);
    /// # Ok::<(), fixray::SceneError>(())
    /// ```
    pub fn render_line_counted(&self, row: u16, line: &mut [C], counters: &mut Counters) {
        if row >= self.scene.camera.height {
            return;
        }
        #[cfg(feature = "sampling")]
        if let Some(sampler) = &self.sampler {
            return self.sampled_line(sampler, row, line, counters);
        }
        self.exact_line(row, line, counters);
    }

    /// [`Frame::render_line_counted`] of a frame sampled in blocks. Out of line: the
    /// blocks' corners and runs live in its stack frame, not in the exact line's.
    #[cfg(feature = "sampling")]
    #[inline(never)]
    fn sampled_line(
        &self,
        sampler: &Sampler<S>,
        row: u16,
        line: &mut [C],
        counters: &mut Counters,
    ) {
        let n = u16::try_from(line.len()).unwrap_or(u16::MAX);
        let stride = line.len();
        let mut corners = 0;
        sampled_rows(
            &self.scene,
            (sampler, self.drawing.primary()),
            (row..row + 1, 0..n),
            (line, stride),
            &mut |r, runs: &[Range<u16>], line: &mut [C]| {
                self.exact_runs(r, runs, line, 0, counters);
            },
            None,
            &mut corners,
        );
        crate::stats::count_n(&mut counters.corners, corners);
    }

    /// [`Frame::render_line_counted`] as the exact frame draws it.
    fn exact_line(&self, row: u16, line: &mut [C], counters: &mut Counters) {
        with_stages!(
            self.shading,
            kernel::line::<S, C>(&self.scene, &self.drawing, self.mode, row, line, counters)
        );
    }

    /// Rows `rows` into `out`, row after row, each the camera's width (`out[(r −
    /// rows.start)·width + x]` is pixel (`x`, `r`)); rows beyond the camera's height or
    /// beyond `out` are left untouched. The pixels of [`Frame::render_line`]; a frame
    /// sampled in blocks traces each band of blocks' corners once here (once per
    /// scanline there): its RAM is the caller's `out`, a band being the block's side in
    /// scanlines. Returns how many of the pixels were filled from blocks' corners rather
    /// than traced (0 in an exact frame).
    pub fn render_rows(&self, rows: core::ops::Range<u16>, out: &mut [C]) -> usize {
        self.render_rows_counted(rows, out, &mut Counters::default())
    }

    /// [`Frame::render_rows`], counting the traced pixels' rays and stage evaluations
    /// and a sampled frame's blocks' corners in `counters` (with the `stats` feature).
    ///
    /// ```
    /// use fixray::stats::Counters;
    /// use fixray::{Frame, Scene, I16F16};
    /// use embedded_graphics::pixelcolor::Rgb888;
    ///
    /// let scene = Scene::<I16F16>::parse(include_str!("../scenes/spheres.scene"))?;
    /// let w = scene.camera.width;
    /// let mut band = vec![Rgb888::new(0, 0, 0); usize::from(w) * 8];
    /// let mut counters = Counters::default();
    /// let frame: Frame<'_, I16F16> = Frame::new(&scene);
    /// let filled = frame.render_rows_counted(0..8, &mut band, &mut counters);
    /// assert_eq!(filled, 0); // an exact frame traces every pixel
    /// if cfg!(feature = "stats") {
    ///     assert_eq!(counters.primary_rays, u32::from(w) * 8);
    /// }
    /// # Ok::<(), fixray::SceneError>(())
    /// ```
    pub fn render_rows_counted(
        &self,
        rows: core::ops::Range<u16>,
        out: &mut [C],
        counters: &mut Counters,
    ) -> usize {
        #[cfg(feature = "sampling")]
        if let Some(sampler) = &self.sampler {
            let mut kept = crate::kernel::sampling::Kept::default();
            return self.render_rows_sampled(sampler, rows, out, counters, &mut kept);
        }
        self.render_rows_exact(rows, out, counters)
    }

    /// [`Frame::render_rows_counted`] of an exact frame.
    fn render_rows_exact(
        &self,
        rows: core::ops::Range<u16>,
        out: &mut [C],
        counters: &mut Counters,
    ) -> usize {
        let width = usize::from(self.scene.camera.width);
        let end = rows.end.min(self.scene.camera.height);
        for row in rows.start..end {
            let at = usize::from(row - rows.start) * width;
            let Some(slice) = out.get_mut(at..) else {
                break;
            };
            let n = width.min(slice.len());
            self.render_line_counted(row, &mut slice[..n], counters);
        }
        0
    }
}

impl<S: Scalar, C: From<Rgb888>> Frame<'_, S, C> {
    /// Columns `columns` of scanline `row` into `out` (`out[i]` is column
    /// `columns.start + i`): the pixels [`Frame::render_line`] draws there, for redrawing
    /// part of a scanline ([`Changes`]). Columns beyond the camera's width or beyond `out`
    /// are left untouched. The kernels resume a scanline at any column with the whole
    /// scanline's pixels (from the last column where it restarts its stepping, at most 15
    /// pixels before; a pure-geometry scanline from the multiple of 64 at or before the
    /// first column): the cost is that of the columns asked for.
    pub fn render_columns(&self, row: u16, columns: core::ops::Range<u16>, out: &mut [C]) {
        #[cfg(feature = "sampling")]
        if let Some(sampler) = &self.sampler {
            if row < self.scene.camera.height {
                let stride = out.len();
                sampled_rows(
                    &self.scene,
                    (sampler, self.drawing.primary()),
                    (row..row + 1, columns.clone()),
                    (out, stride),
                    &mut |r, runs: &[Range<u16>], line: &mut [C]| {
                        self.exact_runs(r, runs, line, columns.start, &mut Counters::default())
                    },
                    None,
                    &mut 0,
                );
            }
            return;
        }
        self.exact_columns(row, columns, out);
    }

    /// [`Frame::render_columns`] as the exact frame draws them.
    fn exact_columns(&self, row: u16, columns: core::ops::Range<u16>, out: &mut [C]) {
        let end = columns.end.min(self.scene.camera.width);
        if row >= self.scene.camera.height || columns.start >= end {
            return;
        }
        if columns.start == 0 {
            // From the row's start: the whole scanline's path, cut at `end`.
            let n = usize::from(end).min(out.len());
            self.exact_line(row, &mut out[..n], &mut Counters::default());
            return;
        }
        let from = kernel::resume_from(&self.drawing, columns.start);
        let mut sink = Skip {
            skip: usize::from(columns.start - from),
            out,
        };
        with_stages!(
            self.shading,
            columns_with::<S, C, Skip<'_, C>>(self, row, from..end, &mut sink)
        );
    }
}

/// Writes a streamed scanline into a slice of colours, after its first `skip` pixels.
struct Skip<'o, C> {
    skip: usize,
    out: &'o mut [C],
}

impl<C: From<Rgb888>> RowSink<Rgb888> for Skip<'_, C> {
    type Error = core::convert::Infallible;

    fn fill(&mut self, pixels: impl Iterator<Item = Rgb888>) -> Result<(), Self::Error> {
        for (slot, c) in self.out.iter_mut().zip(pixels.skip(self.skip)) {
            *slot = C::from(c);
        }
        Ok(())
    }
}

impl<S: Scalar, C: PixelColor + From<Rgb888>> Frame<'_, S, C> {
    /// The frame drawn into `target` as [`Drawable::draw`] draws it (one `fill_contiguous`
    /// call per scanline, top to bottom, cut to the target's bounding box), adding its
    /// rays and stage evaluations to `counters` (counted with the `stats` feature;
    /// without it they stay 0).
    ///
    /// # Errors
    /// The target's own error, from the first scanline it refused.
    ///
    /// ```
    /// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb888};
    /// use fixray::stats::Counters;
    /// use fixray::{Frame, Scene, I16F16};
    ///
    /// let scene = Scene::<I16F16>::parse(
    ///     "camera c { pixeldim 3 2 worlddim 3 2 viewpoint 1.5 1 5 } background 0 1 0",
    /// )?;
    /// let mut display = MockDisplay::<Rgb888>::new();
    /// let mut counters = Counters::default();
    /// Frame::new(&scene).draw_counted(&mut display, &mut counters)?;
    /// display.assert_pattern(&["GGG", "GGG"]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn draw_counted<D>(&self, target: &mut D, counters: &mut Counters) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        #[cfg(feature = "sampling")]
        if self.sampler.is_some() {
            return sampled::draw_sampled(self, target);
        }
        with_stages!(self.shading, draw_with::<S, D>(self, target, counters))
    }
}

/// The frame as an `embedded-graphics` drawable: `frame.draw(&mut display)` streams it
/// into the display, one `fill_contiguous` call per scanline (a frame sampled in blocks:
/// per 64 pixels of a scanline), top to bottom, cut to the display's bounding box: only
/// visible pixels are computed, each written once. The target's error is that of the
/// first scanline it refused.
impl<S: Scalar, C: PixelColor + From<Rgb888>> Drawable for Frame<'_, S, C> {
    type Color = C;
    type Output = ();

    fn draw<D>(&self, target: &mut D) -> Result<(), D::Error>
    where
        D: DrawTarget<Color = C>,
    {
        self.draw_counted(target, &mut Counters::default())
    }
}

impl<S: Scalar, C> Frame<'_, S, C> {
    /// Columns `start..start + out.len()` of scanline `row` into `out` (the shading's
    /// colours, whatever the frame's `C`), streamed as [`Frame::draw_counted`] computes them
    /// (no line buffer of the frame's width: a tool compares two frames chunk by chunk).
    /// Chunks that start at multiples of 64 give exactly the pixels of an exact frame's
    /// [`Frame::render_line`] (the pure-geometry kernel's blocks; the other kernels resume
    /// exactly anywhere).
    pub(crate) fn render_chunk(&self, row: u16, start: u16, out: &mut [Rgb888]) {
        let end = u16::try_from(out.len())
            .ok()
            .and_then(|n| start.checked_add(n))
            .unwrap_or(u16::MAX)
            .min(self.scene.camera.width);
        if row >= self.scene.camera.height || start >= end {
            return;
        }
        with_stages!(
            self.shading,
            columns_with::<S, C, Skip<'_, Rgb888>>(
                self,
                row,
                start..end,
                &mut Skip { skip: 0, out }
            )
        );
    }
}

/// Streams columns `columns` of scanline `row` of `frame` to `sink`.
fn columns_with<S: Scalar, T: KernelStages, C, K: RowSink<Rgb888>>(
    frame: &Frame<'_, S, C>,
    row: u16,
    columns: core::ops::Range<u16>,
    sink: &mut K,
) {
    let _ = kernel::stream::<S, T, Rgb888, _>(
        &frame.scene,
        &frame.drawing,
        frame.mode,
        row,
        columns,
        &mut Counters::default(),
        sink,
    );
}

/// The first and last columns of the frame `camera` draws that `target` shows, and its
/// rows (`None`: none).
fn visible<S, D: DrawTarget>(
    camera: &crate::Camera<S>,
    target: &D,
) -> Option<((u16, u16), core::ops::RangeInclusive<u16>)> {
    let full = Rectangle::new(
        Point::zero(),
        Size::new(u32::from(camera.width), u32::from(camera.height)),
    );
    let area = full.intersection(&target.bounding_box());
    let bottom_right = area.bottom_right()?;
    // Both corners lie inside `full`, whose coordinates fit u16.
    let to_u16 = |v: i32| u16::try_from(v).unwrap_or(0);
    Some((
        (to_u16(area.top_left.x), to_u16(bottom_right.x)),
        to_u16(area.top_left.y)..=to_u16(bottom_right.y),
    ))
}

fn draw_with<S, T, D>(
    frame: &Frame<'_, S, D::Color>,
    target: &mut D,
    counters: &mut Counters,
) -> Result<(), D::Error>
where
    S: Scalar,
    T: KernelStages,
    D: DrawTarget,
    D::Color: From<Rgb888>,
{
    let Some(((x0, x1), rows)) = visible(&frame.scene.camera, target) else {
        return Ok(());
    };
    for row in rows {
        let line = Rectangle::new(
            Point::new(i32::from(x0), i32::from(row)),
            Size::new(u32::from(x1 - x0) + 1, 1),
        );
        kernel::stream::<S, T, D::Color, _>(
            &frame.scene,
            &frame.drawing,
            frame.mode,
            row,
            x0..x1 + 1,
            counters,
            &mut Row { target, area: line },
        )?;
    }
    Ok(())
}

/// One row of a target, as the kernels stream into it.
struct Row<'t, D> {
    target: &'t mut D,
    area: Rectangle,
}

impl<D: DrawTarget> RowSink<D::Color> for Row<'_, D> {
    type Error = D::Error;

    fn fill(&mut self, pixels: impl Iterator<Item = D::Color>) -> Result<(), D::Error> {
        self.target.fill_contiguous(&self.area, pixels)
    }
}

/// Renders scanline `row` into `line`: pixel `i` of `line` is column `i`. Columns beyond
/// the camera's width (or beyond `line`) are left untouched; a row beyond the camera's
/// height leaves `line` untouched.
///
/// ```
/// use embedded_graphics::pixelcolor::Rgb565;
/// use fixray::{render_line, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera c { pixeldim 4 2 worlddim 4 2 viewpoint 2 1 5 } background 0 0 1",
/// )
/// .unwrap();
/// let mut line = [Rgb565::new(0, 0, 0); 4];
/// render_line(&scene, 0, &mut line);
/// assert_eq!(line, [Rgb565::new(0, 0, 31); 4]);
/// ```
pub fn render_line<S: Scalar, C: From<Rgb888>>(scene: &impl AsView<S>, row: u16, line: &mut [C]) {
    Frame::new(scene).render_line(row, line);
}

/// Renders the scene into `target`, one `fill_contiguous` call per scanline, top to bottom:
/// `Frame::new(scene).draw(target)` ([`Frame`] as a [`Drawable`]).
///
/// The image covers the rectangle `(0, 0)`–`(width, height)` of the camera's `pixeldim`,
/// cut to the target's bounding box: only visible pixels are traced, each written once.
///
/// # Errors
/// The target's own error, from the first scanline it refused.
///
/// ```
/// use embedded_graphics::{mock_display::MockDisplay, pixelcolor::Rgb888};
/// use fixray::{render, Scene, I16F16};
///
/// let scene = Scene::<I16F16>::parse(
///     "camera c { pixeldim 3 2 worlddim 3 2 viewpoint 1.5 1 5 } background 1 0 0",
/// )
/// .unwrap();
/// let mut display = MockDisplay::<Rgb888>::new();
/// render(&scene, &mut display).unwrap();
/// display.assert_pattern(&["RRR", "RRR"]);
/// ```
pub fn render<S, D>(scene: &impl AsView<S>, target: &mut D) -> Result<(), D::Error>
where
    S: Scalar,
    D: DrawTarget,
    D::Color: PixelColor + From<Rgb888>,
{
    Frame::new(scene).draw(target)
}

/// Renders scanline `row` with the ambient-only stage set instead of the one the scene's
/// plan picks (for the benchmark of what compiled-out stages save): stages the scene
/// needs are simply not drawn.
#[doc(hidden)]
pub fn render_line_ambient<S: Scalar, C: From<Rgb888>>(
    scene: &impl AsView<S>,
    row: u16,
    line: &mut [C],
    counters: &mut Counters,
) {
    use crate::shade::stages::AmbientOnly;
    let scene = &scene.view();
    if row < scene.camera.height {
        let drawing = kernel::select::<S, AmbientOnly>(scene, &scene.plan());
        kernel::line::<S, AmbientOnly, C>(
            scene,
            &drawing,
            PlaneMode::PerPixel,
            row,
            line,
            counters,
        );
    }
}

/// Streams columns `start..` of scanline `row` (as many as `out` holds, up to the
/// camera's width) into `out` with the kernel the renderer chooses (`Frame::draw`'s path
/// onto a target whose area starts at column `start`); `fast`: with the fast kernel
/// where the renderer would choose a cheaper one. For the tests of the level-plane kernel
/// against the fast kernel on partial scanlines.
#[doc(hidden)]
pub fn render_columns_with<S: Scalar>(
    scene: &impl AsView<S>,
    fast: bool,
    row: u16,
    start: u16,
    out: &mut [Rgb888],
) {
    let mut frame = Frame::<S>::new(scene);
    if fast {
        frame.drawing = kernel::fast_only(&frame.scene);
    }
    frame.render_chunk(row, start, out);
}
