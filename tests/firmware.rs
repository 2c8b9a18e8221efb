//! Bit-exact determinism: the firmware's frame hash under QEMU (Cortex-M0, Cortex-M4F and
//! RISC-V rv32imc) equals the host's hash of the same scene in the same format, for every
//! fixed format. For f32 the result is reported (and explained in the README), not asserted.
//!
//! Needs `qemu-system-arm`, `qemu-system-riscv32` and the three targets, so it is ignored by
//! a plain `cargo test`; `.ci/run` installs them and runs it:
//! ```text
//! cargo test --release --test firmware -- --ignored --nocapture
//! ```
//! Each core × format is built on its own (`FIXRAY_FW_FORMATS=<format>`), so that its
//! flash size is that format's alone; the report table goes to stdout and to
//! `target/firmware-report.md`.

mod common;
use common::qemu;

use std::fmt::Write as _;

use embedded_graphics::pixelcolor::{Rgb888, RgbColor};
use fixray::hash::FrameHash;
use fixray::{Scalar, Scene, render_line};

/// The scenes the hash test runs on the chips: the default scene (the crate's rules) and
/// a real course file at 160×120 (the course rules).
const SCENES: [(&str, &str); 2] = [
    ("default", include_str!("../scenes/default.scene")),
    ("course", include_str!("../scenes/course.scene")),
];

/// The host's hash of a scene in format `S`: every pixel, row by row.
fn host_hash<S: Scalar>(text: &str) -> u32 {
    frame_hash(&Scene::<S>::parse(text).unwrap())
}

/// The hash of a parsed scene's frame, drawn line by line as the firmware draws it.
fn frame_hash<S: Scalar>(scene: &Scene<S>) -> u32 {
    let mut line = vec![Rgb888::BLACK; usize::from(scene.camera.width)];
    let mut hash = FrameHash::new();
    for row in 0..scene.camera.height {
        render_line(scene, row, &mut line);
        line.iter().for_each(|c| hash.push(*c));
    }
    hash.value()
}

/// A field the firmware did not report is not read as 0: as 0, the `full/bare ≤ 1.05`
/// check of `absent_effects_cost_nothing_on_the_chip` would pass when nothing was reported.
#[test]
fn a_missing_report_field_is_not_a_zero() {
    let line = "format=i16f16 size=160x120 hash=0x1 instructions=oops";
    let frame = qemu::Frame(
        line.split_whitespace()
            .filter_map(|kv| kv.split_once('='))
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect(),
    );
    assert_eq!(frame.number("instructions"), None);
    assert_eq!(frame.number("stack"), None);
    assert_eq!(frame.pixels(), 19_200);
}

