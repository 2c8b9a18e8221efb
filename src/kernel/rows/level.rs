//! A level-plane row's plane, found once for the row ([`level`]), and the colour of a
//! pixel on it ([`plane_color`]).

use super::super::fast::{FAST_OBJECTS, Primary, Row};
use super::super::scanline::reference_color;
use super::super::shading::{LightTerms, light_plane_hit, segment_tolerance, shadowed_among};
use super::lean::{row_ll, row_x};
use crate::shade::stages::Stages;
use crate::shade::{
    Incoming, PlaneSides, SideBits, channel_max, diffuse_falloff, shade_with, surface,
};
use crate::stats::{Counters, count};
use crate::{Color, Hit, Light, Scalar, SceneView, Shape, Tiling, Vec3};

/// What a scanline's nearest plane gives every pixel of the row.
#[derive(Debug, Clone)]
pub(super) struct Level<S: Scalar> {
    /// The object.
    pub(super) index: usize,
    /// Its parameter `t'` along `D` (the screen at 1).
    pub(super) t: S,
    /// `t'` as the fraction `p/q` (`q > 0`) the terms compare.
    pub(super) pq: (S, S),
    /// The hit's `y` and `z` (the same at every pixel).
    pub(super) y: S,
    pub(super) z: S,
    /// The plane's normal facing the ray.
    pub(super) facing: Vec3<S>,
    /// Every object's side at the hit (`Primary::sides_at`), for shadow segments; empty
    /// when not kept. With its bits ([`SideBits`]).
    pub(super) sides: heapless::Vec<S, FAST_OBJECTS>,
    pub(super) side_bits: SideBits,
    /// Per light (empty with more than [`ROW_LIGHTS`] lights): the objects that can stand between the
    /// row's hits and the light, as bits: the spheres, and the planes whose sides at the
    /// hit and at the light differ in sign (a plane with both on one side never crosses
    /// a segment, whatever the tolerance: `sides_differ`). Empty: every light takes the
    /// general test (`occludes_segment`).
    pub(super) occluders: heapless::Vec<u8, ROW_LIGHTS>,
    /// The plane's materials (its own, a tiled plane's alternate) and, per material and
    /// light (`material × ROW_LIGHTS + light`), `emissivity × diffuse` per channel: the
    /// first product of `term([emissivity, diffuse, falloff])`, once per row. Empty when
    /// the scene has more than [`ROW_LIGHTS`] lights.
    pub(super) materials: [u8; 2],
    pub(super) weights: heapless::Vec<[S; 3], { 2 * ROW_LIGHTS }>,
    /// Which of `weights` did not fit (bit `3 × entry + channel`): such a term saturates.
    pub(super) overflow: u16,
    /// Per light (empty with more than [`ROW_LIGHTS`] lights), what every hit of the row
    /// shares.
    pub(super) lights: heapless::Vec<RowLight<S>, ROW_LIGHTS>,
    /// A tiled plane's tile row, the same at every hit of the row
    /// ([`crate::PlaneFrame::tile_row`]; `None`: each pixel looks its tile up whole).
    pub(super) tile_row: Option<i32>,
}

/// A light's terms that are the same at every hit of a row (`N.x = 0` and the hits
/// share `y` and `z`): bit for bit what a pixel would compute.
#[derive(Debug, Clone)]
pub(super) struct RowLight<S: Scalar> {
    /// `(L.y, L.z)` of `L = light − hit` (`None`: they do not fit, no hit of the row is
    /// lit by this light).
    pub(super) l: Option<(S, S)>,
    /// `L.y² + L.z²`, unrounded (used in the fixed formats, whose sums are exact).
    pub(super) yz: Option<S::Acc>,
    /// `N·L` with the facing normal when positive (`None`: the light is behind the
    /// plane) and `255·N·L` (`None` when it does not fit: `diffuse_falloff` then divides
    /// first).
    pub(super) nl: Option<S>,
    pub(super) knl: Option<S>,
}

/// How many lights a row keeps per-row terms for (a scene with more lights shades every
/// light the general way).
pub(super) const ROW_LIGHTS: usize = 2;

