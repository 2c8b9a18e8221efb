//! Whether a block may be filled: its certificate ([`Sampler::certifies`]).

use super::corners::{Corner, CornerTerms, Sees};
use super::fill::{Fill, tiles_fill};
use super::{LIGHTS, Sampler};
use crate::{Scalar, SceneView, Shape, Vec3};

impl<S: Scalar> Sampler<S> {
    /// The block side.
    pub(crate) fn size(&self) -> u16 {
        self.size
    }

    /// How a block with these corners (top left, top right, bottom left, bottom right)
    /// over columns `x` and rows `y` (first and last, inclusive) may be filled; `None`:
    /// it is traced.
    pub(super) fn certifies(
        &self,
        scene: &SceneView<'_, S>,
        corners: [&Corner<S>; 4],
        x: (u16, u16),
        y: (u16, u16),
    ) -> Option<Fill<S>> {
        let meets = |(a, b): (u16, u16), (c, d): (u16, u16)| a <= b && a <= d && c <= b;
        if self
            .spheres
            .iter()
            .any(|&(rows, columns)| meets(rows, y) && meets(columns, x))
        {
            return None;
        }
        let colors = corners.map(|c| c.color);
        let seen = corners.map(|c| c.sees);
        if seen.iter().all(|s| matches!(s, Sees::Background)) {
            return Some(Fill::Smooth(colors));
        }
        let Sees::Plane { object, .. } = seen[0] else {
            return None;
        };
        let mut points = [Vec3::new(S::ZERO, S::ZERO, S::ZERO); 4];
        let mut tiles = [(0, 0); 4];
        let mut terms = [[S::ZERO; LIGHTS]; 4];
        let mut states = [[0; LIGHTS]; 4];
        let (mut all, mut any) = ([u32::MAX; LIGHTS], [0; LIGHTS]);
        for ((((slot, tile), at), state), seen) in points
            .iter_mut()
            .zip(tiles.iter_mut())
            .zip(terms.iter_mut())
            .zip(states.iter_mut())
            .zip(seen)
        {
            let Sees::Plane {
                object: o,
                tile: t,
                point,
                shadows,
                terms: here,
            } = seen
            else {
                return None;
            };
            if o != object {
                return None;
            }
            (*slot, *tile, *at, *state) = (point, t, here, shadows);
            for ((a, n), s) in all.iter_mut().zip(any.iter_mut()).zip(shadows) {
                *a &= s;
                *n |= s;
            }
        }
        // `β = N·D` at the corner pixels: the curvature bound's and the tile edges' (once a
        // block).
        let n = scene
            .objects
            .get(usize::from(object))?
            .shape
            .plane()?
            .normal();
        let beta = super::fill::corner_betas(scene, n, (x, y))?;
        let error =
            self.interpolation_error(scene, object, (&points, &terms), (all, any), (x, y), &beta)?;
        if error.iter().any(|c| *c > self.bound) {
            return None;
        }
        if tiles.iter().all(|t| *t == tiles[0]) {
            return Some(Fill::Smooth(colors));
        }
        // Across a tile's edge: only with a bound (the colours are this module's own).
        let lit: [bool; LIGHTS] = core::array::from_fn(|j| all[j] == 0);
        // A corner lit as the block is has its own tile's colour already.
        let known =
            core::array::from_fn(|i| (states[i].map(|s| s == 0) == lit).then_some(colors[i]));
        if self.bound > S::ZERO {
            tiles_fill(
                scene,
                object,
                (&points, &tiles, known),
                &terms,
                lit,
                (x, y),
                beta,
            )
        } else {
            None
        }
    }

