//! Bit-exact determinism: the firmware's frame hash under QEMU (Cortex-M0 and Cortex-M4F)
//! equals the host's hash of the same scene in the same format, for every fixed format.
//! For f32 the result is reported (and explained in the README), not asserted.
//!
//! Needs `qemu-system-arm` and the thumb targets, so it is ignored by a plain `cargo test`;
//! `.ci/run` installs both and runs it:
//! ```text
//! cargo test --release --test firmware -- --ignored --nocapture
//! ```
//! Each core × format is built on its own (`FIXRAY_FW_FORMATS=<format>`), so that its
//! flash size is that format's alone; the report table goes to stdout and to
//! `target/firmware-report.md`.

use std::collections::BTreeMap;

use object::{Object as _, ObjectSection as _};
use std::fmt::Write as _;
use std::process::Command;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use fixray::hash::FrameHash;
use fixray::{I16F16, I20F12, I32F32, Scalar, Scene, render_line};

const SCENE: &str = include_str!("../scenes/default.scene");
const TARGETS: [&str; 2] = ["thumbv6m-none-eabi", "thumbv7em-none-eabihf"];

/// The host's hash of the default scene in format `S`: every pixel, row by row.
fn host_hash<S: Scalar>() -> u32 {
    let scene = Scene::<S>::parse(SCENE).unwrap();
    let mut line = vec![Rgb888::BLACK; usize::from(scene.camera.width)];
    let mut hash = FrameHash::new();
    for row in 0..scene.camera.height {
        render_line(&scene, row, &mut line);
        for c in &line {
            hash.push(*c);
        }
    }
    hash.value()
}

/// Builds the firmware for one target with only `format` in it, runs it through the
/// cargo runner (QEMU), and returns the `key=value` fields of its frame line and the
/// ELF's flash (vector table + text + rodata) and static RAM (data + bss) in bytes.
fn run_firmware(target: &str, format: &str) -> (BTreeMap<String, String>, u64, u64) {
    let out = Command::new(env!("CARGO"))
        .args([
            "run",
            "--quiet",
            "--release",
            "--example",
            "firmware",
            "--target",
            target,
        ])
        .env("FIXRAY_FW_FORMATS", format)
        .env_remove("FIXRAY_FW_PPM")
        .output()
        .expect("cargo runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "firmware for {target} failed: {}\n{stdout}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<BTreeMap<String, String>> = stdout
        .lines()
        .filter(|l| l.starts_with("format="))
        .map(|l| {
            l.split_whitespace()
                .filter_map(|kv| kv.split_once('='))
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect()
        })
        .collect();
    assert_eq!(lines.len(), 1, "{target} {format}:\n{stdout}");
    let elf = std::fs::read(format!(
        "{}/target/{target}/release/examples/firmware",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let file = object::File::parse(&*elf).unwrap();
    let size = |names: &[&str]| -> u64 {
        file.sections()
            .filter(|s| s.name().is_ok_and(|n| names.contains(&n)))
            .map(|s| s.size())
            .sum()
    };
    let flash = size(&[".vector_table", ".text", ".rodata", ".data"]);
    let ram = size(&[".data", ".bss", ".uninit"]);
    (lines.into_iter().next().unwrap(), flash, ram)
}

#[test]
#[ignore = "needs qemu-system-arm and the thumb targets; run by .ci/run"]
fn firmware_frames_match_the_host_bit_for_bit() {
    let host: [(&str, u32); 4] = [
        ("i16f16", host_hash::<I16F16>()),
        ("i20f12", host_hash::<I20F12>()),
        ("i32f32", host_hash::<I32F32>()),
        ("f32", host_hash::<f32>()),
    ];
    let mut report = String::from(
        "| core | format | instructions/frame | instructions/pixel | of which hashing | \
         parse instructions | flash bytes | RAM bytes (static + stack) | hash | equal to host |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut mismatches = Vec::new();
    for target in TARGETS {
        for (format, host_hash) in host {
            let (f, flash, ram) = run_firmware(target, format);
            assert_eq!(f["format"], format);
            let hash = u32::from_str_radix(f["hash"].trim_start_matches("0x"), 16).unwrap();
            let equal = host_hash == hash;
            let pixels: u64 = f["size"]
                .split('x')
                .map(|n| n.parse::<u64>().unwrap())
                .product();
            let hashing = f["hash_instructions"].parse::<u64>().unwrap() as f64 / pixels as f64;
            let stack: u64 = f["stack"].parse().unwrap();
            writeln!(
                report,
                "| {} | {format} | {} | {} | {hashing:.1} | {} | {flash} | {} ({ram} + {stack}) | {} | {} |",
                f["core"],
                f["instructions"],
                f["per_pixel"],
                f["parse_instructions"],
                ram + stack,
                f["hash"],
                if equal { "yes" } else { "no" }
            )
            .unwrap();
            if !equal && format != "f32" {
                mismatches.push(format!(
                    "{target} {format}: firmware 0x{hash:08x}, host 0x{host_hash:08x}"
                ));
            }
        }
    }
    println!("{report}");
    std::fs::write(
        concat!(env!("CARGO_MANIFEST_DIR"), "/target/firmware-report.md"),
        &report,
    )
    .unwrap();
    // Fixed-point arithmetic is exact: any difference is a bug.
    assert!(mismatches.is_empty(), "{mismatches:#?}");
}
