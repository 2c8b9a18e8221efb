//! Build script (the cortex-m-quickstart pattern): puts this board's `memory.x` (the
//! RP2040's flash and RAM, and the `.boot2` section) in `OUT_DIR` and that directory on
//! the linker's search path, where `cortex-m-rt`'s `link.x` (`-Tlink.x`,
//! `.cargo/config.toml`) includes it.

use std::env;
use std::fs;
use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::write(out.join("memory.x"), include_bytes!("memory.x")).expect("OUT_DIR is writable");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
}
