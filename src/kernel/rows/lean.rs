//! Lean rows: a level-plane row whose every pixel needs only its hit's `x`, its tile's
//! parity, `|L|²` and the spheres' shadow cones ([`lean_row`], [`lean_color`]), and quick
//! runs of such pixels ([`quick_step`]).

use embedded_graphics_core::pixelcolor::Rgb888;

use super::super::fast::{self, Primary, Row};
use super::super::shading::{add_weighted, segment_tolerance};
use super::level::{Level, Memo, ROW_LIGHTS, hit_bound};
use crate::geometry::{RowCone, RowTiles, surface_tolerance};
use crate::shade::color::to_pixel;
use crate::shade::diffuse_falloff;
use crate::stats::{Counters, count};
use crate::{Color, Rules, Scalar, SceneView, Shape, Vec3};

/// A lean row's per-row part ([`lean_row`]): what [`lean_color`] would otherwise look up
/// or check at each pixel. Built in place, in the scanline's `Pixels`, at the row's
/// first pixel that needs it (an I32F32 scanline on a 16 KB chip has no room for copies).
#[derive(Debug, Clone)]
pub(super) struct LeanRow<S: Scalar> {
    /// A tiled plane's checkerboard along the row (`None`: a plain plane).
    pub(super) tiles: Option<RowTiles<S>>,
    /// Per tile parity (0: the plane's own material, 1: a tiled plane's odd tiles): the
    /// ambient colour and whether the diffuse colour is not black (the weights per
    /// parity are each light's, [`LeanLight`]).
    pub(super) ambient: [Color<S>; 2],
    pub(super) lit: [bool; 2],
    /// Per light, everything its term needs.
    pub(super) lights: heapless::Vec<LeanLight<S>, ROW_LIGHTS>,
    /// The shadow cones of the spheres that can shadow the row, light by light
    /// ([`LeanLight::cones`]).
    pub(super) cones: heapless::Vec<RowCone<S>, { fast::MAX_CONES }>,
    /// Half the format's range: a pixel's `|L.x|` beyond takes `plane_color`
    /// ([`RowCone::clears`]).
    pub(super) half: S,
    /// Whether quick runs may draw the row (`Pixels::quick_run`): one light, with a
    /// quick term and a lit material for every tile parity the row shows (else each
    /// pixel would try one and fall back).
    pub(super) runs: bool,
}

