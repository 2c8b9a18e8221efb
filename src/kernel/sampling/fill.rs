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
    let w = i32::from(x.1 - x.0).max(1);
    let h = i32::from(y.1 - y.0).max(1);
    let area = w * h;
    // One loop per way of rounding, chosen once a block: a whole block's area is a
    // power of two.
    let at = (how, (w, h), (x.0, y.0));
    let pixels = (rows, columns);
    let out = (out, stride, origin);
    if area.count_ones() == 1 {
        fill_rounded(at, pixels, out, Shift(area.trailing_zeros(), area / 2));
    } else {
        fill_rounded(at, pixels, out, Divide(area));
    }
}

/// [`fill`] with the block's rounding `round`.
#[inline(always)]
fn fill_rounded<S: Scalar, C: From<Rgb888>, R: Round>(
    (how, (w, h), (x0, y0)): (&Fill<S>, (i32, i32), (u16, u16)),
    (rows, columns): (Range<u16>, Range<u16>),
    (out, stride, origin): (&mut [C], usize, (u16, u16)),
    round: R,
) {
    use embedded_graphics_core::pixelcolor::RgbColor;
    let channels = |c: Rgb888| [i32::from(c.r()), i32::from(c.g()), i32::from(c.b())];
    let u0 = i32::from(columns.start - x0);
    // A tiled block's edges on the row before (its `v`), stepped a row by an addition
    // where the format's sums are exact (the same values as `row_edges`).
    let mut before: Option<(i32, RowEdges<S>)> = None;
    for r in rows {
        let v = i32::from(r - y0).min(h);
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
                    *p = pixel(round, value);
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
                // One loop for the stepped sides and one for `odd`'s products, chosen
                // once a row (both in one loop would not stay in registers either).
                match EdgeSteps::new(t, &edges, (u0, w)) {
                    Some(mut stepped) => tiles_row(line, &starts, round, |_| stepped.next_odd()),
                    None => tiles_row(line, &starts, round, |k| t.odd(&edges, u0 + k, w)),
                }
            }
        }
    }
}

/// A tiled block's row: pixel `k` of `line` is `start + k·step` of the colour set
/// (`starts`: the plane's material's, the alternate's) `odd(k)` picks, rounded. The
/// sets are drawn one after the other, each over its own columns (a block's row, of at
/// most 32: each column's set a bit of one word), so that one set's values are read at
/// a time; a longer row is drawn in pieces of 32.
#[inline(always)]
fn tiles_row<C: From<Rgb888>, R: Round>(
    line: &mut [C],
    starts: &[([i32; 3], [i32; 3]); 2],
    round: R,
    mut odd: impl FnMut(i32) -> bool,
) {
    let mut first = 0i32;
    for piece in line.chunks_mut(32) {
        let mut odds = 0u32;
        for bit in 0..piece.len() {
            odds |= u32::from(odd(first + bit as i32)) << bit;
        }
        // The columns of the piece: its low `len` bits (`len` in 1..=32).
        let all = u32::MAX >> (32 - piece.len());
        for (mut mine, (start, step)) in [all & !odds, odds].into_iter().zip(starts) {
            while mine != 0 {
                let bit = mine.trailing_zeros();
                mine &= mine - 1;
                let Some(p) = piece.get_mut(bit as usize) else {
                    break;
                };
                let k = first + bit as i32;
                *p = pixel(
                    round,
                    [
                        start[0] + k * step[0],
                        start[1] + k * step[1],
                        start[2] + k * step[2],
                    ],
                );
            }
        }
        first += 32;
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

/// Rounding an interpolated channel (times the block's area) to a pixel value, to
/// nearest: by a shift where the area is a power of two (a whole block), else by a
/// division. A channel's value `v` (times the area, plus half the area:
/// [`Round::half`]) lies in `0..=255·area + area/2` (the interpolation of values in
/// `0..=255` at a point of the block, a weighted mean), so the quotient is in `0..=255`.
trait Round: Copy {
    /// `v` rounded: its quotient by the area.
    fn quotient(self, v: i32) -> i32;
    /// Half the area, added once to a row's start values so that the quotient rounds
    /// to nearest.
    fn half(self) -> i32;
}

/// The rounding of an area `2^shift` (and its half).
#[derive(Clone, Copy)]
struct Shift(u32, i32);

/// The rounding of any other area.
#[derive(Clone, Copy)]
struct Divide(i32);

impl Round for Shift {
    #[inline(always)]
    fn quotient(self, v: i32) -> i32 {
        v >> self.0
    }
    fn half(self) -> i32 {
        self.1
    }
}

impl Round for Divide {
    #[inline(always)]
    fn quotient(self, v: i32) -> i32 {
        v / self.0
    }
    fn half(self) -> i32 {
        self.0 / 2
    }
}

/// A channel rounded ([`Round`]).
#[inline(always)]
fn channel(round: impl Round, v: i32) -> u8 {
    let q = round.quotient(v);
    // The precondition, checked where debug assertions are on (the tests' builds): the
    // cast keeps the quotient itself.
    debug_assert!(
        (0..=255).contains(&q),
        "a fill's channel {q} out of 0..=255"
    );
    q as u8
}

/// A pixel of three interpolated channels, rounded ([`Round`]).
#[inline(always)]
fn pixel<C: From<Rgb888>>(round: impl Round, value: [i32; 3]) -> C {
    C::from(Rgb888::new(
        channel(round, value[0]),
        channel(round, value[1]),
        channel(round, value[2]),
    ))
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
    #[inline(always)]
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
mod tests;
