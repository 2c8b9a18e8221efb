//! The advisor's answers in `docs/advisor.md` (the figures block `advice`, checked by
//! `cargo xtask figures --check`), and `cargo xtask advise SCENE CORE [BUDGET]`.
//!
//! The block: three shipped scenes on each core, one budget, every candidate priced by
//! its count under QEMU (`docs/calibration.md`, written by `cargo xtask calibrate`; the
//! RP2040's cycles are the Cortex-M0's count times the board's cycles per instruction),
//! beside the model's choice and prediction. Each answer is confirmed by drawing the
//! chosen setting again through `Frame::draw` and comparing it with the `f64` frame drawn
//! by `fixray::render`. `cargo xtask advise` counts a scene file's candidates under QEMU
//! (one firmware build per format) and prints the advice they give.

use std::fmt::Write as _;

use crate::pictures::{Capture, difference, psnr, squared_error};
use embedded_graphics::prelude::Drawable;
use fixray::advise::{
    Advice, Budget, Candidate, Core, RP2040_CYCLES_PER_INSTRUCTION, Work, advise, advise_with,
};
use fixray::scene::LargeScene;
use fixray::{Frame, Sampling, Scalar};

/// The scenes answered for.
const SCENES: [&str; 3] = ["default", "spheres", "boing-240x240"];

/// The budget: the circling camera's (at most 1 % of pixels beyond 2 levels).
const BUDGET: Budget = Budget::Beyond {
    levels: 2,
    percent: 1.0,
};

/// The chosen setting's frame drawn through `Frame::draw`: its share of pixels beyond
/// `levels` of the f64 frame drawn by `fixray::render`, and its PSNR.
fn confirm<S: Scalar>(text: &str, sampling: Sampling, levels: u8) -> Option<(f64, f64)> {
    let scene = LargeScene::<S>::parse(text).ok()?;
    let reference = LargeScene::<f64>::parse(text).ok()?;
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut chosen = Capture::new(w, h);
    Frame::new(&scene)
        .with_sampling(sampling)
        .draw(&mut chosen)
        .ok()?;
    let mut exact = Capture::new(w, h);
    fixray::render(&reference, &mut exact).ok()?;
    // Every pixel drawn, by both.
    let chosen: Vec<_> = chosen.pixels.into_iter().collect::<Option<_>>()?;
    let exact: Vec<_> = exact.pixels.into_iter().collect::<Option<_>>()?;
    let beyond = chosen
        .iter()
        .zip(&exact)
        .filter(|(a, b)| difference(**a, **b) > levels)
        .count();
    let n = chosen.len();
    Some((
        100.0 * beyond as f64 / n as f64,
        psnr(squared_error(&chosen, &exact), n),
    ))
}

/// The counts `docs/calibration.md` holds: (core, format, scene, mode) → instructions
/// per pixel.
type Counts = Vec<(String, String, String, String, f64)>;

fn counts(record: &str) -> Counts {
    record
        .lines()
        .filter_map(|l| {
            let c: Vec<&str> = l.split('|').map(str::trim).collect();
            (c.len() > 7).then(|| {
                let n = c[5].parse().ok()?;
                Some((c[1].into(), c[2].into(), c[3].into(), c[4].into(), n))
            })?
        })
        .collect()
}

/// A candidate's counted price: the count of its frame (of the exact frame when it is
/// not drawn in blocks), in cycles on the RP2040.
fn counted(
    counts: &Counts,
    core: Core,
    scene: &str,
) -> impl FnMut(&'static str, Sampling, bool, &Work) -> Option<(f64, f64)> {
    move |format, sampling, sampled, _| {
        let mode = if sampled {
            sampling.to_string()
        } else {
            "exact".into()
        };
        let (measured, scale) = match core {
            Core::Rp2040 => ("cortex-m0", RP2040_CYCLES_PER_INSTRUCTION),
            c => (c.name(), 1.0),
        };
        counts
            .iter()
            .find(|(c, f, s, m, _)| c == measured && f == format && s == scene && *m == mode)
            .map(|e| (e.4 * scale, 0.0))
    }
}

/// `format mode`, and `(drawn exact)` for a mode whose blocks the scene's kind refuses.
fn setting(c: &Candidate) -> String {
    format!(
        "{} {}{}",
        c.format,
        c.sampling,
        if c.sampled || c.sampling == Sampling::Exact {
            ""
        } else {
            " (drawn exact)"
        }
    )
}

