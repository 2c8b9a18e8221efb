//! The sampling section of `docs/accuracy.md`: frames drawn in blocks
//! (`fixray::Sampling::Blocks`) against the exact frame and against f64, in I16F16 on the
//! host. Every figure is a count of pixels (deterministic), so `cargo xtask figures
//! --check` checks the table; `cargo xtask accuracy` writes the whole section.

use std::fmt::Write as _;

use crate::pictures::{difference, psnr, squared_error};
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use fixray::anim::{Bounce, Orbit};
use fixray::{BlockSize, Frame, I16F16, Sampling, Scalar, Scene};

/// The modes measured: the exact frame, then blocks of each size at bounds 1 and 8 (the
/// board's orbit draws 8×8 blocks at 8).
const MODES: [Sampling; 7] = [
    Sampling::Exact,
    Sampling::blocks(BlockSize::Two, 1),
    Sampling::blocks(BlockSize::Two, 8),
    Sampling::blocks(BlockSize::Four, 1),
    Sampling::blocks(BlockSize::Four, 8),
    Sampling::blocks(BlockSize::Eight, 1),
    Sampling::blocks(BlockSize::Eight, 8),
];

/// A frame drawn whole, with how many of its pixels were filled from blocks' corners.
fn draw<S: Scalar>(scene: &Scene<S>, sampling: Sampling) -> (Vec<Rgb888>, usize) {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut out = vec![Rgb888::BLACK; usize::from(w) * usize::from(h)];
    let filled = Frame::<S>::new(scene)
        .with_sampling(sampling)
        .render_rows(0..h, &mut out);
    (out, filled)
}

/// SSIM of two pictures (the report's: `image-compare`'s, 8×8 windows, worst channel).
fn ssim(a: &[Rgb888], b: &[Rgb888], w: u16) -> f64 {
    let picture = |p: &[Rgb888]| {
        let h = u32::try_from(p.len() / usize::from(w)).unwrap_or(0);
        image::RgbImage::from_fn(u32::from(w), h, |x, y| {
            let c = p[y as usize * usize::from(w) + x as usize];
            image::Rgb([c.r(), c.g(), c.b()])
        })
    };
    image_compare::rgb_similarity_structure(
        &image_compare::Algorithm::MSSIMSimple,
        &picture(a),
        &picture(b),
    )
    .map_or(f64::NAN, |s| s.score)
}

/// What one mode gives over a scene's frames, summed.
#[derive(Default)]
struct Tally {
    pixels: usize,
    filled: usize,
    /// Pixels beyond 1 and 2 levels of the exact frame, and of the f64 frame.
    exact: [usize; 2],
    f64: [usize; 2],
    squared: f64,
    /// The worst frame's SSIM against the exact frame.
    ssim: f64,
}

/// A frame of a scene in I16F16 and in f64.
type Pair = (Scene<I16F16>, Scene<f64>);

/// Tallies every mode over the frames `scenes` (each in I16F16 and in f64).
fn tally(frames: &[Pair]) -> Vec<Tally> {
    let mut tallies: Vec<Tally> = MODES
        .iter()
        .map(|_| Tally {
            ssim: 1.0,
            ..Tally::default()
        })
        .collect();
    for (scene, reference) in frames {
        let w = scene.camera.width;
        let (exact, _) = draw(scene, Sampling::Exact);
        let (truth, _) = draw(reference, Sampling::Exact);
        for (mode, t) in MODES.iter().zip(tallies.iter_mut()) {
            let (picture, filled) = draw(scene, *mode);
            let beyond = |other: &[Rgb888]| {
                [1, 2].map(|k| {
                    picture
                        .iter()
                        .zip(other)
                        .filter(|(a, b)| difference(**a, **b) > k)
                        .count()
                })
            };
            let (e, f) = (beyond(&exact), beyond(&truth));
            t.pixels += picture.len();
            t.filled += filled;
            for i in 0..2 {
                t.exact[i] += e[i];
                t.f64[i] += f[i];
            }
            t.squared += squared_error(&picture, &exact);
            t.ssim = t.ssim.min(ssim(&picture, &exact, w));
        }
    }
    tallies
}

/// A mode as the table names it.
fn mode_name(mode: Sampling) -> String {
    match mode {
        Sampling::Exact => "exact".to_string(),
        Sampling::Blocks { size, bound } => {
            let b = size.pixels();
            format!("{b}×{b}, bound {bound}")
        }
    }
}

