//! What a frame of this kernel must redraw of the frame before it, when the two scenes
//! differ only in where some spheres are ([`changed_columns`]).
//!
//! A pixel of a level row depends on a sphere in two ways only. It sees the sphere: then it
//! lies in the sphere's box on the screen (the fast kernel's `sphere_rows` and
//! `sphere_columns`, outside which the sphere is not even tested; the invariant
//! `no_pixel_outside_a_spheres_box_or_chord_sees_it` holds it). Or the sphere shadows its
//! hit: then the sphere is among the row's occluders of some light (`Level::occluders`, the
//! objects the row's shadow tests consider; a sphere whose shadow cone clears the row's
//! whole line is not among them, and its position is then read by no pixel of the row). So
//! a row whose plane keeps the moved spheres out of its occluders in both frames changes
//! only inside their boxes, old and new. In a row that keeps them, a pixel can change only
//! where their shadow can fall: where the exact segment test of its hit can meet a sphere,
//! in one frame or the other. A hit outside the sphere's shadow cone widened to `r·√(9/8)`
//! is one the exact test finds clear (`ShadowCone::clears`), and the row's hits lie on one
//! line: `ShadowCone::shadow_span` bounds the part of the line within a wider cone,
//! `r·√(5/4)`, and its columns are found from the row's `t'`, two more on each side for the
//! hits' roundings ([`shadow_columns`]; the same columns bound where a quick run's spans
//! may go on a row that keeps shadow cones). Any other row may change anywhere.

use core::ops::Range;

use super::super::fast::{Primary, hull};
use super::Rows;
use super::level::{RowShadows, cone_clears_row, row_shadows};
use crate::shade::stages::DiffuseShadows;
use crate::{Scalar, SceneView, Shape};

