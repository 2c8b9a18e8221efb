//! The per-pixel scanline: each pixel's primary ray on the fast kernel where it has a
//! per-frame part, otherwise (and for any pixel the fast kernel hands back) the reference
//! path, the definition itself: a normalised ray per pixel through
//! [`crate::Camera::primary_ray_at`], traced and shaded.

use embedded_graphics_core::pixelcolor::Rgb888;

use super::fast::{self, Primary, Row};
use crate::geometry::{surface_tolerance, surface_tolerance_fits};
use crate::shade::color::{add_sat, term, to_pixel};
use crate::shade::stages::Stages;
use crate::shade::{
    Incoming, PlaneSides, channel_max, diffuse_falloff, material_at, occluded_among,
    occludes_segment, shade_with, trace_pixel_ray,
};
use crate::stats::{Counters, count};
use crate::{Beam, Color, Hit, Scalar, SceneView, Shape, Vec3};

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

/// Whether [`lit_plane_color`] draws the fast kernel's plane hits with the stage set `T`
/// in format `S` (in a build with the kernels: without them its code is not linked):
/// diffuse lights (with or without shadows: no glint, cone, mirror or
/// translucence), in a format whose products are exact (the hit's facing normal is then
/// read off the row's `N·D`, which is the shading's `D·N` itself).
const fn lit_planes<S: Scalar, T: Stages>() -> bool {
    super::KERNELS
        && S::EXACT_PRODUCTS
        && T::LIGHTING
        && !T::SPECULAR
        && !T::CONES
        && !T::REFLECTION
        && !T::TRANSPARENCY
}

/// The colour of the fast kernel's hit `h` on a plain or tiled plane under a stage set
/// of [`lit_planes`] (`None` for any other): the crate's shading of it (`own_color`, `light_with` and
/// `segment_terms` of `shade/`) flattened to what such a hit needs: the same operations
/// in the same order, so the same colour bit for bit (tested against [`fast_color`]'s
/// general shading), without building the general case's light loop state. The normal
/// facing the ray is the plane's, turned by the sign of the row's `N·D`. `None` where the
/// pixel needs the general shading: another shape, a light on a surface, a projector,
/// a light whose `|L|²` does not fit or is not positive (the general path's ray terms;
/// the statistics then count the earlier lights twice, as the level-plane kernel's do),
/// or a segments' tolerance that does not fit.
#[inline(always)]
fn lit_plane_color<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    r: &mut Row<S>,
    h: &fast::FastHit<S>,
    at: (
        &mut heapless::Vec<S, { fast::FAST_OBJECTS }>,
        Option<&mut PlaneMemo<S>>,
    ),
    counters: &mut Counters,
) -> Option<Color<S>> {
    if !lit_planes::<S, T>() {
        return None;
    }
    lit_plane_with(scene, p, r, h, at, T::SHADOWS, counters)
}

