//! `cargo xtask firmware [FORMAT,...]`: builds the firmware for each core and format on
//! its own, runs it under QEMU and prints the table (instructions per frame and per pixel,
//! flash, RAM, frame hash). The hashes against the host's are asserted by
//! `tests/firmware.rs`; this prints the figures.

use crate::qemu;

pub fn main(args: &[String]) {
    if !qemu::qemu_available() {
        eprintln!("qemu-system-arm or qemu-system-riscv32 is not installed (both are needed)");
        std::process::exit(1);
    }
    let all = fixray::num::formats::FORMATS
        .iter()
        .filter(|f| **f != "f64");
    let formats: Vec<String> = match args.first() {
        Some(list) => list.split(',').map(str::to_string).collect(),
        None => all.map(|f| f.to_string()).collect(),
    };
    for f in &formats {
        if let Err(e) = fixray::num::formats::check(f) {
            eprintln!("{e}");
            std::process::exit(2);
        }
    }
    println!(
        "| core | format | instructions/frame | instructions/pixel | flash bytes | RAM bytes (static + stack) | hash |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (target, core) in qemu::CORES {
        for format in &formats {
            match qemu::run(target, format, "default") {
                Ok(run) => {
                    for f in &run.frames {
                        println!(
                            "| {core} | {format} | {} | {} | {} | {} ({} + {}) | {} |",
                            f.get("instructions"),
                            f.get("per_pixel"),
                            run.flash,
                            run.static_ram + f.number("stack").unwrap_or(0),
                            run.static_ram,
                            f.number("stack").unwrap_or(0),
                            f.get("hash")
                        );
                    }
                }
                Err(e) => {
                    eprintln!("{e}");
                    std::process::exit(1);
                }
            }
        }
    }
}
