//! Primary-ray kernels: how the pixels of a scanline are found. [`select`] is the only
//! eligibility rule and the chain after the flat kernel is written once
//! ([`Drawing::handed_back`]); the renderer (`render.rs`) asks [`select`] once per frame
//! and draws every scanline with what it chose ([`crate::Frame::kernel`] says which).
//!
//! - **flat** (`flat.rs`): pure geometry (infinite planes, no lighting, no mirrors), a
//!   scanline at a time, no division per pixel; per-pixel or span mode.
//! - **fast** (`fast/`): scenes of planes and spheres (the crate's rules): per-frame
//!   `N·eye` and `|eye − c|² − r²`,
//!   unnormalised directions stepped along the scanline, one division per pixel (and a
//!   square root per sphere the ray meets).
//! - **rows** (`rows/`): lit scenes of level planes (`N.x = 0`) and spheres with
//!   diffuse lights and shadows: each scanline's plane and its light terms once per row,
//!   the fast kernel's pixels bit for bit.
//! - **reference**: the definition, one normalised ray per pixel; `scanline.rs` draws a
//!   scanline's pixels with the fast kernel's hits or the definition's, and `shading.rs`
//!   shades the lit plane hits of every kernel (with the scanline's memo, `memo.rs`).
//!
//! A scanline the flat kernel hands back (a quantity out of the format's range) is drawn
//! by the fast kernel if it applies, a scanline the level-plane kernel cannot decide once
//! by the fast kernel, a pixel the fast kernel hands back by the reference path: every
//! entry point (`render`, `render_line`, `Frame`) takes the same chain, so they draw the
//! same pixels (`tests/kernels.rs`).

pub(crate) mod fast;
pub(crate) mod flat;
mod memo;
mod rows;
#[cfg(feature = "sampling")]
pub(crate) mod sampling;
mod scanline;
mod shading;
#[cfg(test)]
mod tests;

use embedded_graphics_core::pixelcolor::Rgb888;

use crate::shade::stages::Stages;
use crate::stats::{Counters, count_primary};
use crate::{Plan, Rules, Scalar, SceneView, Shape};
use fast::Primary;
use flat::{Flat, PlaneMode};
use rows::Rows;

pub(crate) use memo::KernelStages;
pub(crate) use rows::moved_spheres;

/// Where a scanline of a frame drawn with `drawing` must start for its pixels from
/// column `column` on to be the whole scanline's: the fast and level-plane kernels
/// resume at any column (`Primary::row_resumed`: their stepping from the last resync
/// column), the reference path has no state from pixel to pixel, the pure-geometry
/// kernel starts at its block before it.
pub(crate) fn resume_from<S: Scalar>(drawing: &Drawing<S>, column: u16) -> u16 {
    match drawing.kernel {
        Kernel::Flat(_) => column / FLAT_RESUME * FLAT_RESUME,
        Kernel::Fast(_) | Kernel::Rows(_) | Kernel::Reference => column,
    }
}

/// A pure-geometry scanline drawn from a multiple of this has the whole scanline's pixels
/// (its blocks start there, and in the float formats each plane's weight is summed along
/// a block, its roundings from the block's start).
const FLAT_RESUME: u16 = 64;
pub(crate) use scanline::scanline;

/// Whether this build has the kernels (cargo feature `kernels`). Without them every frame
/// is drawn by the reference path, the definition (the kernels draw it within their
/// stated budgets, `tests/fast.rs`), at 1.7 to 36 times the instructions, and none of
/// their code is linked: every effect of the crate's rules on a 64 KB chip.
const KERNELS: bool = cfg!(feature = "kernels");

/// What a frame computes once for all its scanlines: the kernel [`select`] chose.
#[derive(Debug, Clone)]
pub(crate) enum Kernel<S: Scalar> {
    /// The pure-geometry kernel's per-frame part.
    Flat(Flat<S>),
    /// The fast primary-ray kernel's per-frame part.
    Fast(Primary<S>),
    /// The level-plane kernel's per-frame part (the fast kernel's).
    Rows(Rows<S>),
    /// The reference path (nothing per frame).
    Reference,
}