/// [`lit_plane_color`] with the stage set's shadows as a value: one copy per format for
/// both diffuse sets (flash).
#[inline(never)]
fn lit_plane_with<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    r: &mut Row<S>,
    h: &fast::FastHit<S>,
    (at_hit, mut memo): (
        &mut heapless::Vec<S, { fast::FAST_OBJECTS }>,
        Option<&mut PlaneMemo<S>>,
    ),
    set_shadows: bool,
    counters: &mut Counters,
) -> Option<Color<S>> {
    let object = scene.objects.get(h.index)?;
    // A light on a surface or a projector takes the general shading (asked once per
    // scanline where the memo keeps the answer).
    let general = || {
        scene.lights_on_surfaces
            || scene
                .lights
                .iter()
                .any(|l| matches!(l.beam, Beam::Projector(_)))
    };
    let general = match memo.as_deref_mut() {
        Some(m) => *m.general.get_or_insert_with(general),
        None => general(),
    };
    if general || !matches!(object.shape, Shape::Plane(_) | Shape::Tiled { .. }) {
        return None;
    }
    let normal = object.shape.plane()?.normal();
    // The segments' tolerance (`Fixray::segment_tolerance`): formed where a segment test
    // needs it, once it is known to fit (the general path takes its ray terms where it
    // does not), before anything is counted.
    let shadows = set_shadows && scene.shadows;
    if shadows && !surface_tolerance_fits(h.t_bound) {
        segment_tolerance(scene, h)?;
    }
    // As `surface` (no texture: a plain or tiled plane), with the material's index.
    let index = match object.shape {
        Shape::Plane(_) => object.material,
        _ => material_at(object, h.point, scene.rules(), counters),
    };
    let Some(material) = scene.materials.get(usize::from(index)) else {
        return Some([S::ZERO; 3]);
    };
    let mut color = material.ambient;
    if scene.lights.is_empty() || material.diffuse == [S::ZERO; 3] {
        return Some(color);
    }
    // Where every other plane is quiet (`Primary::quiet_planes`), no segment test can
    // find a shadow: none is made, and no side formed.
    let quiet = shadows
        && S::EXACT_QUOTIENTS
        && memo
            .as_deref_mut()
            .is_some_and(|m| quiet_hit(scene, p, r, h, m));
    // The sides need every term: a row stepped by its block's plane alone is brought up
    // to date first (`PlaneMemo::stale`).
    if set_shadows
        && !quiet
        && let Some(m) = memo.as_deref_mut()
        && m.stale
    {
        p.refresh(scene, r)?;
        (m.stale, m.lazy) = (false, false);
    }
    // A term's position is its object's index (every object is a term): the row's `N·D`
    // of the plane is the shading's `D·N` (the exact products' sum, rounded once). Its
    // sign is `num`'s wherever the plane is hit (`ahead`), so the facing normal, and the
    // world axis it may lie along (`Vec3::dot_axis`), are the plane's for the frame:
    // kept for the last plane (`PlaneMemo`).
    let turned = |turn: bool| {
        if turn {
            normal.checked_neg().unwrap_or(normal)
        } else {
            normal
        }
    };
    let facing_of = || -> Option<Facing> {
        let turn = Primary::nd(r, h.index)? > S::ZERO;
        Some((turn, turned(turn).world_axis()))
    };
    let (turn, axis) = match memo.as_deref_mut() {
        Some(m) => match m.facing {
            Some((k, f)) if usize::from(k) == h.index => f,
            _ => {
                let f = facing_of()?;
                m.facing = u8::try_from(h.index).ok().map(|k| (k, f));
                f
            }
        },
        None => facing_of()?,
    };
    // The first lights' `emissivity × diffuse`, the first product of each term, kept
    // for the material (`PlaneMemo`).
    let weights = memo.map(|m| m.weights(scene, index, material));
    // (The own plane's side is not formed where the shadow tests leave it out, below.)
    let own = if S::EXACT_QUOTIENTS {
        h.index
    } else {
        usize::MAX
    };
    let sides = match !quiet && set_shadows && !p.at_lights().is_empty() {
        true => p.sides_but(r, h.param, own, at_hit).map(|bits| PlaneSides {
            at_hit,
            at_lights: p.at_lights(),
            cones: p.cones(),
            bits,
        }),
        false => None,
    };
    let k = channel_max::<S>();
    for (j, light) in scene.lights.iter().enumerate() {
        let Some(to_light) = light.location.diff(h.point) else {
            continue;
        };
        let ll = to_light.dot(to_light).filter(|ll| *ll > S::ZERO)?;
        // (`dot_axis`, with the plane's axis looked up once.)
        let nl = match axis {
            Some(along) => to_light.along(along),
            None => to_light.dot(turned(turn)),
        };
        let Some(nl) = nl.filter(|c| *c > S::ZERO) else {
            continue;
        };
        if shadows {
            count(&mut counters.shadow_rays);
            // (A quiet hit's segments cannot be stopped: `quiet_hit`.)
            if !quiet && plane_hit_shadowed(scene, sides, h, (j, light), to_light, ll)? {
                continue;
            }
        }
        let falloff = diffuse_falloff(nl, nl.checked_mul(k), ll);
        count(&mut counters.diffuse);
        match weights.and_then(|m| m.weight(scene, j)) {
            // `term([e, d, falloff])` is `(e·d)·falloff`, saturating (as where `e·d`
            // overflowed: its bit in the memo's `overflow`).
            Some((w, overflow)) => {
                for (k, (c, w)) in color.iter_mut().zip(w).enumerate() {
                    let t = match overflow & (1 << k) {
                        0 => w.checked_mul(falloff).unwrap_or(S::MAX),
                        _ => S::MAX,
                    };
                    *c = add_sat(*c, t);
                }
            }
            None => {
                for ((c, diffuse), emissivity) in
                    color.iter_mut().zip(material.diffuse).zip(light.emissivity)
                {
                    *c = add_sat(*c, term([emissivity, diffuse, falloff]));
                }
            }
        }
    }
    Some(color)
}