/// What a scanline remembers from pixel to pixel: the last `2|D|∞` and the hit's
/// distance bound `t'·2|D|∞` it gave, and the last `(t, ulp)` key of the segments'
/// tolerance (`surface_tolerance` depends on nothing else) with its value. Along a row
/// `|D|∞` is mostly `|dz|` or `|dy|`, so both are products a pixel mostly skips.
#[derive(Debug, Clone, Copy)]
pub(super) struct Memo<S> {
    pub(super) bound: Option<(S, S)>,
    pub(super) tol: Option<(S, S, S)>,
}

impl<S> Default for Memo<S> {
    fn default() -> Self {
        Self {
            bound: None,
            tol: None,
        }
    }
}

/// The row's nearest plane and what every pixel of the row shares of its hit: the
/// object, `t'`, the hit's `y` and `z`, and the normal facing the ray; `Some(None)` when
/// no plane is accepted, `None` when the row cannot be decided once.
pub(super) fn row_plane<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    first: &Row<S>,
) -> Option<Option<RowPlane<S>>> {
    let Some((index, num, den)) = p.level_row(scene, first, scene.camera.width)? else {
        return Some(None);
    };
    // As `Primary::point`: t' = p/q, hit = eye + t'·D.
    let t = num.checked_div(den)?;
    let eye = scene.camera.viewpoint;
    let d = Primary::dir(first);
    let y = eye.y.checked_add(t.checked_mul(d.y)?)?;
    let z = eye.z.checked_add(t.checked_mul(d.z)?)?;
    let normal = scene
        .objects
        .get(index)?
        .shape
        .normal_at(Vec3::new(eye.x, y, z))?;
    // As `own_color`: `D·N` has no `D.x` term (`N.x = 0`), the same at every pixel.
    let facing = if d.dot_axis(normal).is_some_and(|v| v > S::ZERO) {
        normal.checked_neg().unwrap_or(normal)
    } else {
        normal
    };
    Some(Some(RowPlane {
        index,
        pq: (num, den),
        t,
        y,
        z,
        facing,
    }))
}

/// What [`row_plane`] found: the object, `t'`, the hit's `y` and `z`, the facing normal.
pub(super) struct RowPlane<S> {
    pub(super) index: usize,
    /// `t'` as the fraction `p/q` (`q > 0`) the terms compare.
    pub(super) pq: (S, S),
    pub(super) t: S,
    pub(super) y: S,
    pub(super) z: S,
    pub(super) facing: Vec3<S>,
}

/// The row's plane, worked out once: `Some(None)` when no plane is accepted, `None` when
/// the fast kernel must decide the row pixel by pixel.
pub(super) fn level<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    first: &Row<S>,
) -> Option<Option<Level<S>>> {
    let Some(RowPlane {
        index,
        pq,
        t,
        y,
        z,
        facing,
    }) = row_plane(scene, p, first)?
    else {
        return Some(None);
    };
    let (sides, side_bits, occluders) = row_sides::<S, T>(scene, p, first, (t, y, z))?;
    let object = scene.objects.get(index)?;
    let materials = match object.shape {
        Shape::Tiled { alt, .. } => [object.material, alt],
        _ => [object.material, object.material],
    };
    let (weights, overflow) = row_weights(scene, materials);
    let row_lights = row_lights(scene, (y, z), facing);
    let tile_row = match object.shape {
        Shape::Tiled {
            frame,
            tiling: Tiling::Frame,
            ..
        } => frame.tile_row(y, z),
        _ => None,
    };
    Some(Some(Level {
        tile_row,
        index,
        pq,
        t,
        y,
        z,
        facing,
        sides,
        side_bits,
        occluders,
        materials,
        weights,
        overflow,
        lights: row_lights,
    }))
}

/// Every object's side at a row's hit (`t'`, the hit's `y` and `z`) with their bits,
/// and the row's occluders per light ([`Level::sides`], [`Level::occluders`]).
#[allow(clippy::type_complexity)]
#[inline(always)]
fn row_sides<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    first: &Row<S>,
    (t, y, z): (S, S, S),
) -> Option<(
    heapless::Vec<S, FAST_OBJECTS>,
    SideBits,
    heapless::Vec<u8, ROW_LIGHTS>,
)> {
    let mut sides = heapless::Vec::new();
    let mut side_bits = SideBits::default();
    if T::SHADOWS && !p.at_lights().is_empty() {
        match p.sides_at(first, t, &mut sides) {
            Some(bits) => side_bits = bits,
            None => sides.clear(),
        }
    }
    let occluders = row_occluders(scene, p, &sides, (y, z))?;
    Some((sides, side_bits, occluders))
}

