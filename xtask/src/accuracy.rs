//! `accuracy`: what each bit of accuracy costs in time. Measures every number format on
//! every shipped scene against the f64 reference (accuracy), on the host (criterion
//! medians) and on Cortex-M0 and Cortex-M4F under QEMU (instructions, flash), sweeps the
//! precision epsilon on the grazing scene, and writes `docs/accuracy.md` and
//! `docs/accuracy.png`. Never edit those by hand: run
//!
//! ```text
//! cargo xtask accuracy
//! ```
//!
//! The firmware columns need `qemu-system-arm` and the thumb targets (`.ci/run` installs
//! both); without them the report says so and leaves those columns empty. `--quick` skips
//! the firmware and shortens the host timing (for CI, which checks the command runs).

use crate::qemu;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use criterion::Criterion;
use embedded_graphics::mono_font::{MonoTextStyle, ascii::FONT_6X10};
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Circle, Line, PrimitiveStyle, Rectangle};
use embedded_graphics::text::{Alignment, Text};
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use fixray::compare::{Comparison, compare};
use fixray::{Scalar, Scene, render_line, trace_pixel};

/// The scenes: name, what it is, text. The grazing scene is third (the epsilon sweep).
const SCENES: [(&str, &str, &str); 8] = [
    (
        "default",
        "the default scene: five planes, ambient + one light with shadows",
        include_str!("../../scenes/default.scene"),
    ),
    (
        "planes",
        "planes only: a corridor of five planes, ambient only",
        include_str!("../../scenes/planes.scene"),
    ),
    (
        "horizon",
        "grazing: an infinite floor to the horizon, ambient only",
        include_str!("../../scenes/horizon.scene"),
    ),
    (
        "spheres",
        "spheres on a floor, one light with shadows",
        include_str!("../../scenes/spheres.scene"),
    ),
    (
        "tiles",
        "a tiled checkerboard floor and a finite plane, ambient only",
        include_str!("../../scenes/tiles.scene"),
    ),
    (
        "specular",
        "specular glints (shininess 4 and 40)",
        include_str!("../../scenes/specular.scene"),
    ),
    (
        "spotlight",
        "a spotlight's cone beside a point light",
        include_str!("../../scenes/spotlight.scene"),
    ),
    (
        "mirror",
        "reflection: a mirror sphere and a half-mirror floor",
        include_str!("../../scenes/mirror.scene"),
    ),
];

/// Every format of the one list, with what it is.
const FORMATS: [(&str, &str); 8] = fixray::num::formats::DESCRIBED;

/// Something to do in one number format, chosen at run time by name.
trait PerFormat {
    type Out;
    fn run<S: Scalar>(&mut self) -> Self::Out;
}

/// Runs `v` in the format named `format` (one of the one list's; an unknown name is an
/// error naming the known ones, never silently f64).
fn with_format<V: PerFormat>(format: &str, v: &mut V) -> V::Out {
    fixray::with_format!(format, run_in::<_, V>(v)).unwrap_or_else(|e| panic!("{e}"))
}

fn run_in<S: Scalar, V: PerFormat>(v: &mut V) -> V::Out {
    v.run::<S>()
}

/// Renders a frame into an RGB image.
fn image<S: Scalar>(scene: &Scene<S>) -> image::RgbImage {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut line = vec![Rgb888::BLACK; usize::from(w)];
    let mut img = image::RgbImage::new(u32::from(w), u32::from(h));
    for row in 0..h {
        render_line(scene, row, &mut line);
        for (x, c) in line.iter().enumerate() {
            img.put_pixel(x as u32, u32::from(row), image::Rgb([c.r(), c.g(), c.b()]));
        }
    }
    img
}

/// Accuracy of one format on one scene.
struct Accuracy {
    cmp: Comparison,
    ssim: f64,
    delta: f64,
}

struct MeasureAccuracy<'a>(&'a str);
impl PerFormat for MeasureAccuracy<'_> {
    type Out = Accuracy;
    fn run<S: Scalar>(&mut self) -> Accuracy {
        let scene = Scene::<S>::parse(self.0).expect("shipped scenes parse in every format");
        let reference = Scene::<f64>::parse(self.0).expect("and in f64");
        let cmp = compare(&scene, &reference, |_, _, _, _| {});
        let ssim = image_compare::rgb_similarity_structure(
            &image_compare::Algorithm::MSSIMSimple,
            &image(&scene),
            &image(&reference),
        )
        .map_or(f64::NAN, |s| s.score);
        Accuracy {
            cmp,
            ssim,
            delta: S::DELTA.to_f64(),
        }
    }
}

/// Benchmarks one frame of one scene in one format with criterion.
struct Bench<'a> {
    c: &'a mut Criterion,
    scene: &'a str,
    text: &'a str,
}
impl PerFormat for Bench<'_> {
    type Out = ();
    fn run<S: Scalar>(&mut self) {
        let scene = Scene::<S>::parse(self.text).expect("shipped scenes parse");
        let mut line = vec![Rgb888::BLACK; usize::from(scene.camera.width)];
        self.c
            .benchmark_group(self.scene)
            .bench_function(S::NAME, |b| {
                b.iter(|| {
                    for row in 0..scene.camera.height {
                        render_line(std::hint::black_box(&scene), row, &mut line);
                    }
                })
            });
    }
}