/// The scenes: a name and its frames (I16F16 and f64).
fn scenes() -> Vec<(&'static str, Vec<Pair>)> {
    let boing = include_str!("../../scenes/boing-240x240.scene");
    let parse = |text: &str| {
        (
            Scene::<I16F16>::parse(text).expect("a shipped scene parses"),
            Scene::<f64>::parse(text).expect("a shipped scene parses"),
        )
    };
    let animated = |orbit: bool| -> Vec<Pair> {
        let (a, b) = parse(boing);
        let (bounce_a, bounce_b) = (
            Bounce::boing(&a.objects).expect("the ball"),
            Bounce::boing(&b.objects).expect("the ball"),
        );
        let (orbit_a, orbit_b) = (
            Orbit::boing(&a.objects).expect("the ball"),
            Orbit::boing(&b.objects).expect("the ball"),
        );
        (0..bounce_a.frames())
            .map(|k| {
                let (mut x, mut y) = (a.clone(), b.clone());
                bounce_a.apply(&mut x, k).expect("the path fits");
                bounce_b.apply(&mut y, k).expect("the path fits");
                if orbit {
                    orbit_a.apply(&mut x, k).expect("the turn fits");
                    orbit_b.apply(&mut y, k).expect("the turn fits");
                }
                (x, y)
            })
            .collect()
    };
    vec![
        (
            "the boing ball at 240×240, still camera (16 frames)",
            animated(false),
        ),
        (
            "the boing ball at 240×240, circling camera (16 frames)",
            animated(true),
        ),
        (
            "`spheres`",
            vec![parse(include_str!("../../scenes/spheres.scene"))],
        ),
        (
            "`default`",
            vec![parse(include_str!("../../scenes/default.scene"))],
        ),
    ]
}

/// The table: for each scene and mode, the pixels filled, the pixels beyond 1 and 2
/// levels of the exact frame and of f64, the PSNR and the worst frame's SSIM against the
/// exact frame.
pub fn table() -> String {
    let mut out = String::from(
        "| scene | sampling | pixels filled | > 1 level of exact | > 2 levels of exact | \
         > 1 level of f64 | > 2 levels of f64 | PSNR against exact | SSIM against exact |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for (name, frames) in scenes() {
        for (mode, t) in MODES.iter().zip(tally(&frames)) {
            let share = |n: usize| 100.0 * n as f64 / t.pixels as f64;
            let psnr = if t.squared == 0.0 {
                "∞".to_string()
            } else {
                format!("{:.1} dB", psnr(t.squared, t.pixels))
            };
            writeln!(
                out,
                "| {name} | {} | {:.1} % | {:.3} % | {:.3} % | {:.3} % | {:.3} % | {psnr} | {:.4} |",
                mode_name(*mode),
                share(t.filled),
                share(t.exact[0]),
                share(t.exact[1]),
                share(t.f64[0]),
                share(t.f64[1]),
                t.ssim,
            )
            .unwrap();
        }
    }
    out
}

/// The section of `docs/accuracy.md`: what it measures, and the table between its
/// figures markers.
pub fn section() -> String {
    format!(
        "\n## Sampling: frames drawn in blocks\n\n\
         `Frame::with_sampling(Sampling::blocks(size, bound))` traces blocks of `size × size` \
         pixels at their corners and fills a block from them where a certificate holds (no \
         sphere's box, one plane, the tile or the tile's edge located, one shadow state, the \
         colour's curvature within `bound` levels); any other block is drawn as the exact frame \
         draws it. In I16F16 on the host, every frame of each scene (the boing ball's 16, still \
         and with the camera circling it, `fixray::anim::Orbit`): the share of pixels filled, \
         the share beyond 1 and 2 levels (largest channel difference) of the exact frame and of \
         the f64 frame, the PSNR over all the frames and the worst frame's SSIM (8×8 windows, \
         worst channel) against the exact frame. The exact rows' f64 columns are the format's \
         own error. `cargo xtask figures --check` (CI) checks the table.\n\n\
         <!-- figures: sampling -->\n{}<!-- end figures -->\n\n\
         What each mode costs on the chips: instructions per pixel in I16F16 under QEMU, \
         one frame of each scene, hashing included, as `cargo xtask calibrate` counts them \
         for the advisor (`docs/calibration.md`; the RP2040's cycles are the Cortex-M0's \
         count times the board's cycles per instruction, [`advisor.md`](advisor.md)). A mode \
         whose blocks the scene's kind refuses draws the exact frame and is left out. \
         `cargo xtask figures --check` (CI) checks this table too.\n\n\
         <!-- figures: sampling-cost -->\n{}<!-- end figures -->\n",
        table(),
        crate::advice::sampling_costs().unwrap_or_else(|e| format!("{e}\n"))
    )
}