/// What a row's plane tells of its shadows ([`super::changes`]): `t'`, the hit's `y`
/// and `z`, and the occluders per light, as [`level`] finds them (the same
/// operations), without the row's colour terms. `Some(None)` when no plane is
/// accepted, `None` when the row cannot be decided once.
pub(super) struct RowShadows<S> {
    pub(super) t: S,
    pub(super) y: S,
    pub(super) z: S,
    pub(super) occluders: heapless::Vec<u8, ROW_LIGHTS>,
}

/// [`RowShadows`] of the row started at `first`.
pub(super) fn row_shadows<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    first: &Row<S>,
) -> Option<Option<RowShadows<S>>> {
    let Some(RowPlane { t, y, z, .. }) = row_plane(scene, p, first)? else {
        return Some(None);
    };
    let (_, _, occluders) = row_sides::<S, T>(scene, p, first, (t, y, z))?;
    Some(Some(RowShadows { t, y, z, occluders }))
}

/// Per light (none with more than [`ROW_LIGHTS`] lights or without every side), the
/// objects that can stand between the row's hits (on the line `(x, y, z)`, every `x`)
/// and the light, as bits ([`Level::occluders`]).
#[inline(always)]
fn row_occluders<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    sides: &[S],
    (y, z): (S, S),
) -> Option<heapless::Vec<u8, ROW_LIGHTS>> {
    let lights = scene.lights.len();
    let mut occluders = heapless::Vec::new();
    let n = sides.len();
    if n != scene.objects.len() || lights > ROW_LIGHTS {
        return Some(occluders);
    }
    for j in 0..lights {
        let at_light = p.at_lights().get(j * n..)?.get(..n)?;
        let mut bits = 0u8;
        // The row's hits lie on the line (x, y, z) for every x: its offsets from the
        // light in y and z.
        let light = scene.lights.get(j)?.location;
        let (wy, wz) = (y.checked_sub(light.y), z.checked_sub(light.z));
        for (i, ((o, &a0), &a1)) in scene.objects.iter().zip(sides).zip(at_light).enumerate() {
            let may = match o.shape {
                Shape::Sphere(_) => !cone_clears_row(p, (j, i), (wy, wz)),
                _ => (a0 > S::ZERO) != (a1 > S::ZERO),
            };
            if may {
                bits |= 1 << i;
            }
        }
        let _ = occluders.push(bits);
    }
    Some(occluders)
}

/// Whether a shadow cone of object `i` (a sphere) from light `j` misses the whole row
/// (`crate::geometry::ShadowCone::clears_line`): the row's hits on the line `(x, y, z)`,
/// every `x`, offset `(wy, wz)` from the light in `y` and `z` (`None`: out of the
/// format). Such a sphere is left out of the row's occluders of the light.
#[inline(always)]
pub(super) fn cone_clears_row<S: Scalar>(
    p: &Primary<S>,
    (j, i): (usize, usize),
    (wy, wz): (Option<S>, Option<S>),
) -> bool {
    p.cones().iter().any(|c| {
        usize::from(c.light) == j
            && usize::from(c.object) == i
            && matches!((wy, wz), (Some(wy), Some(wz)) if c.clears_line(wy, wz))
    })
}

/// Per material of the row's plane (`materials`: its own, a tiled plane's alternate)
/// and light, `emissivity × diffuse` per channel, and which did not fit (bit
/// `3 × entry + channel`) ([`Level::weights`]); none with more than [`ROW_LIGHTS`]
/// lights.
#[inline(always)]
fn row_weights<S: Scalar>(
    scene: &SceneView<'_, S>,
    materials: [u8; 2],
) -> (heapless::Vec<[S; 3], { 2 * ROW_LIGHTS }>, u16) {
    let mut weights = heapless::Vec::new();
    let mut overflow = 0u16;
    if scene.lights.len() > ROW_LIGHTS {
        return (weights, overflow);
    }
    for m in materials {
        let diffuse = scene.materials.get(usize::from(m)).map(|m| m.diffuse);
        for j in 0..ROW_LIGHTS {
            let mut w = [S::ZERO; 3];
            for (c, slot) in w.iter_mut().enumerate() {
                let e = scene.lights.get(j).map(|l| l.emissivity[c]);
                match e.zip(diffuse).and_then(|(e, d)| e.checked_mul(d[c])) {
                    Some(v) => *slot = v,
                    None => overflow |= 1 << (3 * weights.len() + c),
                }
            }
            let _ = weights.push(w);
        }
    }
    (weights, overflow)
}

