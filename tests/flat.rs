//! The pure-geometry kernel (`fixray::flat`): per-pixel mode against the general fast
//! path (`fixray::fast`, exact cross-products), span mode against per-pixel mode, and both
//! through `render` (the `fill_contiguous` path, also clipped) against `render_line`.
//! On the shipped plane scenes and on seeded random plane scenes, in every format of the
//! one list (`fixray::num::formats::FORMATS`).

mod common;
use common::sampling;

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use fixray::internals::Flat;
use fixray::internals::Primary;
use fixray::scene::Rules;
use fixray::shade::pixel;
use fixray::shade::to_rgb888;
use fixray::{Frame, I16F16, PlaneMode, Scalar, Scene, render, render_line};
use sampling::SplitMix;

type Image = Vec<Vec<Rgb888>>;

fn lines<S: Scalar>(scene: &Scene<S>) -> Image {
    lines_in(scene, PlaneMode::PerPixel)
}

/// [`lines`] with pure-geometry scanlines drawn in `mode` (through a `Frame`); per-pixel
/// mode is checked against `render_line` on the way.
fn lines_in<S: Scalar>(scene: &Scene<S>, mode: PlaneMode) -> Image {
    let w = usize::from(scene.camera.width);
    let frame = Frame::with_mode(scene, mode);
    (0..scene.camera.height)
        .map(|row| {
            let mut line = vec![Rgb888::new(1, 2, 3); w];
            frame.render_line(row, &mut line);
            if mode == PlaneMode::PerPixel {
                let mut plain = vec![Rgb888::new(1, 2, 3); w];
                render_line(scene, row, &mut plain);
                assert_eq!(line, plain, "row {row}");
            }
            line
        })
        .collect()
}

/// The general fast path's picture of a pure-geometry scene (ambient colour of the plane
/// `fast::Primary` picks; the reference path where it hands a pixel back).
fn primary_image<S: Scalar>(scene: &Scene<S>) -> Image {
    let scene = &scene.view();
    let p = Primary::new(scene).expect("a plane scene");
    (0..scene.camera.height)
        .map(|row| {
            (0..scene.camera.width)
                .map(
                    |col| match p.row(scene, row, col).map(|r| p.nearest(scene, &r)) {
                        Some(Ok(Some(hit))) => {
                            let m = scene.objects[hit.index].material;
                            to_rgb888(scene.materials[usize::from(m)].ambient)
                        }
                        Some(Ok(None)) => to_rgb888(scene.background),
                        _ => pixel(scene, col, row),
                    },
                )
                .collect()
        })
        .collect()
}

fn differ(a: &Image, b: &Image) -> usize {
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .filter(|(x, y)| x != y)
        .count()
}

/// Per-pixel and span images of a scene, checked against each other and the fast path;
/// returns (pixels, per-pixel vs fast path differences, spans vs per-pixel differences).
fn compare<S: Scalar>(name: &str, text: &str) -> (usize, usize, usize) {
    let scene = Scene::<S>::parse_as(text, Rules::Fixray).unwrap();
    assert_eq!(
        fixray::Frame::<_>::new(&scene).kernel(),
        fixray::KernelKind::Flat,
        "{name} {}: the flat kernel draws it",
        S::NAME
    );
    assert!(Flat::new(&scene.view()).is_some(), "{name} {}", S::NAME);
    for row in 0..scene.camera.height {
        assert!(
            Flat::new(&scene.view())
                .unwrap()
                .row(&scene.view(), row)
                .is_some(),
            "{name} {}: row {row} fits",
            S::NAME
        );
    }
    let per_pixel = lines_in(&scene, PlaneMode::PerPixel);
    let spans = lines_in(&scene, PlaneMode::Spans);
    let fast = primary_image(&scene);
    let n = per_pixel.len() * per_pixel[0].len();
    (n, differ(&per_pixel, &fast), differ(&spans, &per_pixel))
}

