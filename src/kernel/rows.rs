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
//! ([`Primary::level_row`], [`level`]); a pixel computes its hit's `x` (one product) and
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

use embedded_graphics_core::pixelcolor::Rgb888;

use super::fast::{self, FAST_OBJECTS, FastHit, Primary, Row};
use super::reference::{fast_color, reference_color};
use crate::geometry::{RowCone, RowTiles, surface_tolerance};
use crate::shade::color::{add_sat, term, to_pixel};
use crate::shade::stages::Stages;
use crate::shade::{
    Incoming, PlaneSides, SideBits, channel_max, diffuse_falloff, occluded_among, occludes_segment,
    shade_with, surface,
};
use crate::stats::{Counters, count};
use crate::{Color, Hit, Rules, Scalar, SceneView, Shape, Tiling, Vec3};

/// The per-frame part: the fast kernel's (its terms, the lights' sides of every plane,
/// the spheres' rows and shadow cones).
#[derive(Debug, Clone)]
pub(crate) struct Rows<S: Scalar> {
    pub(crate) primary: Primary<S>,
}

/// What a scanline's nearest plane gives every pixel of the row.
#[derive(Debug, Clone)]
struct Level<S: Scalar> {
    /// The object.
    index: usize,
    /// Its parameter `t'` along `D` (the screen at 1).
    t: S,
    /// The hit's `y` and `z` (the same at every pixel).
    y: S,
    z: S,
    /// The plane's normal facing the ray.
    facing: Vec3<S>,
    /// Every object's side at the hit (`Primary::sides_at`), for shadow segments; empty
    /// when not kept. With its bits ([`SideBits`]).
    sides: heapless::Vec<S, FAST_OBJECTS>,
    side_bits: SideBits,
    /// Per light (empty with more than [`ROW_LIGHTS`] lights): the objects that can stand between the
    /// row's hits and the light, as bits: the spheres, and the planes whose sides at the
    /// hit and at the light differ in sign (a plane with both on one side never crosses
    /// a segment, whatever the tolerance: `sides_differ`). Empty: every light takes the
    /// general test (`occludes_segment`).
    occluders: heapless::Vec<u8, ROW_LIGHTS>,
    /// The plane's materials (its own, a tiled plane's alternate) and, per material and
    /// light (`material × ROW_LIGHTS + light`), `emissivity × diffuse` per channel: the
    /// first product of `term([emissivity, diffuse, falloff])`, once per row. Empty when
    /// the scene has more than [`ROW_LIGHTS`] lights.
    materials: [u8; 2],
    weights: heapless::Vec<[S; 3], { 2 * ROW_LIGHTS }>,
    /// Which of `weights` did not fit (bit `3 × entry + channel`): such a term saturates.
    overflow: u16,
    /// Per light (empty with more than [`ROW_LIGHTS`] lights), what every hit of the row
    /// shares.
    lights: heapless::Vec<RowLight<S>, ROW_LIGHTS>,
    /// A tiled plane's tile row, the same at every hit of the row
    /// ([`crate::PlaneFrame::tile_row`]; `None`: each pixel looks its tile up whole).
    tile_row: Option<i32>,
}

/// A lean row's per-row part ([`lean_row`]): what [`lean_color`] would otherwise look up
/// or check at each pixel. Built in place, in the scanline's [`Pixels`], at the row's
/// first pixel that needs it (an I32F32 scanline on a 16 KB chip has no room for copies).
#[derive(Debug, Clone)]
struct LeanRow<S: Scalar> {
    /// A tiled plane's checkerboard along the row (`None`: a plain plane).
    tiles: Option<RowTiles<S>>,
    /// Per tile parity (0: the plane's own material, 1: a tiled plane's odd tiles): the
    /// ambient colour and whether the diffuse colour is not black (the weights per
    /// parity are each light's, [`LeanLight`]).
    ambient: [Color<S>; 2],
    lit: [bool; 2],
    /// Per light, everything its term needs.
    lights: heapless::Vec<LeanLight<S>, ROW_LIGHTS>,
    /// The shadow cones of the spheres that can shadow the row, light by light
    /// ([`LeanLight::cones`]).
    cones: heapless::Vec<RowCone<S>, { fast::MAX_CONES }>,
    /// Half the format's range: a pixel's `|L.x|` beyond takes [`plane_color`]
    /// ([`RowCone::clears`]).
    half: S,
    /// Whether quick runs may draw the row ([`Pixels::quick_run`]): one light, with a
    /// quick term and a lit material for every tile parity the row shows (else each
    /// pixel would try one and fall back).
    runs: bool,
}