/// Which primary-ray kernel draws a frame or a scanline ([`crate::Frame::kernel`],
/// [`crate::Frame::row_kernel`]): the renderer picks the cheapest that draws the scene's
/// definition, once per frame; without the cargo feature `kernels` (on by default) it is
/// always [`KernelKind::Reference`].
///
/// ```
/// use fixray::{Frame, KernelKind, Scene, I16F16};
///
/// let spheres = Scene::<I16F16>::parse(include_str!("../../scenes/spheres.scene"))?;
/// let frame: Frame<'_, I16F16> = Frame::new(&spheres);
/// let kind = frame.kernel();
/// assert_ne!(kind, KernelKind::Flat); // spheres are not pure plane geometry
/// assert!((0..spheres.camera.height).all(|row| frame.row_kernel(row) != KernelKind::Flat));
/// # Ok::<(), fixray::SceneError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum KernelKind {
    /// Pure geometry (infinite planes, ambient colours only): no division per pixel
    /// (`kernel/flat.rs`).
    Flat,
    /// Planes and spheres under the crate's rules with unnormalised directions stepped
    /// along the scanline (`kernel/fast/`).
    Fast,
    /// Lit scenes of level planes (`N.x = 0`: floors, back walls) and spheres with
    /// diffuse lights and shadows: each scanline's plane found once per row, the fast
    /// kernel's pixels bit for bit (`kernel/rows/`).
    Rows,
    /// The definition: a normalised ray per pixel (`kernel/scanline.rs`).
    Reference,
}

/// What a frame draws with: the kernel [`select`] chose for it (from the scene's plan),
/// and whether the fast kernel may draw what the flat kernel hands back. (The flat
/// kernel's mode is the frame's drawing option, passed beside it: a constant mode stays
/// visible to the compiler where the frame is made.)
#[derive(Debug, Clone)]
pub(crate) struct Drawing<S: Scalar> {
    pub(crate) kernel: Kernel<S>,
    /// The fast kernel draws the scene's definition (decided by [`select`]).
    fast: bool,
}

impl<S: Scalar> Drawing<S> {
    /// Which kernel draws the frame.
    pub(crate) fn kind(&self) -> KernelKind {
        match self.kernel {
            Kernel::Flat(_) => KernelKind::Flat,
            Kernel::Fast(_) => KernelKind::Fast,
            Kernel::Rows(_) => KernelKind::Rows,
            Kernel::Reference => KernelKind::Reference,
        }
    }

    /// The fast kernel's per-frame part where the frame is drawn by it or by the
    /// level-plane kernel (which keeps one), for what must find a pixel's hit as they do.
    #[cfg(feature = "sampling")]
    pub(crate) fn primary(&self) -> Option<&Primary<S>> {
        match &self.kernel {
            Kernel::Fast(p) | Kernel::Rows(rows::Rows { primary: p, .. }) => Some(p),
            Kernel::Flat(_) | Kernel::Reference => None,
        }
    }

    /// The chain after the flat kernel, written once: the fast kernel's per-frame part
    /// where it draws the scene ([`select`] decided) and can be formed, otherwise `None`
    /// (the reference path). What a frame falls to when the flat kernel does not apply,
    /// and what a scanline the flat kernel hands back is drawn with.
    pub(crate) fn handed_back(&self, scene: &SceneView<'_, S>) -> Option<Primary<S>> {
        if self.fast { Primary::new(scene) } else { None }
    }

    /// Which kernel draws scanline `row`: the frame's, or for a scanline the flat kernel
    /// hands back (a quantity out of the format's range) the next of the chain.
    pub(crate) fn row_kind(&self, scene: &SceneView<'_, S>, row: u16) -> KernelKind {
        match &self.kernel {
            Kernel::Flat(flat) if flat.row(scene, row).is_none() => match self.handed_back(scene) {
                Some(_) => KernelKind::Fast,
                None => KernelKind::Reference,
            },
            Kernel::Rows(r) if !rows::decides(scene, r, row) => KernelKind::Fast,
            _ => self.kind(),
        }
    }
}

