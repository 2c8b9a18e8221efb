//! The fast primary-ray path (`fixray::fast`) against the per-pixel reference path: the
//! same picture except where the two resolve a boundary differently (two planes meeting,
//! the horizon, the screen). Budgets per scene and format, and no difference at all inside
//! an object's area (3×3 neighbourhood of the reference seeing one object). In every
//! format of the one list (`fixray::num::formats::FORMATS`).

mod common;

use common::probes::sqrt_is_rounded;

use embedded_graphics::pixelcolor::Rgb888;
use fixray::num::formats::FORMATS;
use fixray::shade::to_rgb888;
use fixray::shade::trace_pixel;
use fixray::{Scalar, Scene, render_line};

/// The fast path against the reference path in format `S` on one scene, within the
/// scene's budget at I16F16's resolution scaled by [`budget`].
fn check<S: Scalar>(name: &str, text: &str, budget_at_i16f16: f64) {
    let budget = budget::<S>(budget_at_i16f16);
    let bounded = sqrt_is_rounded::<S>();
    let scene = Scene::<S>::parse(text).unwrap();
    assert!(
        fixray::internals::Primary::new(&scene.view()).is_some(),
        "{name}: fast path applies"
    );
    let (w, h) = (
        usize::from(scene.camera.width),
        usize::from(scene.camera.height),
    );
    let mut fast = vec![vec![Rgb888::new(0, 0, 0); w]; h];
    for (row, line) in fast.iter_mut().enumerate() {
        render_line(&scene, u16::try_from(row).unwrap(), line);
    }
    let reference: Vec<Vec<(Option<usize>, Rgb888)>> = (0..h)
        .map(|y| {
            (0..w)
                .map(|x| {
                    let t =
                        trace_pixel(&scene, u16::try_from(x).unwrap(), u16::try_from(y).unwrap());
                    (t.hit.map(|(i, _)| i), to_rgb888(t.color))
                })
                .collect()
        })
        .collect();
    let mut differ = 0;
    for y in 0..h {
        for x in 0..w {
            if fast[y][x] == reference[y][x].1 {
                continue;
            }
            differ += 1;
            // Interior: the reference sees one object in the 3×3 neighbourhood and no
            // colour edge there (a checkerboard's tile edges are edges too).
            let (o, c) = reference[y][x];
            let near = |a: Rgb888, b: Rgb888| {
                use embedded_graphics::pixelcolor::RgbColor;
                a.r()
                    .abs_diff(b.r())
                    .max(a.g().abs_diff(b.g()))
                    .max(a.b().abs_diff(b.b()))
                    <= 8
            };
            let interior = y > 0
                && x > 0
                && y + 1 < h
                && x + 1 < w
                && (y - 1..=y + 1).all(|yy| {
                    (x - 1..=x + 1)
                        .all(|xx| reference[yy][xx].0 == o && near(reference[yy][xx].1, c))
                });
            // Inside an object the two paths may differ only by the shading's last level.
            if interior {
                let (a, b) = (fast[y][x], reference[y][x].1);
                use embedded_graphics::pixelcolor::RgbColor;
                let d = a
                    .r()
                    .abs_diff(b.r())
                    .max(a.g().abs_diff(b.g()))
                    .max(a.b().abs_diff(b.b()));
                assert!(
                    d <= 1 || !bounded,
                    "{name} {}: ({x}, {y}) {a:?} vs {b:?}",
                    S::NAME
                );
            }
        }
    }
    let share = differ as f64 / (w * h) as f64;
    println!(
        "{name:<8} {:<7} fast vs reference: {:.3} % of pixels differ",
        S::NAME,
        100.0 * share
    );
    if bounded {
        assert!(share <= budget, "{name} {}: {share}", S::NAME);
    }
}

/// The budget of format `S` for a scene whose budget at I16F16's resolution is `budget`:
/// the pixels where the two paths resolve a boundary (or a shading level) differently lie
/// in bands as wide as the rounding, so the budget grows with `DELTA` above I16F16's:
/// `budget · max(1, DELTA / 2⁻¹⁶)` (I20F12: 16 ×). Finer formats keep I16F16's.
fn budget<S: Scalar>(budget: f64) -> f64 {
    budget * (S::DELTA.to_f64() / (-16f64).exp2()).max(1.0)
}

#[test]
fn the_fast_path_draws_the_reference_picture() {
    let scenes: [(&str, &str, f64); 6] = [
        ("planes", include_str!("../scenes/planes.scene"), 0.01),
        ("spheres", include_str!("../scenes/spheres.scene"), 0.01),
        ("horizon", include_str!("../scenes/horizon.scene"), 0.01),
        ("default", include_str!("../scenes/default.scene"), 0.03),
        ("tiles", include_str!("../scenes/tiles.scene"), 0.02),
        ("triangles", include_str!("../scenes/triangles.scene"), 0.01),
    ];
    for (name, text, budget) in scenes {
        fixray::for_each_format!(all: check(name, text, budget));
    }
}

/// Against the f64 reference picture: the fast path is as close to it as the reference
/// path is (it changes rounding, not the definition).
fn against_f64<S: Scalar>(name: &str, text: &str) -> (f64, f64) {
    let scene = Scene::<S>::parse(text).unwrap();
    let truth = Scene::<f64>::parse(text).unwrap();
    let (w, h) = (scene.camera.width, scene.camera.height);
    let (mut fast_differ, mut ref_differ) = (0u32, 0u32);
    let mut line = vec![Rgb888::new(0, 0, 0); usize::from(w)];
    for y in 0..h {
        render_line(&scene, y, &mut line);
        for x in 0..w {
            let t = to_rgb888(trace_pixel(&truth, x, y).color);
            fast_differ += u32::from(line[usize::from(x)] != t);
            ref_differ += u32::from(to_rgb888(trace_pixel(&scene, x, y).color) != t);
        }
    }
    let n = f64::from(u32::from(w) * u32::from(h));
    let r = (f64::from(fast_differ) / n, f64::from(ref_differ) / n);
    println!(
        "{name:<8} {:<7} against f64: fast {:.3} %, reference {:.3} %",
        S::NAME,
        100.0 * r.0,
        100.0 * r.1
    );
    r
}

#[test]
fn the_fast_path_is_as_close_to_f64_as_the_reference_path() {
    for (name, text) in [
        ("planes", include_str!("../scenes/planes.scene")),
        ("spheres", include_str!("../scenes/spheres.scene")),
        ("horizon", include_str!("../scenes/horizon.scene")),
        ("default", include_str!("../scenes/default.scene")),
        ("tiles", include_str!("../scenes/tiles.scene")),
        ("triangles", include_str!("../scenes/triangles.scene")),
    ] {
        for format in FORMATS {
            let (fast, reference) = fixray::with_format!(format, against_f64(name, text)).unwrap();
            assert!(
                fast <= 2.0 * reference + 0.005,
                "{name} {format}: fast {fast}, reference {reference}"
            );
        }
    }
}