/// Whether span mode must draw exactly the per-pixel mode's image in format `S`: in the
/// fixed formats `w̃(k)` is exact integer arithmetic along a scanline (`fixray::flat`'s
/// module documentation), floats round its steps. A format is fixed when it has integer
/// bits (`Scalar::INT_BITS` is 0 for the floats, whose resolution is relative).
fn exact_spans<S: Scalar>() -> bool {
    S::INT_BITS > 0
}

fn shipped<S: Scalar>() {
    let exact_spans = exact_spans::<S>();
    for (name, text) in [
        ("planes", include_str!("../scenes/planes.scene")),
        ("horizon", include_str!("../scenes/horizon.scene")),
    ] {
        let (n, vs_fast, vs_spans) = compare::<S>(name, text);
        println!(
            "{name:<8} {:<7} per-pixel vs fast path: {vs_fast} of {n}; spans vs per-pixel: {vs_spans}",
            S::NAME
        );
        // w̃ rounding can only decide near-ties: a few boundary pixels at most.
        assert!(vs_fast * 1000 <= n, "{name} {}: {vs_fast}", S::NAME);
        if exact_spans {
            assert_eq!(vs_spans, 0, "{name} {}", S::NAME);
        } else {
            assert!(vs_spans * 1000 <= n, "{name} {}: {vs_spans}", S::NAME);
        }
    }
}

#[test]
fn shipped_scenes_in_every_format() {
    fixray::for_each_format!(all: shipped());
}

/// A seeded random room: 3–6 planes, an eye anywhere in front of the screen, and in one
/// scene of four a wide precision epsilon (wide parallel bands at the horizons).
fn random_scene(rng: &mut SplitMix) -> String {
    let mut text = String::from("camera c { pixeldim 64 48 worlddim 8 6 ");
    text += &format!(
        "viewpoint {:.3} {:.3} {:.3} }}\nbackground 0.1 0.2 0.3\n",
        rng.uniform(-2.0, 10.0),
        rng.uniform(-2.0, 8.0),
        rng.uniform(0.5, 12.0)
    );
    if rng.below(4) == 0 {
        text += "precision 0.05\n";
    }
    let planes = 3 + rng.below(4);
    for i in 0..planes {
        let n = rng.unit();
        // Some planes axis-aligned (N.x = 0: constant along a scanline).
        let n = if rng.below(3) == 0 {
            [0.0, n[1], n[2]]
        } else {
            n
        };
        text += &format!(
            "material m{i} {{ ambient {:.2} {:.2} {:.2} }}\nplane p{i} {{ material m{i} normal {:.4} {:.4} {:.4} point {:.2} {:.2} {:.2} }}\n",
            0.1 + 0.15 * i as f64,
            0.9 - 0.1 * i as f64,
            0.05 * i as f64,
            n[0],
            n[1],
            n[2] + 1e-3,
            rng.uniform(-20.0, 20.0),
            rng.uniform(-20.0, 20.0),
            rng.uniform(-40.0, 0.0)
        );
    }
    text
}

fn random<S: Scalar>() {
    let exact_spans = exact_spans::<S>();
    let mut rng = SplitMix(0xF1A7_2026);
    let (mut total, mut vs_fast, mut vs_spans, mut seen) = (0, 0, 0, 0);
    for case in 0..60 {
        let text = random_scene(&mut rng);
        let scene = Scene::<S>::parse_as(&text, Rules::Fixray).unwrap();
        if Flat::new(&scene.view()).is_none() {
            continue;
        }
        let (n, f, s) = compare::<S>(&format!("random {case}"), &text);
        // Not vacuous: the picture shows planes.
        seen += usize::from(
            lines(&scene)
                .iter()
                .flatten()
                .any(|c| *c != Rgb888::new(26, 51, 77)),
        );
        if exact_spans {
            assert_eq!(s, 0, "case {case} {}:\n{text}", S::NAME);
        }
        total += n;
        vs_fast += f;
        vs_spans += s;
    }
    println!(
        "random   {:<7} per-pixel vs fast path: {vs_fast} of {total}; spans vs per-pixel: {vs_spans}",
        S::NAME
    );
    assert!(seen >= 40, "{}: {seen} scenes show planes", S::NAME);
    assert!(vs_fast * 1000 <= total, "{}: {vs_fast}", S::NAME);
    assert!(vs_spans * 1000 <= total, "{}: {vs_spans}", S::NAME);
}

