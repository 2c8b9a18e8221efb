//! The per-pixel scanline: each pixel's primary ray on the fast kernel where it has a
//! per-frame part, otherwise (and for any pixel the fast kernel hands back) the reference
//! path, the definition itself: a normalised ray per pixel through
//! [`crate::Camera::primary_ray_at`], traced and shaded.

use embedded_graphics_core::pixelcolor::Rgb888;

use super::fast::{self, Primary, Row};
use super::memo::{KernelStages, MemoSlot};
use super::shading::{lit_plane_color, lit_planes};
use crate::shade::color::to_pixel;
use crate::shade::stages::Stages;
use crate::shade::{Incoming, PlaneSides, shade_with, trace_pixel_ray};
use crate::stats::{Counters, count};
use crate::{Color, Hit, Scalar, SceneView};

/// The pixels of columns `columns` of scanline `row` traced with the stage set `T`, one
/// per step, as the caller (a `fill_contiguous` or a line buffer) pulls them. With a
/// fast-kernel frame (`primary`) primary rays take [`super::fast`]; otherwise, and for
/// any pixel the fast kernel hands back, the reference path.
pub(crate) fn scanline<'a, S: Scalar, T: KernelStages, C: From<Rgb888>>(
    scene: &'a SceneView<'a, S>,
    primary: Option<&'a Primary<S>>,
    row: u16,
    columns: core::ops::Range<u16>,
    counters: &'a mut Counters,
) -> impl Iterator<Item = C> + 'a {
    let y = scene.camera.screen_y(row);
    let rules = scene.rules();
    let mut state: Option<Row<S>> = None;
    // The planes' sides at the current pixel's hit (see `Primary::sides_at`).
    let mut at_hit = heapless::Vec::new();
    // A block of pixels from a resync column whose winner is certified
    // (`Primary::start_block`, `Primary::block_hit`), and the last pixel's winner (the
    // guess a resync column certifies first: `None` where there is none).
    let mut block = fast::Block::default();
    let mut guess = fast::Guess::default();
    // What the stage set's plane hits keep from pixel to pixel (`Stages::Memo`).
    let mut memo = T::Memo::<S>::default();
    let last = columns.end.saturating_sub(1);
    columns.map(move |column| {
        count(&mut counters.primary_rays);
        // Without the kernels (cargo feature `kernels`) the fast kernel's code is not
        // linked: the test is a constant here, where each pixel reads `primary`.
        let found = primary.filter(|_| super::KERNELS).and_then(|p| {
            match state.as_mut() {
                Some(r)
                    if Primary::column(r).checked_add(1) == Some(column)
                        && column % fast::resync_pixels::<S>() != 0 =>
                {
                    // Inside a certified block a stage set with a plane memo steps the
                    // block's plane alone (its pixels need no other term unless they
                    // take the general shading or a shadow test: `PlaneMemo::stale`).
                    match (memo.memo(), block.plane_at(column)) {
                        (Some(m), Some(w)) if m.lazy && p.steps_freely() => {
                            p.advance_one(r, w)?;
                            m.stale = true;
                        }
                        (m, _) => {
                            if let Some(m) = m.filter(|m| m.stale) {
                                p.refresh(scene, r)?;
                                m.stale = false;
                            }
                            p.advance(r)?
                        }
                    }
                }
                Some(r) => {
                    block = fast::Block::default();
                    if let Some(m) = memo.memo() {
                        (m.stale, m.lazy) = (false, true);
                    }
                    if p.restart(scene, row, column, r).is_none() {
                        state = None;
                        return None;
                    }
                }
                None => {
                    block = fast::Block::default();
                    if let Some(m) = memo.memo() {
                        (m.stale, m.lazy) = (false, true);
                    }
                    state = Some(p.row(scene, row, column)?);
                }
            }
            let r = state.as_ref()?;
            // The still planes' hits the stage set's memo keeps (`fast::HitMemo`).
            let mut hits = memo.memo().map(|m| &mut m.hits);
            // Certified blocks: only in the formats that take them (compiled out of the
            // others, `fast::blocks_for`).
            if !fast::blocks_for::<S>() {
                return p.nearest_with(scene, r, hits).ok();
            }
            if let Some(hit) = p.block_hit(scene, r, &block, hits.as_deref_mut()) {
                return hit.ok();
            }
            if column % fast::block_starts::<S>() != 0 {
                return p.nearest_with(scene, r, hits).ok();
            }
            // A resync column: the last pixel's winner certified first (no search where
            // it holds), else the searched one (unless that was the guess).
            if let Some(w) = guess.winner() {
                p.start_block(r, w, last, &mut block);
                if let Some(hit) = p.block_hit(scene, r, &block, hits.as_deref_mut()) {
                    return hit.ok();
                }
            }
            let hit = p.nearest_with(scene, r, hits).ok()?;
            let winner = hit.as_ref().map(|h| h.index);
            if guess.winner() != Some(winner) {
                p.start_block(r, winner, last, &mut block);
            }
            // A restart's block that does not hold to the next restart may hold for its
            // first half (the second half tries its own, `fast::block_starts::<S>()`).
            if block.is_empty() && column % fast::resync_pixels::<S>() == 0 {
                let half = last.min(column.saturating_add(fast::block_starts::<S>() - 1));
                p.start_block(r, winner, half, &mut block);
            }
            Some(hit)
        });
        if fast::blocks_for::<S>() {
            guess = fast::Guess::of(found.as_ref().map(|h| h.as_ref().map(|h| h.index)));
        }
        let color = match found {
            Some(Some(h)) => match state.as_mut() {
                Some(r) => {
                    // The flattened plane shading first (not called at all for the
                    // other stage sets and formats), else the general one (with every
                    // term up to date: `PlaneMemo::stale`).
                    let lit = match primary {
                        Some(p) if lit_planes::<S, T>() => {
                            let at = (&mut at_hit, memo.memo());
                            lit_plane_color::<S, T>(scene, p, r, &h, at, counters)
                        }
                        _ => None,
                    };
                    match lit {
                        Some(color) => color,
                        None => {
                            if let (Some(m), Some(p)) = (memo.memo(), primary)
                                && m.stale
                            {
                                m.stale = p.refresh(scene, r).is_none();
                                m.lazy = false;
                            }
                            fast_color::<S, T>(scene, primary, r, &h, &mut at_hit, counters)
                        }
                    }
                }
                None => scene.background,
            },
            Some(None) => scene.background,
            None => reference_color::<S, T>(scene, y, column, counters),
        };
        C::from(to_pixel(rules, color))
    })
}

