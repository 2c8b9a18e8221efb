//! `cargo xtask calibrate`: the advisor's cost models (`src/advise/model.rs`) and their
//! record (`docs/calibration.md`), fitted to the instructions the firmware counts under
//! QEMU.
//!
//! For each core and main format the firmware draws [`SCENES`] exact and in the modes of
//! [`modes`] (`FIXRAY_FW_SAMPLING`), one build per core × format. The host counts each
//! frame's work (`fixray::advise::work`, the same pixels bit for bit: the hashes are
//! checked). The coefficients are the non-negative least-squares fit of the counted
//! instructions on the work, each frame's residual relative to its count; the stated
//! error is the median and largest relative error of each scene's frames predicted by
//! the fit without that scene. The RP2040's cycles per instruction are the emulated
//! board's whole exact frame (`target/board-report.md`, from `cargo test --release
//! --test board -- --ignored`) over the Cortex-M0's count of the same scene at 240×240.
//! Takes about 5 minutes. With `--check` nothing is written: the command fails when the
//! committed models or record differ from what the counts give, a word or a number by
//! more than the figures' tolerance (a coefficient the fit leaves at zero must stay zero;
//! CI runs it).

use std::fmt::Write as _;

use fixray::Scalar;
use fixray::advise::{FEATURES, Work, work};
use fixray::hash::FrameHash;
use fixray::num::formats::{MAIN, REFERENCE};
use fixray::scene::LargeScene;

use crate::qemu;

/// The shipped scenes the models are fitted to: every kind of object, light and kernel,
/// both rule sets, and the boing ball at the board's 240×240.
const SCENES: [&str; 13] = [
    "default",
    "planes",
    "horizon",
    "spheres",
    "tiles",
    "specular",
    "spotlight",
    "mirror",
    "triangles",
    "course",
    "translucent",
    "revsurf",
    "boing-240x240",
];

