//! The fast shading of a lit plane hit, written once: the crate's shading (`own_color`,
//! `light_with` and `segment_terms` of `shade/`) flattened to what a lit plane hit of a
//! diffuse stage set needs, the same operations in the same order, so the same colour
//! bit for bit ([`light_plane_hit`], its shadow test [`shadowed_among`], its
//! [`segment_tolerance`] and [`add_weighted`]); every kernel that shades plane hits
//! takes it: the fast kernel's per-pixel scanline here ([`lit_plane_color`]), the
//! level-plane kernel's rows with their per-row terms (`rows/level.rs`, and its lean
//! rows' terms, `rows/lean.rs`).

use super::fast::{self, Primary, Row};
use super::memo::{Facing, PlaneMemo};
use crate::geometry::{surface_tolerance, surface_tolerance_fits};
use crate::shade::color::{add_sat, term};
use crate::shade::stages::Stages;
use crate::shade::{
    PlaneSides, channel_max, diffuse_falloff_outlined, material_at, occluded_among,
    occludes_segment,
};
use crate::stats::{Counters, count};
use crate::{Beam, Color, Light, Scalar, SceneView, Shape, Vec3};

mod sphere;
pub(super) use sphere::lit_sphere_color;
#[cfg(test)]
pub(super) use sphere::own_sphere_clear;