/// The segments' tolerance at the fast kernel's hit `h` (`Fixray::segment_tolerance`).
#[inline(always)]
fn segment_tolerance<S: Scalar>(scene: &SceneView<'_, S>, h: &fast::FastHit<S>) -> Option<S> {
    let m = scene.camera.viewpoint.max_abs().max(h.point.max_abs());
    surface_tolerance(h.t_bound, m)
}

/// Whether the shadow segment from the plane hit `h` towards light `j` (`L = to_light`,
/// `|L|² = ll`) is stopped, as `occludes_segment` decides (`None` where the segments'
/// tolerance does not fit, which the caller has ruled out). The objects that may stand
/// between the hit and the light are the ones `occludes_segment` picks, less the hit's
/// own plane where quotients are exact: its side at the hit is `num − t'·(N·D)` with
/// `t'` within a DELTA of `num/(N·D)`, so it lies within `(|N·D| + 1)·DELTA` of zero,
/// inside the tolerance `(t'·2|D|∞ + 12)·DELTA` (`t' ≥ 1`, `|N·D| ≤ √3|D|∞`), and
/// `sides_differ` passes it over. Where none remains, no tolerance is formed. Out of
/// line: the pixels that take it are few (the others are quiet, `quiet_hit`).
#[inline(never)]
fn plane_hit_shadowed<S: Scalar>(
    scene: &SceneView<'_, S>,
    sides: Option<PlaneSides<'_, S>>,
    h: &fast::FastHit<S>,
    (j, light): (usize, &crate::Light<S>),
    to_light: Vec3<S>,
    ll: S,
) -> Option<bool> {
    let shadowed = match sides {
        Some(s) if S::EXACT_QUOTIENTS && s.at_hit.len() == scene.objects.len() => {
            let bits = s.bits.candidates(j) & !object_bit(h.index);
            if bits == 0 {
                Some(false)
            } else {
                let segment = (h.point, to_light, ll, segment_tolerance(scene, h)?);
                occluded_among(scene, s, j, bits, segment, |_| false)
            }
        }
        _ => None,
    };
    Some(match shadowed {
        Some(v) => v,
        None => {
            let sides = sides.map(|s| (s, j));
            let tol = segment_tolerance(scene, h)?;
            occludes_segment(scene, sides, h.point, to_light, ll, tol, light.location)
        }
    })
}

/// Object `index`'s bit in a set of objects as bits (none beyond the eighth).
#[inline(always)]
fn object_bit(index: usize) -> u8 {
    u32::try_from(index)
        .ok()
        .and_then(|i| 1u8.checked_shl(i))
        .unwrap_or(0)
}

/// Whether every plane but the hit's own is quiet for the hit `h` of the row's current
/// pixel ([`Primary::quiet_planes`]: its `t'` within their bound, every plane out of the
/// epsilon's margin, as at every pixel of a certified block), so that no shadow segment
/// from it can be stopped (a frame of plain and tiled planes only; the caller's format
/// has exact quotients).
#[inline(always)]
fn quiet_hit<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    r: &Row<S>,
    h: &fast::FastHit<S>,
    memo: &mut PlaneMemo<S>,
) -> bool {
    let q = memo.quiet(scene, p, r);
    // (Every plane of a certified block's pixel is out of the margin: `HitMemo::certified`.)
    (q.loud == 0 || q.loud == object_bit(h.index))
        && h.param <= q.t_max
        && (memo.hits.certified || Primary::clear_of_margin(r, h.index))
}

/// A plane's normal facing the eye (whether it is the plane's normal turned), and the
/// world axis it lies along if it does (`Vec3::world_axis`).
type Facing = (bool, Option<(u8, bool)>);

/// How many lights' weights a [`PlaneMemo`] keeps (the others' terms take both
/// products): one, as every shipped scene of the crate's rules has (a scanline of a
/// scene drawn on the reference path carries the memo too, and the deepest I32F32
/// stack on a 16 KB chip, the course's, would have almost nothing to spare with two).
const MEMO_LIGHTS: usize = 1;