/// Reads criterion's median (ns) for a benchmark from its estimates file.
fn criterion_median(dir: &Path, group: &str, function: &str) -> Option<f64> {
    let text =
        std::fs::read_to_string(dir.join(group).join(function).join("new/estimates.json")).ok()?;
    let median = &text[text.find("\"median\"")?..];
    let at = median.find("\"point_estimate\":")? + "\"point_estimate\":".len();
    let end = median[at..].find([',', '}'])?;
    median[at..at + end].trim().parse().ok()
}

/// One row of the epsilon sweep.
struct Sweep {
    deltas: f64,
    epsilon: f64,
    false_misses: u32,
    false_hits: u32,
    wrong_object: u32,
}

/// Renders the scene with epsilon = DELTA × 2^k for k = 0, 1, … up to 2⁻⁴ and counts hit/miss
/// disagreements with the f64 render at its default epsilon (the ground truth).
struct SweepEpsilon<'a>(&'a str);
impl PerFormat for SweepEpsilon<'_> {
    type Out = Vec<Sweep>;
    fn run<S: Scalar>(&mut self) -> Vec<Sweep> {
        let mut scene = Scene::<S>::parse(self.0).expect("shipped scenes parse");
        let truth = Scene::<f64>::parse(self.0).expect("and in f64");
        let mut rows = Vec::new();
        let mut deltas = 1.0f64;
        while deltas * S::DELTA.to_f64() <= 1.0 / 16.0 {
            let Some(eps) = S::from_f64(deltas * S::DELTA.to_f64()) else {
                break;
            };
            scene.epsilon = eps;
            let mut row = Sweep {
                deltas,
                epsilon: eps.to_f64(),
                false_misses: 0,
                false_hits: 0,
                wrong_object: 0,
            };
            for y in 0..truth.camera.height {
                for x in 0..truth.camera.width {
                    let seen = trace_pixel(&scene, x, y).hit.map(|(i, _)| i);
                    let true_hit = trace_pixel(&truth, x, y).hit.map(|(i, _)| i);
                    match (seen, true_hit) {
                        (None, Some(_)) => row.false_misses += 1,
                        (Some(_), None) => row.false_hits += 1,
                        (Some(a), Some(b)) if a != b => row.wrong_object += 1,
                        _ => {}
                    }
                }
            }
            rows.push(row);
            deltas *= 2.0;
        }
        rows
    }
}

/// Firmware figures for one core and format: (scene → instructions per pixel), flash.
struct Firmware {
    per_pixel: BTreeMap<String, f64>,
    instructions: BTreeMap<String, u64>,
    flash: u64,
    ram: u64,
}

/// Instructions per pixel of each scene's frame in a firmware run.
fn per_pixel(run: &qemu::Run) -> BTreeMap<String, f64> {
    run.frames
        .iter()
        .map(|f| {
            let px = f.number("instructions").expect("reported") as f64 / f.pixels() as f64;
            (f.get("scene").to_string(), px)
        })
        .collect()
}

fn measure_firmware(log: &mut String) -> BTreeMap<(String, String), Firmware> {
    let mut out = BTreeMap::new();
    if !qemu::qemu_available() {
        log.push_str("qemu-system-arm not found: no firmware figures.\n");
        return out;
    }
    let scenes: Vec<&str> = SCENES.iter().map(|s| s.0).collect();
    let scenes = scenes.join(",");
    for (target, core) in qemu::CORES {
        for (format, _) in FORMATS.iter().filter(|(f, _)| *f != "f64") {
            eprintln!("firmware: {core} {format}");
            match qemu::run(target, format, &scenes) {
                Ok(run) => {
                    let per_pixel = per_pixel(&run);
                    let instructions = run
                        .frames
                        .iter()
                        .map(|f| {
                            (
                                f.get("scene").to_string(),
                                f.number("instructions").expect("reported"),
                            )
                        })
                        .collect();
                    let stack = run
                        .frames
                        .iter()
                        .map(|f| f.number("stack").expect("reported"))
                        .max();
                    out.insert(
                        (core.to_string(), format.to_string()),
                        Firmware {
                            per_pixel,
                            instructions,
                            flash: run.flash,
                            ram: run.static_ram + stack.unwrap_or(0),
                        },
                    );
                }
                Err(e) => {
                    let _ = writeln!(log, "{core} {format}: {e}");
                }
            }
        }
    }
    out
}

/// The scenes and formats of the fast-path table.
const FAST_SCENES: [&str; 3] = ["default", "planes", "horizon"];
const FAST_FORMATS: [&str; 5] = ["i16f16", "i16f16r", "i20f12", "i32f32", "f32"];

/// One primary-ray path on one scene in one format.
struct PathRow {
    scene: &'static str,
    format: &'static str,
    path: &'static str,
    /// Share of pixels differing from the f64 reference picture.
    vs_f64: f64,
    /// Share of pixels differing from this format's reference path.
    vs_reference: f64,
    /// Host median ms per frame, and the ratio to the reference path in the same run.
    ms: f64,
    ratio: f64,
}

