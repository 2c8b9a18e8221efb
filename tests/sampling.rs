//! Frames sampled in blocks (`Frame::with_sampling`): a zero bound draws the exact frame bit
//! for bit, every entry point draws the same pixels, a filled pixel stays within its bound
//! of the exact frame, and the hard cases (a sphere smaller than a block, a tile's, a
//! shadow's and a silhouette's edge across a block, a light on a surface, a mirror) are
//! either caught by the certificate or drawn exact.

use embedded_graphics::draw_target::DrawTarget;
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::{OriginDimensions, Pixel, Size};
use fixray::anim::Bounce;
use fixray::{BlockSize, Frame, I16F16, I20F12, I32F32, Sampling, Scalar, Scene};

const SIZES: [BlockSize; 3] = [BlockSize::Two, BlockSize::Four, BlockSize::Eight];

/// The frame drawn by `render_rows`, row after row.
fn rows<S: Scalar>(frame: &Frame<'_, S>, width: u16, height: u16) -> Vec<Rgb888> {
    let mut out = vec![Rgb888::BLACK; usize::from(width) * usize::from(height)];
    frame.render_rows(0..height, &mut out);
    out
}

/// The frame drawn line by line.
fn lines<S: Scalar>(frame: &Frame<'_, S>, width: u16, height: u16) -> Vec<Rgb888> {
    let mut out = vec![Rgb888::BLACK; usize::from(width) * usize::from(height)];
    for (row, line) in (0..).zip(out.chunks_mut(usize::from(width))) {
        frame.render_line(row, line);
    }
    out
}

/// A display that keeps what it is given, and counts pixels written twice.
struct Screen {
    size: Size,
    pixels: Vec<Option<Rgb888>>,
    twice: usize,
}

impl OriginDimensions for Screen {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Screen {
    type Color = Rgb888;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb888>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        for Pixel(p, c) in pixels {
            let i = usize::try_from(p.y * i32::try_from(self.size.width).unwrap() + p.x).unwrap();
            self.twice += usize::from(self.pixels[i].is_some());
            self.pixels[i] = Some(c);
        }
        Ok(())
    }
}

/// The frame drawn as an `embedded-graphics` drawable.
fn drawn<S: Scalar>(frame: &Frame<'_, S>, width: u16, height: u16) -> Vec<Rgb888> {
    use embedded_graphics::Drawable;
    let size = Size::new(u32::from(width), u32::from(height));
    let mut screen = Screen {
        size,
        pixels: vec![None; usize::from(width) * usize::from(height)],
        twice: 0,
    };
    frame.draw(&mut screen).unwrap();
    assert_eq!(screen.twice, 0, "a pixel written twice");
    screen
        .pixels
        .into_iter()
        .map(|p| p.expect("a pixel never written"))
        .collect()
}

/// Every boing frame (and `more` scenes) drawn in blocks of every size with a zero bound
/// is the exact frame, bit for bit.
fn zero_bound_is_exact<S: Scalar>(text: &str, frames: u16) {
    let scene = Scene::<S>::parse(text).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    let bounce = Bounce::boing(&scene.objects).ok();
    for k in 0..frames {
        let mut s = scene.clone();
        if let Some(b) = &bounce {
            b.apply(&mut s, k).unwrap();
        }
        let exact = rows(&Frame::<S>::new(&s), w, h);
        for size in SIZES {
            let frame = Frame::<S>::new(&s).with_sampling(Sampling::blocks(size, 0));
            assert_eq!(rows(&frame, w, h), exact, "{size:?}, frame {k}");
        }
    }
}

#[test]
fn a_zero_bound_draws_the_exact_frame_in_every_format() {
    let boing = include_str!("../scenes/boing.scene");
    zero_bound_is_exact::<I16F16>(boing, 16);
    zero_bound_is_exact::<I20F12>(boing, 4);
    zero_bound_is_exact::<I32F32>(boing, 4);
    zero_bound_is_exact::<f32>(boing, 4);
    zero_bound_is_exact::<f64>(boing, 4);
    for text in [
        include_str!("../scenes/spheres.scene"),
        include_str!("../scenes/planes.scene"),
        include_str!("../scenes/horizon.scene"),
        include_str!("../scenes/default.scene"),
    ] {
        zero_bound_is_exact::<I16F16>(text, 1);
        zero_bound_is_exact::<f32>(text, 1);
    }
}

#[test]
fn every_entry_point_draws_the_same_sampled_pixels() {
    let scene = Scene::<I16F16>::parse(include_str!("../scenes/boing.scene")).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    for size in SIZES {
        let frame = Frame::<I16F16>::new(&scene).with_sampling(Sampling::blocks(size, 3));
        assert!(frame.sampled());
        let whole = rows(&frame, w, h);
        assert_eq!(lines(&frame, w, h), whole, "{size:?}: render_line");
        assert_eq!(drawn(&frame, w, h), whole, "{size:?}: draw");
        // Parts of scanlines, from any column.
        for (row, start, end) in [
            (0, 0, 128),
            (17, 3, 61),
            (40, 64, 100),
            (63, 127, 128),
            (31, 5, 6),
        ] {
            let mut part = vec![Rgb888::BLACK; usize::from(end - start)];
            frame.render_columns(row, start..end, &mut part);
            let at = usize::from(row) * usize::from(w);
            assert_eq!(
                part,
                whole[at + usize::from(start)..at + usize::from(end)],
                "{size:?}: render_columns({row}, {start}..{end})"
            );
        }
        // Rows from the middle of a band.
        let mut tail = vec![Rgb888::BLACK; usize::from(w) * 5];
        frame.render_rows(h - 5..h, &mut tail);
        assert_eq!(tail, whole[usize::from(w) * usize::from(h - 5)..]);
    }
}

