//! Fast primary rays for scenes of planes (infinite, tiled, finite, triangles) and
//! spheres, under the crate's rules.
//!
//! The reference path ([`crate::shade::trace_pixel`]) normalises every primary ray and
//! divides once per plane. Here, per frame, `num = D' − N·eye` is computed once per plane
//! (the eye is every primary ray's base), and per pixel the ray's direction is left
//! unnormalised, `D = screen point − eye` (its x stepped along the scanline). `N·D` is
//! linear along the scanline: it is kept as the unrounded double-width sum
//! (`KernelArith::Acc`) and grows by the per-frame `N.x × step` per pixel, so that a
//! pixel costs no product for it (in the fixed formats bit for bit the wide dot product
//! of the stepped `D`). Spheres keep `oc·D` the same way (`oc = eye − centre`) and test
//! the discriminant's sign exactly (`sphere_root`). The plane test of `docs/scene-format.md`
//! is then evaluated in an equivalent form without dividing:
//!
//! - parallel, `|N·d| < EPS` with `d = D/|D|`  ⇔  `(N·D)² < EPS·(EPS·|D|²)`;
//! - behind, `t < 0`  ⇔  `num` and `N·D` of opposite signs;
//! - in front of the screen, `hit.z > 0`  ⇔  `t' = num/(N·D) < 1` (the screen point is at
//!   `t' = 1` exactly, since `D` ends on the screen)  ⇔  `|num| < |N·D|`;
//! - nearest: `t'_i < t'_j`  ⇔  `|num_i|·|N·D_j| < |num_j|·|N·D_i|` (exact products,
//!   [`crate::Scalar::cmp_products`]).
//!
//! Only the winning plane is divided (`t' = num/N·D`, hit = eye + t'·D), and a finite
//! plane's bounds are checked on its own hit. Results are those of the definition up to
//! rounding: pixels can differ only where two planes meet, at the epsilon and at the
//! screen (`tests/fast.rs` compares every pixel with the reference path). A pixel whose
//! winner does not fit the format falls back to the reference path, so range misses are
//! exactly the reference's.
//!
//! Its files: this one, the per-frame set-up ([`Primary::new`]: a term per object, the
//! lights' sides, the spheres' shadow cones, whether every term fits the frame);
//! `step.rs`, stepping along a scanline ([`Row`]); `search.rs`, the plane and sphere
//! tests and the nearest hit; `boxes.rs`, the spheres' boxes on the screen;
//! `blocks.rs`, certified blocks; `shadows.rs`, the planes' sides at a hit and the quiet
//! planes.

mod blocks;
mod boxes;
#[cfg(test)]
mod invariants;
#[cfg(test)]
pub(super) use invariants::each_pixel;
mod search;
mod shadows;
mod step;
#[cfg(test)]
mod tests;

pub(crate) use blocks::{Blocks, blocks_for};
pub(crate) use boxes::hull;
pub use search::FastHit;
pub(crate) use search::{HitMemo, accepts};
pub(crate) use shadows::Quiet;
pub(crate) use step::Stepping;
pub(crate) use step::resync_pixels;
pub use step::{RESYNC_PIXELS, Row};

use heapless::Vec;

use crate::geometry::ShadowCone;
use crate::shade::SIDE_BITS_LIGHTS;
use crate::{Scalar, SceneView, Shape, Vec3};
use boxes::{sphere_columns, sphere_rows};

/// A term of the fast path: which object and, for a plane, `num = D' − N·eye`, for a
/// sphere `num = |oc|² − r²` with `oc = eye − centre` (positive: the eye is outside).
/// The vector the scanline dots `D` with (the normal, `oc`) is read from the scene: on a
/// 16 KB chip a copy of every one is RAM the stack needs.
#[derive(Debug, Clone, Copy)]
struct Term<S> {
    index: u8,
    num: S,
    sphere: bool,
    /// The rows the term can be hit on (first, last): every row for a plane; for a
    /// sphere the rows whose plane of rays passes near it ([`sphere_rows`]), so that a
    /// pixel on another row skips its test.
    rows: (u16, u16),
    /// The columns likewise ([`sphere_columns`]): a sphere is tested only inside its
    /// box on the screen.
    columns: (u16, u16),
    /// Whether the sphere is large enough for its box's margin (`boxes::bounded`), and
    /// so for its chords of a row (`Primary::sphere_chords_on_row`).
    bounded: bool,
}

