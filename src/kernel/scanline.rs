//! The per-pixel scanline: each pixel's primary ray on the fast kernel where it has a
//! per-frame part, otherwise (and for any pixel the fast kernel hands back) the reference
//! path, the definition itself: a normalised ray per pixel through
//! [`crate::Camera::primary_ray_at`], traced and shaded.

use embedded_graphics_core::pixelcolor::Rgb888;

use super::fast::{self, Primary, Row};
use super::memo::{KernelStages, MemoSlot, Weights};
use super::shading::{lit_plane_color, lit_planes, lit_sphere_color};
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
    let last = columns.end.saturating_sub(1);
    scanline_over::<S, T, C, false>(scene, primary, (row, last), columns, counters)
}

/// [`scanline`] over any increasing columns of the row (`last`: the last of them, where
/// certified blocks end): with `JUMPS`, where a column is not the one after the previous,
/// the row resumes there as a whole scanline reaches it (`Primary::row_resumed`), so the
/// pixels are the whole scanline's. Without it (consecutive columns, every scanline but a
/// sampled frame's runs) the test is not compiled: it is a compare and a branch a pixel.
pub(crate) fn scanline_over<'a, S: Scalar, T: KernelStages, C: From<Rgb888>, const JUMPS: bool>(
    scene: &'a SceneView<'a, S>,
    primary: Option<&'a Primary<S>>,
    (row, last): (u16, u16),
    columns: impl Iterator<Item = u16> + 'a,
    counters: &'a mut Counters,
) -> impl Iterator<Item = C> + 'a {
    let y = scene.camera.screen_y(row);
    let rules = scene.rules();
    let mut state: Option<Row<S>> = None;
    // The planes' sides at the current pixel's hit (see `Primary::sides_at`).
    let mut at_hit = heapless::Vec::new();
    // The scanline's certified blocks (`Primary::find`).
    let mut blocks = fast::Blocks::default();
    // What the stage set's plane hits keep from pixel to pixel (`KernelStages::Memo`).
    let mut memo = T::Memo::<S>::default();
    let mut next = None;
    columns.map(move |column| {
        count(&mut counters.primary_rays);
        if JUMPS {
            if next != Some(column) {
                // A jump: the row resumes at `column` (`step_to` on no row).
                state = None;
            }
            next = column.checked_add(1);
        }
        // Without the kernels (cargo feature `kernels`) the fast kernel's code is not
        // linked: the test is a constant here, where each pixel reads `primary`.
        let found = primary.filter(|_| super::KERNELS).and_then(|p| {
            let stepping = memo.memo().map(|m| &mut m.stepping);
            let r = p.step_to(scene, (row, column), &mut state, &mut blocks, stepping)?;
            // The still planes' hits the stage set's memo keeps (`fast::HitMemo`).
            let hits = memo.memo().map(|m| &mut m.hits);
            p.find(scene, r, (column, last), &mut blocks, hits)
        });
        blocks.saw::<S>(found.as_ref().map(|h| h.as_ref().map(|h| h.index)));
        let color = match found {
            Some(Some(h)) => match state.as_mut() {
                Some(r) => {
                    // The flattened plane shading first (not called at all for the
                    // other stage sets and formats), else the general one (with every
                    // term up to date: `fast::Stepping`).
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
                            if let (Some(m), Some(p)) = (memo.memo(), primary) {
                                // (Where a term does not fit, the general shading
                                // forms what it needs itself.)
                                let _ = p.catch_up(scene, r, &mut m.stepping);
                            }
                            let weights = memo.memo().map(|m| &mut m.weights);
                            let at = (&mut at_hit, weights);
                            fast_color::<S, T>(scene, primary, r, &h, at, counters)
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

/// The colour of the fast kernel's hit `h` at the row's current pixel: a sphere hit by
/// [`lit_sphere_color`] where it draws one, else by the general shading ([`shaded`];
/// the scanline tries [`lit_plane_color`] first for plane hits).
pub(crate) fn fast_color<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    primary: Option<&Primary<S>>,
    r: &Row<S>,
    h: &fast::FastHit<S>,
    (at_hit, weights): (
        &mut heapless::Vec<S, { fast::FAST_OBJECTS }>,
        Option<&mut Weights<S>>,
    ),
    counters: &mut Counters,
) -> Color<S> {
    shaded::<S, T>(scene, primary, r, h, (at_hit, weights), counters, true)
}

/// [`fast_color`], with [`lit_sphere_color`] tried first where `spheres` (without it: the
/// general shading alone, what `lit_sphere_color` is tested against); otherwise the
/// general shading (`shade_with`): shaded with the unnormalised direction (see
/// `Incoming`; the fast kernel takes only stage sets that need no more of it than its
/// side), shadow segments taking the planes' sides from the kernel's terms (`at_hit`: a
/// buffer the scanline keeps).
#[inline(always)]
pub(super) fn shaded<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    primary: Option<&Primary<S>>,
    r: &Row<S>,
    h: &fast::FastHit<S>,
    (at_hit, weights): (
        &mut heapless::Vec<S, { fast::FAST_OBJECTS }>,
        Option<&mut Weights<S>>,
    ),
    counters: &mut Counters,
    spheres: bool,
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
    if spheres && let Some(color) = lit_sphere_color::<S, T>(scene, h, sides, weights, counters) {
        return color;
    }
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