    /// A bound, per channel, on how far the colour of plane `object` strays from the
    /// bilinear interpolation of its values at the corners over the block whose corner
    /// pixels are at columns and rows `corners` and hit it at `points` (each light's term
    /// there: `corner_terms`), given each light's occluders common to all corners (`all`)
    /// and found at any (`any`); `None` where the
    /// shadow state may change inside the block or a quantity leaves the format.
    ///
    /// **Shadows.** The block's points lie within `ρ` of the corners' centroid `m` (the
    /// largest distance from it to a corner: the block is their convex hull). A segment
    /// from the light to such a point lies within `ρ` of the segment to `m` (point for
    /// point), so a sphere farther than `r·17/16 + ρ` from that segment shadows none of
    /// them (the sixteenth: the shadow test's rounding at its edge); nor does a sphere
    /// clear of the pyramid from the light through the corners ([`pyramid_clear`]),
    /// which decides where that tube is too wide (a block beside a shadow's edge).
    ///
    /// **Colour.** A light's term is `f = K/ρ²` with `K = 255·(N·L)`, the same at every
    /// point of a plane, and `ρ = |L − P|`. Along a scanline the ray's `β = N·D` and
    /// `A = β·(L − P) = β·(L − e) − (N·P − N·e)·D` are affine in the column (and likewise
    /// down a column), so with `a = |A'|/|β|`, `b = |β'|/|β|` (per pixel), the relative
    /// derivatives of `ρ²` obey `|(ρ²)'|/ρ² ≤ 2a/ρ + 2b` and `|(ρ²)''|/ρ² ≤ 2a²/ρ² +
    /// 8ab/ρ + 6b²`, and `|f''| ≤ f·(2p² + q)` for those two bounds `p`, `q`. Bilinear
    /// interpolation over `w × h` pixels strays by at most `w²/8·|f_xx| + h²/8·|f_yy|`.
    /// The bounds take `|β|` at its smallest (a corner: `β` is affine and does not
    /// change sign over the block) and `ρ` at its smallest (`|L − m| − ρ`).
    ///
    /// **Clamping.** Each channel's value over the block lies between its sums with every
    /// term at its least and at its largest (0 and its value at `ρ`'s least, or, where
    /// a channel may be clamped, the term's values at the corners widened by its stray);
    /// where that range reaches
    /// past `0..=255` the pixel is clamped, and [`clamped_error`] bounds the stray of the
    /// clamped colour from the stray of the unclamped one and the range.
    fn interpolation_error(
        &self,
        scene: &SceneView<'_, S>,
        object: u8,
        (points, corner_terms): (&[Vec3<S>; 4], &CornerTerms<S>),
        (all, any): ([u32; LIGHTS], [u32; LIGHTS]),
        corners: ((u16, u16), (u16, u16)),
        betas: &[S; 4],
    ) -> Option<[S; 3]> {
        let (w, h) = (corners.0.1 - corners.0.0, corners.1.1 - corners.1.0);
        let o = scene.objects.get(usize::from(object))?;
        let plane = o.shape.plane()?;
        let n = plane.normal();
        let mut m = points[0];
        for p in &points[1..] {
            m = m.sum(*p)?;
        }
        let m = Vec3::new(
            m.x.mul_ratio(1, 4)?,
            m.y.mul_ratio(1, 4)?,
            m.z.mul_ratio(1, 4)?,
        );
        let mut rho_sq = S::ZERO;
        for p in points {
            let d = p.diff(m)?;
            rho_sq = rho_sq.max(d.dot(d)?);
        }
        let rho = rho_sq.checked_sqrt()?.checked_add(S::DELTA)?;
        let materials = materials(scene, o)?;
        // A few DELTAs over each bound below: the roundings of its own steps.
        let slack = S::DELTA.checked_mul_int(4)?;
        let slopes = self.slopes.get(usize::from(object))?;
        // `β` is affine over the block and keeps its sign: its smallest size is at a corner.
        let beta = betas.iter().fold(S::MAX, |m, b| m.min(b.abs()));
        let k = S::from_i32(255)?;
        let (w, h) = (S::from_i32(i32::from(w))?, S::from_i32(i32::from(h))?);
        let sizes = [
            w.checked_mul(w)?.mul_ratio(1, 8)?,
            h.checked_mul(h)?.mul_ratio(1, 8)?,
        ];
        // Per light lighting the whole block: its term's least and largest value over the
        // block, and the bound on its interpolation's stray.
        let mut terms = [None; LIGHTS];
        for (j, (light, term)) in scene.lights.iter().zip(terms.iter_mut()).enumerate() {
            if all[j] != 0 {
                continue; // shadowed (or facing away) everywhere in the block
            }
            if any[j] != 0 {
                return None; // shadowed at some corners only
            }
            let to_m = m.diff(light.location)?;
            for sphere in scene.objects.iter().filter_map(|o| match &o.shape {
                Shape::Sphere(s) => Some(s),
                _ => None,
            }) {
                let margin = sphere.radius().mul_ratio(17, 16)?.checked_add(rho)?;
                let d = distance_sq_to_segment(sphere.center(), light.location, to_m)?;
                // Where the segment to the centroid meets the sphere, no plane parts them.
                if d <= margin.checked_mul(margin)?
                    && (d <= sphere.radius().checked_mul(sphere.radius())?
                        || !pyramid_clear(light.location, points, sphere.center(), sphere.radius()))
                {
                    return None;
                }
            }
            let centre = to_m.dot(to_m)?.checked_sqrt()?;
            let near = centre.checked_sub(rho)?;
            if near <= S::ZERO {
                return None;
            }
            // `N·L` is affine over the plane and keeps its sign over the block (no corner
            // faces away): its extremes are at corners.
            let mut nl_hi = S::ZERO;
            for p in points {
                nl_hi = nl_hi.max(n.dot(light.location.diff(*p)?)?.abs());
            }
            // The term at its largest over the block (at its least it is no less than 0).
            let f = nl_hi.checked_mul(k)?.checked_div(near.checked_mul(near)?)?;
            let mut curvature = S::ZERO;
            for ((a1, beta1), size) in slopes[j]?.into_iter().zip(sizes) {
                let a = a1.checked_div(beta)?;
                let b = beta1.checked_div(beta)?;
                let an = a.checked_div(near)?;
                let p = an.checked_add(b)?.checked_mul_int(2)?;
                let q = an
                    .checked_mul(an)?
                    .checked_mul_int(2)?
                    .checked_add(an.checked_mul(b)?.checked_mul_int(8)?)?
                    .checked_add(b.checked_mul(b)?.checked_mul_int(6)?)?;
                let second = p.checked_mul(p)?.checked_mul_int(2)?.checked_add(q)?;
                // Each rounding above is at most a DELTA: a few more keep the bound one.
                let second = second.checked_add(slack)?;
                curvature = curvature.checked_add(size.checked_mul(second)?)?;
            }
            let stray = f.checked_mul(curvature)?;
            *term = Some((S::ZERO, f.checked_add(slack)?, stray));
        }
        let (error, clamped) = channel_errors(scene, &materials, &terms)?;
        if !clamped || error.iter().all(|e| *e <= self.bound) {
            return Some(error);
        }
        // Where a channel may be clamped, its range decides: narrow each term's to its
        // values at the corners, widened by its stray (the term strays from its
        // interpolation by at most that, and the interpolation lies between them).
        for (j, term) in terms.iter_mut().enumerate() {
            let Some((least, most, stray)) = term else {
                continue;
            };
            // The corners' own terms (each corner is lit by this light).
            let (mut lo, mut hi) = (S::MAX, S::ZERO);
            for at in corner_terms.iter().filter_map(|t| t.get(j)) {
                (lo, hi) = (lo.min(*at), hi.max(*at));
            }
            *least = (*least).max(lo.checked_sub(*stray)?.checked_sub(slack)?);
            *most = (*most).min(hi.checked_add(*stray)?.checked_add(slack)?);
        }
        channel_errors(scene, &materials, &terms).map(|(error, _)| error)
    }
}