type Picture = Vec<Rgb888>;

fn share(a: &Picture, b: &Picture) -> f64 {
    a.iter().zip(b).filter(|(x, y)| x != y).count() as f64 / a.len() as f64
}

/// Median wall time of `runs` frames, in ms.
fn median_ms(runs: usize, mut frame: impl FnMut() -> Picture) -> (f64, Picture) {
    let mut times = Vec::new();
    let mut picture = Vec::new();
    for _ in 0..runs {
        let start = std::time::Instant::now();
        picture = std::hint::black_box(frame());
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], picture)
}

struct MeasurePaths<'a> {
    scene: &'static str,
    text: &'a str,
    runs: usize,
}
impl PerFormat for MeasurePaths<'_> {
    type Out = Vec<PathRow>;
    fn run<S: Scalar>(&mut self) -> Vec<PathRow> {
        use fixray::PlaneMode;
        let scene = Scene::<S>::parse(self.text).expect("shipped scenes parse");
        let truth = Scene::<f64>::parse(self.text).expect("and in f64");
        let (w, h) = (scene.camera.width, scene.camera.height);
        let every = |f: &dyn Fn(u16, u16) -> Rgb888| -> Picture {
            (0..h)
                .flat_map(|y| (0..w).map(move |x| (x, y)))
                .map(|(x, y)| f(x, y))
                .collect()
        };
        let truth_picture = every(&|x, y| fixray::pixel(&truth, x, y));
        let lines = |scene: &Scene<S>, mode: PlaneMode| -> Picture {
            let mut out = Vec::new();
            let mut line = vec![Rgb888::BLACK; usize::from(w)];
            let frame = fixray::Frame::with_mode(std::hint::black_box(scene), mode);
            for row in 0..h {
                frame.render_line(row, &mut line);
                out.extend_from_slice(&line);
            }
            out
        };
        let (ref_ms, reference) =
            median_ms(self.runs, || every(&|x, y| fixray::pixel(&scene, x, y)));
        let mut rows = Vec::new();
        let mut push = |path, ms: f64, picture: &Picture| {
            rows.push(PathRow {
                scene: self.scene,
                format: S::NAME,
                path,
                vs_f64: share(picture, &truth_picture),
                vs_reference: share(picture, &reference),
                ms,
                ratio: ref_ms / ms,
            })
        };
        push("reference (per pixel, normalised rays)", ref_ms, &reference);
        if fixray::internals::applies(&scene) {
            // The general fast path, as the renderer used it for these scenes before
            // the pure-geometry kernel: the plane `fast::Primary` picks, its ambient colour.
            let primary = fixray::internals::Primary::new(&scene).expect("a plane scene");
            let (ms, picture) = median_ms(self.runs, || {
                every(&|x, y| match primary
                    .row(&scene, y, x)
                    .map(|r| primary.nearest(&scene, &r))
                {
                    Some(Ok(Some(hit))) => {
                        let m = scene.objects[hit.index].material;
                        fixray::to_rgb888(scene.materials[usize::from(m)].ambient)
                    }
                    Some(Ok(None)) => fixray::to_rgb888(scene.background),
                    _ => fixray::pixel(&scene, x, y),
                })
            });
            push("fast: cross-products, one pixel at a time", ms, &picture);
            let (ms, picture) = median_ms(self.runs, || lines(&scene, PlaneMode::PerPixel));
            push("pure geometry, per-pixel mode", ms, &picture);
            let (ms, picture) = median_ms(self.runs, || lines(&scene, PlaneMode::Spans));
            push("pure geometry, span mode", ms, &picture);
        } else {
            let (ms, picture) = median_ms(self.runs, || lines(&scene, PlaneMode::PerPixel));
            push("fast: cross-products, division-free shadows", ms, &picture);
        }
        rows
    }
}

/// I16F16 firmware in span mode on both cores (instructions per pixel per scene).
fn measure_spans(log: &mut String) -> BTreeMap<String, Firmware> {
    let mut out = BTreeMap::new();
    if !qemu::qemu_available() {
        return out;
    }
    for (target, core) in qemu::CORES {
        eprintln!("firmware: {core} i16f16 spans");
        match qemu::run_spans(target, "i16f16", &FAST_SCENES.join(",")) {
            Ok(run) => {
                let per_pixel = per_pixel(&run);
                out.insert(
                    core.to_string(),
                    Firmware {
                        per_pixel,
                        instructions: BTreeMap::new(),
                        flash: run.flash,
                        ram: run.static_ram,
                    },
                );
            }
            Err(e) => {
                let _ = writeln!(log, "{core} i16f16 spans: {e}");
            }
        }
    }
    out
}

