//! Lit scenes of level planes and spheres (the boing ball's kind): each scanline's plane
//! is found once per row, not once per pixel.
//!
//! A primary ray of scanline `j` is `D = (x − eye.x, dy_j, dz)`: only `D.x` changes
//! along the row. For a plane whose normal has `N.x = 0` (a floor, a ceiling, a back
//! wall, any plane tilted only about the x axis), `N·D` is therefore the same at every
//! pixel of the row, and so are its test, its parameter `t' = num/(N·D)` and the hit's
//! `y` and `z`. When every plane is of that kind, the nearest plane of a row, its
//! division, the normal facing the ray, its tile row, every plane's side at the hit, the
//! objects that can shadow the row and each light's terms are worked out once per row
//! ([`Primary::level_row`], `level`); a pixel computes its hit's `x` (one product) and
//! lights it: the tile column, `L.x`, `|L|²`, the shadow tests the row kept and one
//! division for `255·(N·L)/|L|²`. Spheres are tested only inside their boxes on the
//! screen (the fast kernel's `sphere_rows` and `sphere_columns`), by the fast kernel's
//! own test, and shaded its way.
//!
//! Every quantity has the fast kernel's value (the same operations; `|L|²` adds its
//! exact terms in another order only where sums are exact, `KernelArith::EXACT_SUMS`, and a
//! shadow cone's `l·u` only where products are exact too, `KernelArith::EXACT_PRODUCTS`), so a
//! pixel is the fast kernel's bit for bit (`tests/rows.rs`: every boing frame, an
//! unshipped ball scene and seeded random level scenes, whole and partial scanlines, in
//! every format). A row that cannot be decided once (a plane within the epsilon's margin
//! of parallel at some pixel) and any pixel whose quantity leaves the format are drawn by
//! the fast kernel itself. The statistics (`Counters`) of a pixel that this kernel hands
//! to the general shading midway (a light's `|L|²` out of range) count its tile lookup and
//! its earlier lights twice; its colour is not affected.
//!
//! Its files: this one, the scanline ([`scanline`], [`Pixels`]); `level.rs`, the row's
//! plane and its per-row terms (`level`) and the colour of a pixel on it
//! ([`plane_color`]); `lean.rs`, lean rows ([`lean_row`]): the commonest pixels'
//! colours and quick runs; `changes.rs`, what a frame must redraw of the frame before it
//! when spheres move ([`changed_columns`]), and where a sphere's shadow can fall on a row
//! (`shadow_columns`).

mod changes;
#[cfg(test)]
mod invariants;
mod lean;
mod level;
mod spans;

use changes::shadow_columns;
pub(crate) use changes::{changed_columns, moved_spheres};

use embedded_graphics_core::pixelcolor::Rgb888;

use super::fast::{self, FAST_OBJECTS, FastHit, Primary, Row, hull};
use super::memo::Weights;
use super::scanline::{fast_color, reference_color};
use crate::shade::color::to_pixel;
use crate::shade::stages::Stages;
use crate::stats::{Counters, count};
use crate::{Color, Depth, Scalar, SceneView};
use lean::{LeanRow, count_quick, lean_color, lean_row, quick_step};
use level::{Level, Memo, level, plane_color, row_plane};
use spans::{Drew, Span, class};

/// The per-frame part: the fast kernel's (its terms, the lights' sides of every plane,
/// the spheres' rows and shadow cones).
#[derive(Debug, Clone)]
pub(crate) struct Rows<S: Scalar> {
    pub(crate) primary: Primary<S>,
    /// The depth the pixels must be exact in ([`crate::Frame::with_depth`]): what a
    /// quick run's spans compare ([`Pixels::quick_run`]).
    pub(crate) depth: Depth,
}

/// Whether the stage set `T` is the one this kernel draws with (diffuse point lights and
/// shadows, `DiffuseShadows`): [`super::select`] picks it only then, and the scanline
/// code is compiled only for that set (flash: a scene lit without shadows, one plane
/// under a light, is the fast kernel's).
pub(crate) const fn draws_with<T: Stages>() -> bool {
    T::LIGHTING && T::SHADOWS && !T::SPECULAR && !T::CONES && !T::REFLECTION && !T::TRANSPARENCY
}

