//! The level-plane kernel (`kernel/rows.rs`) against the fast kernel it shortcuts: every
//! pixel bit for bit, in every format of the one list, on every frame of the boing ball,
//! on a ball scene of the same kind the repository does not ship, and on seeded random
//! scenes of level planes (tiled and plain, some tilted about the x axis, some nearly
//! edge-on) and spheres under one or two lights, with and without shadows.

use embedded_graphics::pixelcolor::Rgb888;
use fixray::anim::Bounce;
use fixray::internals::render_line_fast;
use fixray::{Frame, KernelKind, Scalar, Scene, render_line};

/// Draws `scene` with the renderer's choice and with the fast kernel; asserts that the
/// choice is the level-plane kernel when `expect_rows` and that the two pictures are
/// equal. Returns the number of pixels compared.
fn agree<S: Scalar>(name: &str, scene: &Scene<S>, expect_rows: bool) -> usize {
    let kernel = Frame::new(scene).kernel();
    if expect_rows {
        assert_eq!(kernel, KernelKind::Rows, "{name} {}", S::NAME);
    }
    let w = usize::from(scene.camera.width);
    let mut a = vec![Rgb888::new(0, 0, 0); w];
    let mut b = vec![Rgb888::new(1, 2, 3); w];
    for row in 0..scene.camera.height {
        render_line(scene, row, &mut a);
        render_line_fast(scene, row, &mut b);
        for (x, (p, q)) in a.iter().zip(&b).enumerate() {
            assert_eq!(p, q, "{name} {} at ({x}, {row})", S::NAME);
        }
    }
    w * usize::from(scene.camera.height)
}

fn boing<S: Scalar>() {
    let mut scene = Scene::<S>::parse(include_str!("../scenes/boing.scene")).unwrap();
    let bounce = Bounce::boing(&scene.objects).unwrap();
    for k in 0..bounce.frames() {
        bounce.apply(&mut scene, k).unwrap();
        agree(&format!("boing frame {k}"), &scene, true);
    }
}

#[test]
fn every_boing_frame_is_the_fast_kernels_bit_for_bit() {
    fixray::for_each_format!(all: boing());
}

/// A ball scene this repository does not ship (issue 25's goal scene).
const BALL: &str = "rules fixray
camera c { pixeldim 160 96 worlddim 10 6 viewpoint 5 4 9 }
background 0.1 0.15 0.3
material m1 { ambient 0.05 0.2 0.05 diffuse 0.2 0.8 0.3 }
material t1 { ambient 0.15 0.15 0.1 diffuse 0.8 0.8 0.6 }
material t2 { ambient 0.02 0.05 0.15 diffuse 0.1 0.3 0.8 }
light sun { location 2 10 6 emissivity 12 12 12 }
tiled_plane ground { material t1 altmaterial t2 normal 0 1 0 point 0 0 0 xdir 1 0 0 dimension 1.5 1.5 }
tiled_plane back { material t2 altmaterial t1 normal 0 0 1 point 0 0 -10 xdir 1 0 0 dimension 2 2 }
sphere ball { material m1 center 6 1.5 -3 radius 1.5 }
";

fn ball<S: Scalar>() {
    agree("ball", &Scene::<S>::parse(BALL).unwrap(), true);
}

#[test]
fn an_unshipped_ball_scene_is_the_fast_kernels_bit_for_bit() {
    fixray::for_each_format!(all: ball());
}

/// A small deterministic generator (xorshift), so that the scenes are the same on every
/// run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// A value in `[lo, hi)` with two decimals.
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next() % 10_000) as f64 / 10_000.0;
        ((lo + u * (hi - lo)) * 100.0).round() / 100.0
    }
}