/// The columns of scanline `row` whose pixels may differ between `before` and `after`,
/// frames of two scenes that differ only in the centres of the objects in `moved` (bit
/// `i`: object `i`, a sphere in both), both drawn by this kernel. `None`: the row's pixels
/// are the same.
pub(crate) fn changed_columns<S: Scalar>(
    before: (&SceneView<'_, S>, &Rows<S>),
    after: (&SceneView<'_, S>, &Rows<S>),
    moved: u8,
    row: u16,
) -> Option<Range<u16>> {
    let width = after.0.camera.width;
    // A row this kernel does not decide once (`None` from `row_shadows`: the fast kernel
    // draws it), or one whose shadows it cannot bound, may change anywhere. The row's
    // plane and its occluders other than the moved spheres are the two frames' alike (the
    // scenes differ in the spheres' centres alone, which neither reads): they are formed
    // once, from the frame after; each frame's own cones decide the moved spheres.
    let first = |(scene, rows): (&SceneView<'_, S>, &Rows<S>)| rows.primary.row(scene, row, 0);
    let (Some(_), Some(first)) = (first(before), first(after)) else {
        return Some(0..width);
    };
    let Some(plane) = row_shadows::<S, DiffuseShadows>(after.0, &after.1.primary, &first) else {
        return Some(0..width);
    };
    let mut columns: Option<(u16, u16)> = None;
    for (kept, (scene, rows)) in [(false, before), (true, after)] {
        let p = &rows.primary;
        if let Some(plane) = &plane {
            match shadows(scene, p, (plane, kept), moved) {
                Some(Some(span)) => hull(&mut columns, span),
                Some(None) => {}
                None => return Some(0..width),
            }
        }
        hull(&mut columns, p.sphere_columns_on_row_of(row, moved));
    }
    let (a, b) = columns?;
    Some(a..b.saturating_add(1).min(width))
}

/// The columns of a row on `plane` where the spheres `moved` may shadow a hit, for
/// any light: `Some(None)`, nowhere; `None`, anywhere (no per-row occluders, no shadow
/// cone, or a bound out of the format). `kept`: whether `plane`'s occluders are this
/// frame's own (formed with `p`); otherwise each moved sphere's bit is formed from `p`'s
/// cones, as `Level::occluders` forms it.
fn shadows<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    (plane, kept): (&RowShadows<S>, bool),
    moved: u8,
) -> Option<Option<(u16, u16)>> {
    // Without per-row occluders every light takes the general test: every object, at
    // every pixel.
    if plane.occluders.is_empty() && !scene.lights.is_empty() {
        return None;
    }
    let t = plane.t;
    let mut columns: Option<(u16, u16)> = None;
    for (j, &bits) in plane.occluders.iter().enumerate() {
        let light = scene.lights.get(j)?.location;
        let (wy, wz) = (plane.y.checked_sub(light.y), plane.z.checked_sub(light.z));
        for i in 0..8u8 {
            if moved & (1 << i) == 0 {
                continue;
            }
            // A moved sphere among this frame's occluders of the row (its bit of
            // `Level::occluders`, from this frame's cones).
            let clear = if kept {
                bits & (1 << i) == 0
            } else {
                cone_clears_row(p, (j, usize::from(i)), (wy, wz))
            };
            if clear {
                continue;
            }
            let span = shadow_columns(scene, p, (j, i), (t, plane.y, plane.z))?;
            if let Some(span) = span {
                hull(&mut columns, span);
            }
        }
    }
    Some(columns)
}

/// The columns of a row whose hits lie on the line `(x, y, z)` (every `x`; `t` the row's
/// `t'`) where the exact segment test of a hit towards light `j` may meet sphere `i`
/// (its shadow cone, `ShadowCone::shadow_span`, two more columns on each side for the
/// hits' roundings): `Some(None)`, nowhere; `None`, anywhere (no cone, or a bound out of
/// the format).
pub(super) fn shadow_columns<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    (j, i): (usize, u8),
    (t, y, z): (S, S, S),
) -> Option<Option<(u16, u16)>> {
    // A pixel's hit is `eye + t'·D`, `D.x` its screen `x` less the eye's: the hit
    // `x = light.x + s` is seen at screen `x` `eye.x + (x − eye.x)/t'`.
    let eye = scene.camera.viewpoint.x;
    if t <= S::ZERO {
        return None;
    }
    let light = scene.lights.get(j)?.location;
    let cone = p
        .cones()
        .iter()
        .find(|c| usize::from(c.light) == j && c.object == i)?;
    let (wy, wz) = (y.checked_sub(light.y)?, z.checked_sub(light.z)?);
    let Some((lo, hi)) = cone.shadow_span(wy, wz)? else {
        return Some(None);
    };
    let screen = |s: S| {
        light
            .x
            .checked_add(s)?
            .checked_sub(eye)?
            .checked_div(t)?
            .checked_add(eye)
    };
    screen_columns(scene, screen(lo)?, screen(hi)?)
}

/// The columns whose screen `x` lies in `lo..=hi`, and two more on each side (the hits'
/// own roundings); `Some(None)`: none.
fn screen_columns<S: Scalar>(scene: &SceneView<'_, S>, lo: S, hi: S) -> Option<Option<(u16, u16)>> {
    let camera = &scene.camera;
    let width = camera.width;
    // The first column whose screen `x` is not `before` (`width`: none); the screen's `x`
    // grows with the column.
    let first_not = |before: &dyn Fn(S) -> bool| -> Option<u16> {
        let (mut a, mut b) = (0u16, width);
        while a < b {
            let mid = a + (b - a) / 2;
            if before(camera.screen_x(mid)?) {
                a = mid + 1;
            } else {
                b = mid;
            }
        }
        Some(a)
    };
    let first = first_not(&|x| x < lo)?;
    let past = first_not(&|x| x <= hi)?;
    let (lo, hi) = (i32::from(first) - 2, i32::from(past) - 1 + 2);
    let last = i32::from(width) - 1;
    if hi < 0 || lo > last || lo > hi {
        return Some(None);
    }
    Some(Some((
        u16::try_from(lo.max(0)).ok()?,
        u16::try_from(hi.min(last)).ok()?,
    )))
}

/// The objects whose centres alone differ between `before` and `after` (bit `i`: object
/// `i`, a sphere in both, of the same radius and material), or `None` when the scenes
/// differ in anything else (or have more objects than bits, textures or projectors).
pub(crate) fn moved_spheres<S: Scalar>(
    before: &SceneView<'_, S>,
    after: &SceneView<'_, S>,
) -> Option<u8> {
    let same = before.camera == after.camera
        && before.materials == after.materials
        && before.lights == after.lights
        && before.background == after.background
        && before.epsilon == after.epsilon
        && before.rules == after.rules
        && before.textures.is_empty()
        && after.textures.is_empty()
        && before.projectors.is_empty()
        && after.projectors.is_empty()
        && before.objects.len() == after.objects.len()
        && before.objects.len() <= 8;
    if !same {
        return None;
    }
    let mut moved = 0u8;
    for (i, (a, b)) in before.objects.iter().zip(after.objects).enumerate() {
        if a == b {
            continue;
        }
        match (&a.shape, &b.shape) {
            (Shape::Sphere(s), Shape::Sphere(t))
                if a.material == b.material && s.radius() == t.radius() =>
            {
                moved |= 1 << i;
            }
            _ => return None,
        }
    }
    Some(moved)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use std::string::String;

    use fixed::types::{I16F16, I20F12};

    use super::super::super::fast::{Primary, Row, resync_pixels};
    use super::super::invariants::scenes;
    use super::super::level::level;
    use super::shadow_columns;
    use crate::shade::stages::DiffuseShadows;
    use crate::{Scalar, Scene};

    /// At every hit of a level row's plane in `scenes` and format `S`, stepped as a scanline
    /// steps, outside the columns where a sphere among the row's occluders may shadow it from
    /// a light ([`shadow_columns`]), the sphere's exact segment test towards that light
    /// (with the segments' tolerance at the hit) says no. Returns the rows with such columns
    /// and the hits tested.
    fn shadow_columns_hold<S: Scalar>(scenes: &[(String, String, Option<u16>)]) -> (usize, usize) {
        let (mut rows, mut hits) = (0, 0);
        for (name, text, _) in scenes {
            let Ok(scene) = Scene::<S>::parse(text) else {
                continue;
            };
            let view = scene.view();
            let Some(p) = Primary::new(&view) else {
                continue;
            };
            let eye = view.camera.viewpoint;
            for row in 0..view.camera.height {
                let Some(first) = p.row(&view, row, 0) else {
                    continue;
                };
                let Some(Some(l)) = level::<S, DiffuseShadows>(&view, &p, &first) else {
                    continue;
                };
                for (j, &bits) in l.occluders.iter().enumerate() {
                    for i in (0..8u8).filter(|i| bits & (1 << i) != 0) {
                        let span = shadow_columns(&view, &p, (j, i), (l.t, l.y, l.z));
                        let (Some(Some((a, b))), Some(light), Some(object)) =
                            (span, view.lights.get(j), view.objects.get(usize::from(i)))
                        else {
                            continue;
                        };
                        let crate::Shape::Sphere(sphere) = &object.shape else {
                            continue;
                        };
                        rows += 1;
                        let mut state: Option<Row<S>> = None;
                        for column in 0..view.camera.width {
                            let stepped = match state.as_mut() {
                                Some(r) if column % resync_pixels::<S>() != 0 => p.advance(r),
                                _ => {
                                    state = p.row(&view, row, column);
                                    state.as_ref().map(|_| ())
                                }
                            };
                            let (Some(()), Some(r)) = (stepped, state.as_ref()) else {
                                state = None;
                                continue;
                            };
                            if (a..=b).contains(&column) {
                                continue;
                            }
                            let Ok(Some(h)) = p.nearest(&view, r) else {
                                continue;
                            };
                            let Some(to_light) = light.location.diff(h.point) else {
                                continue;
                            };
                            let ll = to_light.dot(to_light).filter(|ll| *ll > S::ZERO);
                            let tol = crate::kernel::shading::segment_tolerance(
                                eye, h.point, h.t_bound, None,
                            );
                            let (true, Some(ll), Some(tol)) = (h.index == l.index, ll, tol) else {
                                continue;
                            };
                            hits += 1;
                            assert!(
                                sphere.meets_segment(h.point, to_light, ll, tol) != Some(true),
                                "{} {name}: sphere {i} shadows ({column}, {row}) outside {a}..={b}\n{text}",
                                S::NAME
                            );
                        }
                    }
                }
            }
        }
        (rows, hits)
    }

    /// A row's shadow columns ([`shadow_columns`], what a frame's changes redraw of a
    /// moved sphere's shadow and where a quick run's spans may go on a row with shadow
    /// cones): outside them no hit of the row's plane is shadowed by the sphere. Checked on
    /// every row of eight boing frames and 60 random level scenes in I16F16 and I20F12 (over
    /// 400 rows with such columns and 20,000 hits outside them in each).
    #[test]
    fn no_hit_outside_a_rows_shadow_columns_is_shadowed() {
        let all = scenes(2, 60, 0x5EED_0005_0007);
        for (rows, hits) in [
            shadow_columns_hold::<I16F16>(&all),
            shadow_columns_hold::<I20F12>(&all),
        ] {
            assert!(rows > 400 && hits > 20_000, "{rows} {hits}");
        }
    }
}