/// What a term dots `D` with: the unit normal of a plane-like object, `eye − centre` of
/// a sphere.
#[inline]
fn axis_of<S: Scalar>(scene: &SceneView<'_, S>, index: u8) -> Option<Vec3<S>> {
    match &scene.objects.get(usize::from(index))?.shape {
        Shape::Sphere(s) => scene.camera.viewpoint.diff(s.center()),
        shape @ (Shape::Plane(_)
        | Shape::Tiled { .. }
        | Shape::Finite(_)
        | Shape::Textured(_)
        | Shape::Triangle(_)
        | Shape::Revsurf(_)) => Some(shape.plane()?.normal()),
    }
}

/// The per-frame part of the fast path; `None` from [`Primary::new`] when the scene is not
/// made of planes and spheres (the eye outside them) or a per-frame quantity does not fit
/// the format.
#[derive(Debug, Clone)]
pub struct Primary<S: Scalar> {
    terms: Vec<Term<S>, FAST_OBJECTS>,
    /// `N_i.x × step_x` of every term, unrounded: what `N·D` grows by from pixel to
    /// pixel (`KernelArith::Acc`).
    steps: Vec<S::Acc, FAST_OBJECTS>,
    /// `D'_i − N_i·light_j` at `j × objects + i` (the lights' sides of every plane, for
    /// shadow segments: [`crate::shade::PlaneSides`]); empty when they do not fit
    /// [`MAX_SIDES`] or the format.
    at_lights: Vec<S, MAX_SIDES>,
    /// Per light (the first [`SIDE_BITS_LIGHTS`]), which of its `at_lights` are
    /// positive, as bits (one per object; read only where `at_lights` is kept).
    light_positive: [u8; SIDE_BITS_LIGHTS],
    /// The spheres among the terms, as bits.
    sphere_bits: u8,
    /// Whether a scanline may draw a block of pixels with one certified winner
    /// ([`Primary::certify_block`]): every object a plain or tiled plane, in a format
    /// whose products are exact.
    blocks: bool,
    /// The spheres' shadow cones from the lights ([`ShadowCone`]).
    cones: Vec<ShadowCone<S>, MAX_CONES>,
    /// Whether a term is a sphere (the scanline then keeps `D·D`).
    spheres: bool,
    /// The terms whose vector has `x = 0` (a floor's or a back wall's normal), as bits:
    /// their `N·D` is the same at every pixel of a scanline (its step is `0 × step`), so
    /// a pixel does not step it and a restart of the same scanline keeps it.
    still: u8,
    /// Screen x step between pixel centres, `WX / W`.
    step_x: S,
    /// `resync_pixels·|step_x|`: how far `|D.x|` can move between two restarts of a
    /// scanline (`None`: too far for the format; each pixel then bounds itself).
    resync_span: Option<S>,
    /// `−eye.z`, the z of every `D`.
    dz: S,
    /// The screen's x unit where the window divides exactly (`Camera::x_unit`; zero:
    /// it does not): a restart's screen x is then a product, not a division.
    x_unit: S,
    /// Whether every term's `N·D` (and its unrounded sum, and the sum's rounding) fits
    /// the format at every `D` of the frame ([`Primary::frame_fits`]): a step then
    /// needs no overflow test (`KernelArith::acc_step_fitting`).
    fits: bool,
}

/// How many sphere–light shadow cones a frame keeps (beyond, the exact test alone).
pub const MAX_CONES: usize = 3;

/// How many plane–light sides a frame keeps (objects × lights; beyond, shadow segments
/// compute their sides themselves): 48 bytes in I16F16, 96 in I32F32, a RAM budget a
/// 16 KB chip affords beside the rest of the frame (the shipped scenes need at most 9;
/// the frame's sphere terms and screen boxes share the same budget).
pub const MAX_SIDES: usize = 12;

/// The most objects the fast kernel takes: a scene with more is drawn on the reference
/// path. Its per-frame and per-scanline vectors (terms, steps, `N·D` and its unrounded
/// sum, the planes' sides at a hit) are sized by it, and on a 16 KB chip in I32F32 the
/// frame and the deepest shading stack must fit beside the scene.
pub const FAST_OBJECTS: usize = 8;

// A frame's still terms and a row's occluders are bits of a `u8`, one per object.
const _: () = assert!(FAST_OBJECTS <= 8);

