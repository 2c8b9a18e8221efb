//! The fill against its definition: each pixel the bilinear interpolation of its
//! block's corner colours, rounded.

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
/// `β`, sides within the bound `tiles_fill` certifies; some wider than 32 columns),
/// whole and in part: [`fill`] (stepped colours, stepped tile sides) draws what
/// [`fill_by_pixel`] draws, bit for bit, in each fixed format.
fn fills_are_the_pixels_definition<S: Scalar>(seed: u64) {
    let mut rng = Rng(seed);
    let mut tiled = 0;
    for _ in 0..4000 {
        // One block in 16 is wider than a word's bits (a tiled row's pieces).
        let wide = rng.next().is_multiple_of(16);
        let w = if wide {
            33 + below(&mut rng, 40)
        } else {
            1 + below(&mut rng, 8)
        };
        let h = 1 + below(&mut rng, 8);
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
        let more = if wide { w.unsigned_abs() + 1 } else { 9 };
        let c1 = (c0 + 1 + u16::try_from(below(&mut rng, more)).unwrap_or(0)).min(x.1 + 1);
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
