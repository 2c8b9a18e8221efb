//! Seeded fuzzing (a generator in the test, so it runs on stable Rust in CI; `cargo fuzz`
//! needs a nightly toolchain these machines do not have): any input must end in a value
//! or a typed error, never a panic or a wrap (the test profile has overflow checks on).
//!
//! Every format means every format of the one list (`fixray::num::formats::FORMATS`,
//! through `fixray::for_each_format!(all: …)`): a format added there is fuzzed here.
//!
//! - The scene parser, in every format, on 200 000 inputs: random bytes, soups of the
//!   format's own tokens and numbers at the edges of every range, and valid scenes with
//!   one token replaced.
//! - The PPM reader on 1 000 000 byte strings (random bytes, valid images with flipped,
//!   cut or lying headers), and the course's texture, projector and translucency scenes
//!   on 200 000 mutated files whose textures are such byte strings (parsed in every
//!   format, the files shared out among the formats in turn, 20 000 of them drawn at 3×2
//!   pixels).
//! - The plane test, in every format, on 1 000 000 planes and rays made of arbitrary bit
//!   patterns (any normal, point, base, direction and epsilon the format can hold), and
//!   the renderer on 2 000 one-pixel scenes made of random numbers.

mod common;
use common::sampling;

use embedded_graphics::pixelcolor::Rgb888;
use fixray::geometry::{Plane, Ray, RayKind, Vec3};
use fixray::num::formats::FORMATS;
use fixray::{Scalar, Scene, render_line};
use sampling::SplitMix;

