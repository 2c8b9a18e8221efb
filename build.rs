//! Build script: the firmware's link setup (the cortex-m-quickstart pattern) and its build
//! options. Host builds get nothing but the declarations of the firmware's cfgs.
//!
//! `no_long_multiply` is set for cores without a 32 × 32 → 64 multiply (ARMv6-M, ARMv8-M
//! Baseline): see `src/num/wide.rs`.
//!
//! For the firmware targets (Cortex-M `thumb*`, and RISC-V `riscv32*-none-elf`):
//! - hands the board's layout to this package's examples only (`memory.x`, included by
//!   `cortex-m-rt`'s `link.x`; `memory-riscv.x`, read before `riscv-rt`'s `link.x`): a
//!   crate that depends on fixray links with its own;
//! - `fw_microbit` (thumbv6m: the BBC micro:bit, SysTick at 16 MHz) or `fw_mps2`
//!   (other thumb targets: MPS2 AN386, SysTick at 25 MHz) tell `examples/firmware.rs` its
//!   Arm board (on RISC-V it has one board, QEMU's virt, by `target_arch`);
//! - `FIXRAY_FW_FORMATS` (default `i16f16,f32`: more formats beside them do not fit
//!   256 KB of flash, build them on their own) chooses which number formats the firmware
//!   renders (checked against the one list, `src/num/formats.rs`, and handed to the
//!   firmware as `FIXRAY_FW_FORMATS_BUILT`), so that flash can be measured per format;
//! - `FIXRAY_FW_SCENES` (default `default,boing`: the boing ball is animated, 16 frames;
//!   an entry ending `.scene` is a file's path) chooses which scenes of `scenes/` the firmware
//!   embeds and renders (`$OUT_DIR/fw_scenes.rs`), with the texture files they name
//!   (`include_bytes!`, in flash);
//! - `FIXRAY_FW_SPANS=1` draws pure-geometry plane scenes in span mode (`fw_spans`);
//! - `FIXRAY_FW_SAMPLING` (a list such as `8x8:8,4x4:1`: block side and bound) also
//!   draws each frame sampled in those modes (`fw_sampling`; needs the cargo feature
//!   `sampling`), a band of 8 rows at a time;
//! - `FIXRAY_FW_PPM=1` makes the firmware also write each frame to the host as a PPM file
//!   through semihosting (`fw_ppm`).

use std::env;
use std::fs;
use std::path::PathBuf;

