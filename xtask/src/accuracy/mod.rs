//! `accuracy`: what each bit of accuracy costs in time. Measures every number format on
//! every shipped scene against the f64 reference (accuracy), on the host (criterion
//! medians) and on Cortex-M0, Cortex-M4F and RISC-V rv32imc under QEMU (instructions, flash), sweeps the
//! precision epsilon on the grazing scene, and writes `docs/accuracy.md` and
//! `docs/accuracy.png`. Never edit those by hand: run
//!
//! ```text
//! cargo xtask accuracy
//! ```
//!
//! The firmware columns need `qemu-system-arm`, `qemu-system-riscv32` and the firmware
//! targets (`.ci/run` installs them); a core whose QEMU is missing is left out, and the
//! report says so. `--quick` skips the firmware and shortens the host timing (to check
//! the command runs).

mod chip;
mod entities;
mod measure;
mod plot;
mod report;

use crate::qemu;
use chip::*;
use measure::*;
use plot::*;
use report::*;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use criterion::Criterion;
use embedded_graphics::mono_font::{MonoTextStyle, ascii::FONT_6X10};
use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{Circle, Line, PrimitiveStyle, Rectangle, Triangle};
use embedded_graphics::text::{Alignment, Text};
use embedded_graphics_simulator::{OutputSettings, SimulatorDisplay};
use fixray::compare::{Comparison, compare};
use fixray::shade::trace_pixel;
use fixray::{Scalar, Scene, render_line};

/// The scenes: name, what it is, text. The grazing scene is third (the epsilon sweep).
const SCENES: [(&str, &str, &str); 10] = [
    (
        "default",
        "the default scene: five planes, ambient + one light with shadows",
        include_str!("../../../scenes/default.scene"),
    ),
    (
        "planes",
        "planes only: a corridor of five planes, ambient only",
        include_str!("../../../scenes/planes.scene"),
    ),
    (
        "horizon",
        "grazing: an infinite floor to the horizon, ambient only",
        include_str!("../../../scenes/horizon.scene"),
    ),
    (
        "spheres",
        "spheres on a floor, one light with shadows",
        include_str!("../../../scenes/spheres.scene"),
    ),
    (
        "tiles",
        "a tiled checkerboard floor and a finite plane, ambient only",
        include_str!("../../../scenes/tiles.scene"),
    ),
    (
        "specular",
        "specular glints (shininess 4 and 40)",
        include_str!("../../../scenes/specular.scene"),
    ),
    (
        "spotlight",
        "a spotlight's cone beside a point light",
        include_str!("../../../scenes/spotlight.scene"),
    ),
    (
        "mirror",
        "reflection: a mirror sphere and a half-mirror floor",
        include_str!("../../../scenes/mirror.scene"),
    ),
    (
        "triangles",
        "triangles: a quad split along a shared edge, a pyramid face, one light with shadows",
        include_str!("../../../scenes/triangles.scene"),
    ),
    (
        "course",
        "a real course file (scene5: a sphere on a floor, two lights) at 160x120, course rules",
        include_str!("../../../scenes/course.scene"),
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
    report.push_str(&entities::entities_section(quick));
    report.push_str(&crate::blocks::section());
    std::fs::write(docs.join("accuracy.md"), report).expect("docs/ is writable");
    plot(&accuracy, &host, &firmware, &docs.join("accuracy.png"));
    println!("wrote docs/accuracy.md and docs/accuracy.png");
}

type AccuracyTable<'a> = BTreeMap<(&'a str, &'a str), Accuracy>;
type FirmwareTable = BTreeMap<(String, String), Firmware>;