#[test]
#[ignore = "needs QEMU (arm, riscv32) and the firmware targets; run by .ci/run"]
fn firmware_frames_match_the_host_bit_for_bit() {
    assert!(
        qemu::qemu_available(),
        "qemu-system-arm or qemu-system-riscv32 is not installed"
    );
    // Every format of the one list but the f64 reference (soft float on every core).
    let host: Vec<(&str, [u32; 2])> = fixray::num::formats::FORMATS
        .into_iter()
        .filter(|f| *f != fixray::num::formats::REFERENCE)
        .map(|f| {
            let hash = |text: &str| fixray::with_format!(f, host_hash(text)).unwrap();
            (f, [hash(SCENES[0].1), hash(SCENES[1].1)])
        })
        .collect();
    let mut report = String::from(
        "| core | format | scene | instructions/frame | instructions/pixel | of which hashing | \
         parse instructions | flash bytes | RAM bytes (static + stack) | hash | equal to host |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut mismatches = Vec::new();
    for (target, core) in qemu::CORES {
        for &(format, host_hashes) in &host {
            let run = qemu::run(target, format, "default,course").unwrap();
            assert_eq!(run.frames.len(), 2, "{target} {format}: {:?}", run.frames);
            for (f, ((scene, _), host_hash)) in
                run.frames.iter().zip(SCENES.iter().zip(host_hashes))
            {
                assert_eq!(
                    (f.get("format"), f.get("core"), f.get("scene")),
                    (format, core, *scene)
                );
                let equal = host_hash == f.hash();
                let hashing =
                    f.number("hash_instructions").expect("reported") as f64 / f.pixels() as f64;
                let (ram, stack) = (run.static_ram, f.number("stack").expect("reported"));
                writeln!(
                report,
                "| {core} | {format} | {scene} | {} | {} | {hashing:.1} | {} | {} | {} ({ram} + {stack}) | {} | {} |",
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
                        "{target} {format} {scene}: firmware 0x{:08x}, host 0x{host_hash:08x}",
                        f.hash()
                    ));
                }
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

/// What absent effects cost: every effect scene's instructions per pixel on the Cortex-M4F
/// (I16F16), the flash of the firmware per set of cargo features (planes and ambient
/// only, then with lighting, spheres, everything; then without the kernels, where every
/// effect of the crate's rules fits 64 KiB), and the ambient-only scene rendered by the
/// full renderer against the same scene with every other stage compiled out: at most 5 %
/// more instructions (instruction counts are deterministic).
#[test]
#[ignore = "needs qemu-system-arm and the thumb targets; run by .ci/run"]
fn absent_effects_cost_nothing_on_the_chip() {
    let target = "thumbv7em-none-eabihf";
    assert!(
        qemu::qemu_available_for(target),
        "{} is not installed",
        qemu::qemu_for(target)
    );
    let scenes = "default,planes,horizon,spheres,tiles,specular,spotlight,mirror";
    let mut report = String::from(
        "| scene (Cortex-M4F) | i16f16 instructions/pixel | f32 instructions/pixel |\n|---|---|---|\n",
    );
    let i16 = qemu::run(target, "i16f16", scenes).unwrap();
    let f32 = qemu::run(target, "f32", scenes).unwrap();
    for (a, b) in i16.frames.iter().zip(&f32.frames) {
        writeln!(
            report,
            "| {} | {} | {} |",
            a.get("scene"),
            a.get("per_pixel"),
            b.get("per_pixel")
        )
        .unwrap();
    }
    report.push_str("\n| cargo features | flash bytes (M0, i16f16) | planes scene instructions (M0) |\n|---|---|---|\n");
    let mut flash = Vec::new();
    for features in [
        Some("kernels"),
        Some("kernels,lighting"),
        Some("kernels,lighting,spheres"),
        Some("kernels,lighting,spheres,reflection"),
        None,
        Some(""),
        Some("lighting,spheres,reflection"),
    ] {
        let run =
            qemu::run_with_features("thumbv6m-none-eabi", "i16f16", "planes", features).unwrap();
        let name = features.map_or("all (default: with `course`)", |f| match f {
            "kernels" => "kernels: planes + ambient",
            "" => "none: planes + ambient, the reference path only",
            f => f,
        });
        writeln!(
            report,
            "| {name} | {} | {} |",
            run.flash,
            run.frames[0].get("instructions")
        )
        .unwrap();
        // A count that was not reported is a failure, not a 0 (which would make the ratio
        // below pass whatever the renderer costs).
        let instructions = run.frames[0]
            .number("instructions")
            .expect("the firmware reports its instructions");
        flash.push((run.flash, instructions));
    }
    println!("{report}");
    std::fs::write(
        concat!(env!("CARGO_MANIFEST_DIR"), "/target/effects-report.md"),
        &report,
    )
    .unwrap();
    let (bare, full) = (flash[0], flash[4]);
    // The planes + ambient firmware carries no lighting, sphere or reflection code.
    assert!(
        bare.0 < flash[1].0 && flash[1].0 < flash[2].0 && flash[2].0 <= flash[3].0,
        "{flash:?}"
    );
    // Without the `course` feature the course's tracer (at least 4 KB) is not linked.
    assert!(
        full.0.saturating_sub(flash[3].0) >= 4096,
        "the course's tracer is {} bytes: is it gated by its feature? {flash:?}",
        full.0.saturating_sub(flash[3].0)
    );
    // The `spheres` feature gates the sphere intersection, normal and spawn, not only the
    // parser's arm: without it none of them is linked.
    assert!(
        flash[2].0 - flash[1].0 >= 1024,
        "the sphere code is {} bytes: is it gated by its feature? {flash:?}",
        flash[2].0 - flash[1].0
    );
    // Without the kernels none of their code is linked (the reference path draws every
    // frame: `every_effect_draws_the_definition_without_the_kernels`).
    for (lean, fast) in [(flash[5], flash[0]), (flash[6], flash[3])] {
        assert!(
            fast.0.saturating_sub(lean.0) >= 8 * 1024,
            "the kernels are {} bytes: are they gated by their feature? {flash:?}",
            fast.0.saturating_sub(lean.0)
        );
    }
    // Every effect of the crate's rules fits a 64 KB chip without the kernels.
    assert!(
        flash[6].0 <= 64 * 1024,
        "every effect without the kernels: {} bytes of flash, above 64 KiB",
        flash[6].0
    );
    // The full renderer on an ambient-only scene: within 5 % of the compiled-out one.
    let ratio = full.1 as f64 / bare.1 as f64;
    println!("ambient-only scene, full renderer / stages compiled out: {ratio:.4}");
    assert!(ratio <= 1.05, "{ratio}");
}

/// The host's hash of a scene drawn by the reference path, pixel by pixel
/// ([`fixray::shade::trace_pixel`], the definition): what a firmware without the kernels draws.
fn reference_hash<S: Scalar>(scene: &Scene<S>) -> u32 {
    let mut hash = FrameHash::new();
    for row in 0..scene.camera.height {
        for column in 0..scene.camera.width {
            hash.push(fixray::shade::to_rgb888(
                fixray::shade::trace_pixel(scene, column, row).color,
            ));
        }
    }
    hash.value()
}

/// Every effect of the crate's rules without the kernels (cargo feature
/// `kernels` off, the firmware that fits a 64 KB chip: its flash is asserted in
/// `absent_effects_cost_nothing_on_the_chip`): the M0 I16F16 firmware with lighting,
/// spheres and reflection draws every shipped scene of the crate's rules (the boing
/// ball's 16 frames among them) with the hash of the host's reference path, and the
/// firmware with the kernels with the hash of the host's kernels. Their instructions per
/// pixel go to stdout and `target/lean-report.md`.
#[test]
#[ignore = "needs qemu-system-arm and the thumb targets; run by .ci/run"]
fn every_effect_draws_the_definition_without_the_kernels() {
    assert!(
        qemu::qemu_available_for("thumbv6m-none-eabi"),
        "qemu-system-arm is not installed"
    );
    let scenes: [(&str, &str); 10] = [
        ("default", include_str!("../scenes/default.scene")),
        ("planes", include_str!("../scenes/planes.scene")),
        ("horizon", include_str!("../scenes/horizon.scene")),
        ("spheres", include_str!("../scenes/spheres.scene")),
        ("tiles", include_str!("../scenes/tiles.scene")),
        ("specular", include_str!("../scenes/specular.scene")),
        ("spotlight", include_str!("../scenes/spotlight.scene")),
        ("mirror", include_str!("../scenes/mirror.scene")),
        ("triangles", include_str!("../scenes/triangles.scene")),
        ("boing", include_str!("../scenes/boing.scene")),
    ];
    let names: Vec<&str> = scenes.iter().map(|(n, _)| *n).collect();
    let names = names.join(",");
    let lean = "lighting,spheres,reflection";
    let fast = format!("kernels,{lean}");
    let lean_run = qemu::run_with_features("thumbv6m-none-eabi", "i16f16", &names, Some(lean))
        .unwrap_or_else(|e| panic!("without the kernels: {e}"));
    let fast_run = qemu::run_with_features("thumbv6m-none-eabi", "i16f16", &names, Some(&fast))
        .unwrap_or_else(|e| panic!("with the kernels: {e}"));
    let mut report = String::from(
        "| scene (M0, I16F16) | instructions/pixel without the kernels | with them | \
         hashes equal to the host's |\n|---|---|---|---|\n",
    );
    let mut mismatches = Vec::new();
    let mut frames = lean_run.frames.iter().zip(&fast_run.frames);
    for (name, text) in scenes {
        let mut scene = Scene::<fixray::I16F16>::parse(text).unwrap();
        let bounce =
            (name == "boing").then(|| fixray::anim::Bounce::boing(&scene.objects).unwrap());
        for k in 0..bounce.map_or(1, |b| b.frames()) {
            if let Some(b) = bounce {
                b.apply(&mut scene, k).unwrap();
            }
            let host = (reference_hash(&scene), frame_hash(&scene));
            let (lean, fast) = frames
                .next()
                .unwrap_or_else(|| panic!("{name}: frame {k} was not reported"));
            assert_eq!((lean.get("scene"), fast.get("scene")), (name, name));
            let equal = (lean.hash(), fast.hash()) == host;
            let label = match bounce {
                Some(_) => format!("{name} frame {k}"),
                None => name.to_string(),
            };
            writeln!(
                report,
                "| {label} | {} | {} | {} |",
                lean.get("per_pixel"),
                fast.get("per_pixel"),
                if equal { "yes" } else { "no" }
            )
            .unwrap();
            if !equal {
                mismatches.push(format!(
                    "{label}: host (reference, kernels) 0x{:08x}, 0x{:08x}; \
                     firmware 0x{:08x}, 0x{:08x}",
                    host.0,
                    host.1,
                    lean.hash(),
                    fast.hash()
                ));
            }
        }
    }
    assert!(frames.next().is_none(), "more frames than scenes");
    println!("{report}");
    std::fs::write(
        concat!(env!("CARGO_MANIFEST_DIR"), "/target/lean-report.md"),
        &report,
    )
    .unwrap();
    assert!(mismatches.is_empty(), "{mismatches:#?}");
}

/// The course's entities on the chips: one shipped scene each (translucency,
/// a textured plane, a projector, surfaces of revolution), built with the `textures`
/// feature (its texture, 32×32, in flash), in I16F16 and f32 on the three cores: instructions
/// per pixel, flash, and the frame hash against the host's (equal in I16F16, asserted).
#[test]
#[ignore = "needs QEMU (arm, riscv32) and the firmware targets; run by .ci/run"]
fn course_entities_on_the_chips() {
    assert!(
        qemu::qemu_available(),
        "qemu-system-arm or qemu-system-riscv32 is not installed"
    );
    let scenes = [
        ("translucent", include_str!("../scenes/translucent.scene")),
        ("texplane", include_str!("../scenes/texplane.scene")),
        ("projector", include_str!("../scenes/projector.scene")),
        ("revsurf", include_str!("../scenes/revsurf.scene")),
        ("vases", include_str!("../scenes/vases.scene")),
    ];
    let names = scenes.map(|s| s.0).join(",");
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/x.scene");
    let host = |format: &str, text: &str| -> u32 {
        fn hash<S: Scalar>(text: &str, dir: &str) -> u32 {
            let mut scene = Scene::<S>::empty();
            scene
                .read_with(text, None, &mut fixray::scene::files::beside(dir.as_ref()))
                .unwrap();
            frame_hash(&scene)
        }
        fixray::with_format!(format, hash(text, dir)).unwrap()
    };
    let mut report = String::from(
        "| core | format | scene | instructions/pixel | flash bytes | stack bytes | hash equal to host |\n|---|---|---|---|---|---|---|\n",
    );
    let mut mismatches = Vec::new();
    for (target, core) in qemu::CORES {
        for format in ["i16f16", "f32"] {
            let run = qemu::run_with_features(
                target,
                format,
                &names,
                Some("kernels,lighting,spheres,reflection,course,textures"),
            )
            .unwrap();
            assert_eq!(
                run.frames.len(),
                scenes.len(),
                "{target} {format}: {:?}",
                run.frames
            );
            for (f, (scene, text)) in run.frames.iter().zip(scenes) {
                assert_eq!(f.get("scene"), scene);
                let equal = f.hash() == host(format, text);
                writeln!(
                    report,
                    "| {core} | {format} | {scene} | {} | {} | {} | {} |",
                    f.get("per_pixel"),
                    run.flash,
                    f.get("stack"),
                    if equal { "yes" } else { "no" }
                )
                .unwrap();
                if !equal && format == "i16f16" {
                    mismatches.push(format!("{target} {format} {scene}"));
                }
            }
        }
    }
    println!("{report}");
    std::fs::write(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/target/course-entities-report.md"
        ),
        &report,
    )
    .unwrap();
    assert!(mismatches.is_empty(), "{mismatches:?}");
}

/// The largest format's scene (I32F32, 6.5 KB) on the Cortex-M0's 16 KB of RAM: the
/// firmware (default features) over every shipped scene it draws, with 2 KB to spare
/// (static RAM plus the deepest stack, painted, at most `M0_RAM_BUDGET`). The mirror
/// scene's four reflections are a loop (`shade/fixray.rs`), not a recursion, so its stack
/// does not grow with the depth. The firmware with the `textures` feature (the course
/// entities' scenes: a larger scene, texture and projector blocks in the parser) must fit
/// 16 KB; its headroom is reported, not held to 2 KB (`README.md`, "Cost and size"). A
/// frame that outgrows 16 KB is a HardFault under QEMU (QEMU then exits with an error),
/// one that eats the headroom a report above the budget: either fails here.
#[test]
#[ignore = "needs qemu-system-arm and the thumb targets; run by .ci/run"]
fn i32f32_fits_the_cortex_m0_in_every_shipped_scene() {
    /// 16 KB of RAM on the micro:bit's Cortex-M0, less 2 KB of headroom.
    const M0_RAM_BUDGET: u64 = 14 * 1024;
    assert!(
        qemu::qemu_available_for("thumbv6m-none-eabi"),
        "qemu-system-arm is not installed"
    );
    let names = [
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
    ];
    // The scenes of the course's entities need the `textures` feature (room for
    // textures in the scene, the texel lookups).
    // Not `vases`: its root search takes I32F32 to 16,356 bytes of stack on the M0 (and
    // 920,000 instructions a pixel), over the 16 KB with the static RAM; it runs in
    // I16F16 and f32 in `course_entities_on_the_chips`.
    let textured = ["translucent", "texplane", "projector", "revsurf"];
    let runs = [
        (names.as_slice(), None, M0_RAM_BUDGET),
        (
            textured.as_slice(),
            Some("kernels,lighting,spheres,reflection,course,textures"),
            16 * 1024,
        ),
    ];
    for (names, features, budget) in runs {
        let run =
            qemu::run_with_features("thumbv6m-none-eabi", "i32f32", &names.join(","), features)
                .unwrap_or_else(|e| panic!("I32F32 on the Cortex-M0 ({features:?}): {e}"));
        assert_eq!(run.frames.len(), names.len(), "{:?}", run.frames);
        for (f, name) in run.frames.iter().zip(names) {
            assert_eq!(f.get("scene"), *name);
            let ram = run.static_ram + f.number("stack").expect("reported");
            println!("i32f32 cortex-m0 {name}: {ram} bytes of RAM (static + deepest stack)");
            assert!(
                ram <= budget,
                "{name} ({features:?}): {ram} bytes of RAM, above {budget}"
            );
        }
    }
}

/// The host's hash of frame `k` of the boing ball in format `S` (its sphere moved by
/// `Bounce::boing`, as the firmware moves it).
fn boing_hash<S: Scalar>(k: u16) -> u32 {
    let mut scene = Scene::<S>::parse(include_str!("../scenes/boing.scene")).unwrap();
    fixray::anim::Bounce::boing(&scene.objects)
        .unwrap()
        .apply(&mut scene, k)
        .unwrap();
    frame_hash(&scene)
}

/// The boing ball as the README's plain firmware commands build it (default
/// features and formats, I16F16 and f32): 16 frames on each core, every frame's hash
/// equal to the host's (asserted for both formats: f32 is correctly rounded everywhere),
/// and the animation's table (instructions per pixel per core; no frame rate: that needs
/// cycles, which QEMU does not count) to stdout and
/// `target/boing-report.md`.
#[test]
#[ignore = "needs QEMU (arm, riscv32) and the firmware targets; run by .ci/run"]
fn the_boing_ball_bounces_bit_for_bit_on_every_core() {
    assert!(
        qemu::qemu_available(),
        "qemu-system-arm or qemu-system-riscv32 is not installed"
    );
    let mut per_pixel = std::collections::BTreeMap::new();
    let mut mismatches = Vec::new();
    for (target, core) in qemu::CORES {
        let run = qemu::run(target, "i16f16,f32", "boing").unwrap();
        assert_eq!(run.frames.len(), 32, "{target}: {:?}", run.frames);
        for f in &run.frames {
            let format = f.get("format");
            let k: u16 = f.get("frame").parse().expect("a frame number");
            let host = fixray::with_format!(format, boing_hash(k)).unwrap();
            if host != f.hash() {
                mismatches.push(format!("{core} {format} frame {k}"));
            }
            let cost: f64 = f.get("per_pixel").parse().expect("per_pixel");
            per_pixel.insert((format.to_string(), k, core), cost);
        }
    }
    let mut report = String::from(
        "| format | frame | M0 instructions/pixel | M4F instructions/pixel | RISC-V instructions/pixel |\n|---|---|---|---|---|\n",
    );
    for format in ["i16f16", "f32"] {
        let mut sums = [0.0; 3];
        for k in 0..16u16 {
            let costs = qemu::CORES.map(|(_, core)| per_pixel[&(format.to_string(), k, core)]);
            for (sum, c) in sums.iter_mut().zip(costs) {
                *sum += c;
            }
            let [m0, m4, rv] = costs;
            writeln!(report, "| {format} | {k} | {m0:.1} | {m4:.1} | {rv:.1} |").unwrap();
        }
        let [m0, m4, rv] = sums.map(|s| s / 16.0);
        writeln!(
            report,
            "| {format} | **mean** | **{m0:.1}** | **{m4:.1}** | **{rv:.1}** |"
        )
        .unwrap();
    }
    println!("{report}");
    std::fs::write(
        concat!(env!("CARGO_MANIFEST_DIR"), "/target/boing-report.md"),
        &report,
    )
    .unwrap();
    assert!(mismatches.is_empty(), "{mismatches:?}");
}

/// The Cortex-M0's quick pixels (`Scalar::quick_pixel`, used on cores without a long
/// multiply and on the host; the M4F and RISC-V keep the exact terms): the level-plane
/// scenes the repository ships, in both formats that have them, on the M0, each frame's
/// hash equal to the host's (the spheres and tiles scenes and all 16 boing frames in
/// I16F16 and I20F12).
#[test]
#[ignore = "needs qemu-system-arm; run with --ignored (CI does)"]
fn quick_pixels_on_the_m0_are_the_hosts_bit_for_bit() {
    assert!(
        qemu::qemu_available_for("thumbv6m-none-eabi"),
        "qemu-system-arm is not installed"
    );
    let scenes = [
        ("spheres", include_str!("../scenes/spheres.scene")),
        ("tiles", include_str!("../scenes/tiles.scene")),
    ];
    // One firmware per format: both with the three scenes do not fit the micro:bit's
    // 256 KB of flash.
    let runs = ["i16f16", "i20f12"]
        .map(|format| qemu::run("thumbv6m-none-eabi", format, "spheres,tiles,boing").unwrap());
    let frames: Vec<_> = runs.iter().flat_map(|run| &run.frames).collect();
    assert_eq!(frames.len(), 2 * (2 + 16), "{frames:?}");
    let mut mismatches = Vec::new();
    for f in frames {
        let format = f.get("format");
        let host = match scenes.iter().find(|(name, _)| *name == f.get("scene")) {
            Some((_, text)) => fixray::with_format!(format, host_hash(text)).unwrap(),
            None => {
                assert_eq!(f.get("scene"), "boing");
                let k: u16 = f.get("frame").parse().expect("a frame number");
                fixray::with_format!(format, boing_hash(k)).unwrap()
            }
        };
        if host != f.hash() {
            mismatches.push(format!("{format} {} {:?}", f.get("scene"), f.get("frame")));
        }
    }
    assert!(mismatches.is_empty(), "{mismatches:?}");
}