fn fast_section(
    rows: &[PathRow],
    fw: &FirmwareTable,
    spans: &BTreeMap<String, Firmware>,
) -> String {
    let mut r = String::from(
        "\n## Fast primary-ray paths\n\n\
         Each path of the renderer against the per-pixel reference path of its own format and \
         against the f64 reference picture (share of pixels with any channel different), with \
         its host time (median of 15 frames, `std::time::Instant`, in one run: the ratio is \
         reference time / path time) and, for I16F16 and its reciprocal variant, its cost on \
         the chips (instructions per pixel including about 11–13 of frame hashing; the default renderer's path is the \
         firmware table's, span mode is the same firmware built with `FIXRAY_FW_SPANS=1`).\n\n\
         - *fast: cross-products* is the fast kernel (`kernel/fast.rs`): unnormalised directions, the epsilon and \
         screen tests in squared and cross-multiplied form, one division per pixel (for the \
         hit point); shadow rays against planes without division (`Plane::occludes`).\n\
         - *pure geometry* is the pure-geometry kernel (`kernel/flat.rs`), the renderer's path for scenes of infinite planes \
         without lighting: per scanline the interval where each plane is accepted (settled by \
         the per-pixel test) and `1/t'` as a line; per pixel a multiply-add per plane (per-pixel \
         mode) or per run of equal pixels a few comparisons (span mode). Span mode is \
         bit-identical to per-pixel mode in the fixed formats (`tests/flat.rs`).\n\
         - Division: the pure-geometry kernel divides once per plane per frame; the fast \
         path once per pixel (the hit point) plus the lighting's divisions. *i16f16r* is \
         I16F16 with every division replaced by a reciprocal (256-entry table, two Newton \
         steps, 32-bit arithmetic; `fixray::num::variants::I16F16Recip`, within 1 + |q|/2²⁸ \
         DELTAs of the exact quotient): its rows here and in every scene table above show \
         what that costs in accuracy.\n\
         - The reference path is the renderer as it was before the fast paths (one \
         normalised ray and one division per plane per pixel): *× reference* is the \
         speed-up over it, measured in the same run.\n\n\
         | scene | format | path | differ vs reference | differ vs f64 | host ms/frame | host frames/s | × reference | M0 instr/px | M4F instr/px |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for row in rows {
        let chip = |core: &str| -> String {
            if row.format != "i16f16" && row.format != "i16f16r" {
                return "—".into();
            }
            if row.path.contains("span mode") && row.format == "i16f16" {
                spans
                    .get(core)
                    .and_then(|f| f.per_pixel.get(row.scene))
                    .map_or("—".into(), |v| format!("{v:.0}"))
            } else if row.path.contains("per-pixel mode")
                || (row.path.starts_with("fast") && !fixray_flat_scene(row.scene))
            {
                firmware_cell(fw, core, row.format, row.scene)
            } else {
                "—".into()
            }
        };
        let _ = writeln!(
            r,
            "| {} | {} | {} | {:.3} % | {:.3} % | {:.3} | {:.0} | {:.1} | {} | {} |",
            row.scene,
            row.format,
            row.path,
            100.0 * row.vs_reference,
            100.0 * row.vs_f64,
            row.ms,
            1000.0 / row.ms,
            row.ratio,
            chip("cortex-m0"),
            chip("cortex-m4f"),
        );
    }
    r
}

/// Whether a shipped scene is drawn by the pure-geometry kernel.
fn fixray_flat_scene(scene: &str) -> bool {
    scene != "default"
}

fn fmt_sci(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if !v.is_finite() {
        "∞".into()
    } else {
        format!("{v:.2e}")
    }
}

pub fn main(args: &[String]) {
    let quick = args.iter().any(|a| a == "--quick");
    let manifest = crate::root();
    let docs = manifest.join("docs");
    let _ = std::fs::create_dir_all(&docs);

    // Accuracy.
    let mut accuracy = BTreeMap::new();
    for (scene, _, text) in SCENES {
        for (format, _) in FORMATS {
            eprintln!("accuracy: {scene} {format}");
            accuracy.insert(
                (scene, format),
                with_format(format, &mut MeasureAccuracy(text)),
            );
        }
    }

    // Host time: criterion medians, all formats of a scene in one run.
    let criterion_dir = manifest.join("target/accuracy-criterion");
    let mut c = Criterion::default()
        .output_directory(&criterion_dir)
        .without_plots()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(if quick { 50 } else { 300 }))
        .measurement_time(Duration::from_millis(if quick { 100 } else { 1500 }));
    for (scene, _, text) in SCENES {
        for (format, _) in FORMATS {
            with_format(
                format,
                &mut Bench {
                    c: &mut c,
                    scene,
                    text,
                },
            );
        }
    }
    let host: BTreeMap<(&str, &str), f64> = SCENES
        .iter()
        .flat_map(|(s, _, _)| FORMATS.iter().map(move |(f, _)| (*s, *f)))
        .filter_map(|(s, f)| criterion_median(&criterion_dir, s, f).map(|ns| ((s, f), ns)))
        .collect();

    // Epsilon sweep on the grazing scene.
    let horizon = SCENES[2].2; // the grazing scene
    let sweeps: Vec<(&str, Vec<Sweep>)> = FORMATS
        .iter()
        .map(|(f, _)| (*f, with_format(f, &mut SweepEpsilon(horizon))))
        .collect();

    // Firmware.
    let mut firmware_log = String::new();
    let firmware = if quick {
        firmware_log.push_str("--quick: firmware not measured.\n");
        BTreeMap::new()
    } else {
        measure_firmware(&mut firmware_log)
    };

    // Fast paths: each against the reference path and f64, host time, chip cost.
    let mut fast_rows = Vec::new();
    for (scene, _, text) in SCENES.iter().filter(|s| FAST_SCENES.contains(&s.0)) {
        for format in FAST_FORMATS {
            eprintln!("fast paths: {scene} {format}");
            fast_rows.extend(with_format(
                format,
                &mut MeasurePaths {
                    scene,
                    text,
                    runs: if quick { 3 } else { 15 },
                },
            ));
        }
    }
    let spans_fw = if quick {
        BTreeMap::new()
    } else {
        measure_spans(&mut firmware_log)
    };

    let mut report = write_report(&accuracy, &host, &sweeps, &firmware, &firmware_log);
    report.push_str(&fast_section(&fast_rows, &firmware, &spans_fw));
    std::fs::write(docs.join("accuracy.md"), report).expect("docs/ is writable");
    plot(&accuracy, &host, &firmware, &docs.join("accuracy.png"));
    println!("wrote docs/accuracy.md and docs/accuracy.png");
}

