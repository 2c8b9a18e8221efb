//! Whether a block may be filled: its certificate ([`Sampler::certifies`]).

use super::corners::{Corner, Sees};
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
        let (mut all, mut any) = ([u32::MAX; LIGHTS], [0; LIGHTS]);
        for ((slot, tile), seen) in points.iter_mut().zip(tiles.iter_mut()).zip(seen) {
            let Sees::Plane {
                object: o,
                tile: t,
                point,
                shadows,
            } = seen
            else {
                return None;
            };
            if o != object {
                return None;
            }
            (*slot, *tile) = (point, t);
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
        let error = self.interpolation_error(scene, object, &points, (all, any), (x, y), &beta)?;
        if error.iter().any(|c| *c > self.bound) {
            return None;
        }
        if tiles.iter().all(|t| *t == tiles[0]) {
            return Some(Fill::Smooth(colors));
        }
        // Across a tile's edge: only with a bound (the colours are this module's own).
        let lit = core::array::from_fn(|j| all[j] == 0);
        if self.bound > S::ZERO {
            tiles_fill(scene, object, (&points, &tiles), lit, (x, y), beta)
        } else {
            None
        }
    }

    /// A bound, per channel, on how far the colour of plane `object` strays from the
    /// bilinear interpolation of its values at the corners over the block whose corner
    /// pixels are at columns and rows `corners` and hit it at `points`, given each light's occluders common to all
    /// corners (`all`) and found at any (`any`); `None` where the shadow state may change
    /// inside the block, a channel may reach 255 (where it is clamped, the colour is not
    /// smooth) or a quantity leaves the format.
    ///
    /// **Shadows.** The block's points lie within `ρ` of the corners' centroid `m` (the
    /// largest distance from it to a corner: the block is their convex hull). A segment
    /// from the light to such a point lies within `ρ` of the segment to `m` (point for
    /// point), so a sphere farther than `r·17/16 + ρ` from that segment shadows none of
    /// them (the sixteenth: the shadow test's rounding at its edge).
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
    fn interpolation_error(
        &self,
        scene: &SceneView<'_, S>,
        object: u8,
        points: &[Vec3<S>; 4],
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
        let (diffuse, ambient) = materials_bound(scene, o)?;
        let slopes = self.slopes.get(usize::from(object))?;
        // `β` is affine over the block and keeps its sign: its smallest size is at a corner.
        let beta = betas.iter().fold(S::MAX, |m, b| m.min(b.abs()));
        let k = S::from_i32(255)?;
        let (w, h) = (S::from_i32(i32::from(w))?, S::from_i32(i32::from(h))?);
        let sizes = [
            w.checked_mul(w)?.mul_ratio(1, 8)?,
            h.checked_mul(h)?.mul_ratio(1, 8)?,
        ];
        let mut error = [S::ZERO; 3];
        let mut top = ambient;
        for (j, light) in scene.lights.iter().enumerate() {
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
                if d <= margin.checked_mul(margin)? {
                    return None;
                }
            }
            let near = to_m.dot(to_m)?.checked_sqrt()?.checked_sub(rho)?;
            if near <= S::ZERO {
                return None;
            }
            let mut nl = S::ZERO;
            for p in points {
                nl = nl.max(n.dot(light.location.diff(*p)?)?.abs());
            }
            // The term at its largest.
            let f = nl.checked_mul(k)?.checked_div(near.checked_mul(near)?)?;
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
                let second = second.checked_add(S::DELTA.checked_mul_int(4)?)?;
                curvature = curvature.checked_add(size.checked_mul(second)?)?;
            }
            let stray = f.checked_mul(curvature)?;
            for (((e, t), c), d) in error
                .iter_mut()
                .zip(top.iter_mut())
                .zip(light.emissivity)
                .zip(diffuse)
            {
                let weight = c.abs().checked_mul(d)?;
                *e = e.checked_add(weight.checked_mul(stray)?)?;
                *t = t.checked_add(weight.checked_mul(f)?)?;
            }
        }
        if top.iter().any(|t| *t >= k) {
            return None;
        }
        Some(error)
    }
}

/// The larger per-channel diffuse and ambient of an object's materials (a tiled plane
/// has two).
fn materials_bound<S: Scalar>(
    scene: &SceneView<'_, S>,
    o: &crate::Object<S>,
) -> Option<([S; 3], [S; 3])> {
    let first = scene.materials.get(usize::from(o.material))?;
    let (mut d, mut a) = (first.diffuse.map(S::abs), first.ambient.map(S::abs));
    if let Shape::Tiled { alt, .. } = o.shape {
        let alt = scene.materials.get(usize::from(alt))?;
        for (x, y) in d.iter_mut().zip(alt.diffuse) {
            *x = x.max(y.abs());
        }
        for (x, y) in a.iter_mut().zip(alt.ambient) {
            *x = x.max(y.abs());
        }
    }
    Some((d, a))
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
