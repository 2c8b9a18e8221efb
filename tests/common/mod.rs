//! The test-support module: helpers shared by the integration tests (each test binary
//! includes it with `mod common;` and uses what it needs) and by the `xtask` tools (the
//! accuracy report and the numerics document include `sampling.rs` and `qemu.rs`).
//!
//! - `sampling.rs`: the seeded generator and the random ray/plane cases behind the
//!   property tests, the fuzzers and `docs/numerics.md`;
//! - `qemu.rs`: building the firmware and running it under QEMU;
//! - `probes.rs`: what a format is (rounded square root, dot products, division), measured.
#![allow(dead_code, unused_macros, unused_imports)]

pub mod probes;
pub mod qemu;
pub mod sampling;

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::Rgb888;
use fixray::{Rules, Scalar, Scene, Vec3, render};

/// A vector of format `S` from exact `f64` components.
pub fn v<S: Scalar>(x: f64, y: f64, z: f64) -> Vec3<S> {
    Vec3::from_f64([x, y, z]).unwrap()
}

/// Runs a generic check `$check::<S>()` in every main format (the one list's
/// `fixray::num::formats::MAIN`).
macro_rules! every_format {
    ($check:ident) => {
        fixray::for_each_format!($check())
    };
}
#[allow(unused_imports)]
pub(crate) use every_format;

/// A scene rendered in format `S` into a `MockDisplay` (which also catches overdraw and
/// out-of-bounds writes).
pub fn pattern<S: Scalar>(text: &str) -> MockDisplay<Rgb888> {
    let scene = Scene::<S>::parse_as(text, Rules::Fixray).unwrap();
    let mut display = MockDisplay::new();
    render(&scene, &mut display).unwrap();
    display
}

/// Checks an ASCII pattern in every main format.
pub fn assert_pattern_everywhere(text: &str, expected: &[&str]) {
    fn one<S: Scalar>(text: &str, expected: &[&str]) {
        pattern::<S>(text).assert_pattern(expected);
    }
    fixray::for_each_format!(one(text, expected));
}

/// The top-left pixel of a scene (the only one of a 1×1 scene) in every main format, in
/// the order of `fixray::num::formats::MAIN`: I16F16, I20F12, I32F32, f32, f64.
pub fn top_left_pixel(text: &str) -> [Rgb888; 5] {
    fn one<S: Scalar>(text: &str) -> Rgb888 {
        let scene = Scene::<S>::parse_as(text, Rules::Fixray).unwrap();
        let mut line = vec![Rgb888::new(0, 0, 0); usize::from(scene.camera.width)];
        fixray::render_line(&scene, 0, &mut line);
        line[0]
    }
    let mut out = [Rgb888::new(0, 0, 0); 5];
    for (slot, name) in out.iter_mut().zip(fixray::num::formats::MAIN) {
        *slot = fixray::with_format!(name, one(text)).unwrap();
    }
    out
}