/// Per channel, the largest over `materials` of a bound on how far the clamped colour
/// strays from its interpolation over a block, given each light's term there (`None`:
/// the light lights none of the block) as its least and largest value and its stray;
/// and whether a channel may be clamped in the block (only then can a narrower range of
/// the terms narrow the bound).
fn channel_errors<S: Scalar>(
    scene: &SceneView<'_, S>,
    materials: &[&crate::Material<S>],
    terms: &[Option<(S, S, S)>; LIGHTS],
) -> Option<([S; 3], bool)> {
    let (mut error, mut clamped) = ([S::ZERO; 3], false);
    let max = S::from_i32(255)?;
    for material in materials {
        for (c, e) in error.iter_mut().enumerate() {
            let ambient = material.ambient[c];
            let (mut stray, mut lo, mut hi) = (S::ZERO, ambient, ambient);
            for (light, term) in scene.lights.iter().zip(terms) {
                let Some((least, most, own)) = term else {
                    continue;
                };
                let weight = light.emissivity[c].checked_mul(material.diffuse[c])?;
                stray = stray.checked_add(weight.abs().checked_mul(*own)?)?;
                let (a, b) = (weight.checked_mul(*least)?, weight.checked_mul(*most)?);
                lo = lo.checked_add(a.min(b))?;
                hi = hi.checked_add(a.max(b))?;
            }
            clamped |= lo < S::ZERO || hi > max;
            *e = e.max(clamped_error(stray, (lo, hi), max)?);
        }
    }
    Some((error, clamped))
}