/// Each light's terms shared by every hit of the row (its `y` and `z`, the normal
/// `facing` the ray): [`RowLight`]; none with more than [`ROW_LIGHTS`] lights.
#[inline(always)]
fn row_lights<S: Scalar>(
    scene: &SceneView<'_, S>,
    (y, z): (S, S),
    facing: Vec3<S>,
) -> heapless::Vec<RowLight<S>, ROW_LIGHTS> {
    let mut row_lights = heapless::Vec::new();
    if scene.lights.len() > ROW_LIGHTS {
        return row_lights;
    }
    for light in scene.lights {
        let l = light
            .location
            .y
            .checked_sub(y)
            .zip(light.location.z.checked_sub(z));
        let yz = l.and_then(|(ly, lz)| S::acc_add(S::acc_mul(ly, ly)?, S::acc_mul(lz, lz)?));
        // `L·N` has no `L.x` term (`N.x = 0`): any `L.x` gives the row's value.
        let nl = l
            .and_then(|(ly, lz)| Vec3::new(S::ZERO, ly, lz).dot_axis(facing))
            .filter(|c| *c > S::ZERO);
        let knl = nl.and_then(|nl| nl.checked_mul(channel_max::<S>()));
        let _ = row_lights.push(RowLight { l, yz, nl, knl });
    }
    row_lights
}

/// The colour of the row's plane at the row's current pixel (the background without
/// one): its hit's `x`, tile and lights. A pixel whose quantity leaves the format is the
/// fast kernel's (the reference path), a light whose `|L|²` does not fit the general
/// shading's.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(super) fn plane_color<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    state: &Row<S>,
    level: Option<&Level<S>>,
    memo: &mut Memo<S>,
    y: Option<S>,
    column: u16,
    counters: &mut Counters,
) -> Color<S> {
    let Some(l) = level else {
        return scene.background;
    };
    let d = Primary::dir(state);
    let eye = scene.camera.viewpoint;
    // As `Primary::point`: the hit, and the bound t'·2|D|∞ on its world distance.
    let hit = row_x(scene, l, d.x)
        .map(|x| Vec3::new(x, l.y, l.z))
        .and_then(|point| {
            let t_bound = hit_bound(l, d, memo)?;
            Some(Hit { t: t_bound, point })
        });
    let Some(hit) = hit else {
        return reference_color::<S, T>(scene, y, column, counters);
    };
    let sides = (!l.sides.is_empty()).then(|| PlaneSides {
        at_hit: &l.sides,
        at_lights: p.at_lights(),
        cones: p.cones(),
        bits: l.side_bits,
    });
    match lit::<S, T>(scene, l, &hit, sides, memo, counters) {
        Some(c) => c,
        None => {
            let incoming = Incoming {
                base: eye,
                dir: d,
                unit: false,
                sides,
            };
            shade_with::<S, T>(scene, &incoming, l.index, &hit, counters)
        }
    }
}

