//! Frames sampled in blocks (`Frame::with_sampling`): a zero bound draws the exact frame bit
//! for bit, every entry point draws the same pixels, a filled pixel stays within its bound
//! of the exact frame, and the hard cases (a sphere smaller than a block, a tile's, a
//! shadow's and a silhouette's edge across a block, a light on a surface, a mirror) are
//! either caught by the certificate or drawn exact.

mod common;

use common::pictures::{Capture, difference, psnr, squared_error};
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
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

/// The frame drawn as an `embedded-graphics` drawable; every pixel written once.
fn drawn<S: Scalar>(frame: &Frame<'_, S>, width: u16, height: u16) -> Vec<Rgb888> {
    use embedded_graphics::Drawable;
    let mut screen = Capture::new(width, height);
    frame.draw(&mut screen).unwrap();
    assert!(screen.writes.iter().all(|&n| n == 1), "every pixel once");
    screen.pixels.into_iter().map(Option::unwrap).collect()
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

/// A frame drawn band by band ([`Frame::bands`]) is the frame `render_rows` draws at
/// once, in bands of the blocks' side and of other heights, and its corners are traced
/// once each where a row's corners are kept (up to 64), as `render_rows` over every row
/// traces them (counted with `stats`); band after band through separate `render_rows`
/// calls traces each band's top corners again.
#[test]
fn bands_draw_the_frame_and_trace_each_corner_once() {
    use fixray::stats::Counters;
    let base = Scene::<I16F16>::parse(include_str!("../scenes/boing-240x240.scene")).unwrap();
    let (w, h) = (base.camera.width, base.camera.height);
    let (bounce, orbit) = (
        Bounce::boing(&base.objects).unwrap(),
        fixray::anim::Orbit::boing(&base.objects).unwrap(),
    );
    let mut s = base.clone();
    bounce.apply(&mut s, 3).unwrap();
    orbit.apply(&mut s, 3).unwrap();
    for size in SIZES {
        let frame = Frame::<I16F16>::new(&s).with_sampling(Sampling::blocks(size, 8));
        assert!(frame.sampled());
        let mut at_once = Counters::default();
        let mut whole = vec![Rgb888::BLACK; usize::from(w) * usize::from(h)];
        frame.render_rows_counted(0..h, &mut whole, &mut at_once);
        let side = size.pixels();
        for band in [side, 3 * side, 5] {
            let (mut kept, mut again) = (Counters::default(), Counters::default());
            let mut bands = frame.bands();
            let mut out = vec![Rgb888::BLACK; usize::from(w) * usize::from(band)];
            for top in (0..h).step_by(usize::from(band)) {
                let rows = top..(top + band).min(h);
                let n = usize::from(w) * rows.len();
                bands.render_rows_counted(rows.clone(), &mut out[..n], &mut kept);
                let at = usize::from(top) * usize::from(w);
                assert_eq!(
                    out[..n],
                    whole[at..at + n],
                    "{size:?}, bands of {band}, row {top}"
                );
                frame.render_rows_counted(rows, &mut out[..n], &mut again);
            }
            if cfg!(feature = "stats") && band == side {
                assert_eq!(kept.corners, at_once.corners, "{size:?}");
                // A row of 2 × 2 blocks at 240 pixels has more corners than are kept
                // (64): its bands trace their top corners again either way.
                if size == BlockSize::Two {
                    assert_eq!(again.corners, kept.corners);
                } else {
                    assert!(again.corners > kept.corners, "{size:?}");
                }
            }
        }
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
        // Planes seen far away (a long lit floor: rays' parameters up to about 4) and the
        // spheres on a floor.
        for (name, text) in [
            ("default", include_str!("../scenes/default.scene")),
            ("spheres", include_str!("../scenes/spheres.scene")),
        ] {
            let scene = Scene::<I16F16>::parse(text).unwrap();
            let (w, h) = (scene.camera.width, scene.camera.height);
            let exact = rows(&Frame::<I16F16>::new(&scene), w, h);
            for size in SIZES {
                let frame =
                    Frame::<I16F16>::new(&scene).with_sampling(Sampling::blocks(size, bound));
                assert!(frame.sampled(), "{name}");
                let what = format!("{name}, {size:?}, bound {bound}");
                let sampled = rows(&frame, w, h);
                let (worst, _) = within_bound(&sampled, &exact, usize::from(w), bound, &what);
                assert!(worst <= bound + 2, "{what}: {worst} levels");
            }
        }
    }
}

#[test]
fn a_looser_bound_fills_more_blocks() {
    // A zero bound fills only blocks of one colour; a bound of one level fills much of
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
        assert!(counts[1] > all / 3, "{size:?}: {counts:?}");
    }
}