/// A bound on how far the bilinear interpolation of a channel clamped to `0..=max` strays
/// from it, over a block where the unclamped channel `f` lies in `lo..=hi` and its own
/// interpolation strays by at most `stray`.
///
/// With `g = clamp(f)`, `g = f − (f − max)⁺ + (−f)⁺`: each of the two cut-off terms and
/// its interpolation lie in `0..=(hi − max)⁺` (or `(−lo)⁺`), so `g`'s interpolation
/// strays by at most `stray + (hi − max)⁺ + (−lo)⁺`. And `g` and its interpolation (a
/// weighted mean of its values at the corners) both lie in `clamp(lo)..=clamp(hi)`, so
/// it strays by at most their difference. Where the channel is not clamped in the block
/// this is `stray` (or less); where it is clamped everywhere, nothing.
fn clamped_error<S: Scalar>(stray: S, (lo, hi): (S, S), max: S) -> Option<S> {
    let cut = hi
        .checked_sub(max)?
        .max(S::ZERO)
        .checked_add(S::ZERO.checked_sub(lo)?.max(S::ZERO))?;
    let clamp = |v: S| v.max(S::ZERO).min(max);
    let range = clamp(hi).checked_sub(clamp(lo))?;
    Some(stray.checked_add(cut)?.min(range))
}

/// The materials of an object: a tiled plane's two (one where both are the same), a
/// plain one's own.
fn materials<'s, S: Scalar>(
    scene: &'s SceneView<'_, S>,
    o: &crate::Object<S>,
) -> Option<heapless::Vec<&'s crate::Material<S>, 2>> {
    let mut all = heapless::Vec::new();
    all.push(scene.materials.get(usize::from(o.material))?)
        .ok()?;
    if let Shape::Tiled { alt, .. } = o.shape
        && alt != o.material
    {
        all.push(scene.materials.get(usize::from(alt))?).ok()?;
    }
    Some(all)
}

