//! Filling a certified block from its corners: bilinear interpolation, and across a
//! tile's edge the edge's line located on the screen.

use core::ops::Range;

use embedded_graphics_core::pixelcolor::Rgb888;

use super::LIGHTS;
use super::corners::{CornerTerms, plane_color};
use crate::geometry::Tiling;
use crate::{Scalar, SceneView, Shape, Vec3};

/// Per axis of a tiled block, an edge's interpolated side at the left and right ends of
/// a row ([`Tiles::row_edges`]; `None`: the block does not cross that axis's edge, or
/// the side does not fit).
type RowEdges<S> = [Option<(S, S)>; 2];

/// A tiled block's corners for [`tiles_fill`]: their points, their tiles, and each one's
/// colour in its own tile's material where the caller has it.
pub(super) type TiledCorners<'a, S> = (&'a [Vec3<S>; 4], &'a [(i32, i32); 4], [Option<Rgb888>; 4]);

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

/// The fill of a block of tiled plane `object` whose corners (at `points`, in `tiles`,
/// each light's term there `terms`) lie in at most two tiles along each axis, under the
/// lights `lit` (lit everywhere in
/// the block; the others light none of it), over columns `x` and rows `y`, with `β` at
/// its corner pixels ([`corner_betas`]). `known`: a corner's colour in its own tile's
/// material under the lights `lit`, where its caller has it ([`plane_color`]'s, not
/// formed again).
pub(super) fn tiles_fill<S: Scalar>(
    scene: &SceneView<'_, S>,
    object: u8,
    (points, tiles, known): TiledCorners<'_, S>,
    terms: &CornerTerms<S>,
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
    for (parity, (material, out)) in [own, other].into_iter().zip(colors.iter_mut()).enumerate() {
        for (((slot, terms), tile), known) in out.iter_mut().zip(terms).zip(tiles).zip(known) {
            let odd = usize::from((tile.0.wrapping_add(tile.1)) & 1 == 1);
            *slot = match known {
                Some(color) if odd == parity => color,
                _ => plane_color(scene, material, terms, lit)?,
            };
        }
    }
    Some(Fill::Tiles(Tiles {
        colors,
        edges,
        first,
        negative,
    }))
}

/// Fills pixels `rows × columns` of a block over columns `x`, rows `y` (its corners',
/// inclusive; `rows × columns` lie within) as `how` says: each pixel the bilinear
/// interpolation of four corner colours (rounded to nearest), in a tiled block those of
/// the pixel's tile's material. Along a row the interpolation is affine: each channel
/// steps by one addition a pixel, and so does each tile edge's side ([`EdgeSteps`]), in
/// integers where the format's sums and products are exact.
pub(super) fn fill<S: Scalar, C: From<Rgb888>>(
    (how, x, y): (&Fill<S>, (u16, u16), (u16, u16)),
    (rows, columns): (Range<u16>, Range<u16>),
    (out, stride, origin): (&mut [C], usize, (u16, u16)),
) {
    use embedded_graphics_core::pixelcolor::RgbColor;
    let w = i32::from(x.1 - x.0).max(1);
    let h = i32::from(y.1 - y.0).max(1);
    let round = Rounding::new(w * h);
    let channels = |c: Rgb888| [i32::from(c.r()), i32::from(c.g()), i32::from(c.b())];
    let u0 = i32::from(columns.start - x.0);
    // A tiled block's edges on the row before (its `v`), stepped a row by an addition
    // where the format's sums are exact (the same values as `row_edges`).
    let mut before: Option<(i32, RowEdges<S>)> = None;
    for r in rows {
        let v = i32::from(r - y.0).min(h);
        let row = usize::from(r - origin.0) * stride;
        // The row's pixels that `out` holds.
        let Some(line) = out.get_mut(row + usize::from(columns.start - origin.1)..) else {
            continue;
        };
        let len = columns.len().min(line.len());
        let line = &mut line[..len];
        match how {
            Fill::Smooth(colors) => {
                let (mut value, step) = row_start(&colors.map(channels), (v, h), (u0, w));
                value = value.map(|c| c + round.half());
                for p in line.iter_mut() {
                    *p = round.pixel(value);
                    for (a, b) in value.iter_mut().zip(step) {
                        *a += b;
                    }
                }
            }
            Fill::Tiles(t) => {
                // Each set's start and step; a pixel takes its set's `start + k·step` (two
                // sets stepped together would not stay in a small core's registers).
                let starts = t.colors.map(|set| {
                    let (start, step) = row_start(&set.map(channels), (v, h), (u0, w));
                    (start.map(|c| c + round.half()), step)
                });
                let edges = match before {
                    Some((b, edges)) if b + 1 == v => t.step_edges(edges),
                    _ => None,
                }
                .unwrap_or_else(|| t.row_edges(v, h));
                if S::EXACT_SUMS {
                    before = Some((v, edges));
                }
                let mut stepped = EdgeSteps::new(t, &edges, (u0, w));
                for (k, p) in (0i32..).zip(line.iter_mut()) {
                    let odd = match stepped.as_mut() {
                        Some(s) => s.next_odd(),
                        None => t.odd(&edges, u0 + k, w),
                    };
                    let (start, step) = &starts[usize::from(odd)];
                    *p = round.pixel([
                        start[0] + k * step[0],
                        start[1] + k * step[1],
                        start[2] + k * step[2],
                    ]);
                }
            }
        }
    }
}