/// What a fast-kernel scanline of a diffuse stage set keeps from pixel to pixel for its
/// lit plane hits ([`lit_plane_color`]; `Stages::Memo`): the material last shaded and,
/// for the first [`MEMO_LIGHTS`] lights, `emissivity × diffuse` per channel, the first
/// product of every term, the same for every hit that shows that material (bit
/// `3 × light + channel` of `overflow`: the product does not fit, the term saturates);
/// and the last still plane's hit.
#[derive(Debug, Clone)]
pub struct PlaneMemo<S> {
    /// The material (`None`: none yet).
    material: Option<u8>,
    overflow: u8,
    weights: [[S; 3]; MEMO_LIGHTS],
    /// The last still plane's hit (`fast::HitMemo`).
    hits: fast::HitMemo<S>,
    /// The quiet planes (`Primary::quiet_planes`) of the scanline it last looked at.
    quiet: Option<(u16, fast::Quiet<S>)>,
    /// The last plane shaded: its index and [`Facing`].
    facing: Option<(u8, Facing)>,
    /// Whether the scene's lights send every plane hit to the general shading (a light
    /// on a surface, a projector), once asked.
    general: Option<bool>,
    /// Whether the scanline's row has stepped its certified block's plane alone since
    /// its terms were last all up to date (`Primary::advance_one`): a pixel that needs
    /// the others refreshes them first (`Primary::refresh`, bit for bit what stepping
    /// them would have given, in the formats that step so: `Primary::steps_freely`).
    pub(crate) stale: bool,
    /// Whether the scanline steps its blocks' planes alone (until a restart, once a
    /// pixel has had to refresh its terms: a block of such pixels steps them all).
    pub(crate) lazy: bool,
}

impl<S: Scalar> Default for PlaneMemo<S> {
    fn default() -> Self {
        Self {
            material: None,
            overflow: 0,
            weights: [[S::ZERO; 3]; MEMO_LIGHTS],
            hits: fast::HitMemo::default(),
            quiet: None,
            facing: None,
            general: None,
            stale: false,
            lazy: true,
        }
    }
}

impl<S: Scalar> PlaneMemo<S> {
    /// The quiet planes of `r`'s scanline, looked for at its first lit plane hit.
    #[inline(always)]
    fn quiet(&mut self, scene: &SceneView<'_, S>, p: &Primary<S>, r: &Row<S>) -> fast::Quiet<S> {
        let row = Primary::row_index(r);
        match self.quiet {
            Some((k, q)) if k == row => q,
            _ => {
                let q = p.quiet_planes(scene, r);
                self.quiet = Some((row, q));
                q
            }
        }
    }

    /// The memo with the weights of material `index` (`material`), formed where it
    /// held another's: one per light of the first [`MEMO_LIGHTS`] ([`PlaneMemo::weight`]).
    #[inline(always)]
    fn weights(
        &mut self,
        scene: &SceneView<'_, S>,
        index: u8,
        material: &crate::Material<S>,
    ) -> &Self {
        if self.material != Some(index) {
            self.overflow = 0;
            for (j, (w, light)) in self.weights.iter_mut().zip(scene.lights).enumerate() {
                for (k, ((w, e), d)) in w
                    .iter_mut()
                    .zip(light.emissivity)
                    .zip(material.diffuse)
                    .enumerate()
                {
                    match e.checked_mul(d) {
                        Some(v) => *w = v,
                        None => self.overflow |= 1 << (3 * j + k),
                    }
                }
            }
            self.material = Some(index);
        }
        self
    }

    /// Light `j`'s weights for the material kept ([`PlaneMemo::weights`]), and their
    /// three overflow bits; `None` beyond the first [`MEMO_LIGHTS`].
    #[inline(always)]
    fn weight(&self, scene: &SceneView<'_, S>, j: usize) -> Option<([S; 3], u8)> {
        if j >= scene.lights.len() {
            return None;
        }
        let w = *self.weights.get(j)?;
        Some((w, (self.overflow >> (3 * j)) & 7))
    }
}

/// A stage set's room for a [`PlaneMemo`] (`Stages::Memo`): the memo itself, or `()`
/// where the set's plane hits take the general shading.
pub trait MemoSlot<S>: Default {
    /// The memo, if the set keeps one.
    fn memo(&mut self) -> Option<&mut PlaneMemo<S>>;
}

impl<S> MemoSlot<S> for () {
    #[inline(always)]
    fn memo(&mut self) -> Option<&mut PlaneMemo<S>> {
        None
    }
}

