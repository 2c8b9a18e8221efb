//! Helpers shared by the integration tests (each test binary includes this module with
//! `mod common;` and uses what it needs).
#![allow(dead_code, unused_macros)]

use embedded_graphics::mock_display::MockDisplay;
use embedded_graphics::pixelcolor::Rgb888;
use fixray::{I16F16, I20F12, I32F32, Scalar, Scene, Vec3, render};

/// A vector of format `S` from exact `f64` components.
pub fn v<S: Scalar>(x: f64, y: f64, z: f64) -> Vec3<S> {
    Vec3::from_f64([x, y, z]).unwrap()
}

/// Runs a generic check `$check::<S>()` in every format.
macro_rules! every_format {
    ($check:ident) => {
        $check::<fixray::I16F16>();
        $check::<fixray::I20F12>();
        $check::<fixray::I32F32>();
        $check::<f32>();
        $check::<f64>();
    };
}
#[allow(unused_imports)]
pub(crate) use every_format;

/// A scene rendered in format `S` into a `MockDisplay` (which also catches overdraw and
/// out-of-bounds writes).
pub fn pattern<S: Scalar>(text: &str) -> MockDisplay<Rgb888> {
    let scene = Scene::<S>::parse(text).unwrap();
    let mut display = MockDisplay::new();
    render(&scene, &mut display).unwrap();
    display
}

/// Checks an ASCII pattern in every format.
pub fn assert_pattern_everywhere(text: &str, expected: &[&str]) {
    pattern::<I16F16>(text).assert_pattern(expected);
    pattern::<I20F12>(text).assert_pattern(expected);
    pattern::<I32F32>(text).assert_pattern(expected);
    pattern::<f32>(text).assert_pattern(expected);
    pattern::<f64>(text).assert_pattern(expected);
}

/// The top-left pixel of a scene (the only one of a 1×1 scene) in every format:
/// I16F16, I20F12, I32F32, f32, f64.
pub fn top_left_pixel(text: &str) -> [Rgb888; 5] {
    fn one<S: Scalar>(text: &str) -> Rgb888 {
        let scene = Scene::<S>::parse(text).unwrap();
        let mut line = vec![Rgb888::new(0, 0, 0); usize::from(scene.camera.width)];
        fixray::render_line(&scene, 0, &mut line);
        line[0]
    }
    [
        one::<I16F16>(text),
        one::<I20F12>(text),
        one::<I32F32>(text),
        one::<f32>(text),
        one::<f64>(text),
    ]
}