#[test]
fn random_plane_scenes_in_every_format() {
    fixray::for_each_format!(all: random());
}

#[test]
fn render_draws_what_render_line_draws_in_both_modes_and_clipped() {
    let text = "
        camera c { pixeldim 48 40 worlddim 8 6 viewpoint 3 2 5 }
        material a { ambient 1 0 0 } material b { ambient 0 1 0 } material c { ambient 0 0 1 }
        plane floor { material a normal 0 1 0 point 0 0 0 }
        plane wall  { material b normal 1 0 0.2 point 1 0 0 }
        plane back  { material c normal 0.3 0.1 1 point 0 0 -12 }
    ";
    for mode in [PlaneMode::PerPixel, PlaneMode::Spans] {
        let scene = Scene::<I16F16>::parse_as(text, Rules::Fixray).unwrap();
        let frame = Frame::with_mode(&scene, mode);
        let expected = lines_in(&scene, mode);
        let mut display = MockDisplay::<Rgb888>::new();
        frame.draw(&mut display).unwrap();
        if mode == PlaneMode::PerPixel {
            let mut plain = MockDisplay::<Rgb888>::new();
            render(&scene, &mut plain).unwrap();
            assert_eq!(plain, display);
        }
        for (y, line) in expected.iter().enumerate() {
            for (x, c) in line.iter().enumerate() {
                let p = Point::new(i32::try_from(x).unwrap(), i32::try_from(y).unwrap());
                assert_eq!(display.get_pixel(p), Some(*c), "{mode:?} ({x}, {y})");
            }
        }
        // A target smaller than the image: only its pixels, each once (MockDisplay
        // panics on overdraw and out-of-bounds writes).
        let mut small = MockDisplay::<Rgb888>::new();
        let mut clipped = small.clipped(&embedded_graphics::primitives::Rectangle::new(
            Point::new(5, 7),
            Size::new(30, 20),
        ));
        frame.draw(&mut clipped).unwrap();
        for y in 0..40 {
            for x in 0..48 {
                let inside = (5..35).contains(&x) && (7..27).contains(&y);
                let got = small.get_pixel(Point::new(x, y));
                let want = inside.then(|| expected[y as usize][x as usize]);
                assert_eq!(got, want, "{mode:?} clipped ({x}, {y})");
            }
        }
    }
}

#[test]
fn an_eye_on_a_plane_and_a_one_column_image() {
    // The eye lies on the wall x = 3: that plane is never accepted (hits at the eye).
    let text = "
        camera c { pixeldim 1 6 worlddim 6 6 viewpoint 3 3 4 }
        material a { ambient 1 0 0 } material b { ambient 0 1 0 }
        plane wall  { material a normal 1 0 0 point 3 0 0 }
        plane floor { material b normal 0 1 0 point 0 1 0 }
    ";
    for mode in [PlaneMode::PerPixel, PlaneMode::Spans] {
        let scene = Scene::<I16F16>::parse_as(text, Rules::Fixray).unwrap();
        let got = lines_in(&scene, mode);
        let want: Vec<Vec<Rgb888>> = (0..6).map(|row| vec![pixel(&scene, 0, row)]).collect();
        assert_eq!(got, want, "{mode:?}");
        assert!(got.iter().flatten().any(|c| *c == Rgb888::new(0, 255, 0)));
        assert!(got.iter().flatten().all(|c| *c != Rgb888::new(255, 0, 0)));
    }
}
