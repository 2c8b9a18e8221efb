//! Filling a certified block from its corners: bilinear interpolation, and across a
//! tile's edge the edge's line located on the screen.

use core::ops::Range;

use embedded_graphics_core::pixelcolor::Rgb888;

use super::LIGHTS;
use super::corners::plane_color;
use crate::geometry::Tiling;
use crate::{Scalar, SceneView, Shape, Vec3};

/// How a certified block is filled.
#[derive(Debug, Clone, Copy)]
pub(super) enum Fill<S> {
    /// From its corners' colours (top left, top right, bottom left, bottom right).
    Smooth([Rgb888; 4]),
    /// A tiled plane across one tile edge or two: each pixel's tile from the edges'
    /// lines located on the screen, its colour interpolated from the corners' colours in
    /// that tile's material.
    Tiles(Tiles<S>),
}

/// A block of a tiled plane that crosses a tile edge along `u`, along `v`, or both.
#[derive(Debug, Clone, Copy)]
pub(super) struct Tiles<S> {
    /// The corners' colours in the plane's material and in its alternate.
    colors: [[Rgb888; 4]; 2],
    /// Per axis: the corners' `(a − A)·β` for the edge `a = A` between the block's two
    /// tiles (`β = N·D`, so that it is affine on the screen), or `None` where the block
    /// lies in one tile along that axis.
    edges: [Option<[S; 4]>; 2],
    /// The lower tile along each axis.
    first: (i32, i32),
    /// Whether `β` is negative over the block (the sides are then swapped).
    negative: bool,
}

/// `β = N·D` of the rays through a block's corner pixels (columns `x`, rows `y`: top
/// left, top right, bottom left, bottom right), `D` the unnormalised direction from the
/// eye to the pixel's point of the window; `None` where one is zero, where they differ in
/// sign (the plane is edge-on within the block), or out of range.
pub(super) fn corner_betas<S: Scalar>(
    scene: &SceneView<'_, S>,
    n: Vec3<S>,
    (x, y): ((u16, u16), (u16, u16)),
) -> Option<[S; 4]> {
    let camera = &scene.camera;
    let eye = camera.viewpoint;
    let mut beta = [S::ZERO; 4];
    for (b, (c, r)) in beta
        .iter_mut()
        .zip([(x.0, y.0), (x.1, y.0), (x.0, y.1), (x.1, y.1)])
    {
        let d = Vec3::new(camera.screen_x(c)?, camera.screen_y(r)?, S::ZERO).diff(eye)?;
        *b = n.dot(d)?;
    }
    let negative = beta[0] < S::ZERO;
    let same = beta
        .iter()
        .all(|b| (*b < S::ZERO) == negative && *b != S::ZERO);
    same.then_some(beta)
}

/// The fill of a block of tiled plane `object` whose corners (at `points`, in `tiles`)
/// lie in at most two tiles along each axis, under the lights `lit` (lit everywhere in
/// the block; the others light none of it), over columns `x` and rows `y`, with `β` at
/// its corner pixels ([`corner_betas`]).
pub(super) fn tiles_fill<S: Scalar>(
    scene: &SceneView<'_, S>,
    object: u8,
    (points, tiles): (&[Vec3<S>; 4], &[(i32, i32); 4]),
    lit: [bool; LIGHTS],
    (x, y): ((u16, u16), (u16, u16)),
    beta: [S; 4],
) -> Option<Fill<S>> {
    let o = scene.objects.get(usize::from(object))?;
    let Shape::Tiled {
        frame,
        alt,
        tiling: Tiling::Frame,
    } = &o.shape
    else {
        return None;
    };
    let first = (
        tiles.iter().map(|t| t.0).min()?,
        tiles.iter().map(|t| t.1).min()?,
    );
    let last = (
        tiles.iter().map(|t| t.0).max()?,
        tiles.iter().map(|t| t.1).max()?,
    );
    if last.0.abs_diff(first.0) > 1 || last.1.abs_diff(first.1) > 1 {
        return None;
    }
    let negative = beta[0] < S::ZERO;
    let size = frame.size();
    let mut edges = [None; 2];
    for (axis, edge) in edges.iter_mut().enumerate() {
        let (lo, hi) = if axis == 0 {
            (first.0, last.0)
        } else {
            (first.1, last.1)
        };
        if lo == hi {
            continue;
        }
        let bound = size[axis].checked_mul(S::from_i32(hi)?)?;
        let mut values = [S::ZERO; 4];
        let mut largest = S::ZERO;
        for ((v, p), b) in values.iter_mut().zip(points).zip(beta) {
            let (a, c) = frame.coords(*p)?;
            let coord = if axis == 0 { a } else { c };
            *v = coord.checked_sub(bound)?.checked_mul(b)?;
            largest = largest.max(v.abs());
        }
        // A pixel's interpolated value sums the four weighted by at most `w·h` in all:
        // where that may not fit, the block is traced (the side could not be told).
        let (w, h) = (i32::from(x.1 - x.0).max(1), i32::from(y.1 - y.0).max(1));
        largest.checked_mul_int(4 * w * h)?;
        *edge = Some(values);
    }
    let own = scene.materials.get(usize::from(o.material))?;
    let other = scene.materials.get(usize::from(*alt))?;
    let mut colors = [[Rgb888::new(0, 0, 0); 4]; 2];
    for (material, out) in [own, other].into_iter().zip(colors.iter_mut()) {
        for (slot, p) in out.iter_mut().zip(points) {
            *slot = plane_color(scene, frame.plane(), material, *p, lit)?;
        }
    }
    Some(Fill::Tiles(Tiles {
        colors,
        edges,
        first,
        negative,
    }))
}