/// Whether a sphere (`centre`, `radius`) lies clear of the pyramid from `apex` through
/// the four `points` (a block's corners: top left, top right, bottom left, bottom right),
/// with a sixteenth of its radius to spare: every segment from the apex to a point of
/// the points' convex hull then misses it, as the shadow test decides at its edge (its
/// rounding is within the sixteenth, as in the segment test above).
///
/// A side of the pyramid is the plane through the apex and two neighbouring points; the
/// sphere lies clear of it where its centre lies beyond that plane, on the side away from
/// the other points, by more than `r·17/16`. Beside an edge of the pyramid (the ray to a
/// point), the plane through that ray facing the centre's nearest point `m` of its line
/// separates them where every point lies on or behind it and `|m| > r·17/16`.
pub(super) fn pyramid_clear<S: Scalar>(
    apex: Vec3<S>,
    points: &[Vec3<S>; 4],
    centre: Vec3<S>,
    radius: S,
) -> bool {
    let (Some(c), Some(margin)) = (centre.diff(apex), radius.mul_ratio(17, 16)) else {
        return false;
    };
    // The rays in turn round the block.
    let mut d = [c; 4];
    for (ray, k) in d.iter_mut().zip([0, 1, 3, 2]) {
        match points[k].diff(apex) {
            Some(v) => *ray = v,
            None => return false,
        }
    }
    let side = |i: usize| -> Option<bool> {
        let (a, b) = (d[i], d[(i + 1) % 4]);
        let n = a.cross(b.diff(a)?)?;
        // The other two points lie on the inner side.
        let inner = n.dot(d[(i + 2) % 4].sum(d[(i + 3) % 4])?)?;
        if inner == S::ZERO {
            return Some(false);
        }
        let beyond = n.dot(c)?;
        let beyond = if inner > S::ZERO {
            S::ZERO.checked_sub(beyond)?
        } else {
            beyond
        };
        let length = n.dot(n)?.checked_sqrt()?.checked_add(S::DELTA)?;
        Some(beyond > margin.checked_mul(length)?)
    };
    let edge = |i: usize| -> Option<bool> {
        let a = d[i];
        let t = c.dot(a)?.checked_div(a.dot(a)?)?;
        let m = c.diff(a.scale(t)?)?;
        let behind = d.iter().all(|q| m.dot(*q).is_some_and(|v| v <= S::ZERO));
        Some(behind && t > S::ZERO && m.dot(m)? > margin.checked_mul(margin)?)
    };
    (0..4).any(|i| side(i) == Some(true) || edge(i) == Some(true))
}

/// The squared distance from `c` to the segment from `a` to `a + v`.
fn distance_sq_to_segment<S: Scalar>(c: Vec3<S>, a: Vec3<S>, v: Vec3<S>) -> Option<S> {
    let w = c.diff(a)?;
    let wv = w.dot(v)?;
    let vv = v.dot(v)?;
    let s = if wv <= S::ZERO || vv <= S::ZERO {
        S::ZERO
    } else if wv >= vv {
        S::ONE
    } else {
        wv.checked_div(vv)?
    };
    let d = w.diff(v.scale(s)?)?;
    d.dot(d)
}

#[cfg(test)]
mod tests {
    use super::{clamped_error, pyramid_clear};
    use crate::Vec3;
    use crate::num::unit_reals;
    use fixed::types::I16F16;

    /// Seeded functions on a segment, each its linear interpolation plus a bump within
    /// `stray` that vanishes at the ends, around 0 or around 255, some crossing a limit:
    /// the interpolation of the clamped function's end values stays within
    /// `clamped_error` of the clamped function everywhere (the range given is the
    /// function's over the segment, or wider).
    #[test]
    fn a_clamped_function_strays_within_its_bound() {
        let mut real = unit_reals(0x5EED_C1A3_0001);
        let clamp = |v: f64| v.clamp(0.0, 255.0);
        let (mut crossing, mut checked) = (0, 0);
        for _ in 0..20_000 {
            let limit = if real() < 0.5 { 0.0 } else { 255.0 };
            let (a, b) = (limit + 60.0 * real() - 30.0, limit + 60.0 * real() - 30.0);
            let stray = 10.0 * real() * real();
            let bump = stray * (2.0 * real() - 1.0);
            let f = |u: f64| a + (b - a) * u + bump * 4.0 * u * (1.0 - u);
            let samples: Vec<f64> = (0..=64).map(|i| f(f64::from(i) / 64.0)).collect();
            let widen = 5.0 * real();
            let lo = samples.iter().copied().fold(f64::MAX, f64::min) - widen;
            let hi = samples.iter().copied().fold(f64::MIN, f64::max) + widen;
            let s = |v: f64| I16F16::from_num(v);
            let bound = clamped_error(s(stray), (s(lo), s(hi)), s(255.0))
                .unwrap()
                .to_num::<f64>();
            if (lo < 0.0 && hi > 0.0) || (lo < 255.0 && hi > 255.0) {
                crossing += 1;
            }
            for (i, v) in samples.iter().enumerate() {
                let u = i as f64 / 64.0;
                let interpolated = clamp(a) + (clamp(b) - clamp(a)) * u;
                let off = (interpolated - clamp(*v)).abs();
                assert!(off <= bound + 1e-3, "{a} {b} {bump}: {off} > {bound}");
                checked += 1;
            }
        }
        assert!(crossing > 5_000 && checked > 1_000_000);
    }