/// The block's table.
pub fn table() -> Result<String, String> {
    let record = std::fs::read_to_string(crate::root().join("docs/calibration.md"))
        .map_err(|e| format!("docs/calibration.md: {e} (run `cargo xtask calibrate`)"))?;
    let counts = counts(&record);
    let mut out = format!(
        "Budget: {BUDGET}. Costs per pixel: instructions (cycles on the RP2040).\n\n\
         | scene | core | choice (counted) | its cost, counted | the model's choice | its cost, predicted | and counted | pixels beyond 2 levels | PSNR | drawn again: beyond, PSNR |\n\
         |---|---|---|---|---|---|---|---|---|---|\n"
    );
    for scene in SCENES {
        let text = std::fs::read_to_string(crate::root().join(format!("scenes/{scene}.scene")))
            .map_err(|e| format!("scenes/{scene}.scene: {e}"))?;
        for core in Core::ALL {
            let advice = advise_with(&text, core, BUDGET, &mut counted(&counts, core, scene))
                .map_err(|e| format!("{scene}: {e}"))?;
            let model = advise(&text, core, BUDGET).map_err(|e| format!("{scene}: {e}"))?;
            let Some(c) = advice.choice() else {
                writeln!(
                    out,
                    "| {scene} | {} | none holds | | | | | | | |",
                    core.name()
                )
                .unwrap();
                continue;
            };
            let again = fixray::with_format!(c.format, confirm(&text, c.sampling, 2))
                .ok()
                .flatten()
                .ok_or(format!("{scene}: {} does not draw again", c.format))?;
            if again.0 > 1.0 || (again.0 - c.beyond).abs() > 1e-9 {
                return Err(format!(
                    "{scene} on {}: the choice {} drawn again has {:.3} % beyond, the advisor said {:.3} %",
                    core.name(),
                    setting(c),
                    again.0,
                    c.beyond
                ));
            }
            let (model_choice, model_cost, model_counted) = match model.choice() {
                None => ("none holds".to_string(), String::new(), String::new()),
                Some(m) => (
                    setting(m),
                    format!("{:.1} (± {:.0} %)", m.cost, 100.0 * m.cost_error),
                    counted(&counts, core, scene)(
                        m.format,
                        m.sampling,
                        m.sampled,
                        &Work::default(),
                    )
                    .map_or("—".into(), |p| format!("{:.1}", p.0)),
                ),
            };
            writeln!(
                out,
                "| {scene} | {} | {} | {:.1} | {model_choice} | {model_cost} | {model_counted} | {:.3} % | {:.1} dB | {:.3} %, {:.1} dB |",
                core.name(),
                setting(c),
                c.cost,
                c.beyond,
                c.psnr,
                again.0,
                again.1
            )
            .unwrap();
        }
    }
    Ok(out)
}

/// The sampling section's cost table (`docs/accuracy.md`, figures block `sampling-cost`):
/// each scene of [`SCENES`] exact and in each mode that draws it in blocks, I16F16, the
/// instructions per pixel `docs/calibration.md` holds for the three QEMU cores and the
/// RP2040's cycles from the Cortex-M0's.
pub fn sampling_costs() -> Result<String, String> {
    let record = std::fs::read_to_string(crate::root().join("docs/calibration.md"))
        .map_err(|e| format!("docs/calibration.md: {e} (run `cargo xtask calibrate`)"))?;
    let counts = counts(&record);
    let mut out = String::from(
        "| scene | sampling | Cortex-M0 | Cortex-M4F | RISC-V | RP2040 cycles (estimated) |\n\
         |---|---|---|---|---|---|\n",
    );
    for scene in SCENES {
        for mode in fixray::advise::MODES {
            let name = mode.to_string();
            let of = |core: &str| {
                counts
                    .iter()
                    .find(|(c, f, s, m, _)| c == core && f == "i16f16" && s == scene && *m == name)
                    .map(|e| e.4)
            };
            let (Some(m0), Some(m4), Some(rv)) =
                (of("cortex-m0"), of("cortex-m4f"), of("riscv32imc"))
            else {
                continue;
            };
            writeln!(
                out,
                "| {scene} | {name} | {m0:.1} | {m4:.1} | {rv:.1} | {:.1} |",
                m0 * RP2040_CYCLES_PER_INSTRUCTION
            )
            .unwrap();
        }
    }
    Ok(out)
}