/// One light of a lean row: [`RowLight`]'s terms, the light's `x`, its weights per tile
/// parity (with their overflow bits) and where in [`LeanRow::cones`] the shadow cones of
/// the spheres that can shadow the row from it are (each must clear the pixel).
#[derive(Debug, Clone)]
struct LeanLight<S: Scalar> {
    x: S,
    /// `L.y² + L.z²` (`None`: `L.y`, `L.z` do not fit, no hit of the row is lit).
    yz: Option<S::Acc>,
    nl: Option<S>,
    knl: Option<S>,
    weights: [[S; 3]; 2],
    overflow: [u16; 2],
    /// Per tile parity, the quick term (`KernelArith::quick_term`): the numerators
    /// `weights × knl` per channel and the slack `(⌊w_max⌋ + 3)·DELTA`, what the exact
    /// term's truncations can add to the quick quotients' bound ([`lean_color`]); `None`
    /// where `knl` is not known, that parity's weights are negative or overflow, the
    /// products do not fit or are all zero, or the format has no quick pixel.
    quick: [Option<S::QuickTerm>; 2],
    /// The light's cones: `cones.0..cones.1` in [`LeanRow::cones`].
    cones: (u8, u8),
}

/// A light's terms that are the same at every hit of a row (`N.x = 0` and the hits
/// share `y` and `z`): bit for bit what a pixel would compute.
#[derive(Debug, Clone)]
struct RowLight<S: Scalar> {
    /// `(L.y, L.z)` of `L = light − hit` (`None`: they do not fit, no hit of the row is
    /// lit by this light).
    l: Option<(S, S)>,
    /// `L.y² + L.z²`, unrounded (used in the fixed formats, whose sums are exact).
    yz: Option<S::Acc>,
    /// `N·L` with the facing normal when positive (`None`: the light is behind the
    /// plane) and `255·N·L` (`None` when it does not fit: `diffuse_falloff` then divides
    /// first).
    nl: Option<S>,
    knl: Option<S>,
}

/// How many lights a row keeps per-row terms for (a scene with more lights shades every
/// light the general way).
const ROW_LIGHTS: usize = 2;

/// What a scanline remembers from pixel to pixel: the last `2|D|∞` and the hit's
/// distance bound `t'·2|D|∞` it gave, and the last `(t, ulp)` key of the segments'
/// tolerance (`surface_tolerance` depends on nothing else) with its value. Along a row
/// `|D|∞` is mostly `|dz|` or `|dy|`, so both are products a pixel mostly skips.
#[derive(Debug, Clone, Copy)]
struct Memo<S> {
    bound: Option<(S, S)>,
    tol: Option<(S, S, S)>,
}

/// Whether the stage set `T` is the one this kernel draws with (diffuse point lights and
/// shadows, `DiffuseShadows`): [`super::select`] picks it only then, and the scanline
/// code is compiled only for that set (flash: a scene lit without shadows, one plane
/// under a light, is the fast kernel's).
pub(crate) const fn draws_with<T: Stages>() -> bool {
    T::LIGHTING && T::SHADOWS && !T::SPECULAR && !T::CONES && !T::REFLECTION && !T::TRANSPARENCY
}

/// The row's nearest plane and what every pixel of the row shares of its hit: the
/// object, `t'`, the hit's `y` and `z`, and the normal facing the ray; `Some(None)` when
/// no plane is accepted, `None` when the row cannot be decided once.
fn row_plane<S: Scalar>(
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
        t,
        y,
        z,
        facing,
    }))
}

/// What [`row_plane`] found: the object, `t'`, the hit's `y` and `z`, the facing normal.
struct RowPlane<S> {
    index: usize,
    t: S,
    y: S,
    z: S,
    facing: Vec3<S>,
}

/// Whether this kernel draws scanline `row` itself (`false`: it hands it to the fast
/// kernel), for [`crate::Frame::row_kernel`].
pub(crate) fn decides<S: Scalar>(scene: &SceneView<'_, S>, rows: &Rows<S>, row: u16) -> bool {
    let p = &rows.primary;
    p.row(scene, row, 0)
        .is_some_and(|first| row_plane(scene, p, &first).is_some())
}

