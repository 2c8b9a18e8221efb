//! `render`: the main job. Renders a scene (the built-in default scene unless a file is
//! given) in every number format, writes a PNG and prints what each format costs in time
//! and accuracy against the f64 reference.
//!
//! ```text
//! cargo run --release --example render
//! cargo run --release --example render -- [SCENE_FILE] [--format FORMAT]
//!                                         [--out FILE.png] [--compare FILE.png]
//!                                         [--rules course|fixray]
//! cargo run --release --example render -- scenes/boing.scene --bounce-strip FILE.png
//! cargo run --release --example render -- scenes/spheres.scene --advise cortex-m0 [--budget 2:1]
//! ```
//!
//! Without `--format` every main format is rendered and reported, and `--out` (default
//! `render.png`) receives the I16F16 render. With `--format` only that format is rendered
//! into `--out`, at the scene's pixeldim, scale 1, Rgb888. `--compare` writes one picture:
//! the format | the f64 render | a heat map of the per-pixel channel error (black: equal;
//! blue → red: 1 → 255 levels, log scale). `--rules` draws the scene by that rule set
//! whatever its file says (a file without a `rules` statement is a course file); the
//! first line printed names the rule set used.
//!
//! Errors: bad arguments exit with status 2. A scene error exits with status 1 in every
//! mode and prints `FILE:LINE:COL: message` on stderr, naming the number format when the
//! error is that format's alone (a number or a derived quantity it cannot hold, a normal
//! that rounds to zero in it); a number that not even f64 holds is said to fit no format;
//! a scene over this program's capacities (1024 objects, 256 materials, 64 lights) is
//! told so. Without `--format`, a format that refuses the scene is reported in its row
//! of the table and its error printed after the table; the program then writes no
//! picture (neither `--out` nor `--compare`) and exits with status 1, so that a picture
//! on disk is always the one its name promises.
//!
//! Texture files are read from beside the scene file, once: every format's scene shares
//! their bytes (`fixray::scene::files::beside`), so memory does not grow with the number
//! of formats.
//!
//! `--bounce-strip FILE.png` draws the 16 frames of the scene's bounce
//! (`fixray::anim::Bounce::boing`: its first sphere moved as the firmware moves it) in
//! `--format` (default I16F16) into one picture, 8 frames a row, and prints each frame's
//! share of pixels that differ from the f64 frame.
//!
//! `--advise CORE` (`cortex-m0`, `cortex-m4f`, `riscv32imc` or `rp2040`) prints the
//! advisor's answer (`fixray::advise`): the cheapest main format and sampling mode whose
//! frame holds the budget against f64, and every candidate's predicted cost per pixel
//! and measured accuracy. `--budget` is `LEVELS:PERCENT` (at most PERCENT % of pixels
//! with a channel more than LEVELS levels off; default `2:1`) or `DBdB` (a PSNR of at
//! least DB). The advisor reads the scene as its file says (no texture files).

use std::process::ExitCode;
use std::time::{Duration, Instant};

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use fixray::compare::{Comparison, compare, heat_color};
use fixray::num::formats::{self, MAIN};
use fixray::scene::{LargeScene as Scene, Rules};
use fixray::{Scalar, SceneError, render_line};

#[path = "common/scene_error.rs"]
mod scene_error;
use scene_error::explain;

/// The built-in default scene, compiled in.
const DEFAULT_SCENE: &str = include_str!("../scenes/default.scene");
const DEFAULT_SCENE_NAME: &str = "scenes/default.scene";

const USAGE: &str = "usage: render [SCENE_FILE] [--format FORMAT] [--out FILE.png] \
                     [--compare FILE.png] [--rules course|fixray] [--bounce-strip FILE.png] [--advise CORE [--budget 2:1|40dB]]   (FORMAT: one of \
                     fixray::num::formats::FORMATS; without it, every main format)";

