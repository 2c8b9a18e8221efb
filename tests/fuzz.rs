//! Seeded fuzzing (a generator in the test, so it runs on stable Rust in CI; `cargo fuzz`
//! needs a nightly toolchain these machines do not have): any input must end in a value
//! or a typed error, never a panic or a wrap (the test profile has overflow checks on).
//!
//! - The scene parser, in every format, on 200 000 inputs: random bytes, soups of the
//!   format's own tokens and numbers at the edges of every range, and valid scenes with
//!   one token replaced.
//! - The plane test, in every format, on 1 000 000 planes and rays made of arbitrary bit
//!   patterns (any normal, point, base, direction and epsilon the format can hold), and
//!   the renderer on 2 000 one-pixel scenes made of random numbers.

mod common;
use common::sampling;

use embedded_graphics::pixelcolor::Rgb888;
use fixray::num::variants::{F32Micro, I16F16Narrow};
use fixray::{I16F16, I20F12, I32F32, Plane, Ray, RayKind, Scalar, Scene, Vec3, render_line};
use sampling::SplitMix;

const TOKENS: [&str; 40] = [
    "camera",
    "material",
    "light",
    "spotlight",
    "plane",
    "sphere",
    "tiled_plane",
    "fplane",
    "background",
    "precision",
    "pixeldim",
    "worlddim",
    "viewpoint",
    "ambient",
    "diffuse",
    "specular",
    "shininess",
    "reflective",
    "location",
    "emissivity",
    "normal",
    "point",
    "center",
    "radius",
    "xdir",
    "dimension",
    "dimensions",
    "altmaterial",
    "theta",
    "{",
    "}",
    "#",
    "\n",
    "m",
    "p",
    "c",
    "x_1",
    "é",
    "\t",
    "{}",
];
const NUMBERS: [&str; 16] = [
    "0",
    "-0",
    "1",
    "-1",
    "0.5",
    ".25",
    "1e-3",
    "32767.99",
    "32768",
    "-32768",
    "4096",
    "4097",
    "1e999",
    "1e-999",
    "123456789012345678901234567890",
    "0.000000000000000000001",
];

fn parse_everywhere(text: &str) {
    let _ = Scene::<I16F16>::parse(text);
    let _ = Scene::<I16F16Narrow>::parse(text);
    let _ = Scene::<I20F12>::parse(text);
    let _ = Scene::<I32F32>::parse(text);
    let _ = Scene::<f32>::parse(text);
    let _ = Scene::<F32Micro>::parse(text);
    let _ = Scene::<f64>::parse(text);
}

#[test]
fn the_parser_survives_200_000_inputs() {
    let mut rng = SplitMix(0xFA22_2026);
    let base = include_str!("../scenes/default.scene");
    let words: Vec<&str> = base.split_whitespace().collect();
    let mut inputs = 0u32;
    for i in 0..200_000u32 {
        let text: String = match i % 3 {
            0 => {
                let len = rng.next() % 200;
                let bytes: Vec<u8> = (0..len).map(|_| (rng.next() % 128) as u8).collect();
                String::from_utf8_lossy(&bytes).into_owned()
            }
            1 => (0..rng.next() % 60)
                .map(|_| {
                    if rng.next().is_multiple_of(3) {
                        NUMBERS[(rng.next() % NUMBERS.len() as u64) as usize]
                    } else {
                        TOKENS[(rng.next() % TOKENS.len() as u64) as usize]
                    }
                })
                .collect::<Vec<_>>()
                .join(" "),
            _ => {
                let mut w = words.clone();
                let at = (rng.next() % w.len() as u64) as usize;
                w[at] = if rng.next().is_multiple_of(2) {
                    NUMBERS[(rng.next() % NUMBERS.len() as u64) as usize]
                } else {
                    TOKENS[(rng.next() % TOKENS.len() as u64) as usize]
                };
                w.join(" ")
            }
        };
        parse_everywhere(&text);
        inputs += 1;
    }
    assert_eq!(inputs, 200_000);
}