/// The row's plane, worked out once: `Some(None)` when no plane is accepted, `None` when
/// the fast kernel must decide the row pixel by pixel.
fn level<S: Scalar, T: Stages>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    first: &Row<S>,
) -> Option<Option<Level<S>>> {
    let Some(RowPlane {
        index,
        t,
        y,
        z,
        facing,
    }) = row_plane(scene, p, first)?
    else {
        return Some(None);
    };
    let mut sides = heapless::Vec::new();
    let mut side_bits = SideBits::default();
    if T::SHADOWS && !p.at_lights().is_empty() {
        match p.sides_at(first, t, &mut sides) {
            Some(bits) => side_bits = bits,
            None => sides.clear(),
        }
    }
    let lights = scene.lights.len();
    let mut occluders = heapless::Vec::new();
    let n = sides.len();
    if n == scene.objects.len() && lights <= ROW_LIGHTS {
        for j in 0..lights {
            let at_light = p.at_lights().get(j * n..)?.get(..n)?;
            let mut bits = 0u8;
            // The row's hits lie on the line (x, y, z) for every x: its offsets from the
            // light in y and z.
            let light = scene.lights.get(j)?.location;
            let (wy, wz) = (y.checked_sub(light.y), z.checked_sub(light.z));
            for (i, ((o, &a0), &a1)) in scene.objects.iter().zip(&sides).zip(at_light).enumerate() {
                let may = match o.shape {
                    // A sphere whose shadow cone from this light misses the whole row
                    // (`crate::geometry::ShadowCone::clears_line`) is left out.
                    Shape::Sphere(_) => !p.cones().iter().any(|c| {
                        usize::from(c.light) == j
                            && usize::from(c.object) == i
                            && matches!((wy, wz), (Some(wy), Some(wz)) if c.clears_line(wy, wz))
                    }),
                    _ => (a0 > S::ZERO) != (a1 > S::ZERO),
                };
                if may {
                    bits |= 1 << i;
                }
            }
            let _ = occluders.push(bits);
        }
    }
    let object = scene.objects.get(index)?;
    let materials = match object.shape {
        Shape::Tiled { alt, .. } => [object.material, alt],
        _ => [object.material, object.material],
    };
    let mut weights = heapless::Vec::new();
    let mut overflow = 0u16;
    if lights <= ROW_LIGHTS {
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
    }
    let mut row_lights = heapless::Vec::new();
    if lights <= ROW_LIGHTS {
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
    }
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

/// Fills `out` with the per-row part of a lean row ([`LeanRow`]) of the row's plane `l`
/// (`(dy, dz)`: the row's `D.y` and `D.z`, the same at every pixel); `None` where the
/// row is not one. A lean row:
/// sums are exact (`KernelArith::EXACT_SUMS`), the sides are kept, every light has its row
/// terms and weights, only spheres can shadow the row, each of them has exactly one
/// shadow cone from that light and the format's products are exact
/// (`KernelArith::EXACT_PRODUCTS`: the cone's `l·u` is summed in another order), the row's
/// `|L.y|`, `|L.z|` and the cones' `u` lie within half the format's range; the plane is a
/// plain plane, or a tiled one with its tile row and `u` along x ([`RowTiles`]); its
/// materials are there; `t' > 0`, and at every `D.x` of the row ([`Primary::dx_range`])
/// the hit's distance bound and the segments' tolerance fit the format (both grow with
/// `|D.x|` and the hit's `|x|`, so checking the row's extremes checks every pixel;
/// `lean_color` then skips them).
fn lean_row<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    l: &Level<S>,
    (dy, dz): (S, S),
    out: &mut LeanRow<S>,
) -> Option<()> {
    out.lights.clear();
    out.cones.clear();
    let lights = scene.lights.len();
    // Every light has its row terms and weights, the sums are exact, the sides are
    // kept, and no plane can shadow the row (a plane's shadow test needs the segments'
    // tolerance at each pixel).
    let spheres_only = l.occluders.iter().all(|&bits| {
        scene
            .objects
            .iter()
            .enumerate()
            .all(|(i, o)| bits & (1 << i) == 0 || matches!(o.shape, Shape::Sphere(_)))
    });
    (S::EXACT_SUMS
        && !l.sides.is_empty()
        && l.occluders.len() == lights
        && l.lights.len() == lights
        && l.weights.len() == 2 * ROW_LIGHTS
        && spheres_only
        && l.lights.iter().all(|rl| rl.l.is_none() || rl.yz.is_some()))
    .then_some(())?;
    let object = scene.objects.get(l.index)?;
    let (t, y, z, tile_row) = (l.t, l.y, l.z, l.tile_row);
    let (weights, overflow) = (&l.weights, l.overflow);
    let (tiles, alt) = match (object.shape, tile_row) {
        (Shape::Tiled { frame, alt, .. }, Some(j)) => (Some(frame.row_tiles(y, z, j)?), alt),
        (Shape::Plane(_), _) => (None, object.material),
        _ => return None,
    };
    // The tolerance at the row's extremes (t' > 0: the bound and `|x|` grow with `|D.x|`).
    (t > S::ZERO).then_some(())?;
    let eye = scene.camera.viewpoint;
    let (lo, hi) = p.dx_range(scene, scene.camera.width)?;
    let widest = lo.abs().max(hi.abs()).max(dy.abs()).max(dz.abs());
    let t_bound = t.checked_mul(widest.checked_add(widest)?)?;
    let x_lo = eye.x.checked_add(t.checked_mul(lo)?)?;
    let x_hi = eye.x.checked_add(t.checked_mul(hi)?)?;
    let m = eye
        .max_abs()
        .max(Vec3::new(x_lo, y, z).max_abs())
        .max(x_hi.abs());
    surface_tolerance(t_bound, m)?;
    let mut slot = [0; 2];
    for (k, m) in [object.material, alt].into_iter().enumerate() {
        let material = scene.materials.get(usize::from(m))?;
        out.ambient[k] = material.ambient;
        out.lit[k] = material.diffuse != [S::ZERO; 3];
        slot[k] = usize::from(m != object.material) * ROW_LIGHTS;
    }
    let half = S::MAX.mul_ratio(1, 2)?;
    out.half = half;
    out.tiles = tiles;
    let (lights, cones) = (&mut out.lights, &mut out.cones);
    for (j, ((&bits, rl), light)) in l
        .occluders
        .iter()
        .zip(&l.lights)
        .zip(scene.lights)
        .enumerate()
    {
        let entry = |k: usize| -> Option<([S; 3], u16)> {
            let e = slot[k] + j;
            Some((*weights.get(e)?, (overflow >> (3 * e)) & 7))
        };
        let ((w0, o0), (w1, o1)) = (entry(0)?, entry(1)?);
        let start = cones.len();
        for i in (0..fast::FAST_OBJECTS).filter(|i| bits & (1 << i) != 0) {
            // `RowCone::clears` sums `l·u` in another order than `ShadowCone::clears`:
            // the same answer only where no partial sum can leave the double width (a
            // format whose wide type is not double width, `i16f16n`, takes the row the
            // general way).
            S::EXACT_PRODUCTS.then_some(())?;
            let mut matching = p
                .cones()
                .iter()
                .filter(|c| usize::from(c.light) == j && usize::from(c.object) == i);
            let (Some(cone), None) = (matching.next(), matching.next()) else {
                return None;
            };
            let row_cone = match rl.l {
                Some((ly, lz)) if ly.abs() <= half && lz.abs() <= half => cone.in_row(ly, lz)?,
                // No pixel of the row reaches this light's cones.
                None => continue,
                Some(_) => return None,
            };
            cones.push(row_cone).ok()?;
        }
        // The quick terms' numerators and their slack (`lean_color`).
        // `KernelArith::quick_pixel` maps colours to pixels as the crate's rules do.
        let mut quick = [None; 2];
        if let (Some(knl), Rules::Fixray, true) = (rl.knl, scene.rules(), S::QUICK_PIXEL) {
            for (k, (w, o)) in [(w0, o0), (w1, o1)].into_iter().enumerate() {
                let products = [0, 1, 2].map(|c| w[c].checked_mul(knl));
                let top = w[0].max(w[1]).max(w[2]);
                let extra = top
                    .floor_to_i32()
                    .and_then(|n| n.checked_add(3))
                    .and_then(|n| S::DELTA.checked_mul_int(n));
                if let ([Some(a), Some(b), Some(c)], Some(extra), 0) = (products, extra, o)
                    && w.iter().all(|c| *c >= S::ZERO)
                {
                    quick[k] = S::quick_term([a, b, c], extra);
                }
            }
        }
        let lean = LeanLight {
            x: light.location.x,
            yz: rl.l.and(rl.yz),
            nl: rl.nl,
            knl: rl.knl,
            weights: [w0, w1],
            overflow: [o0, o1],
            quick,
            cones: (u8::try_from(start).ok()?, u8::try_from(cones.len()).ok()?),
        };
        lights.push(lean).ok()?;
    }
    let parities = if out.tiles.is_some() { 2 } else { 1 };
    out.runs = match out.lights.as_slice() {
        [light] => (0..parities).all(|k| light.quick[k].is_some() && out.lit[k]),
        _ => false,
    };
    Some(())
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
    Ok(Pixels {
        scene,
        p,
        level,
        lean: LeanRow {
            tiles: None,
            ambient: [[S::ZERO; 3]; 2],
            lit: [false; 2],
            lights: heapless::Vec::new(),
            cones: heapless::Vec::new(),
            half: S::ZERO,
            runs: false,
        },
        lean_built: None,
        lazy,
        stale: false,
        state: first,
        fresh: true,
        // From another column than 0 the first pixel restarts there, as the fast
        // kernel's scanline starts its row there.
        valid: columns.start == 0,
        at_hit: heapless::Vec::new(),
        memo: Memo {
            bound: None,
            tol: None,
        },
        spheres: p.sphere_columns_on_row(row),
        y: scene.camera.screen_y(row),
        row,
        columns,
        counters,
        stages: core::marker::PhantomData,
        run: [Rgb888::new(0, 0, 0); RUN],
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
    /// as `reference::scanline` does.
    state: Row<S>,
    fresh: bool,
    valid: bool,
    /// Whether the row steps only `D` outside the spheres' columns (the formats whose
    /// products and sums are exact, and every term fits along the whole row:
    /// [`Primary::terms_fit_row`]), and whether its terms are behind its `D` now.
    lazy: bool,
    stale: bool,
    at_hit: heapless::Vec<S, FAST_OBJECTS>,
    memo: Memo<S>,
    /// The columns where a sphere can be met on this row.
    spheres: (u16, u16),
    y: Option<S>,
    row: u16,
    columns: core::ops::Range<u16>,
    counters: &'a mut Counters,
    stages: core::marker::PhantomData<T>,
    /// Pixels a quick run drew ahead ([`Pixels::quick_run`]): `run[run_at..run_len]`
    /// are the next ones, before `columns`.
    run: [Rgb888; RUN],
    run_at: u8,
    run_len: u8,
    /// Which of `run` were lit (bit `i`: `run[i]`): their counts are added as they are
    /// handed out, so that a caller that stops early counts only the pixels it took.
    #[cfg(feature = "stats")]
    run_lit: u32,
}

/// How many pixels a quick run draws ahead of the one asked for ([`Pixels::quick_run`]).
const RUN: usize = 32;

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
    /// The pixel at `column` (the next of the row's columns).
    #[inline(never)]
    fn pixel(&mut self, column: u16) -> Rgb888 {
        let (scene, p) = (self.scene, self.p);
        count(&mut self.counters.primary_rays);
        let in_spheres = column >= self.spheres.0 && column <= self.spheres.1;
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
            Some(()) if in_spheres => match p.nearest(scene, &self.state) {
                Ok(Some(h)) if self.level.as_ref().is_some_and(|l| l.index == h.index) => Ok(None),
                Ok(Some(h)) => Ok(Some(h)),
                Ok(None) => return to_pixel(scene.rules(), scene.background),
                Err(()) => Err(()),
            },
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
        let (first, lit) = quick_step(scene, p, l, f, light, &mut self.state, row, column)?;
        // (The first pixel's primary ray was counted by `pixel`, the caller; the others'
        // counts are added as `next` hands them out.)
        count_quick(self.counters, tiled, lit, false);
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
            let Some((pixel, lit)) = quick_step(scene, p, l, f, light, &mut self.state, row, c)
            else {
                break;
            };
            #[cfg(feature = "stats")]
            {
                self.run_lit |= u32::from(lit) << n;
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
            &mut self.at_hit,
            self.counters,
        )
    }
}

/// The colour of the row's plane at the row's current pixel (the background without
/// one): its hit's `x`, tile and lights. A pixel whose quantity leaves the format is the
/// fast kernel's (the reference path), a light whose `|L|²` does not fit the general
/// shading's.
#[inline]
#[allow(clippy::too_many_arguments)]
fn plane_color<S: Scalar, T: Stages>(
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
fn lit<S: Scalar, T: Stages>(
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
    let mut color = material.ambient;
    if material.diffuse == [S::ZERO; 3] {
        return Some(color);
    }
    let eye = scene.camera.viewpoint;
    let tol = if T::SHADOWS {
        segment_tolerance(eye, hit.point, hit.t, memo)?
    } else {
        S::ZERO
    };
    // The per-row weights of the material shown (`usize::MAX`: not kept).
    let slot = m.map_or(usize::MAX, |m| {
        usize::from(m != l.materials[0]) * ROW_LIGHTS
    });
    for (j, light) in scene.lights.iter().enumerate() {
        let (to_light, ll, nl, knl) = match l.lights.get(j) {
            // The row's terms of this light: `L.y`, `L.z`, `N·L` and `255·N·L`, and in
            // the fixed formats `L.y² + L.z²`, so that `|L|²` takes one product.
            Some(rl) => {
                let (Some(lx), Some((ly, lz))) = (light.location.x.checked_sub(hit.point.x), rl.l)
                else {
                    continue;
                };
                let to_light = Vec3::new(lx, ly, lz);
                let ll = match rl.yz {
                    Some(yz) if S::EXACT_SUMS => row_ll(lx, yz),
                    _ => to_light.dot(to_light),
                };
                let ll = ll.filter(|ll| *ll > S::ZERO)?;
                let Some(nl) = rl.nl else {
                    continue;
                };
                (to_light, ll, nl, rl.knl)
            }
            None => {
                let Some(to_light) = light.location.diff(hit.point) else {
                    continue;
                };
                let ll = to_light.dot(to_light).filter(|ll| *ll > S::ZERO)?;
                let Some(nl) = to_light.dot_axis(l.facing).filter(|c| *c > S::ZERO) else {
                    continue;
                };
                (to_light, ll, nl, nl.checked_mul(channel_max::<S>()))
            }
        };
        if T::SHADOWS {
            count(&mut counters.shadow_rays);
            let shadowed = match (sides, l.occluders.get(j)) {
                (Some(s), Some(&bits)) => {
                    occluded_among(scene, s, j, bits, (hit.point, to_light, ll, tol), |_| false)
                }
                _ => None,
            };
            let shadowed = match shadowed {
                Some(v) => v,
                None => occludes_segment(
                    scene,
                    sides.map(|s| (s, j)),
                    hit.point,
                    to_light,
                    ll,
                    tol,
                    light.location,
                ),
            };
            if shadowed {
                continue;
            }
        }
        let falloff = diffuse_falloff(nl, knl, ll);
        count(&mut counters.diffuse);
        match l.weights.get(slot.saturating_add(j)) {
            Some(w) => color = add_weighted(color, *w, l.overflow >> (3 * (slot + j)), falloff),
            None => {
                let e = light.emissivity;
                for ((c, diffuse), emissivity) in color.iter_mut().zip(material.diffuse).zip(e) {
                    *c = add_sat(*c, term([emissivity, diffuse, falloff]));
                }
            }
        }
    }
    Some(color)
}

/// [`plane_color`] for the rows it draws most (a lean row, [`lean_row`]): the same
/// operations in the same order, without its general cases (the per-row ones, the
/// distance bound and the segments' tolerance among them, were checked once by
/// [`lean_row`]). `None` (and nothing counted) where a pixel needs one of them: the
/// caller then draws it with [`plane_color`]. Those cases: the hit's `x` or `L.x` out of
/// the format's range, a light whose `|L|²` does not fit or is not positive, a pixel
/// whose `|L.x|` is beyond half the range where a cone must be tested, and a sphere whose
/// shadow cone does not clear the pixel (its exact segment test needs the tolerance,
/// [`occluded_among`]).
///
/// Its colour (`Err`), or its pixel (`Ok`) where the last light's term
/// `w·(255·N·L/|L|²)` was taken quickly, by `KernelArith::quick_pixel` (on cores where it
/// pays): the pixel of `(w·255·N·L)/|L|²` over the colour so far by
/// one approximate reciprocal, returned only where its error bound settles it. With
/// `|L|² ≥ 1` and `w ≥ 0` the exact term (a truncated quotient times `w`, floored) is
/// within `(w + 2)·DELTA` of the real quotients (`w` DELTAs for the quotient's
/// truncation, one for the product's and one for `w·255·N·L`'s, divided by
/// `|L|² ≥ 1`; the row keeps `(⌊w_max⌋ + 3)·DELTA` in its [`LeanLight::quick`] term),
/// so the pixel is this function's exact one, bit for bit. Where it does not settle, the format has
/// no shortcut, the row's light has no quick numerators or `|L|² < 1`, the term is the
/// exact one.
#[inline(always)]
fn lean_color<S: Scalar>(
    scene: &SceneView<'_, S>,
    state: &Row<S>,
    l: &Level<S>,
    f: &LeanRow<S>,
    counters: &mut Counters,
) -> Option<Result<Rgb888, Color<S>>> {
    let x = row_x(scene, l, Primary::dir(state).x)?;
    // The material by the tile's parity (`row_material`); the hit's distance bound and
    // the segments' tolerance fit at every pixel of a lean row (`lean_row`).
    let parity = f.parity(x);
    let tiled = u32::from(f.tiles.is_some());
    let mut color = *f.ambient.get(parity)?;
    if !*f.lit.get(parity)? {
        counters_add(&mut counters.tile_lookups, tiled);
        return Some(Err(color));
    }
    let (mut shadow_rays, mut diffuse) = (0u32, 0u32);
    for (index, light) in f.lights.iter().enumerate() {
        let (Some(lx), Some(yz)) = (light.x.checked_sub(x), light.yz) else {
            continue;
        };
        let ll = row_ll(lx, yz)?;
        if ll <= S::ZERO {
            return None;
        }
        let Some(nl) = light.nl else {
            continue;
        };
        shadow_rays += 1;
        // Only spheres can shadow a lean row: each cleared by its cone, or the pixel
        // takes the exact test (`plane_color`).
        for cone in f.cones_at(light, lx)? {
            if !cone.clears(lx, ll) {
                return None;
            }
        }
        diffuse += 1;
        let last = index + 1 == f.lights.len();
        if S::QUICK_PIXEL
            && last
            && ll >= S::ONE
            && let Some(term) = light.quick.get(parity)?
            && let Some([r, g, b]) = S::quick_pixel(color, term, ll)
        {
            counters_add(&mut counters.tile_lookups, tiled);
            counters_add(&mut counters.shadow_rays, shadow_rays);
            counters_add(&mut counters.diffuse, diffuse);
            return Some(Ok(Rgb888::new(r, g, b)));
        }
        let falloff = diffuse_falloff(nl, light.knl, ll);
        let (w, overflow) = (light.weights.get(parity)?, light.overflow.get(parity)?);
        color = add_weighted(color, *w, *overflow, falloff);
    }
    counters_add(&mut counters.tile_lookups, tiled);
    counters_add(&mut counters.shadow_rays, shadow_rays);
    counters_add(&mut counters.diffuse, diffuse);
    Some(Err(color))
}

/// A quick step's counts, as the general path counts its pixel (`pixel`, `lean_color`,
/// and `lit` for a shadowed one): its primary ray where `ray`, its tile lookup where the
/// row is tiled, its shadow ray, and its diffuse term where it is lit.
#[inline(always)]
fn count_quick(counters: &mut Counters, tiled: u32, lit: bool, ray: bool) {
    counters_add(&mut counters.primary_rays, u32::from(ray));
    counters_add(&mut counters.tile_lookups, tiled);
    count(&mut counters.shadow_rays);
    counters_add(&mut counters.diffuse, u32::from(lit));
}

/// `count` `n` times.
#[inline(always)]
fn counters_add(counter: &mut u32, n: u32) {
    for _ in 0..n {
        count(counter);
    }
}

/// The `x` of the row's hit at `D.x = dx`: `eye.x + t'·dx`, as `Primary::point` forms it.
#[inline(always)]
fn row_x<S: Scalar>(scene: &SceneView<'_, S>, l: &Level<S>, dx: S) -> Option<S> {
    scene.camera.viewpoint.x.checked_add(l.t.checked_mul(dx)?)
}

/// `|L|²` of a row's hit from `L.x` and the row's `L.y² + L.z²`, one rounding (the
/// fixed formats' sums are exact).
#[inline(always)]
fn row_ll<S: Scalar>(lx: S, yz: S::Acc) -> Option<S> {
    S::acc_round(S::acc_add(S::acc_mul(lx, lx)?, yz)?)
}

impl<S: Scalar> LeanRow<S> {
    /// The tile parity of the row's hit at `x` (0: the plane's own material, 1: a tiled
    /// plane's odd tiles), as `row_material` chooses it.
    #[inline(always)]
    fn parity(&self, x: S) -> usize {
        match &self.tiles {
            Some(tiles) => usize::from(tiles.odd(x) == Some(true)),
            None => 0,
        }
    }

    /// The shadow cones of `light`'s occluding spheres at a hit with `L.x = lx`; `None`
    /// where there are some and `|L.x|` is beyond half the range (their row part of `l·u`
    /// then does not hold: the pixel takes the general path).
    #[inline(always)]
    fn cones_at(&self, light: &LeanLight<S>, lx: S) -> Option<&[RowCone<S>]> {
        let cones = self
            .cones
            .get(usize::from(light.cones.0)..usize::from(light.cones.1))?;
        (cones.is_empty() || lx.abs() <= self.half).then_some(cones)
    }
}

/// The pixel at `column` of a lean row `f` (of level `l`) with one light, where
/// [`Pixels::pixel`]'s general path would step `D` alone (a lazy row, a column outside
/// the spheres' columns: [`Primary::advance_dir`] from the last column, or
/// [`Primary::restart_dir`] at a resync) and draw the row's plane by [`lean_color`]
/// (where the quick term settles it), or by `plane_color` where a sphere's cone does
/// not clear the pixel (its exact segment test, [`exact_shadow`]: shadowed, the
/// ambient colour): the same operations in the same order for those cases (the step,
/// the hit's `x`, the tile's parity, `L.x`, `|L|²`, the cones, `KernelArith::quick_pixel`),
/// without the general cases' lookups and loops; `state` is stepped to `column`; with
/// the pixel, whether the light lit it. `None` wherever the case is another, with
/// `state` unchanged but at a resync column, which is restarted (the general path then
/// restarts it again, to the same state). The caller counts.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn quick_step<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    l: &Level<S>,
    f: &LeanRow<S>,
    light: &LeanLight<S>,
    state: &mut Row<S>,
    (row, dy): (u16, S),
    column: u16,
) -> Option<(Rgb888, bool)> {
    let resync = column.is_multiple_of(fast::resync_pixels::<S>());
    let dx = if resync {
        p.restart_dir_in_row(scene, row, dy, column, state)?;
        Primary::dir(state).x
    } else {
        // The general path steps only from the last column (else it restarts).
        (Primary::column(state).checked_add(1) == Some(column)).then_some(())?;
        p.next_dx(state)?
    };
    let x = row_x(scene, l, dx)?;
    let parity = f.parity(x);
    let term = light.quick.get(parity)?.as_ref()?;
    if !*f.lit.get(parity)? || light.nl.is_none() {
        return None;
    }
    let lx = light.x.checked_sub(x)?;
    let ll = row_ll(lx, light.yz?)?;
    if ll < S::ONE {
        return None;
    }
    let cones = f.cones_at(light, lx)?;
    // A sphere whose cone does not clear the pixel takes its exact segment test, as
    // `plane_color` takes it (`occluded_among`, with the tolerance `lit` gives it): where it
    // meets the segment the light adds nothing and the pixel is the ambient colour's.
    let mut shadowed = false;
    for (k, cone) in cones.iter().enumerate() {
        if !cone.clears(lx, ll) && exact_shadow(scene, p, l, (dx, dy), x, (lx, ll), k)? {
            shadowed = true;
            break;
        }
    }
    let color = *f.ambient.get(parity)?;
    let pixel = if shadowed {
        to_pixel(Rules::Fixray, color)
    } else {
        let [r, g, b] = S::quick_pixel(color, term, ll)?;
        Rgb888::new(r, g, b)
    };
    if !resync {
        // `next_dx` fitted and the column follows the state's: this step cannot fail.
        p.advance_dir(state)?;
    }
    Some((pixel, !shadowed))
}

/// Whether the sphere of the light's `cone`-th cone shadows a lean row's hit at `x` from
/// the row's one light (`L = (lx, L.y, L.z)`, `|L|² = ll`): its exact segment test with the segments'
/// tolerance at the hit, what `plane_color` decides there (`lit` → `occluded_among`: the hit's
/// distance bound `t'·2|D|∞`, `segment_tolerance`, the sides of light 0). `None` where a
/// quantity does not fit (the general path then draws the pixel).
#[inline(never)]
fn exact_shadow<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    l: &Level<S>,
    (dx, dy): (S, S),
    x: S,
    (lx, ll): (S, S),
    cone: usize,
) -> Option<bool> {
    // The hit's distance bound and the segments' tolerance as `plane_color` finds them.
    let mut memo = Memo {
        bound: None,
        tol: None,
    };
    let t = hit_bound(l, Vec3::new(dx, dy, p.dz()), &mut memo)?;
    let point = Vec3::new(x, l.y, l.z);
    let tol = segment_tolerance(scene.camera.viewpoint, point, t, &mut memo)?;
    let (y, z) = l.lights.first()?.l?;
    // The row's cones of the light are its occluders' spheres in order (`lean_row`).
    let bits = *l.occluders.first()?;
    let i = (0..fast::FAST_OBJECTS)
        .filter(|i| bits & (1 << i) != 0)
        .nth(cone)?;
    let n = l.sides.len();
    let (a0, a1) = (*l.sides.get(i)?, *p.at_lights().get(..n)?.get(i)?);
    let shape = &scene.objects.get(i)?.shape;
    Some(shape.meets_segment_with(
        Some((a0, a1)),
        point,
        Vec3::new(lx, y, z),
        ll,
        tol,
        scene.epsilon,
    ))
}