    /// Seeded lights, blocks (a rectangle's corners on a plane of any slope) and spheres:
    /// where `pyramid_clear` says a sphere is clear, no segment from the light to a point
    /// of the block (a grid over it, corners included) passes within the radius and most
    /// of its sixteenth of the centre; and most spheres that clear every segment by the
    /// whole sixteenth are found clear.
    #[test]
    fn a_sphere_clear_of_the_light_pyramid_shadows_no_point_of_the_block() {
        let mut real = unit_reals(0x5EED_C1EA_0002);
        let s = |v: f64| I16F16::from_num(v);
        let v3 = |v: [f64; 3]| Vec3::new(s(v[0]), s(v[1]), s(v[2]));
        let (mut clear, mut missed, mut free) = (0, 0, 0);
        for _ in 0..20_000 {
            let r3 = |real: &mut dyn FnMut() -> f64, scale: f64| {
                [0; 3].map(|_| scale * (2.0 * real() - 1.0))
            };
            let light = r3(&mut real, 8.0);
            let origin = r3(&mut real, 4.0);
            let (u, v) = (r3(&mut real, 1.0), r3(&mut real, 1.0));
            let (wu, wv) = (0.05 + 0.5 * real(), 0.05 + 0.5 * real());
            let at = |a: f64, b: f64| [0, 1, 2].map(|i| origin[i] + a * wu * u[i] + b * wv * v[i]);
            let corners = [at(0.0, 0.0), at(1.0, 0.0), at(0.0, 1.0), at(1.0, 1.0)];
            // A sphere near the segments: on one of them, pushed aside.
            let (ta, pa, pb) = (0.2 + 0.7 * real(), real(), real());
            let p = at(pa, pb);
            let push = r3(&mut real, 1.0);
            let centre = [0, 1, 2].map(|i| light[i] + ta * (p[i] - light[i]) + push[i]);
            let r = 0.1 + 0.6 * real();
            let quantised = |x: [f64; 3]| [0, 1, 2].map(|i| s(x[i]).to_num::<f64>());
            let (l, c) = (quantised(light), quantised(centre));
            let r = s(r).to_num::<f64>();
            // The least distance from the centre to the segments to a grid of the block.
            let mut least = f64::MAX;
            for i in 0..=8 {
                for j in 0..=8 {
                    let q = at(f64::from(i) / 8.0, f64::from(j) / 8.0);
                    let d = [0, 1, 2].map(|k| q[k] - l[k]);
                    let w = [0, 1, 2].map(|k| c[k] - l[k]);
                    let dd: f64 = d.iter().map(|x| x * x).sum();
                    let t =
                        (d.iter().zip(&w).map(|(a, b)| a * b).sum::<f64>() / dd).clamp(0.0, 1.0);
                    let gap: f64 = (0..3).map(|k| (w[k] - t * d[k]).powi(2)).sum();
                    least = least.min(gap.sqrt());
                }
            }
            let points = corners.map(v3);
            if pyramid_clear(v3(light), &points, v3(centre), s(r)) {
                clear += 1;
                assert!(
                    least > r * (1.0 + 1.0 / 20.0),
                    "{light:?} {corners:?} {centre:?} {r}: {least}"
                );
            } else if least > r * 1.5 {
                missed += 1;
            }
            if least > r * 1.5 {
                free += 1;
            }
        }
        assert!(clear > 4_000, "{clear} clear");
        assert!(
            missed * 4 < free,
            "{missed} of {free} clear spheres not found"
        );
    }
}