/// One light of a lean row: `RowLight`'s terms, the light's `x`, its weights per tile
/// parity (with their overflow bits) and where in [`LeanRow::cones`] the shadow cones of
/// the spheres that can shadow the row from it are (each must clear the pixel).
#[derive(Debug, Clone)]
pub(super) struct LeanLight<S: Scalar> {
    pub(super) x: S,
    /// `L.y² + L.z²` (`None`: `L.y`, `L.z` do not fit, no hit of the row is lit).
    pub(super) yz: Option<S::Acc>,
    pub(super) nl: Option<S>,
    pub(super) knl: Option<S>,
    pub(super) weights: [[S; 3]; 2],
    pub(super) overflow: [u16; 2],
    /// Per tile parity, the quick term (`KernelArith::quick_term`): the numerators
    /// `weights × knl` per channel and the slack `(⌊w_max⌋ + 3)·DELTA`, what the exact
    /// term's truncations can add to the quick quotients' bound ([`lean_color`]); `None`
    /// where `knl` is not known, that parity's weights are negative or overflow, the
    /// products do not fit or are all zero, or the format has no quick pixel.
    pub(super) quick: [Option<S::QuickTerm>; 2],
    /// The light's cones: `cones.0..cones.1` in [`LeanRow::cones`].
    pub(super) cones: (u8, u8),
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
pub(super) fn lean_row<S: Scalar>(
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
    let tol = surface_tolerance(t_bound, m)?;
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
                Some((ly, lz)) if ly.abs() <= half && lz.abs() <= half => {
                    cone.in_row(ly, lz, tol)?
                }
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

/// `plane_color` for the rows it draws most (a lean row, [`lean_row`]): the same
/// operations in the same order, without its general cases (the per-row ones, the
/// distance bound and the segments' tolerance among them, were checked once by
/// [`lean_row`]). `None` (and nothing counted) where a pixel needs one of them: the
/// caller then draws it with `plane_color`. Those cases: the hit's `x` or `L.x` out of
/// the format's range, a light whose `|L|²` does not fit or is not positive, a pixel
/// whose `|L.x|` is beyond half the range where a cone must be tested, and a sphere whose
/// shadow cone neither clears the pixel nor blocks its light certainly (its umbra,
/// `RowCone::blocks`; its exact segment test needs the tolerance, `occluded_among`).
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
pub(super) fn lean_color<S: Scalar>(
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
        // Only spheres can shadow a lean row: each cleared by its cone, or blocking the
        // segment certainly (its umbra: the light adds nothing), or the pixel takes the
        // exact test (`plane_color`).
        let mut blocked = false;
        for cone in f.cones_at(light, lx)? {
            if cone.clears(lx, ll) {
                continue;
            }
            if !cone.blocks(lx, ll) {
                return None;
            }
            blocked = true;
            break;
        }
        if blocked {
            continue;
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
pub(super) fn count_quick(counters: &mut Counters, tiled: u32, lit: bool, ray: bool) {
    counters_add(&mut counters.primary_rays, u32::from(ray));
    counters_add(&mut counters.tile_lookups, tiled);
    count(&mut counters.shadow_rays);
    counters_add(&mut counters.diffuse, u32::from(lit));
}

/// `count` `n` times.
#[inline(always)]
pub(super) fn counters_add(counter: &mut u32, n: u32) {
    for _ in 0..n {
        count(counter);
    }
}

/// The `x` of the row's hit at `D.x = dx`: `eye.x + t'·dx`, as `Primary::point` forms it.
#[inline(always)]
pub(super) fn row_x<S: Scalar>(scene: &SceneView<'_, S>, l: &Level<S>, dx: S) -> Option<S> {
    scene.camera.viewpoint.x.checked_add(l.t.checked_mul(dx)?)
}

/// `|L|²` of a row's hit from `L.x` and the row's `L.y² + L.z²`, one rounding (the
/// fixed formats' sums are exact).
#[inline(always)]
pub(super) fn row_ll<S: Scalar>(lx: S, yz: S::Acc) -> Option<S> {
    S::acc_round(S::acc_add(S::acc_mul(lx, lx)?, yz)?)
}

impl<S: Scalar> LeanRow<S> {
    /// A lean part not built yet ([`lean_row`] fills it).
    pub(super) fn empty() -> Self {
        Self {
            tiles: None,
            ambient: [[S::ZERO; 3]; 2],
            lit: [false; 2],
            lights: heapless::Vec::new(),
            cones: heapless::Vec::new(),
            half: S::ZERO,
            runs: false,
        }
    }

    /// The tile parity of the row's hit at `x` (0: the plane's own material, 1: a tiled
    /// plane's odd tiles), as `row_material` chooses it.
    #[inline(always)]
    pub(super) fn parity(&self, x: S) -> usize {
        self.tile(x).0
    }

    /// [`LeanRow::parity`] of the row's hit at `x`, with its tile column (`Some(0)` on a
    /// plain plane; `None` where it does not fit, parity 0 as `row_material` takes it).
    #[inline(always)]
    pub(super) fn tile(&self, x: S) -> (usize, Option<i32>) {
        match &self.tiles {
            Some(tiles) => {
                let i = tiles.column(x);
                (usize::from(i.is_some_and(|i| tiles.odd_column(i))), i)
            }
            None => (0, Some(0)),
        }
    }

    /// The shadow cones of `light`'s occluding spheres at a hit with `L.x = lx`; `None`
    /// where there are some and `|L.x|` is beyond half the range (their row part of `l·u`
    /// then does not hold: the pixel takes the general path).
    #[inline(always)]
    pub(super) fn cones_at(&self, light: &LeanLight<S>, lx: S) -> Option<&[RowCone<S>]> {
        let cones = self
            .cones
            .get(usize::from(light.cones.0)..usize::from(light.cones.1))?;
        (cones.is_empty() || lx.abs() <= self.half).then_some(cones)
    }
}

/// The pixel at `column` of a lean row `f` (of level `l`) with one light, where
/// `Pixels::pixel`'s general path would step `D` alone (a lazy row, a column outside
/// the spheres' columns: [`Primary::advance_dir`] from the last column, or
/// [`Primary::restart_dir`] at a resync) and draw the row's plane by [`lean_color`]
/// (where the quick term settles it), or by `plane_color` where a sphere's cone does
/// not clear the pixel (its exact segment test, [`exact_shadow`]: shadowed, the
/// ambient colour): the same operations in the same order for those cases (the step,
/// then [`quick_at`]), without the general cases' lookups and loops; `state` is stepped
/// to `column`; with the pixel, whether the light lit it and its [`Side`]. `None`
/// wherever the case is another, with `state` unchanged but at a resync column, which is
/// restarted (the general path then restarts it again, to the same state). The caller
/// counts. `cones`: whether the pixel may lie in a sphere's shadow ([`quick_at`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn quick_step<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    l: &Level<S>,
    f: &LeanRow<S>,
    light: &LeanLight<S>,
    state: &mut Row<S>,
    (row, dy): (u16, S),
    (column, cones): (u16, bool),
) -> Option<(Rgb888, bool, Side)> {
    let resync = column.is_multiple_of(fast::resync_pixels::<S>());
    let dx = if resync {
        p.restart_dir_in_row(scene, row, dy, column, state)?;
        Primary::dir(state).x
    } else {
        // The general path steps only from the last column (else it restarts).
        (Primary::column(state).checked_add(1) == Some(column)).then_some(())?;
        p.next_dx(state)?
    };
    let at = quick_at(scene, p, (l, f, light), (dx, dy), cones)?;
    if !resync {
        // `next_dx` fitted and the column follows the state's: this step cannot fail.
        p.advance_dir(state)?;
    }
    Some(at)
}

/// What a quick pixel's colour depends on besides `|L|²`, for the spans that compare
/// two of them (`spans.rs`): the tile column of its hit (`None` where it does not fit;
/// `Some(0)` on a plain plane) and whether `L.x < 0`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Side {
    pub(super) tile: Option<i32>,
    pub(super) left: bool,
}

/// The quick pixel of a lean row's hit at `D = (dx, dy, dz)` ([`quick_step`]'s, after
/// its step): the hit's `x`, its tile, `L.x`, `|L|²`, the cones and
/// `KernelArith::quick_pixel`; with whether the light lit it and its [`Side`]. Reads
/// nothing but `dx` of the pixel, so a span may ask it at any column whose `D.x` it knows.
///
/// `cones`: whether the pixel may lie in a sphere's shadow. A caller that knows it does
/// not (the pixel lies outside the row's shadow columns, `changes::shadow_columns`, where
/// the exact segment test finds every hit clear) passes `false`, and no cone is tested:
/// a cone's test there would say what the exact test says, lit (or pass the pixel to the
/// general path, which draws it lit).
#[inline(always)]
pub(super) fn quick_at<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    (l, f, light): (&Level<S>, &LeanRow<S>, &LeanLight<S>),
    (dx, dy): (S, S),
    cones: bool,
) -> Option<(Rgb888, bool, Side)> {
    let x = row_x(scene, l, dx)?;
    let (parity, tile) = f.tile(x);
    let term = light.quick.get(parity)?.as_ref()?;
    if !*f.lit.get(parity)? || light.nl.is_none() {
        return None;
    }
    let lx = light.x.checked_sub(x)?;
    let ll = row_ll(lx, light.yz?)?;
    if ll < S::ONE {
        return None;
    }
    let cones = if cones { f.cones_at(light, lx)? } else { &[] };
    // A sphere whose cone does not clear the pixel takes its exact segment test, as
    // `plane_color` takes it (`occluded_among`, with the tolerance `lit` gives it), unless
    // its umbra says what the test would (`RowCone::blocks`): where it meets the segment
    // the light adds nothing and the pixel is the ambient colour's.
    let mut shadowed = false;
    for (k, cone) in cones.iter().enumerate() {
        if cone.clears(lx, ll) {
            continue;
        }
        if cone.blocks(lx, ll) || exact_shadow(scene, p, l, (dx, dy), x, (lx, ll), k)? {
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
    let side = Side {
        tile,
        left: lx < S::ZERO,
    };
    Some((pixel, !shadowed, side))
}

/// Whether the sphere of the light's `cone`-th cone shadows a lean row's hit at `x` from
/// the row's one light (`L = (lx, L.y, L.z)`, `|L|² = ll`): its exact segment test with the segments'
/// tolerance at the hit, what `plane_color` decides there (`lit` → `occluded_among`: the hit's
/// distance bound `t'·2|D|∞`, `segment_tolerance`, the sides of light 0). `None` where a
/// quantity does not fit (the general path then draws the pixel).
#[inline(never)]
pub(super) fn exact_shadow<S: Scalar>(
    scene: &SceneView<'_, S>,
    p: &Primary<S>,
    l: &Level<S>,
    (dx, dy): (S, S),
    x: S,
    (lx, ll): (S, S),
    cone: usize,
) -> Option<bool> {
    // The hit's distance bound and the segments' tolerance as `plane_color` finds them.
    let mut memo = Memo::default();
    let t = hit_bound(l, Vec3::new(dx, dy, p.dz()), &mut memo)?;
    let point = Vec3::new(x, l.y, l.z);
    let tol = segment_tolerance(scene.camera.viewpoint, point, t, Some(&mut memo.tol))?;
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