type AccuracyTable<'a> = BTreeMap<(&'a str, &'a str), Accuracy>;
type FirmwareTable = BTreeMap<(String, String), Firmware>;

fn firmware_cell(fw: &FirmwareTable, core: &str, format: &str, scene: &str) -> String {
    fw.get(&(core.to_string(), format.to_string()))
        .and_then(|f| f.per_pixel.get(scene))
        .map_or("—".into(), |v| format!("{v:.0}"))
}

fn write_report(
    accuracy: &AccuracyTable<'_>,
    host: &BTreeMap<(&str, &str), f64>,
    sweeps: &[(&str, Vec<Sweep>)],
    fw: &FirmwareTable,
    firmware_log: &str,
) -> String {
    let mut r = String::new();
    let date = std::process::Command::new("date")
        .args(["-u", "+%Y-%m-%d %H:%M UTC"])
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    let _ = writeln!(
        r,
        "# What accuracy costs\n\n\
         Generated by `cargo xtask accuracy` ({date}). Do not edit by hand: \
         every figure here is measured by that command.\n\n\
         - **Accuracy** is against the f64 render of the same scene, pixel by pixel \
         (`fixray::compare`): |Δt| and hit-point error over pixels where both see the same \
         object; *objects* is the share of pixels whose primary rays see different objects \
         (hit/miss disagreement included); *differ* the share with any channel different; \
         SSIM from the `image-compare` crate (MIT), 8×8 windows, worst channel.\n\
         - **Host time** is criterion's median of 10 samples for one frame (`render_line` \
         over every row), with the ratio to f64 measured in the same run. The host is a \
         shared 2-core x86-64 machine: compare ratios, not absolute times.\n\
         - **Instructions** are counted on the firmware (`examples/firmware.rs`) under QEMU \
         with `-icount shift=0` (deterministic), per pixel of the frame, including about \
         11–13 instructions per pixel of frame hashing. **Flash** is the firmware with that \
         one format and the scenes' text; **RAM** is static data plus the deepest stack.\n\
         - The pixel columns (differing pixels, PSNR, SSIM) are the pixels the renderer \
         draws (`render` / `render_line`, which the kernel chooses once per frame: \
         `tests/kernels.rs` checks they agree), so they and the host and chip costs \
         describe the same path, in which primary rays of plane scenes take the fast kernel \
         (`kernel/fast.rs`) and scenes of infinite planes without lighting the pure-geometry \
         kernel (`kernel/flat.rs`, per-pixel mode). |Δt|, the hit-point error and hit/miss \
         disagreement are properties of the primary ray, defined by the reference path \
         (`trace_pixel`, the definition of `scene-format.md`). The last section gives the \
         reference path a row of its own and compares every kernel with it, with its \
         cost.\n"
    );

    // Goals.
    let per_px = |core: &str, f: &str| {
        fw.get(&(core.to_string(), f.to_string()))
            .and_then(|x| x.instructions.get("default"))
            .copied()
    };
    let _ = writeln!(r, "## Goals\n");
    match (per_px("cortex-m0", "i16f16"), per_px("cortex-m0", "f32")) {
        (Some(fixed), Some(float)) => {
            let ratio = float as f64 / fixed as f64;
            let mismatch = accuracy[&("default", "i16f16")].cmp.differing_share() * 100.0;
            let met = ratio >= 10.0 && mismatch < 1.0;
            let _ = writeln!(
                r,
                "- **Cortex-M0: I16F16 at least 10× fewer instructions than soft-float f32 on \
                 the default scene, under 1 % pixel mismatch.** Measured: I16F16 {fixed} \
                 instructions per frame, f32 {float}: **{ratio:.2}×**, at {mismatch:.2} % \
                 differing pixels. **{}** {}",
                if met { "Met." } else { "Not met." },
                if met {
                    ""
                } else {
                    "Primary rays take the fast kernel (`kernel/fast.rs`: no normalisation, one \
                     division per pixel), shadow rays against planes divide no more \
                     (`Plane::occludes`), and on the M0 double-width products are formed \
                     from 16-bit halves instead of the 64-bit multiply helper. What remains \
                     is per light and pixel: normalising the direction to the light (divisions \
                     and a square root) and the falloff division, each I16F16 division a \
                     ~370-instruction 64-bit helper call on the M0. Soft-float f32 has the \
                     same structure, so the ratio moves less than the counts."
                }
            );
        }
        _ => {
            let _ = writeln!(r, "- Cortex-M0 goal: not measured (no firmware figures).");
        }
    }
    let fixed_m4: Vec<(&str, u64)> = ["i16f16", "i16f16n", "i16f16r", "i20f12", "i32f32"]
        .iter()
        .filter_map(|f| per_px("cortex-m4f", f).map(|n| (*f, n)))
        .collect();
    match (
        fixed_m4.iter().min_by_key(|(_, n)| *n),
        per_px("cortex-m4f", "f32"),
    ) {
        (Some((best, fixed)), Some(float)) => {
            let ratio = *fixed as f64 / float as f64;
            let met = ratio <= 1.5;
            let _ = writeln!(
                r,
                "- **Cortex-M4F: the fastest fixed format within 1.5× of hardware f32.** \
                 Measured: {best} {fixed} instructions per frame, f32 {float}: **{ratio:.2}×**. \
                 **{}** {}\n",
                if met { "Met." } else { "Not met." },
                if met {
                    ""
                } else {
                    "With an FPU, f32 division and square root are single instructions; the \
                     fixed formats pay a 64-bit division helper (~120 instructions) per \
                     division and a bit-by-bit square root (~170), and after the fast primary \
                     path most of them are in the lighting (normalising the direction to the \
                     light and the falloff; shadow rays against planes no longer divide)."
                }
            );
        }
        _ => {
            let _ = writeln!(
                r,
                "- Cortex-M4F goal: not measured (no firmware figures).\n"
            );
        }
    }

    // Per-scene tables.
    for (scene, what, _) in SCENES {
        let f64_ns = host.get(&(scene, "f64")).copied();
        let _ = writeln!(
            r,
            "## Scene `{scene}`: {what}\n\n\
             | format | max \\|Δt\\| | max \\|Δt\\| (DELTAs) | mean \\|Δt\\| | max hit error | \
             objects | differ | PSNR dB | SSIM | host ms/frame | × f64 | M0 instr/px | \
             M4F instr/px |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|"
        );
        for (format, _) in FORMATS {
            let a = &accuracy[&(scene, format)];
            let c = &a.cmp;
            let ns = host.get(&(scene, format)).copied();
            let _ = writeln!(
                r,
                "| {format} | {} | {} | {} | {} | {:.3} % | {:.3} % | {} | {:.4} | {} | {} | {} | {} |",
                fmt_sci(c.max_dt),
                if c.max_dt == 0.0 {
                    "0".into()
                } else {
                    format!("{:.0}", c.max_dt / a.delta)
                },
                fmt_sci(c.mean_dt()),
                fmt_sci(c.max_hit_error),
                100.0 * f64::from(c.object_disagreements) / f64::from(c.pixels.max(1)),
                100.0 * c.differing_share(),
                if c.psnr().is_finite() {
                    format!("{:.1}", c.psnr())
                } else {
                    "∞".into()
                },
                a.ssim,
                ns.map_or("—".into(), |n| format!("{:.3}", n / 1e6)),
                match (ns, f64_ns) {
                    (Some(n), Some(f)) => format!("{:.2}", n / f),
                    _ => "—".into(),
                },
                firmware_cell(fw, "cortex-m0", format, scene),
                firmware_cell(fw, "cortex-m4f", format, scene),
            );
        }
        r.push('\n');
    }

    // Flash.
    if !fw.is_empty() {
        let _ = writeln!(
            r,
            "## Flash and RAM per format\n\n| format | M0 flash | M0 RAM | M4F flash | M4F RAM |\n|---|---|---|---|---|"
        );
        for (format, _) in FORMATS.iter().filter(|(f, _)| *f != "f64") {
            let cell = |core: &str| {
                fw.get(&(core.to_string(), format.to_string()))
                    .map_or(("—".into(), "—".into()), |f| {
                        (f.flash.to_string(), f.ram.to_string())
                    })
            };
            let (m0f, m0r) = cell("cortex-m0");
            let (m4f, m4r) = cell("cortex-m4f");
            let _ = writeln!(r, "| {format} | {m0f} | {m0r} | {m4f} | {m4r} |");
        }
        r.push('\n');
    }

    // Epsilon sweep.
    let _ = writeln!(
        r,
        "## Precision epsilon sweep (grazing scene `horizon`)\n\n\
         Each format renders the horizon scene with epsilon = DELTA × 2^k, from 1 DELTA up to \
         2⁻⁴; the ground truth is the f64 render at its default epsilon. *False misses*: \
         the truth sees an object, the format the background; *false hits*: the reverse; \
         *wrong object*: both hit, different objects. The row marked ◀ is the format's \
         shipped default (16 DELTAs).\n"
    );
    for (format, rows) in sweeps {
        let _ = writeln!(
            r,
            "### {format}\n\n| epsilon (DELTAs) | epsilon | false misses | false hits | wrong object |\n|---|---|---|---|---|"
        );
        for row in rows {
            let _ = writeln!(
                r,
                "| {:.0}{} | {:.3e} | {} | {} | {} |",
                row.deltas,
                if row.deltas == 16.0 { " ◀" } else { "" },
                row.epsilon,
                row.false_misses,
                row.false_hits,
                row.wrong_object
            );
        }
        r.push('\n');
    }
    let _ = writeln!(
        r,
        "**Defaults.** Every format ships epsilon = 16 DELTAs (`fixray::EPSILON_DELTAS`): \
         the computed N·d carries at most 7.5 DELTAs of rounding, so 16 keeps its sign right \
         with a 2× margin, and a ray that passes the test is never sent to the wrong side of \
         a plane. Measured here, per format:\n"
    );
    for (format, rows) in sweeps {
        let at = |d: f64| rows.iter().find(|row| row.deltas == d);
        if let (Some(one), Some(def)) = (at(1.0), at(16.0)) {
            let floor = one.false_misses;
            let _ = writeln!(
                r,
                "- {format}: at 16 DELTAs {} false misses, {} false hits, {} wrong objects; \
                 at 1 DELTA {} / {} / {}. {}",
                def.false_misses,
                def.false_hits,
                def.wrong_object,
                one.false_misses,
                one.false_hits,
                one.wrong_object,
                if def.false_misses == floor && def.false_hits == 0 {
                    "The default costs nothing over the smallest epsilon: the misses that \
                     remain are rays whose t leaves the format's range (the horizon)."
                        .to_string()
                } else {
                    format!(
                        "Going from 1 to 16 DELTAs trades {} false hits and wrong objects \
                         for {} more grazing misses, next to the horizon where t is huge \
                         and its error largest.",
                        (one.false_hits + one.wrong_object)
                            .saturating_sub(def.false_hits + def.wrong_object),
                        def.false_misses.saturating_sub(floor)
                    )
                }
            );
        }
    }
    r.push('\n');

    let _ = writeln!(
        r,
        "## The plot\n\n![error against instructions per pixel](accuracy.png)\n"
    );
    let _ = writeln!(
        r,
        "Two errors on the default scene against instructions per pixel (all log scales), \
         one point per format and core: left, the mean hit-point error in world units \
         (geometry); right, the share of pixels that differ from f64 (what the user sees). \
         The lines join each core's Pareto front (no other point of that core is both cheaper \
         and more accurate). f64 is the reference and has no error to plot. Without firmware \
         figures the x axis is host nanoseconds per pixel.\n"
    );
    if !firmware_log.is_empty() {
        let _ = writeln!(r, "## Notes from this run\n\n```text\n{firmware_log}```");
    }
    r
}

