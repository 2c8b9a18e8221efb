//! What a frame of this kernel must redraw of the frame before it, when the two scenes
//! differ only in where some spheres are ([`changed_columns`]).
//!
//! A pixel of a level row depends on a sphere in two ways only. It sees the sphere: then
//! it lies in the sphere's box on the screen (the fast kernel's `sphere_rows` and
//! `sphere_columns`, outside which the sphere is not even tested; the invariant
//! `no_pixel_outside_a_spheres_box_sees_it` holds it). Or the sphere shadows its hit:
//! then the sphere is among the row's occluders of some light (`Level::occluders`, the
//! objects the row's shadow tests consider; a sphere whose shadow cone clears the row's
//! whole line is not among them, and its position is then read by no pixel of the row).
//! So a row whose plane keeps the moved spheres out of its occluders in both frames
//! changes only inside their boxes, old and new; any other row may change anywhere.

use core::ops::Range;

use super::Rows;
use super::level::level;
use crate::shade::stages::DiffuseShadows;
use crate::{Scalar, SceneView, Shape};

/// A scanline drawn from a column that is a multiple of this has the pixels of the whole
/// scanline (its restarts fall there: the fast kernel's blocks and resyncs).
pub(crate) const RESUME: u16 = 64;

/// The columns of scanline `row` whose pixels may differ between `before` and `after`,
/// frames of two scenes that differ only in the centres of the objects in `moved` (bit
/// `i`: object `i`, a sphere in both), both drawn by this kernel. `None`: the row's pixels
/// are the same; a range starts at a multiple of [`RESUME`].
pub(crate) fn changed_columns<S: Scalar>(
    before: (&SceneView<'_, S>, &Rows<S>),
    after: (&SceneView<'_, S>, &Rows<S>),
    moved: u8,
    row: u16,
) -> Option<Range<u16>> {
    let width = after.0.camera.width;
    let mut columns: Option<(u16, u16)> = None;
    for (scene, rows) in [before, after] {
        let p = &rows.primary;
        // A row this kernel does not decide once is drawn by the fast kernel, whose
        // shadow tests take every object.
        let Some(first) = p.row(scene, row, 0) else {
            return Some(0..width);
        };
        let Some(plane) = level::<S, DiffuseShadows>(scene, p, &first) else {
            return Some(0..width);
        };
        if let Some(plane) = plane {
            // Without per-row occluders every light takes the general test: every
            // object, at every pixel.
            let general = plane.occluders.is_empty() && !scene.lights.is_empty();
            if general || plane.occluders.iter().any(|bits| bits & moved != 0) {
                return Some(0..width);
            }
        }
        let (a, b) = p.sphere_columns_on_row_of(row, moved);
        if a <= b {
            columns = Some(columns.map_or((a, b), |(c, d)| (c.min(a), d.max(b))));
        }
    }
    let (a, b) = columns?;
    Some(a / RESUME * RESUME..b.saturating_add(1).min(width))
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
                if a.material == b.material
                    && s.radius_sq() == t.radius_sq()
                    && s.radius() == t.radius() =>
            {
                moved |= 1 << i;
            }
            _ => return None,
        }
    }
    Some(moved)
}