/// The material of the row's plane at `point`: a tiled plane's by its tile (the row's
/// tile row `j` and the point's column), a plane's own; `None` for any other tiling (the
/// general lookup, `surface`, whose material index this kernel does not see: its per-row
/// weights are then not used).
#[inline(always)]
fn row_material<S: Scalar>(
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

/// `color + w·falloff` per channel, saturating: the light's term with the row's
/// `emissivity × diffuse` weights `w` (`overflow`: the entry's three overflow bits, a
/// weight that did not fit saturates the channel).
#[inline(always)]
fn add_weighted<S: Scalar>(color: Color<S>, w: [S; 3], overflow: u16, falloff: S) -> Color<S> {
    let add = |c: S, w: S, bit: u16| {
        let t = if overflow & bit == 0 {
            w.checked_mul(falloff)
        } else {
            None
        };
        add_sat(c, t.unwrap_or(S::MAX))
    };
    [
        add(color[0], w[0], 1),
        add(color[1], w[1], 2),
        add(color[2], w[2], 4),
    ]
}

/// As `Primary::point`: the bound `t'·2|D|∞` on the hit's world distance, remembered
/// for the last `2|D|∞` (`None`: it does not fit).
#[inline(always)]
fn hit_bound<S: Scalar>(l: &Level<S>, d: Vec3<S>, memo: &mut Memo<S>) -> Option<S> {
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

/// The segments' tolerance at a hit (`surface_tolerance(t, m)`: `(t + c)·ulp(max(1, t,
/// m))`), remembered for the last `(t, ulp)` (`None`: it does not fit).
#[inline(always)]
fn segment_tolerance<S: Scalar>(
    eye: Vec3<S>,
    point: Vec3<S>,
    t: S,
    memo: &mut Memo<S>,
) -> Option<S> {
    let m = eye.max_abs().max(point.max_abs());
    let ulp = S::ONE.max(t).max(m).ulp();
    match memo.tol {
        Some((k, u, tol)) if k == t && u == ulp => Some(tol),
        _ => {
            let tol = surface_tolerance(t, m)?;
            memo.tol = Some((t, ulp, tol));
            Some(tol)
        }
    }
}