/// Colour per format in the plot.
fn format_color(format: &str) -> Rgb888 {
    match format {
        "i16f16" => Rgb888::new(0, 114, 178),
        "i16f16n" => Rgb888::new(86, 180, 233),
        "i16f16r" => Rgb888::new(120, 60, 160),
        "i20f12" => Rgb888::new(0, 158, 115),
        "i32f32" => Rgb888::new(213, 94, 0),
        "f32" => Rgb888::new(204, 121, 167),
        _ => Rgb888::new(230, 159, 0),
    }
}

fn plot(
    accuracy: &AccuracyTable<'_>,
    host: &BTreeMap<(&str, &str), f64>,
    fw: &FirmwareTable,
    path: &Path,
) {
    // Points: (cost, label, core, format); errors looked up per panel.
    let mut points: Vec<(f64, String, &str, &str)> = Vec::new();
    let use_fw = !fw.is_empty();
    for (format, _) in FORMATS.iter().filter(|(f, _)| *f != "f64") {
        if use_fw {
            for (_, core) in qemu::CORES {
                if let Some(x) = fw
                    .get(&(core.to_string(), format.to_string()))
                    .and_then(|f| f.per_pixel.get("default"))
                {
                    points.push((*x, format.to_string(), core, format));
                }
            }
        } else if let Some(ns) = host.get(&("default", *format)) {
            points.push((ns / 19200.0, format.to_string(), "host", format));
        }
    }
    let (w, h) = (1200i32, 560i32);
    let mut d = SimulatorDisplay::<Rgb888>::new(Size::new(w as u32, h as u32));
    let _ = d.clear(Rgb888::WHITE);
    let text = MonoTextStyle::new(&FONT_6X10, Rgb888::BLACK);
    let title = if use_fw {
        "What accuracy costs (default scene). x: instructions per pixel under QEMU; circle: Cortex-M0, square: Cortex-M4F; lines: Pareto fronts"
    } else {
        "What accuracy costs (default scene). x: host ns per pixel; lines: Pareto front"
    };
    let _ = Text::new(title, Point::new(20, 16), text).draw(&mut d);
    type Metric = fn(&Comparison) -> f64;
    let panels: [(&str, Metric); 2] = [
        (
            "mean hit-point error vs f64 (world units)",
            Comparison::mean_hit_error,
        ),
        (
            "share of pixels differing from f64",
            Comparison::differing_share,
        ),
    ];
    for (k, (label, metric)) in panels.into_iter().enumerate() {
        let series: Vec<(f64, f64, &str, &str, &str)> = points
            .iter()
            .map(|(x, l, core, f)| {
                (
                    *x,
                    metric(&accuracy[&("default", *f)].cmp),
                    l.as_str(),
                    *core,
                    *f,
                )
            })
            .filter(|p| p.1 > 0.0)
            .collect();
        let origin = Point::new(k as i32 * w / 2, 30);
        panel(
            &mut d,
            origin,
            Size::new((w / 2) as u32, (h - 30) as u32),
            label,
            &series,
            use_fw,
        );
    }
    let _ = d
        .to_rgb_output_image(&OutputSettings::default())
        .save_png(path);
}