/// The columns of scanline `row` whose pixels may differ between `before` and `after`,
/// frames of two scenes whose objects `moved` alone differ, in their centres (a sphere in
/// both: [`moved_spheres`]); `None`: the row is the same. Only the level-plane kernel
/// tells which (`rows/changes.rs`); a frame of another kernel may change anywhere.
pub(crate) fn changed_columns<S: Scalar>(
    before: (&SceneView<'_, S>, &Drawing<S>),
    after: (&SceneView<'_, S>, &Drawing<S>),
    moved: u8,
    row: u16,
) -> Option<core::ops::Range<u16>> {
    match (&before.1.kernel, &after.1.kernel) {
        (Kernel::Rows(a), Kernel::Rows(b)) => {
            rows::changed_columns((before.0, a), (after.0, b), moved, row)
        }
        _ => Some(0..after.0.camera.width),
    }
}

/// What a frame of `scene` drawn with stage set `T` draws with: the cheapest kernel that
/// draws the scene's definition. The only place that decides which kernel applies (the
/// kernels' constructors refuse only what they cannot form: a quantity out of the
/// format's range, too many objects, an eye inside a sphere). Not inlined: the kernels'
/// per-frame parts it builds and moves are temporaries of its own frame, not of the
/// caller's, which stays under the parser and the scanlines (on a 16 KB chip in I32F32
/// that is a kilobyte).
#[inline(never)]
pub(crate) fn select<S: Scalar, T: Stages>(scene: &SceneView<'_, S>, plan: &Plan) -> Drawing<S> {
    // The course rules divide every colour by the distance travelled and look through
    // the window's corners: only the reference path draws them.
    let fast = fast_draws(scene);
    // Pure geometry: only infinite planes, and stages that show ambient colours only.
    let flat = fast && !T::LIGHTING && !T::REFLECTION && plan.planes_only;
    let mut drawing = Drawing {
        kernel: Kernel::Reference,
        fast,
    };
    // Level planes and spheres lit by diffuse point lights with shadows:
    // each scanline's plane once per row (`rows/`, the fast kernel's pixels bit for bit).
    let rows = fast
        && rows::draws_with::<T>()
        && plan.lighting
        && !plan.projectors
        && !plan.lights_on_surfaces
        && !scene.lights_on_surfaces
        && scene.objects.iter().all(|o| match &o.shape {
            Shape::Sphere(_) => true,
            shape @ (Shape::Plane(_) | Shape::Tiled { .. }) => {
                shape.plane().is_some_and(|p| p.normal().x == S::ZERO)
            }
            Shape::Finite(_) | Shape::Textured(_) | Shape::Triangle(_) | Shape::Revsurf(_) => false,
        });
    drawing.kernel = match flat.then(|| Flat::new(scene)).flatten() {
        Some(f) => Kernel::Flat(f),
        None => match drawing.handed_back(scene) {
            Some(primary) if rows => Kernel::Rows(Rows {
                primary,
                depth: crate::Depth::RGB888,
            }),
            Some(primary) => Kernel::Fast(primary),
            None => Kernel::Reference,
        },
    };
    drawing
}

/// Whether the fast kernel draws `scene`: every scene under the crate's rules (shading
/// takes its unnormalised direction: `shade::Incoming`) whose spheres it resolves
/// ([`resolves_spheres`]), in a build with the kernels.
fn fast_draws<S: Scalar>(scene: &SceneView<'_, S>) -> bool {
    KERNELS && scene.rules() == Rules::Fixray && resolves_spheres(scene)
}

/// Whether the fast kernel resolves the spheres of `scene` as finely as the reference
/// path: always in a float (its rounding is relative), in a fixed format where the eye
/// is at `z ≥ 1` (or there is no sphere). The kernel's discriminant `b² − a·c`
/// (`fast::sphere_root`) is the reference path's `r² − dist²` times `a = |D|²`, with
/// `|D| ≥ eye.z` (`D` ends on the screen, at `z = 0`); rounded once to `DELTA`, it errs
/// by `DELTA/(2a)` in the reference's units: no more than the reference's `DELTA/2`
/// where `a ≥ 1`, and `1/a` times more below, where the hit lies off the sphere by as
/// much more. A millimetre scene in I32F32 (eye at z = 0.002, radius 0.0005): `a·r²` is
/// 0.004 `DELTA`, the discriminant rounds to 0 at every pixel and every hit lands inside
/// the sphere (41 % of the pixels off f64's); the same scene 100 times larger (eye at
/// z = 0.2): hits up to 110 `DELTA` off the surface, beyond the shadow test's tolerance
/// of 12, so that the sphere shadows itself in specks (16 %). The reference path then
/// draws the frame (0.5 % and none).
fn resolves_spheres<S: Scalar>(scene: &SceneView<'_, S>) -> bool {
    S::INT_BITS == 0
        || scene.camera.viewpoint.z >= S::ONE
        || !scene
            .objects
            .iter()
            .any(|o| matches!(o.shape, Shape::Sphere(_)))
}

/// The fast kernel for a frame of the crate's rules where [`select`] would pick a
/// cheaper one (what the tests of the level-plane kernel compare with, bit for bit); the
/// reference path where it cannot be formed.
pub(crate) fn fast_only<S: Scalar>(scene: &SceneView<'_, S>) -> Drawing<S> {
    let fast = fast_draws(scene);
    let kernel = match fast.then(|| Primary::new(scene)).flatten() {
        Some(p) => Kernel::Fast(p),
        None => Kernel::Reference,
    };
    Drawing { kernel, fast }
}

/// Fills `line` (at most the camera's width) with scanline `row` drawn by `kernel`.
pub(crate) fn line<S: Scalar, T: KernelStages, C: From<Rgb888>>(
    scene: &SceneView<'_, S>,
    drawing: &Drawing<S>,
    mode: PlaneMode,
    row: u16,
    line: &mut [C],
    counters: &mut Counters,
) {
    let width = line.len().min(usize::from(scene.camera.width));
    let line = &mut line[..width];
    if !KERNELS {
        return primary_line::<S, T, C>(scene, None, row, line, counters);
    }
    let primary = match &drawing.kernel {
        Kernel::Flat(flat) => {
            if flat_line(scene, flat, mode, row, line) {
                count_primary(counters, u16::try_from(width).unwrap_or(0));
                return;
            }
            // Handed back: this scanline takes the next kernel of the chain.
            return fallback_line::<S, T, C>(scene, drawing, row, line, counters);
        }
        Kernel::Fast(p) => Some(p),
        Kernel::Rows(r) if rows::draws_with::<T>() => {
            match rows_line::<S, T, C>(scene, r, row, line, counters) {
                Ok(()) => return,
                // A row the level-plane kernel cannot decide once: the fast kernel's,
                // drawn from here (the level-plane kernel's frame is gone by then).
                Err(counters) => {
                    return primary_line::<S, T, C>(scene, Some(&r.primary), row, line, counters);
                }
            }
        }
        // Never chosen for another stage set (`select`): not compiled for it.
        Kernel::Rows(r) => Some(&r.primary),
        Kernel::Reference => None,
    };
    primary_line::<S, T, C>(scene, primary, row, line, counters);
}

/// A scanline the flat kernel handed back, on the next kernel of the chain
/// ([`Drawing::handed_back`]).
#[inline(never)]
fn fallback_line<S: Scalar, T: KernelStages, C: From<Rgb888>>(
    scene: &SceneView<'_, S>,
    drawing: &Drawing<S>,
    row: u16,
    line: &mut [C],
    counters: &mut Counters,
) {
    let primary = drawing.handed_back(scene);
    primary_line::<S, T, C>(scene, primary.as_ref(), row, line, counters);
}

/// Where a streamed scanline goes: a `fill_contiguous` of one row. Generic in the
/// iterator, so that a display driver's `fill_contiguous` is compiled for the kernel's own
/// iterator (no dynamic call per pixel).
pub(crate) trait RowSink<C> {
    /// The target's error.
    type Error;
    /// Takes the row's pixels, left to right.
    fn fill(&mut self, pixels: impl Iterator<Item = C>) -> Result<(), Self::Error>;
}

/// Streams columns `columns` of scanline `row` to `sink`, drawn by the frame's kernel:
/// the pixels of [`line`], without a line buffer.
pub(crate) fn stream<S, T, C, K>(
    scene: &SceneView<'_, S>,
    drawing: &Drawing<S>,
    mode: PlaneMode,
    row: u16,
    columns: core::ops::Range<u16>,
    counters: &mut Counters,
    sink: &mut K,
) -> Result<(), K::Error>
where
    S: Scalar,
    T: KernelStages,
    C: From<Rgb888> + Clone,
    K: RowSink<C>,
{
    if !KERNELS {
        return sink.fill(scanline::<S, T, C>(scene, None, row, columns, counters));
    }
    let fallback;
    let (primary, counters) = match &drawing.kernel {
        Kernel::Flat(flat) => match flat.row(scene, row) {
            Some(r) => {
                count_primary(counters, columns.end.saturating_sub(columns.start));
                return match mode {
                    PlaneMode::PerPixel => sink.fill(r.blocks(columns).map(C::from)),
                    PlaneMode::Spans => sink.fill(
                        r.spans(columns.start, columns.end)
                            .flat_map(|(n, c)| core::iter::repeat_n(C::from(c), n.into())),
                    ),
                };
            }
            None => {
                fallback = drawing.handed_back(scene);
                (fallback.as_ref(), counters)
            }
        },
        Kernel::Fast(p) => (Some(p), counters),
        Kernel::Rows(r) if !rows::draws_with::<T>() => (Some(&r.primary), counters),
        Kernel::Rows(r) => {
            match rows_stream::<S, T, C, K>(scene, r, row, columns.clone(), counters, sink) {
                Ok(done) => return done,
                // A row the level-plane kernel cannot decide once: the fast kernel's.
                Err(counters) => (Some(&r.primary), counters),
            }
        }
        Kernel::Reference => (None, counters),
    };
    sink.fill(scanline::<S, T, C>(scene, primary, row, columns, counters))
}

/// Columns `runs` (increasing and disjoint) of scanline `row` drawn by the frame's
/// kernel, each pixel handed to `put` with its column: the pixels of [`line`] there, with
/// one set-up of the scanline for all the runs (a sampled frame's blocks that are traced).
#[cfg(feature = "sampling")]
pub(crate) fn runs<S, T, C>(
    scene: &SceneView<'_, S>,
    drawing: &Drawing<S>,
    mode: PlaneMode,
    row: u16,
    runs: &[core::ops::Range<u16>],
    counters: &mut Counters,
    put: &mut impl FnMut(u16, C),
) where
    S: Scalar,
    T: KernelStages,
    C: From<Rgb888>,
{
    let last = runs.last().map_or(0, |r| r.end.saturating_sub(1));
    let columns = || runs.iter().flat_map(Clone::clone);
    let fallback;
    let (primary, counters) = match &drawing.kernel {
        _ if !KERNELS => (None, counters),
        Kernel::Flat(flat) => match flat.row(scene, row) {
            Some(r) => {
                for run in runs {
                    let from = resume_from(drawing, run.start);
                    let skip = usize::from(run.start - from);
                    let pixels: &mut dyn Iterator<Item = Rgb888> = match mode {
                        PlaneMode::PerPixel => &mut r.blocks(from..run.end),
                        PlaneMode::Spans => &mut r
                            .spans(from, run.end)
                            .flat_map(|(n, c)| core::iter::repeat_n(c, n.into())),
                    };
                    for (column, c) in run.clone().zip(pixels.skip(skip)) {
                        put(column, C::from(c));
                    }
                }
                return;
            }
            None => {
                fallback = drawing.handed_back(scene);
                (fallback.as_ref(), counters)
            }
        },
        Kernel::Fast(p) => (Some(p), counters),
        Kernel::Rows(r) if !rows::draws_with::<T>() => (Some(&r.primary), counters),
        Kernel::Rows(r) => match rows_runs::<S, T, C>(scene, r, row, runs, counters, put) {
            Ok(()) => return,
            Err(counters) => (Some(&r.primary), counters),
        },
        Kernel::Reference => (None, counters),
    };
    let pixels =
        scanline::scanline_over::<S, T, C, true>(scene, primary, (row, last), columns(), counters);
    for (column, c) in columns().zip(pixels) {
        put(column, c);
    }
}

/// [`runs`] on the level-plane kernel; `Err` (the counters handed back) when it cannot
/// decide the row once.
#[cfg(feature = "sampling")]
#[inline(never)]
fn rows_runs<'a, S, T, C>(
    scene: &'a SceneView<'a, S>,
    rows: &'a Rows<S>,
    row: u16,
    runs: &[core::ops::Range<u16>],
    counters: &'a mut Counters,
    put: &mut impl FnMut(u16, C),
) -> Result<(), &'a mut Counters>
where
    S: Scalar,
    T: KernelStages,
    C: From<Rgb888>,
{
    let Some(first) = runs.first() else {
        return Ok(());
    };
    let mut pixels = rows::scanline::<S, T>(scene, rows, row, first.clone(), counters);
    match &mut pixels {
        Ok(pixels) => {
            for (i, run) in runs.iter().enumerate() {
                if i > 0 {
                    pixels.resume_at(run.clone());
                }
                for (column, c) in run.clone().zip(pixels.by_ref()) {
                    put(column, C::from(c));
                }
            }
            Ok(())
        }
        Err(_) => pixels.map(|_| ()),
    }
}

/// Streams a scanline of the level-plane kernel to `sink`; `Err` (the counters handed
/// back) when the kernel cannot decide the row once. Not inlined: its per-row data are
/// on the stack only while it draws (the caller's frame is under every other path).
#[inline(never)]
fn rows_stream<'a, S, T, C, K>(
    scene: &'a SceneView<'a, S>,
    rows: &'a Rows<S>,
    row: u16,
    columns: core::ops::Range<u16>,
    counters: &'a mut Counters,
    sink: &mut K,
) -> Result<Result<(), K::Error>, &'a mut Counters>
where
    S: Scalar,
    T: KernelStages,
    C: From<Rgb888> + Clone,
    K: RowSink<C>,
{
    let mut pixels = rows::scanline::<S, T>(scene, rows, row, columns, counters);
    match &mut pixels {
        Ok(pixels) => Ok(sink.fill(pixels.by_ref().map(C::from))),
        Err(_) => pixels.map(|_| Ok(())),
    }
}