struct Args {
    scene: Option<String>,
    format: Option<String>,
    out: String,
    compare: Option<String>,
    rules: Option<Rules>,
    strip: Option<String>,
    advise: Option<fixray::advise::Core>,
    budget: fixray::advise::Budget,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args {
        scene: None,
        format: None,
        out: "render.png".into(),
        compare: None,
        rules: None,
        strip: None,
        advise: None,
        budget: fixray::advise::Budget::Beyond {
            levels: 2,
            percent: 1.0,
        },
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        let mut value = |flag: &str| it.next().ok_or(format!("{flag} needs a value"));
        match a.as_str() {
            "--format" => {
                let f = value("--format")?;
                formats::check(&f).map_err(|e| e.to_string())?;
                args.format = Some(f);
            }
            "--out" => args.out = value("--out")?,
            "--compare" => args.compare = Some(value("--compare")?),
            "--bounce-strip" => args.strip = Some(value("--bounce-strip")?),
            "--rules" => {
                let r = value("--rules")?;
                args.rules = Some(r.parse().map_err(|e| format!("--rules `{r}`: {e}"))?);
            }
            "--advise" => {
                let c = value("--advise")?;
                args.advise = Some(fixray::advise::Core::from_name(&c).ok_or(format!(
                    "--advise `{c}`: not a core (cortex-m0, cortex-m4f, riscv32imc, rp2040)"
                ))?);
            }
            "--budget" => {
                let b = value("--budget")?;
                args.budget = fixray::advise::Budget::parse(&b).ok_or(format!(
                    "--budget `{b}`: write LEVELS:PERCENT (e.g. 2:1) or a PSNR (e.g. 40dB)"
                ))?;
            }
            "-h" | "--help" => return Err(String::new()),
            s if s.starts_with("--") => return Err(format!("unknown option `{s}`")),
            s if args.scene.is_none() => args.scene = Some(s.into()),
            s => return Err(format!("unexpected argument `{s}`")),
        }
    }
    Ok(args)
}

/// An image in memory, row-major.
struct Image {
    width: u16,
    height: u16,
    pixels: Vec<Rgb888>,
}

impl Image {
    fn save_png(&self, path: &str) -> Result<(), String> {
        let size = Size::new(u32::from(self.width), u32::from(self.height));
        let mut display = SimulatorDisplay::<Rgb888>::new(size);
        self.draw_at(&mut display, 0);
        save(&display, path)
    }

    fn draw_at(&self, display: &mut SimulatorDisplay<Rgb888>, x0: i32) {
        let w = usize::from(self.width);
        let pixels = self.pixels.iter().enumerate().map(|(i, c)| {
            let (x, y) = (i % w, i / w);
            Pixel(Point::new(x0 + x as i32, y as i32), *c)
        });
        // SimulatorDisplay's drawing is infallible.
        let _ = display.draw_iter(pixels);
    }
}

fn save(display: &SimulatorDisplay<Rgb888>, path: &str) -> Result<(), String> {
    display
        .to_rgb_output_image(&OutputSettings::default())
        .save_png(path)
        .map_err(|e| format!("cannot write {path}: {e}"))
}

/// What rendering one format produced.
struct Run {
    image: Image,
    frame: Duration,
    comparison: Comparison,
    heat: Vec<Rgb888>,
    delta: f64,
}

/// Renders one frame line by line with the library's `render_line`.
fn render_image<S: Scalar>(scene: &Scene<S>) -> Image {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut pixels = vec![Rgb888::BLACK; usize::from(w) * usize::from(h)];
    for (row, line) in (0..h).zip(pixels.chunks_mut(usize::from(w))) {
        render_line(scene, row, line);
    }
    Image {
        width: w,
        height: h,
        pixels,
    }
}

/// Median frame time over enough frames to fill about 0.3 s (3 to 51 frames).
fn time_frames<S: Scalar>(scene: &Scene<S>) -> (Image, Duration) {
    let start = Instant::now();
    let image = render_image(scene);
    let first = start.elapsed();
    let n = (Duration::from_millis(300).as_nanos() / first.as_nanos().max(1)).clamp(3, 51);
    let mut times: Vec<Duration> = (0..n)
        .map(|_| {
            let t = Instant::now();
            std::hint::black_box(render_image(std::hint::black_box(scene)));
            t.elapsed()
        })
        .collect();
    times.sort();
    (image, times[times.len() / 2])
}