impl<S: Scalar> MemoSlot<S> for PlaneMemo<S> {
    #[inline(always)]
    fn memo(&mut self) -> Option<&mut PlaneMemo<S>> {
        Some(self)
    }
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

#[cfg(test)]
mod tests {
    extern crate std;
    use std::format;
    use std::string::String;
    use std::vec::Vec;

    use super::*;
    use crate::Scene;
    use crate::shade::stages::DiffuseShadows;

    /// A seeded random scene of planes only (plain and tiled, any normal: walls with
    /// `N.x ≠ 0` among them), sometimes lit.
    fn random_scene(mut next: impl FnMut() -> u64) -> String {
        // A whole number in `0..n`, and a real in `[lo, hi)`.
        let mut below = |n: u64| u32::try_from(next() % n).unwrap();
        let (w, h) = (16 + below(48), 8 + below(24));
        let mut uniform =
            |lo: f64, hi: f64| lo + (hi - lo) * f64::from(below(1 << 24)) / f64::from(1u32 << 24);
        let mut text = format!(
            "rules fixray\ncamera c {{ pixeldim {w} {h} worlddim 8 6 viewpoint {:.3} {:.3} {:.3} }}\n",
            uniform(0.0, 8.0),
            uniform(0.5, 5.5),
            uniform(2.0, 9.0)
        );
        // A coarse epsilon now and then: planes near parallel to the rays over wide bands,
        // where each pixel takes the exact test.
        if uniform(0.0, 1.0) < 0.3 {
            text.push_str(&format!("precision {:.3}\n", uniform(0.005, 0.2)));
        }
        text.push_str("material a { ambient 0.3 0.2 0.1 diffuse 0.5 0.4 0.3 }\n");
        text.push_str("material b { ambient 0.1 0.2 0.3 diffuse 0.2 0.6 0.3 }\n");
        if uniform(0.0, 1.0) < 0.7 {
            text.push_str(&format!(
                "light l {{ location {:.2} {:.2} {:.2} emissivity 5 5 5 }}\n",
                uniform(0.0, 8.0),
                uniform(1.0, 8.0),
                uniform(-8.0, 4.0)
            ));
        }
        let x = uniform(0.0, 4.0);
        let planes = 2 + u32::from(x >= 1.0) + u32::from(x >= 2.0) + u32::from(x >= 3.0);
        for i in 0..planes {
            let n = [uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0)];
            let p = [
                uniform(-4.0, 12.0),
                uniform(-3.0, 3.0),
                uniform(-16.0, -1.0),
            ];
            let r = uniform(0.0, 1.0);
            if i > 0 && r < 0.25 {
                // A twin of the first plane, turned by a hair: two planes whose `t'` cross
                // along whole rows, where only the roundings of `N·D` decide.
                let k = uniform(-0.002, 0.002);
                text.push_str(&format!(
                    "plane q{i} {{ material b normal {:.4} 1 {:.4} point 1 -1 -4 }}\n",
                    0.3 + k,
                    0.2 - k
                ));
                text.push_str(&format!(
                    "plane r{i} {{ material a normal 0.3 1 0.2 point 1 -1 -4 }}\n"
                ));
            } else if i == 0 && r < 0.5 {
                text.push_str("tiled_plane t { material a altmaterial b normal 0 1 0 point 0 -1 0 xdir 1 0 0 dimension 1 1 }\n");
            } else {
                text.push_str(&format!(
                    "plane p{i} {{ material {} normal {:.3} {:.3} {:.3} point {:.2} {:.2} {:.2} }}\n",
                    if i % 2 == 0 { "a" } else { "b" },
                    n[0], n[1], n[2], p[0], p[1], p[2]
                ));
            }
        }
        text
    }