/// Object `index`'s term and the vector its `N·D` dots `D` with (`axis_of`); `None`
/// where the fast kernel cannot take the object (a surface of revolution, a sphere with
/// the eye inside or without the `spheres` feature, a quantity out of range).
#[inline(always)]
fn term_of<S: Scalar>(
    scene: &SceneView<'_, S>,
    index: usize,
    object: &crate::Object<S>,
) -> Option<(Term<S>, Vec3<S>)> {
    let eye = scene.camera.viewpoint;
    let all_rows = (0, scene.camera.height.saturating_sub(1));
    let all_columns = (0, scene.camera.width.saturating_sub(1));
    let (num, axis, sphere, rows, columns, bounded) = match &object.shape {
        Shape::Sphere(s) => {
            // Only with the eye outside every sphere (the near root is then the one, and
            // c/q has no cancellation), and with the sphere code built in.
            if !cfg!(feature = "spheres") {
                return None;
            }
            let oc = eye.diff(s.center())?;
            let c = S::sub_dot3(s.radius_sq(), oc.to_array(), oc.to_array())?.checked_neg()?;
            if c <= S::ZERO {
                return None;
            }
            let dz = S::ZERO.checked_sub(eye.z)?;
            let rr = s.radius_sq();
            let rows = sphere_rows(scene, oc, rr, dz);
            let columns = sphere_columns(scene, oc, rr, dz);
            (c, oc, true, rows, columns, boxes::bounded(oc, rr, dz))
        }
        // The kernel has no term for a surface of revolution: the reference path.
        Shape::Revsurf(_) => return None,
        shape @ (Shape::Plane(_)
        | Shape::Tiled { .. }
        | Shape::Finite(_)
        | Shape::Textured(_)
        | Shape::Triangle(_)) => {
            let plane = shape.plane()?;
            let num = S::sub_dot3(plane.offset(), plane.normal().to_array(), eye.to_array())?;
            (num, plane.normal(), false, all_rows, all_columns, false)
        }
    };
    let term = Term {
        index: u8::try_from(index).ok()?,
        num,
        sphere,
        rows,
        columns,
        bounded,
    };
    Some((term, axis))
}

/// Fills `at_lights` with the lights' sides of every plane (`D'_i − N_i·light_j` at
/// `j × objects + i`, a sphere's a place holder) and `light_positive`, per light, with
/// which are positive as bits ([`crate::shade::SideBits`]); no sides where they do not
/// fit [`MAX_SIDES`] or the format (shadow segments then form them). In place: the
/// frame is built where the renderer keeps it (a 16 KB chip's stack).
#[inline(always)]
fn light_sides<S: Scalar>(
    scene: &SceneView<'_, S>,
    terms: &[Term<S>],
    at_lights: &mut Vec<S, MAX_SIDES>,
    light_positive: &mut [u8; SIDE_BITS_LIGHTS],
) -> Option<()> {
    let sides = terms.len().checked_mul(scene.lights.len());
    if sides.is_none_or(|n| n > MAX_SIDES) {
        return Some(());
    }
    for (j, light) in scene.lights.iter().enumerate() {
        let mut positive = 0u8;
        for (i, term) in terms.iter().enumerate() {
            if term.sphere {
                // A sphere's shadow test does not use sides (`meets_segment_with`): a
                // place holder keeps the list indexed by object.
                at_lights.push(S::ZERO).ok()?;
                continue;
            }
            let object = scene.objects.get(usize::from(term.index))?;
            let plane = object.shape.plane()?;
            let side = S::sub_dot3(
                plane.offset(),
                plane.normal().to_array(),
                light.location.to_array(),
            );
            let Some(a1) = side else {
                at_lights.clear();
                return Some(());
            };
            if a1 > S::ZERO {
                positive |= 1 << i;
            }
            at_lights.push(a1).ok()?;
        }
        // Beyond `SIDE_BITS_LIGHTS` lights, those lights have no bits.
        if let Some(slot) = light_positive.get_mut(j) {
            *slot = positive;
        }
    }
    Some(())
}