/// Whether this kernel draws scanline `row` itself (`false`: it hands it to the fast
/// kernel), for [`crate::Frame::row_kernel`].
pub(crate) fn decides<S: Scalar>(scene: &SceneView<'_, S>, rows: &Rows<S>, row: u16) -> bool {
    let p = &rows.primary;
    p.row(scene, row, 0)
        .is_some_and(|first| row_plane(scene, p, &first).is_some())
}

/// The pixels of columns `columns` of scanline `row`: the row's plane worked out once
/// ([`Primary::level_row`]), then per pixel its hit's `x` and light, spheres by the fast
/// kernel's test inside their boxes. `Err` (the counters handed back) when this kernel
/// cannot decide the row once: the fast kernel then draws it, pixel by pixel. One pixel
/// is one out-of-line call ([`Pixels::pixel`]): the kernel's code is compiled once per
/// format, not again for every colour type and display driver that takes the pixels
/// (flash on a small chip). Not inlined: the scanline is built in the caller's slot, not
/// copied there (stack).
#[inline(never)]
pub(crate) fn scanline<'a, S: Scalar, T: Stages>(
    scene: &'a SceneView<'a, S>,
    rows: &'a Rows<S>,
    row: u16,
    columns: core::ops::Range<u16>,
    counters: &'a mut Counters,
) -> Result<Pixels<'a, S, T>, &'a mut Counters> {
    let p = &rows.primary;
    let Some(first) = p.row(scene, row, 0) else {
        return Err(counters);
    };
    let Some(level) = level::<S, T>(scene, p, &first) else {
        return Err(counters);
    };
    let lazy = S::EXACT_PRODUCTS && p.terms_fit_row(scene, &first, scene.camera.width);
    // From another column than 0 the first pixel is where a whole scanline's stepping
    // reaches it ([`Primary::row_resumed`]): the same pixels from any column.
    let (state, valid) = match columns.start {
        0 => (first, true),
        c => match p.row_resumed(scene, row, c) {
            Some(r) => (r, true),
            None => (first, false),
        },
    };
    Ok(Pixels {
        scene,
        p,
        level,
        lean: LeanRow::empty(),
        lean_built: None,
        lazy,
        stale: false,
        state,
        fresh: true,
        valid,
        at_hit: heapless::Vec::new(),
        weights: Weights::default(),
        memo: Memo::default(),
        spheres: p.sphere_columns_on_row_of(row, u8::MAX),
        chords: false,
        shadow: core::cell::Cell::new(None),
        y: scene.camera.screen_y(row),
        row,
        columns,
        counters,
        stages: core::marker::PhantomData,
        run: [Rgb888::new(0, 0, 0); RUN],
        depth: rows.depth,
        run_at: 0,
        run_len: 0,
        #[cfg(feature = "stats")]
        run_lit: 0,
    })
}

/// A scanline of the level-plane kernel, pixel by pixel ([`scanline`]).
pub(crate) struct Pixels<'a, S: Scalar, T> {
    scene: &'a SceneView<'a, S>,
    p: &'a Primary<S>,
    level: Option<Level<S>>,
    /// The row's lean part ([`lean_row`]), built at the first pixel that needs it
    /// (`lean_built`: `None` until then, then whether the row is a lean one).
    lean: LeanRow<S>,
    lean_built: Option<bool>,
    /// The fast kernel's row at the current pixel: at column 0 as the fast kernel starts
    /// it (`fresh`); after a pixel whose step failed (`valid` false) the next restarts,
    /// as `kernel::scanline` does.
    state: Row<S>,
    fresh: bool,
    valid: bool,
    /// Whether the row steps only `D` outside the spheres' columns (the formats whose
    /// products and sums are exact, and every term fits along the whole row:
    /// [`Primary::terms_fit_row`]), and whether its terms are behind its `D` now.
    lazy: bool,
    stale: bool,
    at_hit: heapless::Vec<S, FAST_OBJECTS>,
    /// The spheres' materials' weights (a sphere hit's shading, [`Pixels::other`]).
    weights: Weights<S>,
    memo: Memo<S>,
    /// The columns where a sphere can be met on this row: the spheres' boxes, narrowed to
    /// their chords of the row ([`Primary::sphere_chords_on_row`], `chords`) at the first
    /// pixel inside them (a row whose pixels stay outside forms none), in the formats with
    /// a quick pixel (`KernelArith::QUICK_PIXEL`: a pixel outside the spheres' columns
    /// then takes a quick run; in the others the boxes alone, and no chord's code in a
    /// small chip's flash).
    spheres: (u16, u16),
    chords: bool,
    /// The columns where a sphere may shadow the row's hits from its one light
    /// ([`Pixels::unshadowed_to`]; `None` until a quick run asks).
    shadow: core::cell::Cell<Option<(u16, u16)>>,
    y: Option<S>,
    row: u16,
    columns: core::ops::Range<u16>,
    counters: &'a mut Counters,
    stages: core::marker::PhantomData<T>,
    /// Pixels a quick run drew ahead ([`Pixels::quick_run`]): `run[run_at..run_len]`
    /// are the next ones, before `columns`.
    run: [Rgb888; RUN],
    /// What the pixels must be exact in: a quick run's spans compare its keys.
    depth: Depth,
    run_at: u8,
    run_len: u8,
    /// Which of `run` were lit (bit `i`: `run[i]`): their counts are added as they are
    /// handed out, so that a caller that stops early counts only the pixels it took.
    #[cfg(feature = "stats")]
    run_lit: u64,
}