/// A colour set's interpolation on row `v` (of `h`) from column `u0` (of `w`): each
/// channel's value times the block's area there, and its step a column.
#[inline(always)]
fn row_start(set: &[[i32; 3]; 4], (v, h): (i32, i32), (u0, w): (i32, i32)) -> ([i32; 3], [i32; 3]) {
    let mut value = [0; 3];
    let mut step = [0; 3];
    for i in 0..3 {
        let left = set[0][i] * (h - v) + set[2][i] * v;
        let right = set[1][i] * (h - v) + set[3][i] * v;
        step[i] = right - left;
        value[i] = left * w + step[i] * u0;
    }
    (value, step)
}

/// Rounding an interpolated channel (times the block's area) to a pixel value: to
/// nearest, by a shift where the area is a power of two (a whole block).
#[derive(Clone, Copy)]
struct Rounding {
    area: i32,
    shift: Option<u32>,
}

impl Rounding {
    fn new(area: i32) -> Self {
        Self {
            area,
            shift: (area.count_ones() == 1).then(|| area.trailing_zeros()),
        }
    }

    /// A channel's value `v` (times the area, plus half the area: [`Rounding::half`])
    /// rounded. `v` lies in `0..=255·area + area/2` (the interpolation of values in
    /// `0..=255` at a point of the block, a weighted mean), so the quotient is in
    /// `0..=255`.
    #[inline(always)]
    fn channel(self, v: i32) -> u8 {
        let q = match self.shift {
            Some(s) => v >> s,
            None => v / self.area,
        };
        // The precondition above, checked where debug assertions are on (the tests'
        // builds): the cast keeps the quotient itself.
        debug_assert!((0..=255).contains(&q), "a fill's channel {q} out of 0..=255");
        q as u8
    }

    /// Half the area, added once to a row's start values so that [`Rounding::channel`]
    /// rounds to nearest.
    fn half(self) -> i32 {
        self.area / 2
    }

    #[inline(always)]
    fn pixel<C: From<Rgb888>>(self, value: [i32; 3]) -> C {
        C::from(Rgb888::new(
            self.channel(value[0]),
            self.channel(value[1]),
            self.channel(value[2]),
        ))
    }
}

/// A tiled block's row, its tile edges' sides stepped column by column: what
/// [`Tiles::odd`] computes at each column, one addition a column instead of two
/// products. Only where the format's products and sums are exact (the sides are then
/// the same integers either way; `None` otherwise, or where a start does not fit:
/// each column then takes [`Tiles::odd`]).
struct EdgeSteps<S> {
    /// Per axis: the side's value at the current column and its step (`None`: the
    /// block lies in one tile along that axis).
    sides: [Option<(S, S)>; 2],
    first: [i32; 2],
    negative: bool,
}

impl<S: Scalar> EdgeSteps<S> {
    fn new(t: &Tiles<S>, edges: &RowEdges<S>, (u0, w): (i32, i32)) -> Option<Self> {
        if !(S::EXACT_SUMS && S::EXACT_PRODUCTS) {
            return None;
        }
        let mut sides = [None; 2];
        for ((side, edge), crosses) in sides.iter_mut().zip(edges).zip(t.edges) {
            if crosses.is_none() {
                continue;
            }
            // As `odd` at `u0`; a side that does not fit there is `odd`'s to decide.
            let (left, right) = (*edge)?;
            let start = times(left, w - u0)?.checked_add(times(right, u0)?)?;
            *side = Some((start, right.checked_sub(left)?));
        }
        Some(Self {
            sides,
            first: [t.first.0, t.first.1],
            negative: t.negative,
        })
    }