/// Every sphere's shadow cone from every light that fits ([`ShadowCone`]), up to
/// [`MAX_CONES`].
fn shadow_cones<S: Scalar>(
    scene: &SceneView<'_, S>,
    terms: &[Term<S>],
) -> Vec<ShadowCone<S>, MAX_CONES> {
    let mut cones = Vec::new();
    for (j, light) in scene.lights.iter().enumerate() {
        for term in terms.iter().filter(|t| t.sphere) {
            let Some(Shape::Sphere(s)) =
                scene.objects.get(usize::from(term.index)).map(|o| o.shape)
            else {
                continue;
            };
            let cone = ShadowCone::new(j, term.index, &s, light.location);
            if let Some(c) = cone
                && cones.push(c).is_err()
            {
                return cones;
            }
        }
    }
    cones
}

impl<S: Scalar> Primary<S> {
    /// Prepares a frame, or `None` when the fast path does not apply (the eye inside a
    /// sphere, more than
    /// `FAST_OBJECTS` objects, or a quantity out of range): the caller then uses the
    /// reference path.
    pub fn new(scene: &SceneView<'_, S>) -> Option<Self> {
        let eye = scene.camera.viewpoint;
        let step_x = scene
            .camera
            .world_width
            .mul_ratio(1, i32::from(scene.camera.width))?;
        let mut terms = Vec::new();
        let mut steps = Vec::new();
        let mut spheres = false;
        let mut still = 0u8;
        let mut sphere_bits = 0u8;
        for (index, object) in scene.objects.iter().enumerate() {
            let (term, axis) = term_of(scene, index, object)?;
            spheres |= term.sphere;
            terms.push(term).ok()?;
            if axis.x == S::ZERO {
                still |= 1 << (terms.len() - 1);
            }
            if term.sphere {
                sphere_bits |= 1 << (terms.len() - 1);
            }
            steps.push(S::acc_mul(axis.x, step_x)?).ok()?;
        }
        let mut at_lights = Vec::new();
        let mut light_positive = [0u8; SIDE_BITS_LIGHTS];
        light_sides(scene, &terms, &mut at_lights, &mut light_positive)?;
        let blocks = blocks_for::<S>()
            && scene
                .objects
                .iter()
                .all(|o| matches!(o.shape, Shape::Plane(_) | Shape::Tiled { .. }));
        let cones = if spheres {
            shadow_cones(scene, &terms)
        } else {
            Vec::new()
        };
        let mut primary = Self {
            terms,
            steps,
            at_lights,
            light_positive,
            cones,
            spheres,
            sphere_bits,
            blocks,
            still,
            step_x,
            resync_span: S::from_i32(i32::from(resync_pixels::<S>()))
                .and_then(|n| n.checked_mul(step_x.abs())),
            dz: S::ZERO.checked_sub(eye.z)?,
            x_unit: scene.camera.x_unit().unwrap_or(S::ZERO),
            fits: false,
        };
        primary.fits = primary.frame_fits(scene);
        Some(primary)
    }

    /// Whether every term fits at every `D` a scanline of the frame can take: `D.x`
    /// within [`Primary::dx_range`] (the stepped drift included), `D.y` between the first
    /// and the last row's, `D.z` the frame's. A term is affine in `D`, so its unrounded
    /// sum lies between its values at the four corners, and if each of those rounds
    /// into the format (half a DELTA added, no overflow) so does every sum between.
    fn frame_fits(&self, scene: &SceneView<'_, S>) -> bool {
        let fits = || -> Option<()> {
            let camera = &scene.camera;
            let (lo, hi) = self.dx_range(scene, camera.width)?;
            let dy = |row: u16| camera.screen_y(row)?.checked_sub(camera.viewpoint.y);
            let (top, bottom) = (dy(0)?, dy(camera.height.checked_sub(1)?)?);
            for term in &self.terms {
                let axis = axis_of(scene, term.index)?.to_array();
                for d in [[lo, top], [lo, bottom], [hi, top], [hi, bottom]] {
                    S::acc_round(S::acc_dot3(axis, [d[0], d[1], self.dz])?)?;
                }
            }
            Some(())
        };
        fits().is_some()
    }

    /// Every pixel's `D.z` (`−eye.z`: the screen is the plane `z = 0`).
    #[inline(always)]
    pub(crate) fn dz(&self) -> S {
        self.dz
    }

    /// The lights' sides of every plane, per frame (empty when not kept).
    pub(crate) fn at_lights(&self) -> &[S] {
        &self.at_lights
    }

    /// The spheres' shadow cones, per frame.
    pub(crate) fn cones(&self) -> &[ShadowCone<S>] {
        &self.cones
    }
}
