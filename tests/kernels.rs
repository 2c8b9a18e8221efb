//! One kernel choice: `render`, `render_line` and `Frame::render_line` draw bit-identical
//! pixels, in both plane modes, for every shipped scene in every number format of the one
//! list and for seeded random scenes, including scanlines the pure-geometry kernel hands
//! back (a quantity out of the format's range): `Frame::render_line` draws such a
//! scanline on the same path as `render`, so the two cannot differ.

mod common;

use common::pictures::Capture;
use common::sampling::SplitMix;
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::*;
use fixray::geometry::Shape;
use fixray::internals::Flat;
use fixray::{Frame, KernelKind, PlaneMode, Scalar, Scene, render, render_line};

/// The three entry points in one plane mode: the image they agree on, and how many
/// scanlines the pure-geometry kernel handed back.
fn agree<S: Scalar>(name: &str, text: &str, mode: PlaneMode) -> (Vec<Rgb888>, usize) {
    // A shipped scene's textures lie beside it (`name` is its path); others name none.
    let mut scene = Scene::<S>::empty();
    scene
        .read_with(text, None, &mut fixray::scene::files::beside(name.as_ref()))
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let (w, h) = (scene.camera.width, scene.camera.height);
    let frame = Frame::with_mode(&scene, mode);
    let mut streamed = Capture::new(w, h);
    frame.draw(&mut streamed).unwrap();
    if mode == PlaneMode::PerPixel {
        let mut plain = Capture::new(w, h);
        render(&scene, &mut plain).unwrap();
        assert_eq!(plain.pixels, streamed.pixels, "{name} {}: render", S::NAME);
    }
    assert!(
        streamed.writes.iter().all(|&n| n == 1),
        "{name}: every pixel once"
    );
    let mut lines = Vec::new();
    let (mut line, mut framed) = (
        vec![Rgb888::BLACK; usize::from(w)],
        vec![Rgb888::BLACK; usize::from(w)],
    );
    for row in 0..h {
        frame.render_line(row, &mut framed);
        if mode == PlaneMode::PerPixel {
            render_line(&scene, row, &mut line);
            assert_eq!(line, framed, "{name} {}: row {row}", S::NAME);
        }
        lines.extend_from_slice(&framed);
    }
    let drawn: Vec<Rgb888> = streamed.pixels.iter().map(|p| p.unwrap()).collect();
    // Part of a scanline from any column (`Frame::render_columns`, what a display's
    // changed columns are drawn with) is the whole scanline's pixels there.
    for row in (0..h).step_by(usize::from(h / 5).max(1)) {
        for start in [1, 5, 15, 16, 17, 31, 63, 65, 100, w - 1] {
            if start >= w {
                continue;
            }
            let mut part = vec![Rgb888::new(1, 2, 3); usize::from(w - start)];
            frame.render_columns(row, start..w, &mut part);
            let at = usize::from(row) * usize::from(w);
            assert_eq!(
                part,
                lines[at + usize::from(start)..at + usize::from(w)],
                "{name} {} {mode:?}: row {row} from column {start}",
                S::NAME
            );
        }
    }
    if mode == PlaneMode::PerPixel {
        // The frame's reference path is the free function's, with the plan worked out once.
        for row in [0, h / 2, h - 1] {
            for column in 0..w {
                assert_eq!(
                    frame.trace_pixel(column, row),
                    fixray::shade::trace_pixel(&scene, column, row),
                    "{name} {}: ({column}, {row})",
                    S::NAME
                );
            }
        }
        // The accuracy report's pixels (`compare`, 64 columns at a time) are these too.
        let mut compared = vec![Rgb888::BLACK; drawn.len()];
        fixray::compare::compare(&scene, &scene, |x, y, px, _| {
            compared[usize::from(y) * usize::from(w) + usize::from(x)] = px;
        });
        assert_eq!(
            compared,
            drawn,
            "{name} {}: compare against render_line",
            S::NAME
        );
    }
    assert_eq!(
        drawn,
        lines,
        "{name} {} {mode:?}: draw against render_line",
        S::NAME
    );
    // The chooser the renderer uses: the frame's kernel, and the kernel of each row.
    let frame = Frame::<S>::with_mode(&scene, mode);
    let kernel = frame.kernel();
    let handed_back = (0..h)
        .filter(|&r| {
            let row = frame.row_kernel(r);
            if row != kernel {
                // Flat rows go on to the fast kernel or the reference path, level-plane
                // rows to the fast kernel.
                match kernel {
                    KernelKind::Flat => assert_ne!(row, KernelKind::Flat),
                    KernelKind::Rows => assert_eq!(row, KernelKind::Fast, "{name}"),
                    _ => panic!("{name}: only flat and level-plane rows are handed back"),
                }
            }
            row != kernel
        })
        .count();
    // What each kind of scene is drawn with.
    let plan = scene.plan();
    let expected = if scene.rules() == fixray::scene::Rules::Course {
        KernelKind::Reference
    } else if !(plan.lighting || plan.reflection)
        && plan.planes_only
        && Flat::new(&scene.view()).is_some()
    {
        KernelKind::Flat
    } else if fixray::internals::Primary::new(&scene.view()).is_some() {
        // Level planes (`N.x = 0`) and spheres lit by diffuse point lights with shadows:
        // the level-plane kernel; any other scene of the crate's rules: the fast kernel.
        let diffuse = plan.lighting
            && plan.shadows
            && !(plan.specular
                || plan.spotlights
                || plan.reflection
                || plan.transparency
                || plan.projectors
                || plan.lights_on_surfaces);
        let level = scene.objects.iter().all(|o| match &o.shape {
            Shape::Sphere(_) => true,
            Shape::Plane(p) => p.normal().x == S::ZERO,
            Shape::Tiled { frame, .. } => frame.plane().normal().x == S::ZERO,
            _ => false,
        });
        if diffuse && level {
            KernelKind::Rows
        } else {
            KernelKind::Fast
        }
    } else {
        KernelKind::Reference
    };
    assert_eq!(kernel, expected, "{name} {}", S::NAME);
    (drawn, handed_back)
}

