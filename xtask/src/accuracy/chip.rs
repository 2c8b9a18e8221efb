//! Measurements on the chips: the firmware under QEMU, per core and format.

use super::*;

/// Firmware figures for one core and format: (scene → instructions per pixel), flash.
pub(super) struct Firmware {
    pub(super) per_pixel: BTreeMap<String, f64>,
    pub(super) instructions: BTreeMap<String, u64>,
    pub(super) flash: u64,
    pub(super) ram: u64,
}

/// Instructions per pixel of each scene's frame in a firmware run.
pub(super) fn per_pixel(run: &qemu::Run) -> BTreeMap<String, f64> {
    run.frames
        .iter()
        .map(|f| {
            let px = f.number("instructions").expect("reported") as f64 / f.pixels() as f64;
            (f.get("scene").to_string(), px)
        })
        .collect()
}

pub(super) fn measure_firmware(log: &mut String) -> BTreeMap<(String, String), Firmware> {
    let mut out = BTreeMap::new();
    let scenes: Vec<&str> = SCENES.iter().map(|s| s.0).collect();
    let scenes = scenes.join(",");
    for (target, core) in qemu::CORES {
        if !qemu::qemu_available_for(target) {
            let _ = writeln!(
                log,
                "{} not found: no {core} figures.",
                qemu::qemu_for(target)
            );
            continue;
        }
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

/// I16F16 firmware in span mode on every core (instructions per pixel per scene).
pub(super) fn measure_spans(log: &mut String) -> BTreeMap<String, Firmware> {
    let mut out = BTreeMap::new();
    for (target, core) in qemu::CORES {
        if !qemu::qemu_available_for(target) {
            continue;
        }
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
