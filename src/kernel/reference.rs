//! The per-pixel scanline: each pixel's primary ray on the fast kernel where it has a
//! per-frame part, otherwise (and for any pixel the fast kernel hands back) the reference
//! path, the definition itself: a normalised ray per pixel through
//! [`crate::Camera::primary_ray_at`], traced and shaded.

use embedded_graphics_core::pixelcolor::Rgb888;

use super::fast::{self, Primary, Row};
use crate::shade::color::to_pixel;
use crate::shade::stages::Stages;
use crate::shade::{Incoming, PlaneSides, shade_with, trace_pixel_ray};
use crate::stats::{Counters, count};
use crate::{Color, Hit, Scalar, SceneView};

/// The pixels of columns `columns` of scanline `row` traced with the stage set `T`, one
/// per step, as the caller (a `fill_contiguous` or a line buffer) pulls them. With a
/// fast-kernel frame (`primary`) primary rays take [`super::fast`]; otherwise, and for
/// any pixel the fast kernel hands back, the reference path.
pub(crate) fn scanline<'a, S: Scalar, T: Stages, C: From<Rgb888>>(
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
    columns.map(move |column| {
        count(&mut counters.primary_rays);
        let found = primary.and_then(|p| {
            match state.as_mut() {
                Some(r)
                    if Primary::column(r).checked_add(1) == Some(column)
                        && column % fast::RESYNC_PIXELS != 0 =>
                {
                    p.advance(r)?
                }
                Some(r) => {
                    if p.restart(scene, row, column, r).is_none() {
                        state = None;
                        return None;
                    }
                }
                None => state = Some(p.row(scene, row, column)?),
            }
            p.nearest(scene, state.as_ref()?).ok()
        });
        let color = match found {
            Some(Some(h)) => match state.as_ref() {
                Some(r) => fast_color::<S, T>(scene, primary, r, &h, &mut at_hit, counters),
                None => scene.background,
            },
            Some(None) => scene.background,
            None => reference_color::<S, T>(scene, y, column, counters),
        };
        C::from(to_pixel(rules, color))
    })
}

/// The colour of the fast kernel's hit `h` at the row's current pixel: shaded with the
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
