//! Image-level numerical checks on the grazing scene `scenes/horizon.scene` (an infinite
//! floor, a slightly tilted ridge, sky), in every format of the one list
//! (`fixray::num::formats::FORMATS`):
//! - the horizon is clean: every pixel is sky, ridge or floor (nothing wrapped), and down
//!   each column the picture never goes back to sky below the floor (no shimmer: rays
//!   beyond the format's range are a clean miss, not garbage);
//! - no speckle: no pixel differs from both its left and right neighbours where the f64
//!   render has the three equal.

use embedded_graphics::pixelcolor::Rgb888;
use fixray::shade::to_rgb888;
use fixray::{Scalar, Scene, render_line};

const HORIZON: &str = include_str!("../scenes/horizon.scene");

fn frame<S: Scalar>(text: &str) -> (Vec<Vec<Rgb888>>, Scene<S>) {
    let scene = Scene::<S>::parse(text).unwrap();
    let w = usize::from(scene.camera.width);
    let rows = (0..scene.camera.height)
        .map(|row| {
            let mut line = vec![Rgb888::new(0, 0, 0); w];
            render_line(&scene, row, &mut line);
            line
        })
        .collect();
    (rows, scene)
}

fn check<S: Scalar>() {
    let (img, scene) = frame::<S>(HORIZON);
    let (reference, _) = frame::<f64>(HORIZON);
    let sky = to_rgb888(scene.background);
    let allowed: Vec<Rgb888> = scene
        .materials
        .iter()
        .map(|m| to_rgb888(m.ambient))
        .chain([sky])
        .collect();
    let (h, w) = (img.len(), img[0].len());
    for x in 0..w {
        let mut seen_ground = false;
        for (y, row) in img.iter().enumerate() {
            let c = row[x];
            assert!(
                allowed.contains(&c),
                "{}: ({x}, {y}) is {c:?}, not sky or a surface",
                S::NAME
            );
            if c != sky {
                seen_ground = true;
            } else {
                assert!(
                    !seen_ground,
                    "{}: sky at ({x}, {y}) below the ground",
                    S::NAME
                );
            }
        }
    }
    let mut speckles = 0;
    for y in 0..h {
        for x in 1..w - 1 {
            let (l, c, r) = (img[y][x - 1], img[y][x], img[y][x + 1]);
            let (rl, rc, rr) = (reference[y][x - 1], reference[y][x], reference[y][x + 1]);
            if c != l && c != r && rl == rc && rc == rr {
                speckles += 1;
            }
        }
    }
    assert_eq!(speckles, 0, "{}: {speckles} isolated pixels", S::NAME);
}

#[test]
fn the_horizon_is_clean_and_free_of_speckle_in_every_format() {
    fixray::for_each_format!(all: check());
}