    /// Every scanline of `scenes` random plane scenes in format `S`: the hits a scanline
    /// takes from certified blocks (stepping and restarting as `scanline` does) against
    /// `nearest` at every pixel (object, point, bound and `t'`, bit for bit), and the
    /// pixels of whole and partial scanlines with blocks and without. Returns the pixels
    /// the blocks answered.
    fn blocks_agree<S: Scalar>(scenes: usize) -> usize {
        let mut next = crate::num::xorshift(0x5EED_2026_1205);
        let mut blocked = 0;
        let mut guessed = 0;
        let mut parsed = 0;
        for case in 0..scenes {
            let text = random_scene(&mut next);
            let scene = match Scene::<S>::parse(&text) {
                Ok(scene) => scene,
                // Only a format's range may refuse a scene.
                Err(e) => {
                    assert!(
                        std::format!("{e}").contains("range") || !fast::blocks_for::<S>(),
                        "{e}\n{text}"
                    );
                    continue;
                }
            };
            parsed += 1;
            let view = scene.view();
            let Some(p) = Primary::new(&view) else {
                continue;
            };
            let plain = p.clone().without_blocks();
            let w = view.camera.width;
            for row in 0..view.camera.height {
                // The hits, as the scanline steps.
                let mut state: Option<Row<S>> = None;
                let mut block = fast::Block::default();
                for column in 0..w {
                    let stepped = match state.as_mut() {
                        Some(r) if column % fast::resync_pixels::<S>() != 0 => {
                            p.advance(r).is_some()
                        }
                        _ => {
                            block = fast::Block::default();
                            state = p.row(&view, row, column);
                            state.is_some()
                        }
                    };
                    if !stepped {
                        state = None;
                        continue;
                    }
                    let Some(r) = state.as_ref() else { continue };
                    let want = plain.nearest(&view, r).ok();
                    let got = match p.block_hit(&view, r, &block, None) {
                        Some(hit) => {
                            blocked += 1;
                            hit.ok()
                        }
                        None => {
                            let hit = p.nearest(&view, r).ok();
                            if column % fast::resync_pixels::<S>() == 0
                                && let Some(h) = &hit
                            {
                                // Any guess of the winner (as `scanline` guesses the last
                                // pixel's) is certified only where it is the answer.
                                let n = view.objects.len();
                                let mut certified = 0;
                                for guess in (0..n).map(Some).chain([None]) {
                                    let mut trial = fast::Block::default();
                                    p.start_block(r, guess, w - 1, &mut trial);
                                    if let Some(g) = p.block_hit(&view, r, &trial, None) {
                                        certified += 1;
                                        assert_eq!(g.ok(), want, "{} case {case}", S::NAME);
                                    }
                                }
                                assert!(certified <= 1, "{} case {case}", S::NAME);
                                guessed += certified;
                                p.start_block(r, h.as_ref().map(|h| h.index), w - 1, &mut block);
                            }
                            hit
                        }
                    };
                    assert_eq!(
                        got,
                        want,
                        "{} case {case} row {row} column {column}:\n{text}",
                        S::NAME
                    );
                }
                // The pixels, whole scanlines and one from the middle.
                for columns in [0..w, w / 3..w] {
                    let mut counters = Counters::default();
                    let with: Vec<Rgb888> = scanline::<S, DiffuseShadows, Rgb888>(
                        &view,
                        Some(&p),
                        row,
                        columns.clone(),
                        &mut counters,
                    )
                    .collect();
                    let without: Vec<Rgb888> = scanline::<S, DiffuseShadows, Rgb888>(
                        &view,
                        Some(&plain),
                        row,
                        columns,
                        &mut counters,
                    )
                    .collect();
                    assert_eq!(with, without, "{} case {case} row {row}:\n{text}", S::NAME);
                }
            }
        }
        assert!(
            parsed * 10 >= scenes * 9,
            "{parsed} of {scenes} scenes parsed"
        );
        // Guesses were certified (the right ones) wherever blocks were.
        assert_eq!(
            guessed > 0,
            blocked > 0,
            "{guessed} guesses, {blocked} pixels"
        );
        blocked
    }