const TOKENS: [&str; 47] = [
    "texture",
    "texplane",
    "projector",
    "transparency",
    "filename",
    "texname",
    "mode",
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

fn parse_in<S: Scalar>(text: &str) {
    let _ = Scene::<S>::parse(text);
}

fn parse_everywhere(text: &str) {
    fixray::for_each_format!(all: parse_in(text));
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
    fixray::for_each_format!(all: fuzz_intersection(1_000_000));
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
    fixray::for_each_format!(all: fuzz_render(2_000));
}

/// A PPM-like byte string: random bytes, or a valid image (up to 5×4, maxval 255 or
/// 65535) with a header number replaced, bytes flipped, or cut short.
fn ppm_bytes(rng: &mut SplitMix) -> Vec<u8> {
    if rng.next().is_multiple_of(5) {
        let len = rng.next() % 64;
        return (0..len).map(|_| rng.next() as u8).collect();
    }
    let (w, h) = (1 + rng.next() % 5, 1 + rng.next() % 4);
    let maxval = if rng.next().is_multiple_of(4) {
        65535
    } else {
        255
    };
    let mut fields = [w.to_string(), h.to_string(), maxval.to_string()];
    if rng.next().is_multiple_of(3) {
        let lies = [
            "0",
            "-1",
            "99999999999",
            "16385",
            "65536",
            "4x",
            "",
            "#",
            "1e3",
        ];
        fields[rng.below(3)] = lies[rng.below(lies.len())].to_string();
    }
    let comment = if rng.next().is_multiple_of(2) {
        "# c\n"
    } else {
        ""
    };
    let mut bytes =
        format!("P6\n{comment}{} {}\n{}\n", fields[0], fields[1], fields[2]).into_bytes();
    let samples = (w * h * 3 * if maxval > 255 { 2 } else { 1 }) as usize;
    bytes.extend((0..samples).map(|_| rng.next() as u8));
    match rng.next() % 4 {
        0 => {
            let cut = rng.below(bytes.len() + 1);
            bytes.truncate(cut);
        }
        1 => {
            for _ in 0..1 + rng.next() % 3 {
                let at = rng.below(bytes.len());
                bytes[at] ^= 1 << (rng.next() % 8);
            }
        }
        _ => {}
    }
    bytes
}

#[test]
fn the_ppm_reader_survives_a_million_inputs() {
    let mut rng = SplitMix(0x99A1_2026);
    let mut read = 0u32;
    for _ in 0..1_000_000u32 {
        let bytes = ppm_bytes(&mut rng);
        if let Ok(image) = fixray::ppm::Ppm::parse(&bytes) {
            read += 1;
            let (w, h) = (image.width(), image.height());
            for (x, y) in [(0, 0), (w - 1, h - 1), (w, 0), (0, h), (u32::MAX, u32::MAX)] {
                let inside = x < w && y < h;
                assert_eq!(image.pixel(x, y).is_some(), inside, "{w}x{h} ({x}, {y})");
            }
        }
    }
    // Both outcomes occur: the generator reaches valid and invalid images.
    assert!(read > 100_000 && read < 900_000, "{read} read");
}

/// Surfaces of revolution of every profile made of arbitrary bit patterns (any base,
/// direction, height and ray the format can hold): the intersection, the normal and the
/// spawned ray end in a value or a typed miss.
fn fuzz_revsurf<S: Scalar>(cases: u32) {
    let mut rng = SplitMix(0x2E75_F022);
    let mut outcomes = [0u32; 2];
    for i in 0..cases {
        let mut vec = || {
            Vec3::new(
                arbitrary::<S>(&mut rng),
                arbitrary::<S>(&mut rng),
                arbitrary::<S>(&mut rng),
            )
        };
        let (base, direction, origin, dir) = (vec(), vec(), vec(), vec());
        let height = arbitrary::<S>(&mut rng);
        let surfer = i64::from(i % 5);
        let Ok(shape) = fixray::geometry::Revsurf::new(surfer, base, direction, height) else {
            continue;
        };
        // Half the rays with a unit direction, as the tracer casts them.
        let dir = if i % 2 == 0 {
            dir.unit().unwrap_or(dir)
        } else {
            dir
        };
        let ray = Ray {
            base: origin,
            dir,
            kind: RayKind::Secondary,
        };
        let result = shape.intersect(&ray);
        outcomes[usize::from(result.is_ok())] += 1;
        if let Ok(hit) = result {
            let _ = shape.normal_at(hit.point);
            let _ = shape.spawn(&ray, &hit, dir);
        }
    }
    assert!(
        outcomes[0] > 0 && outcomes[1] > 0,
        "{}: {outcomes:?}",
        S::NAME
    );
}

#[test]
fn surfaces_of_revolution_survive_arbitrary_bit_patterns() {
    fixray::for_each_format!(all: fuzz_revsurf(20_000));
}

/// The course's scenes with textures, projectors and translucency, mutated (a token
/// replaced, numbers at the edges of the ranges), their texture files fuzzed PPM bytes:
/// parsed in every format, the small ones drawn.
#[test]
fn the_course_entities_survive_200_000_mutated_files() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/course/scenes");
    let bases: Vec<Vec<String>> = [
        "texplane1",
        "texplane3",
        "translucent",
        "proj1",
        "proj3",
        "revsurfa",
        "revsurfe",
    ]
    .iter()
    .map(|n| {
        let text = std::fs::read_to_string(format!("{dir}/{n}.txt")).unwrap();
        // Drawn at 3×2 pixels: the pixel count is not what is fuzzed.
        let text = text.replace("640 480", "3 2").replace("800 600", "3 2");
        text.split_whitespace().map(str::to_string).collect()
    })
    .collect();
    let mut rng = SplitMix(0x7E47_2026);
    let (mut parsed, mut drawn) = (0u32, 0u32);
    for i in 0..200_000u32 {
        let mut words = bases[rng.below(bases.len())].clone();
        for _ in 0..1 + rng.next() % 2 {
            let at = rng.below(words.len());
            words[at] = if rng.next().is_multiple_of(2) {
                NUMBERS[rng.below(NUMBERS.len())].to_string()
            } else {
                TOKENS[rng.below(TOKENS.len())].to_string()
            };
        }
        let text = words.join(" ");
        // Most files get a valid 2×2 texture, some fuzzed bytes.
        let bytes: &'static [u8] = if rng.next().is_multiple_of(4) {
            Box::leak(ppm_bytes(&mut rng).into_boxed_slice())
        } else {
            b"P6 2 2 255\n\xff\x00\x00\x00\xff\x00\x00\x00\xff\xff\xff\xff"
        };
        let mut files = |_: &str| (!rng.next().is_multiple_of(50)).then_some(bytes);
        fn one<S: Scalar>(
            text: &str,
            files: &mut dyn FnMut(&str) -> Option<&'static [u8]>,
            draw: bool,
        ) -> (bool, bool) {
            let mut scene = fixray::scene::LargeScene::<S>::empty();
            if scene.read_with(text, None, files).is_err() {
                return (false, false);
            }
            if draw && u32::from(scene.camera.width) * u32::from(scene.camera.height) <= 16 {
                let mut line = vec![Rgb888::new(0, 0, 0); usize::from(scene.camera.width)];
                for row in 0..scene.camera.height {
                    render_line(&scene, row, &mut line);
                }
                return (true, true);
            }
            (true, false)
        }
        // The formats take the files in turn (the same total whatever their number), and
        // each draws one round in ten of its share.
        let round = i as usize / FORMATS.len();
        let format = FORMATS[i as usize % FORMATS.len()];
        let draw = round.is_multiple_of(10);
        let (p, d) = fixray::with_format!(format, one(&text, &mut files, draw)).unwrap();
        parsed += u32::from(p);
        drawn += u32::from(d);
    }
    assert!(
        parsed > 20_000 && drawn > 2_000,
        "{parsed} parsed, {drawn} drawn"
    );
    println!("{parsed} of 200000 mutated course files parsed, {drawn} drawn");
}