/// How many pixels a quick run draws ahead of the one asked for ([`Pixels::quick_run`]).
const RUN: usize = 64;

impl<S: Scalar, T: Stages> Iterator for Pixels<'_, S, T> {
    type Item = Rgb888;

    #[inline]
    fn next(&mut self) -> Option<Rgb888> {
        // The pixels a quick run drew ahead ([`Pixels::quick_run`]) first.
        if self.run_at < self.run_len
            && let Some(pixel) = self.run.get(usize::from(self.run_at))
        {
            #[cfg(feature = "stats")]
            {
                let lit = (self.run_lit >> self.run_at) & 1 != 0;
                let tiled = u32::from(self.lean.tiles.is_some());
                count_quick(self.counters, tiled, lit, true);
            }
            self.run_at += 1;
            return Some(*pixel);
        }
        let column = self.columns.next()?;
        Some(self.pixel(column))
    }
}

impl<S: Scalar, T: Stages> Pixels<'_, S, T> {
    /// Goes on with columns `columns` of the same row (after the ones drawn so far), as a
    /// whole scanline reaches them ([`Primary::row_resumed`]): the row's plane and lean
    /// part are kept, the stepping resumes there.
    #[cfg(feature = "sampling")]
    pub(crate) fn resume_at(&mut self, columns: core::ops::Range<u16>) {
        self.run_at = self.run_len;
        match self.p.row_resumed(self.scene, self.row, columns.start) {
            Some(r) => (self.state, self.valid) = (r, true),
            None => self.valid = false,
        }
        (self.fresh, self.stale) = (true, false);
        self.columns = columns;
    }

    /// The pixel at `column` (the next of the row's columns).
    #[inline(never)]
    fn pixel(&mut self, column: u16) -> Rgb888 {
        let (scene, p) = (self.scene, self.p);
        count(&mut self.counters.primary_rays);
        let mut in_spheres = column >= self.spheres.0 && column <= self.spheres.1;
        if S::QUICK_PIXEL && in_spheres && !self.chords {
            self.chords = true;
            self.spheres = p.sphere_chords_on_row(scene, self.row);
            in_spheres = column >= self.spheres.0 && column <= self.spheres.1;
        }
        // The commonest pixels first ([`Pixels::quick_run`]): a lazy row's columns
        // outside the spheres' columns, on a lean row already built.
        if S::QUICK_PIXEL
            && S::EXACT_SUMS
            && S::EXACT_PRODUCTS
            && self.lazy
            && !in_spheres
            && !self.fresh
            && self.valid
            && self.lean_built == Some(true)
            && self.lean.runs
            && let Some(pixel) = self.quick_run(column)
        {
            return pixel;
        }
        // Outside the spheres' columns a lazy row steps `D` alone (the pixel's plane
        // needs nothing else); its terms are brought up to date where a sphere can be met.
        // (Only where products are exact: elsewhere none of it is compiled, flash.)
        let lazy = S::EXACT_PRODUCTS && self.lazy;
        let skip = lazy && !in_spheres;
        let stale = S::EXACT_PRODUCTS && self.stale;
        let stepped = if self.fresh && Primary::column(&self.state) == column {
            Some(())
        } else if self.valid
            && Primary::column(&self.state).checked_add(1) == Some(column)
            && !column.is_multiple_of(fast::resync_pixels::<S>())
        {
            if skip || stale {
                p.advance_dir(&mut self.state)
            } else {
                p.advance(&mut self.state)
            }
        } else if skip {
            // `D.y` is the row's at every pixel (`scanline` started it on this row).
            let dy = Primary::dir(&self.state).y;
            p.restart_dir_in_row(scene, self.row, dy, column, &mut self.state)
        } else {
            self.stale = false;
            p.restart(scene, self.row, column, &mut self.state)
        };
        self.fresh = false;
        self.stale |= skip;
        let stepped = match stepped {
            Some(()) if S::EXACT_PRODUCTS && self.stale && !skip => {
                self.stale = false;
                p.refresh(scene, &mut self.state)
            }
            s => s,
        };
        self.valid = stepped.is_some();
        // What the pixel shows: the row's plane, or what the fast kernel found.
        let found = match stepped {
            None => Err(()),
            Some(()) if in_spheres => {
                let level = self.level.as_ref().map(|l| (l.index, l.pq, l.t));
                match p.nearest_over_level(scene, &self.state, level) {
                    Ok(Some(None)) => Ok(None),
                    Ok(Some(Some(h))) => Ok(Some(h)),
                    Ok(None) => return to_pixel(scene.rules(), scene.background),
                    Err(()) => Err(()),
                }
            }
            Some(()) => Ok(None),
        };
        let color = match found {
            // The lean path exists only where sums are exact (fixed formats): elsewhere
            // not even its call is made.
            Ok(None) if S::EXACT_SUMS => match self.lean() {
                Some(Ok(pixel)) => return pixel,
                Some(Err(color)) => color,
                None => self.plane(column),
            },
            Ok(None) => self.plane(column),
            Ok(Some(h)) => self.other(&h),
            Err(()) => self.reference(column),
        };
        to_pixel(scene.rules(), color)
    }

    /// The pixel at `column` and as many of the row's next columns as [`Pixels::run`]
    /// holds, while each is a quick step ([`quick_step`]), in a loop: the row's lean part
    /// is looked up once, not once a pixel, and one call draws them all. `None` when
    /// `column`'s is not one (nothing changed but a resync column's restart, which the
    /// general path then does again, to the same state).
    #[inline(never)]
    fn quick_run(&mut self, column: u16) -> Option<Rgb888> {
        // `D.y` is the row's at every pixel (`scanline` started it on this row).
        let (scene, p) = (self.scene, self.p);
        let row = (self.row, Primary::dir(&self.state).y);
        let (l, f) = (self.level.as_ref()?, &self.lean);
        let [light] = f.lights.as_slice() else {
            return None;
        };
        let tiled = u32::from(f.tiles.is_some());
        // A pixel outside the row's shadow columns tests no cone (`quick_at`).
        let (a, b) = self.shadow(column);
        let cones = |c: u16| c >= a && c <= b;
        let at = (column, cones(column));
        let (first, lit, side) = quick_step(scene, p, l, f, light, &mut self.state, row, at)?;
        // (The first pixel's primary ray was counted by `pixel`, the caller; the others'
        // counts are added as `next` hands them out.)
        count_quick(self.counters, tiled, lit, false);
        // Spans where no sphere can shadow the row from its light, in a depth shallower
        // than Rgb888, with the cargo feature `depth` (`spans.rs`). (In the exact depth a
        // span would draw hardly fewer pixels than the run: neighbours seldom have one
        // Rgb888 colour, and halving costs more than it saves.)
        if cfg!(feature = "depth")
            && self.depth != Depth::RGB888
            && let Some(limit) = self.unshadowed_to(column)
        {
            return self.spans(column, (first, side), limit);
        }
        #[cfg(feature = "stats")]
        {
            self.run_lit = 0;
        }
        let (end, spheres) = (self.columns.end, self.spheres);
        let mut n = 0u8;
        for slot in self.run.iter_mut() {
            let c = self.columns.start;
            if c >= end || (c >= spheres.0 && c <= spheres.1) {
                break;
            }
            let at = (c, cones(c));
            let Some((pixel, lit, _)) = quick_step(scene, p, l, f, light, &mut self.state, row, at)
            else {
                break;
            };
            #[cfg(feature = "stats")]
            {
                self.run_lit |= u64::from(lit) << n;
            }
            #[cfg(not(feature = "stats"))]
            let _ = lit;
            *slot = pixel;
            n += 1;
            self.columns.start = c + 1;
        }
        (self.run_at, self.run_len) = (0, n);
        (self.fresh, self.stale, self.valid) = (false, true, true);
        Some(first)
    }

    /// [`Pixels::quick_run`]'s run after its first pixel (at `column`, with its side), in
    /// spans ([`Span::draw`]) up to the column before each restart of the stepping (a
    /// restart's column is a quick step's); a span that meets a pixel the quick path does
    /// not draw ends the run before it, and the run ends at column `limit` at the latest
    /// (up to it no sphere can shadow the row from its light: [`Pixels::unshadowed_to`]).
    /// Every pixel is lit.
    #[inline(never)]
    fn spans(
        &mut self,
        column: u16,
        (first, side): (Rgb888, lean::Side),
        limit: u16,
    ) -> Option<Rgb888> {
        let (scene, p) = (self.scene, self.p);
        let row = (self.row, Primary::dir(&self.state).y);
        let (l, f) = (self.level.as_ref()?, &self.lean);
        let [light] = f.lights.as_slice() else {
            return None;
        };
        // The run's last column: before the row's end, before the spheres' columns, and
        // within the run's pixels.
        let (end, spheres) = (self.columns.end, self.spheres);
        let mut last = end
            .checked_sub(1)?
            .min(column.saturating_add(u16::try_from(RUN).ok()?));
        if column < spheres.0 {
            last = last.min(spheres.0 - 1);
        }
        last = last.min(limit);
        let resync = fast::resync_pixels::<S>();
        let mut span = Span {
            depth: self.depth,
            from: column,
            at: (column, first, class(side)),
            n: 0,
        };
        while span.at.0 < last {
            let c = span.at.0 + 1;
            if !c.is_multiple_of(resync) {
                let b = last.min((c / resync + 1).saturating_mul(resync) - 1);
                if b > c {
                    let lean = (l, f, light);
                    match span.draw(scene, p, lean, &mut self.state, row.1, b, &mut self.run) {
                        Drew::All => continue,
                        // The run ends before a column the quick path does not draw.
                        Drew::Before(bad) => {
                            last = bad - 1;
                            continue;
                        }
                        Drew::Not => {}
                    }
                }
            }
            // (Up to `limit` no pixel lies in a sphere's shadow.)
            let at = (c, false);
            let Some((pixel, _, side)) =
                quick_step(scene, p, l, f, light, &mut self.state, row, at)
            else {
                break;
            };
            *self.run.get_mut(usize::from(span.n))? = pixel;
            span.n += 1;
            span.at = (c, pixel, class(side));
        }
        #[cfg(feature = "stats")]
        {
            self.run_lit = 1u64
                .checked_shl(u32::from(span.n))
                .map_or(u64::MAX, |m| m - 1);
        }
        self.columns.start = span.at.0 + 1;
        (self.run_at, self.run_len) = (0, span.n);
        (self.fresh, self.stale, self.valid) = (false, true, true);
        Some(first)
    }

    /// The last column up to which, from `column`, no sphere can shadow the row's hits
    /// from its one light; `None` where one may at `column`, or the row's shadow columns
    /// are not formed ([`Pixels::shadow`]). Outside the columns of each sphere the row
    /// keeps a shadow cone of ([`shadow_columns`]) the exact segment test finds every hit
    /// clear: its quick pixels are lit.
    fn unshadowed_to(&self, column: u16) -> Option<u16> {
        let (a, b) = self.shadow(column);
        if column < a {
            Some(a - 1)
        } else if column > b {
            Some(u16::MAX)
        } else {
            None
        }
    }

    /// The columns where a sphere may shadow the row's hits from its one light
    /// ([`Pixels::shadow_of_row`]), formed at the row's first ask from `column` that
    /// leaves more than half the row's width to draw (a frame's changes are mostly its
    /// spheres' boxes and their shadows' columns, where forming them costs more than
    /// the cones' tests it saves); until then, on a row with cones, every column. Only
    /// with the cargo feature `depth`, whose spans need them: without it, as in a small
    /// chip's firmware, their code would not fit its flash with a copy per format.
    fn shadow(&self, column: u16) -> (u16, u16) {
        if !cfg!(feature = "depth") {
            return (0, u16::MAX);
        }
        if let Some(columns) = self.shadow.get() {
            return columns;
        }
        let cones = matches!(self.lean.lights.as_slice(), [l] if l.cones.0 != l.cones.1);
        let left = self.columns.end.saturating_sub(column);
        if cones && left <= self.scene.camera.width / 2 {
            return (0, u16::MAX);
        }
        let columns = self.shadow_of_row();
        self.shadow.set(Some(columns));
        columns
    }

    /// [`Pixels::shadow`]'s columns: `(u16::MAX, 0)` where no sphere can shadow
    /// the row, `(0, u16::MAX)` where one may anywhere.
    #[inline(never)]
    fn shadow_of_row(&self) -> (u16, u16) {
        const ANYWHERE: (u16, u16) = (0, u16::MAX);
        let (Some(l), [light]) = (self.level.as_ref(), self.lean.lights.as_slice()) else {
            return ANYWHERE;
        };
        if light.cones.0 == light.cones.1 {
            return (u16::MAX, 0);
        }
        // The spheres the row keeps cones of are its occluders of the light (`lean_row`).
        let Some(&bits) = l.occluders.first() else {
            return ANYWHERE;
        };
        let mut columns = None;
        for i in (0..8u8).filter(|i| bits & (1 << i) != 0) {
            match shadow_columns(self.scene, self.p, (0, i), (l.t, l.y, l.z)) {
                Some(Some(span)) => hull(&mut columns, span),
                Some(None) => {}
                None => return ANYWHERE,
            }
        }
        columns.unwrap_or((u16::MAX, 0))
    }

    /// The row's plane at the current pixel ([`plane_color`]). Out of line, as is
    /// [`Pixels::other`]: the plane's locals are not on the stack under the general
    /// shading's deep calls (an I32F32 frame on a 16 KB chip).
    #[inline(never)]
    fn plane(&mut self, column: u16) -> Color<S> {
        plane_color::<S, T>(
            self.scene,
            self.p,
            &self.state,
            self.level.as_ref(),
            &mut self.memo,
            self.y,
            column,
            self.counters,
        )
    }

    /// The row's plane at the current column by [`lean_color`]: its pixel where the
    /// quick term settled it, else its colour (`None`: [`Pixels::plane`] draws it).
    #[inline(never)]
    fn lean(&mut self) -> Option<Result<Rgb888, Color<S>>> {
        // Only formats with exact sums have lean rows: in the others (floats) this is
        // all there is of it (flash), and `pixel` does not call it.
        if !S::EXACT_SUMS {
            return None;
        }
        let l = self.level.as_ref()?;
        let lean = match self.lean_built {
            Some(lean) => lean,
            None => {
                let d = Primary::dir(&self.state);
                let lean = lean_row(self.scene, self.p, l, (d.y, d.z), &mut self.lean).is_some();
                self.lean_built = Some(lean);
                lean
            }
        };
        if !lean {
            return None;
        }
        lean_color(self.scene, &self.state, l, &self.lean, self.counters)
    }

    /// The pixel on the reference path (a quantity out of the format's range).
    #[inline(never)]
    fn reference(&mut self, column: u16) -> Color<S> {
        reference_color::<S, T>(self.scene, self.y, column, self.counters)
    }

    /// Another object the fast kernel found at the current pixel (a sphere), shaded the
    /// fast kernel's way.
    #[inline(never)]
    fn other(&mut self, h: &FastHit<S>) -> Color<S> {
        fast_color::<S, T>(
            self.scene,
            Some(self.p),
            &self.state,
            h,
            (&mut self.at_hit, Some(&mut self.weights)),
            self.counters,
        )
    }
}