/// The scene file's path, for its texture files (none for the built-in scene).
static SCENE_PATH: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();

/// Reads a scene, drawn by `rules` if given (else by the file's own), its textures from
/// beside the scene file.
fn read<S: Scalar>(text: &str, rules: Option<Rules>) -> Result<Scene<S>, SceneError> {
    let mut scene = Scene::<S>::empty();
    match SCENE_PATH.get() {
        Some(path) => scene.read_with(text, rules, &mut fixray::scene::files::beside(path))?,
        None => scene.read_with(text, rules, &mut |_| None)?,
    }
    Ok(scene)
}

fn run<S: Scalar>(text: &str, reference: &Scene<f64>) -> Result<Run, SceneError> {
    let scene = read::<S>(text, Some(reference.rules()))?;
    let (image, frame) = time_frames(&scene);
    let mut heat = Vec::with_capacity(image.pixels.len());
    let comparison = compare(&scene, reference, |_, _, px, ref_px| {
        heat.push(heat_color(px, ref_px));
    });
    Ok(Run {
        image,
        frame,
        comparison,
        heat,
        delta: S::DELTA.to_f64(),
    })
}

/// Renders in the format named `format`, which `parse_args` checked against the one list.
fn run_format(format: &str, text: &str, reference: &Scene<f64>) -> Result<Run, SceneError> {
    match fixray::with_format!(format, run(text, reference)) {
        Ok(run) => run,
        Err(unknown) => unreachable!("{unknown}: checked when the arguments were read"),
    }
}

fn write_compare(run: &Run, reference: &Image, path: &str) -> Result<(), String> {
    let (w, h) = (u32::from(run.image.width), u32::from(run.image.height));
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(3 * w, h));
    run.image.draw_at(&mut display, 0);
    reference.draw_at(&mut display, w as i32);
    let heat = Image {
        width: run.image.width,
        height: run.image.height,
        pixels: run.heat.clone(),
    };
    heat.draw_at(&mut display, 2 * w as i32);
    save(&display, path)
}

fn print_header(scene_name: &str, reference: &Scene<f64>) {
    let c = &reference.camera;
    println!(
        "{scene_name}: {}x{} pixels, {} objects, {} lights",
        c.width,
        c.height,
        reference.objects.len(),
        reference.lights.len()
    );
    println!(
        "{:<7} {:>10} {:>8} {:>12} {:>10} {:>10} {:>9} {:>8}",
        "format", "ms/frame", "x f64", "max|dt|", "DELTAs", "mean|dt|", "differ", "PSNR dB"
    );
}

fn print_row(format: &str, run: &Run, f64_frame: Duration) {
    let c = &run.comparison;
    let ms = run.frame.as_secs_f64() * 1e3;
    println!(
        "{:<7} {:>10.3} {:>8.2} {:>12.3e} {:>10.1} {:>10.3e} {:>8.3}% {:>8.1}",
        format,
        ms,
        run.frame.as_secs_f64() / f64_frame.as_secs_f64(),
        c.max_dt,
        c.max_dt / run.delta,
        c.mean_dt(),
        100.0 * c.differing_share(),
        c.psnr(),
    );
}

/// The error of reading the scene in the format named `format` (checked against the one
/// list when the arguments were read), if any.
fn read_error(format: &str, text: &str, rules: Option<Rules>) -> Option<SceneError> {
    fixray::with_format!(format, read_err(text, rules))
        .unwrap_or_else(|unknown| unreachable!("{unknown}: checked with the arguments"))
}

fn read_err<S: Scalar>(text: &str, rules: Option<Rules>) -> Option<SceneError> {
    read::<S>(text, rules).err()
}