    /// Whether the current column lies on an odd tile (as [`Tiles::odd`]), then steps to
    /// the next column. Every column of the block's row is `left·(w − u) + right·u`, within
    /// the bound the block was certified with (`tiles_fill`: four times the largest
    /// corner value times `w·h`), so no step overflows; one that would ends on the
    /// block's last column, whose value is not read.
    #[inline(always)]
    fn next_odd(&mut self) -> bool {
        let mut tile = self.first;
        for (index, side) in tile.iter_mut().zip(self.sides.iter_mut()) {
            let Some((sum, step)) = side else {
                continue;
            };
            let upper = if self.negative {
                *sum <= S::ZERO
            } else {
                *sum >= S::ZERO
            };
            if upper {
                *index += 1;
            }
            *sum = sum.checked_add(*step).unwrap_or(*sum);
        }
        (tile[0].wrapping_add(tile[1])) & 1 == 1
    }
}

/// `x·n`, as `checked_mul_int` (its value, and `None` where it overflows), by additions
/// where `n` is 0 or a power of two up to 8 (a block's side: `x` doubled, exact in the
/// formats this is called in, whose sums are exact).
#[inline(always)]
fn times<S: Scalar>(x: S, n: i32) -> Option<S> {
    match n {
        0 => Some(S::ZERO),
        1 => Some(x),
        2 => x.checked_add(x),
        4 => {
            let d = x.checked_add(x)?;
            d.checked_add(d)
        }
        8 => {
            let d = x.checked_add(x)?;
            let q = d.checked_add(d)?;
            q.checked_add(q)
        }
        _ => x.checked_mul_int(n),
    }
}

impl<S: Scalar> Tiles<S> {
    /// [`Tiles::row_edges`] of the next row from this row's: each end's value steps by
    /// its bottom corner's minus its top corner's (`top·(h − v) + bottom·v`, one more
    /// `v`), exact where the format's sums are. `None` where a step does not fit or a
    /// side of this row did not.
    fn step_edges(&self, edges: RowEdges<S>) -> Option<RowEdges<S>> {
        let mut next = [None; 2];
        for ((slot, edge), corners) in next.iter_mut().zip(edges).zip(self.edges) {
            let Some([tl, tr, bl, br]) = corners else {
                continue;
            };
            // A row whose side did not fit is `row_edges`' to redo.
            let (left, right) = edge?;
            let left = left.checked_add(bl.checked_sub(tl)?)?;
            *slot = Some((left, right.checked_add(br.checked_sub(tr)?)?));
        }
        Some(next)
    }