/// Every frame of the ball bouncing before the circling camera, in blocks of 8 at a bound
/// of 8 levels (the board's setting), against the exact frame: at most 1 % of the pixels
/// beyond 2 levels, and a PSNR of at least 40 dB (the orbit's budget).
fn orbit_within_budget<S: Scalar>(text: &str, step: usize) {
    let base = Scene::<S>::parse(text).unwrap();
    let (w, h) = (base.camera.width, base.camera.height);
    let (bounce, orbit) = (
        Bounce::boing(&base.objects).unwrap(),
        fixray::anim::Orbit::boing(&base.objects).unwrap(),
    );
    for k in (0..orbit.frames()).step_by(step) {
        let mut s = base.clone();
        bounce.apply(&mut s, k).unwrap();
        orbit.apply(&mut s, k).unwrap();
        let exact = rows(&Frame::<S>::new(&s), w, h);
        let frame = Frame::<S>::new(&s).with_sampling(Sampling::blocks(BlockSize::Eight, 8));
        assert!(frame.sampled(), "{} frame {k}", S::NAME);
        let sampled = rows(&frame, w, h);
        let beyond = sampled
            .iter()
            .zip(&exact)
            .filter(|(a, b)| difference(**a, **b) > 2)
            .count();
        let share = beyond as f64 / exact.len() as f64;
        let p = psnr(squared_error(&sampled, &exact), exact.len());
        assert!(
            share <= 0.01,
            "{} frame {k}: {share} beyond 2 levels",
            S::NAME
        );
        assert!(p >= 40.0, "{} frame {k}: PSNR {p:.1} dB", S::NAME);
    }
}

#[test]
fn every_orbit_frame_in_blocks_holds_the_budget() {
    orbit_within_budget::<I16F16>(include_str!("../scenes/boing.scene"), 1);
    orbit_within_budget::<I20F12>(include_str!("../scenes/boing.scene"), 3);
    orbit_within_budget::<f32>(include_str!("../scenes/boing.scene"), 3);
    orbit_within_budget::<I16F16>(include_str!("../scenes/boing-240x240.scene"), 5);
}

/// A floor under a light with a sphere far smaller than a block (2 × 2 pixels in blocks
/// of 8), whose block's corners all see the floor, lit and clear of its shadow: every
/// block its box meets is traced, so the sphere is drawn as the exact frame draws it,
/// whatever the bound (without the boxes it is missed at a bound of 8).
#[test]
fn a_sphere_smaller_than_a_block_is_never_missed() {
    let text = "rules fixray
        camera c { pixeldim 64 48 worlddim 16 12 viewpoint 8 11 8 }
        background 0 0 0.2
        material floor { ambient 0.2 0.2 0.2 diffuse 0.6 0.6 0.6 }
        material dot { ambient 1 0 0 }
        light l { location 30 12 -1 emissivity 6 6 6 }
        plane floor { material floor normal 0 1 0 point 0 0 0 }
        sphere dot { material dot center 8.3 2 -1 radius 0.3 }";
    let scene = Scene::<I16F16>::parse(text).unwrap();
    let exact = rows(&Frame::<I16F16>::new(&scene), 64, 48);
    let red = exact.iter().filter(|c| c.r() > 200 && c.g() < 50).count();
    assert!((1..16).contains(&red), "the dot covers a few pixels: {red}");
    for bound in [1, 8, 100] {
        let frame =
            Frame::<I16F16>::new(&scene).with_sampling(Sampling::blocks(BlockSize::Eight, bound));
        let sampled = rows(&frame, 64, 48);
        for (i, (a, b)) in sampled.iter().zip(&exact).enumerate() {
            if b.r() > 200 && b.g() < 50 {
                assert_eq!(a, b, "bound {bound}: the dot's pixel {i}");
            }
        }
        within_bound(&sampled, &exact, 64, bound, "a small sphere");
    }
}