    /// Every fast-kernel hit of `scenes` random plane scenes (and the default scene) in
    /// format `S`, lit by the stage set `T`: the hits found with a scanline's memo of its
    /// still planes (`fast::HitMemo`) are the hits, and [`lit_plane_color`]'s colour is
    /// the general shading's ([`fast_color`]) bit for bit wherever it draws one.
    /// Returns how many hits it drew.
    fn lit_planes_agree<S: Scalar, T: Stages>(scenes: usize) -> (usize, usize) {
        let mut next = crate::num::xorshift(0x5EED_2026_1206);
        let (mut drawn, mut quiet) = (0, 0);
        let texts = (0..scenes)
            .map(|_| random_scene(&mut next))
            .chain([String::from(include_str!("../../scenes/default.scene"))]);
        for (case, text) in texts.enumerate() {
            let Ok(scene) = Scene::<S>::parse(&text) else {
                continue;
            };
            // As a frame sets its view up (`render.rs`): a light on a surface is the
            // plan's to find.
            let mut view = scene.view();
            view.lights_on_surfaces = view.plan().lights_on_surfaces;
            let Some(p) = Primary::new(&view) else {
                continue;
            };
            let mut at_hit = heapless::Vec::new();
            // One memo for the whole frame, as a scanline keeps one for its pixels.
            let mut memo = PlaneMemo::default();
            let mut hits = fast::HitMemo::default();
            for row in 0..view.camera.height {
                let mut state: Option<Row<S>> = None;
                for column in 0..view.camera.width {
                    let stepped = match state.as_mut() {
                        Some(r) if column % fast::resync_pixels::<S>() != 0 => {
                            p.advance(r).is_some()
                        }
                        _ => {
                            state = p.row(&view, row, column);
                            state.is_some()
                        }
                    };
                    let Some(r) = state.as_ref().filter(|_| stepped) else {
                        state = None;
                        continue;
                    };
                    // The still planes' hits from the memo are the hits themselves.
                    let found = p.nearest(&view, r);
                    let memoized = p.nearest_with(&view, r, Some(&mut hits));
                    assert_eq!(found, memoized, "{} case {case} ({row}, {column})", S::NAME);
                    let Ok(Some(h)) = found else {
                        continue;
                    };
                    let (mut c1, mut c2) = (Counters::default(), Counters::default());
                    let at = (&mut at_hit, Some(&mut memo));
                    let mut lit_row = r.clone();
                    let lit = lit_plane_color::<S, T>(&view, &p, &mut lit_row, &h, at, &mut c1);
                    let general = fast_color::<S, T>(&view, Some(&p), r, &h, &mut at_hit, &mut c2);
                    if let Some(lit) = lit {
                        drawn += 1;
                        if T::SHADOWS && quiet_hit(&view, &p, r, &h, &mut memo) {
                            quiet += 1;
                        }
                        assert_eq!(
                            lit,
                            general,
                            "{} case {case} ({row}, {column}):\n{text}",
                            S::NAME
                        );
                    }
                }
            }
        }
        (drawn, quiet)
    }

    /// The fast kernel's flattened plane shading (`lit_plane_color`) draws the general
    /// shading's colours, with shadows and without, in the formats that take it.
    #[test]
    fn lit_planes_draw_the_general_shading() {
        use crate::shade::stages::Diffuse;
        // (Tens of thousands of hits each; with shadows, thousands of them where every
        // other plane is quiet.)
        let (drawn, quiet) = lit_planes_agree::<fixed::types::I16F16, DiffuseShadows>(60);
        assert!(drawn > 40_000 && quiet > 5_000, "{drawn} {quiet}");
        assert!(lit_planes_agree::<fixed::types::I16F16, Diffuse>(30).0 > 25_000);
        let (drawn, quiet) = lit_planes_agree::<fixed::types::I20F12, DiffuseShadows>(30);
        assert!(drawn > 25_000 && quiet > 2_000, "{drawn} {quiet}");
        let (drawn, quiet) = lit_planes_agree::<fixed::types::I32F32, DiffuseShadows>(20);
        assert!(drawn > 20_000 && quiet > 2_000, "{drawn} {quiet}");
        assert!(
            lit_planes_agree::<crate::num::variants::I16F16Recip, DiffuseShadows>(20).0 > 20_000
        );
        // Not in the float formats (the facing normal would not be the row's `N·D`).
        assert_eq!(lit_planes_agree::<f32, DiffuseShadows>(5).0, 0);
    }

    /// The certified blocks (`Primary::certify_block`) answer what a search of every pixel
    /// answers, in the formats that take them and in the others (which never do).
    #[test]
    fn certified_blocks_draw_what_every_pixel_searched_draws() {
        let blocked = blocks_agree::<fixed::types::I16F16>(150);
        // The blocks ran (tens of thousands of pixels over these scenes).
        assert!(blocked > 10_000, "{blocked} pixels in certified blocks");
        assert!(blocks_agree::<fixed::types::I20F12>(150) > 10_000);
        assert!(blocks_agree::<crate::num::variants::I16F16Recip>(60) > 1_000);
        assert_eq!(blocks_agree::<fixed::types::I32F32>(40), 0);
        assert_eq!(blocks_agree::<f32>(20), 0);
    }
}