/// A random scene of level planes and spheres: a floor or ceiling, a back wall, a plane
/// tilted about the x axis (sometimes nearly edge-on to the eye's rows), up to two
/// spheres and one or two lights.
fn random_scene(rng: &mut Rng) -> String {
    let mut s = String::from("rules fixray\n");
    let (w, h) = (48 + rng.next() % 40, 24 + rng.next() % 30);
    let eye_y = rng.range(1.0, 5.0);
    s += &format!(
        "camera c {{ pixeldim {w} {h} worlddim 8 5 viewpoint {} {eye_y} {} }}\n",
        rng.range(2.0, 6.0),
        rng.range(5.0, 9.0)
    );
    s += "background 0.1 0.1 0.2\n";
    for i in 0..3 {
        s += &format!(
            "material m{i} {{ ambient {} {} {} diffuse {} {} {} }}\n",
            rng.range(0.0, 0.3),
            rng.range(0.0, 0.3),
            rng.range(0.0, 0.3),
            rng.range(0.1, 1.0),
            rng.range(0.1, 1.0),
            rng.range(0.1, 1.0)
        );
    }
    let lights = 1 + rng.next() % 2;
    for i in 0..lights {
        s += &format!(
            "light l{i} {{ location {} {} {} emissivity {} {} {} }}\n",
            rng.range(-2.0, 10.0),
            rng.range(3.0, 12.0),
            rng.range(-4.0, 6.0),
            rng.range(2.0, 12.0),
            rng.range(2.0, 12.0),
            rng.range(2.0, 12.0)
        );
    }
    // Tiles along x (their row the scanline's), or turned about y (each pixel looks its
    // tile up whole).
    let xdir = if rng.next().is_multiple_of(3) {
        "1 0 0.3"
    } else {
        "1 0 0"
    };
    s += &format!(
        "tiled_plane floor {{ material m0 altmaterial m1 normal 0 1 0 point {} {} {} xdir {xdir} dimension {} {} }}\n",
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 0.5),
        rng.range(-1.0, 1.0),
        rng.range(0.5, 2.0),
        rng.range(0.5, 2.0)
    );
    if rng.next().is_multiple_of(2) {
        s += &format!(
            "plane back {{ material m2 normal 0 0 1 point 0 0 {} }}\n",
            rng.range(-12.0, -5.0)
        );
    } else {
        s += &format!(
            "tiled_plane back {{ material m1 altmaterial m2 normal 0 0 1 point 0 0 {} xdir 1 0 0 dimension 1 1 }}\n",
            rng.range(-12.0, -5.0)
        );
    }
    // Tilted about x: through a point at the eye's height now and then, so that its rows
    // near the eye are nearly edge-on.
    let tilt_y = if rng.next().is_multiple_of(3) {
        eye_y
    } else {
        rng.range(0.0, 6.0)
    };
    let (ny, nz, tz) = (
        rng.range(-1.0, 1.0),
        rng.range(0.2, 1.0),
        rng.range(-14.0, -8.0),
    );
    if rng.next().is_multiple_of(2) {
        s += &format!("plane tilt {{ material m2 normal 0 {ny} {nz} point 0 {tilt_y} {tz} }}\n");
    } else {
        // Tiled, its v axis in the plane of y and z: a tile row per scanline again.
        s += &format!(
            "tiled_plane tilt {{ material m2 altmaterial m0 normal 0 {ny} {nz} point 0.3 {tilt_y} {tz} xdir 1 0 0 dimension 0.7 0.9 }}\n"
        );
    }
    for i in 0..rng.next() % 3 {
        s += &format!(
            "sphere s{i} {{ material m{} center {} {} {} radius {} }}\n",
            i % 3,
            rng.range(0.0, 8.0),
            rng.range(0.5, 3.0),
            rng.range(-6.0, 0.0),
            rng.range(0.3, 1.5)
        );
    }
    s
}

fn random<S: Scalar>(text: &str, n: usize) -> usize {
    let scene = Scene::<S>::parse(text).unwrap();
    let rows = Frame::new(&scene).kernel() == KernelKind::Rows;
    if rows {
        agree(&format!("random scene {n}:\n{text}"), &scene, false)
    } else {
        0
    }
}

#[test]
fn random_level_scenes_are_the_fast_kernels_bit_for_bit() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut drawn = 0;
    for n in 0..40 {
        let text = random_scene(&mut rng);
        for name in fixray::num::formats::MAIN {
            drawn += fixray::with_format!(name, random(&text, n)).unwrap();
        }
    }
    // Most of them are drawn by the level-plane kernel (the rest: a sphere around the eye
    // or a quantity out of range, where the renderer chose another kernel).
    assert!(drawn > 40 * 5 * 48 * 24 / 2, "{drawn} pixels compared");
}