/// A value of format `S` made of arbitrary bits (any representable value, NaN and
/// infinities refused by `from_f64` for floats, which then take a random finite value).
fn arbitrary<S: Scalar>(rng: &mut SplitMix) -> S {
    loop {
        let bits = rng.next();
        let candidate = match rng.next() % 4 {
            // Anywhere in the format's range, including its extremes.
            0 => f64::from_bits(bits),
            1 => (bits as i64 as f64) / (1u64 << (bits % 64)) as f64,
            2 => S::MAX.to_f64() * (if bits & 1 == 0 { 1.0 } else { -1.0 }),
            _ => rng.uniform(-4.0, 4.0),
        };
        if let Some(v) = S::from_f64(candidate) {
            return v;
        }
    }
}

fn fuzz_intersection<S: Scalar>(cases: u32) {
    let mut rng = SplitMix(0xB175_2026);
    let mut outcomes = [0u32; 2];
    for _ in 0..cases {
        let mut vec = || {
            Vec3::new(
                arbitrary::<S>(&mut rng),
                arbitrary::<S>(&mut rng),
                arbitrary::<S>(&mut rng),
            )
        };
        let (normal, point, base, dir) = (vec(), vec(), vec(), vec());
        let eps = arbitrary::<S>(&mut rng).abs();
        let kind = if rng.next() & 1 == 0 {
            RayKind::Primary
        } else {
            RayKind::Secondary
        };
        let _ = (dir.unit(), dir.length(), base.normalize());
        if let Ok(plane) = Plane::new(normal, point) {
            let ray = Ray { base, dir, kind };
            let result = plane.intersect(&ray, eps);
            outcomes[usize::from(result.is_ok())] += 1;
            if let Ok(hit) = result {
                let _ = plane.residual_bound(&ray, &hit);
                let _ = plane.spawn(&ray, &hit, dir);
            }
        }
    }
    // Both outcomes occur: the generator reaches the interesting part of the space.
    assert!(
        outcomes[0] > 0 && outcomes[1] > 0,
        "{}: {outcomes:?}",
        S::NAME
    );
}

#[test]
fn the_plane_test_survives_arbitrary_bit_patterns() {
    fuzz_intersection::<I16F16>(1_000_000);
    fuzz_intersection::<I16F16Narrow>(1_000_000);
    fuzz_intersection::<I20F12>(1_000_000);
    fuzz_intersection::<I32F32>(1_000_000);
    fuzz_intersection::<f32>(1_000_000);
    fuzz_intersection::<F32Micro>(1_000_000);
    fuzz_intersection::<f64>(1_000_000);
}

fn fuzz_render<S: Scalar>(scenes: u32) {
    let mut rng = SplitMix(0x5CE2_2026);
    let mut rendered = 0;
    for _ in 0..scenes {
        // Every `N` becomes a random number from the edges of the ranges.
        let template = "camera c { pixeldim 2 2 worlddim N N viewpoint N N N }
             material m { ambient N N N diffuse N N N }
             light l { location N N N emissivity N N N }
             plane p { material m normal N N N point N N N }
             precision N";
        let text: String = template
            .split('N')
            .enumerate()
            .map(|(i, piece)| {
                let number = if i == 0 {
                    ""
                } else {
                    NUMBERS[(rng.next() % NUMBERS.len() as u64) as usize]
                };
                format!("{number}{piece}")
            })
            .collect();
        if let Ok(scene) = Scene::<S>::parse(&text) {
            let mut line = [Rgb888::new(0, 0, 0); 2];
            render_line(&scene, 0, &mut line);
            render_line(&scene, 1, &mut line);
            rendered += 1;
        }
    }
    assert!(rendered > 0, "{}: no random scene parsed", S::NAME);
}

#[test]
fn the_renderer_survives_random_scenes() {
    fuzz_render::<I16F16>(2_000);
    fuzz_render::<I20F12>(2_000);
    fuzz_render::<I32F32>(2_000);
    fuzz_render::<f32>(2_000);
    fuzz_render::<f64>(2_000);
}