/// Prints the advisor's answer for `text` on `core` (`--advise`).
fn advise(text: &str, core: fixray::advise::Core, budget: fixray::advise::Budget) -> ExitCode {
    let advice = match fixray::advise::advise(text, core, budget) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("render: --advise: {e}");
            return ExitCode::from(1);
        }
    };
    let unit = core.unit();
    println!("advice for {}, budget: {budget}", core.name());
    match advice.choice() {
        Some(c) => println!(
            "choice: {} {}: {:.1} {unit}/pixel (model, within {:.1} % on the calibration \
             scenes), {:.3} % of pixels beyond, PSNR {:.1} dB",
            c.format,
            c.sampling,
            c.cost,
            100.0 * c.cost_error,
            c.beyond,
            c.psnr
        ),
        None => println!("choice: none of the candidates holds the budget"),
    }
    println!(
        "{:<7} {:<7} {:>7} {:>16} {:>9} {:>8} {:>6}",
        "format",
        "mode",
        "blocks",
        format!("{unit}/pixel"),
        "beyond %",
        "PSNR dB",
        "holds"
    );
    for c in &advice.candidates {
        // Padded as a string (the mode's `Display` writes its name as it is).
        let mode = c.sampling.to_string();
        println!(
            "{:<7} {mode:<7} {:>7} {:>16.1} {:>9.3} {:>8.1} {:>6}",
            c.format,
            if c.sampled { "yes" } else { "no" },
            c.cost,
            c.beyond,
            c.psnr,
            if c.holds { "yes" } else { "no" }
        );
    }
    ExitCode::SUCCESS
}

fn main() -> ExitCode {
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            if !e.is_empty() {
                eprintln!("render: {e}");
            }
            eprintln!("{USAGE}");
            return ExitCode::from(2);
        }
    };
    let (scene_name, text) = match &args.scene {
        None => (DEFAULT_SCENE_NAME.to_string(), DEFAULT_SCENE.to_string()),
        Some(path) => match std::fs::read_to_string(path) {
            Ok(t) => {
                let _ = SCENE_PATH.set(path.into());
                (path.clone(), t)
            }
            Err(e) => {
                eprintln!("render: cannot read {path}: {e}");
                return ExitCode::from(1);
            }
        },
    };
    // The format this run draws in; none: the report of every main format.
    let named = match (&args.format, &args.strip) {
        (Some(f), _) => Some(f.as_str()),
        (None, Some(_)) => Some("i16f16"),
        (None, None) => None,
    };
    let scene_error = |format: &str, e: &SceneError, reference: Option<&SceneError>| {
        eprintln!("{}", explain(&scene_name, format, e, reference));
        ExitCode::from(1)
    };
    let reference = match read::<f64>(&text, args.rules) {
        Ok(s) => s,
        Err(r) => {
            // Every run needs f64: the named format's own reading says which format the
            // error concerns.
            return match named.filter(|f| *f != "f64") {
                Some(format) => match read_error(format, &text, args.rules) {
                    Some(e) => scene_error(format, &e, Some(&r)),
                    None => scene_error("f64", &r, Some(&r)),
                },
                None => scene_error("f64", &r, Some(&r)),
            };
        }
    };
    let from = if args.rules.is_some() {
        "--rules"
    } else {
        "the file"
    };
    println!("rules: {} (from {from})", reference.rules());
    if let Some(core) = args.advise {
        return advise(&text, core, args.budget);
    }
    if let Some(path) = &args.strip {
        let format = named.unwrap_or("i16f16");
        let outcome = fixray::with_format!(format, bounce_strip(&text, &reference, path))
            .unwrap_or_else(|unknown| unreachable!("{unknown}: checked with the arguments"));
        return match outcome {
            Ok(()) => ExitCode::SUCCESS,
            Err(StripError::Scene(e)) => scene_error(format, &e, None),
            Err(StripError::Bounce(e)) => {
                eprintln!("{scene_name}: {e}");
                ExitCode::from(1)
            }
            Err(StripError::Write(e)) => {
                eprintln!("render: {e}");
                ExitCode::from(1)
            }
        };
    }
    let reference_image = render_image(&reference);
    let outcome = match &args.format {
        Some(format) => {
            let run = match run_format(format, &text, &reference) {
                Ok(r) => r,
                Err(e) => return scene_error(format, &e, None),
            };
            print_header(&scene_name, &reference);
            let f64_frame = if format == "f64" {
                run.frame
            } else {
                time_frames(&reference).1
            };
            print_row(format, &run, f64_frame);
            finish(format, &run, &reference_image, &args)
        }
        None => {
            print_header(&scene_name, &reference);
            // Every format first, so that each row's ratio uses the f64 time of this run.
            let runs: Vec<_> = MAIN
                .iter()
                .map(|f| (*f, run_format(f, &text, &reference)))
                .collect();
            let f64_frame = runs
                .iter()
                .find_map(|(f, r)| r.as_ref().ok().filter(|_| *f == "f64"))
                .map_or(Duration::from_secs(1), |r| r.frame);
            let mut shown = None;
            let mut refused = Vec::new();
            for (format, result) in runs {
                match result {
                    Ok(run) => {
                        print_row(format, &run, f64_frame);
                        if format == "i16f16" {
                            shown = Some(run);
                        }
                    }
                    Err(e) => {
                        println!("{format:<7} refused the scene (the error follows the table)");
                        refused.push(explain(&scene_name, format, &e, None));
                    }
                }
            }
            if !refused.is_empty() {
                for line in &refused {
                    eprintln!("{line}");
                }
                eprintln!(
                    "render: {} of {} formats refused the scene: no picture written",
                    refused.len(),
                    MAIN.len()
                );
                return ExitCode::from(1);
            }
            match shown {
                Some(run) => finish("i16f16", &run, &reference_image, &args),
                None => Err("i16f16 is not among the main formats".into()),
            }
        }
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("render: {e}");
            ExitCode::from(1)
        }
    }
}