    /// Each edge's interpolated `(a − A)·β` at the left and right ends of the block's row
    /// `v` (of `h`), times `h`.
    fn row_edges(&self, v: i32, h: i32) -> RowEdges<S> {
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
    fn odd(&self, edges: &RowEdges<S>, u: i32, w: i32) -> bool {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Rng;
    use fixed::types::{I16F16, I20F12};

    /// A whole number in `0..n` from the tests' seeded sequence.
    fn below(rng: &mut Rng, n: u32) -> i32 {
        i32::try_from(rng.below(n)).unwrap_or(0)
    }

    /// The fill as it is defined, pixel by pixel: each pixel's bilinear value from the
    /// four corners, its tile from [`Tiles::odd`] (two products a column).
    fn fill_by_pixel<S: Scalar>(
        how: &Fill<S>,
        (x, y): ((u16, u16), (u16, u16)),
        (rows, columns): (Range<u16>, Range<u16>),
    ) -> Vec<Rgb888> {
        use embedded_graphics_core::pixelcolor::RgbColor;
        let w = i32::from(x.1 - x.0).max(1);
        let h = i32::from(y.1 - y.0).max(1);
        let area = w * h;
        let channels = |c: Rgb888| [i32::from(c.r()), i32::from(c.g()), i32::from(c.b())];
        let sets = match how {
            Fill::Smooth(colors) => [colors.map(channels); 2],
            Fill::Tiles(t) => t.colors.map(|set| set.map(channels)),
        };
        let mut out = Vec::new();
        for r in rows {
            let v = i32::from(r - y.0).min(h);
            let edges = match how {
                Fill::Tiles(t) => Some((t, t.row_edges(v, h))),
                Fill::Smooth(_) => None,
            };
            for col in columns.clone() {
                let u = i32::from(col - x.0);
                let set = match &edges {
                    Some((t, e)) if t.odd(e, u, w) => &sets[1],
                    _ => &sets[0],
                };
                let c = [0, 1, 2].map(|i| {
                    let value = set[0][i] * (h - v) * (w - u)
                        + set[1][i] * (h - v) * u
                        + set[2][i] * v * (w - u)
                        + set[3][i] * v * u;
                    let q = (value + area / 2).div_euclid(area);
                    u8::try_from(q.clamp(0, 255)).unwrap_or(u8::MAX)
                });
                out.push(Rgb888::new(c[0], c[1], c[2]));
            }
        }
        out
    }

    fn corners(rng: &mut Rng) -> [Rgb888; 4] {
        [0; 4].map(|_: i32| {
            let mut c = || u8::try_from(rng.next() % 256).unwrap_or(0);
            Rgb888::new(c(), c(), c())
        })
    }

    /// Four corner sides within `±limit`, some of either sign.
    fn sides<S: Scalar>(rng: &mut Rng, limit: f64) -> [S; 4] {
        [0; 4].map(|_: i32| {
            let f = (rng.next() % 2001) as f64 / 1000.0 - 1.0;
            S::from_f64(f * limit * 0.999).unwrap_or(S::ZERO)
        })
    }

    /// Seeded blocks, smooth and tiled (crossing one tile edge or two, either sign of
    /// `β`, sides within the bound `tiles_fill` certifies), whole and in part: [`fill`]
    /// (stepped colours, stepped tile sides) draws what [`fill_by_pixel`] draws, bit for
    /// bit, in each fixed format.
    fn fills_are_the_pixels_definition<S: Scalar>(seed: u64) {
        let mut rng = Rng(seed);
        let mut tiled = 0;
        for _ in 0..4000 {
            let (w, h) = (1 + below(&mut rng, 8), 1 + below(&mut rng, 8));
            let (x0, y0) = (u16::try_from(below(&mut rng, 50)).unwrap_or(0), 3u16);
            let x = (x0, x0 + u16::try_from(w).unwrap_or(1));
            let y = (y0, y0 + u16::try_from(h).unwrap_or(1));
            let how = if rng.next().is_multiple_of(4) {
                Fill::Smooth(corners(&mut rng))
            } else {
                tiled += 1;
                // Corner sides up to the largest whose `4·w·h` multiple fits the format.
                let limit = S::MAX.to_f64().min(1e30) / f64::from(4 * w * h);
                let edges = match rng.next() % 3 {
                    0 => [Some(sides::<S>(&mut rng, limit)), None],
                    1 => [None, Some(sides::<S>(&mut rng, limit))],
                    _ => [
                        Some(sides::<S>(&mut rng, limit)),
                        Some(sides::<S>(&mut rng, limit)),
                    ],
                };
                Fill::Tiles(Tiles {
                    colors: [corners(&mut rng), corners(&mut rng)],
                    edges,
                    first: (below(&mut rng, 9) - 4, below(&mut rng, 9) - 4),
                    negative: rng.next().is_multiple_of(2),
                })
            };
            // Whole, or some of its rows and columns.
            let c0 = x.0 + u16::try_from(below(&mut rng, w.unsigned_abs())).unwrap_or(0);
            let c1 = (c0 + 1 + u16::try_from(below(&mut rng, 9)).unwrap_or(0)).min(x.1 + 1);
            let r0 = y.0 + u16::try_from(below(&mut rng, h.unsigned_abs())).unwrap_or(0);
            let r1 = (r0 + 1 + u16::try_from(below(&mut rng, 9)).unwrap_or(0)).min(y.1 + 1);
            let (rows, columns) = (r0..r1, c0..c1);
            let want = fill_by_pixel(&how, (x, y), (rows.clone(), columns.clone()));
            let stride = columns.len();
            let mut got = vec![Rgb888::new(1, 2, 3); want.len()];
            fill(
                (&how, x, y),
                (rows.clone(), columns.clone()),
                (&mut got, stride, (rows.start, columns.start)),
            );
            assert_eq!(
                got,
                want,
                "{} {how:?} {x:?} {y:?} {rows:?} {columns:?}",
                S::NAME
            );
        }
        assert!(tiled > 2000);
    }

    #[test]
    fn a_fill_is_its_pixels_by_definition() {
        fills_are_the_pixels_definition::<I16F16>(0x5EED_F111_0001);
        fills_are_the_pixels_definition::<I20F12>(0x5EED_F111_0002);
        fills_are_the_pixels_definition::<f32>(0x5EED_F111_0003);
    }
}
