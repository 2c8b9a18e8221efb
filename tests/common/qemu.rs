//! Builds `examples/firmware.rs` for a Cortex-M or RISC-V target, runs it under QEMU through the
//! cargo runner (`.cargo/config.toml`), and reads what it reports. Part of the
//! test-support module (`tests/firmware.rs`), shared with `xtask` (the accuracy report
//! and `cargo xtask firmware`).

use std::collections::BTreeMap;
use std::process::Command;

use object::{Object as _, ObjectSection as _};

/// The three cores: Rust target and the name the firmware reports.
pub const CORES: [(&str, &str); 3] = [
    ("thumbv6m-none-eabi", "cortex-m0"),
    ("thumbv7em-none-eabihf", "cortex-m4f"),
    ("riscv32imc-unknown-none-elf", "riscv32imc"),
];

/// One `format=...` line of the firmware: its `key=value` fields.
#[derive(Debug, Clone)]
pub struct Frame(pub BTreeMap<String, String>);

impl Frame {
    /// A field as text ("" when absent).
    pub fn get(&self, key: &str) -> &str {
        self.0.get(key).map_or("", String::as_str)
    }

    /// A numeric field; `None` when absent or malformed (never a silent 0).
    pub fn number(&self, key: &str) -> Option<u64> {
        self.get(key).parse().ok()
    }

    /// The frame hash.
    pub fn hash(&self) -> u32 {
        u32::from_str_radix(self.get("hash").trim_start_matches("0x"), 16).unwrap_or(0)
    }

    /// Pixels in the frame (`size=WxH`).
    pub fn pixels(&self) -> u64 {
        self.get("size")
            .split('x')
            .map(|n| n.parse::<u64>().unwrap_or(0))
            .product()
    }
}

/// What one firmware build reported, with its size.
#[derive(Debug, Clone)]
pub struct Run {
    /// One entry per rendered frame (scene × format).
    pub frames: Vec<Frame>,
    /// Vector table + text + rodata + data (initialisers) in bytes.
    pub flash: u64,
    /// data + bss in bytes (the stack is in each frame's `stack`).
    pub static_ram: u64,
}

/// The repository's root (this file is compiled into the tests and into `xtask/`).
pub fn root() -> std::path::PathBuf {
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    match here.file_name() {
        Some(name) if name == "xtask" => here.parent().unwrap_or(here).to_path_buf(),
        _ => here.to_path_buf(),
    }
}

/// The QEMU that runs a target's firmware (the runners in `.cargo/config.toml`).
pub fn qemu_for(target: &str) -> &'static str {
    if target.starts_with("riscv") {
        "qemu-system-riscv32"
    } else {
        "qemu-system-arm"
    }
}

/// Whether the QEMU for `target` can be started.
pub fn qemu_available_for(target: &str) -> bool {
    Command::new(qemu_for(target))
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Whether the QEMU of every core in [`CORES`] can be started.
pub fn qemu_available() -> bool {
    CORES.iter().all(|(target, _)| qemu_available_for(target))
}

/// Builds and runs the firmware for `target` with the given formats and scenes (comma
/// lists, as `FIXRAY_FW_FORMATS` and `FIXRAY_FW_SCENES` take them) and the crate's
/// default features.
pub fn run(target: &str, formats: &str, scenes: &str) -> Result<Run, String> {
    run_with_features(target, formats, scenes, None)
}

/// [`run`] with `--no-default-features --features <features>` when `features` is given.
pub fn run_with_features(
    target: &str,
    formats: &str,
    scenes: &str,
    features: Option<&str>,
) -> Result<Run, String> {
    run_with(target, formats, scenes, features, false, "")
}

/// [`run`] with each frame also drawn sampled in blocks (`FIXRAY_FW_SAMPLING`, e.g.
/// `8x8:8,4x4:1`; `features` must hold `sampling`): one more frame reported per mode,
/// with `sampling=` and `filled=`.
pub fn run_sampled(
    target: &str,
    formats: &str,
    scenes: &str,
    features: &str,
    sampling: &str,
) -> Result<Run, String> {
    run_with(target, formats, scenes, Some(features), false, sampling)
}

/// [`run`] with pure-geometry plane scenes drawn in span mode (`FIXRAY_FW_SPANS=1`).
pub fn run_spans(target: &str, formats: &str, scenes: &str) -> Result<Run, String> {
    run_with(target, formats, scenes, None, true, "")
}

/// One firmware build and run at a time: the builds share `target/` (one ELF per
/// target), and the test harness runs tests on parallel threads, so without it one
/// test's `cargo run` could start the ELF another test's build had just replaced.
static FIRMWARE: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn run_with(
    target: &str,
    formats: &str,
    scenes: &str,
    features: Option<&str>,
    spans: bool,
    sampling: &str,
) -> Result<Run, String> {
    // A panic in another test while it held the lock leaves nothing half-done here.
    let _one_at_a_time = FIRMWARE.lock().unwrap_or_else(|e| e.into_inner());
    let root = root();
    let manifest = root.to_str().ok_or("the repository path is not UTF-8")?;
    let mut args = vec![
        "run",
        "--quiet",
        "--release",
        "--example",
        "firmware",
        "--target",
        target,
    ];
    if let Some(f) = features {
        args.extend(["--no-default-features", "--features", f]);
    }
    let out = Command::new(env!("CARGO"))
        .current_dir(manifest)
        .args(&args)
        .env("FIXRAY_FW_FORMATS", formats)
        .env("FIXRAY_FW_SCENES", scenes)
        .env_remove("FIXRAY_FW_PPM")
        .env("FIXRAY_FW_SPANS", if spans { "1" } else { "0" })
        .env("FIXRAY_FW_SAMPLING", sampling)
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() {
        return Err(format!(
            "firmware for {target} ({formats}; {scenes}) failed: {}\n{stdout}\n{}",
            out.status,
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let frames: Vec<Frame> = stdout
        .lines()
        .filter(|l| l.starts_with("format="))
        .map(|l| {
            Frame(
                l.split_whitespace()
                    .filter_map(|kv| kv.split_once('='))
                    .map(|(k, v)| (k.to_string(), v.to_string()))
                    .collect(),
            )
        })
        .collect();
    if let Some(bad) = frames.iter().find(|f| !f.get("error").is_empty()) {
        return Err(format!("{target}: {:?}", bad.0));
    }
    let elf = std::fs::read(format!(
        "{manifest}/target/{target}/release/examples/firmware"
    ))
    .map_err(|e| format!("cannot read the firmware ELF: {e}"))?;
    let file = object::File::parse(&*elf).map_err(|e| format!("bad ELF: {e}"))?;
    let size = |names: &[&str]| -> u64 {
        file.sections()
            .filter(|s| s.name().is_ok_and(|n| names.contains(&n)))
            .map(|s| s.size())
            .sum()
    };
    Ok(Run {
        frames,
        // What the image holds: cortex-m-rt's sections, and riscv-rt's (`.init.rust`;
        // `.eh_frame` only if a layout kept unwind tables: `memory-riscv.x` drops them).
        flash: size(&[
            ".vector_table",
            ".text",
            ".init.rust",
            ".rodata",
            ".eh_frame",
            ".data",
        ]),
        static_ram: size(&[".data", ".bss", ".uninit"]),
    })
}