fn finish(format: &str, run: &Run, reference: &Image, args: &Args) -> Result<(), String> {
    run.image.save_png(&args.out)?;
    println!("wrote {} ({format})", args.out);
    if let Some(path) = &args.compare {
        write_compare(run, reference, path)?;
        println!("wrote {path} ({format} | f64 | channel error heat map)");
    }
    Ok(())
}

/// Why a bounce strip was not drawn.
enum StripError {
    /// The scene in the strip's format.
    Scene(SceneError),
    /// The scene's bounce.
    Bounce(fixray::anim::AnimError),
    /// The picture.
    Write(String),
}

/// The scene's bounce (`Bounce::boing`), every frame in format `S` and in f64
/// (`reference`), 8 frames a row, into `path`; prints each frame's share of pixels that
/// differ from f64.
fn bounce_strip<S: Scalar>(
    text: &str,
    reference: &Scene<f64>,
    path: &str,
) -> Result<(), StripError> {
    use fixray::anim::Bounce;
    const PER_ROW: u32 = 8;
    let mut scene = read::<S>(text, Some(reference.rules())).map_err(StripError::Scene)?;
    let mut reference = reference.clone();
    let bounce = Bounce::boing(&scene.objects).map_err(StripError::Bounce)?;
    let reference_bounce = Bounce::boing(&reference.objects).map_err(StripError::Bounce)?;
    let (w, h) = (
        u32::from(scene.camera.width),
        u32::from(scene.camera.height),
    );
    let n = u32::from(bounce.frames());
    let rows = n.div_ceil(PER_ROW);
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(PER_ROW * w, rows * h));
    println!("frame  differ from f64 ({})", S::NAME);
    for k in 0..bounce.frames() {
        bounce.apply(&mut scene, k).map_err(StripError::Bounce)?;
        reference_bounce
            .apply(&mut reference, k)
            .map_err(StripError::Bounce)?;
        let image = render_image(&scene);
        let differ = compare(&scene, &reference, |_, _, _, _| {}).differing_share();
        println!("{k:>5}  {:>6.3}%", 100.0 * differ);
        let (col, row) = (u32::from(k) % PER_ROW, u32::from(k) / PER_ROW);
        let wu = usize::from(image.width);
        let pixels = image.pixels.iter().enumerate().map(|(i, c)| {
            let (x, y) = ((i % wu) as u32 + col * w, (i / wu) as u32 + row * h);
            Pixel(Point::new(x as i32, y as i32), *c)
        });
        // SimulatorDisplay's drawing is infallible.
        let _ = display.draw_iter(pixels);
    }
    save(&display, path).map_err(StripError::Write)?;
    println!("wrote {path} ({} frames, {})", n, S::NAME);
    Ok(())
}