/// Shadows' edges, silhouettes and a shadow far from its sphere's box: in the plain
/// planes' room (no tiles) under two lights, with the ball low and high, every pixel
/// within the bound of the exact frame, in blocks of every size.
#[test]
fn shadow_edges_and_silhouettes_are_caught() {
    let text = include_str!("../scenes/boing.scene")
        .replace("tiled_plane", "plane")
        .replace(" altmaterial plum", "")
        .replace(" xdir 1 0 0 dimension 1 1", "")
        .replace(
            "light lamp { location 7 9 2 emissivity 9 9 9 }",
            "light lamp { location 7 9 2 emissivity 6 6 6 }
             light low { location -2 3 4 emissivity 3 3 3 }",
        );
    let scene = Scene::<I16F16>::parse(&text).unwrap();
    let bounce = Bounce::boing(&scene.objects).unwrap();
    for k in [0, 4, 6] {
        let mut s = scene.clone();
        bounce.apply(&mut s, k).unwrap();
        let exact = rows(&Frame::<I16F16>::new(&s), 128, 64);
        for size in SIZES {
            for bound in [1, 4] {
                let frame = Frame::<I16F16>::new(&s).with_sampling(Sampling::blocks(size, bound));
                let what = format!("frame {k}, {size:?}, bound {bound}");
                let (worst, edges) =
                    within_bound(&rows(&frame, 128, 64), &exact, 128, bound, &what);
                assert_eq!(edges, 0, "{what}: no tiles here");
                assert!(worst <= bound + 2, "{what}: {worst}");
            }
        }
    }
}

/// A light bright enough to clamp the room's colour: where a channel passes 255 inside a
/// block, the clamped colour's stray is bounded from how far past it the channel may go,
/// or by its range over the block; blocks clamped throughout stray by nothing. Every
/// pixel stays within the bound, and most of the room is filled (refusing every block a
/// channel may clamp in fills a seventh of it at 20 units of emissivity, none at 40).
#[test]
fn a_clamped_colour_is_filled_within_its_bound() {
    let base = include_str!("../scenes/boing-240x240.scene");
    for emissivity in ["20 20 20", "40 40 40"] {
        let text = base.replace("emissivity 9 9 9", &format!("emissivity {emissivity}"));
        let scene = Scene::<I16F16>::parse(&text).unwrap();
        let (w, h) = (scene.camera.width, scene.camera.height);
        let exact = rows(&Frame::<I16F16>::new(&scene), w, h);
        let clamped = exact
            .iter()
            .filter(|p| p.r() == 255 || p.g() == 255 || p.b() == 255)
            .count();
        assert!(clamped > exact.len() / 2, "{emissivity}: {clamped} clamped");
        for size in SIZES {
            for bound in [1, 4, 8] {
                let frame =
                    Frame::<I16F16>::new(&scene).with_sampling(Sampling::blocks(size, bound));
                let mut sampled = vec![Rgb888::BLACK; exact.len()];
                let filled = frame.render_rows(0..h, &mut sampled);
                let what = format!("emissivity {emissivity}, {size:?}, bound {bound}");
                let (worst, _) = within_bound(&sampled, &exact, usize::from(w), bound, &what);
                assert!(worst <= bound + 2, "{what}: {worst} levels");
                if bound >= 4 && size != BlockSize::Two {
                    assert!(filled > exact.len() / 2, "{what}: {filled} filled");
                }
            }
        }
    }
}

/// Frames the certificates do not cover are drawn exact: a mirror (the moved ball seen
/// in it), a glint, a light lying on a surface, the course's rules.
#[test]
fn frames_the_certificates_do_not_cover_are_exact() {
    let boing = include_str!("../scenes/boing.scene");
    let on_floor = boing.replace("location 7 9 2", "location 7 0 2");
    let mirror = boing.replace(
        "material pale  { ambient 0.12 0.12 0.14 diffuse 0.75 0.75 0.8 }",
        "material pale  { ambient 0.12 0.12 0.14 diffuse 0.75 0.75 0.8 reflective 0.5 }",
    );
    for (name, text) in [
        ("mirror", mirror.as_str()),
        ("a light on the floor", on_floor.as_str()),
        ("specular", include_str!("../scenes/specular.scene")),
        ("course rules", include_str!("../scenes/course.scene")),
    ] {
        let scene = Scene::<I16F16>::parse(text).unwrap();
        let (w, h) = (scene.camera.width, scene.camera.height);
        let frame =
            Frame::<I16F16>::new(&scene).with_sampling(Sampling::blocks(BlockSize::Four, 8));
        assert!(!frame.sampled(), "{name}");
        assert_eq!(
            rows(&frame, w, h),
            rows(&Frame::<I16F16>::new(&scene), w, h),
            "{name}"
        );
    }
}