/// The number formats, read from the one list (`src/num/formats.rs`, `pub const
/// DESCRIBED`, rows `("name", "what it is")`): the build script cannot use the crate it
/// builds, so it reads the list's text.
fn formats(dir: &str) -> Vec<String> {
    let path = format!("{dir}/src/num/formats.rs");
    println!("cargo:rerun-if-changed={path}");
    let text = fs::read_to_string(&path).expect("src/num/formats.rs is readable");
    let start = text
        .find("pub const DESCRIBED")
        .expect("src/num/formats.rs defines DESCRIBED");
    let list = &text[start..];
    let open = list.find("= [").expect("DESCRIBED is an array") + 3;
    let close = list[open..].find("];").expect("DESCRIBED ends") + open;
    // The quoted strings alternate: name, what it is, name, … (no string holds a quote).
    list[open..close]
        .split('"')
        .skip(1)
        .step_by(4)
        .map(str::to_string)
        .collect()
}

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=memory-riscv.x");
    println!("cargo:rerun-if-env-changed=FIXRAY_FW_FORMATS");
    println!("cargo:rerun-if-env-changed=FIXRAY_FW_PPM");
    println!("cargo:rerun-if-env-changed=FIXRAY_FW_SCENES");
    println!("cargo:rerun-if-env-changed=FIXRAY_FW_SPANS");
    println!("cargo:rerun-if-env-changed=FIXRAY_FW_SAMPLING");
    for cfg in [
        "fw_microbit",
        "fw_mps2",
        "fw_ppm",
        "fw_sampling",
        "fw_spans",
        "no_long_multiply",
    ] {
        println!("cargo:rustc-check-cfg=cfg({cfg})");
    }
    let dir = env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    let known = formats(&dir);

    let target = env::var("TARGET").unwrap_or_default();
    // ARMv6-M and ARMv8-M Baseline have no 32 × 32 → 64 multiply (SMULL): the library
    // then forms double-width products from 16-bit halves (`num/wide.rs`,
    // bit-identical) instead of calling the 64-bit multiply helper.
    if target.starts_with("thumbv6m") || target.starts_with("thumbv8m.base") {
        println!("cargo:rustc-cfg=no_long_multiply");
    }
    let riscv = target.starts_with("riscv32") && target.ends_with("-none-elf");
    if !target.starts_with("thumb") && !riscv {
        return;
    }
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    // The board's layout: `memory.x` (cortex-m-rt's `link.x` includes it by that name) or
    // `memory-riscv.x` (named on the command line before riscv-rt's `link.x`: under its
    // own name, as the linker looks in the working directory, the crate's root, first).
    let (name, memory): (&str, &[u8]) = if riscv {
        ("memory-riscv.x", include_bytes!("memory-riscv.x"))
    } else {
        ("memory.x", include_bytes!("memory.x"))
    };
    fs::write(out.join(name), memory).expect("OUT_DIR is writable");
    // The search path as a link argument of this package's examples only: a
    // `rustc-link-search` would reach every binary that depends on fixray (a board crate
    // with its own `memory.x`, `boards/`) and could shadow that crate's layout.
    println!("cargo:rustc-link-arg-examples=-L{}", out.display());
    println!("cargo:rustc-link-arg-examples=--nmagic");
    // A firmware that draws sampled frames holds a band of 8 rows and the blocks' corners
    // beside the exact frame's stack: more than a micro:bit's 16 KiB. Its stack starts at
    // 64 KiB (the QEMU runner gives the micro:bit that much SRAM; `memory.x`, found first
    // in the crate's root, keeps the static data within 16 KiB). The riscv layout has
    // 64 KiB already.
    if !riscv && env::var("FIXRAY_FW_SAMPLING").is_ok_and(|v| !v.is_empty()) {
        println!("cargo:rustc-link-arg-examples=--defsym=_stack_start=0x20010000");
    }
    if riscv {
        // riscv-rt's `link.x` leaves the regions to a layout read before it.
        println!("cargo:rustc-link-arg-examples=-Tmemory-riscv.x");
    }
    println!("cargo:rustc-link-arg-examples=-Tlink.x");

    if !riscv {
        let board = if target.starts_with("thumbv6m") {
            "fw_microbit"
        } else {
            "fw_mps2"
        };
        println!("cargo:rustc-cfg={board}");
    }
    // The default is one fixed and one float format: with the course's tracer and every
    // effect built in, I16F16 and f32 take 219 KB of the 256 KB of flash in `memory.x` on
    // either core (with I20F12 beside them it overflows). Others build on
    // their own (I32F32 alone takes about 180 KB on the M0).
    let formats = env::var("FIXRAY_FW_FORMATS").unwrap_or_else(|_| "i16f16,f32".into());
    let mut chosen = Vec::new();
    for f in formats.split(',').map(str::trim).filter(|f| !f.is_empty()) {
        assert!(
            known.iter().any(|k| k == f),
            "FIXRAY_FW_FORMATS: unknown number format `{f}` (known: {})",
            known.join(", ")
        );
        chosen.push(f);
    }
    // The firmware reads the checked list at compile time (`env!`).
    println!(
        "cargo:rustc-env=FIXRAY_FW_FORMATS_BUILT={}",
        chosen.join(",")
    );
    let scenes = env::var("FIXRAY_FW_SCENES").unwrap_or_else(|_| "default,boing".into());
    let mut textures: Vec<(String, String)> = Vec::new();
    let mut table = String::from(
        "/// The scenes this firmware renders: (name, text).\nconst SCENES: &[(&str, &str)] = &[\n",
    );
    for entry in scenes.split(',').map(str::trim).filter(|n| !n.is_empty()) {
        // A name of `scenes/`, or the path of a scene file (ending `.scene`), named by its
        // file's stem.
        let (name, path) = match entry.strip_suffix(".scene") {
            Some(stem) => (stem.rsplit('/').next().unwrap_or(stem), entry.to_string()),
            None => (entry, format!("{dir}/scenes/{entry}.scene")),
        };
        assert!(
            name.chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-'),
            "FIXRAY_FW_SCENES: bad scene name `{name}`"
        );
        assert!(
            fs::metadata(&path).is_ok(),
            "FIXRAY_FW_SCENES: no file {path}"
        );
        println!("cargo:rerun-if-changed={path}");
        table.push_str(&format!("    (\"{name}\", include_str!({path:?})),\n"));
        // The texture files it names (`filename PATH`, relative to `scenes/`).
        let text = fs::read_to_string(&path).expect("the scene is readable");
        let words: Vec<&str> = text.split_whitespace().collect();
        for pair in words.windows(2).filter(|w| w[0] == "filename") {
            let file = pair[1];
            let full = format!("{dir}/scenes/{file}");
            assert!(
                fs::metadata(&full).is_ok(),
                "FIXRAY_FW_SCENES: {name} names a texture file {full} that is not there"
            );
            if !textures.iter().any(|(f, _)| f == file) {
                println!("cargo:rerun-if-changed={full}");
                textures.push((file.to_string(), full));
            }
        }
    }
    table.push_str("];\n");
    table.push_str(
        "/// The texture files those scenes name: (name as written, bytes), in flash.\n\
         const TEXTURES: &[(&str, &[u8])] = &[\n",
    );
    for (file, full) in &textures {
        table.push_str(&format!("    ({file:?}, include_bytes!({full:?})),\n"));
    }
    table.push_str("];\n");
    fs::write(out.join("fw_scenes.rs"), table).expect("OUT_DIR is writable");
    if env::var("FIXRAY_FW_SPANS").is_ok_and(|v| v == "1") {
        println!("cargo:rustc-cfg=fw_spans");
    }
    let sampling = env::var("FIXRAY_FW_SAMPLING").unwrap_or_default();
    for mode in sampling.split(',').filter(|m| !m.is_empty()) {
        let ok = mode.split_once(':').is_some_and(|(size, bound)| {
            ["2x2", "4x4", "8x8"].contains(&size) && bound.parse::<u8>().is_ok()
        });
        assert!(
            ok,
            "FIXRAY_FW_SAMPLING: bad mode `{mode}` (SIDExSIDE:BOUND, SIDE 2, 4 or 8, BOUND 0 to 255)"
        );
    }
    if !sampling.is_empty() {
        assert!(
            env::var_os("CARGO_FEATURE_SAMPLING").is_some(),
            "FIXRAY_FW_SAMPLING needs the cargo feature `sampling`"
        );
        println!("cargo:rustc-cfg=fw_sampling");
    }
    println!("cargo:rustc-env=FIXRAY_FW_SAMPLING_BUILT={sampling}");
    if env::var("FIXRAY_FW_PPM").is_ok_and(|v| v == "1") {
        println!("cargo:rustc-cfg=fw_ppm");
    }
}