/// One log-log panel: points (cost, error, label, core, format) and each core's Pareto front.
fn panel(
    d: &mut SimulatorDisplay<Rgb888>,
    origin: Point,
    size: Size,
    ylabel: &str,
    points: &[(f64, f64, &str, &str, &str)],
    use_fw: bool,
) {
    let (w, h) = (size.width as i32, size.height as i32);
    let (left, right, top, bottom) = (70, 20, 30, 50);
    let text = MonoTextStyle::new(&FONT_6X10, Rgb888::BLACK);
    let grey = PrimitiveStyle::with_stroke(Rgb888::new(220, 220, 220), 1);
    let axis = PrimitiveStyle::with_stroke(Rgb888::BLACK, 1);
    let lg = |v: f64| v.log10();
    let (mut xmin, mut xmax, mut ymin, mut ymax) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in points {
        xmin = xmin.min(lg(p.0));
        xmax = xmax.max(lg(p.0));
        ymin = ymin.min(lg(p.1));
        ymax = ymax.max(lg(p.1));
    }
    if points.is_empty() {
        (xmin, xmax, ymin, ymax) = (0.0, 1.0, 0.0, 1.0);
    }
    let (xmin, xmax) = (xmin.floor(), xmax.ceil().max(xmin.floor() + 1.0));
    let (ymin, ymax) = (ymin.floor(), ymax.ceil().max(ymin.floor() + 1.0));
    let px = |x: f64| {
        origin.x + left + ((lg(x) - xmin) / (xmax - xmin) * f64::from(w - left - right)) as i32
    };
    let py = |y: f64| {
        origin.y + h
            - bottom
            - ((lg(y) - ymin) / (ymax - ymin) * f64::from(h - top - bottom)) as i32
    };
    for e in xmin as i32..=xmax as i32 {
        let x = px(10f64.powi(e));
        let _ = Line::new(
            Point::new(x, origin.y + top),
            Point::new(x, origin.y + h - bottom),
        )
        .into_styled(grey)
        .draw(d);
        let _ = Text::with_alignment(
            &format!("1e{e}"),
            Point::new(x, origin.y + h - bottom + 14),
            text,
            Alignment::Center,
        )
        .draw(d);
    }
    for e in ymin as i32..=ymax as i32 {
        let y = py(10f64.powi(e));
        let _ = Line::new(
            Point::new(origin.x + left, y),
            Point::new(origin.x + w - right, y),
        )
        .into_styled(grey)
        .draw(d);
        let _ = Text::with_alignment(
            &format!("1e{e}"),
            Point::new(origin.x + left - 6, y + 3),
            text,
            Alignment::Right,
        )
        .draw(d);
    }
    let _ = Rectangle::new(
        origin + Point::new(left, top),
        Size::new((w - left - right) as u32, (h - top - bottom) as u32),
    )
    .into_styled(axis)
    .draw(d);
    let xlabel = if use_fw {
        "instructions per pixel"
    } else {
        "host ns per pixel"
    };
    let _ = Text::with_alignment(
        xlabel,
        origin + Point::new((left + w - right) / 2, h - bottom + 30),
        text,
        Alignment::Center,
    )
    .draw(d);
    let _ = Text::new(ylabel, origin + Point::new(left, top - 8), text).draw(d);
    for core in ["cortex-m0", "cortex-m4f", "host"] {
        let mut pts: Vec<&(f64, f64, &str, &str, &str)> =
            points.iter().filter(|p| p.3 == core).collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best = f64::MAX;
        let front: Vec<Point> = pts
            .iter()
            .filter(|p| {
                let keep = p.1 < best;
                best = best.min(p.1);
                keep
            })
            .map(|p| Point::new(px(p.0), py(p.1)))
            .collect();
        let colour = if core == "cortex-m0" {
            Rgb888::new(150, 150, 150)
        } else {
            Rgb888::BLACK
        };
        for pair in front.windows(2) {
            let _ = Line::new(pair[0], pair[1])
                .into_styled(PrimitiveStyle::with_stroke(colour, 2))
                .draw(d);
        }
    }
    for (x, y, label, core, format) in points {
        let c = Point::new(px(*x), py(*y));
        let style = PrimitiveStyle::with_fill(format_color(format));
        if *core == "cortex-m4f" {
            let _ = Rectangle::with_center(c, Size::new(11, 11))
                .into_styled(style)
                .draw(d);
        } else {
            let _ = Circle::with_center(c, 12).into_styled(style).draw(d);
        }
        let _ = Text::new(label, c + Point::new(8, -5), text).draw(d);
    }
}