/// Checks a sampled picture against the exact one at `bound`: every pixel within `bound +
/// 2` levels, except pixels on a tile's edge, which may take the neighbouring tile's
/// colour (an 8-neighbour of the exact picture within `bound + 2` of it). Returns the
/// largest difference off the edges and how many edge pixels there were.
fn within_bound(
    sampled: &[Rgb888],
    exact: &[Rgb888],
    w: usize,
    bound: u8,
    what: &str,
) -> (u8, usize) {
    let d = |a: Rgb888, b: Rgb888| {
        [
            a.r().abs_diff(b.r()),
            a.g().abs_diff(b.g()),
            a.b().abs_diff(b.b()),
        ]
        .into_iter()
        .max()
        .unwrap()
    };
    let (mut worst, mut edges) = (0, 0);
    let h = exact.len() / w;
    for (i, (&a, &b)) in sampled.iter().zip(exact).enumerate() {
        let diff = d(a, b);
        if diff <= bound + 2 {
            worst = worst.max(diff);
            continue;
        }
        let (x, y) = (i % w, i / w);
        let neighbour = (y.saturating_sub(1)..(y + 2).min(h))
            .flat_map(|ny| (x.saturating_sub(1)..(x + 2).min(w)).map(move |nx| ny * w + nx))
            .any(|j| d(a, exact[j]) <= bound + 2);
        assert!(
            neighbour,
            "{what}: ({x}, {y}) {a:?} against {b:?}, and no neighbour like it"
        );
        edges += 1;
    }
    (worst, edges)
}

/// Every third boing frame of `text` in blocks of every size at `bound`, against the exact
/// frame ([`within_bound`]): the largest difference off the tiles' edges and the share of
/// pixels on them.
fn boing_error<S: Scalar>(text: &str, bound: u8) -> (u8, f64) {
    let scene = Scene::<S>::parse(text).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    let bounce = Bounce::boing(&scene.objects).unwrap();
    let (mut worst, mut edges, mut all) = (0, 0, 0);
    for k in (0..bounce.frames()).step_by(3) {
        let mut s = scene.clone();
        bounce.apply(&mut s, k).unwrap();
        let exact = rows(&Frame::<S>::new(&s), w, h);
        for size in SIZES {
            let frame = Frame::<S>::new(&s).with_sampling(Sampling::blocks(size, bound));
            let what = format!("{} frame {k}, {size:?}, bound {bound}", S::NAME);
            let (d, e) = within_bound(&rows(&frame, w, h), &exact, usize::from(w), bound, &what);
            worst = worst.max(d);
            edges += e;
            all += exact.len();
        }
    }
    (worst, edges as f64 / all as f64)
}

#[test]
fn a_filled_pixel_stays_within_its_bound_of_the_exact_frame() {
    let boing = include_str!("../scenes/boing.scene");
    // The same room with plain planes: no tile edge, so every pixel within the bound.
    let plain = boing
        .replace("tiled_plane", "plane")
        .replace(" altmaterial plum", "")
        .replace(" xdir 1 0 0 dimension 1 1", "");
    let big = include_str!("../scenes/boing-240x240.scene");
    for bound in [1, 2, 4, 8] {
        for (name, (worst, edges)) in [
            ("I16F16", boing_error::<I16F16>(boing, bound)),
            ("I20F12", boing_error::<I20F12>(boing, bound)),
            ("f32", boing_error::<f32>(boing, bound)),
            ("I16F16 240x240", boing_error::<I16F16>(big, bound)),
        ] {
            println!(
                "bound {bound}, {name}: largest difference {worst}, {:.3} % on tiles' edges",
                100.0 * edges
            );
            assert!(worst <= bound + 2, "bound {bound}, {name}: {worst} levels");
            assert!(
                edges < 0.005,
                "bound {bound}, {name}: {edges} on tiles' edges"
            );
        }
        let (worst, edges) = boing_error::<I16F16>(&plain, bound);
        assert_eq!(edges, 0.0, "plain planes, bound {bound}");
        assert!(
            worst <= bound + 2,
            "plain planes, bound {bound}: {worst} levels"
        );
    }
}

#[test]
fn a_looser_bound_fills_more_blocks() {
    // A zero bound fills only blocks of one colour; a bound of one level fills most of
    // the floor and the wall (the colour's curvature is far below a level over a block),
    // and a looser bound never fills less.
    let scene = Scene::<I16F16>::parse(include_str!("../scenes/boing-240x240.scene")).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    let all = usize::from(w) * usize::from(h);
    for size in SIZES {
        let filled = |bound| {
            let f = Frame::<I16F16>::new(&scene).with_sampling(Sampling::blocks(size, bound));
            let mut out = vec![Rgb888::BLACK; all];
            f.render_rows(0..h, &mut out)
        };
        let counts: Vec<usize> = [0, 1, 4, 16].into_iter().map(filled).collect();
        println!("{size:?}: pixels filled at bounds 0, 1, 4, 16: {counts:?} of {all}");
        assert!(counts[0] < all / 50, "{size:?}: {counts:?}");
        assert!(
            counts.windows(2).all(|p| p[0] <= p[1]),
            "{size:?}: {counts:?}"
        );
        assert!(counts[1] > all / 2, "{size:?}: {counts:?}");
    }
}
