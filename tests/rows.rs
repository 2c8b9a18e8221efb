//! The level-plane kernel (`kernel/rows/`) against the fast kernel it shortcuts: every
//! pixel bit for bit, in every format of the one list, on every frame of the boing ball,
//! on a ball scene of the same kind the repository does not ship, and on seeded random
//! scenes of level planes (tiled and plain, some tilted about the x axis, some nearly
//! edge-on) and spheres under one to three lights, whole scanlines and scanlines streamed
//! from other columns than the first (a display area that does not start at x = 0).

use embedded_graphics::pixelcolor::Rgb888;
use fixray::anim::Bounce;
use fixray::internals::render_columns_with;
use fixray::scene::SceneErrorKind;
use fixray::{Frame, KernelKind, Scalar, Scene, render_line};

/// Draws `scene` with the renderer's choice and with the fast kernel; asserts that the
/// choice is the level-plane kernel when `expect_rows` and that the two pictures are
/// equal. Returns the number of pixels compared.
fn agree<S: Scalar>(name: &str, scene: &Scene<S>, expect_rows: bool) -> usize {
    let kernel = Frame::<_>::new(scene).kernel();
    if expect_rows {
        assert_eq!(kernel, KernelKind::Rows, "{name} {}", S::NAME);
    }
    let w = usize::from(scene.camera.width);
    let mut a = vec![Rgb888::new(0, 0, 0); w];
    let mut b = vec![Rgb888::new(1, 2, 3); w];
    for row in 0..scene.camera.height {
        render_line(scene, row, &mut a);
        render_columns_with(scene, true, row, 0, &mut b);
        for (x, (p, q)) in a.iter().zip(&b).enumerate() {
            assert_eq!(p, q, "{name} {} at ({x}, {row})", S::NAME);
        }
    }
    // Streamed from other columns (`Frame::draw` onto an area that starts there): both
    // kernels resume the whole scanline's stepping there.
    for start in [1, 3, 7, 8, 13] {
        let Some(n) = w.checked_sub(start) else {
            continue;
        };
        let mut a = vec![Rgb888::new(0, 0, 0); n];
        let mut b = vec![Rgb888::new(1, 2, 3); n];
        let start = u16::try_from(start).unwrap();
        for row in (0..scene.camera.height).step_by(3) {
            render_columns_with(scene, false, row, start, &mut a);
            render_columns_with(scene, true, row, start, &mut b);
            for (x, (p, q)) in a.iter().zip(&b).enumerate() {
                assert_eq!(
                    p,
                    q,
                    "{name} {} from column {start} at ({x}, {row})",
                    S::NAME
                );
            }
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
#[cfg_attr(
    debug_assertions,
    ignore = "every boing frame in every format: run in release"
)]
fn every_boing_frame_is_the_fast_kernels_bit_for_bit() {
    fixray::for_each_format!(all: boing());
}

/// A ball scene this repository does not ship (one the performance goals are set on).
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
#[cfg_attr(debug_assertions, ignore = "160x96 in every format: run in release")]
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
    // Up to three: a scene with more than the kernel's per-row lights too.
    let lights = 1 + rng.next() % 3;
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
    // A radius the format does not resolve (`MIN_RADIUS_SQ_DELTAS`: below ½ in I20F12)
    // is refused: nothing to draw.
    let scene = match Scene::<S>::parse(text) {
        Err(e) if matches!(e.kind, SceneErrorKind::BelowResolution { .. }) => return 0,
        parsed => parsed.unwrap(),
    };
    let rows = Frame::<_>::new(&scene).kernel() == KernelKind::Rows;
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
        for name in fixray::num::formats::FORMATS {
            drawn += fixray::with_format!(name, random(&text, n)).unwrap();
        }
    }
    // Most of them are drawn by the level-plane kernel (the rest: a sphere around the eye
    // or a quantity out of range, where the renderer chose another kernel).
    assert!(drawn > 40 * 8 * 48 * 24 / 2, "{drawn} pixels compared");
}

/// A row whose rays are exactly parallel to the floor (`D.y = 0`) far from the screen,
/// where `ε·|D|²` does not fit I16F16: the fast kernel hands that row's pixels to the
/// reference path, and so must the level-plane kernel (it leaves a row with `N·D = 0`
/// to the fast kernel).
const EDGE_ON: &str = "rules fixray
camera c { pixeldim 64 40 worlddim 8 5 viewpoint 4 2.5625 190 }
background 0.1 0.1 0.2
material a { ambient 0.1 0.1 0.1 diffuse 0.8 0.7 0.6 }
material b { ambient 0.05 0.1 0.05 diffuse 0.3 0.8 0.4 }
light l { location 2 9 5 emissivity 9 9 9 }
tiled_plane floor { material a altmaterial b normal 0 1 0 point 0 0 0 xdir 1 0 0 dimension 1 1 }
plane back { material b normal 0 0 1 point 0 0 -20 }
";