/// The sampling modes measured beside the exact frame: every mode the advisor tries
/// (`fixray::advise::MODES`).
pub fn modes() -> String {
    fixray::advise::MODES
        .into_iter()
        .filter(|m| *m != fixray::Sampling::Exact)
        .map(|m| m.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// The firmware's features: the default set with sampling.
pub const FEATURES_BUILT: &str = "kernels,lighting,spheres,reflection,course,sampling";

/// The firmware's features without sampling.
pub const EXACT: &str = "kernels,lighting,spheres,reflection,course";

/// One measured frame.
struct Measured {
    core: &'static str,
    format: &'static str,
    scene: String,
    mode: String,
    instructions: f64,
    work: Work,
}

/// The host's work and hash of `scene` in `S` drawn in `mode`.
fn host<S: Scalar>(scene: &str, mode: &str) -> Option<(Work, u32)> {
    let text = std::fs::read_to_string(crate::root().join(format!("scenes/{scene}.scene"))).ok()?;
    host_text::<S>(&text, mode)
}

/// The host's work and hash of the scene `text` in `S` drawn in `mode`.
pub fn host_text<S: Scalar>(text: &str, mode: &str) -> Option<(Work, u32)> {
    let parsed = LargeScene::<S>::parse(text).ok()?;
    let sampling = mode.parse::<fixray::Sampling>().ok()?;
    let (pixels, work) = work(&parsed, sampling);
    let mut hash = FrameHash::new();
    pixels.iter().for_each(|p| hash.push(*p));
    Some((work, hash.value()))
}

/// Non-negative least squares: `x ≥ 0` minimising `‖A·x − y‖²`, by coordinate descent on
/// the normal equations (columns scaled to unit norm first). Indices, as the matrix
/// algebra is written.
#[allow(clippy::needless_range_loop)]
fn nnls(a: &[[f64; FEATURES.len()]], y: &[f64]) -> [f64; FEATURES.len()] {
    const N: usize = FEATURES.len();
    let mut scale = [0.0; N];
    for j in 0..N {
        scale[j] = a.iter().map(|r| r[j] * r[j]).sum::<f64>().sqrt();
    }
    let col = |r: &[f64; N], j: usize| if scale[j] > 0.0 { r[j] / scale[j] } else { 0.0 };
    let mut q = [[0.0; N]; N];
    let mut b = [0.0; N];
    for (r, &t) in a.iter().zip(y) {
        for i in 0..N {
            b[i] += col(r, i) * t;
            for j in 0..N {
                q[i][j] += col(r, i) * col(r, j);
            }
        }
    }
    let mut x = [0.0; N];
    for _ in 0..20_000 {
        for j in 0..N {
            if q[j][j] <= 0.0 {
                continue;
            }
            let g: f64 = (0..N).map(|k| q[j][k] * x[k]).sum::<f64>() - b[j];
            x[j] = (x[j] - g / q[j][j]).max(0.0);
        }
    }
    let mut out = [0.0; N];
    for j in 0..N {
        if scale[j] > 0.0 {
            out[j] = x[j] / scale[j];
        }
    }
    out
}

/// The fit of `frames` with each row divided by its count (relative residuals).
fn fit(frames: &[&Measured]) -> [f64; FEATURES.len()] {
    let a: Vec<[f64; FEATURES.len()]> = frames
        .iter()
        .map(|f| f.work.counts.map(|c| c / f.instructions))
        .collect();
    let y = vec![1.0; frames.len()];
    nnls(&a, &y)
}

fn predict(c: &[f64; FEATURES.len()], w: &Work) -> f64 {
    c.iter().zip(w.counts).map(|(a, x)| a * x).sum()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

/// Cycles per displayed pixel of the board's whole exact frame on one core at 200 MHz.
fn board_cycles() -> Result<f64, String> {
    let text = std::fs::read_to_string(crate::root().join("target/board-report.md"))
        .map_err(|e| format!("target/board-report.md: {e} (run `cargo test --release --test board -- --ignored` first)"))?;
    text.lines()
        .map(|l| l.split('|').map(str::trim).collect::<Vec<_>>())
        .find(|c| c.len() > 6 && c[1] == "whole" && c[2] == "1")
        .and_then(|c| c[6].parse().ok())
        .ok_or("target/board-report.md has no `whole | 1` row".into())
}

pub fn main(args: &[String]) {
    let check = match args {
        [] => false,
        [flag] if flag == "--check" => true,
        _ => {
            eprintln!("usage: cargo xtask calibrate [--check]");
            std::process::exit(2);
        }
    };
    if !qemu::qemu_available() {
        eprintln!("qemu-system-arm or qemu-system-riscv32 is not installed (both are needed)");
        std::process::exit(1);
    }
    let board = board_cycles().unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(1);
    });
    let formats: Vec<&'static str> = MAIN.into_iter().filter(|f| *f != REFERENCE).collect();
    let mut measured: Vec<Measured> = Vec::new();
    for (target, core) in qemu::CORES {
        for &format in &formats {
            eprintln!("calibrate: {core} {format}");
            let scenes = SCENES.join(",");
            // A format whose sampled firmware overflows the flash (I32F32 on the Cortex-M0)
            // is measured exact only, without the sampling code, half the scenes a build
            // (its model then offers no sampled mode).
            let run = qemu::run_sampled(target, format, &scenes, FEATURES_BUILT, &modes())
                .map(|r| r.frames)
                .or_else(|e| {
                    let first = e.lines().next().unwrap_or_default().to_string();
                    eprintln!("calibrate: {core} {format} sampled: {first}; measured exact only");
                    let (a, b) = SCENES.split_at(SCENES.len() / 2);
                    let mut frames = Vec::new();
                    for half in [a, b] {
                        frames.extend(
                            qemu::run_with_features(target, format, &half.join(","), Some(EXACT))?
                                .frames,
                        );
                    }
                    Ok::<_, String>(frames)
                })
                .unwrap_or_else(|e| {
                    eprintln!("{e}");
                    std::process::exit(1);
                });
            for f in &run {
                let scene = f.get("scene").to_string();
                let mode = match f.get("sampling") {
                    "" => "exact".to_string(),
                    m => m.to_string(),
                };
                let Some((work, hash)) = fixray::with_format!(format, host(&scene, &mode))
                    .ok()
                    .flatten()
                else {
                    eprintln!("calibrate: the host cannot draw {scene} in {format}");
                    std::process::exit(1);
                };
                if hash != f.hash() {
                    eprintln!(
                        "calibrate: {core} {format} {scene} {mode}: the firmware's hash {:#010x} is not the host's {hash:#010x}",
                        f.hash()
                    );
                    std::process::exit(1);
                }
                let Some(instructions) = f.number("instructions") else {
                    eprintln!("calibrate: {core} {format} {scene} {mode}: no instruction count");
                    std::process::exit(1);
                };
                measured.push(Measured {
                    core,
                    format,
                    scene,
                    mode,
                    instructions: instructions as f64,
                    work,
                });
            }
        }
    }
    let mut raw = String::new();
    for m in &measured {
        let mut counts: Vec<String> = m.work.counts.iter().map(|c| c.to_string()).collect();
        let text = std::fs::read_to_string(crate::root().join(format!("scenes/{}.scene", m.scene)))
            .unwrap_or_default();
        if let Ok(scene) = LargeScene::<f64>::parse(&text) {
            let spheres = scene
                .objects
                .iter()
                .filter(|o| matches!(o.shape, fixray::geometry::Shape::Sphere(_)))
                .count();
            counts.push(spheres.to_string());
            counts.push(scene.objects.len().to_string());
            counts.push(scene.lights.len().to_string());
        }
        writeln!(
            raw,
            "{}\t{}\t{}\t{}\t{}\t{}",
            m.core,
            m.format,
            m.scene,
            m.mode,
            m.instructions,
            counts.join("\t")
        )
        .unwrap();
    }
    std::fs::write(crate::root().join("target/calibration.tsv"), raw).expect("target/ is writable");
    write(&measured, &formats, board, check);
}

/// `text` as `cargo fmt` leaves it (the models are Rust source, checked by `cargo fmt
/// --check`).
fn rustfmt(text: &str) -> String {
    use std::io::Write as _;
    let mut child = std::process::Command::new("rustfmt")
        .args(["--edition", "2024", "--emit", "stdout"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("rustfmt runs (the toolchain's)");
    child
        .stdin
        .take()
        .expect("piped")
        .write_all(text.as_bytes())
        .expect("rustfmt reads");
    let out = child.wait_with_output().expect("rustfmt ends");
    assert!(out.status.success(), "rustfmt formats the models");
    String::from_utf8(out.stdout).expect("rustfmt writes UTF-8")
}

/// Writes the models and the record.
fn write(measured: &[Measured], formats: &[&'static str], board: f64, check: bool) {
    let mut models = String::from(
        "//! The cost models, written by `cargo xtask calibrate` from the firmware's counts under\n\
         //! QEMU (`docs/calibration.md` holds every frame): do not edit.\n\n\
         use super::Model;\n\n\
         /// Every core × format calibrated: instructions per frame = Σ coefficient × count.\n\
         pub const MODELS: &[Model] = &[\n",
    );
    let mut record = String::from(
        "# The advisor's cost models\n\n\
         Written by `cargo xtask calibrate` (do not edit): every frame the firmware drew under \
         QEMU for the fit, its instructions per pixel as counted and as the model predicts \
         with its scene left out of the fit. The models are in `src/advise/model.rs`; how they \
         are made is in `xtask/src/calibrate.rs`.\n\n",
    );
    let mut rows = String::new();
    let mut summary = String::from(
        "| core | format | frames | median error (scene left out) | largest error |\n|---|---|---|---|---|\n",
    );
    let mut m0_boing = None;
    for (_, core) in qemu::CORES {
        for &format in formats {
            let frames: Vec<&Measured> = measured
                .iter()
                .filter(|m| m.core == core && m.format == format)
                // A mode whose blocks the scene's kind refuses drew the exact frame: it
                // would count twice.
                .filter(|m| m.mode == "exact" || m.work.sampled)
                .collect();
            if frames.is_empty() {
                continue;
            }
            let all = fit(&frames);
            let mut errors = Vec::new();
            for m in &frames {
                let others: Vec<&Measured> = frames
                    .iter()
                    .copied()
                    .filter(|o| o.scene != m.scene)
                    .collect();
                let c = fit(&others);
                let p = predict(&c, &m.work);
                let e = (p - m.instructions).abs() / m.instructions;
                errors.push(e);
                let px = m.work.pixels();
                writeln!(
                    rows,
                    "| {core} | {format} | {} | {} | {:.1} | {:.1} | {:+.1} % |",
                    m.scene,
                    m.mode,
                    m.instructions / px,
                    p / px,
                    100.0 * (p - m.instructions) / m.instructions
                )
                .unwrap();
                if core == "cortex-m0"
                    && format == "i16f16"
                    && m.scene == "boing-240x240"
                    && m.mode == "exact"
                {
                    m0_boing = Some(m.instructions / px);
                }
            }
            let sampled = frames.iter().any(|m| m.mode != "exact");
            let (med, max) = (
                median(errors.clone()),
                errors.iter().copied().fold(0.0, f64::max),
            );
            writeln!(
                summary,
                "| {core} | {format} | {} | {:.1} % | {:.1} % |",
                frames.len(),
                100.0 * med,
                100.0 * max
            )
            .unwrap();
            let coefficients: Vec<String> = all.iter().map(|c| format!("{c:.6e}")).collect();
            writeln!(
                models,
                "    Model {{\n        core: {core:?},\n        format: {format:?},\n        \
                 coefficients: [{}],\n        sampled: {sampled},\n        frames: {},\n        \
                 error: ({med:.4}, {max:.4}),\n    }},",
                coefficients.join(", "),
                frames.len()
            )
            .unwrap();
        }
    }
    let Some(m0) = m0_boing else {
        eprintln!("calibrate: no Cortex-M0 I16F16 count of boing-240x240");
        std::process::exit(1);
    };
    let cpi = board / m0;
    writeln!(
        models,
        "];\n\n/// Cycles per instruction of the RP2040's Cortex-M0+ on this code: the emulated board's\n\
         /// whole exact frame of the boing ball at 240×240 ({board:.1} cycles per pixel at 200 MHz)\n\
         /// over the Cortex-M0's count of `scenes/boing-240x240.scene` in I16F16 ({m0:.1}\n\
         /// instructions per pixel).\n\
         pub const RP2040_CYCLES_PER_INSTRUCTION: f64 = {cpi:.4};"
    )
    .unwrap();
    writeln!(
        record,
        "Features (`fixray::advise::FEATURES`): {}.\n\n\
         The RP2040's cycles per instruction: {cpi:.3} ({board:.1} cycles per pixel of the \
         board's whole exact frame over {m0:.1} instructions per pixel on the Cortex-M0).\n\n\
         {summary}\n\
         | core | format | scene | mode | counted instructions/pixel | predicted (scene left out) | error |\n\
         |---|---|---|---|---|---|---|\n{rows}",
        FEATURES.join(", ")
    )
    .unwrap();
    let files = [
        ("src/advise/model.rs", rustfmt(&models)),
        ("docs/calibration.md", record),
    ];
    if check {
        // The counts are deterministic for one QEMU; numbers may differ within the
        // figures' tolerance, words not at all.
        let stale: Vec<&str> = files
            .iter()
            .filter(|(path, text)| {
                let committed =
                    std::fs::read_to_string(crate::root().join(path)).unwrap_or_default();
                !crate::figures::agree(&committed, text)
            })
            .map(|(path, _)| *path)
            .collect();
        if !stale.is_empty() {
            eprintln!(
                "calibrate: {} differ from the counts (run `cargo xtask calibrate` and commit)",
                stale.join(" and ")
            );
            std::process::exit(1);
        }
        println!("calibrate: the models and their record are the counts'");
        return;
    }
    for (path, text) in files {
        std::fs::write(crate::root().join(path), text).unwrap_or_else(|e| panic!("{path}: {e}"));
    }
    println!("calibrate: src/advise/model.rs and docs/calibration.md written");
}
