//! `cargo xtask`: fixray's tools (the usual Rust `xtask` pattern; the alias is in
//! `.cargo/config.toml`). They run on the host, never on a chip:
//!
//! ```text
//! cargo xtask accuracy [--quick]   # docs/accuracy.md and docs/accuracy.png (needs qemu-system-arm, qemu-system-riscv32)
//! cargo xtask numerics             # docs/numerics.md
//! cargo xtask firmware [FORMATS]   # every core × format under QEMU: instructions, flash, hash
//! cargo xtask scene-format         # docs/scene-format.md's reference tables, from the schema
//! cargo xtask calibrate [--check] # the advisor's cost models, from the firmware's counts under QEMU
//! cargo xtask advise SCENE CORE [BUDGET]   # the advisor with every candidate counted under QEMU
//! cargo xtask figures [--check]    # the measured figures of README.md and docs/, from the reports and host renders
//! ```

// The test-support module's helpers, shared with the integration tests.
#[allow(dead_code)]
#[path = "../../tests/common/pictures.rs"]
mod pictures;
#[allow(dead_code)]
#[path = "../../tests/common/qemu.rs"]
mod qemu;
#[allow(dead_code)]
#[path = "../../tests/common/sampling.rs"]
mod sampling;

mod accuracy;
mod advice;
mod blocks;
mod calibrate;
mod figures;
mod firmware;
mod numerics;
mod scene_format;

const USAGE: &str = "usage: cargo xtask accuracy [--quick] | numerics | firmware [FORMAT,...] | calibrate [--check] | advise SCENE CORE [BUDGET] | figures [--check] | scene-format";

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("accuracy") => accuracy::main(&args[1..]),
        Some("numerics") => numerics::main(),
        Some("firmware") => firmware::main(&args[1..]),
        Some("scene-format") => scene_format::main(),
        Some("figures") => figures::main(&args[1..]),
        Some("calibrate") => calibrate::main(&args[1..]),
        Some("advise") => advice::main(&args[1..]),
        _ => {
            eprintln!("{USAGE}");
            std::process::exit(2);
        }
    }
}

/// The repository's root (this crate lives in `xtask/`).
fn root() -> &'static std::path::Path {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask/ has a parent")
}