fn both_modes<S: Scalar>(name: &str, text: &str, handed_back: &mut usize) {
    let (_, n) = agree::<S>(name, text, PlaneMode::PerPixel);
    agree::<S>(name, text, PlaneMode::Spans);
    *handed_back += n;
}

fn shipped<S: Scalar>(handed_back: &mut usize) {
    for entry in std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|x| x != "scene") {
            continue; // scenes/textures/
        }
        let text = std::fs::read_to_string(&path).unwrap();
        both_modes::<S>(&path.display().to_string(), &text, handed_back);
    }
}

#[test]
#[cfg_attr(
    debug_assertions,
    ignore = "every shipped scene in every format: run in release"
)]
fn every_entry_point_draws_the_same_pixels_for_every_shipped_scene_and_format() {
    let mut handed_back = 0;
    fixray::for_each_format!(all: shipped(&mut handed_back));
}

/// A random scene: a small camera, a few planes, sometimes a light, a sphere, a tiled or a
/// finite plane; and in a third of them a floor just below the eye, seen at grazing angles
/// by the scanline through the eye's height, where the pure-geometry kernel's per-row
/// quantities overflow the narrower fixed formats and it hands the row back.
fn random_scene(rng: &mut SplitMix) -> String {
    let (w, h) = (8 + rng.below(24), 6 + rng.below(18));
    let grazing = rng.below(3) == 0;
    let (eye_x, eye_z) = (rng.uniform(1.0, 7.0), rng.uniform(2.0, 9.0));
    let (eye_y, floor_y) = if grazing {
        // The centre of a row, a hair below the eye: D.y = −δ there.
        let row = 1 + rng.below(h - 2);
        let centre = 6.0 * (1.0 - (row as f64 + 0.5) / h as f64);
        let delta = rng.uniform(0.002, 0.01);
        (centre + delta, centre + delta - 2.0 * delta)
    } else {
        (rng.uniform(1.0, 5.0), rng.uniform(-3.0, 0.0))
    };
    // The crate's rules: a file without `rules` is a course file, which only the
    // reference path draws (as such, these scenes would not reach the kernels, and the
    // count of rows the flat kernel hands back would count rows no frame drew with it).
    let mut text = format!(
        "rules fixray\ncamera c {{ pixeldim {w} {h} worlddim 8 6 viewpoint {eye_x:.4} {eye_y:.5} {eye_z:.4} }}\n"
    );
    text.push_str("material a { ambient 0.7 0.2 0.1 diffuse 0.5 0.5 0.5 }\n");
    text.push_str("material b { ambient 0.1 0.3 0.6 diffuse 0.2 0.6 0.3 }\n");
    text.push_str(&format!(
        "plane floor {{ material a normal 0 1 0 point 0 {floor_y:.5} 0 }}\n"
    ));
    for i in 0..rng.below(4) {
        let n = rng.unit();
        text.push_str(&format!(
            "plane p{i} {{ material {} normal {:.4} {:.4} {:.4} point {:.3} {:.3} {:.3} }}\n",
            if i % 2 == 0 { "b" } else { "a" },
            n[0],
            n[1],
            n[2],
            rng.uniform(-15.0, 15.0),
            rng.uniform(-15.0, 15.0),
            rng.uniform(-15.0, -1.0)
        ));
    }
    match rng.below(6) {
        0 => text.push_str("light l { location 4 9 -2 emissivity 6 6 6 }\n"),
        1 => text.push_str("sphere s { material a center 4 3 -8 radius 1.5 }\n"),
        2 => text.push_str(
            "fplane f { material b normal 0 0 1 point 2 1 -6 xdir 1 0 0 dimensions 3 2 }\n",
        ),
        3 => text.push_str(
            "tiled_plane t { material a altmaterial b normal 0 1 0 point 0 -1 0 xdir 1 0 0 dimension 1 1 }\n",
        ),
        _ => {}
    }
    text
}

fn random<S: Scalar>(handed_back: &mut usize) {
    let mut rng = SplitMix(0x2026_1201);
    for case in 0..200 {
        let text = random_scene(&mut rng);
        // A scene a format cannot hold is a parse error, not a case.
        if Scene::<S>::parse(&text).is_ok() {
            both_modes::<S>(&format!("random scene {case}:\n{text}"), &text, handed_back);
        }
    }
}

#[test]
fn every_entry_point_draws_the_same_pixels_for_random_scenes() {
    let mut handed_back = 0;
    fixray::for_each_format!(all: random(&mut handed_back));
    // Not vacuous: the kernel handed scanlines back, and they were compared too.
    assert!(handed_back > 0, "no scanline was handed back");
    println!("scanlines handed back by the pure-geometry kernel: {handed_back}");
}