/// The colour of the fast kernel's hit `h` at the row's current pixel by the general
/// shading (`shade_with`; the scanline tries [`lit_plane_color`] first): shaded with the
/// unnormalised direction (see `Incoming`; the fast kernel takes only stage sets that
/// need no more of it than its side), shadow segments taking the planes' sides from the
/// kernel's terms (`at_hit`: a buffer the scanline keeps).
pub(crate) fn fast_color<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    primary: Option<&Primary<S>>,
    r: &Row<S>,
    h: &fast::FastHit<S>,
    at_hit: &mut heapless::Vec<S, { fast::FAST_OBJECTS }>,
    counters: &mut Counters,
) -> Color<S> {
    let sides = match primary {
        Some(p) if T::SHADOWS && !p.at_lights().is_empty() => {
            p.sides_at(r, h.param, at_hit).map(|bits| PlaneSides {
                at_hit,
                at_lights: p.at_lights(),
                cones: p.cones(),
                bits,
            })
        }
        _ => None,
    };
    let incoming = Incoming {
        base: scene.camera.viewpoint,
        dir: h.dir,
        unit: false,
        sides,
    };
    let hit = Hit {
        t: h.t_bound,
        point: h.point,
    };
    shade_with::<S, T>(scene, &incoming, h.index, &hit, counters)
}

/// The colour of pixel `column` of the scanline at screen `y` on the reference path (the
/// background when its ray cannot be formed).
#[inline]
pub(crate) fn reference_color<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    y: Option<S>,
    column: u16,
    counters: &mut Counters,
) -> Color<S> {
    match y.and_then(|y| scene.camera.pixel_ray_at(column, y)) {
        Some(pixel) => trace_pixel_ray::<S, T>(scene, &pixel, counters).color,
        None => scene.background,
    }
}