/// Fills `line` with columns `0..line.len()` of a pure-geometry scanline; `false` when
/// the kernel hands the scanline back. Not inlined: its frame (the kernel's per-scanline
/// data) and the general path's are never on the stack together (on a 16 KB chip in
/// I32F32 that is the difference between fitting and not).
#[inline(never)]
fn flat_line<S: Scalar, C: From<Rgb888>>(
    scene: &SceneView<'_, S>,
    flat: &Flat<S>,
    mode: PlaneMode,
    row: u16,
    line: &mut [C],
) -> bool {
    let Some(r) = flat.row(scene, row) else {
        return false;
    };
    let width = u16::try_from(line.len()).unwrap_or(u16::MAX);
    match mode {
        PlaneMode::PerPixel => r.fill_line(line),
        PlaneMode::Spans => {
            let mut rest = line;
            for (n, color) in r.spans(0, width) {
                let (run, tail) = rest.split_at_mut(usize::from(n).min(rest.len()));
                for slot in run {
                    *slot = C::from(color);
                }
                rest = tail;
            }
        }
    }
    true
}

/// A scanline of the level-plane kernel into `line`; `Err` (the counters handed back)
/// for a row it cannot decide once, which the caller hands to the fast kernel. Not
/// inlined: its per-row data are on the stack only while it draws, never under the fast
/// kernel's scanline.
#[inline(never)]
fn rows_line<'a, S: Scalar, T: KernelStages, C: From<Rgb888>>(
    scene: &'a SceneView<'a, S>,
    rows: &'a Rows<S>,
    row: u16,
    line: &mut [C],
    counters: &'a mut Counters,
) -> Result<(), &'a mut Counters> {
    let width = u16::try_from(line.len()).unwrap_or(0);
    // Drawn where `scanline` built it (a move would be a second copy on the stack).
    let mut pixels = rows::scanline::<S, T>(scene, rows, row, 0..width, counters);
    match &mut pixels {
        Ok(pixels) => {
            for (slot, c) in line.iter_mut().zip(pixels.by_ref()) {
                *slot = C::from(c);
            }
            Ok(())
        }
        Err(_) => pixels.map(|_| ()),
    }
}

/// A scanline of the fast kernel (with its per-frame part `primary`) or, without it, of
/// the reference path, into `line`.
#[inline(never)]
fn primary_line<S: Scalar, T: KernelStages, C: From<Rgb888>>(
    scene: &SceneView<'_, S>,
    primary: Option<&Primary<S>>,
    row: u16,
    line: &mut [C],
    counters: &mut Counters,
) {
    let width = u16::try_from(line.len()).unwrap_or(0);
    let pixels = scanline::<S, T, C>(scene, primary, row, 0..width, counters);
    for (slot, c) in line.iter_mut().zip(pixels) {
        *slot = c;
    }
}