/// Prints an advice's choice and candidates.
fn print(advice: &Advice) {
    let unit = advice.core.unit();
    println!(
        "advice for {}, budget: {}",
        advice.core.name(),
        advice.budget
    );
    match advice.choice() {
        Some(c) => println!("choice: {}: {:.1} {unit}/pixel counted", setting(c), c.cost),
        None => println!("choice: none of the candidates holds the budget"),
    }
    for c in &advice.candidates {
        println!(
            "{:<28} {:>10.1} {unit}/pixel {:>8.3} % beyond {:>6.1} dB {}",
            setting(c),
            c.cost,
            c.beyond,
            c.psnr,
            if c.holds { "holds" } else { "" }
        );
    }
}

/// `cargo xtask advise SCENE CORE [BUDGET]`: every candidate of the scene file counted
/// under QEMU (the RP2040 from the Cortex-M0's count), and the advice.
pub fn main(args: &[String]) {
    let usage =
        "usage: cargo xtask advise SCENE_FILE cortex-m0|cortex-m4f|riscv32imc|rp2040 [2:1|40dB]";
    let (Some(path), Some(core)) = (args.first(), args.get(1).and_then(|c| Core::from_name(c)))
    else {
        eprintln!("{usage}");
        std::process::exit(2);
    };
    let budget = match args.get(2) {
        None => BUDGET,
        Some(b) => Budget::parse(b).unwrap_or_else(|| {
            eprintln!("budget `{b}`: write LEVELS:PERCENT (e.g. 2:1) or a PSNR (e.g. 40dB)");
            std::process::exit(2);
        }),
    };
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| {
        eprintln!("{path}: {e}");
        std::process::exit(1);
    });
    // The firmware embeds the scene under a name of its own (a file stem the firmware
    // animates, or one it cannot name, would draw another frame or not build).
    let name = "advised".to_string();
    let copy = crate::root().join("target/advise/advised.scene");
    let written = std::fs::create_dir_all(crate::root().join("target/advise"))
        .and_then(|()| std::fs::write(&copy, &text));
    if let Err(e) = written {
        eprintln!("target/advise: {e}");
        std::process::exit(1);
    }
    let target = match core {
        Core::CortexM0 | Core::Rp2040 => "thumbv6m-none-eabi",
        Core::CortexM4F => "thumbv7em-none-eabihf",
        Core::RiscV => "riscv32imc-unknown-none-elf",
    };
    let measured = match core {
        Core::Rp2040 => "cortex-m0",
        c => c.name(),
    };
    let modes = crate::calibrate::modes();
    let file = copy.to_string_lossy().into_owned();
    let mut counts: Counts = Vec::new();
    for format in fixray::num::formats::MAIN
        .into_iter()
        .filter(|f| *f != fixray::num::formats::REFERENCE)
    {
        eprintln!("advise: counting {format} on {target}");
        let run = crate::qemu::run_sampled(
            target,
            format,
            &file,
            crate::calibrate::FEATURES_BUILT,
            &modes,
        )
        .or_else(|_| {
            crate::qemu::run_with_features(target, format, &file, Some(crate::calibrate::EXACT))
        });
        let run = match run {
            Ok(run) => run,
            Err(e) => {
                eprintln!("advise: {format}: {}", e.lines().next().unwrap_or_default());
                continue;
            }
        };
        for f in &run.frames {
            let mode = match f.get("sampling") {
                "" => "exact".to_string(),
                m => m.to_string(),
            };
            let host = fixray::with_format!(format, crate::calibrate::host_text(&text, &mode))
                .ok()
                .flatten();
            match (host, f.number("instructions")) {
                (Some((_, hash)), Some(n)) if hash == f.hash() => counts.push((
                    measured.into(),
                    format.into(),
                    name.clone(),
                    mode,
                    n as f64 / f.pixels() as f64,
                )),
                _ => {
                    eprintln!(
                        "advise: {format} {mode}: the chip's frame is not the host's (or has no count)"
                    );
                    std::process::exit(1);
                }
            }
        }
    }
    match advise_with(&text, core, budget, &mut counted(&counts, core, &name)) {
        Ok(advice) => print(&advice),
        Err(e) => {
            eprintln!("advise: {e}");
            std::process::exit(1);
        }
    }
}