fn edge_on<S: Scalar>() {
    let scene = Scene::<S>::parse(EDGE_ON).unwrap();
    agree("edge-on", &scene, true);
    // Row 19's rays have D.y = 0 exactly: the fast kernel draws it (and rows near it
    // within the epsilon's margin, more of them in the coarser formats); the rows far from
    // the horizon are the level-plane kernel's.
    let frame = Frame::<S>::new(&scene);
    assert_eq!(frame.row_kernel(19), KernelKind::Fast, "{}", S::NAME);
    assert_eq!(frame.row_kernel(0), KernelKind::Rows, "{}", S::NAME);
    assert_eq!(frame.row_kernel(39), KernelKind::Rows, "{}", S::NAME);
}

#[test]
fn a_row_edge_on_to_the_floor_is_the_fast_kernels_bit_for_bit() {
    fixray::for_each_format!(all: edge_on());
}

/// One primary ray per pixel, however the level-plane kernel draws it (its quick runs
/// draw many pixels a call and hand them out one by one): `primary_rays` over a whole
/// frame is the frame's pixel count, on two boing frames and the ball scene.
fn one_ray_a_pixel<S: Scalar>() {
    let count = |name: &str, scene: &Scene<S>| {
        assert_eq!(
            Frame::<_>::new(scene).kernel(),
            KernelKind::Rows,
            "{name} {}",
            S::NAME
        );
        let mut line = vec![Rgb888::new(0, 0, 0); usize::from(scene.camera.width)];
        let mut counters = fixray::stats::Counters::default();
        let frame = Frame::new(scene);
        for row in 0..scene.camera.height {
            frame.render_line_counted(row, &mut line, &mut counters);
        }
        let pixels = u32::from(scene.camera.width) * u32::from(scene.camera.height);
        assert_eq!(counters.primary_rays, pixels, "{name} {}", S::NAME);
    };
    let mut boing = Scene::<S>::parse(include_str!("../scenes/boing.scene")).unwrap();
    let bounce = Bounce::boing(&boing.objects).unwrap();
    for k in [0, 8] {
        bounce.apply(&mut boing, k).unwrap();
        count(&format!("boing frame {k}"), &boing);
    }
    count("ball", &Scene::<S>::parse(BALL).unwrap());
}

#[test]
fn the_level_plane_kernel_traces_one_primary_ray_a_pixel() {
    fixray::for_each_format!(all: one_ray_a_pixel());
}

/// A display that takes the first `take` pixels of a scanline and then refuses it (a
/// driver whose bus failed): its bounding box is one row of the frame.
struct Refusing {
    take: usize,
    row: i32,
    width: u32,
}

impl embedded_graphics::geometry::Dimensions for Refusing {
    fn bounding_box(&self) -> embedded_graphics::primitives::Rectangle {
        embedded_graphics::primitives::Rectangle::new(
            embedded_graphics::geometry::Point::new(0, self.row),
            embedded_graphics::geometry::Size::new(self.width, 1),
        )
    }
}

impl embedded_graphics::draw_target::DrawTarget for Refusing {
    type Color = Rgb888;
    type Error = ();

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), ()>
    where
        I: IntoIterator<Item = embedded_graphics::Pixel<Rgb888>>,
    {
        let _ = pixels.into_iter().take(self.take).count();
        Err(())
    }

    fn fill_contiguous<I>(
        &mut self,
        _area: &embedded_graphics::primitives::Rectangle,
        colors: I,
    ) -> Result<(), ()>
    where
        I: IntoIterator<Item = Rgb888>,
    {
        let _ = colors.into_iter().take(self.take).count();
        Err(())
    }
}

/// The level-plane kernel's counters count the pixels a display took, not those its
/// quick runs drew ahead (a scanline stopped after `k` pixels counts none of the up to 31
/// more primary rays, shadow rays and diffuse terms drawn past it).
fn counts_what_was_taken<S: Scalar>() {
    let boing = Scene::<S>::parse(include_str!("../scenes/boing.scene")).unwrap();
    let frame = Frame::new(&boing);
    let width = boing.camera.width;
    for row in [4, 20, 40, 60] {
        if frame.row_kernel(row) != KernelKind::Rows {
            continue;
        }
        let mut whole = fixray::stats::Counters::default();
        let mut line = vec![Rgb888::new(0, 0, 0); usize::from(width)];
        frame.render_line_counted(row, &mut line, &mut whole);
        for take in [1, 2, 7, 33, 40, 100] {
            let mut counters = fixray::stats::Counters::default();
            let mut display = Refusing {
                take,
                row: i32::from(row),
                width: u32::from(width),
            };
            assert!(frame.draw_counted(&mut display, &mut counters).is_err());
            let rays = u32::try_from(take).unwrap();
            assert_eq!(
                counters.primary_rays,
                rays,
                "row {row}, {take} taken, {}",
                S::NAME
            );
            assert!(
                counters.shadow_rays <= whole.shadow_rays,
                "row {row}, {take} taken"
            );
        }
    }
}

#[test]
fn a_scanline_stopped_early_counts_only_the_pixels_taken() {
    fixray::for_each_format!(all: counts_what_was_taken());
}