/// The crate's shading of a plane hit for a diffuse stage set (`own_color`, `light_with`
/// and `segment_terms` of `shade/`, for what this kernel's scenes have: no glint, cone,
/// projector, mirror or light on a surface), with the row's facing normal, sides,
/// occluders and weights. `None` where a light takes the general path (its `|L|²` or the
/// segments' tolerance does not fit the format): the caller then shades the pixel the
/// general way.
#[inline]
pub(super) fn lit<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    l: &Level<S>,
    hit: &Hit<S>,
    sides: Option<PlaneSides<'_, S>>,
    memo: &mut Memo<S>,
    counters: &mut Counters,
) -> Option<Color<S>> {
    let object = scene.objects.get(l.index)?;
    let m = row_material(object, l.tile_row, hit.point);
    if l.tile_row.is_some() && matches!(object.shape, Shape::Tiled { .. }) {
        count(&mut counters.tile_lookups);
    }
    let material = match m {
        Some(m) => scene.materials.get(usize::from(m)).copied(),
        None => surface(scene, l.index, hit.point, counters).map(|(_, m)| m),
    };
    let Some(material) = material else {
        return Some([S::ZERO; 3]);
    };
    if material.diffuse == [S::ZERO; 3] {
        return Some(material.ambient);
    }
    let eye = scene.camera.viewpoint;
    let tol = if T::SHADOWS {
        segment_tolerance(eye, hit.point, hit.t, Some(&mut memo.tol))?
    } else {
        S::ZERO
    };
    // The per-row weights of the material shown (`usize::MAX`: not kept).
    let slot = m.map_or(usize::MAX, |m| {
        usize::from(m != l.materials[0]) * ROW_LIGHTS
    });
    let terms = |j: usize, light: &Light<S>| match l.lights.get(j) {
        // The row's terms of this light: `L.y`, `L.z`, `N·L` and `255·N·L`, and in
        // the fixed formats `L.y² + L.z²`, so that `|L|²` takes one product.
        Some(rl) => {
            let (Some(lx), Some((ly, lz))) = (light.location.x.checked_sub(hit.point.x), rl.l)
            else {
                return Some(None);
            };
            let to_light = Vec3::new(lx, ly, lz);
            let ll = match rl.yz {
                Some(yz) if S::EXACT_SUMS => row_ll(lx, yz),
                _ => to_light.dot(to_light),
            };
            let ll = ll.filter(|ll| *ll > S::ZERO)?;
            Some(rl.nl.map(|nl| LightTerms {
                to_light,
                ll,
                nl,
                knl: rl.knl,
            }))
        }
        None => {
            let Some(to_light) = light.location.diff(hit.point) else {
                return Some(None);
            };
            let ll = to_light.dot(to_light).filter(|ll| *ll > S::ZERO)?;
            let nl = to_light.dot_axis(l.facing).filter(|c| *c > S::ZERO);
            Some(nl.map(|nl| LightTerms {
                to_light,
                ll,
                nl,
                knl: nl.checked_mul(channel_max::<S>()),
            }))
        }
    };
    // The row's occluders of the light (`Level::occluders`), where it keeps them.
    let shadowed = |j: usize, light: &Light<S>, t: &LightTerms<S>| {
        let candidates = sides.and(l.occluders.get(j).copied());
        let segment = (hit.point, t.to_light, t.ll);
        shadowed_among(scene, sides, candidates, (j, light), segment, || Some(tol))
    };
    let weight = |j: usize| {
        let e = slot.saturating_add(j);
        Some((*l.weights.get(e)?, l.overflow >> (3 * e)))
    };
    let diffuse = material.diffuse;
    light_plane_hit(
        scene,
        material.ambient,
        diffuse,
        T::SHADOWS,
        (terms, shadowed, weight, |t: &LightTerms<S>| {
            diffuse_falloff(t.nl, t.knl, t.ll)
        }),
        counters,
    )
}

/// The material of the row's plane at `point`: a tiled plane's by its tile (the row's
/// tile row `j` and the point's column), a plane's own; `None` for any other tiling (the
/// general lookup, `surface`, whose material index this kernel does not see: its per-row
/// weights are then not used).
#[inline(always)]
pub(super) fn row_material<S: Scalar>(
    object: &crate::Object<S>,
    tile_row: Option<i32>,
    point: Vec3<S>,
) -> Option<u8> {
    match (object.shape, tile_row) {
        (Shape::Tiled { frame, alt, .. }, Some(j)) => {
            if frame.odd_tile_in_row(point, j) == Some(true) {
                Some(alt)
            } else {
                Some(object.material)
            }
        }
        (Shape::Plane(_), _) => Some(object.material),
        _ => None,
    }
}

/// As `Primary::point`: the bound `t'·2|D|∞` on the hit's world distance, remembered
/// for the last `2|D|∞` (`None`: it does not fit).
#[inline(always)]
pub(super) fn hit_bound<S: Scalar>(l: &Level<S>, d: Vec3<S>, memo: &mut Memo<S>) -> Option<S> {
    let twice = d.max_abs().checked_add(d.max_abs())?;
    match memo.bound {
        Some((k, b)) if k == twice => Some(b),
        _ => {
            let b = l.t.checked_mul(twice)?;
            memo.bound = Some((twice, b));
            Some(b)
        }
    }
}
