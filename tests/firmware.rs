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

// Shared with examples/accuracy.rs, which uses other parts of it.
#[allow(dead_code)]
#[path = "../examples/support/qemu.rs"]
mod qemu;

use std::fmt::Write as _;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use fixray::hash::FrameHash;
use fixray::variants::{F32Micro, I16F16Narrow};
use fixray::{I16F16, I20F12, I32F32, Scalar, Scene, render_line};

const SCENE: &str = include_str!("../scenes/default.scene");

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

#[test]
#[ignore = "needs qemu-system-arm and the thumb targets; run by .ci/run"]
fn firmware_frames_match_the_host_bit_for_bit() {
    assert!(qemu::qemu_available(), "qemu-system-arm is not installed");
    let host: [(&str, u32); 6] = [
        ("i16f16", host_hash::<I16F16>()),
        ("i16f16n", host_hash::<I16F16Narrow>()),
        ("i20f12", host_hash::<I20F12>()),
        ("i32f32", host_hash::<I32F32>()),
        ("f32", host_hash::<f32>()),
        ("f32m", host_hash::<F32Micro>()),
    ];
    let mut report = String::from(
        "| core | format | instructions/frame | instructions/pixel | of which hashing | \
         parse instructions | flash bytes | RAM bytes (static + stack) | hash | equal to host |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut mismatches = Vec::new();
    for (target, core) in qemu::CORES {
        for (format, host_hash) in host {
            let run = qemu::run(target, format, "default").unwrap();
            assert_eq!(run.frames.len(), 1, "{target} {format}: {:?}", run.frames);
            let f = &run.frames[0];
            assert_eq!((f.get("format"), f.get("core")), (format, core));
            let equal = host_hash == f.hash();
            let hashing = f.number("hash_instructions") as f64 / f.pixels() as f64;
            let (ram, stack) = (run.static_ram, f.number("stack"));
            writeln!(
                report,
                "| {core} | {format} | {} | {} | {hashing:.1} | {} | {} | {} ({ram} + {stack}) | {} | {} |",
                f.get("instructions"),
                f.get("per_pixel"),
                f.get("parse_instructions"),
                run.flash,
                ram + stack,
                f.get("hash"),
                if equal { "yes" } else { "no" }
            )
            .unwrap();
            // Fixed-point arithmetic is exact: any difference is a bug. f32 is reported.
            if !equal && !format.starts_with("f32") {
                mismatches.push(format!(
                    "{target} {format}: firmware 0x{:08x}, host 0x{host_hash:08x}",
                    f.hash()
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
    assert!(mismatches.is_empty(), "{mismatches:#?}");
}
