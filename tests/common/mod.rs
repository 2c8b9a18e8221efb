//! The test-support module: helpers shared by the integration tests (each test binary
//! includes it with `mod common;` and uses what it needs) and by the `xtask` tools (the
//! accuracy report and the numerics document include `sampling.rs` and `qemu.rs`).
//!
//! - `sampling.rs`: the seeded generator and the random ray/plane cases behind the
//!   property tests, the fuzzers and `docs/numerics.md`;
//! - `qemu.rs`: building the firmware and running it under QEMU;
//! - `probes.rs`: what a format is (rounded square root, dot products, division), measured;
//! - `pictures.rs`: a target that records what it is drawn, pixel differences, PSNR.
#![allow(dead_code, unused_macros, unused_imports)]

pub mod pictures;
pub mod probes;
pub mod qemu;
pub mod sampling;

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::Rgb888;
use fixray::geometry::Vec3;
use fixray::scene::Rules;
use fixray::{Scalar, Scene, render};

/// A vector of format `S` from exact `f64` components.
pub fn v<S: Scalar>(x: f64, y: f64, z: f64) -> Vec3<S> {
    Vec3::from_f64([x, y, z]).unwrap()
}

/// Runs a generic check `$check::<S>()` in every format of the one list
/// (`fixray::num::formats::FORMATS`).
macro_rules! every_format {
    ($check:ident) => {
        fixray::for_each_format!(all: $check())
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

/// Checks an ASCII pattern in every format of the one list whose square root is rounded
/// ([`probes::sqrt_is_rounded`]: an exact picture assumes unit directions; `f32m`'s
/// approximate root misses a spotlight's cone edge by a pixel).
pub fn assert_pattern_everywhere(text: &str, expected: &[&str]) {
    fn one<S: Scalar>(text: &str, expected: &[&str]) {
        if probes::sqrt_is_rounded::<S>() {
            pattern::<S>(text).assert_pattern(expected);
        }
    }
    fixray::for_each_format!(all: one(text, expected));
}

/// The top-left pixel of a scene (the only one of a 1×1 scene) with the format's name, in
/// every format of `fixray::num::formats::FORMATS` whose square root is rounded (the
/// exact values these pixels are checked against assume unit directions: `f32m`'s glint
/// is 47 where the formula gives 51.8).
pub fn top_left_pixel(text: &str) -> Vec<(&'static str, Rgb888)> {
    fn one<S: Scalar>(text: &str) -> Option<Rgb888> {
        if !probes::sqrt_is_rounded::<S>() {
            return None;
        }
        let scene = Scene::<S>::parse_as(text, Rules::Fixray).unwrap();
        let mut line = vec![Rgb888::new(0, 0, 0); usize::from(scene.camera.width)];
        fixray::render_line(&scene, 0, &mut line);
        Some(line[0])
    }
    fixray::num::formats::FORMATS
        .into_iter()
        .filter_map(|name| Some((name, fixray::with_format!(name, one(text)).unwrap()?)))
        .collect()
}