/// Fills the pixels `rows × columns` of a block over columns `x` and rows `y` (its
/// corners') as `how` says: each pixel the bilinear interpolation of four corner colours
/// (rounded to nearest), in a tiled block those of the pixel's tile's material. Along a
/// row the interpolation is affine: each channel steps by one addition a pixel.
pub(super) fn fill<S: Scalar, C: From<Rgb888>>(
    (how, x, y): (&Fill<S>, (u16, u16), (u16, u16)),
    (rows, columns): (Range<u16>, Range<u16>),
    (out, stride, origin): (&mut [C], usize, (u16, u16)),
) {
    use embedded_graphics_core::pixelcolor::RgbColor;
    let w = i32::from(x.1 - x.0).max(1);
    let h = i32::from(y.1 - y.0).max(1);
    let area = w * h;
    // A whole block's area is a power of two: a shift, not a division.
    let shift = (area.count_ones() == 1).then(|| area.trailing_zeros());
    let divide = |v: i32| {
        let v = v + area / 2;
        let q = match shift {
            Some(s) => v >> s,
            None => v / area,
        };
        u8::try_from(q.clamp(0, 255)).unwrap_or(u8::MAX)
    };
    let channels = |c: Rgb888| [i32::from(c.r()), i32::from(c.g()), i32::from(c.b())];
    let sets = match how {
        Fill::Smooth(colors) => [colors.map(channels); 2],
        Fill::Tiles(t) => t.colors.map(|set| set.map(channels)),
    };
    let u0 = i32::from(columns.start - x.0);
    for r in rows {
        let v = i32::from(r - y.0).min(h);
        // Per colour set and channel: the value at the row's first column (times the
        // area) and its step.
        let mut value = [[0; 3]; 2];
        let mut step = [[0; 3]; 2];
        for (set, (val, st)) in sets.iter().zip(value.iter_mut().zip(step.iter_mut())) {
            for i in 0..3 {
                let left = set[0][i] * (h - v) + set[2][i] * v;
                let right = set[1][i] * (h - v) + set[3][i] * v;
                st[i] = right - left;
                val[i] = left * w + st[i] * u0;
            }
        }
        let edges = match how {
            Fill::Tiles(t) => Some((t, t.row_edges(v, h))),
            Fill::Smooth(_) => None,
        };
        let row = usize::from(r - origin.0) * stride;
        for (k, col) in columns.clone().enumerate() {
            let u = u0 + i32::try_from(k).unwrap_or(0);
            let set = match &edges {
                Some((t, e)) if t.odd(e, u, w) => 1,
                _ => 0,
            };
            let c = value[set].map(divide);
            for (val, st) in value.iter_mut().zip(step) {
                for (a, b) in val.iter_mut().zip(st) {
                    *a += b;
                }
            }
            if let Some(p) = out.get_mut(row + usize::from(col - origin.1)) {
                *p = C::from(Rgb888::new(c[0], c[1], c[2]));
            }
        }
    }
}

impl<S: Scalar> Tiles<S> {
    /// Each edge's interpolated `(a − A)·β` at the left and right ends of the block's row
    /// `v` (of `h`), times `h`.
    fn row_edges(&self, v: i32, h: i32) -> [Option<(S, S)>; 2] {
        self.edges.map(|e| {
            let [tl, tr, bl, br] = e?;
            let side = |top: S, bottom: S| {
                top.checked_mul_int(h - v)?
                    .checked_add(bottom.checked_mul_int(v)?)
            };
            Some((side(tl, bl)?, side(tr, br)?))
        })
    }

    /// Whether column `u` (of `w`) of the row whose edges are `edges` ([`Tiles::row_edges`])
    /// lies on an odd tile: on each axis the block crosses, the side of the edge's line
    /// its interpolated `(a − A)·β` gives (exact for a function affine on the screen).
    /// `a ≥ A` puts it on the upper tile (as `floor` puts a point on the edge): `(a −
    /// A)·β` has `β`'s sign there, or is zero.
    fn odd(&self, edges: &[Option<(S, S)>; 2], u: i32, w: i32) -> bool {
        let mut tile = [self.first.0, self.first.1];
        for ((index, edge), crosses) in tile.iter_mut().zip(edges).zip(self.edges) {
            if crosses.is_none() {
                continue;
            }
            let Some(sum) = edge.and_then(|(left, right)| {
                left.checked_mul_int(w - u)?
                    .checked_add(right.checked_mul_int(u)?)
            }) else {
                return false;
            };
            let upper = if self.negative {
                sum <= S::ZERO
            } else {
                sum >= S::ZERO
            };
            if upper {
                *index += 1;
            }
        }
        (tile[0].wrapping_add(tile[1])) & 1 == 1
    }
}