/// Whether [`lit_plane_color`] draws the fast kernel's plane hits with the stage set `T`
/// in format `S` (in a build with the kernels: without them its code is not linked):
/// diffuse lights (with or without shadows: no glint, cone, mirror or
/// translucence), in a format whose products are exact (the hit's facing normal is then
/// read off the row's `N·D`, which is the shading's `D·N` itself).
pub(super) const fn lit_planes<S: Scalar, T: Stages>() -> bool {
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
/// in the same order, so the same colour bit for bit (tested against `fast_color`'s
/// general shading), without building the general case's light loop state. The normal
/// facing the ray is the plane's, turned by the sign of the row's `N·D`. `None` where the
/// pixel needs the general shading: another shape, a light on a surface, a projector,
/// a light whose `|L|²` does not fit or is not positive (the general path's ray terms;
/// the statistics then count the earlier lights twice, as the level-plane kernel's do),
/// or a segments' tolerance that does not fit.
#[inline(always)]
pub(super) fn lit_plane_color<S: Scalar, T: Stages>(
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
        segment_tolerance(scene.camera.viewpoint, h.point, h.t_bound, None)?;
    }
    // As `surface` (no texture: a plain or tiled plane), with the material's index.
    let index = match object.shape {
        Shape::Plane(_) => object.material,
        _ => material_at(object, h.point, scene.rules(), counters),
    };
    let Some(material) = scene.materials.get(usize::from(index)) else {
        return Some([S::ZERO; 3]);
    };
    let color = material.ambient;
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
    // to date first (`fast::Stepping`).
    if set_shadows
        && !quiet
        && let Some(m) = memo.as_deref_mut()
    {
        p.catch_up(scene, r, &mut m.stepping)?;
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
    let weights = memo.map(|m| m.weights.of(scene, index, material));
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
    let terms = |_: usize, light: &Light<S>| {
        let Some(to_light) = light.location.diff(h.point) else {
            return Some(None);
        };
        let ll = to_light.dot(to_light).filter(|ll| *ll > S::ZERO)?;
        // (`dot_axis`, with the plane's axis looked up once.)
        let nl = match axis {
            Some(along) => to_light.along(along),
            None => to_light.dot(turned(turn)),
        };
        Some(nl.filter(|c| *c > S::ZERO).map(|nl| LightTerms {
            to_light,
            ll,
            nl,
            knl: None,
        }))
    };
    let shadowed = |j: usize, light: &Light<S>, t: &LightTerms<S>| {
        // (A quiet hit's segments cannot be stopped: `quiet_hit`.)
        if quiet {
            return Some(false);
        }
        shadowed_but_own(scene, sides, h, (j, light), t)
    };
    let weight = |j: usize| {
        let (w, overflow) = weights.and_then(|m| m.weight(scene, j))?;
        Some((w, u16::from(overflow)))
    };
    let diffuse = material.diffuse;
    light_plane_hit(
        scene,
        color,
        diffuse,
        shadows,
        (terms, shadowed, weight, |t: &LightTerms<S>| {
            diffuse_falloff_outlined(t.nl, t.nl.checked_mul(k), t.ll)
        }),
        counters,
    )
}

/// The segments' tolerance at a hit (`Fixray::segment_tolerance`: `surface_tolerance(t,
/// m)`, `(t + c)·ulp(max(1, t, m))` with `m` the largest coordinate of the eye and the
/// hit), remembered in `memo` for the last `(t, ulp)` where the caller keeps one
/// (`surface_tolerance` depends on nothing else). `None`: it does not fit.
#[inline(always)]
pub(super) fn segment_tolerance<S: Scalar>(
    eye: Vec3<S>,
    point: Vec3<S>,
    t: S,
    memo: Option<&mut Option<(S, S, S)>>,
) -> Option<S> {
    let m = eye.max_abs().max(point.max_abs());
    let Some(memo) = memo else {
        return surface_tolerance(t, m);
    };
    let ulp = S::ONE.max(t).max(m).ulp();
    match *memo {
        Some((k, u, tol)) if k == t && u == ulp => Some(tol),
        _ => {
            let tol = surface_tolerance(t, m)?;
            *memo = Some((t, ulp, tol));
            Some(tol)
        }
    }
}

/// Whether the shadow segment from a plane hit towards light `j` (`(point, L, |L|²)`)
/// is stopped, as `occludes_segment` decides. `candidates`: the objects that may stand
/// between (as bits, `occluded_among`), where the caller knows them from the planes'
/// sides (`sides`, every object's); otherwise, or where the sides do not cover every
/// object, every object is tested (`occludes_segment`). The segments' tolerance `tol`
/// is formed only where a segment is tested (`None` where it does not fit: the caller
/// then shades the pixel the general way).
#[inline(always)]
pub(super) fn shadowed_among<S: Scalar>(
    scene: &SceneView<'_, S>,
    sides: Option<PlaneSides<'_, S>>,
    candidates: Option<u8>,
    (j, light): (usize, &Light<S>),
    (point, to_light, ll): (Vec3<S>, Vec3<S>, S),
    tol: impl Fn() -> Option<S>,
) -> Option<bool> {
    let shadowed = match (sides, candidates) {
        (Some(s), Some(bits)) if s.at_hit.len() == scene.objects.len() => {
            if bits == 0 {
                Some(false)
            } else {
                occluded_among(scene, s, j, bits, (point, to_light, ll, tol()?), |_| false)
            }
        }
        _ => None,
    };
    Some(match shadowed {
        Some(v) => v,
        None => {
            let sides = sides.map(|s| (s, j));
            occludes_segment(scene, sides, point, to_light, ll, tol()?, light.location)
        }
    })
}

/// One light's terms at a lit plane hit, as the shading forms them: `L = light − hit`,
/// `|L|²` (positive), `N·L` with the normal facing the ray (positive) and, where the
/// caller forms it with the others, `255·N·L` (read by the caller's `knl`; `None` where
/// it does not fit, and `diffuse_falloff` divides first).
#[derive(Debug, Clone, Copy)]
pub(super) struct LightTerms<S> {
    pub(super) to_light: Vec3<S>,
    pub(super) ll: S,
    pub(super) nl: S,
    pub(super) knl: Option<S>,
}

/// The diffuse lights added to a plane hit's colour `color` (its ambient colour): the
/// crate's light loop (`light_with` of `shade/`) for what a lit plane hit of a diffuse
/// stage set has (no glint, cone or projector), the same operations in the same order,
/// so the same colour bit for bit. What differs between the kernels is where a light's
/// terms come from, and which objects its shadow test looks at, given as
/// `(terms, shadowed, weight)`:
/// - `terms(j, light)`: light `j`'s [`LightTerms`]; `Some(None)` where the light adds
///   nothing (`L` does not fit, or the light is behind the plane); `None` where the
///   pixel takes the general shading (`|L|²` does not fit or is not positive: the
///   statistics then count the earlier lights twice, in every kernel alike);
/// - `shadowed(j, light, terms)`: whether the light is stopped (asked only where
///   `shadows`; `None`: the general shading);
/// - `weight(j)`: the light's `emissivity × diffuse` per channel kept for the material
///   shown, with its overflow bits ([`add_weighted`]), if the caller keeps it;
/// - `falloff(terms)`: the light's `diffuse_falloff`, `255·(N·L)/|L|²`, formed once
///   the light is known to reach the hit (with the `255·N·L` the caller's `terms` kept,
///   or formed then).
///
/// `diffuse`: the material's diffuse colour.
#[inline(always)]
pub(super) fn light_plane_hit<S: Scalar>(
    scene: &SceneView<'_, S>,
    mut color: Color<S>,
    diffuse: [S; 3],
    shadows: bool,
    (mut terms, mut shadowed, weight, falloff): (
        impl FnMut(usize, &Light<S>) -> Option<Option<LightTerms<S>>>,
        impl FnMut(usize, &Light<S>, &LightTerms<S>) -> Option<bool>,
        impl Fn(usize) -> Option<([S; 3], u16)>,
        impl Fn(&LightTerms<S>) -> S,
    ),
    counters: &mut Counters,
) -> Option<Color<S>> {
    for (j, light) in scene.lights.iter().enumerate() {
        let Some(t) = terms(j, light)? else {
            continue;
        };
        if shadows {
            count(&mut counters.shadow_rays);
            if shadowed(j, light, &t)? {
                continue;
            }
        }
        let falloff = falloff(&t);
        count(&mut counters.diffuse);
        color = match weight(j) {
            Some((w, overflow)) => add_weighted(color, w, overflow, falloff),
            None => {
                let mut c = color;
                for ((c, diffuse), emissivity) in c.iter_mut().zip(diffuse).zip(light.emissivity) {
                    *c = add_sat(*c, term([emissivity, diffuse, falloff]));
                }
                c
            }
        };
    }
    Some(color)
}

/// `color + w·falloff` per channel, saturating: a light's term with the kept
/// `emissivity × diffuse` weights `w`, `term([e, d, falloff])` of the light loop
/// (`overflow`: the weights' three overflow bits; a weight that did not fit saturates
/// its channel, as `term` does where `e·d` overflows).
#[inline(always)]
pub(super) fn add_weighted<S: Scalar>(
    color: Color<S>,
    w: [S; 3],
    overflow: u16,
    falloff: S,
) -> Color<S> {
    /// One channel (`saturated`: its weight did not fit).
    #[inline(always)]
    fn add<S: Scalar>(c: S, w: S, falloff: S, saturated: bool) -> S {
        let t = if saturated {
            None
        } else {
            w.checked_mul(falloff)
        };
        add_sat(c, t.unwrap_or(S::MAX))
    }
    [
        add(color[0], w[0], falloff, overflow & 1 != 0),
        add(color[1], w[1], falloff, overflow & 2 != 0),
        add(color[2], w[2], falloff, overflow & 4 != 0),
    ]
}

/// Whether the shadow segment from the fast kernel's hit `h` towards light `j` is stopped
/// ([`shadowed_among`]), its own object left out. The objects that may stand between the
/// hit and the light are the ones `occludes_segment` picks, less the hit's own object
/// where it cannot stop the segment: a plane hit's own plane where quotients are exact
/// (its side at the hit is `num − t'·(N·D)` with `t'` within a DELTA of `num/(N·D)`, so
/// it lies within `(|N·D| + 1)·DELTA` of zero, inside the tolerance
/// `(t'·2|D|∞ + 12)·DELTA` (`t' ≥ 1`, `|N·D| ≤ √3|D|∞`), and `sides_differ` passes it
/// over), a sphere hit's own sphere where its caller's certificate says so
/// ([`own_sphere_clear`]; the fixed formats, whose quotients are exact). Out of line:
/// the plane pixels that take it are few (the others are quiet, `quiet_hit`), and the
/// sphere hits' shading calls it rather than holding a copy (flash).
#[inline(never)]
fn shadowed_but_own<S: Scalar>(
    scene: &SceneView<'_, S>,
    sides: Option<PlaneSides<'_, S>>,
    h: &fast::FastHit<S>,
    (j, light): (usize, &Light<S>),
    t: &LightTerms<S>,
) -> Option<bool> {
    let candidates = match sides {
        Some(s) if S::EXACT_QUOTIENTS => Some(s.bits.candidates(j) & !object_bit(h.index)),
        _ => None,
    };
    let eye = scene.camera.viewpoint;
    let tol = || segment_tolerance(eye, h.point, h.t_bound, None);
    let segment = (h.point, t.to_light, t.ll);
    shadowed_among(scene, sides, candidates, (j, light), segment, tol)
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
pub(super) fn quiet_hit<S: Scalar>(
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
